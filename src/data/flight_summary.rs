//! How well the flight model matches measured flights: per club (the `group` column) and
//! overall, the carry, side (offline), apex and land-angle errors of a flight output file
//! (its `pred_` and `err_` columns, predicted − measured).
//!
//! Per quantity: the number of shots measured, the bias (mean error), the RMSE, the median and
//! 90th percentile of the absolute error, and for carry the same in percent of the measured
//! carry (the figure launch-monitor makers quote). Pure: the table comes in as cells.

use std::fmt::Write as _;

use serde::Serialize;

use crate::data::columns::{flag, flight_column, read_measured};

/// The compared quantities: (flight column, label, unit).
pub const SUMMARY_QUANTITIES: [(&str, &str, &str); 4] = [
    ("carry_yd", "carry", "yd"),
    ("offline_yd", "side", "yd"),
    ("apex_yd", "apex", "yd"),
    ("land_angle_deg", "land angle", "deg"),
];

/// Error statistics of one quantity over a set of shots.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorStats {
    /// Shots with a measured and a predicted value.
    pub n: usize,
    /// Mean error (predicted − measured), in the quantity's unit.
    pub bias: f64,
    /// Root mean square error.
    pub rmse: f64,
    /// Median absolute error.
    pub median_abs: f64,
    /// 90th percentile of the absolute error.
    pub p90_abs: f64,
    /// Carry only: median of |error| / measured, %.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub median_abs_pct: Option<f64>,
    /// Carry only: 90th percentile of |error| / measured, %.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub p90_abs_pct: Option<f64>,
    /// Carry only: mean of error / measured, %.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bias_pct: Option<f64>,
}

/// The quantile `q` of sorted values, linear between order statistics (type 7, as R's and
/// NumPy's default).
pub fn quantile_sorted(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let pos = q * (sorted.len() - 1) as f64;
    let (lo, frac) = (pos.floor() as usize, pos - pos.floor());
    let hi = (lo + 1).min(sorted.len() - 1);
    sorted[lo] + frac * (sorted[hi] - sorted[lo])
}

impl ErrorStats {
    /// From `(error, measured)` pairs; `percent`: add the percent figures (relative to
    /// measured values away from 0). `None` when there are no pairs.
    pub fn new(pairs: &[(f64, f64)], percent: bool) -> Option<Self> {
        if pairs.is_empty() {
            return None;
        }
        let n = pairs.len();
        let nf = n as f64;
        let bias = pairs.iter().map(|p| p.0).sum::<f64>() / nf;
        let rmse = (pairs.iter().map(|p| p.0 * p.0).sum::<f64>() / nf).sqrt();
        let mut abs: Vec<f64> = pairs.iter().map(|p| p.0.abs()).collect();
        abs.sort_by(f64::total_cmp);
        let (mut median_abs_pct, mut p90_abs_pct, mut bias_pct) = (None, None, None);
        if percent {
            let rel: Vec<f64> = pairs
                .iter()
                .filter(|p| p.1.abs() > 1.0)
                .map(|p| 100.0 * p.0 / p.1)
                .collect();
            if !rel.is_empty() {
                let mut r: Vec<f64> = rel.iter().map(|x| x.abs()).collect();
                r.sort_by(f64::total_cmp);
                median_abs_pct = Some(quantile_sorted(&r, 0.5));
                p90_abs_pct = Some(quantile_sorted(&r, 0.9));
                bias_pct = Some(rel.iter().sum::<f64>() / rel.len() as f64);
            }
        }
        Some(Self {
            n,
            bias,
            rmse,
            median_abs: quantile_sorted(&abs, 0.5),
            p90_abs: quantile_sorted(&abs, 0.9),
            median_abs_pct,
            p90_abs_pct,
            bias_pct,
        })
    }
}

/// One row of the summary: a club (or all shots) and its statistics per quantity.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SummaryRow {
    /// The club (`group`), or `all`.
    pub group: String,
    /// Shots in the group.
    pub shots: usize,
    /// Per quantity of [`SUMMARY_QUANTITIES`] (by its flight column), when measured.
    pub errors: Vec<(String, ErrorStats)>,
}

