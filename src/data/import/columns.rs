//! Matching the mapping's columns to the export's header, and settling the unit of each.
//!
//! A unit may come from the header (`Ball Speed (mph)`), from a units row, from the mapping's
//! `unit` (which the file must agree with) or from its `default_unit` (reported as assumed).

use std::collections::HashSet;
use std::path::Path;

use super::cell::{header_legend, split_header};
use super::table::Table;
use super::target::Target;
use super::units::Unit;
use super::{ColumnSpec, ImportOptions, Mapping, OffsetSide, UnknownColumns};
use crate::data::DataError;

/// The index of a column the file does not have (read as empty cells).
pub(super) const ABSENT: usize = usize::MAX;

/// A mapped column found in the export.
pub(super) struct Resolved<'a> {
    /// The mapping's entry.
    pub spec: &'a ColumnSpec,
    /// What it feeds.
    pub target: Target,
    /// Its index among the export's cells.
    pub index: usize,
    /// Its header as written.
    pub header: String,
    /// The unit its cells are in (numeric targets only).
    pub unit: Option<Unit>,
    /// Whether that unit was assumed (a preset's default unit; the file and mapping state none).
    pub unit_assumed: bool,
    /// The factor the header's sign legend gives its signed numbers (1 without a legend).
    pub legend_sign: i8,
    /// The side of a positive heel–toe offset, when the header's legend names it.
    pub legend_offset: Option<OffsetSide>,
}

/// Find every mapped column in `table` and its unit. Refuses a file missing a required column,
/// an export column mapped twice, contradicting units, or (unless `opts` allows it) export
/// columns the mapping does not know. Returns the columns and the notes for the user (unknown
/// columns dropped, units assumed).
pub(super) fn resolve_columns<'a>(
    path: &Path,
    table: &Table,
    mapping: &'a Mapping,
    opts: &ImportOptions,
) -> Result<(Vec<Resolved<'a>>, Vec<String>), DataError> {
    let vendor = &mapping.export.name;
    refuse_duplicate_headers(path, table)?;
    let mut used = vec![false; table.headers.len()];
    let mut resolved: Vec<Resolved> = Vec::new();
    let mut missing: Vec<String> = Vec::new();
    let mut assumed: Vec<String> = Vec::new();
    for spec in &mapping.column {
        let target = Target::parse(&spec.target).expect("checked when parsed");
        let Some(index) = find_column(table, &spec.source, target, &used) else {
            if !spec.optional {
                missing.push(format!("'{}' ({})", spec.source[0], spec.target));
            } else if spec.assume.is_some() {
                // A column the mapping assumes a value for is there even when the file has
                // none of it: every shot gets the assumed value, counted in the summary.
                resolved.push(Resolved {
                    spec,
                    target,
                    index: ABSENT,
                    header: format!("{} (absent)", spec.source[0]),
                    unit: target.unit(),
                    unit_assumed: false,
                    legend_sign: 1,
                    legend_offset: None,
                });
            }
            continue;
        };
        if used[index] {
            return Err(DataError::at(
                path,
                Some(table.header_line),
                Some(format!("column '{}'", table.header[index])),
                "this column is mapped to two targets",
            ));
        }
        used[index] = true;
        let (unit, unit_assumed) = match target.unit() {
            None => (None, false),
            Some(to) => {
                let col = ColumnAt { table, spec, index };
                let (unit, was_assumed) = col.unit(path, to, vendor)?;
                if was_assumed {
                    assumed.push(format!("{} in {}", table.header[index], unit.name));
                }
                (Some(unit), was_assumed)
            }
        };
        let (legend_sign, legend_offset) = legend_of(path, table, spec, index)?;
        resolved.push(Resolved {
            spec,
            target,
            index,
            header: table.header[index].clone(),
            unit,
            unit_assumed,
            legend_sign,
            legend_offset,
        });
    }
    if !missing.is_empty() {
        let present: Vec<String> = table
            .header
            .iter()
            .filter(|h| !h.is_empty())
            .cloned()
            .collect();
        return Err(DataError::at(
            path,
            Some(table.header_line),
            None,
            format!(
                "not a {vendor} export as expected: missing column(s) {}; the file has: {}; if \
                 the monitor does not measure them (an original Mevo gives no launch \
                 direction), a mapping file can give each an `assume` value (docs/import.md, \
                 \"Mapping files\")",
                missing.join(", "),
                listed(&present, ", ")
            ),
        ));
    }
    let mut notes = Vec::new();
    let unknown = unknown_columns(table, mapping, &used);
    let lenient = mapping.export.unknown_columns == UnknownColumns::Note;
    if !unknown.is_empty() && !opts.ignore_unknown_columns && !lenient {
        return Err(DataError::at(
            path,
            Some(table.header_line),
            None,
            format!(
                "unknown column(s) for the {vendor} format: '{}'; map or ignore them in a mapping file (--format FILE.toml), \
                 or pass --ignore-unknown-columns",
                listed(&unknown, "', '")
            ),
        ));
    }
    if !unknown.is_empty() {
        notes.push(format!(
            "{} column(s) not used by the {vendor} format (left in the export): {}",
            unknown.len(),
            listed(&unknown, ", ")
        ));
    }
    if !assumed.is_empty() {
        notes.push(format!(
            "the file states no unit for {}: the {vendor} preset's units were assumed",
            assumed.join(", ")
        ));
    }
    Ok((resolved, notes))
}

