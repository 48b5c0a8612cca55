//! Converting the export's rows to shots: rows to skip (summary rows, shots the monitor
//! flagged), cells to numbers in the shots file's units, ids, derived columns and the flags of
//! what the monitor estimated or modelled.
//!
//! A bad row does not sink the file: it is left out and counted under its reason, with its
//! line, and the import ends with one summary (`--strict` refuses the file at the first). A shot
//! that lacks part of its delivery (a session without impact-location hardware) keeps those
//! cells empty, so its launch can still be flown.
//!
//! Size: one row's way from cells to a shot (skip rules, shape, values, spin, delivery, flags)
//! is one sequence, read best in one file; what "not measured" means is in `missing.rs`.

use std::collections::HashSet;
use std::path::Path;

use super::cell::{parse_cell, parse_number, split_header};
use super::checks::SpinCheck;
use super::condition::Condition;
use super::layout::Layout;
use super::missing::{
    club_zeros_not_measured, flight_range, launch_target, not_measured, sentinel,
    spin_zeros_not_measured,
};
use super::summary::{summarise, Tally};
use super::table::{is_unit_row, Table};
use super::target::{Target, LAUNCH};
use super::units::Unit;
use super::{ExportSpec, SkipRule};
use crate::data::{fmt_f64, DataError};
use crate::model::DeliveryVar;

/// Cells that mark a row of statistics, never a shot, whatever the mapping says (case
/// ignored): the rows vendors append per club or per session.
const SUMMARY: [&str; 12] = [
    "average",
    "avg",
    "avg.",
    "mean",
    "median",
    "dev",
    "deviation",
    "std. dev.",
    "std dev",
    "stddev",
    "std. deviation",
    "consistency",
];

/// The carries' units checked against the flight model ([`super::carry_units::check`]): the
/// refusal of carries far shorter than their launches fly when a reading of the units explains
/// it, else the note, if any.
fn carry_units(
    path: &Path,
    layout: &Layout,
    redundancy: &super::checks::Redundancy,
) -> Result<Option<String>, DataError> {
    let (Some(c), Some(b)) = (layout.column("carry_yd"), layout.column("ball_speed_mph")) else {
        return Ok(None);
    };
    let unit = |u: Option<Unit>| u.map_or("", |u| u.name);
    let read = super::carry_units::AsRead {
        header: &c.header,
        carry_unit: unit(c.unit),
        carry_assumed: c.unit_assumed,
        speed_unit: unit(b.unit),
        speed_assumed: b.unit_assumed,
    };
    redundancy.carry_units(path, &read)
}

/// Why a row holding a spreadsheet's error value is left out.
const SPREADSHEET_ROW: &str = "a cell holds a spreadsheet's error value (a row a formula computed)";

/// The start of the reason a row with no measured launch is left out for (an empty cell, a
/// value read as not measured: a vendor's sentinel or 0, lost spin).
const NO_LAUNCH: &str = "no measured launch";

/// The start of the reason a row with no delivery is left out for (in an export that does not
/// measure the launch).
const NO_DELIVERY: &str = "no delivery";

/// Why a row whose back and side spin are both exactly 0 is left out: the monitor lost the
/// spin (`docs/import.md`, "Not measured").
const LOST_SPIN: &str =
    "no measured launch (back and side spin both exactly 0: the monitor lost the spin)";

/// Whether a row left out for `reason` was left out by a rule `docs/import.md` states as
/// skipped and counted: a row a spreadsheet's formula computed, or one whose launch (or
/// delivery) the monitor did not measure. Such rows are no sign that the file is read wrongly
/// (unlike a cell that is not a number, a value outside its range, a row of the wrong width).
fn left_out_by_rule(reason: &str) -> bool {
    reason == SPREADSHEET_ROW || reason.starts_with(NO_LAUNCH) || reason.starts_with(NO_DELIVERY)
}

