//! Flight files: launch columns in (measured or predicted), flight columns out; the
//! `[atmosphere]` TOML table.
//!
//! Output columns: every input column except earlier flight outputs, then `pred_carry_yd`,
//! `pred_offline_yd`, `pred_apex_yd`, `pred_flight_time_s`, `pred_land_angle_deg` (and
//! `pred_total_yd` with a ground model), then `err_<name>` = predicted − measured for each of
//! those whose measured column (`carry_yd`, …) is in the input.

use std::path::Path;

use crate::data::columns::measured_value;
use crate::data::number::push_cell;
use crate::data::{csv_error_at, read_text, DataError};
use crate::flight::{Atmosphere, Flight, FlightError, FlightLaunch};
use crate::line_index::LineIndex;

pub use super::columns::{FLIGHT_COLUMNS, LAUNCH_COLUMNS};

pub(crate) fn flight_value(f: &Flight, k: usize) -> Option<f64> {
    match k {
        0 => Some(f.carry_yd()),
        1 => Some(f.offline_yd()),
        2 => Some(f.apex_yd()),
        3 => Some(f.flight_time_s),
        4 => Some(f.land_angle_deg()),
        _ => f.total_yd(),
    }
}

/// Which launch columns to fly.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LaunchSource {
    /// `ball_speed_mph`, `launch_angle_deg`, `azimuth_deg`, `backspin_rpm`, `sidespin_rpm`.
    Measured,
    /// The same with `pred_` (as `smash predict` writes them).
    Predicted,
}

impl LaunchSource {
    /// Prefix of its column names.
    pub fn prefix(self) -> &'static str {
        match self {
            Self::Measured => "",
            Self::Predicted => "pred_",
        }
    }
}

/// A CSV of launches: the raw table and the parsed launches (of the rows kept).
#[derive(Debug, Clone, PartialEq)]
pub struct LaunchTable {
    /// Header as in the file.
    pub headers: Vec<String>,
    /// Raw cells.
    pub records: Vec<csv::StringRecord>,
    /// 1-based file line of each record.
    pub lines: Vec<usize>,
    /// Parsed launches, SI.
    pub launches: Vec<FlightLaunch>,
    /// Which columns were flown.
    pub source: LaunchSource,
    /// Rows left out (a value that cannot be used), by reason, in file order.
    pub left_out: Vec<crate::data::left_out::LeftOut>,
}

/// A raw CSV table with the line of each record.
#[derive(Debug)]
pub struct RawCsv {
    /// Header.
    pub headers: Vec<String>,
    /// Cells.
    pub records: Vec<csv::StringRecord>,
    /// 1-based lines.
    pub lines: Vec<usize>,
}

/// Read a CSV with a header into raw cells. Large files without quotes are split at line
/// starts and parsed in parallel (the same records and lines as one pass; any irregularity
/// falls back to the one-pass reader, whose error is reported).
pub fn parse_raw_csv(path: &Path, bytes: &[u8]) -> Result<RawCsv, DataError> {
    if bytes.len() >= PARALLEL_CSV_BYTES && !bytes.contains(&b'"') && !bytes.contains(&b'\r') {
        if let Some(raw) = parse_raw_csv_parallel(bytes) {
            return Ok(raw);
        }
    }
    parse_raw_csv_serial(path, bytes)
}

/// Files at least this large are parsed in parallel.
const PARALLEL_CSV_BYTES: usize = 1 << 20;

fn reader(bytes: &[u8], headers: bool) -> csv::Reader<&[u8]> {
    csv::ReaderBuilder::new()
        .has_headers(headers)
        .trim(csv::Trim::All)
        .from_reader(bytes)
}