/// Column names for a message: a file of thousands of columns (or of one 100 kB name) gets a
/// line, not a page: the first [`SHOWN_NAMES`] names, each cut after [`SHOWN_NAME_CHARS`]
/// characters, then `… and N more`.
fn listed(names: &[String], sep: &str) -> String {
    let cut = |n: &String| -> String {
        if n.chars().count() <= SHOWN_NAME_CHARS {
            n.clone()
        } else {
            let head: String = n.chars().take(SHOWN_NAME_CHARS).collect();
            format!("{head}…")
        }
    };
    let shown: Vec<String> = names.iter().take(SHOWN_NAMES).map(cut).collect();
    let mut s = shown.join(sep);
    if names.len() > SHOWN_NAMES {
        s.push_str(&format!(" … and {} more", names.len() - SHOWN_NAMES));
    }
    s
}

/// Most column names a message lists.
const SHOWN_NAMES: usize = 20;

/// Most characters of one column name a message shows.
const SHOWN_NAME_CHARS: usize = 48;

/// The export column a mapping entry reads: the first of its `source` names the header has
/// (case and spacing ignored). A header may name a column twice when a unit tells the two apart
/// (FlightScope writes `club` for the club's name and `Club (mph)` for its speed): a source
/// written with a unit (`Club (mph)`) takes only a column with a unit, a text target prefers the
/// column without one, and a numeric target the column with one; a source's unit and the
/// column's must measure the same kind of quantity. Columns already `used` are skipped.
pub(super) fn find_column(
    table: &Table,
    source: &[String],
    target: Target,
    used: &[bool],
) -> Option<usize> {
    for name in source {
        let (want, want_unit) = split_header(name);
        // A source written with a unit takes a column with a unit of the same kind (`SIDE
        // (rpm)` is not SkyTrak's `SIDE` in degrees).
        let kind = |u: &str| Unit::parse(u).map(|u| u.quantity);
        let fits = |i: usize| match (&want_unit, &table.headers[i].1) {
            (None, _) => true,
            (Some(_), None) => false,
            (Some(w), Some(u)) => match (kind(w), kind(u)) {
                (Some(a), Some(b)) => a == b,
                _ => true,
            },
        };
        let candidates: Vec<usize> = (0..table.headers.len())
            .filter(|&i| !used[i] && table.headers[i].0 == want && fits(i))
            .collect();
        let has_unit = |i: &&usize| table.headers[**i].1.is_some();
        // A target without a unit (a club's name, a date) never takes a column with one: with
        // FlightScope's `club` column gone, `Club (mph)` is not the club.
        let found = if target.unit().is_some() {
            candidates.iter().find(has_unit).or(candidates.first())
        } else {
            candidates.iter().find(|i| !has_unit(i))
        };
        if let Some(&i) = found {
            return Some(i);
        }
    }
    None
}

