//! `smash flight` on a file of any size: the launch CSV is read a chunk at a time; each chunk is
//! cut at line starts into pieces that rayon's threads parse, fly and format (one pass over a
//! piece, so its launches and flights stay in cache); a writer thread appends the pieces, in
//! input order, to a temporary file beside the output while the next chunk is worked on, and
//! the temporary replaces the output only when every row has flown. Memory is bounded by the
//! chunk size whatever the file's length.
//!
//! The output is byte for byte what [`flight_csv`] writes for the same input (tested below).
//! Files the plain splitter does not handle exactly as the `csv` reader does (quoted cells,
//! carriage returns, a byte-order mark, invalid UTF-8) go through the one-piece path instead:
//! [`fly_csv_bytes`] ([`parse_launches`], [`fly`](crate::flight::fly), [`flight_csv`]).

use std::io::{Read, Write};
use std::path::Path;

use rayon::prelude::*;

use crate::data::flight_files::{
    flight_csv, flight_error_at, flight_value, launch_columns, parse_launches, split_at_line_ends,
    LaunchSource, OutputLayout, FLIGHT_COLUMNS, LAUNCH_COLUMNS,
};
use crate::data::flight_measured::{check_measured, measured_flight_value};
use crate::data::flight_output::Temporary;
use crate::data::number::{parse_f64, push_cell};
use crate::data::{safe_write, write_atomic, DataError};
use crate::flight::integrate::fly_serial;
use crate::flight::{Flight, FlightConfig, FlightError, FlightLaunch};

/// Bytes of input read per chunk (about 60,000 launches of a typical file): large enough that
/// the threads' start-up per chunk is negligible, small enough to bound memory.
pub const CHUNK_BYTES: usize = 1 << 22;
/// Bytes of input per piece a thread takes (about a thousand launches).
const PIECE_BYTES: usize = 1 << 16;

/// What a run flew.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Flown {
    /// Launches flown (data rows).
    pub shots: usize,
    /// Which launch columns were flown.
    pub source: LaunchSource,
}

/// Fly every launch of `input` and write the flight file `out` (see the module
/// documentation). `chunk_bytes`: input read per chunk ([`CHUNK_BYTES`] in use; tests make it
/// small). The first bad row (in file order) stops the run with an error naming the file, line
/// and column; then `out` is left as it was.
pub fn fly_csv_file(
    input: &Path,
    out: &Path,
    cfg: &FlightConfig,
    source: Option<LaunchSource>,
    chunk_bytes: usize,
) -> Result<Flown, DataError> {
    match stream(input, out, cfg, source, chunk_bytes.max(1))? {
        Some(flown) => Ok(flown),
        None => in_memory(input, out, cfg, source),
    }
}

/// The one-piece path (files with quoting, carriage returns, a byte-order mark or invalid
/// UTF-8).
fn in_memory(
    input: &Path,
    out: &Path,
    cfg: &FlightConfig,
    source: Option<LaunchSource>,
) -> Result<Flown, DataError> {
    let text = crate::data::read_text(input)?;
    let (bytes, flown) = fly_csv_bytes(input, text.as_bytes(), cfg, source)?;
    write_atomic(out, &bytes)?;
    Ok(flown)
}

/// The flight file of the launch CSV `bytes` (`input` names it in messages), in memory: what
/// [`fly_csv_file`] writes for a file holding `bytes`.
pub fn fly_csv_bytes(
    input: &Path,
    bytes: &[u8],
    cfg: &FlightConfig,
    source: Option<LaunchSource>,
) -> Result<(Vec<u8>, Flown), DataError> {
    let table = parse_launches(input, bytes, source)?;
    let layout = OutputLayout::new(&table.headers, cfg.ground.is_some());
    check_measured(input, &layout, &table.records, &table.lines)?;
    let results = crate::flight::fly(cfg, &table.launches);
    let prefix = table.source.prefix();
    let flights = results
        .into_iter()
        .zip(&table.lines)
        .map(|(r, &line)| r.map_err(|e| flight_error_at(input, line, prefix, &e)))
        .collect::<Result<Vec<Flight>, DataError>>()?;
    let csv = flight_csv(
        &table.headers,
        &table.records,
        &flights,
        cfg.ground.is_some(),
    );
    Ok((
        csv,
        Flown {
            shots: flights.len(),
            source: table.source,
        },
    ))
}