/// `bytes` cut into consecutive pieces of about `target` bytes (at least 1), each extended to
/// the end of its last line (`\n`), so that no line is split; the last piece takes the rest.
pub(crate) fn split_at_line_ends(bytes: &[u8], target: usize) -> Vec<&[u8]> {
    let target = target.max(1);
    let mut pieces = Vec::with_capacity(bytes.len() / target + 1);
    let mut start = 0;
    while start < bytes.len() {
        let mut end = (start + target).min(bytes.len());
        while end < bytes.len() && bytes[end - 1] != b'\n' {
            end += 1;
        }
        pieces.push(&bytes[start..end]);
        start = end;
    }
    pieces
}

/// Header line, then chunks of whole lines parsed on rayon's threads; `None` when a chunk does
/// not parse cleanly or a record's width differs from the header's (the serial reader then
/// reports it).
fn parse_raw_csv_parallel(bytes: &[u8]) -> Option<RawCsv> {
    use rayon::prelude::*;
    let head_end = bytes.iter().position(|&b| b == b'\n')? + 1;
    let headers: Vec<String> = reader(&bytes[..head_end], false)
        .records()
        .next()?
        .ok()?
        .iter()
        .map(str::to_string)
        .collect();
    let body = &bytes[head_end..];
    let n_chunks = (rayon::current_num_threads() * 8).max(1);
    let target = body.len().div_ceil(n_chunks).max(1);
    let chunks = split_at_line_ends(body, target);
    // First line of each chunk (the header is line 1).
    let newlines: Vec<usize> = chunks
        .par_iter()
        .map(|c| c.iter().filter(|&&b| b == b'\n').count())
        .collect();
    let mut first = Vec::with_capacity(chunks.len());
    let mut line = 2;
    for n in &newlines {
        first.push(line);
        line += n;
    }
    let width = headers.len();
    let parts: Option<Vec<(Vec<csv::StringRecord>, Vec<usize>)>> = chunks
        .par_iter()
        .zip(&first)
        .map(|(c, &first_line)| {
            let mut rdr = reader(c, false);
            let index = LineIndex::new(c);
            let mut rec = csv::StringRecord::new();
            let (mut recs, mut lines) = (Vec::new(), Vec::new());
            loop {
                match rdr.read_record(&mut rec) {
                    Ok(false) => break,
                    Ok(true) if rec.len() == width => {
                        let l = rec.position().map_or(1, |p| index.line_of(p));
                        lines.push(first_line + l - 1);
                        recs.push(rec.clone());
                    }
                    _ => return None,
                }
            }
            Some((recs, lines))
        })
        .collect();
    let parts = parts?;
    let total = parts.iter().map(|p| p.0.len()).sum();
    let (mut records, mut lines) = (Vec::with_capacity(total), Vec::with_capacity(total));
    for (r, l) in parts {
        records.extend(r);
        lines.extend(l);
    }
    Some(RawCsv {
        headers,
        records,
        lines,
    })
}

/// One pass of the `csv` reader; lines from [`LineIndex`] (right for `\n`, `\r\n` and `\r` line
/// ends alike).
fn parse_raw_csv_serial(path: &Path, bytes: &[u8]) -> Result<RawCsv, DataError> {
    let index = LineIndex::new(bytes);
    let mut rdr = reader(bytes, true);
    let headers: Vec<String> = rdr
        .headers()
        .map_err(|e| csv_error_at(&index, path, &e))?
        .iter()
        .map(str::to_string)
        .collect();
    let mut records = Vec::new();
    let mut lines = Vec::new();
    let mut rec = csv::StringRecord::new();
    loop {
        match rdr.read_record(&mut rec) {
            Ok(false) => break,
            Ok(true) => {
                lines.push(rec.position().map_or(0, |p| index.line_of(p)));
                records.push(rec.clone());
            }
            Err(e) => return Err(csv_error_at(&index, path, &e)),
        }
    }
    Ok(RawCsv {
        headers,
        records,
        lines,
    })
}