/// What the sign legend of column `index`'s header (`Push/Pull (deg L-/R+)`) says: the factor
/// its signed numbers take to follow the mapping's `direction`, and the side of a positive
/// heel–toe offset. A legend naming sides the column does not have refuses the file; a legend
/// on a column without a direction (`Lie (deg toe down-/toe up+)`) is documentation only.
fn legend_of(
    path: &Path,
    table: &Table,
    spec: &ColumnSpec,
    index: usize,
) -> Result<(i8, Option<OffsetSide>), DataError> {
    let header = &table.header[index];
    let Some(legend) = header_legend(header) else {
        return Ok((1, None));
    };
    let refuse = |allowed: &str| {
        DataError::at(
            path,
            Some(table.header_line),
            Some(format!("column '{header}'")),
            format!(
                "its sign legend '{}' does not name the sides of {} ({allowed}); a mapping \
                 file can read the column with its own `direction`",
                legend.text(),
                spec.target
            ),
        )
    };
    if let Some(dir) = spec.direction.as_deref() {
        let sign = legend
            .sign_for(dir)
            .ok_or_else(|| refuse("left/right, in-out/out-in, open/closed or low/high"))?;
        return Ok((sign, None));
    }
    if spec.target == "impact_offset_mm" {
        let side = legend.offset_side().ok_or_else(|| refuse("toe/heel"))?;
        return Ok((1, Some(side)));
    }
    Ok((1, None))
}

/// Refuse an export whose header names one column twice (case, spacing and the spelling of a
/// bracketed unit ignored): which of the two a mapping would read is a guess, and the other
/// would be lost. `club` and `Club (mph)` are two columns.
fn refuse_duplicate_headers(path: &Path, table: &Table) -> Result<(), DataError> {
    let unit = |u: &Option<String>| u.as_deref().map(|u| Unit::parse(u).map(|u| u.name));
    for (j, (name, u)) in table.headers.iter().enumerate() {
        if name.is_empty() {
            continue;
        }
        if let Some(i) = table.headers[..j]
            .iter()
            .position(|(h, v)| h == name && unit(v) == unit(u))
        {
            return Err(DataError::at(
                path,
                Some(table.header_line),
                Some(format!("column '{}'", table.header[j])),
                if u.is_none() {
                    format!(
                        "the header has this column twice (columns {} and {}) and nothing tells \
                         the two apart: give each its unit, in a units row under the header (as \
                         SkyTrak's `RPM` and `DEG` under its two `SIDE` columns) or in its name \
                         (`SIDE (rpm)`), or remove or rename one",
                        i + 1,
                        j + 1
                    )
                } else {
                    format!(
                        "the header has this column twice (columns {} and {}), in the same unit; \
                         each column may appear once: remove or rename one",
                        i + 1,
                        j + 1
                    )
                },
            ));
        }
    }
    Ok(())
}

/// Export columns neither mapped (`used`) nor listed as ignored or as a skip-rule column.
fn unknown_columns(table: &Table, mapping: &Mapping, used: &[bool]) -> Vec<String> {
    let ignored: HashSet<String> = mapping
        .export
        .ignore
        .iter()
        .map(|n| split_header(n).0)
        .chain(
            mapping
                .export
                .skip_rows
                .iter()
                .filter_map(|r| r.column.as_ref().map(|c| split_header(c).0)),
        )
        .collect();
    let named = table
        .header
        .iter()
        .enumerate()
        .filter(|(i, h)| !h.is_empty() && !used[*i] && !ignored.contains(&table.headers[*i].0))
        .map(|(_, h)| h.clone());
    // A column without a name that holds data is reported too, never dropped unseen.
    // (A row with more cells than the header is the row's own fault, reported with it.)
    let unnamed = (0..table.header.len())
        .filter(|&i| table.header[i].is_empty())
        .filter(|&i| {
            table
                .rows
                .iter()
                .any(|(_, c)| c.get(i).is_some_and(|v| !v.is_empty()))
        })
        .map(|i| format!("column {} (no name in the header, holds data)", i + 1));
    named.chain(unnamed).collect()
}