/// Whether a cell holds the error value a spreadsheet writes where a formula failed: Excel's
/// and Google Sheets' `#DIV/0!`, `#VALUE!`, `#NAME?`, `#SPILL!`, … (a `#`, letters, digits or `/`,
/// then `!` or `?`), `#N/A` and its translations (`#NV`, `#N/D`, `#I/T`), `#GETTING_DATA`, and
/// LibreOffice's `Err:5xx` codes. A row holding one in a column the import reads was computed
/// by a spreadsheet (an AVERAGE row under the shots, a lookup that failed), not exported by the
/// monitor, and is left out and counted.
fn is_spreadsheet_error(cell: &str) -> bool {
    if ["#N/A", "#NV", "#N/D", "#I/T", "#GETTING_DATA"].contains(&cell) {
        return true;
    }
    if let Some(code) = cell.strip_prefix("Err:") {
        return code.len() == 3
            && code.starts_with('5')
            && code.bytes().all(|b| b.is_ascii_digit());
    }
    let Some(body) = cell
        .strip_prefix('#')
        .and_then(|c| c.strip_suffix('!').or_else(|| c.strip_suffix('?')))
    else {
        return false;
    };
    (2..=12).contains(&body.chars().count())
        && body.chars().any(char::is_alphabetic)
        && body
            .chars()
            .all(|c| c.is_alphanumeric() || c == '/' || c == '_')
}

/// The group of shots whose club cell is empty.
pub(super) const NO_CLUB: &str = "(no club)";

/// The shots CSV (bytes), the number of shots written and the export's file line of each.
pub(super) struct Shots {
    pub csv: Vec<u8>,
    pub count: usize,
    pub lines: Vec<usize>,
    /// Shots with a complete delivery (when the export gives one).
    pub complete: usize,
}

/// Refuse an export the rows show to be read wrongly: most rows unusable, or the values it
/// gives twice disagreeing on most shots (spin, units, smash factor).
fn refuse_read_wrongly(
    path: &Path,
    vendor: &str,
    layout: &Layout,
    tally: &Tally,
    written: usize,
) -> Result<(), DataError> {
    super::summary::refuse_mostly_bad(path, vendor, tally, written)?;
    tally.redundancy.refuse_systematic(path, vendor)?;
    tally.redundancy.refuse_units(path, &layout.units_read())?;
    tally.redundancy.refuse_smash(path, vendor)
}

/// Write the shots of `table` laid out by `layout`; the summary goes to `notes`. Under
/// `strict` the first bad or incomplete row refuses the file. Refuses a file with no usable
/// rows, and one whose redundant values disagree on most shots (a mapping reading a column
/// with the wrong sign).
pub(super) fn write_shots(
    path: &Path,
    table: &Table,
    export: &ExportSpec,
    layout: &Layout,
    strict: bool,
    notes: &mut Vec<String>,
) -> Result<Shots, DataError> {
    let (skip_rules, vendor) = (&export.skip_rows, &export.name);
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(layout.header()).expect("writing to memory");
    let mut tally = Tally::default();
    let (mut ids, mut lines, mut complete) = (HashSet::new(), Vec::new(), 0usize);
    let not_summary: Vec<usize> = ["golfer", "datetime", "ball_type", "shot_id"]
        .iter()
        .filter_map(|t| layout.column(t).map(|c| c.index))
        .collect();
    let day_first = layout.column("datetime").is_some_and(|c| {
        crate::data::datetime::day_first(
            table
                .rows
                .iter()
                .map(|(_, cells)| cells.get(c.index).map_or("", String::as_str)),
        )
    });
    for (line, e) in &table.broken {
        if strict {
            return Err(e.clone());
        }
        tally.leave_out("not valid JSON (a line cut short?)".into(), *line, e, false);
    }
    for (line, cells) in &table.rows {
        if is_unit_row(cells) {
            repeated_units(path, *line, cells, layout)?;
            tally.skip("repeated units".into(), *line);
            continue;
        }
        let row = RowAt {
            path,
            line: *line,
            cells,
            decimal_comma: table.decimal_comma,
            export_missing: &export.missing,
            strict,
            day_first,
        };
        if let Some(label) = row.skipped_by(skip_rules, table, &not_summary) {
            tally.skip(label, *line);
            continue;
        }
        if let Some(e) = row.spreadsheet_error(table, layout) {
            if strict {
                return Err(e);
            }
            tally.leave_out(SPREADSHEET_ROW.into(), *line, &e, true);
            continue;
        }
        if let Some(flag) = row.flag(layout) {
            tally.flagged.push((*line, flag));
            continue;
        }
        match row.convert(table, layout, &mut ids) {
            Ok(shot) => {
                if let Some(what) = shot.lacks {
                    if strict {
                        return Err(shot.lack_error.expect("a lack has its message"));
                    }
                    Tally::push_to(&mut tally.lacking, what, *line);
                } else if layout.delivery_all {
                    complete += 1;
                }
                for flag in shot.flags {
                    Tally::push_to(&mut tally.flags, flag, *line);
                }
                for (reason, e) in &shot.blanked {
                    tally.blank(reason.clone(), *line, e);
                }
                tally.redundancy.add(*line, &shot.spin, shot.smash);
                let [b, c, l, carry, back] = shot.physics;
                if back.is_some_and(|v| v < 0.0) {
                    tally.topspin.push(*line);
                }
                tally.redundancy.add_physics(b, c, l, carry, back);
                w.write_record(&shot.record).expect("writing to memory");
                lines.push(*line);
            }
            Err((reason, e)) => {
                if strict {
                    return Err(e);
                }
                // A row whose quoted cell ran over its line's end took the lines it ran into.
                let by_rule = left_out_by_rule(&reason);
                for l in *line..=row.last_line() {
                    tally.leave_out(reason.clone(), l, &e, by_rule);
                }
            }
        }
    }
    refuse_read_wrongly(path, vendor, layout, &tally, lines.len())?;
    let carry_note = carry_units(path, layout, &tally.redundancy)?;
    summarise(&tally, lines.len(), notes);
    notes.extend(carry_note);
    if lines.is_empty() {
        return Err(super::summary::no_shots(path, vendor, &tally));
    }
    Ok(Shots {
        csv: w.into_inner().expect("flushing memory"),
        count: lines.len(),
        lines,
        complete,
    })
}