/// Which launch columns to fly and where they are: `source` picks them; `None` takes measured
/// columns when `ball_speed_mph` is present, else predicted ones. `azimuth_deg` and
/// `sidespin_rpm` may be absent (`None`: 0).
pub fn launch_columns(
    path: &Path,
    headers: &[String],
    source: Option<LaunchSource>,
) -> Result<(LaunchSource, [Option<usize>; 5]), DataError> {
    check_header(path, headers)?;
    super::columns::check_known_case(path, headers)?;
    let col = |name: &str| headers.iter().position(|h| h == name);
    let source = source.unwrap_or(if col("ball_speed_mph").is_some() {
        LaunchSource::Measured
    } else {
        LaunchSource::Predicted
    });
    let p = source.prefix();
    let mut idx = [None; 5];
    for (k, n) in LAUNCH_COLUMNS.iter().enumerate() {
        let full = format!("{p}{n}");
        idx[k] = col(&full);
        if idx[k].is_none() && k != 2 && k != 4 {
            // No shots-file launch column at all: most likely a monitor's export as written.
            let export = !headers.iter().any(|h| {
                LAUNCH_COLUMNS
                    .iter()
                    .any(|n| h == n || h.strip_prefix("pred_") == Some(n))
            });
            return Err(DataError::file(
                path,
                format!(
                    "missing column '{full}' (a launch file needs {p}ball_speed_mph, {p}launch_angle_deg, \
                     {p}backspin_rpm, and optionally {p}azimuth_deg and {p}sidespin_rpm){}",
                    if export {
                        "; a launch monitor's export is converted first: smash import EXPORT.csv \
                         --out shots.csv (docs/import.md)"
                    } else {
                        ""
                    }
                ),
            ));
        }
    }
    Ok((source, idx))
}

/// A launch file's header says what it is before any column is looked for: an empty file, or a
/// header of one column holding `;` or a tab (another separator), is named as such rather than
/// as lacking `pred_ball_speed_mph`; a column given twice is refused (the first was flown, the
/// second silently ignored).
fn check_header(path: &Path, headers: &[String]) -> Result<(), DataError> {
    let at = |m: String| DataError::at(path, Some(1), None, m);
    match headers {
        [] => {
            return Err(at(
                "the file is empty; a launch file has a header line naming its \
                            comma-separated columns, then one line per launch"
                    .into(),
            ))
        }
        [one] if one.contains(';') || one.contains('\t') => {
            let sep = if one.contains(';') { "';'" } else { "tabs" };
            return Err(at(format!(
                "the header is one column separated by {sep}, not commas; a launch file is \
                 comma-separated (decimal points, not commas)"
            )));
        }
        _ => {}
    }
    for (j, h) in headers.iter().enumerate() {
        if let Some(k) = headers[..j].iter().position(|x| x == h && !h.is_empty()) {
            return Err(DataError::at(
                path,
                Some(1),
                Some(format!("column '{}'", crate::data::escape(h))),
                format!(
                    "given twice (columns {} and {}); give each column once",
                    k + 1,
                    j + 1
                ),
            ));
        }
    }
    Ok(())
}

/// A flight error at a record, as a file error (`prefix` is the launch columns' prefix).
pub fn flight_error_at(path: &Path, line: usize, prefix: &str, e: &FlightError) -> DataError {
    match e {
        FlightError::InvalidLaunch { field, .. } => DataError::at(
            path,
            Some(line),
            Some(format!("column '{prefix}{field}'")),
            e.to_string(),
        ),
        FlightError::NeverLands { .. } => DataError::at(path, Some(line), None, e.to_string()),
    }
}

fn is_flight_output(h: &str) -> bool {
    FLIGHT_COLUMNS
        .iter()
        .any(|c| h.strip_prefix("pred_").or_else(|| h.strip_prefix("err_")) == Some(c))
}

