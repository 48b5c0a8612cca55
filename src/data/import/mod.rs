//! Launch-monitor exports to shots files.
//!
//! A [`Mapping`] says which export column feeds which shots column, in which unit, with which
//! sign and left/right convention, and which rows to skip. The presets (`trackman`, `foresight`,
//! `flightscope`, `uneekor`) are mappings kept as TOML under `configs/import/` and built into
//! the binary; a user's own mapping file has the same form (docs/import.md).
//!
//! What the import handles: a UTF-8 byte-order mark, a leading `sep=;` line (Excel's delimiter
//! hint), units in the header (`Ball Speed (mph)`) or in a units row under it (`[mph]`), unit
//! suffixes in cells (`152 mph`; a different unit in one cell is an error, never converted
//! silently), directions written `5.4 L` / `R5.4`, spin given as rate and axis, rows of averages,
//! and rows a monitor flags as estimated (skipped and reported). The heel–toe sign of the impact
//! location is stated by the user when the vendor does not document it: the import never guesses.

mod carry_units;
mod cell;
mod checks;
mod columns;
mod condition;
mod conventions;
mod detect;
mod json;
mod layout;
mod legend;
mod missing;
mod rows;
mod summary;
mod table;
mod target;
mod text;
pub mod units;

use std::collections::HashSet;
use std::path::Path;

use serde::Deserialize;

use self::cell::split_header;
use self::columns::resolve_columns;
pub use self::detect::{detect, Detected};
use self::layout::Layout;
use self::rows::write_shots;
use self::table::read_table;
use self::target::Target;
use self::units::Unit;
use super::shots::{parse_shots_with, ReadOptions, ShotTable};
use super::DataError;

/// The presets: name and the mapping TOML built into the binary.
pub const PRESETS: [(&str, &str); 14] = [
    (
        "trackman",
        include_str!("../../../configs/import/trackman.toml"),
    ),
    (
        "foresight",
        include_str!("../../../configs/import/foresight.toml"),
    ),
    (
        "flightscope",
        include_str!("../../../configs/import/flightscope.toml"),
    ),
    (
        "uneekor",
        include_str!("../../../configs/import/uneekor.toml"),
    ),
    (
        "garmin-r10",
        include_str!("../../../configs/import/garmin-r10.toml"),
    ),
    (
        "rapsodo",
        include_str!("../../../configs/import/rapsodo.toml"),
    ),
    (
        "skytrak",
        include_str!("../../../configs/import/skytrak.toml"),
    ),
    ("gspro", include_str!("../../../configs/import/gspro.toml")),
    (
        "foresight-session",
        include_str!("../../../configs/import/foresight-session.toml"),
    ),
    (
        "trackman-report",
        include_str!("../../../configs/import/trackman-report.toml"),
    ),
    (
        "openflight",
        include_str!("../../../configs/import/openflight.toml"),
    ),
    (
        "flightscope-scrape",
        include_str!("../../../configs/import/flightscope-scrape.toml"),
    ),
    (
        "awesome-golf",
        include_str!("../../../configs/import/awesome-golf.toml"),
    ),
    (
        "square-golf",
        include_str!("../../../configs/import/square-golf.toml"),
    ),
];

/// Other names of the presets: `(alias, preset)`.
pub const PRESET_ALIASES: [(&str, &str); 8] = [
    ("gc3", "foresight"),
    ("gcquad", "foresight"),
    ("fsx", "foresight"),
    ("mevo", "flightscope"),
    ("garmin", "garmin-r10"),
    ("r10", "garmin-r10"),
    ("mlm2pro", "rapsodo"),
    ("fsx-session", "foresight-session"),
];

/// Presets whose vendor also writes JSON, and the preset that reads that JSON: `--format fsx`
/// given a `.session` file reads it as one.
pub const JSON_SIBLINGS: [(&str, &str); 2] = [
    ("foresight", "foresight-session"),
    ("trackman", "trackman-report"),
];

