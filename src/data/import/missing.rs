//! What "not measured" looks like in an export, beyond an empty cell: the words (`-`, `N/A`)
//! and the values a mapping names, the vendors' sentinels, the zeros no shot can have, the
//! club angles of exactly 0 a monitor writes when it did not see the club, and, in a column the
//! launch does not need, a value `smash flight` would refuse. Each is read as no value, so that
//! a shot keeps what was measured and nothing the import writes sinks a later command.

use super::target::LAUNCH;

/// Whether a (trimmed) cell means "not measured": empty, `-`, `--`, `N/A`, or one of the
/// column's or the export's `missing` values (compared as numbers, else as text).
pub(super) fn not_measured(raw: &str, column: &[String], export: &[String]) -> bool {
    let num = crate::data::number::parse_f64;
    // `NaN`: what pandas writes for a missing value (a TrackMan export passed through it).
    matches!(raw, "" | "-" | "--" | "—" | "N/A" | "n/a" | "NA")
        || raw.eq_ignore_ascii_case("nan")
        || column
            .iter()
            .chain(export)
            .any(|m| match (num(m.trim()), num(raw)) {
                (Some(a), Some(b)) => a == b,
                _ => m.trim().eq_ignore_ascii_case(raw),
            })
}

/// Targets whose 0 a vendor writes for "not measured" (GSPro's `Carry` and `ClubSpeed`,
/// TrackMan's carry and flight time of an untracked flight, Garmin's spin floor): no shot
/// flies 0 yd, for 0 s, or leaves or meets the ball at 0 mph.
const ZERO_IS_MISSING: [&str; 8] = [
    "carry_yd",
    "total_yd",
    "flight_time_s",
    "apex_yd",
    "ball_speed_mph",
    "club_speed_mph",
    "spin_rate_rpm",
    "land_angle_deg",
];

/// Why a cell's value (in the file's own unit) means "not measured", when it does: a vendor's
/// sentinel (TrackMan's −2147483648 and 2147483647, Foresight's 2²⁴ − 1 = 16777215 and 2²⁴
/// give or take a few), or a 0 in a column of [`ZERO_IS_MISSING`].
pub(super) fn sentinel(target: &str, v: f64) -> Option<&'static str> {
    const TWO_24: f64 = 16_777_216.0;
    // At or beyond the 32-bit limits: TrackMan's −2147483648, also seen scaled by a unit
    // conversion (−21474836480); no quantity an export holds comes near 2·10⁹.
    if v.abs() >= f64::from(i32::MAX) || (v.abs() - TWO_24).abs() <= 16.0 {
        return Some("a vendor's sentinel for not measured (−2147483648, 2147483647, 16777215, …)");
    }
    if v == 0.0 && ZERO_IS_MISSING.contains(&target) {
        return Some("0, which vendors write when they did not measure it");
    }
    None
}

/// The club's angles that monitors write as exact zeros when they did not measure the club
/// (Garmin's `Club Face` 0.0 beside a blank club speed; camera range exports' `L0.0`, `0.0`).
const CLUB_ANGLES: [&str; 4] = [
    "attack_angle_deg",
    "club_path_deg",
    "face_angle_deg",
    "dynamic_loft_deg",
];

