//! Per-shot conditions in a launch file: an export normalized by `smash import` may state, per
//! shot, the altitude, air temperature, pressure and humidity it was measured (or normalized)
//! in, the ball, and flags for estimated spin or club and for the vendor's own flight model.
//! `smash flight` flies each shot in its stated atmosphere; a condition the user sets with a
//! flag (or an `--atmosphere` file) overrides the file's for every shot. The text columns and
//! flags are passed through to the output unchanged.

use std::path::Path;

use crate::app::flight::stream::Flown;
use crate::data::flight_files::flight_csv;
use crate::data::launch_read::{read_launches, LaunchRead};
use crate::data::number::parse_f64;
use crate::data::{quote_cell, write_atomic, DataError};
use crate::flight::{Atmosphere, Flight, FlightConfig};

pub use crate::data::columns::CONDITION_COLUMNS;

/// Columns passed through without use in the flight: the ball (text) and the 0/1 flags.
pub const PASSED_COLUMNS: [&str; 4] = [
    "ball_type",
    "spin_estimated",
    "club_estimated",
    "flight_modelled",
];

/// Which conditions the user set (flags or an atmosphere file): those are not read from the
/// file.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct UserConditions {
    /// Temperature given.
    pub temperature: bool,
    /// Pressure or elevation given (either fixes the pressure).
    pub pressure: bool,
    /// Humidity given.
    pub humidity: bool,
}

impl UserConditions {
    /// For reports: `"; flags override temperature, pressure"`, or nothing.
    pub fn overridden_text(&self) -> String {
        let names: Vec<&str> = [
            (self.temperature, "temperature"),
            (self.pressure, "pressure"),
            (self.humidity, "humidity"),
        ]
        .iter()
        .filter(|c| c.0)
        .map(|c| c.1)
        .collect();
        if names.is_empty() {
            String::new()
        } else {
            format!("; the user's {} for every shot", names.join(", "))
        }
    }
}

/// The header of a CSV file (a leading byte-order mark dropped), to see which columns it has
/// before choosing how to fly it.
pub fn file_headers(path: &Path) -> Result<Vec<String>, DataError> {
    let file = std::fs::File::open(path)
        .map_err(|e| DataError::at(path, None, None, format!("cannot read: {e}")))?;
    let mut r = csv::ReaderBuilder::new().flexible(true).from_reader(file);
    let headers = match r.headers() {
        Ok(h) => h
            .iter()
            .map(|c| c.trim_start_matches('\u{feff}').to_string())
            .collect(),
        // Not readable as CSV here: the flight's own reader names the problem.
        Err(_) => Vec::new(),
    };
    Ok(headers)
}

/// The condition columns of `headers` the flight will read, with their indices (those the
/// user overrides left out).
pub fn columns_used(headers: &[String], user: UserConditions) -> Vec<(usize, &'static str)> {
    CONDITION_COLUMNS
        .iter()
        .filter(|&&c| match c {
            "air_temperature_c" => !user.temperature,
            "relative_humidity_pct" => !user.humidity,
            _ => !user.pressure,
        })
        .filter_map(|&c| headers.iter().position(|h| h == c).map(|i| (i, c)))
        .collect()
}

/// A conditions cell that is not a finite number ([`shot_atmosphere`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{} is not a finite number", quote_cell(cell))]
pub struct ConditionCellError {
    /// The column.
    pub column: String,
    /// The cell as read.
    pub cell: String,
}

/// The atmosphere of one shot: `base` with the file's conditions `cells` (column name, cell)
/// put in; empty cells keep the base value. A stated pressure wins over a stated altitude.
pub fn shot_atmosphere(
    base: &Atmosphere,
    cells: &[(&str, &str)],
) -> Result<Atmosphere, ConditionCellError> {
    let mut atm = *base;
    let mut pressure_pa = None;
    for &(col, cell) in cells {
        if cell.is_empty() {
            continue;
        }
        let x = parse_f64(cell)
            .filter(|x| x.is_finite())
            .ok_or_else(|| ConditionCellError {
                column: col.to_owned(),
                cell: cell.to_owned(),
            })?;
        match col {
            "altitude_m" => {
                atm.elevation_m = Some(x);
                atm.pressure_hpa = None;
            }
            "air_temperature_c" => atm.temperature_c = x,
            "air_pressure_pa" => pressure_pa = Some(x),
            _ => atm.humidity_pct = x,
        }
    }
    if let Some(p) = pressure_pa {
        atm.pressure_hpa = Some(p / 100.0);
        atm.elevation_m = None;
    }
    Ok(atm)
}

/// What a conditions run used: the columns read and how many distinct atmospheres the shots
/// had.
#[derive(Debug, Clone, PartialEq)]
pub struct ConditionsUsed {
    /// Condition columns read from the file.
    pub columns: Vec<&'static str>,
    /// Distinct atmospheres flown.
    pub atmospheres: usize,
}

