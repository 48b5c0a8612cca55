//! Converting the export's rows to shots: rows to skip (summary rows, shots the monitor
//! flagged), cells to numbers in the shots file's units, ids, and derived columns.

use std::collections::HashSet;
use std::path::Path;

use super::cell::{list_lines, parse_cell};
use super::layout::Layout;
use super::table::{split_header, Table};
use super::target::is_core;
use super::{OffsetSide, SkipRule};
use crate::data::{fmt_f64, DataError};

/// The shots CSV (bytes), the number of shots written and the export's file line of each.
pub(super) struct Shots {
    pub csv: Vec<u8>,
    pub count: usize,
    pub lines: Vec<usize>,
}

/// Write the shots of `table` laid out by `layout`; notes on skipped rows go to `notes`.
/// Refuses a file with no usable rows.
pub(super) fn write_shots(
    path: &Path,
    table: &Table,
    skip_rules: &[SkipRule],
    layout: &Layout,
    vendor: &str,
    notes: &mut Vec<String>,
) -> Result<Shots, DataError> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(layout.header()).expect("writing to memory");
    let mut skipped_by_rule: Vec<(String, Vec<usize>)> = Vec::new();
    let mut flagged: Vec<(usize, String)> = Vec::new();
    let mut ids = HashSet::new();
    let mut count = 0usize;
    let mut lines = Vec::new();
    for (line, cells) in &table.rows {
        let row = RowAt {
            path,
            line: *line,
            cells,
        };
        if let Some(label) = row.skipped_by(skip_rules, table) {
            match skipped_by_rule.iter_mut().find(|(l, _)| *l == label) {
                Some((_, v)) => v.push(*line),
                None => skipped_by_rule.push((label, vec![*line])),
            }
            continue;
        }
        if let Some(flag) = row.flag(layout) {
            flagged.push((*line, flag));
            continue;
        }
        let rec = row.record(layout, &mut ids)?;
        w.write_record(&rec).expect("writing to memory");
        count += 1;
        lines.push(*line);
    }
    for (label, lines) in &skipped_by_rule {
        notes.push(format!(
            "skipped {} {label} row(s) (line(s) {})",
            lines.len(),
            list_lines(lines)
        ));
    }
    if !flagged.is_empty() {
        let lines: Vec<usize> = flagged.iter().map(|(l, _)| *l).collect();
        notes.push(format!(
            "skipped {} shot(s) the monitor flagged ({}; line(s) {}): not used",
            flagged.len(),
            flagged[0].1,
            list_lines(&lines)
        ));
    }
    if count == 0 {
        return Err(DataError::file(
            path,
            format!("no shots: the {vendor} export has no usable rows"),
        ));
    }
    Ok(Shots {
        csv: w.into_inner().expect("flushing memory"),
        count,
        lines,
    })
}

/// One row of the export, for conversion and messages.
struct RowAt<'r> {
    path: &'r Path,
    line: usize,
    cells: &'r [String],
}