/// Where the columns are, from the header.
struct Plan {
    width: usize,
    launch: [Option<usize>; 5],
    prefix: &'static str,
    layout: OutputLayout,
}

/// Why a piece stopped.
enum Stop {
    /// Not plain CSV: the whole file goes the one-piece way.
    NotPlain,
    /// A bad row at this 0-based line of the piece.
    Bad(usize, Bad),
}

enum Bad {
    Width(usize),
    /// A launch cell (index into [`LAUNCH_COLUMNS`]) that is not a finite number.
    Cell(usize, String),
    /// A measured flight cell (index into [`FLIGHT_COLUMNS`]) and what is wrong with it.
    Measured(usize, String),
    Flight(FlightError),
}

/// One piece's output.
struct Piece {
    bytes: Vec<u8>,
    newlines: usize,
    shots: usize,
    stop: Option<Stop>,
}

/// Whether the streamed path can take `bytes`: no quoting, no CR, and no zero byte (UTF-16
/// text, which the one-piece path's reader refuses in words, looks like UTF-8 with zero bytes).
fn is_plain(bytes: &[u8]) -> bool {
    !bytes.iter().any(|&b| b == b'"' || b == b'\r' || b == 0)
}

fn trim(b: &[u8]) -> &[u8] {
    b.trim_ascii()
}

/// Read from `f` until `buf` holds at least `want` bytes or the file ends; `true` at the end.
/// Reads straight into `buf`'s spare capacity.
fn fill(f: &mut impl Read, buf: &mut Vec<u8>, want: usize) -> std::io::Result<bool> {
    while buf.len() < want {
        let need = (want - buf.len()) as u64;
        if f.by_ref().take(need).read_to_end(buf)? == 0 {
            return Ok(true);
        }
    }
    Ok(false)
}

/// `Ok(None)`: not plain, nothing written (the caller takes the one-piece path).
fn stream(
    input: &Path,
    out: &Path,
    cfg: &FlightConfig,
    source: Option<LaunchSource>,
    chunk_bytes: usize,
) -> Result<Option<Flown>, DataError> {
    let read_err = |e: std::io::Error| DataError::file(input, format!("cannot read: {e}"));
    safe_write::note_input(input);
    let mut file = std::fs::File::open(input).map_err(read_err)?;
    let mut buf: Vec<u8> = Vec::with_capacity(chunk_bytes + PIECE_BYTES);
    // The header: the first line.
    let mut eof = false;
    let head_end = loop {
        if let Some(i) = buf.iter().position(|&b| b == b'\n') {
            break i + 1;
        }
        if eof {
            break buf.len();
        }
        let want = buf.len() + PIECE_BYTES;
        eof = fill(&mut file, &mut buf, want).map_err(read_err)?;
    };
    let head = &buf[..head_end];
    let head_text = match std::str::from_utf8(head) {
        Ok(t) if is_plain(head) && !t.starts_with('\u{feff}') && !trim(head).is_empty() => t,
        _ => return Ok(None),
    };
    let headers: Vec<String> = head_text
        .trim_end_matches('\n')
        .split(',')
        .map(|h| h.trim_ascii().to_string())
        .collect();
    let (source, launch) = launch_columns(input, &headers, source)?;
    let plan = Plan {
        width: headers.len(),
        launch,
        prefix: source.prefix(),
        layout: OutputLayout::new(&headers, cfg.ground.is_some()),
    };
    buf.drain(..head_end);
    let tmp = Temporary::create(out)?;
    let mut w = tmp
        .file
        .try_clone()
        .map_err(|e| DataError::file(out, format!("cannot write: {e}")))?;
    let written = std::thread::scope(|scope| {
        let (tx, rx) = std::sync::mpsc::sync_channel::<Vec<Vec<u8>>>(2);
        let writer = scope.spawn(move || -> std::io::Result<()> {
            for parts in rx {
                for p in parts {
                    w.write_all(&p)?;
                }
            }
            Ok(())
        });
        let run = (|| -> Result<Option<usize>, DataError> {
            if tx.send(vec![plan.layout.header_line()]).is_err() {
                return Ok(Some(0));
            }
            let (mut line, mut shots) = (2usize, 0usize);
            loop {
                if !eof {
                    eof = fill(&mut file, &mut buf, chunk_bytes).map_err(read_err)?;
                }
                let end = if eof {
                    buf.len()
                } else {
                    match buf.iter().rposition(|&b| b == b'\n') {
                        Some(i) => i + 1,
                        None => {
                            // A line longer than the chunk: read on.
                            let want = buf.len() + chunk_bytes;
                            eof = fill(&mut file, &mut buf, want).map_err(read_err)?;
                            continue;
                        }
                    }
                };
                let chunk = &buf[..end];
                if !is_plain(chunk) {
                    return Ok(None);
                }
                let pieces = fly_chunk(&plan, cfg, chunk);
                let mut parts = Vec::with_capacity(pieces.len());
                for p in pieces {
                    match p.stop {
                        None => {}
                        Some(Stop::NotPlain) => return Ok(None),
                        Some(Stop::Bad(at, bad)) => {
                            return Err(bad_row(input, &plan, line + at, bad));
                        }
                    }
                    line += p.newlines;
                    shots += p.shots;
                    parts.push(p.bytes);
                }
                if tx.send(parts).is_err() {
                    break;
                }
                buf.drain(..end);
                if eof && buf.is_empty() {
                    break;
                }
            }
            Ok(Some(shots))
        })();
        drop(tx);
        let wrote = writer.join().expect("the writer thread does not panic");
        (run, wrote)
    });
    match written {
        (Ok(Some(shots)), Ok(())) => {
            tmp.commit()?;
            Ok(Some(Flown { shots, source }))
        }
        (Ok(None), _) => Ok(None),
        (Err(e), _) => Err(e),
        (Ok(Some(_)), Err(e)) => Err(DataError::file(out, format!("cannot write: {e}"))),
    }
}