/// The preset `format` names (an alias resolved), or `format` itself; for a JSON export, the
/// JSON sibling of the preset when it has one.
pub fn preset_for(format: &str, bytes: &[u8]) -> String {
    let key = format.to_ascii_lowercase();
    let key = PRESET_ALIASES
        .iter()
        .find(|(a, _)| *a == key)
        .map_or(key.as_str(), |(_, p)| *p)
        .to_owned();
    let json = std::str::from_utf8(bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes))
        .is_ok_and(json::is_json);
    match JSON_SIBLINGS.iter().find(|(p, _)| *p == key) {
        Some((_, sibling)) if json => (*sibling).to_owned(),
        _ if PRESETS.iter().any(|(n, _)| *n == key) => key,
        _ => format.to_owned(),
    }
}

/// Which way a positive heel–toe impact offset points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum OffsetSide {
    /// Positive offsets are toward the toe (the shots file's `impact_z_mm` sign).
    Toe,
    /// Positive offsets are toward the heel.
    Heel,
}

/// A mapping file: the export's layout and its columns.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mapping {
    /// The export as a whole.
    pub export: ExportSpec,
    /// One entry per shots column fed by the export.
    #[serde(default)]
    pub column: Vec<ColumnSpec>,
}

/// Layout of an export.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExportSpec {
    /// Name used in messages.
    pub name: String,
    /// Where the column names and units come from (informational).
    #[serde(default)]
    pub source: Option<String>,
    /// Lines to drop before the header (after any BOM and `sep=` line).
    #[serde(default)]
    pub skip_lines: usize,
    /// Rows to skip (averages, deviations): a row is skipped when the named column (or any cell,
    /// when no column is named) equals one of the values, ignoring case.
    #[serde(default)]
    pub skip_rows: Vec<SkipRule>,
    /// Export columns known and not used.
    #[serde(default)]
    pub ignore: Vec<String>,
    /// The sign of the heel–toe impact offset, when the export documents it.
    #[serde(default)]
    pub impact_offset_positive: Option<OffsetSide>,
    /// What to do with an export column the mapping neither maps nor ignores: `refuse` (the
    /// default for a user's mapping: a renamed column is not lost unseen) or `note` (the vendor
    /// presets: an export's many other columns are listed once in the import's summary).
    #[serde(default)]
    pub unknown_columns: UnknownColumns,
    /// Cell values that mean "not measured" in every column (Foresight writes 16777215,
    /// 2²⁴ − 1); compared as numbers. Empty cells, `-`, `--` and `N/A` always mean it.
    #[serde(default)]
    pub missing: Vec<String>,
    /// Every carry, side, apex and landing in the export is the vendor's flight model of the
    /// measured launch, not a tracked flight (camera and short-range radar monitors): each
    /// shot is written with `flight_modelled = 1`.
    #[serde(default)]
    pub flight_modelled: bool,
    /// Rows whose only text is in the first cell name (the club of) the rows under them
    /// (SkyTrak): they are read as a column of this name, which a mapping can take.
    #[serde(default)]
    pub section_rows: Option<String>,
}

/// [`ExportSpec::unknown_columns`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum UnknownColumns {
    /// Refuse the file, naming the columns.
    #[default]
    Refuse,
    /// List them once in the import's notes.
    Note,
}

/// Rows to skip.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SkipRule {
    /// Export column to look at; every cell when absent.
    #[serde(default)]
    pub column: Option<String>,
    /// Cell values that mark a row to skip.
    pub values: Vec<String>,
    /// What such rows are, for the report (e.g. `average`).
    #[serde(default)]
    pub label: Option<String>,
}

