//! The column names smash reads from a shots or launch file, and the check that a header does
//! not spell one of them in another case.
//!
//! Columns are matched exactly, so `Carry_yd` or `Group` would be carried through as an unknown
//! column without a word: the shots would lose their measured carry or their clubs, and the
//! results would change with no sign why. A header that differs from a known column only in
//! case (or in surrounding spaces) is refused, naming the column to write.

use std::path::Path;

use super::DataError;
use crate::model::DeliveryVar;

/// The numeric condition columns a flight uses: altitude (m), air temperature (°C), air
/// pressure (Pa, station), relative humidity (%).
pub const CONDITION_COLUMNS: [&str; 4] = [
    "altitude_m",
    "air_temperature_c",
    "air_pressure_pa",
    "relative_humidity_pct",
];

/// The flight outputs (file names without prefix).
pub const FLIGHT_COLUMNS: [&str; 6] = [
    "carry_yd",
    "offline_yd",
    "apex_yd",
    "flight_time_s",
    "land_angle_deg",
    "total_yd",
];

/// The launch columns (file names without prefix), in
/// [`crate::flight::FlightLaunch::from_file_units`] order.
pub const LAUNCH_COLUMNS: [&str; 5] = [
    "ball_speed_mph",
    "launch_angle_deg",
    "azimuth_deg",
    "backspin_rpm",
    "sidespin_rpm",
];

/// The 0/1 columns that mark values a monitor estimated, with what they mark.
pub const ESTIMATED_FLAGS: [(&str, &str); 2] = [
    ("spin_estimated", "estimated spin"),
    ("club_estimated", "estimated club data"),
];

/// Columns a shots file must have: `shot_id` and the required [`DeliveryVar`]s.
pub fn required_columns() -> Vec<&'static str> {
    std::iter::once("shot_id")
        .chain(
            DeliveryVar::ALL
                .into_iter()
                .filter(|v| v.required())
                .map(DeliveryVar::column),
        )
        .collect()
}

/// Optional input columns the engine reads: `group`, `golfer`, `shaft_mass_g` and the
/// optional [`DeliveryVar`]s.
pub fn optional_columns() -> Vec<&'static str> {
    ["group", "golfer", "shaft_mass_g"]
        .into_iter()
        .chain(
            DeliveryVar::ALL
                .into_iter()
                .filter(|v| !v.required())
                .map(DeliveryVar::column),
        )
        .collect()
}

/// Per measured flight column ([`FLIGHT_COLUMNS`]: carry, offline, apex, flight time, land
/// angle, total), whether a value of exactly 0 means "not measured": a monitor writes 0 for a
/// flight it did not track (TrackMan's carry, apex and landing; GSPro's carry), and a ball
/// that flew has none of them 0, as `smash import` reads them (`docs/import.md`, "Not
/// measured"). An offline of 0 is a straight shot.
pub const ZERO_IS_NOT_MEASURED: [bool; 6] = [true, false, true, true, true, true];

/// The index of flight column `name` in [`FLIGHT_COLUMNS`].
pub fn flight_column(name: &str) -> Option<usize> {
    FLIGHT_COLUMNS.iter().position(|c| *c == name)
}

/// The measured value of flight column `k` in `cell` to compare with or fit to: a finite
/// number, not a 0 that means "not measured" ([`ZERO_IS_NOT_MEASURED`]); else `None`.
pub fn measured_value(k: usize, cell: &str) -> Option<f64> {
    read_measured(k, cell).0
}

/// [`measured_value`], and whether the cell was a 0 read as "not measured" (the cell parsed
/// once, for a reader that counts such zeros).
pub fn read_measured(k: usize, cell: &str) -> (Option<f64>, bool) {
    match crate::data::number::parse_f64(cell.trim()).filter(|x| x.is_finite()) {
        Some(x) if x == 0.0 && ZERO_IS_NOT_MEASURED[k] => (None, true),
        v => (v, false),
    }
}