/// A mapped numeric column at `index` of the export.
struct ColumnAt<'t, 'a> {
    table: &'t Table,
    spec: &'a ColumnSpec,
    index: usize,
}

impl ColumnAt<'_, '_> {
    /// Where messages point: the column's header.
    fn place(&self) -> Option<String> {
        Some(format!("column '{}'", self.table.header[self.index]))
    }

    /// The unit of the column's cells, converted to `to`: the file's (header or units row),
    /// else the mapping's `unit`, else its `default_unit` (then `true`: assumed). The file and
    /// the mapping must agree; no unit at all is an error.
    fn unit(&self, path: &Path, to: Unit, vendor: &str) -> Result<(Unit, bool), DataError> {
        let table = self.table;
        let spec = self.spec;
        let file_unit = self.file_unit(path, to)?;
        let asserted = spec.unit.as_deref().and_then(Unit::parse);
        if let (Some(f), Some(a)) = (file_unit, asserted) {
            if f.name != a.name {
                return Err(DataError::at(
                    path,
                    table
                        .unit_row
                        .as_ref()
                        .map_or(Some(table.header_line), |(l, _)| Some(*l)),
                    self.place(),
                    format!(
                        "the file says {} but the mapping says {}; fix the mapping's unit",
                        f.name, a.name
                    ),
                ));
            }
        }
        let default = spec.default_unit.as_deref().and_then(Unit::parse);
        match file_unit.or(asserted).or(default) {
            Some(u) => Ok((u, file_unit.is_none() && asserted.is_none())),
            None => Err(DataError::at(
                path,
                Some(table.header_line),
                self.place(),
                format!(
                    "no unit: the file states none (no unit row, no unit in the header) and the {vendor} mapping gives none; \
                     add a unit row or use a mapping file with unit = one of {}",
                    to.quantity.allowed()
                ),
            )),
        }
    }

    /// The unit the file states for the column, in its header or its units row (both must
    /// agree, and measure what `to` measures).
    fn file_unit(&self, path: &Path, to: Unit) -> Result<Option<Unit>, DataError> {
        let table = self.table;
        let from_header = table.headers[self.index].1.as_deref();
        let from_row = table
            .unit_row
            .as_ref()
            .and_then(|(_, cells)| cells.get(self.index))
            .map(String::as_str)
            .filter(|s| !s.is_empty() && *s != "[]");
        let h = from_header
            .map(|s| self.parse_file_unit(path, to, s, table.header_line, "header"))
            .transpose()?;
        let r = match (&table.unit_row, from_row) {
            (Some((line, _)), Some(s)) => {
                Some(self.parse_file_unit(path, to, s, *line, "unit row")?)
            }
            _ => None,
        };
        if let (Some(h), Some(r)) = (h, r) {
            if h.name != r.name {
                return Err(DataError::at(
                    path,
                    table.unit_row.as_ref().map(|(l, _)| *l),
                    self.place(),
                    format!(
                        "the header says {} but the unit row says {}",
                        h.name, r.name
                    ),
                ));
            }
        }
        Ok(h.or(r))
    }

    /// Read a unit the file states (`s`, on `line`, in its `what`): a unit of the quantity `to`.
    fn parse_file_unit(
        &self,
        path: &Path,
        to: Unit,
        s: &str,
        line: usize,
        what: &str,
    ) -> Result<Unit, DataError> {
        let target = &self.spec.target;
        let u = Unit::parse(s).ok_or_else(|| {
            DataError::at(
                path,
                Some(line),
                self.place(),
                format!(
                    "the {what} says '{s}', which is not a unit of {target} (allowed: {})",
                    to.quantity.allowed()
                ),
            )
        })?;
        if u.quantity != to.quantity {
            return Err(DataError::at(
                path,
                Some(line),
                self.place(),
                format!(
                    "the {what} says '{s}', but {target} needs one of: {}",
                    to.quantity.allowed()
                ),
            ));
        }
        Ok(u)
    }
}
