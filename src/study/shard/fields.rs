//! The cells and records of a shard's CSV files (`rows.csv`, `metrics.csv`) for `smash merge`:
//! each cell checked against what `smash run --shard` writes, each record at its line (any line
//! ends, streamed).

use std::path::Path;

use crate::data::{csv_error_at, quote_cell, DataError};
use crate::line_index::{LineTracker, RecordLines};

/// `value` of `col` on `line` as an index below `limit` (what it counts is `what`).
pub(super) fn index(
    path: &Path,
    line: u64,
    col: &str,
    s: &str,
    limit: usize,
    what: &str,
) -> Result<usize, DataError> {
    let at = |m: String| DataError::at(path, Some(line as usize), Some(format!("column {col}")), m);
    let v = s
        .parse::<usize>()
        .map_err(|_| at(format!("not an index: {}", quote_cell(s))))?;
    if v >= limit {
        return Err(at(format!(
            "{v} is outside the study: it has {limit} {what} (0 to {})",
            limit.saturating_sub(1)
        )));
    }
    Ok(v)
}

pub(super) fn num(path: &Path, line: u64, col: &str, s: &str) -> Result<f64, DataError> {
    if s.is_empty() {
        return Ok(f64::NAN);
    }
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| {
            DataError::at(
                path,
                Some(line as usize),
                Some(format!("column {col}")),
                format!("not a finite number: {}", quote_cell(s)),
            )
        })
}

/// Largest launch value (SI units) a shard's point may hold: far above any impact's (ball speeds
/// of ~100 m/s, spins of ~1000 rad/s) and far below what overflows in the merge's unit
/// conversions (1e308 m/s became an infinite mph).
const MAX_LAUNCH_SI: f64 = 1e6;

/// A launch value of a point: a number within ±[`MAX_LAUNCH_SI`] where the point is valid, an
/// empty cell where it is not (as `smash run --shard` writes them; anything else is a damaged
/// or edited file).
pub(super) fn launch_value(
    path: &Path,
    line: u64,
    col: &str,
    s: &str,
    valid: bool,
) -> Result<f64, DataError> {
    let at = |m: String| DataError::at(path, Some(line as usize), Some(format!("column {col}")), m);
    if !valid {
        return match s {
            "" => Ok(f64::NAN),
            _ => Err(at(format!(
                "{} on a point marked invalid (valid = 0), whose values are empty",
                quote_cell(s)
            ))),
        };
    }
    match s.parse::<f64>() {
        Ok(v) if v.abs() <= MAX_LAUNCH_SI => Ok(v),
        _ => Err(at(format!(
            "{} on a valid point: a number within ±{} is required (SI units; the shard file \
             is damaged or was edited)",
            quote_cell(s),
            crate::limits::fmt_value(MAX_LAUNCH_SI)
        ))),
    }
}

/// A CSV reader whose lines are counted as it reads (any line ends; a few kB of memory).
pub(super) type Tracked<R> = csv::Reader<LineTracker<R>>;

/// A CSV reader over `input` whose header must be exactly `header`; records must have as many
/// fields.
pub(super) fn csv_records<R: std::io::Read>(
    path: &Path,
    input: R,
    header: &str,
) -> Result<Tracked<R>, DataError> {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(LineTracker::new(input));
    let h = match r.headers() {
        Ok(h) => h,
        Err(e) => return Err(csv_error_at(r.get_ref(), path, &e)),
    };
    if h.iter().collect::<Vec<_>>().join(",") != header {
        return Err(DataError::at(
            path,
            Some(1),
            None,
            format!("header must be {header}"),
        ));
    }
    Ok(r)
}

/// The next record of `r` into `rec` and its line, `None` at the end.
pub(super) fn next_record<R: std::io::Read>(
    path: &Path,
    r: &mut Tracked<R>,
    rec: &mut csv::StringRecord,
) -> Result<Option<u64>, DataError> {
    match r.read_record(rec) {
        Ok(false) => Ok(None),
        Ok(true) => Ok(Some(
            rec.position().map_or(0, |p| r.get_ref().line_of(p)) as u64
        )),
        Err(e) => Err(csv_error_at(r.get_ref(), path, &e)),
    }
}