/// A flag cell (`flight_modelled`, `club_estimated`, `spin_estimated`): `Some(true)` for 1,
/// `Some(false)` for 0 (also written `1.0`/`0.0`, as pandas writes a 0/1 column with gaps, or
/// `true`/`false` in any case), `None` for an empty cell, `Err` for anything else. Surrounding
/// spaces are ignored.
#[allow(clippy::result_unit_err)]
pub fn flag(cell: &str) -> Result<Option<bool>, ()> {
    match cell.trim() {
        "" => Ok(None),
        t if t.eq_ignore_ascii_case("true") => Ok(Some(true)),
        t if t.eq_ignore_ascii_case("false") => Ok(Some(false)),
        t => match t.parse::<f64>() {
            Ok(v) if v == 1.0 && !t.contains(['e', 'E']) => Ok(Some(true)),
            Ok(v) if v == 0.0 && !t.contains(['e', 'E']) => Ok(Some(false)),
            _ => Err(()),
        },
    }
}

/// Every column a shots or launch file is read by, exactly as it must be written: the shots
/// columns (`shot_id`, `group`, `golfer`, `shaft_mass_g`, the delivery and measured launch),
/// the launch columns of a flight (measured and `pred_`), the measured flight columns and
/// `flight_modelled`, `ball_type`, the estimated flags, the delivery convention and the
/// conditions. (Session and date columns are matched in any case: `crate::data::sessions`.)
pub fn known_columns() -> Vec<String> {
    let mut out: Vec<String> = required_columns()
        .into_iter()
        .chain(optional_columns())
        .map(str::to_string)
        .collect();
    for c in LAUNCH_COLUMNS {
        out.push(c.to_string());
        out.push(format!("pred_{c}"));
    }
    out.extend(FLIGHT_COLUMNS.map(str::to_string));
    out.extend(ESTIMATED_FLAGS.map(|(c, _)| c.to_string()));
    out.extend(
        [
            "flight_modelled",
            "ball_type",
            crate::model::convention::FACE_AT_COLUMN,
            crate::model::convention::VELOCITY_AT_COLUMN,
            crate::model::convention::FACE_ANGLE_FROM_COLUMN,
        ]
        .map(str::to_string),
    );
    out.extend(CONDITION_COLUMNS.map(str::to_string));
    out.sort_unstable();
    out.dedup();
    out
}

/// Refuse a header that spells a known column ([`known_columns`]) in another case or with
/// surrounding spaces, unless the file also has the column as written: one line naming the file,
/// line 1, the column, and the name to write.
pub fn check_known_case(path: &Path, headers: &[String]) -> Result<(), DataError> {
    let known = known_columns();
    for h in headers {
        if known.iter().any(|k| k == h) {
            continue;
        }
        let t = h.trim();
        let Some(k) = known.iter().find(|k| k.eq_ignore_ascii_case(t)) else {
            continue;
        };
        if headers.iter().any(|x| x == k) {
            continue;
        }
        return Err(DataError::at(
            path,
            Some(1),
            Some(format!("column '{}'", super::escape(h))),
            format!(
                "is smash's '{k}' written {}: column names are matched exactly, so it would be \
                 carried through unread; rename it '{k}'",
                if t == h {
                    "in another case"
                } else {
                    "with spaces around it"
                }
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(headers: &[&str]) -> Result<(), String> {
        let h: Vec<String> = headers.iter().map(|s| s.to_string()).collect();
        check_known_case(Path::new("s.csv"), &h).map_err(|e| e.to_string())
    }

    #[test]
    fn another_case_is_refused_and_named() {
        let e = check(&["shot_id", "Carry_yd", "group"]).unwrap_err();
        assert!(e.contains("s.csv:1"), "{e}");
        assert!(e.contains("column 'Carry_yd'"), "{e}");
        assert!(e.contains("rename it 'carry_yd'"), "{e}");
        let e = check(&["Flight_Modelled"]).unwrap_err();
        assert!(e.contains("'flight_modelled'"), "{e}");
        let e = check(&["shot_id", " group"]).unwrap_err();
        assert!(e.contains("with spaces around it"), "{e}");
    }

    #[test]
    fn exact_unknown_and_both_spellings_pass() {
        assert!(check(&["shot_id", "group", "carry_yd", "flight_modelled", "notes"]).is_ok());
        assert!(check(&["Date", "Session", "Club Name"]).is_ok());
        // Both spellings: the exact one is read, the other is the user's own column.
        assert!(check(&["group", "Group"]).is_ok());
        assert!(check(&["pred_carry_yd", "PRED_BALL_SPEED_MPH"]).is_err());
    }
}