/// The columns of a flight output file: which input columns are kept, which flight columns
/// follow, and which of them have a measured column (for `err_`).
#[derive(Debug, Clone)]
pub struct OutputLayout {
    /// Input columns kept (earlier flight outputs dropped).
    pub keep: Vec<usize>,
    /// Flight outputs written, indices into [`FLIGHT_COLUMNS`].
    pub outs: Vec<usize>,
    /// `(flight output, input column of its measured value)` for the `err_` columns.
    pub measured: Vec<(usize, usize)>,
    header: Vec<String>,
}

impl OutputLayout {
    /// The layout for an input header; `with_total`: add `total_yd`.
    pub fn new(headers: &[String], with_total: bool) -> Self {
        let keep: Vec<usize> = (0..headers.len())
            .filter(|&i| !is_flight_output(&headers[i]))
            .collect();
        let outs: Vec<usize> = (0..FLIGHT_COLUMNS.len())
            .filter(|&k| k < 5 || with_total)
            .collect();
        let measured: Vec<(usize, usize)> = outs
            .iter()
            .filter_map(|&k| {
                headers
                    .iter()
                    .position(|h| h == FLIGHT_COLUMNS[k])
                    .map(|i| (k, i))
            })
            .collect();
        let mut header: Vec<String> = keep.iter().map(|&i| headers[i].clone()).collect();
        header.extend(outs.iter().map(|&k| format!("pred_{}", FLIGHT_COLUMNS[k])));
        header.extend(
            measured
                .iter()
                .map(|&(k, _)| format!("err_{}", FLIGHT_COLUMNS[k])),
        );
        Self {
            keep,
            outs,
            measured,
            header,
        }
    }

    /// The header line, CSV-quoted where needed, with its newline.
    pub fn header_line(&self) -> Vec<u8> {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(&self.header).expect("writing to memory");
        w.into_inner().expect("flushing memory")
    }
}

/// CSV bytes: input columns (earlier flight outputs dropped), the `pred_` flight columns and
/// `err_` columns where measured flight columns exist. `with_total`: add `total_yd`.
pub fn flight_csv<F: FlightRow>(
    headers: &[String],
    records: &[csv::StringRecord],
    flights: &[F],
    with_total: bool,
) -> Vec<u8> {
    assert_eq!(records.len(), flights.len(), "one flight per record");
    let layout = OutputLayout::new(headers, with_total);
    let (keep, outs, measured) = (&layout.keep, &layout.outs, &layout.measured);
    let mut out = layout.header_line();
    // Rows in parallel chunks, each its own CSV writer (same quoting), joined in order.
    use rayon::prelude::*;
    let chunk = 4096;
    let parts: Vec<Vec<u8>> = records
        .par_chunks(chunk)
        .zip(flights.par_chunks(chunk))
        .map(|(recs, fs)| {
            let mut w = csv::Writer::from_writer(Vec::with_capacity(recs.len() * 96));
            let mut num = Vec::with_capacity(32);
            for (rec, f) in recs.iter().zip(fs) {
                let f = f.flight();
                for &i in keep {
                    w.write_field(rec.get(i).unwrap_or(""))
                        .expect("writing to memory");
                }
                for &k in outs {
                    num.clear();
                    if let Some(v) = f.and_then(|f| flight_value(f, k)) {
                        push_cell(&mut num, v);
                    }
                    w.write_field(&num).expect("writing to memory");
                }
                for &(k, i) in measured {
                    let m = rec.get(i).and_then(|c| measured_value(k, c));
                    num.clear();
                    if let (Some(p), Some(m)) = (f.and_then(|f| flight_value(f, k)), m) {
                        push_cell(&mut num, p - m);
                    }
                    w.write_field(&num).expect("writing to memory");
                }
                w.write_record(None::<&[u8]>).expect("writing to memory");
            }
            w.into_inner().expect("flushing memory")
        })
        .collect();
    out.reserve(parts.iter().map(Vec::len).sum());
    for p in parts {
        out.extend_from_slice(&p);
    }
    out
}