fn bad_row(input: &Path, plan: &Plan, line: usize, bad: Bad) -> DataError {
    match bad {
        Bad::Width(n) => DataError::at(
            input,
            Some(line),
            None,
            crate::line_index::field_count_message(n as u64, plan.width as u64),
        ),
        Bad::Cell(k, cell) => DataError::at(
            input,
            Some(line),
            Some(format!("column '{}{}'", plan.prefix, LAUNCH_COLUMNS[k])),
            format!("{} is not a finite number", crate::data::quote_cell(&cell)),
        ),
        Bad::Measured(k, message) => DataError::at(
            input,
            Some(line),
            Some(format!("column '{}'", FLIGHT_COLUMNS[k])),
            message,
        ),
        Bad::Flight(e) => flight_error_at(input, line, plan.prefix, &e),
    }
}

/// Cut `chunk` (whole lines) into pieces at line starts and work them in parallel, in order.
fn fly_chunk(plan: &Plan, cfg: &FlightConfig, chunk: &[u8]) -> Vec<Piece> {
    split_at_line_ends(chunk, PIECE_BYTES)
        .par_iter()
        .map(|p| fly_piece(plan, cfg, p))
        .collect()
}

/// Parse, fly and format one piece of whole lines. Stops at its first bad row (parse errors
/// and flight errors in line order).
fn fly_piece(plan: &Plan, cfg: &FlightConfig, bytes: &[u8]) -> Piece {
    let newlines = bytes.iter().filter(|&&b| b == b'\n').count();
    let mut piece = Piece {
        bytes: Vec::new(),
        newlines,
        shots: 0,
        stop: None,
    };
    if std::str::from_utf8(bytes).is_err() {
        piece.stop = Some(Stop::NotPlain);
        return piece;
    }
    let w = plan.width;
    // Field spans of every row (w per row), the row's 0-based line in the piece, its launch.
    let mut spans: Vec<(u32, u32)> = Vec::with_capacity(newlines * w + w);
    let mut rows: Vec<usize> = Vec::with_capacity(newlines + 1);
    let mut launches: Vec<FlightLaunch> = Vec::with_capacity(newlines + 1);
    let mut parse_stop: Option<(usize, Bad)> = None;
    let mut pos = 0usize;
    for (li, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line_start = pos;
        pos += raw.len() + 1;
        if raw.is_empty() {
            continue;
        }
        let first = spans.len();
        let mut at = line_start;
        for field in raw.split(|&b| b == b',') {
            let t = trim(field);
            let s = at + (t.as_ptr() as usize - field.as_ptr() as usize);
            spans.push((s as u32, (s + t.len()) as u32));
            at += field.len() + 1;
        }
        let n = spans.len() - first;
        if n != w {
            spans.truncate(first);
            parse_stop = Some((li, Bad::Width(n)));
            break;
        }
        let cells = &spans[first..];
        let mut v = [0.0; 5];
        let mut bad = None;
        for (k, col) in plan.launch.iter().enumerate() {
            if let Some(i) = *col {
                let (s, e) = cells[i];
                let cell = &bytes[s as usize..e as usize];
                // Valid UTF-8 (checked above) split at ASCII bytes.
                let text = std::str::from_utf8(cell).unwrap_or("");
                match parse_f64(text) {
                    Some(x) if x.is_finite() => v[k] = x,
                    _ => {
                        bad = Some(Bad::Cell(k, text.to_string()));
                        break;
                    }
                }
            }
        }
        if bad.is_none() {
            for &(k, i) in &plan.layout.measured {
                let (s, e) = cells[i];
                let text = std::str::from_utf8(&bytes[s as usize..e as usize]).unwrap_or("");
                if let Err(m) = measured_flight_value(k, text) {
                    bad = Some(Bad::Measured(k, m));
                    break;
                }
            }
        }
        if let Some(b) = bad {
            spans.truncate(first);
            parse_stop = Some((li, b));
            break;
        }
        rows.push(li);
        launches.push(FlightLaunch::from_file_units(v[0], v[1], v[2], v[3], v[4]));
    }
    let mut results = vec![Err(FlightError::NeverLands { time_limit_s: 0.0 }); launches.len()];
    fly_serial(cfg, &launches, &mut results);
    if let Some(r) = results.iter().position(|r| r.is_err()) {
        if let Err(e) = results[r] {
            piece.stop = Some(Stop::Bad(rows[r], Bad::Flight(e)));
            return piece;
        }
    }
    if let Some((li, bad)) = parse_stop {
        piece.stop = Some(Stop::Bad(li, bad));
        return piece;
    }
    piece.shots = launches.len();
    piece.bytes = format_rows(plan, bytes, &spans, &results);
    piece
}