/// The summary of a flight output: per club in order of first appearance, then all shots.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FlightSummary {
    /// Per club, then `all`.
    pub rows: Vec<SummaryRow>,
    /// Every shot's (measured carry, carry error), yd, for charts.
    #[serde(skip)]
    pub carry_points: Vec<(f64, f64)>,
    /// Shots compared whose "measured" flight is the vendor's flight model
    /// (`flight_modelled = 1`): for them two models are compared, not a model and a flight.
    pub modelled: usize,
    /// Shots with any quantity compared.
    pub compared: usize,
    /// Shots compared whose `flight_modelled` cell is not a flag (0, 1, `true`, `false` or
    /// empty): counted as tracked, and said so ([`FlightSummary::modelled_notes`]).
    #[serde(skip)]
    pub unflagged: usize,
    /// Per quantity, the shots whose measured cell is a 0 read as "not measured"
    /// ([`crate::data::flight_measured::ZERO_IS_NOT_MEASURED`]): not compared, and said so.
    #[serde(skip)]
    pub zeros: Vec<(&'static str, usize)>,
}

/// Summarise a flight output table (header and rows of cells). Rows whose `err_` or measured
/// cell is empty are not counted for that quantity. `None` when the table has no `err_`
/// column of [`SUMMARY_QUANTITIES`] (nothing measured to compare with).
pub fn summarise(headers: &[String], rows: &[Vec<&str>]) -> Option<FlightSummary> {
    let mut t = Compact::new(headers)?;
    for row in rows {
        t.push(|c| row.get(c).copied());
    }
    Some(t.summary())
}

/// What the summary reads of a flight output, row by row: each row's group and the values of
/// the compared quantities' `err_` and measured columns (so that a file of millions of rows is
/// summarised without holding its cells).
struct Compact {
    group: Option<usize>,
    /// Per compared quantity: (index in [`SUMMARY_QUANTITIES`], err column, measured column).
    quantities: Vec<(usize, usize, usize)>,
    groups: Vec<String>,
    members: Vec<Vec<usize>>,
    /// Per row and quantity, the (error, measured) pair when both cells hold a finite number.
    values: Vec<Option<(f64, f64)>>,
    rows: usize,
    /// The `flight_modelled` column, and the rows compared with it 1, and all rows compared.
    modelled_col: Option<usize>,
    modelled: usize,
    compared: usize,
    unflagged: usize,
    /// Per compared quantity, the rows whose measured cell is a 0 read as not measured.
    zeros: Vec<usize>,
    /// Per compared quantity, its index in [`crate::data::columns::FLIGHT_COLUMNS`].
    columns: Vec<usize>,
}

impl Compact {
    /// `None` when the header has no compared quantity.
    fn new(headers: &[String]) -> Option<Self> {
        let col = |name: &str| headers.iter().position(|h| h == name);
        let quantities: Vec<(usize, usize, usize)> = SUMMARY_QUANTITIES
            .iter()
            .enumerate()
            .filter_map(|(q, (name, _, _))| Some((q, col(&format!("err_{name}"))?, col(name)?)))
            .collect();
        if quantities.is_empty() {
            return None;
        }
        Some(Self {
            group: col("group"),
            zeros: vec![0; quantities.len()],
            columns: quantities
                .iter()
                .map(|&(q, _, _)| {
                    flight_column(SUMMARY_QUANTITIES[q].0)
                        .expect("every summary quantity is a flight column")
                })
                .collect(),
            quantities,
            groups: Vec::new(),
            members: Vec::new(),
            values: Vec::new(),
            rows: 0,
            modelled_col: col("flight_modelled"),
            modelled: 0,
            compared: 0,
            unflagged: 0,
        })
    }