/// A row's flight for [`flight_csv`]: a [`Flight`], or an `Option` of one whose `None` writes the
/// row with empty flight cells (a predicted launch the flight model does not take).
pub trait FlightRow: Sync {
    /// The flight, if the row has one.
    fn flight(&self) -> Option<&Flight>;
}

impl FlightRow for Flight {
    fn flight(&self) -> Option<&Flight> {
        Some(self)
    }
}

impl FlightRow for Option<Flight> {
    fn flight(&self) -> Option<&Flight> {
        self.as_ref()
    }
}

/// Read the `[atmosphere]` table of a TOML file (other tables are ignored, so a study file can
/// carry it); unknown keys inside it are errors naming the key.
pub fn read_atmosphere(path: &Path) -> Result<Atmosphere, DataError> {
    let text = read_text(path)?;
    parse_atmosphere(path, &text)
}

/// [`read_atmosphere`] from text.
pub fn parse_atmosphere(path: &Path, text: &str) -> Result<Atmosphere, DataError> {
    let table: toml::Table = crate::data::toml_check::parse_toml(
        path,
        text,
        "an atmosphere file holds an [atmosphere] table",
    )?;
    let Some(a) = table.get("atmosphere") else {
        return Err(DataError::file(path, "no [atmosphere] table"));
    };
    let atm: Atmosphere = a.clone().try_into().map_err(|e: toml::de::Error| {
        DataError::at(
            path,
            None,
            Some("table [atmosphere]".into()),
            e.message().to_string(),
        )
    })?;
    atm.air().map_err(|e| {
        DataError::at(
            path,
            None,
            Some(format!("key atmosphere.{}", e.key)),
            e.to_string(),
        )
    })?;
    Ok(atm)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parallel_csv_reading_equals_one_pass() {
        // Over the parallel threshold, with blank lines, padded cells and no final newline.
        let mut text = String::from("shot_id, ball_speed_mph,launch_angle_deg\n");
        let mut k = 0;
        while text.len() < 3 * PARALLEL_CSV_BYTES {
            text.push_str(&format!("s{k}, {}.5 ,{}\n", 100 + k % 90, k % 40));
            if k % 977 == 0 {
                text.push('\n');
            }
            k += 1;
        }
        text.push_str("last,150,12");
        let p = Path::new("big.csv");
        let par = parse_raw_csv(p, text.as_bytes()).unwrap();
        let one = parse_raw_csv_serial(p, text.as_bytes()).unwrap();
        assert!(parse_raw_csv_parallel(text.as_bytes()).is_some());
        assert_eq!(par.headers, one.headers);
        assert_eq!(par.records, one.records);
        assert_eq!(par.lines, one.lines);
        // A short row: the one-pass reader's error, with its line.
        let bad = text.replacen("s5, 105.5 ,5", "s5,105.5", 1);
        let e = parse_raw_csv(p, bad.as_bytes()).unwrap_err().to_string();
        // Line 8: the header, s0, the blank line after it, s1 … s5.
        assert!(e.contains("big.csv:8"), "{e}");
    }

    #[test]
    fn atmosphere_table() {
        let p = Path::new("a.toml");
        let a =
            parse_atmosphere(p, "[atmosphere]\ntemperature_c = 30\nelevation_m = 1600\n").unwrap();
        assert_eq!(a.temperature_c, 30.0);
        assert_eq!(a.elevation_m, Some(1600.0));
        let e = parse_atmosphere(p, "[atmosphere]\ntemprature_c = 30\n").unwrap_err();
        assert!(e.to_string().contains("temprature_c"), "{e}");
        let e = parse_atmosphere(p, "[atmosphere]\nhumidity_pct = 130\n").unwrap_err();
        assert!(e.to_string().contains("humidity_pct"), "{e}");
        assert!(parse_atmosphere(p, "[club]\n").is_err());
    }
}