/// Read a shot's club angles of exactly 0 as not measured when the club was not measured: its
/// club speed is not measured, or every club angle it gives a value for is exactly 0, two at
/// least: two angles of a real swing are both exactly 0 about once in a thousand shots at the
/// 0.1° resolution of the coarsest export seen (each within ±0.05° of 0 about one shot in 40),
/// far less at the finer ones. A column's own "not measured" value has been read as no value
/// already (GSPro's `AoA` 0): its zero does not make the others' count as measured.
pub(super) fn club_zeros_not_measured(
    values: &mut [(&str, Option<f64>)],
    blanked: &mut Vec<(String, String)>,
    line: usize,
) {
    let given = |values: &[(&str, Option<f64>)], t: &str| {
        values.iter().find(|(n, _)| *n == t).map(|(_, v)| *v)
    };
    let speed_missing = matches!(given(values, "club_speed_mph"), Some(None));
    let angles: Vec<Option<f64>> = CLUB_ANGLES
        .iter()
        .filter_map(|t| given(values, t))
        .collect();
    let valued: Vec<f64> = angles.iter().flatten().copied().collect();
    let all_zero = valued.len() >= 2 && valued.iter().all(|v| *v == 0.0);
    if !(speed_missing || all_zero) {
        return;
    }
    let why = if all_zero {
        "club angles all exactly 0 (the club was not measured)"
    } else {
        "club angle exactly 0 beside an unmeasured club speed"
    };
    for (n, v) in values.iter_mut() {
        if CLUB_ANGLES.contains(n) && *v == Some(0.0) {
            *v = None;
            blanked.push((why.to_owned(), format!("line {line}: {n} 0")));
        }
    }
    // The same monitor writes the impact location and the lie of a club it did not measure
    // as zeros too (FSX Play without club markers: every club cell 0): a strike at exactly
    // (0, 0) whose club was not measured is not a measured location.
    let located = |t: &str| given(values, t) == Some(Some(0.0));
    let heel_toe = ["impact_offset_mm", "impact_z_mm"]
        .into_iter()
        .find(|t| given(values, t).is_some());
    let zero_location = located("impact_y_mm") && heel_toe.is_some_and(located);
    let unmeasured = |n: &str| {
        (zero_location && (n == "impact_y_mm" || Some(n) == heel_toe)) || n == "dynamic_lie_deg"
    };
    for (n, v) in values.iter_mut() {
        if unmeasured(n) && *v == Some(0.0) {
            *v = None;
            blanked.push((
                "impact location or lie exactly 0 where the club was not measured".to_owned(),
                format!("line {line}: {n} 0"),
            ));
        }
    }
}

/// Why back and side spin are read as not measured when both are exactly 0.
pub(super) const SPIN_ZEROS: &str = "back and side spin both exactly 0 (the spin was not measured)";

/// Read back and side spin that are both exactly 0 as not measured: a struck ball spins, and
/// a monitor that lost the spin writes zeros in both (an FSX Play row whose `Total Spin` is
/// `0 rpm`). The shot then has no spin: left out of what needs a launch, and counted.
pub(super) fn spin_zeros_not_measured(
    values: &mut [(&str, Option<f64>)],
    blanked: &mut Vec<(String, String)>,
    line: usize,
) {
    let zero = |values: &[(&str, Option<f64>)], t: &str| {
        values.iter().any(|(n, v)| *n == t && *v == Some(0.0))
    };
    if !(zero(values, "backspin_rpm") && zero(values, "sidespin_rpm")) {
        return;
    }
    for (n, v) in values.iter_mut() {
        if matches!(*n, "backspin_rpm" | "sidespin_rpm") {
            *v = None;
            blanked.push((SPIN_ZEROS.to_owned(), format!("line {line}: {n} 0")));
        }
    }
}

/// Whether `target` is part of the measured launch (a bad cell there leaves the row out).
pub(super) fn launch_target(target: &str) -> bool {
    LAUNCH.contains(&target)
        || matches!(
            target,
            "backspin_rpm" | "sidespin_rpm" | "spin_rate_rpm" | "spin_axis_deg"
        )
}

/// The range `smash flight` accepts for a measured flight column (a value outside it is read
/// as not measured, so the import never writes a file flight refuses).
pub(super) fn flight_range(target: &str) -> Option<crate::limits::PhysicalRange> {
    use crate::data::flight_files::FLIGHT_COLUMNS;
    use crate::data::flight_measured::MEASURED_FLIGHT_RANGES;
    FLIGHT_COLUMNS
        .iter()
        .position(|c| *c == target)
        .map(|k| MEASURED_FLIGHT_RANGES[k])
}
