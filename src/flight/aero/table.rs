//! A user's table of coefficients ([`TableModel`]): `C_D`, `C_L` and optionally `C_M` at spin
//! factors and optionally Reynolds numbers, read from CSV and interpolated linearly.

use std::path::Path;

use super::{CoefficientModel, Coefficients, SMITS_SMITH_CM_PER_S};
use crate::limits::fmt_value;
use crate::line_index::{csv_message, normalise_line_ends, LineIndex};

/// A `csv` error as `source: line N: message` (the line from [`LineIndex`], the wording every
/// CSV reader shares).
fn csv_fault(source: &str, index: &LineIndex, e: &csv::Error) -> TableError {
    TableError::Csv {
        table: source.to_owned(),
        line: e.position().map(|p| index.line_of(p)),
        message: csv_message(e),
    }
}

/// Why a coefficient table cannot be read; every message names the table (its file), and the
/// line and column where there is one.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TableError {
    /// The file cannot be read.
    #[error("{table}: cannot read the coefficient table: {message}")]
    Read {
        /// The table's file.
        table: String,
        /// The system's words.
        message: String,
    },
    /// The file is not UTF-8 text.
    #[error("{table}: line {line}: {message}")]
    Text {
        /// The table's file.
        table: String,
        /// The line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// Not CSV the reader can read.
    #[error("{table}: {}{message}", line.map(|l| format!("line {l}: ")).unwrap_or_default())]
    Csv {
        /// The table.
        table: String,
        /// The line, when known.
        line: Option<usize>,
        /// The reader's words.
        message: String,
    },
    /// A column the table format does not have.
    #[error("{table}: unknown column '{column}' (allowed: spin_factor, reynolds, cd, cl, cm)")]
    UnknownColumn {
        /// The table.
        table: String,
        /// The header.
        column: String,
    },
    /// A required column is missing.
    #[error("{table}: missing column '{column}'")]
    MissingColumn {
        /// The table.
        table: String,
        /// The column.
        column: &'static str,
    },
    /// A cell that is not a number.
    #[error("{table}: line {line}, column {column}: '{cell}' is not a number")]
    NotANumber {
        /// The table.
        table: String,
        /// The line.
        line: usize,
        /// The column.
        column: &'static str,
        /// The cell as read.
        cell: String,
    },
    /// A value outside the column's range.
    #[error(
        "{table}: line {line}, column {column}: {} is outside [{}, {}]",
        fmt_value(*value),
        fmt_value(*lo),
        fmt_value(*hi)
    )]
    OutOfRange {
        /// The table.
        table: String,
        /// The line.
        line: usize,
        /// The column.
        column: &'static str,
        /// The value.
        value: f64,
        /// Lowest allowed.
        lo: f64,
        /// Highest allowed.
        hi: f64,
    },
    /// No rows.
    #[error("{table}: the coefficient table has no rows")]
    NoRows {
        /// The table.
        table: String,
    },
    /// A spin factor given twice (at one Reynolds number).
    #[error(
        "{table}: spin_factor {spin_factor} appears twice{}",
        reynolds.map(|re| format!(" at reynolds {re}")).unwrap_or_default()
    )]
    Duplicate {
        /// The table.
        table: String,
        /// The spin factor.
        spin_factor: f64,
        /// The Reynolds number, when the table has that column.
        reynolds: Option<f64>,
    },
}

/// One Reynolds-number slice of a table: spin factors ascending with their coefficients.
#[derive(Debug, Clone, PartialEq)]
struct Slice {
    re: f64,
    s: Vec<f64>,
    c: Vec<Coefficients>,
}

impl Slice {
    fn at(&self, s: f64) -> Coefficients {
        let n = self.s.len();
        if !(s > self.s[0]) {
            return self.c[0];
        }
        if s >= self.s[n - 1] {
            return self.c[n - 1];
        }
        let k = self.s.partition_point(|&x| x <= s) - 1;
        let f = (s - self.s[k]) / (self.s[k + 1] - self.s[k]);
        lerp(self.c[k], self.c[k + 1], f)
    }
}