/// A units row among the shots (a second export pasted under the first, a units row moved):
/// skipped when it states the units the columns are read in, else the file is refused, since
/// which shots it holds for is not clear.
fn repeated_units(
    path: &Path,
    line: usize,
    cells: &[String],
    layout: &Layout,
) -> Result<(), DataError> {
    for r in layout.resolved {
        let (Some(unit), Some(cell)) = (r.unit, cells.get(r.index)) else {
            continue;
        };
        if cell.is_empty() || cell == "[]" {
            continue;
        }
        if Unit::parse(cell).is_none_or(|u| u.name != unit.name) {
            return Err(DataError::at(
                path,
                Some(line),
                Some(format!("column '{}'", r.header)),
                format!(
                    "a units row among the shots says '{cell}', but the column is read in {} \
                     (the header, the units row above the shots or the mapping): which shots \
                     it holds for is not clear; keep one units row, under the header",
                    unit.name
                ),
            ));
        }
    }
    Ok(())
}

/// A row converted to a shot.
struct Converted {
    record: Vec<String>,
    /// What the shot lacks (`impact location`, `delivery`), with the strict refusal.
    lacks: Option<&'static str>,
    lack_error: Option<DataError>,
    /// The flags set on it.
    flags: Vec<&'static str>,
    /// Cells read as not measured (a sentinel, a 0 the vendor writes for "no value", a value
    /// outside its range in a column the launch does not need): why, and the message.
    blanked: Vec<(String, String)>,
    /// Values given twice, to check against each other.
    spin: Option<SpinCheck>,
    smash: Option<(f64, f64, f64)>,
    /// Ball speed, club speed, launch angle and carry, for the unit checks.
    physics: [Option<f64>; 5],
}

/// One row of the export, for conversion and messages.
struct RowAt<'r> {
    path: &'r Path,
    line: usize,
    cells: &'r [String],
    decimal_comma: bool,
    /// The export's values meaning "not measured".
    export_missing: &'r [String],
    /// Refuse the file at a cell that would be read as not measured for being out of range.
    strict: bool,
    /// Slash dates in the datetime column are day-first.
    day_first: bool,
}

/// A row left out: its reason (the key of the summary) and its full message.
type Bad = (String, DataError);