/// Fly every shot of `input` in its own atmosphere (`base` with the file's conditions, those
/// in `user` left as the user set them) and write the flight file `out`. A condition cell out
/// of its range or not a number leaves its row out, counted, as does a launch that cannot be
/// flown (under `read.strict` the first is refused with file, line and column).
pub fn fly_with_conditions(
    input: &Path,
    out: &Path,
    cfg: &FlightConfig,
    base: &Atmosphere,
    user: UserConditions,
    read: LaunchRead,
) -> Result<(Flown, ConditionsUsed), DataError> {
    let read = LaunchRead {
        with_total: cfg.ground.is_some(),
        ..read
    };
    let mut table = read_launches(input, read)?;
    let used = columns_used(&table.headers, user);
    let airs = shot_airs(input, &mut table, base, &used, read.strict)?;
    let (airs, members) = distinct_airs(airs);
    let mut results: Vec<Option<Result<Flight, crate::flight::FlightError>>> =
        vec![None; table.launches.len()];
    for (air, idx) in airs.iter().zip(&members) {
        let group_cfg = FlightConfig {
            air: *air,
            ..cfg.clone()
        };
        let launches: Vec<_> = idx.iter().map(|&r| table.launches[r]).collect();
        for (&r, res) in idx.iter().zip(crate::flight::fly(&group_cfg, &launches)) {
            results[r] = Some(res);
        }
    }
    let results = results
        .into_iter()
        .map(|f| f.expect("every shot flown"))
        .collect();
    let (flights, errs) = crate::app::flight::stream::split_results(
        input,
        &table.lines,
        table.source.prefix(),
        results,
    );
    table.leave_out(input, errs, read.strict)?;
    write_atomic(
        out,
        &flight_csv(
            &table.headers,
            &table.records,
            &flights,
            cfg.ground.is_some(),
        ),
    )?;
    Ok((
        Flown {
            shots: flights.len(),
            source: table.source,
            left_out: table.left_out,
        },
        ConditionsUsed {
            columns: used.iter().map(|c| c.1).collect(),
            atmospheres: airs.len(),
        },
    ))
}

/// The distinct airs of `airs` (by value) and the shots of each.
fn distinct_airs(airs: Vec<crate::flight::Air>) -> (Vec<crate::flight::Air>, Vec<Vec<usize>>) {
    let mut out: Vec<crate::flight::Air> = Vec::new();
    let mut members: Vec<Vec<usize>> = Vec::new();
    for (r, air) in airs.into_iter().enumerate() {
        match out.iter().position(|a| *a == air) {
            Some(k) => members[k].push(r),
            None => {
                out.push(air);
                members.push(vec![r]);
            }
        }
    }
    (out, members)
}

/// Each kept shot's air from its condition cells (`used`); a row whose cells are bad is left
/// out of `table` and counted (under `strict`, refused).
fn shot_airs(
    input: &Path,
    table: &mut crate::data::flight_files::LaunchTable,
    base: &Atmosphere,
    used: &[(usize, &'static str)],
    strict: bool,
) -> Result<Vec<crate::flight::Air>, DataError> {
    let mut airs = Vec::with_capacity(table.launches.len());
    let mut errs = Vec::with_capacity(table.launches.len());
    for (rec, &line) in table.records.iter().zip(&table.lines) {
        match shot_air(input, rec, line, base, used) {
            Ok(air) => {
                airs.push(air);
                errs.push(None);
            }
            Err(e) => errs.push(Some(e)),
        }
    }
    table.leave_out(input, errs, strict)?;
    Ok(airs)
}

/// One shot's air, or the error naming its file, line and column.
fn shot_air(
    input: &Path,
    rec: &csv::StringRecord,
    line: usize,
    base: &Atmosphere,
    used: &[(usize, &'static str)],
) -> Result<crate::flight::Air, DataError> {
    let cells: Vec<(&str, &str)> = used
        .iter()
        .map(|&(i, c)| (c, rec.get(i).unwrap_or("").trim()))
        .collect();
    let at = |col: &str, msg: String| {
        DataError::at(input, Some(line), Some(format!("column '{col}'")), msg)
    };
    let atm = shot_atmosphere(base, &cells).map_err(|e| at(&e.column, e.to_string()))?;
    atm.air().map_err(|e| {
        let col = match e.key {
            "temperature_c" => "air_temperature_c",
            "humidity_pct" => "relative_humidity_pct",
            "elevation_m" => "altitude_m",
            "pressure_hpa" => "air_pressure_pa",
            k => k,
        };
        at(col, e.to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shots_conditions_replace_the_base_and_pressure_wins() {
        let base = Atmosphere::default();
        let a = shot_atmosphere(
            &base,
            &[("altitude_m", "1600"), ("air_temperature_c", "30")],
        )
        .unwrap();
        assert_eq!((a.elevation_m, a.temperature_c), (Some(1600.0), 30.0));
        let b = shot_atmosphere(
            &base,
            &[("altitude_m", "1600"), ("air_pressure_pa", "85000")],
        )
        .unwrap();
        assert_eq!((b.elevation_m, b.pressure_hpa), (None, Some(850.0)));
        let c = shot_atmosphere(&base, &[("relative_humidity_pct", "")]).unwrap();
        assert_eq!(c, base);
        let e = shot_atmosphere(&base, &[("air_temperature_c", "warm")]).unwrap_err();
        assert_eq!(e.column, "air_temperature_c");
        assert!(
            e.to_string().contains("'warm' is not a finite number"),
            "{e}"
        );
    }

    #[test]
    fn user_conditions_leave_their_columns_unread() {
        let h: Vec<String> = ["shot_id", "altitude_m", "air_temperature_c", "ball_type"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        let all = columns_used(&h, UserConditions::default());
        assert_eq!(all, [(1, "altitude_m"), (2, "air_temperature_c")]);
        let user = UserConditions {
            temperature: true,
            ..UserConditions::default()
        };
        assert_eq!(columns_used(&h, user), [(1, "altitude_m")]);
    }
}