/// One shots column fed by the export.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ColumnSpec {
    /// The shots column (or `spin_rate_rpm`, `spin_axis_deg`, `impact_offset_mm`, `status`).
    pub target: String,
    /// Accepted export column names (case and spacing ignored; a unit in brackets is read).
    pub source: Vec<String>,
    /// The unit the mapping asserts: a file stating another unit is an error.
    #[serde(default)]
    pub unit: Option<String>,
    /// The unit assumed when the file states none (reported on stderr).
    #[serde(default)]
    pub default_unit: Option<String>,
    /// Multiply by −1 (`sign = -1`) when the vendor's positive direction is the other way.
    #[serde(default)]
    pub sign: Option<i8>,
    /// `R+` or `L+`: cells may carry an L/R letter and this letter means positive.
    #[serde(default)]
    pub direction: Option<String>,
    /// The column may be absent.
    #[serde(default)]
    pub optional: bool,
    /// For `status`: cell values that mean the shot is measured normally (default: empty cell).
    #[serde(default)]
    pub ok: Vec<String>,
    /// For `spin_estimated` and `club_estimated`: cell values that mean the monitor estimated
    /// the values instead of measuring them (case ignored; any other value means measured).
    #[serde(default)]
    pub estimated: Vec<String>,
    /// For `spin_estimated` and `club_estimated`: when given, the only cell values that mean
    /// measured; any other non-empty value (`Est.`, `N/A`, a reading the mapping does not know)
    /// is read as estimated, not trusted as a measurement.
    #[serde(default)]
    pub measured: Vec<String>,
    /// Cell values that mean "not measured" in this column, compared as numbers (GSPro writes
    /// 0 for a dynamic loft or impact location its monitor does not measure).
    #[serde(default)]
    pub missing: Vec<String>,
    /// The value (in the shots file's unit) used when a cell is not measured, each use counted
    /// in the summary: for a monitor that does not measure a launch component on most shots
    /// (OpenFlight's launch direction), so that its shots can still be flown.
    #[serde(default)]
    pub assume: Option<f64>,
    /// For the delivery's angles and velocity: where the vendor defines the value. Dynamic
    /// loft and face angle: `contact_point` or `face_centre`; club speed, attack angle and
    /// path: `com`, `geometric_centre` or `face_centre` ([`crate::conventions`]). Absent:
    /// the model's own (face centre, CoM).
    #[serde(default)]
    pub at: Option<String>,
    /// For a delivery column: `measured`, or (face angle only) `derived_from_launch` when the
    /// monitor computes it from the launch direction and path. Absent: measured.
    #[serde(default)]
    pub how: Option<String>,
}

/// Options given on the command line.
#[derive(Debug, Clone, Default)]
pub struct ImportOptions {
    /// Which way a positive heel–toe offset points (overrides the mapping's).
    pub impact_offset_positive: Option<OffsetSide>,
    /// Drop export columns the mapping does not know instead of refusing the file.
    pub ignore_unknown_columns: bool,
    /// Refuse the whole file at the first bad or incomplete row (the default leaves such rows
    /// out, or keeps a shot without its impact location, and counts them in the notes).
    pub strict: bool,
}

/// A converted export.
#[derive(Debug, Clone)]
pub struct Imported {
    /// The shots file, CSV bytes.
    pub csv: Vec<u8>,
    /// Shots written.
    pub shots: usize,
    /// What was skipped and assumed, one line each.
    pub notes: Vec<String>,
    /// Shots written with a complete delivery (0 for a launch-only file, for flight).
    pub complete_delivery: usize,
    /// The export's file line of the header and of each shot written, in order.
    header_line: usize,
    lines: Vec<usize>,
    /// Each shots column fed by the export, with where in the export it came from
    /// (`column 'Club Speed'`), for messages.
    places: Vec<(&'static str, String)>,
}

impl Imported {
    /// Read the converted shots back as a shots table (ranges, ids, launch columns), every
    /// error placed at the export's own file line and column (`path` is the export).
    pub fn read_back(&self, path: &Path) -> Result<ShotTable, DataError> {
        self.read_back_with(path, ReadOptions::default())
    }