fn lerp(a: Coefficients, b: Coefficients, f: f64) -> Coefficients {
    Coefficients {
        cd: a.cd + f * (b.cd - a.cd),
        cl: a.cl + f * (b.cl - a.cl),
        cm: a.cm + f * (b.cm - a.cm),
    }
}

/// A user's table of coefficients (CSV with a header): columns `spin_factor`, `cd`, `cl`, and
/// optionally `cm` (default Smits & Smith `0.01·S`) and `reynolds`. Without `reynolds` the
/// coefficients depend on `S` only. With it, rows are grouped by Reynolds number; the
/// coefficients are interpolated linearly in `S` within each Reynolds number and then linearly
/// in `Re` between the two nearest. Outside the tabulated range the end values are held (the
/// table's own range is reported by [`TableModel::describe`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TableModel {
    slices: Vec<Slice>,
    source: String,
}

impl TableModel {
    /// Read a table from a CSV file; errors name the file, line and column.
    pub fn from_path(path: &Path) -> Result<Self, TableError> {
        crate::inputs::note_input(path);
        let table = || path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| TableError::Read {
            table: table(),
            message: e.to_string(),
        })?;
        let text =
            crate::line_index::utf8_text(bytes).map_err(|(line, message)| TableError::Text {
                table: table(),
                line,
                message,
            })?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parse a table from CSV text; `source` names it in errors.
    pub fn parse(text: &str, source: &str) -> Result<Self, TableError> {
        // Comments end only at `\n` in the csv crate: CR-only files are normalised (same lines).
        let text = &*normalise_line_ends(text);
        let mut rdr = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        let index = LineIndex::new(text.as_bytes()).with_comments(b'#');
        let headers = rdr
            .headers()
            .map_err(|e| csv_fault(source, &index, &e))?
            .clone();
        let col = |name: &str| headers.iter().position(|h| h == name);
        for h in headers.iter() {
            if !["spin_factor", "reynolds", "cd", "cl", "cm"].contains(&h) {
                return Err(TableError::UnknownColumn {
                    table: source.to_owned(),
                    column: h.to_owned(),
                });
            }
        }
        let need = |name: &'static str| {
            col(name).ok_or_else(|| TableError::MissingColumn {
                table: source.to_owned(),
                column: name,
            })
        };
        let (is, icd, icl) = (need("spin_factor")?, need("cd")?, need("cl")?);
        let (icm, ire) = (col("cm"), col("reynolds"));
        let mut rows: Vec<(f64, f64, Coefficients)> = Vec::new();
        for rec in rdr.records() {
            let rec = rec.map_err(|e| csv_fault(source, &index, &e))?;
            let line = rec.position().map_or(0, |p| index.line_of(p));
            let num = |i: usize, column: &'static str, lo: f64, hi: f64| {
                let t = rec.get(i).unwrap_or("");
                let v: f64 = t.parse().map_err(|_| TableError::NotANumber {
                    table: source.to_owned(),
                    line,
                    column,
                    cell: t.to_owned(),
                })?;
                if !(v >= lo && v <= hi) {
                    return Err(TableError::OutOfRange {
                        table: source.to_owned(),
                        line,
                        column,
                        value: v,
                        lo,
                        hi,
                    });
                }
                Ok(v)
            };
            let s = num(is, "spin_factor", 0.0, 5.0)?;
            let re = match ire {
                Some(i) => num(i, "reynolds", 1.0, 1e7)?,
                None => 0.0,
            };
            let c = Coefficients {
                cd: num(icd, "cd", 0.0, 2.0)?,
                cl: num(icl, "cl", -1.0, 2.0)?,
                cm: match icm {
                    Some(i) => num(i, "cm", 0.0, 1.0)?,
                    None => SMITS_SMITH_CM_PER_S * s,
                },
            };
            rows.push((re, s, c));
        }
        if rows.is_empty() {
            return Err(TableError::NoRows {
                table: source.to_owned(),
            });
        }
        rows.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        let mut slices: Vec<Slice> = Vec::new();
        for (re, s, c) in rows {
            match slices.last_mut() {
                Some(sl) if sl.re == re => {
                    if sl.s.last() == Some(&s) {
                        return Err(TableError::Duplicate {
                            table: source.to_owned(),
                            spin_factor: s,
                            reynolds: ire.is_some().then_some(re),
                        });
                    }
                    sl.s.push(s);
                    sl.c.push(c);
                }
                _ => slices.push(Slice {
                    re,
                    s: vec![s],
                    c: vec![c],
                }),
            }
        }
        Ok(Self {
            slices,
            source: source.to_string(),
        })
    }

    /// One line: where the table came from and its range.
    pub fn describe(&self) -> String {
        let smin = self
            .slices
            .iter()
            .map(|s| s.s[0])
            .fold(f64::INFINITY, f64::min);
        let smax = self
            .slices
            .iter()
            .map(|s| s.s[s.s.len() - 1])
            .fold(f64::NEG_INFINITY, f64::max);
        if self.slices.len() > 1 {
            format!(
                "table {} (S {smin}–{smax}, Re {}–{})",
                self.source,
                self.slices[0].re,
                self.slices[self.slices.len() - 1].re
            )
        } else {
            format!("table {} (S {smin}–{smax})", self.source)
        }
    }
}

