//! Flight files: launch columns in (measured or predicted), flight columns out; the
//! `[atmosphere]` TOML table.
//!
//! Output columns: every input column except earlier flight outputs, then `pred_carry_yd`,
//! `pred_offline_yd`, `pred_apex_yd`, `pred_flight_time_s`, `pred_land_angle_deg` (and
//! `pred_total_yd` with a ground model), then `err_<name>` = predicted − measured for each of
//! those whose measured column (`carry_yd`, …) is in the input.

use std::path::Path;

use crate::data::{fmt_f64, read_text, DataError};
use crate::flight::{Atmosphere, Flight, FlightError, FlightLaunch};

/// The flight outputs (file names without prefix).
pub const FLIGHT_COLUMNS: [&str; 6] = [
    "carry_yd",
    "offline_yd",
    "apex_yd",
    "flight_time_s",
    "land_angle_deg",
    "total_yd",
];

fn flight_value(f: &Flight, k: usize) -> Option<f64> {
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
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LaunchSource {
    /// `ball_speed_mph`, `launch_angle_deg`, `azimuth_deg`, `backspin_rpm`, `sidespin_rpm`.
    Measured,
    /// The same with `pred_` (as `smash predict` writes them).
    Predicted,
}

impl LaunchSource {
    fn prefix(self) -> &'static str {
        match self {
            Self::Measured => "",
            Self::Predicted => "pred_",
        }
    }
}

/// A CSV of launches: the raw table and the parsed launches.
#[derive(Debug, Clone, PartialEq)]
pub struct LaunchTable {
    /// Header as in the file.
    pub headers: Vec<String>,
    /// Raw cells.
    pub records: Vec<Vec<String>>,
    /// 1-based file line of each record.
    pub lines: Vec<usize>,
    /// Parsed launches, SI.
    pub launches: Vec<FlightLaunch>,
    /// Which columns were flown.
    pub source: LaunchSource,
}

/// A raw CSV table with the line of each record.
pub struct RawCsv {
    /// Header.
    pub headers: Vec<String>,
    /// Cells.
    pub records: Vec<Vec<String>>,
    /// 1-based lines.
    pub lines: Vec<usize>,
}

/// Read a CSV with a header into raw cells.
pub fn parse_raw_csv(path: &Path, bytes: &[u8]) -> Result<RawCsv, DataError> {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .from_reader(bytes);
    let headers: Vec<String> = rdr
        .headers()
        .map_err(|e| DataError::file(path, e.to_string()))?
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
                lines.push(rec.position().map_or(0, |p| p.line() as usize));
                records.push(rec.iter().map(str::to_string).collect());
            }
            Err(e) => {
                let line = e.position().map(|p| p.line() as usize);
                return Err(DataError::at(path, line, None, e.to_string()));
            }
        }
    }
    Ok(RawCsv {
        headers,
        records,
        lines,
    })
}

/// Read launches from a CSV: `source` picks the columns; `None` takes measured columns when
/// `ball_speed_mph` is present, else predicted ones. `azimuth_deg` and `sidespin_rpm` may be
/// absent (0).
pub fn read_launches(path: &Path, source: Option<LaunchSource>) -> Result<LaunchTable, DataError> {
    let text = read_text(path)?;
    let raw = parse_raw_csv(path, text.as_bytes())?;
    let col = |name: &str| raw.headers.iter().position(|h| h == name);
    let source = source.unwrap_or(if col("ball_speed_mph").is_some() {
        LaunchSource::Measured
    } else {
        LaunchSource::Predicted
    });
    let p = source.prefix();
    let names = [
        "ball_speed_mph",
        "launch_angle_deg",
        "azimuth_deg",
        "backspin_rpm",
        "sidespin_rpm",
    ];
    let mut idx = [None; 5];
    for (k, n) in names.iter().enumerate() {
        let full = format!("{p}{n}");
        idx[k] = col(&full);
        if idx[k].is_none() && k != 2 && k != 4 {
            return Err(DataError::file(
                path,
                format!(
                    "missing column '{full}' (a launch file needs {p}ball_speed_mph, {p}launch_angle_deg, \
                     {p}backspin_rpm, and optionally {p}azimuth_deg and {p}sidespin_rpm)"
                ),
            ));
        }
    }
    let mut launches = Vec::with_capacity(raw.records.len());
    for (rec, &line) in raw.records.iter().zip(&raw.lines) {
        let mut v = [0.0; 5];
        for k in 0..5 {
            if let Some(i) = idx[k] {
                let cell = rec.get(i).map(String::as_str).unwrap_or("");
                v[k] = cell
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| {
                        DataError::at(
                            path,
                            Some(line),
                            Some(format!("column '{p}{}'", names[k])),
                            format!("'{cell}' is not a finite number"),
                        )
                    })?;
            }
        }
        launches.push(FlightLaunch::from_file_units(v[0], v[1], v[2], v[3], v[4]));
    }
    Ok(LaunchTable {
        headers: raw.headers,
        records: raw.records,
        lines: raw.lines,
        launches,
        source,
    })
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

/// CSV bytes: input columns (earlier flight outputs dropped), the `pred_` flight columns and
/// `err_` columns where measured flight columns exist. `with_total`: add `total_yd`.
pub fn flight_csv(
    headers: &[String],
    records: &[Vec<String>],
    flights: &[Flight],
    with_total: bool,
) -> Vec<u8> {
    assert_eq!(records.len(), flights.len(), "one flight per record");
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
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut header: Vec<String> = keep.iter().map(|&i| headers[i].clone()).collect();
    header.extend(outs.iter().map(|&k| format!("pred_{}", FLIGHT_COLUMNS[k])));
    header.extend(
        measured
            .iter()
            .map(|&(k, _)| format!("err_{}", FLIGHT_COLUMNS[k])),
    );
    w.write_record(&header).expect("writing to memory");
    let mut row: Vec<String> = Vec::with_capacity(header.len());
    for (rec, f) in records.iter().zip(flights) {
        row.clear();
        row.extend(
            keep.iter()
                .map(|&i| rec.get(i).cloned().unwrap_or_default()),
        );
        row.extend(
            outs.iter()
                .map(|&k| flight_value(f, k).map(fmt_f64).unwrap_or_default()),
        );
        for &(k, i) in &measured {
            let m = rec.get(i).and_then(|c| c.parse::<f64>().ok());
            row.push(match (flight_value(f, k), m) {
                (Some(p), Some(m)) if m.is_finite() => fmt_f64(p - m),
                _ => String::new(),
            });
        }
        w.write_record(&row).expect("writing to memory");
    }
    w.into_inner().expect("flushing memory")
}

/// Read the `[atmosphere]` table of a TOML file (other tables are ignored, so a study file can
/// carry it); unknown keys inside it are errors naming the key.
pub fn read_atmosphere(path: &Path) -> Result<Atmosphere, DataError> {
    let text = read_text(path)?;
    parse_atmosphere(path, &text)
}

/// [`read_atmosphere`] from text.
pub fn parse_atmosphere(path: &Path, text: &str) -> Result<Atmosphere, DataError> {
    let table: toml::Table =
        toml::from_str(text).map_err(|e| DataError::file(path, e.message().to_string()))?;
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