    /// The check every conversion ends with, as `smash import` makes it: the shots with a
    /// complete delivery must read back as a shots file (ranges, ids, launch columns), estimated
    /// values included; `None` for a launch-only export (for flight), which has nothing to read.
    pub fn checked_read_back(
        &self,
        path: &Path,
        strict: bool,
    ) -> Result<Option<ShotTable>, DataError> {
        if self.complete_delivery == 0 {
            return Ok(None);
        }
        let opts = ReadOptions {
            strict,
            include_estimated: true,
        };
        self.read_back_with(path, opts).map(Some)
    }

    /// [`Imported::read_back`] with the shots reader's options; the lines of rows left out
    /// are the export's own.
    pub fn read_back_with(&self, path: &Path, opts: ReadOptions) -> Result<ShotTable, DataError> {
        let mut table =
            parse_shots_with(path, self.csv.as_slice(), opts).map_err(|e| self.in_export(e))?;
        let export_line = |l: usize| self.lines.get(l.wrapping_sub(2)).copied().unwrap_or(l);
        for line in table.lines.iter_mut() {
            *line = export_line(*line);
        }
        for l in table.left_out.iter_mut() {
            for line in l.lines.iter_mut() {
                *line = export_line(*line);
            }
            l.first = l.first.take().map(|e| self.in_export(e));
        }
        Ok(table)
    }