impl RowAt<'_> {
    /// The cell at `i`, empty when the row is short.
    fn cell(&self, i: usize) -> &str {
        self.cells.get(i).map_or("", |c| c.trim())
    }

    /// The error, naming its column, when a cell the import reads ([`Layout::resolved`])
    /// holds a spreadsheet's error value ([`is_spreadsheet_error`]); one in a column it does
    /// not read leaves the shot as it is.
    fn spreadsheet_error(&self, table: &Table, layout: &Layout) -> Option<DataError> {
        let i = layout
            .resolved
            .iter()
            .map(|r| r.index)
            .filter(|&i| i != super::columns::ABSENT)
            .find(|&i| is_spreadsheet_error(self.cell(i)))?;
        let header = table.header.get(i).map(String::as_str);
        Some(self.error_in(
            header,
            format!(
                "'{}' is a spreadsheet's error value, not a measurement: the row was computed \
                 by a formula (an average row?), not exported by the monitor",
                self.cell(i)
            ),
        ))
    }

    /// The file line the row ends on: a quoted cell may run over line ends.
    fn last_line(&self) -> usize {
        let breaks: usize = self
            .cells
            .iter()
            .map(|c| c.matches('\n').count() + c.matches('\r').count() - c.matches("\r\n").count())
            .sum();
        self.line + breaks
    }

    /// A row the file cut short inside a quoted cell, or one whose mapped cell runs over its
    /// line's end (a quote left open by a cut line takes the next line into the cell): its
    /// cells are not trusted.
    fn cut_or_run_on(&self, table: &Table, layout: &Layout) -> Result<(), Bad> {
        if table.cut_last == Some(self.line) {
            let e = self.error_in(
                None,
                "the file ends inside a quoted cell of this row: the row is cut short (a \
                 truncated file?), so its cells are not trusted",
            );
            return Err((
                "cut short inside a quoted cell (the file ends there)".into(),
                e,
            ));
        }
        let run_on = layout.resolved.iter().find(|r| {
            self.cells
                .get(r.index)
                .is_some_and(|c| c.contains(['\n', '\r']))
        });
        if let Some(r) = run_on {
            let e = self.error_in(
                Some(&r.header),
                format!(
                    "a quoted cell runs from line {} to line {} (a quote left open by a cut \
                     line?), so the row's cells are not trusted",
                    self.line,
                    self.last_line()
                ),
            );
            return Err(("a quoted cell runs over its line's end".into(), e));
        }
        Ok(())
    }

    /// An error at this row, in the column headed `header`.
    fn error_in(&self, header: Option<&str>, message: impl std::fmt::Display) -> DataError {
        DataError::at(
            self.path,
            Some(self.line),
            header.map(|h| format!("column '{h}'")),
            message,
        )
    }

    /// The label of the first skip rule the row matches, or `summary` for a row of statistics
    /// (a cell reading Average, Avg, Dev, Deviation, Std. Dev., …).
    fn skipped_by(
        &self,
        rules: &[SkipRule],
        table: &Table,
        skip_for_summary: &[usize],
    ) -> Option<String> {
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
                // Any cell but the golfer's, date's, ball's and shot id's: a golfer named
                // Average is a golfer.
                None => self
                    .cells
                    .iter()
                    .enumerate()
                    .any(|(i, c)| !skip_for_summary.contains(&i) && hit(c)),
            }
        });
        if let Some(rule) = rule {
            return Some(rule.label.clone().unwrap_or_else(|| "summary".into()));
        }
        // A golfer named Dev or Mean is a golfer: the golfer, date and text columns are not
        // looked at.
        let summary = |c: &String| SUMMARY.iter().any(|s| s.eq_ignore_ascii_case(c.trim()));
        self.cells
            .iter()
            .enumerate()
            .filter(|(i, _)| !skip_for_summary.contains(i))
            .any(|(_, c)| summary(c))
            .then(|| "summary".into())
    }

    /// `column = 'value'` when the monitor's status column flags the shot as not measured
    /// normally.
    fn flag(&self, layout: &Layout) -> Option<String> {
        let st = layout.status?;
        let v = self.cell(st.index);
        let ok = if st.spec.ok.is_empty() {
            v.is_empty()
        } else {
            st.spec.ok.iter().any(|o| o.eq_ignore_ascii_case(v))
        };
        (!ok).then(|| format!("{} = '{v}'", st.header))
    }

    /// A row with more cells than the header: a separator inside an unquoted cell (a decimal
    /// comma in a comma-separated file) has shifted them, and no cell can be trusted.
    fn too_long(&self, table: &Table) -> Result<(), Bad> {
        let n = table.header.len();
        if self.cells.len() > n && self.cells[n..].iter().any(|c| !c.trim().is_empty()) {
            let n = n - table.added;
            let reason = "more cells than the header has columns".to_owned();
            let e = self.error_in(
                None,
                format!(
                    "{} cells where the header has {n} columns: a separator inside an unquoted \
                     cell (a decimal comma?) has shifted the cells, so none of them is trusted",
                    self.cells.len() - table.added
                ),
            );
            return Err((reason, e));
        }
        Ok(())
    }

    /// A row with fewer cells than the header whose last cell, or a column after it, is mapped:
    /// a line cut short (a truncated file's last row), whose last cell may be cut too (`16` for
    /// `162.4`).
    fn too_short(&self, table: &Table, layout: &Layout) -> Result<(), Bad> {
        let n = self.cells.len();
        // The file's own columns (not those added after them, which a cut row lacks too).
        let width = table.header.len() - table.added;
        if n >= width {
            return Ok(());
        }
        // A mapped column missing, or the last cell there is mapped: it may be cut itself.
        let cut = |r: &&super::columns::Resolved| {
            r.index + 1 >= n && r.index < width && r.index != super::columns::ABSENT
        };
        if let Some(r) = layout.resolved.iter().find(cut) {
            let e = self.error_in(
                Some(&r.header),
                format!(
                    "{n} cells where the header has {width} columns: the row is cut short (a \
                     truncated file?), so its last cell is not trusted either"
                ),
            );
            return Err(("fewer cells than the header has columns".to_owned(), e));
        }
        Ok(())
    }

    /// The numeric cells converted to the shots file's units, by target (`None`: empty, `-`,
    /// a sentinel, a 0 that means "not measured", or, in a column the launch does not need, a
    /// value outside its range: those go to `blanked`, with why).
    fn values<'a>(
        &self,
        layout: &Layout<'_, 'a>,
        blanked: &mut Vec<(String, String)>,
    ) -> Result<Vec<(&'a str, Option<f64>)>, Bad> {
        let mut values = Vec::new();
        for r in layout.resolved {
            let raw = self.cell(r.index);
            let numeric = r.target.unit().is_some() || r.target == Target::SmashFactor;
            if !numeric {
                continue;
            }
            let target = r.spec.target.as_str();
            if not_measured(raw, &r.spec.missing, self.export_missing) {
                if let Some(a) = r.spec.assume {
                    blanked.push((
                        format!(
                            "column '{}': not measured, {a} assumed (the mapping's assume)",
                            r.header
                        ),
                        format!("line {}", self.line),
                    ));
                }
                values.push((target, r.spec.assume));
                continue;
            }
            let bad = |kind: &str, m: &dyn std::fmt::Display| {
                (
                    format!("column '{}' {kind}", r.header),
                    self.error_in(Some(&r.header), m),
                )
            };
            let not_a_number = || format!("{} is not a number", crate::data::quote_cell(raw));
            let (v, raw_v) = match r.unit {
                Some(from) => {
                    let to = r.target.unit().expect("numeric");
                    let v = parse_cell(raw, from, r.spec.direction.as_deref(), self.decimal_comma)
                        .map_err(|m| bad("is not a number", &m))?;
                    let sign = r.spec.sign.unwrap_or(1) * r.legend_sign;
                    // `+ 0.0`: a 0 read with a sign of −1 is 0, never −0.
                    (from.convert(v, to) * f64::from(sign) + 0.0, v)
                }
                None => {
                    let v = parse_number(raw, self.decimal_comma)
                        .ok_or_else(|| bad("is not a number", &not_a_number()))?;
                    (v, v)
                }
            };
            if !v.is_finite() {
                let m = format!("{} is not a finite number", crate::data::quote_cell(raw));
                // Where the launch does not need the column, the shot keeps its launch (a
                // Garmin smash factor `inf` beside a club speed of 0, not measured).
                if self.strict || launch_target(target) {
                    return Err(bad("is not a finite number", &m));
                }
                blanked.push((
                    format!("column '{}': not a finite number", r.header),
                    format!("line {}: {m}", self.line),
                ));
                values.push((target, None));
                continue;
            }
            if let Some(why) = sentinel(target, raw_v) {
                blanked.push((
                    format!("column '{}': {why}", r.header),
                    format!("line {}: {}", self.line, crate::data::quote_cell(raw)),
                ));
                values.push((target, None));
                continue;
            }
            let range = r.target.range().or_else(|| flight_range(target));
            if let Some(range) = range {
                if let Err(m) = range.check(v) {
                    if self.strict || launch_target(target) {
                        return Err(bad("is outside its physical range", &m));
                    }
                    blanked.push((
                        format!("column '{}': outside its physical range", r.header),
                        format!("line {}: {m}", self.line),
                    ));
                    values.push((target, None));
                    continue;
                }
            }
            values.push((target, Some(v)));
        }
        Ok(values)
    }

    /// The shot's id: the mapped id column, else `row<line>`; unique within the file.
    fn shot_id(&self, layout: &Layout, ids: &mut HashSet<String>) -> Result<String, Bad> {
        let header = layout.id.map(|c| c.header.as_str());
        let id = match layout.id {
            Some(c) => self.cell(c.index).to_owned(),
            None => format!("row{}", self.line),
        };
        if id.is_empty() {
            return Err((
                "an empty shot id".into(),
                self.error_in(header, "empty shot id"),
            ));
        }
        if !ids.insert(id.clone()) {
            return Err((
                "a shot id used twice".into(),
                self.error_in(
                    header,
                    format!("shot id '{id}' is used twice; ids must be unique (drop the shot_id mapping to number rows instead)"),
                ),
            ));
        }
        Ok(id)
    }

    /// The row's shot: id, group and golfer, the numeric columns (back and side spin from
    /// rate and axis, `impact_z_mm` from the signed heel–toe offset, when so laid out), then
    /// the text and flag columns.
    fn convert(
        &self,
        table: &Table,
        layout: &Layout,
        ids: &mut HashSet<String>,
    ) -> Result<Converted, Bad> {
        self.cut_or_run_on(table, layout)?;
        self.too_long(table)?;
        self.too_short(table, layout)?;
        let mut blanked = Vec::new();
        let mut values = self.values(layout, &mut blanked)?;
        club_zeros_not_measured(&mut values, &mut blanked, self.line);
        spin_zeros_not_measured(&mut values, &mut blanked, self.line);
        let get = |name: &str| {
            values
                .iter()
                .find(|(n, _)| *n == name)
                .and_then(|(_, v)| *v)
        };
        let mut rec: Vec<String> = vec![self.shot_id(layout, ids)?];
        for col in [layout.group, layout.golfer].into_iter().flatten() {
            let v = self.cell(col.index);
            // A shot without a club name is a shot: flight needs no club. Such shots are a
            // group of their own.
            if v.is_empty() && col.spec.target == "group" {
                rec.push(NO_CLUB.to_owned());
                continue;
            }
            rec.push(v.to_owned());
        }
        let spin = SpinCheck::of(layout, &get);
        let (back, side) = if layout.use_rate_axis {
            match (get("spin_rate_rpm"), get("spin_axis_deg")) {
                (Some(rate), Some(axis)) => {
                    let a = axis.to_radians();
                    (Some(rate * a.cos()), Some(rate * a.sin()))
                }
                _ => (None, None),
            }
        } else if layout.use_back_axis {
            // Back spin is the component about the horizontal axis: side = back · tan(axis).
            match (get("backspin_rpm"), get("spin_axis_deg")) {
                (Some(b), Some(axis)) if axis.abs() < 89.0 => {
                    (Some(b), Some(b * axis.to_radians().tan()))
                }
                _ => (None, None),
            }
        } else {
            (get("backspin_rpm"), get("sidespin_rpm"))
        };
        if layout.launch_all {
            let lost_spin = blanked.iter().any(|(r, _)| r == super::missing::SPIN_ZEROS);
            self.launch_complete(layout, &get, back.zip(side).is_some(), lost_spin)?;
        }
        let condition = layout
            .of(Target::Condition)
            .and_then(|c| Condition::parse(self.cell(c.index)));
        // A condition the sentence states, when inside its range (a sentence's number is a
        // cell too: `1e400 ℉` is not a temperature).
        let stated = |c: &str, v: Option<f64>| {
            let range = Target::parse(c).and_then(Target::range);
            v.filter(|x| x.is_finite() && range.is_none_or(|r| r.check(*x).is_ok()))
        };
        let numeric_value = |c: &str| match c {
            "impact_z_mm" if layout.from_offset => {
                get("impact_offset_mm").map(|o| match layout.offset_side {
                    // `0.0 - o`, not `-o`: a centred strike is 0, never −0.
                    Some(super::OffsetSide::Heel) => 0.0 - o,
                    _ => o,
                })
            }
            "backspin_rpm" => back,
            "sidespin_rpm" => side,
            "altitude_m" => get(c).or(stated(c, condition.as_ref().and_then(|k| k.altitude_m))),
            "air_temperature_c" => {
                get(c).or(stated(c, condition.as_ref().and_then(|k| k.temperature_c)))
            }
            c => get(c),
        };
        let mut delivery_missing: Vec<&str> = Vec::new();
        for c in &layout.numeric {
            let v = numeric_value(c);
            if v.is_none() && DeliveryVar::from_column(c).is_some_and(|d| d.required()) {
                delivery_missing.push(c);
            }
            rec.push(v.filter(|x| x.is_finite()).map(fmt_f64).unwrap_or_default());
        }
        let (lacks, lack_error) = self.lacks(layout, &delivery_missing)?;
        let mut flags = Vec::new();
        for c in &layout.extra {
            let v = self.extra_value(c, layout, condition.as_ref(), &get);
            if v == "1" {
                flags.push(*c);
            }
            rec.push(v);
        }
        let smash = get("smash_factor")
            .zip(get("ball_speed_mph"))
            .zip(get("club_speed_mph"))
            .map(|((s, b), c)| (s, b, c));
        Ok(Converted {
            record: rec,
            lacks,
            lack_error,
            flags,
            blanked,
            spin,
            smash,
            physics: [
                get("ball_speed_mph"),
                get("club_speed_mph"),
                get("launch_angle_deg"),
                get("carry_yd"),
                get("backspin_rpm").or_else(|| {
                    let rate = get("spin_rate_rpm")?;
                    Some(rate * get("spin_axis_deg").unwrap_or(0.0).to_radians().cos())
                }),
            ],
        })
    }

    /// A row of an export that measures the launch must have all of it.
    fn launch_complete(
        &self,
        layout: &Layout,
        get: &dyn Fn(&str) -> Option<f64>,
        spin: bool,
        lost_spin: bool,
    ) -> Result<(), Bad> {
        let spin_cols: &[&str] = if layout.use_rate_axis {
            &["spin_rate_rpm", "spin_axis_deg"]
        } else if layout.use_back_axis {
            &["backspin_rpm", "spin_axis_deg"]
        } else {
            &["backspin_rpm", "sidespin_rpm"]
        };
        let missing = LAUNCH.iter().chain(spin_cols).find(|c| get(c).is_none());
        match missing {
            None if spin => Ok(()),
            _ => {
                let c = missing.copied().unwrap_or(spin_cols[0]);
                let header = layout.column(c).map_or(c, |r| r.header.as_str());
                if lost_spin && !LAUNCH.contains(&c) {
                    let e = self.error_in(
                        Some(header),
                        "back and side spin are both exactly 0, read as not measured (a struck \
                         ball spins: the monitor lost the spin); the measured launch needs them",
                    );
                    return Err((LOST_SPIN.to_owned(), e));
                }
                // A cell with a value read as not measured (a vendor's 0, a sentinel) is not
                // an empty cell.
                let raw = layout.column(c).map_or("", |r| self.cell(r.index).trim());
                let (what, why) = if raw.is_empty() {
                    ("empty".to_owned(), "empty cell".to_owned())
                } else {
                    let q = crate::data::quote_cell(raw);
                    (
                        "not measured".to_owned(),
                        format!("{q} read as not measured"),
                    )
                };
                let e = self.error_in(
                    Some(header),
                    format!("{why}; the measured launch needs {c}"),
                );
                Err((format!("{NO_LAUNCH} (column '{header}' {what})"), e))
            }
        }
    }

    /// What a shot lacks of its delivery: nothing, the impact location (kept, with empty
    /// cells), or more (kept when the launch is measured, left out otherwise).
    fn lacks(
        &self,
        layout: &Layout,
        missing: &[&str],
    ) -> Result<(Option<&'static str>, Option<DataError>), Bad> {
        if !layout.delivery_all || missing.is_empty() {
            return Ok((None, None));
        }
        let c = missing[0];
        let source = if c == "impact_z_mm" && layout.from_offset {
            "impact_offset_mm"
        } else {
            c
        };
        let header = layout.column(source).map_or(c, |r| r.header.as_str());
        let e = self.error_in(
            Some(header),
            format!("empty cell; a number is required for {c}"),
        );
        if !layout.launch_all {
            return Err((format!("{NO_DELIVERY} (column '{header}' empty)"), e));
        }
        let what = if missing.iter().all(|c| c.starts_with("impact_")) {
            "impact location"
        } else {
            "complete delivery"
        };
        Ok((Some(what), Some(e)))
    }

    /// A text or flag column's value.
    fn extra_value(
        &self,
        column: &str,
        layout: &Layout,
        condition: Option<&Condition>,
        get: &dyn Fn(&str) -> Option<f64>,
    ) -> String {
        let flag = |b: bool| if b { "1" } else { "0" }.to_owned();
        match column {
            "datetime" => layout
                .column("datetime")
                .map(|c| {
                    let cell = self.cell(c.index).trim();
                    crate::data::datetime::parse(cell, self.day_first)
                        .map_or_else(|| cell.to_owned(), |d| d.format())
                })
                .unwrap_or_default(),
            "ball_type" => layout
                .column("ball_type")
                .map(|c| self.cell(c.index).to_owned())
                .filter(|b| !b.is_empty())
                .or_else(|| condition.and_then(|k| k.ball.clone()))
                .unwrap_or_default(),
            "face_at" | "velocity_at" | "face_angle_from" => layout
                .convention
                .and_then(|c| {
                    super::conventions::cells(c)
                        .into_iter()
                        .find(|(col, _)| *col == column)
                })
                .map_or_else(String::new, |(_, v)| v.to_owned()),
            "spin_estimated" | "club_estimated" => {
                let c = layout.column(column).expect("laid out when mapped");
                let v = self.cell(c.index);
                let listed = |l: &[String]| l.iter().any(|e| e.eq_ignore_ascii_case(v));
                let unknown = !c.spec.measured.is_empty() && !v.is_empty();
                flag(listed(&c.spec.estimated) || (unknown && !listed(&c.spec.measured)))
            }
            _ => {
                if layout.all_modelled || condition.is_some_and(|k| k.normalized) {
                    return flag(true);
                }
                match (get("tracked_length_yd"), get("carry_yd")) {
                    (Some(t), Some(c)) => flag(modelled(t, c)),
                    _ => String::new(),
                }
            }
        }
    }
}

/// Whether a carry of `carry_yd` whose radar track ends at `tracked_yd` is the vendor's model
/// rather than a measurement: the track stops more than 10 % of the carry short of it (indoor
/// radars track the first few yards only).
pub(super) fn modelled(tracked_yd: f64, carry_yd: f64) -> bool {
    tracked_yd < 0.9 * carry_yd
}

#[cfg(test)]
mod tests {
    #[test]
    fn spreadsheet_error_values_and_not() {
        for e in [
            "#DIV/0!",
            "#N/A",
            "#VALUE!",
            "#NAME?",
            "#SPILL!",
            "#GETTING_DATA",
            "#NV",
        ] {
            assert!(super::is_spreadsheet_error(e), "{e}");
        }
        for e in [
            "#WERT!",
            "#VALEUR!",
            "#VERDI!",
            "#BLOCKED!",
            "Err:502",
            "Err:522",
        ] {
            assert!(super::is_spreadsheet_error(e), "{e}");
        }
        for v in [
            "#1", "#12!", "# !", "Err:42", "Err:5021", "Driver", "5.4 L", "N/A", "#",
        ] {
            assert!(!super::is_spreadsheet_error(v), "{v}");
        }
    }
}
