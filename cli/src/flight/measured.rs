//! The measured flights of a launch file, its ball types and sessions: what `--calibrate` and
//! `--diagnose` fit to.

use smash::data::flight_files::LaunchTable;
use smash::data::number::parse_f64;
use smash::flight::calibrate::MeasuredFlight;
use smash::flight::M_PER_YD;

/// Each shot's launch and measured carry, apex and land angle (SI; empty cells `None`).
pub fn measured_flights(table: &LaunchTable) -> Vec<MeasuredFlight> {
    let col = |n: &str| table.headers.iter().position(|h| h == n);
    let (carry, apex, land) = (col("carry_yd"), col("apex_yd"), col("land_angle_deg"));
    table
        .records
        .iter()
        .zip(&table.launches)
        .map(|(rec, l)| {
            let get = |i: Option<usize>| {
                i.and_then(|i| rec.get(i))
                    .and_then(parse_f64)
                    .filter(|x| x.is_finite())
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