impl RowAt<'_> {
    /// The cell at `i`, empty when the row is short.
    fn cell(&self, i: usize) -> &str {
        self.cells.get(i).map_or("", String::as_str)
    }

    /// An error at this row, in the column headed `header`.
    fn error_in(&self, header: Option<&str>, message: impl Into<String>) -> DataError {
        DataError::at(
            self.path,
            Some(self.line),
            header.map(|h| format!("column '{h}'")),
            message,
        )
    }

    /// The label of the first skip rule the row matches (summary rows: averages, deviations).
    fn skipped_by(&self, rules: &[SkipRule], table: &Table) -> Option<String> {
        let rule = rules.iter().find(|rule| {
            let hit = |c: &str| rule.values.iter().any(|v| v.eq_ignore_ascii_case(c.trim()));
            match &rule.column {
                Some(col) => {
                    let want = split_header(col).0;
                    table
                        .headers
                        .iter()
                        .position(|(h, _)| *h == want)
                        .is_some_and(|i| hit(self.cell(i)))
                }
                None => self.cells.iter().any(|c| hit(c)),
            }
        })?;
        Some(rule.label.clone().unwrap_or_else(|| "summary".into()))
    }

    /// `column = 'value'` when the monitor's status column flags the shot as not measured
    /// normally.
    fn flag(&self, layout: &Layout) -> Option<String> {
        let st = layout.status?;
        let v = self.cell(st.index).trim();
        let ok = if st.spec.ok.is_empty() {
            v.is_empty()
        } else {
            st.spec.ok.iter().any(|o| o.eq_ignore_ascii_case(v))
        };
        (!ok).then(|| format!("{} = '{v}'", st.header))
    }

    /// The numeric cells converted to the shots file's units, by target; `None` for an empty
    /// cell of an optional flight column.
    fn values<'a>(
        &self,
        layout: &Layout<'_, 'a>,
    ) -> Result<Vec<(&'a str, Option<f64>)>, DataError> {
        let mut values = Vec::new();
        for r in layout.resolved {
            let Some(to) = r.target.unit() else { continue };
            let raw = self.cell(r.index);
            let here = |m: String| self.error_in(Some(&r.header), m);
            if raw.is_empty() || raw == "-" || raw == "--" {
                if r.spec.optional && !is_core(r.spec.target.as_str()) {
                    values.push((r.spec.target.as_str(), None));
                    continue;
                }
                return Err(here(format!(
                    "empty cell; a number is required for {}",
                    r.spec.target
                )));
            }
            let from = r.unit.expect("numeric columns have a unit");
            let v = parse_cell(raw, from, r.spec.direction.as_deref()).map_err(here)?;
            let v = from.convert(v, to) * f64::from(r.spec.sign.unwrap_or(1));
            if !v.is_finite() {
                return Err(here(format!(
                    "{} is not a finite number",
                    crate::data::quote_cell(raw)
                )));
            }
            if let Some(range) = r.target.range() {
                range.check(v).map_err(here)?;
            }
            values.push((r.spec.target.as_str(), Some(v)));
        }
        Ok(values)
    }

    /// The shot's id: the mapped id column, else `row<line>`; unique within the file.
    fn shot_id(&self, layout: &Layout, ids: &mut HashSet<String>) -> Result<String, DataError> {
        let header = layout.id.map(|c| c.header.as_str());
        let id = match layout.id {
            Some(c) => self.cell(c.index).trim().to_owned(),
            None => format!("row{}", self.line),
        };
        if id.is_empty() {
            return Err(self.error_in(header, "empty shot id"));
        }
        if !ids.insert(id.clone()) {
            return Err(self.error_in(
                header,
                format!("shot id '{id}' is used twice; ids must be unique (drop the shot_id mapping to number rows instead)"),
            ));
        }
        Ok(id)
    }

    /// The row's shots record: id, group and golfer, then the numeric columns (back and side
    /// spin from rate and axis, `impact_z_mm` from the signed heel–toe offset, when so laid out).
    fn record(&self, layout: &Layout, ids: &mut HashSet<String>) -> Result<Vec<String>, DataError> {
        let values = self.values(layout)?;
        let get = |name: &str| {
            values
                .iter()
                .find(|(n, _)| *n == name)
                .and_then(|(_, v)| *v)
        };
        let mut rec: Vec<String> = vec![self.shot_id(layout, ids)?];
        for col in [layout.group, layout.golfer].into_iter().flatten() {
            let v = self.cell(col.index).trim();
            if v.is_empty() && col.spec.target == "group" {
                return Err(self.error_in(Some(&col.header), "empty group (club) name"));
            }
            rec.push(v.to_owned());
        }
        let (back, side) = if layout.use_rate_axis {
            let rate = get("spin_rate_rpm").expect("core");
            let axis = get("spin_axis_deg").expect("core").to_radians();
            (Some(rate * axis.cos()), Some(rate * axis.sin()))
        } else {
            (get("backspin_rpm"), get("sidespin_rpm"))
        };
        for c in &layout.numeric {
            let v =
                match *c {
                    "impact_z_mm" if layout.from_offset => get("impact_offset_mm").map(|o| {
                        match layout.offset_side.expect("checked in the layout") {
                            OffsetSide::Toe => o,
                            OffsetSide::Heel => -o,
                        }
                    }),
                    "backspin_rpm" => back,
                    "sidespin_rpm" => side,
                    c => get(c),
                };
            rec.push(v.map(fmt_f64).unwrap_or_default());
        }
        Ok(rec)
    }
}