impl CoefficientModel for TableModel {
    fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        let n = self.slices.len();
        if n == 1 || !(re > self.slices[0].re) {
            return self.slices[0].at(s);
        }
        if re >= self.slices[n - 1].re {
            return self.slices[n - 1].at(s);
        }
        let k = self.slices.partition_point(|sl| sl.re <= re) - 1;
        let (a, b) = (&self.slices[k], &self.slices[k + 1]);
        lerp(a.at(s), b.at(s), (re - a.re) / (b.re - a.re))
    }

    fn uses_reynolds(&self) -> bool {
        self.slices.len() > 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flight::aero::{AeroModel, Fmm2022};

    #[test]
    fn table_interpolates_and_reproduces_a_model() {
        // A table sampled from fmm2022 at fine S reproduces it between the nodes to the
        // interpolation error of a quadratic (h²/8·|f''| ≤ 2.9e-5 at h = 0.01), above the lift's
        // taper to zero below S = 0.02 and below the blend into the hold that starts at 0.70.
        let mut csv = String::from("spin_factor,cd,cl,cm\n");
        for k in 0..=75 {
            let s = k as f64 * 0.01;
            let c = Fmm2022.coefficients(s, 0.0);
            csv.push_str(&format!("{s},{},{},{}\n", c.cd, c.cl, c.cm));
        }
        let t = TableModel::parse(&csv, "t.csv").unwrap();
        for s in [0.025, 0.237, 0.5, 0.695] {
            let (a, b) = (t.coefficients(s, 1e5), Fmm2022.coefficients(s, 1e5));
            assert!(
                (a.cd - b.cd).abs() < 4e-5 && (a.cl - b.cl).abs() < 4e-5,
                "{s}"
            );
        }
        assert!(!t.uses_reynolds());
        // Two Reynolds slices: halfway between them, halfway between their values.
        let t = TableModel::parse(
            "reynolds,spin_factor,cd,cl\n1e5,0,0.2,0.0\n1e5,1,0.4,0.4\n2e5,0,0.3,0.1\n2e5,1,0.5,0.5\n",
            "t2",
        )
        .unwrap();
        let c = t.coefficients(0.5, 1.5e5);
        assert!((c.cd - 0.35).abs() < 1e-12 && (c.cl - 0.25).abs() < 1e-12);
    }

    #[test]
    fn table_errors_name_line_and_column() {
        let e = TableModel::parse("spin_factor,cd,cl\n0.1,0.2,x\n", "t.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2") && e.contains("cl"), "{e}");
        let e = TableModel::parse("spin_factor,cd\n0.1,0.2\n", "t.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing column 'cl'"), "{e}");
        let e = TableModel::parse("spin_factor,cd,cl,foo\n", "t.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("unknown column 'foo'"), "{e}");
        let e = TableModel::parse("spin_factor,cd,cl\n0.1,-0.2,0\n", "t.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("outside"), "{e}");
        assert!(AeroModel::from_name("magic").is_err());
    }
}