    /// `e`, about the converted CSV, moved to the export's line and column names.
    fn in_export(&self, mut e: DataError) -> DataError {
        e.line = e.line.map(|l| match l {
            0 | 1 => self.header_line,
            l => self.lines.get(l - 2).copied().unwrap_or(l),
        });
        if let Some(place) = &e.place {
            if let Some((_, to)) = self
                .places
                .iter()
                .find(|(c, _)| *place == format!("column '{c}'"))
            {
                e.place = Some(to.clone());
            }
        }
        e
    }
}

/// Resolve `--format`: a preset name or a mapping file path.
pub fn load_mapping(format: &str) -> Result<Mapping, DataError> {
    let key = format.to_ascii_lowercase();
    let key = PRESET_ALIASES
        .iter()
        .find(|(a, _)| *a == key)
        .map_or(key.as_str(), |(_, p)| *p);
    if let Some((_, text)) = PRESETS.iter().find(|(n, _)| *n == key) {
        return parse_mapping(Path::new(&format!("<preset {key}>")), text);
    }
    let path = Path::new(format);
    if path.extension().is_some_and(|e| e == "toml") {
        let text = super::read_text(path)?;
        return parse_mapping(path, &text);
    }
    let names: Vec<&str> = PRESETS.iter().map(|(n, _)| *n).collect();
    Err(DataError::file(
        path,
        format!(
            "unknown format '{format}': use shots, auto, a preset ({}) or a mapping file NAME.toml",
            names.join(", ")
        ),
    ))
}

/// Parse and check a mapping.
pub fn parse_mapping(path: &Path, text: &str) -> Result<Mapping, DataError> {
    let m: Mapping = super::parse_toml(
        path,
        text,
        "a mapping has [export] and [[column]] tables; see docs/import.md",
    )?;
    let err = |msg: String| DataError::file(path, msg);
    let mut seen = HashSet::new();
    for c in &m.column {
        let target = Target::parse(&c.target).ok_or_else(|| {
            err(format!(
                "column target '{}' is not known (allowed: {})",
                c.target,
                Target::names().join(", ")
            ))
        })?;
        if !seen.insert(c.target.clone()) {
            return Err(err(format!("target '{}' is mapped twice", c.target)));
        }
        if c.source.is_empty() {
            return Err(err(format!("target '{}' has no source column", c.target)));
        }
        for u in [&c.unit, &c.default_unit].into_iter().flatten() {
            let unit = Unit::parse(u)
                .ok_or_else(|| err(format!("target '{}': '{u}' is not a unit", c.target)))?;
            match target.quantity() {
                Some(q) if q == unit.quantity => {}
                Some(q) => {
                    return Err(err(format!(
                        "target '{}': unit '{u}' does not measure what it holds (allowed: {})",
                        c.target,
                        q.allowed()
                    )))
                }
                None => {
                    return Err(err(format!(
                        "target '{}' is text and takes no unit",
                        c.target
                    )))
                }
            }
        }
        if let Some(s) = c.sign {
            if s != 1 && s != -1 {
                return Err(err(format!(
                    "target '{}': sign must be 1 or -1, got {s}",
                    c.target
                )));
            }
        }
        conventions::check_column(c).map_err(|e| err(e.to_string()))?;
        if let Some(d) = &c.direction {
            if cell::direction_words(d).is_none() {
                return Err(err(format!(
                    "target '{}': direction must be one of {}, got '{d}'",
                    c.target,
                    cell::DIRECTIONS.join(", ")
                )));
            }
        }
    }
    conventions::check_mapping(&m).map_err(|e| err(e.to_string()))?;
    Ok(m)
}

/// Convert an export (`bytes`, read from `path`) with `mapping`: read its rows, find the mapped
/// columns and their units, check that they feed a shots file, and write the shots.
pub fn import(
    path: &Path,
    bytes: &[u8],
    mapping: &Mapping,
    opts: &ImportOptions,
) -> Result<Imported, DataError> {
    let vendor = &mapping.export.name;
    let names: HashSet<String> = mapping
        .column
        .iter()
        .flat_map(|c| c.source.iter())
        .chain(&mapping.export.ignore)
        .map(|n| split_header(n).0)
        .collect();
    let known = |name: &str| names.contains(name);
    let mut table = read_table(path, bytes, mapping.export.skip_lines, vendor, &known)?;
    if let Some(name) = &mapping.export.section_rows {
        let found = table.sections_as_column(name);
        if found > 0 {
            table.notes.push(format!(
                "{found} row(s) with text in the first cell only read as the '{name}' of the \
                 rows under them"
            ));
        }
    }
    let (resolved, column_notes) = resolve_columns(path, &table, mapping, opts)?;
    let mut notes = table.notes.clone();
    notes.extend(column_notes);
    let layout = Layout::plan(path, &table, &resolved, mapping, opts)?;
    let shots = write_shots(
        path,
        &table,
        &mapping.export,
        &layout,
        opts.strict,
        &mut notes,
    )?;
    let places = export_places(&layout);
    Ok(Imported {
        csv: shots.csv,
        shots: shots.count,
        notes,
        complete_delivery: shots.complete,
        header_line: table.header_line,
        lines: shots.lines,
        places,
    })
}

/// Each shots column `layout` writes from the export, with the export column(s) it comes from.
fn export_places(layout: &Layout) -> Vec<(&'static str, String)> {
    let header = |target: &str| {
        layout
            .resolved
            .iter()
            .find(|r| r.spec.target == target)
            .map(|r| r.header.as_str())
    };
    let mut places = Vec::new();
    for &c in &layout.numeric {
        let place = match c {
            "backspin_rpm" | "sidespin_rpm" if layout.use_rate_axis => header("spin_rate_rpm")
                .zip(header("spin_axis_deg"))
                .map(|(r, a)| format!("columns '{r}' and '{a}' (the {c} they give)")),
            "sidespin_rpm" if layout.use_back_axis => header("backspin_rpm")
                .zip(header("spin_axis_deg"))
                .map(|(r, a)| format!("columns '{r}' and '{a}' (the {c} they give)")),
            "impact_z_mm" if layout.from_offset => {
                header("impact_offset_mm").map(|h| format!("column '{h}'"))
            }
            c => header(c).map(|h| format!("column '{h}'")),
        };
        if let Some(p) = place {
            places.push((c, p));
        }
    }
    for (c, col) in [
        ("group", layout.group),
        ("golfer", layout.golfer),
        ("shot_id", layout.id),
    ] {
        if let Some(r) = col {
            places.push((c, format!("column '{}'", r.header)));
        }
    }
    places
}

#[cfg(test)]
mod tests;
