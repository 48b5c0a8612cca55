//! Measured flight columns (`carry_yd`, `offline_yd`, …) in a launch file: their physical
//! ranges and the check every reader applies before comparing with them, so that a cell that is
//! not a number, or not a golf shot, is refused with its file, line and column instead of
//! giving an empty or absurd `err_` value.

use std::path::Path;

use crate::data::flight_files::{OutputLayout, FLIGHT_COLUMNS};
use crate::data::DataError;
use crate::limits::PhysicalRange;

/// Physical range of each measured flight column, in [`FLIGHT_COLUMNS`] order. A measured cell
/// outside its range (or not a number) is refused with the file, line and column; an empty
/// cell means "not measured" (no `err_` value).
///
/// - carry, offline and total, yd (carry and total are signed along the target line, offline
///   across it): magnitude at most 600 yd. No golf ball has been driven that far: the longest
///   drive on record, 515 yd including the roll, is Mike Austin's at the 1974 U.S. National
///   Seniors Open (Las Vegas, at altitude), and a ball cannot land farther from the tee than
///   it flies.
/// - apex, yd: from 0 (it is the greatest height above the launch height) to 700 yd, the
///   vacuum height `v²/2g` = 637 m of the fastest launch accepted (250 mph straight up); air
///   only lowers it.
/// - flight time, s: above 0 and at most 30 s, the default flight time limit; the vacuum
///   flight of that fastest launch straight up, `2v/g`, lasts 22.8 s, and measured drives land
///   after about 7 s.
/// - land angle, deg: the descent below horizontal, from 0 to 90 (vertical).
pub const MEASURED_FLIGHT_RANGES: [PhysicalRange; 6] = [
    yd_range("measured carry", -600.0, 600.0),
    yd_range("measured offline", -600.0, 600.0),
    yd_range("measured apex", 0.0, 700.0),
    PhysicalRange {
        quantity: "measured flight time",
        unit: "s",
        min: 0.0,
        max: 30.0,
        min_inclusive: false,
    },
    PhysicalRange {
        quantity: "measured land angle",
        unit: "deg",
        min: 0.0,
        max: 90.0,
        min_inclusive: true,
    },
    yd_range("measured total", -600.0, 600.0),
];

const fn yd_range(quantity: &'static str, min: f64, max: f64) -> PhysicalRange {
    PhysicalRange {
        quantity,
        unit: "yd",
        min,
        max,
        min_inclusive: true,
    }
}

pub use super::columns::{flag, measured_value, read_measured, ZERO_IS_NOT_MEASURED};

/// A measured flight cell ([`FLIGHT_COLUMNS`]`[k]`): `None` when empty, the value when a number
/// inside [`MEASURED_FLIGHT_RANGES`]`[k]`, else what was wrong and what is allowed.
pub fn measured_flight_value(k: usize, cell: &str) -> Result<Option<f64>, MeasuredCellError> {
    if cell.is_empty() {
        return Ok(None);
    }
    let range = MEASURED_FLIGHT_RANGES[k];
    match crate::data::number::parse_f64(cell) {
        Some(x) if x.is_finite() => Ok(Some(range.check(x)?)),
        _ => Err(MeasuredCellError::NotANumber {
            cell: cell.to_owned(),
            column: FLIGHT_COLUMNS[k],
            range,
        }),
    }
}

/// A measured flight cell that is not a measurement ([`measured_flight_value`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeasuredCellError {
    /// A number outside the column's physical range.
    #[error(transparent)]
    Range(#[from] crate::limits::LimitError),
    /// Not a finite number.
    #[error(
        "{} is not a finite number ({column} must be a number within {range}, or empty)",
        crate::data::quote_cell(cell)
    )]
    NotANumber {
        /// The cell as read.
        cell: String,
        /// Its column.
        column: &'static str,
        /// The column's physical range.
        range: crate::limits::PhysicalRange,
    },
}

/// Check every measured flight column the output compares with (`layout.measured`): the first
/// bad cell, in file order, as one error naming `path`, its line (`lines`, one per record) and
/// column.
pub fn check_measured(
    path: &Path,
    layout: &OutputLayout,
    records: &[csv::StringRecord],
    lines: &[usize],
) -> Result<(), DataError> {
    for (rec, &line) in records.iter().zip(lines) {
        for &(k, i) in &layout.measured {
            measured_flight_value(k, rec.get(i).unwrap_or("")).map_err(|m| {
                DataError::at(
                    path,
                    Some(line),
                    Some(format!("column '{}'", FLIGHT_COLUMNS[k])),
                    m,
                )
            })?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn measured_cells_are_numbers_in_their_physical_range_or_empty() {
        assert_eq!(measured_flight_value(0, ""), Ok(None));
        assert_eq!(measured_flight_value(0, "-12.5"), Ok(Some(-12.5)));
        assert_eq!(measured_flight_value(4, "90"), Ok(Some(90.0)));
        for (k, cell, says) in [
            (0, "abc", "'abc' is not a finite number (carry_yd must be a number within [-600, 600] yd, or empty)"),
            (0, "NaN", "'NaN' is not a finite number"),
            (1, "inf", "'inf' is not a finite number"),
            (0, "1e308", "measured carry 1e308 is outside the physical range [-600, 600] yd"),
            (2, "-1", "measured apex -1 is outside the physical range [0, 700] yd"),
            (3, "0", "measured flight time 0 is outside the physical range (0, 30] s"),
            (4, "91", "measured land angle 91 is outside the physical range [0, 90] deg"),
            (5, "-1e300", "measured total -1e300 is outside"),
        ] {
            let e = measured_flight_value(k, cell).unwrap_err().to_string();
            assert!(e.contains(says), "{cell}: {e}");
            assert!(e.len() < 160, "short: {e}");
        }
    }

    #[test]
    fn the_first_bad_cell_is_named_by_file_line_and_column() {
        let headers: Vec<String> = ["id", "carry_yd", "apex_yd", "total_yd"]
            .map(String::from)
            .to_vec();
        let rec = |c: &[&str]| csv::StringRecord::from(c.to_vec());
        let records = [
            rec(&["a", "250", "30", "1e9"]),
            rec(&["b", "", "31", ""]),
            rec(&["c", "240", "NaN", ""]),
            rec(&["d", "abc", "29", ""]),
        ];
        let lines = [2, 3, 5, 6];
        let p = Path::new("l.csv");
        // total_yd is compared only with --total.
        let e = check_measured(p, &OutputLayout::new(&headers, false), &records, &lines)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("l.csv:5: column 'apex_yd': 'NaN'"), "{e}");
        let e = check_measured(p, &OutputLayout::new(&headers, true), &records, &lines)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("l.csv:2: column 'total_yd': measured total 1e9 is outside"),
            "{e}"
        );
        assert!(check_measured(
            p,
            &OutputLayout::new(&headers, false),
            &records[..2],
            &lines
        )
        .is_ok());
    }
}
