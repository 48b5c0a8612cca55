//! Reading a launch file for `smash flight`: the launch of every row, checked (a number in each
//! launch cell, a launch the flight model takes, measured flight cells in their ranges), and the
//! rows that fail left out and counted ([`crate::data::left_out`]) unless `--strict`. The
//! streamed flight ([`crate::app::flight::stream`]) makes the same checks piece by piece.

use std::path::Path;

use crate::data::flight_files::{
    flight_error_at, launch_columns, parse_raw_csv, LaunchSource, LaunchTable, OutputLayout,
    FLIGHT_COLUMNS, LAUNCH_COLUMNS,
};
use crate::data::number::parse_f64;
use crate::data::{read_text, DataError};
use crate::flight::FlightLaunch;

/// How to read a launch file.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LaunchRead {
    /// Which launch columns: `None` takes measured columns when `ball_speed_mph` is present,
    /// else predicted ones.
    pub source: Option<LaunchSource>,
    /// The output has `total_yd` (a ground model): the measured `total_yd` is checked too.
    pub with_total: bool,
    /// Refuse the file at its first row that cannot be used; by default such rows are left
    /// out and counted ([`LaunchTable::left_out`], [`crate::data::left_out`]).
    pub strict: bool,
}

/// Read launches from a CSV (`read`: which columns, how strictly). `azimuth_deg` and
/// `sidespin_rpm` may be absent (0). A row whose launch cell is not a number, whose launch the
/// flight model does not take ([`FlightLaunch::check`]) or whose measured flight cell is bad
/// ([`crate::data::flight_measured`]) is left out and counted.
pub fn read_launches(path: &Path, read: LaunchRead) -> Result<LaunchTable, DataError> {
    let text = read_text(path)?;
    parse_launches(path, text.as_bytes(), read)
}

/// [`read_launches`] from the file's bytes (`path` names it in messages).
pub fn parse_launches(
    path: &Path,
    bytes: &[u8],
    read: LaunchRead,
) -> Result<LaunchTable, DataError> {
    let raw = parse_raw_csv(path, bytes)?;
    let (source, idx) = launch_columns(path, &raw.headers, read.source)?;
    let layout = OutputLayout::new(&raw.headers, read.with_total);
    let p = source.prefix();
    let names = LAUNCH_COLUMNS;
    use rayon::prelude::*;
    let parsed: Vec<Result<FlightLaunch, DataError>> = raw
        .records
        .par_iter()
        .zip(&raw.lines)
        .map(|(rec, &line)| {
            let mut v = [0.0; 5];
            for k in 0..5 {
                if let Some(i) = idx[k] {
                    let cell = rec.get(i).unwrap_or("");
                    v[k] = parse_f64(cell).filter(|x| x.is_finite()).ok_or_else(|| {
                        DataError::at(
                            path,
                            Some(line),
                            Some(format!("column '{p}{}'", names[k])),
                            format!("{} is not a finite number", crate::data::quote_cell(cell)),
                        )
                    })?;
                }
            }
            let launch = FlightLaunch::from_file_units(v[0], v[1], v[2], v[3], v[4]);
            launch
                .check()
                .map_err(|e| flight_error_at(path, line, p, &e))?;
            check_measured_row(path, &layout, rec, line)?;
            Ok(launch)
        })
        .collect();
    let rows = raw.records.len();
    let mut table = LaunchTable {
        headers: raw.headers,
        records: Vec::with_capacity(rows),
        lines: Vec::with_capacity(rows),
        launches: Vec::with_capacity(rows),
        source,
        left_out: Vec::new(),
    };
    for ((rec, line), r) in raw.records.into_iter().zip(raw.lines).zip(parsed) {
        match r {
            Ok(l) => {
                table.records.push(rec);
                table.lines.push(line);
                table.launches.push(l);
            }
            Err(e) if read.strict => return Err(e),
            Err(e) => crate::data::left_out::push_bad(&mut table.left_out, line, e),
        }
    }
    crate::data::left_out::refuse_when_unusable(path, &table.left_out, table.launches.len())?;
    Ok(table)
}

/// The measured flight cells of one record the output compares with, checked
/// ([`crate::data::flight_measured::measured_flight_value`]).
fn check_measured_row(
    path: &Path,
    layout: &OutputLayout,
    rec: &csv::StringRecord,
    line: usize,
) -> Result<(), DataError> {
    for &(k, i) in &layout.measured {
        crate::data::flight_measured::measured_flight_value(k, rec.get(i).unwrap_or("")).map_err(
            |m| {
                DataError::at(
                    path,
                    Some(line),
                    Some(format!("column '{}'", FLIGHT_COLUMNS[k])),
                    m,
                )
            },
        )?;
    }
    Ok(())
}

impl LaunchTable {
    /// Keep the rows where `keep` holds; each row dropped is left out and counted with its
    /// error (`errs`, parallel to `keep`: `Some` where dropped). Under `strict` the first is
    /// returned instead. Then the file is refused when no row is left or more than half are
    /// bad ([`crate::data::left_out::refuse_when_unusable`]).
    pub fn leave_out(
        &mut self,
        path: &Path,
        errs: Vec<Option<DataError>>,
        strict: bool,
    ) -> Result<(), DataError> {
        if errs.iter().all(Option::is_none) {
            return Ok(());
        }
        let mut fresh = Vec::new();
        let mut keep = Vec::with_capacity(errs.len());
        for (e, &line) in errs.into_iter().zip(&self.lines) {
            keep.push(e.is_none());
            if let Some(e) = e {
                if strict {
                    return Err(e);
                }
                fresh.push((line, e));
            }
        }
        for (line, e) in fresh {
            crate::data::left_out::push_bad(&mut self.left_out, line, e);
        }
        crate::data::left_out::retain_kept(&mut self.records, &keep);
        crate::data::left_out::retain_kept(&mut self.lines, &keep);
        crate::data::left_out::retain_kept(&mut self.launches, &keep);
        crate::data::left_out::refuse_when_unusable(path, &self.left_out, self.launches.len())
    }

    /// Rows of the file: those kept and those left out.
    pub fn rows(&self) -> usize {
        self.launches.len() + self.left_out.iter().map(|l| l.lines.len()).sum::<usize>()
    }
}
