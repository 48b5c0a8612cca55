//! The measured flights of a launch file, its ball types and sessions: what `--calibrate` and
//! `--diagnose` fit to.

use std::path::Path;

use smash::data::columns::{flag, flight_column, measured_value};
use smash::data::flight_files::LaunchTable;
use smash::data::left_out::list_lines;
use smash::flight::calibrate::MeasuredFlight;
use smash::flight::M_PER_YD;

/// Each shot's launch and measured carry, apex and land angle (SI; empty cells `None`).
pub fn measured_flights(table: &LaunchTable) -> Vec<MeasuredFlight> {
    // Each column's place in the file and its index among the flight columns.
    let col = |n: &str| {
        let k = flight_column(n).expect("a flight column");
        (table.headers.iter().position(|h| h == n), k)
    };
    let (carry, apex, land) = (col("carry_yd"), col("apex_yd"), col("land_angle_deg"));
    table
        .records
        .iter()
        .zip(&table.launches)
        .map(|(rec, l)| {
            // A 0 carry, apex or landing is not measured (`measured_value`).
            let get = |(i, k): (Option<usize>, usize)| {
                i.and_then(|i| rec.get(i))
                    .and_then(|c| measured_value(k, c))
            };
            MeasuredFlight {
                launch: *l,
                carry_m: get(carry).map(|v| v * M_PER_YD),
                apex_m: get(apex).map(|v| v * M_PER_YD),
                land_angle_rad: get(land).map(f64::to_radians),
            }
        })
        .collect()
}

/// The measured flights a fit may use: the rows (indices into the table) with a measured
/// value to fit to, and what was left out, in words.
pub struct FitFlights {
    /// The rows fitted to, in file order.
    pub rows: Vec<usize>,
    /// One note per reason rows were left out of the fit, or the caveat of rows whose every
    /// flight is the vendor's model.
    pub notes: Vec<String>,
    /// Every row fitted to is the vendor's flight model (`flight_modelled = 1`).
    pub all_modelled: bool,
}

/// Which of the rows `of` (of `table`, whose measured flights are `shots`; `what` names them in
/// notes, e.g. " for ball_type 'range'") a fit may use. A carry, apex and landing the monitor's
/// own flight model computed from the launch (`flight_modelled = 1`, as `smash import` marks an
/// indoor session's) are not a flight: fitted to, they calibrate this model to the vendor's.
/// Beside tracked rows (0 or empty) they are left out; when every row is modelled they are
/// fitted and `all_modelled` says what the fit is. A `flight_modelled` cell that is not 0, 1,
/// `true`, `false` or empty leaves its row out, counted (`strict`: refuses the file, naming
/// its line). Rows without a measured value are not fitted to.
pub fn fit_flights(
    table: &LaunchTable,
    shots: &[MeasuredFlight],
    of: &[usize],
    (what, path, strict): (&str, &Path, bool),
) -> anyhow::Result<FitFlights> {
    let measured = |s: &MeasuredFlight| {
        s.carry_m.is_some() || s.apex_m.is_some() || s.land_angle_rad.is_some()
    };
    let rows: Vec<usize> = of
        .iter()
        .copied()
        .filter(|&i| measured(&shots[i]))
        .collect();
    let Some(col) = table.headers.iter().position(|h| h == "flight_modelled") else {
        return Ok(FitFlights {
            rows,
            notes: Vec::new(),
            all_modelled: false,
        });
    };
    let (mut modelled, mut bad, mut tracked) = (Vec::new(), Vec::new(), Vec::new());
    for &i in &rows {
        let cell = table.records[i].get(col).unwrap_or("");
        match flag(cell) {
            Ok(Some(true)) => modelled.push(i),
            Ok(_) => tracked.push(i),
            Err(()) => {
                if strict {
                    anyhow::bail!(
                        "{}:{}: column 'flight_modelled': {} is not a flag: 0 (a tracked \
                         flight), 1 (the vendor's flight model), true, false or empty",
                        path.display(),
                        table.lines[i],
                        smash::data::quote_cell(cell.trim())
                    );
                }
                bad.push(i);
            }
        }
    }
    let lines =
        |idx: &[usize]| list_lines(&idx.iter().map(|&i| table.lines[i]).collect::<Vec<_>>());
    let mut notes = Vec::new();
    if let Some(&first) = bad.first() {
        let cell = table.records[first].get(col).unwrap_or("").trim();
        notes.push(format!(
            "left out of the fit{what} {} shot(s) whose flight_modelled is not a flag (0, 1, \
             true, false or empty; line(s) {}; the first: {})",
            bad.len(),
            lines(&bad),
            smash::data::quote_cell(cell)
        ));
    }
    let all_modelled = !modelled.is_empty() && tracked.is_empty();
    let rows = if all_modelled {
        notes.push(format!(
            "all {} shot(s) fitted to{what} have the vendor's flight model for their carry, \
             apex and landing (flight_modelled = 1), not a tracked flight: the fit matches this \
             model to the vendor's, and its values say nothing of the ball in the air",
            modelled.len()
        ));
        modelled
    } else {
        if !modelled.is_empty() {
            notes.push(format!(
                "left out of the fit{what} {} shot(s) whose carry, apex and landing are the \
                 vendor's flight model (flight_modelled = 1; line(s) {}), not a tracked flight: \
                 fitted to the {} other(s)",
                modelled.len(),
                lines(&modelled),
                tracked.len()
            ));
        }
        tracked
    };
    Ok(FitFlights {
        rows,
        notes,
        all_modelled,
    })
}

/// Each shot's `ball_type` (an empty cell: `unstated`), when the file has the column.
pub fn ball_types(table: &LaunchTable) -> Option<Vec<String>> {
    let i = table.headers.iter().position(|h| h == "ball_type")?;
    Some(
        table
            .records
            .iter()
            .map(|r| match r.get(i).map(str::trim) {
                Some(b) if !b.is_empty() => b.to_string(),
                _ => "unstated".to_string(),
            })
            .collect(),
    )
}

/// Column names (without case) whose cells name a shot's session: a `session` label, or the
/// date of a `date`, `datetime`, `date_time` or `timestamp` cell (`2026-05-06 19:03:21`,
/// `2026-05-06T19:03`, `5/6/2026 7:03 PM`, an Excel serial day: the date, in one form).
const SESSION_COLUMNS: [&str; 5] = ["session", "date", "datetime", "date_time", "timestamp"];

/// Each shot's session and the column it was read from, when a session or date column names
/// one for every shot.
pub fn sessions(table: &LaunchTable) -> Option<(String, Vec<String>)> {
    let i = table
        .headers
        .iter()
        .position(|h| SESSION_COLUMNS.iter().any(|c| h.eq_ignore_ascii_case(c)))?;
    let whole = table.headers[i].eq_ignore_ascii_case("session");
    // One day written two ways (`5/1/2026`, `2026-05-01`) is one session, and an Excel serial
    // (`46143.79`) is a day, not a session of its own (smash::data::datetime).
    let cells = || table.records.iter().map(|r| r.get(i).unwrap_or("").trim());
    let day_first = smash::data::datetime::day_first(cells());
    let keys: Vec<String> = cells()
        .map(|cell| {
            if whole {
                cell.to_string()
            } else if let Some(d) = smash::data::datetime::parse(cell, day_first) {
                d.date()
            } else {
                cell.split([' ', 'T']).next().unwrap_or("").to_string()
            }
        })
        .collect();
    if keys.iter().any(String::is_empty) {
        return None;
    }
    Some((table.headers[i].clone(), keys))
}