/// The output rows of a piece (as [`flight_csv`] writes them: no cell of a plain file needs
/// quoting).
fn format_rows(
    plan: &Plan,
    bytes: &[u8],
    spans: &[(u32, u32)],
    results: &[Result<Flight, FlightError>],
) -> Vec<u8> {
    let w = plan.width;
    let l = &plan.layout;
    let mut out = Vec::with_capacity(bytes.len() + results.len() * 100);
    for (cells, f) in spans.chunks_exact(w).zip(results) {
        let Ok(f) = f else { continue };
        let cell = |i: usize| &bytes[cells[i].0 as usize..cells[i].1 as usize];
        let mut first = true;
        let mut sep = |out: &mut Vec<u8>| {
            if !first {
                out.push(b',');
            }
            first = false;
        };
        // Kept cells that follow one another in the input with one comma between them (no
        // padding) are copied as one run of bytes, commas included.
        let mut run: Option<(usize, u32, u32)> = None;
        for &i in &l.keep {
            let (s, e) = cells[i];
            match &mut run {
                Some((last, _, end)) if i == *last + 1 && s == *end + 1 => {
                    *last = i;
                    *end = e;
                }
                _ => {
                    if let Some((_, rs, re)) = run {
                        sep(&mut out);
                        out.extend_from_slice(&bytes[rs as usize..re as usize]);
                    }
                    run = Some((i, s, e));
                }
            }
        }
        if let Some((_, rs, re)) = run {
            sep(&mut out);
            out.extend_from_slice(&bytes[rs as usize..re as usize]);
        }
        for &k in &l.outs {
            sep(&mut out);
            if let Some(v) = flight_value(f, k) {
                push_cell(&mut out, v);
            }
        }
        for &(k, i) in &l.measured {
            sep(&mut out);
            let m = std::str::from_utf8(cell(i)).ok().and_then(parse_f64);
            if let (Some(p), Some(m)) = (flight_value(f, k), m) {
                if m.is_finite() {
                    push_cell(&mut out, p - m);
                }
            }
        }
        out.push(b'\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn launch_file(n: usize, extra: &str) -> String {
        let mut t = String::from("shot_id, ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm,carry_yd\n");
        for k in 0..n {
            let f = |a: f64| (k as f64 * a).fract();
            t.push_str(&format!(
                "s{k}, {} ,{},{},{},{},{}\n",
                150.0 + 30.0 * f(0.618),
                8.0 + 6.0 * f(0.755),
                -3.0 + 6.0 * f(0.57),
                2000.0 + 1200.0 * f(0.439),
                -600.0 + 1200.0 * f(0.352),
                if k % 7 == 0 {
                    String::new()
                } else {
                    format!("{}", 250 + k % 40)
                }
            ));
            if k % 500 == 0 {
                t.push('\n');
            }
        }
        t.push_str(extra);
        t
    }

    #[test]
    fn streamed_output_equals_the_one_piece_output() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("l.csv");
        // No final newline, blank lines, padded cells, an empty measured cell.
        std::fs::write(&input, launch_file(3000, "last,160,11,0,2500,0,270")).unwrap();
        let cfg = FlightConfig {
            ground: Some(crate::flight::Ground::default()),
            ..FlightConfig::default()
        };
        let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
        let fa = fly_csv_file(&input, &a, &cfg, None, 10_000).unwrap();
        let fb = in_memory(&input, &b, &cfg, None).unwrap();
        assert_eq!(fa, fb);
        assert_eq!(fa.shots, 3001);
        assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
        // One chunk or many: the same bytes.
        let c = dir.path().join("c.csv");
        fly_csv_file(&input, &c, &cfg, None, CHUNK_BYTES).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&c).unwrap());
    }

    #[test]
    fn the_first_bad_row_is_reported_and_nothing_written() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("o.csv");
        std::fs::write(&out, "keep me").unwrap();
        let cfg = FlightConfig::default();
        let text = launch_file(2000, "");
        let lines: Vec<&str> = text.lines().collect();
        // Line 1500 of the file gets a bad speed, line 1800 a short row: the first is named.
        let mut bad = String::new();
        for (i, l) in lines.iter().enumerate() {
            let l = match i + 1 {
                1500 => "bad, abc ,10,0,2500,0,".to_string(),
                1800 => "x,1".to_string(),
                _ => l.to_string(),
            };
            bad.push_str(&l);
            bad.push('\n');
        }
        let input = dir.path().join("bad.csv");
        std::fs::write(&input, &bad).unwrap();
        let one = in_memory(&input, &out, &cfg, None).unwrap_err().to_string();
        for chunk in [4096, CHUNK_BYTES] {
            let e = fly_csv_file(&input, &out, &cfg, None, chunk)
                .unwrap_err()
                .to_string();
            assert!(e.contains("bad.csv:1500"), "{e}");
            assert!(
                one.contains("bad.csv:1500") || one.contains("bad.csv:1800"),
                "{one}"
            );
        }
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "keep me");
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(left.len(), 2, "no temporary left");
    }

    #[test]
    fn quoted_files_take_the_one_piece_path() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("q.csv");
        let mut text = launch_file(200, "");
        text.push_str("\"a, quoted\",150,10,0,2500,0,\n");
        std::fs::write(&input, &text).unwrap();
        let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
        let cfg = FlightConfig::default();
        fly_csv_file(&input, &a, &cfg, None, 1000).unwrap();
        in_memory(&input, &b, &cfg, None).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
        assert!(std::fs::read_to_string(&a)
            .unwrap()
            .contains("\"a, quoted\""));
    }
}