    /// Adds the row whose cell in column `c` is `cell(c)`.
    fn push<'a>(&mut self, cell: impl Fn(usize) -> Option<&'a str>) {
        let value = |c: usize| {
            cell(c)
                .and_then(crate::data::number::parse_f64)
                .filter(|x| x.is_finite())
        };
        let g = self.group.and_then(&cell).unwrap_or("");
        let g = if g.is_empty() { "(no group)" } else { g };
        let r = self.rows;
        match self.groups.iter().position(|x| x == g) {
            Some(k) => self.members[k].push(r),
            None => {
                self.groups.push(g.to_string());
                self.members.push(vec![r]);
            }
        }
        let mut any = false;
        for (j, &(_, e, m)) in self.quantities.iter().enumerate() {
            let k = self.columns[j];
            let measured = cell(m).and_then(|c| {
                let (v, zero) = read_measured(k, c);
                self.zeros[j] += usize::from(zero);
                v
            });
            let v = value(e).zip(measured);
            any |= v.is_some();
            self.values.push(v);
        }
        if any {
            self.compared += 1;
            match self.modelled_col.and_then(&cell).map(flag) {
                Some(Ok(Some(true))) => self.modelled += 1,
                Some(Err(())) => self.unflagged += 1,
                _ => {}
            }
        }
        self.rows += 1;
    }

    fn summary(&self) -> FlightSummary {
        let nq = self.quantities.len();
        let stats_of = |idx: &mut dyn Iterator<Item = usize>| -> Vec<(String, ErrorStats)> {
            let idx: Vec<usize> = idx.collect();
            self.quantities
                .iter()
                .enumerate()
                .filter_map(|(k, &(q, _, _))| {
                    let pairs: Vec<(f64, f64)> = idx
                        .iter()
                        .filter_map(|&r| self.values[r * nq + k])
                        .collect();
                    let stats = ErrorStats::new(&pairs, q == 0)?;
                    Some((SUMMARY_QUANTITIES[q].0.to_string(), stats))
                })
                .collect()
        };
        let mut out: Vec<SummaryRow> = self
            .groups
            .iter()
            .zip(&self.members)
            .map(|(g, idx)| SummaryRow {
                group: g.clone(),
                shots: idx.len(),
                errors: stats_of(&mut idx.iter().copied()),
            })
            .collect();
        out.push(SummaryRow {
            group: "all".into(),
            shots: self.rows,
            errors: stats_of(&mut (0..self.rows)),
        });
        let carry_points = self
            .quantities
            .iter()
            .position(|q| q.0 == 0)
            .map(|k| {
                (0..self.rows)
                    .filter_map(|r| self.values[r * nq + k].map(|(e, m)| (m, e)))
                    .collect()
            })
            .unwrap_or_default();
        FlightSummary {
            rows: out,
            carry_points,
            modelled: self.modelled,
            compared: self.compared,
            unflagged: self.unflagged,
            zeros: self
                .quantities
                .iter()
                .zip(&self.zeros)
                .filter(|(_, &n)| n > 0)
                .map(|(&(q, _, _), &n)| (SUMMARY_QUANTITIES[q].0, n))
                .collect(),
        }
    }
}

/// Summarise a flight output file (see [`summarise`]), streamed: the header first (a file
/// without measured columns is not read further), then row by row, holding only the compared
/// values (a 2-million-row output is summarised in a few MB, not read into memory whole).
pub fn summarise_file(
    path: &std::path::Path,
) -> Result<Option<FlightSummary>, crate::data::DataError> {
    use crate::data::DataError;
    let file = std::fs::File::open(path)
        .map_err(|e| DataError::file(path, format!("cannot be read: {e}")))?;
    let mut reader = csv::ReaderBuilder::new()
        .flexible(true)
        .from_reader(std::io::BufReader::with_capacity(1 << 20, file));
    let bad = |e: csv::Error| {
        let line = e.position().map(|p| p.line() as usize);
        DataError::at(path, line, None, crate::data::csv_message(&e))
    };
    let headers: Vec<String> = reader
        .headers()
        .map_err(bad)?
        .iter()
        .map(|h| h.trim_start_matches('\u{feff}').to_string())
        .collect();
    let Some(mut t) = Compact::new(&headers) else {
        return Ok(None);
    };
    let mut record = csv::StringRecord::new();
    while reader.read_record(&mut record).map_err(bad)? {
        t.push(|c| record.get(c));
    }
    Ok(Some(t.summary()))
}

impl FlightSummary {
    /// What the "measured" flights of the comparison are, when some are the vendor's model,
    /// and the shots whose `flight_modelled` cell could not be read.
    pub fn modelled_notes(&self) -> Vec<String> {
        let mut notes = Vec::new();
        if self.modelled > 0 {
            notes.push(format!(
                "{} of the {} shots compared have the vendor's flight model for their measured \
                 carry, apex and landing (flight_modelled = 1), not a tracked flight: for them \
                 two models are compared",
                self.modelled, self.compared
            ));
        }
        for (column, n) in &self.zeros {
            notes.push(format!(
                "{n} shot(s) have a {column} of 0, read as not measured (a monitor writes 0 for \
                 a flight it did not track): not compared"
            ));
        }
        if self.unflagged > 0 {
            notes.push(format!(
                "{} of the {} shots compared have a flight_modelled cell that is not a flag (0, \
                 1, true, false or empty): compared as tracked flights",
                self.unflagged, self.compared
            ));
        }
        notes
    }

    /// The text table: one block per quantity, one line per club and `all`.
    pub fn text(&self) -> String {
        let mut t = String::new();
        for (name, label, unit) in SUMMARY_QUANTITIES {
            let lines: Vec<(&SummaryRow, &ErrorStats)> = self
                .rows
                .iter()
                .filter_map(|r| Some((r, r.errors.iter().find(|e| e.0 == name).map(|e| &e.1)?)))
                .collect();
            if lines.is_empty() {
                continue;
            }
            let pct = name == "carry_yd";
            let _ = write!(
                t,
                "{label} error ({unit}, predicted - measured)\n{:<18} {:>5} {:>8} {:>8} {:>8} {:>8}",
                "club", "n", "bias", "rmse", "median", "p90"
            );
            if pct {
                let _ = write!(t, " {:>8} {:>8} {:>8}", "bias %", "median %", "p90 %");
            }
            t.push('\n');
            for (r, s) in lines {
                let g: String = r.group.chars().take(18).collect();
                let _ = write!(
                    t,
                    "{g:<18} {:>5} {:>8.2} {:>8.2} {:>8.2} {:>8.2}",
                    s.n, s.bias, s.rmse, s.median_abs, s.p90_abs
                );
                if let (Some(b), Some(m), Some(p)) = (s.bias_pct, s.median_abs_pct, s.p90_abs_pct) {
                    let _ = write!(t, " {b:>8.2} {m:>8.2} {p:>8.2}");
                }
                t.push('\n');
            }
            t.push('\n');
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_interpolate_between_order_statistics() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0];
        assert_eq!(quantile_sorted(&v, 0.5), 3.0);
        assert!((quantile_sorted(&v, 0.9) - 4.6).abs() < 1e-12);
        assert_eq!(quantile_sorted(&[7.0], 0.9), 7.0);
    }

    /// Statistics by hand: errors 1, −2, 3 on carries 100, 200, 150.
    #[test]
    fn statistics_by_hand() {
        let s = ErrorStats::new(&[(1.0, 100.0), (-2.0, 200.0), (3.0, 150.0)], true).unwrap();
        assert_eq!(s.n, 3);
        assert!((s.bias - 2.0 / 3.0).abs() < 1e-12);
        assert!((s.rmse - (14.0f64 / 3.0).sqrt()).abs() < 1e-12);
        assert_eq!(s.median_abs, 2.0);
        assert!((s.p90_abs - 2.8).abs() < 1e-12);
        // Percent errors 1, −1, 2: |.| sorted 1, 1, 2.
        assert_eq!(s.median_abs_pct, Some(1.0));
        assert!((s.bias_pct.unwrap() - 2.0 / 3.0).abs() < 1e-12);
        assert!((s.p90_abs_pct.unwrap() - 1.8).abs() < 1e-12);
        assert_eq!(ErrorStats::new(&[], true), None);
    }

    /// Groups in order of first appearance, `all` last; empty cells are not counted; a table
    /// without `err_` columns has no summary.
    #[test]
    fn groups_and_missing_cells() {
        let h: Vec<String> = [
            "group",
            "carry_yd",
            "err_carry_yd",
            "apex_yd",
            "err_apex_yd",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let rows = vec![
            vec!["7i", "150", "3", "30", "1"],
            vec!["driver", "250", "-5", "", ""],
            vec!["7i", "160", "-1", "32", "-1"],
        ];
        let s = summarise(&h, &rows).unwrap();
        let names: Vec<&str> = s.rows.iter().map(|r| r.group.as_str()).collect();
        assert_eq!(names, ["7i", "driver", "all"]);
        assert_eq!(s.rows[0].errors[0].1.n, 2);
        assert_eq!(s.rows[0].errors[0].1.bias, 1.0);
        // The driver has no apex: only carry.
        assert_eq!(s.rows[1].errors.len(), 1);
        assert_eq!(s.rows[2].errors[1].0, "apex_yd");
        assert_eq!(s.rows[2].errors[1].1.n, 2);
        let text = s.text();
        assert!(
            text.contains("carry error (yd, predicted - measured)"),
            "{text}"
        );
        assert!(text.contains("apex error"), "{text}");
        assert!(!text.contains("side error"), "{text}");
        assert_eq!(summarise(&h[..2], &[vec!["7i", "150"]]), None);
    }
}
