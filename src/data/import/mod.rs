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

pub mod units;

use std::collections::HashSet;
use std::path::Path;

use serde::Deserialize;

use self::units::{Quantity, Unit};
use super::{fmt_f64, DataError};

/// The presets: name and the mapping TOML built into the binary.
pub const PRESETS: [(&str, &str); 4] = [
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
];

/// Which way a positive heel–toe impact offset points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
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
}

/// Options given on the command line.
#[derive(Debug, Clone, Default)]
pub struct ImportOptions {
    /// Which way a positive heel–toe offset points (overrides the mapping's).
    pub impact_offset_positive: Option<OffsetSide>,
    /// Drop export columns the mapping does not know instead of refusing the file.
    pub ignore_unknown_columns: bool,
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
}

/// Resolve `--format`: a preset name or a mapping file path.
pub fn load_mapping(format: &str) -> Result<Mapping, DataError> {
    let key = format.to_ascii_lowercase();
    let key = match key.as_str() {
        "gc3" | "gcquad" | "fsx" => "foresight",
        k => k,
    };
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
            "unknown format '{format}': use shots, a preset ({}) or a mapping file NAME.toml",
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
        if let Some(d) = &c.direction {
            if !matches!(d.as_str(), "R+" | "L+") {
                return Err(err(format!(
                    "target '{}': direction must be \"R+\" or \"L+\", got '{d}'",
                    c.target
                )));
            }
        }
    }
    Ok(m)
}

/// What a mapped column feeds.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Target {
    /// A numeric shots column with its unit.
    Num(&'static str, &'static str),
    /// Heel–toe offset, sign stated by the user.
    ImpactOffset,
    /// Total spin, rpm.
    SpinRate,
    /// Spin axis tilt, deg (+ tilts right: the ball curves right).
    SpinAxis,
    /// Text columns.
    ShotId,
    Group,
    Golfer,
    Status,
}

/// Numeric shots columns an import may write, with their units, in output order.
const NUMERIC: [(&str, &str); 19] = [
    ("club_speed_mph", "mph"),
    ("attack_angle_deg", "deg"),
    ("club_path_deg", "deg"),
    ("dynamic_loft_deg", "deg"),
    ("face_angle_deg", "deg"),
    ("lie_tilt_deg", "deg"),
    ("impact_y_mm", "mm"),
    ("impact_z_mm", "mm"),
    ("ball_speed_mph", "mph"),
    ("launch_angle_deg", "deg"),
    ("azimuth_deg", "deg"),
    ("backspin_rpm", "rpm"),
    ("sidespin_rpm", "rpm"),
    ("carry_yd", "yd"),
    ("apex_yd", "yd"),
    ("total_yd", "yd"),
    ("offline_yd", "yd"),
    ("land_angle_deg", "deg"),
    ("dynamic_lie_deg", "deg"),
];

impl Target {
    fn parse(s: &str) -> Option<Target> {
        Some(match s {
            "impact_offset_mm" => Target::ImpactOffset,
            "spin_rate_rpm" => Target::SpinRate,
            "spin_axis_deg" => Target::SpinAxis,
            "shot_id" => Target::ShotId,
            "group" => Target::Group,
            "golfer" => Target::Golfer,
            "status" => Target::Status,
            _ => {
                let (c, u) = NUMERIC.iter().find(|(c, _)| *c == s)?;
                Target::Num(c, u)
            }
        })
    }

    fn names() -> Vec<&'static str> {
        let mut v: Vec<&str> = NUMERIC.iter().map(|(c, _)| *c).collect();
        v.extend([
            "impact_offset_mm",
            "spin_rate_rpm",
            "spin_axis_deg",
            "shot_id",
            "group",
            "golfer",
            "status",
        ]);
        v
    }

    /// The unit values are converted to.
    fn unit(self) -> Option<Unit> {
        let name = match self {
            Target::Num(_, u) => u,
            Target::ImpactOffset => "mm",
            Target::SpinRate => "rpm",
            Target::SpinAxis => "deg",
            _ => return None,
        };
        Unit::parse(name)
    }

    fn quantity(self) -> Option<Quantity> {
        self.unit().map(|u| u.quantity)
    }
}

/// Column names compared without case, spacing or a trailing unit in brackets.
fn normalise(name: &str) -> String {
    name.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_lowercase()
}

/// Split `Ball Speed (mph)` / `Carry[yd]` into the name and the bracketed text.
fn split_header(h: &str) -> (String, Option<String>) {
    let t = h.trim();
    for (open, close) in [('(', ')'), ('[', ']')] {
        if t.ends_with(close) {
            if let Some(i) = t.rfind(open) {
                let inner = &t[i + 1..t.len() - 1];
                if Unit::parse(inner).is_some() {
                    return (normalise(&t[..i]), Some(inner.trim().to_owned()));
                }
            }
        }
    }
    (normalise(t), None)
}

/// A resolved numeric column.
struct Resolved<'a> {
    spec: &'a ColumnSpec,
    target: Target,
    index: usize,
    header: String,
    unit: Option<Unit>,
}

/// Convert an export (`bytes`, read from `path`) with `mapping`.
pub fn import(
    path: &Path,
    bytes: &[u8],
    mapping: &Mapping,
    opts: &ImportOptions,
) -> Result<Imported, DataError> {
    let vendor = &mapping.export.name;
    let text = std::str::from_utf8(bytes)
        .map_err(|e| DataError::file(path, format!("not UTF-8 text: {e}")))?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    // Line bookkeeping: `offset_lines` lines precede the CSV body.
    let mut body = text;
    let mut offset_lines = 0usize;
    let mut delimiter = b',';
    {
        let l = body
            .split('\n')
            .next()
            .unwrap_or("")
            .trim_end_matches('\r')
            .trim();
        if let Some(sep) = l.strip_prefix("sep=") {
            let sep = sep.trim_matches('"');
            let [b] = sep.as_bytes() else {
                return Err(DataError::at(
                    path,
                    Some(1),
                    None,
                    format!("'{l}': the sep= line must name one character"),
                ));
            };
            delimiter = *b;
            body = body.split_once('\n').map_or("", |(_, r)| r);
            offset_lines += 1;
        }
    }
    for _ in 0..mapping.export.skip_lines {
        body = body.split_once('\n').map_or("", |(_, r)| r);
        offset_lines += 1;
    }
    let newlines: Vec<usize> = body
        .bytes()
        .enumerate()
        .filter(|(_, b)| *b == b'\n')
        .map(|(i, _)| i)
        .collect();
    let line_of = |p: &csv::Position| {
        newlines.partition_point(|&nl| (nl as u64) <= p.byte()) + 1 + offset_lines
    };
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .delimiter(delimiter)
        .from_reader(body.as_bytes());
    let mut rows: Vec<(usize, Vec<String>)> = Vec::new();
    for rec in rdr.records() {
        let rec =
            rec.map_err(|e| DataError::at(path, e.position().map(line_of), None, e.to_string()))?;
        let line = rec
            .position()
            .map_or(rows.len() + 1 + offset_lines, line_of);
        let cells: Vec<String> = rec.iter().map(str::to_owned).collect();
        if cells.iter().all(|c| c.is_empty()) {
            continue;
        }
        rows.push((line, cells));
    }
    let mut rows = rows.into_iter();
    let (header_line, header) = rows.next().ok_or_else(|| {
        DataError::file(
            path,
            format!("empty file: a {vendor} export has a header row"),
        )
    })?;
    let headers: Vec<(String, Option<String>)> = header.iter().map(|h| split_header(h)).collect();
    let mut rows: Vec<(usize, Vec<String>)> = rows.collect();

    // A units row: every non-empty cell is a unit or bracketed, at least one a unit.
    let mut unit_row: Option<(usize, Vec<String>)> = None;
    if let Some((line, cells)) = rows.first() {
        let non_empty: Vec<&String> = cells.iter().filter(|c| !c.is_empty()).collect();
        let is_unitish =
            |c: &str| Unit::parse(c).is_some() || (c.starts_with('[') && c.ends_with(']'));
        if !non_empty.is_empty()
            && non_empty.iter().all(|c| is_unitish(c))
            && non_empty.iter().any(|c| Unit::parse(c).is_some())
        {
            unit_row = Some((*line, cells.clone()));
            rows.remove(0);
        }
    }

    // Resolve columns.
    let find = |names: &[String]| {
        let wanted: Vec<String> = names.iter().map(|n| split_header(n).0).collect();
        headers.iter().position(|(h, _)| wanted.contains(h))
    };
    let mut used = vec![false; headers.len()];
    let mut resolved: Vec<Resolved> = Vec::new();
    let mut missing: Vec<String> = Vec::new();
    let mut notes: Vec<String> = Vec::new();
    let mut assumed: Vec<String> = Vec::new();
    for spec in &mapping.column {
        let target = Target::parse(&spec.target).expect("checked when parsed");
        let Some(index) = find(&spec.source) else {
            if !spec.optional {
                missing.push(format!("'{}' ({})", spec.source[0], spec.target));
            }
            continue;
        };
        if used[index] {
            return Err(DataError::at(
                path,
                Some(header_line),
                Some(format!("column '{}'", header[index])),
                "this column is mapped to two targets",
            ));
        }
        used[index] = true;
        let place = || Some(format!("column '{}'", header[index]));
        let unit = match target.unit() {
            None => None,
            Some(to) => {
                let from_header = headers[index].1.as_deref();
                let from_row = unit_row
                    .as_ref()
                    .and_then(|(_, cells)| cells.get(index))
                    .map(String::as_str)
                    .filter(|s| !s.is_empty() && *s != "[]");
                let parse_file_unit = |s: &str, line: usize, what: &str| {
                    let u = Unit::parse(s).ok_or_else(|| {
                        DataError::at(
                            path,
                            Some(line),
                            place(),
                            format!(
                                "the {what} says '{s}', which is not a unit of {} (allowed: {})",
                                spec.target,
                                to.quantity.allowed()
                            ),
                        )
                    })?;
                    if u.quantity != to.quantity {
                        return Err(DataError::at(
                            path,
                            Some(line),
                            place(),
                            format!(
                                "the {what} says '{s}', but {} needs one of: {}",
                                spec.target,
                                to.quantity.allowed()
                            ),
                        ));
                    }
                    Ok(u)
                };
                let h = from_header
                    .map(|s| parse_file_unit(s, header_line, "header"))
                    .transpose()?;
                let r = match (&unit_row, from_row) {
                    (Some((line, _)), Some(s)) => Some(parse_file_unit(s, *line, "unit row")?),
                    _ => None,
                };
                if let (Some(h), Some(r)) = (h, r) {
                    if h.name != r.name {
                        return Err(DataError::at(
                            path,
                            unit_row.as_ref().map(|(l, _)| *l),
                            place(),
                            format!(
                                "the header says {} but the unit row says {}",
                                h.name, r.name
                            ),
                        ));
                    }
                }
                let file_unit = h.or(r);
                let asserted = spec.unit.as_deref().and_then(Unit::parse);
                if let (Some(f), Some(a)) = (file_unit, asserted) {
                    if f.name != a.name {
                        return Err(DataError::at(
                            path,
                            unit_row
                                .as_ref()
                                .map_or(Some(header_line), |(l, _)| Some(*l)),
                            place(),
                            format!(
                                "the file says {} but the mapping says {}; fix the mapping's unit",
                                f.name, a.name
                            ),
                        ));
                    }
                }
                let default = spec.default_unit.as_deref().and_then(Unit::parse);
                let unit = file_unit.or(asserted).or(default);
                match unit {
                    Some(u) => {
                        if file_unit.is_none() && asserted.is_none() {
                            assumed.push(format!("{} in {}", header[index], u.name));
                        }
                        Some(u)
                    }
                    None => {
                        return Err(DataError::at(
                            path,
                            Some(header_line),
                            place(),
                            format!(
                                "no unit: the file states none (no unit row, no unit in the header) and the {vendor} mapping gives none; \
                                 add a unit row or use a mapping file with unit = one of {}",
                                to.quantity.allowed()
                            ),
                        ))
                    }
                }
            }
        };
        resolved.push(Resolved {
            spec,
            target,
            index,
            header: header[index].clone(),
            unit,
        });
    }
    if !missing.is_empty() {
        let present: Vec<&str> = header
            .iter()
            .filter(|h| !h.is_empty())
            .map(String::as_str)
            .collect();
        return Err(DataError::at(
            path,
            Some(header_line),
            None,
            format!(
                "not a {vendor} export as expected: missing column(s) {}; the file has: {}",
                missing.join(", "),
                present.join(", ")
            ),
        ));
    }
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
    let unknown: Vec<&str> = header
        .iter()
        .enumerate()
        .filter(|(i, h)| !h.is_empty() && !used[*i] && !ignored.contains(&headers[*i].0))
        .map(|(_, h)| h.as_str())
        .collect();
    if !unknown.is_empty() && !opts.ignore_unknown_columns {
        return Err(DataError::at(
            path,
            Some(header_line),
            None,
            format!(
                "unknown column(s) for the {vendor} format: '{}'; map or ignore them in a mapping file (--format FILE.toml), \
                 or pass --ignore-unknown-columns",
                unknown.join("', '")
            ),
        ));
    }
    if !unknown.is_empty() {
        notes.push(format!("ignored unknown column(s): {}", unknown.join(", ")));
    }
    if !assumed.is_empty() {
        notes.push(format!(
            "the file states no unit for {}: the {vendor} preset's units were assumed",
            assumed.join(", ")
        ));
    }

    let has = |name: &str| resolved.iter().any(|r| r.spec.target == name);
    let offset_side = opts
        .impact_offset_positive
        .or(mapping.export.impact_offset_positive);
    if has("impact_offset_mm") && offset_side.is_none() {
        let r = resolved
            .iter()
            .find(|r| r.spec.target == "impact_offset_mm")
            .expect("has");
        return Err(DataError::at(
            path,
            Some(header_line),
            Some(format!("column '{}'", r.header)),
            format!(
                "{vendor} does not document which way a positive heel–toe impact offset points; \
                 state it with --impact-offset-positive toe|heel (the import does not guess)"
            ),
        ));
    }
    if has("impact_offset_mm") && has("impact_z_mm") {
        return Err(DataError::file(
            path,
            "both impact_offset_mm and impact_z_mm are mapped; map one",
        ));
    }
    for need in [
        "club_speed_mph",
        "attack_angle_deg",
        "club_path_deg",
        "dynamic_loft_deg",
        "face_angle_deg",
        "impact_y_mm",
    ] {
        if !has(need) {
            return Err(DataError::file(
                path,
                format!("the mapping does not feed the required shots column {need}"),
            ));
        }
    }
    if !has("impact_offset_mm") && !has("impact_z_mm") {
        return Err(DataError::file(
            path,
            "the mapping feeds neither impact_z_mm nor impact_offset_mm (the heel–toe impact location)",
        ));
    }
    let spin_pair = has("backspin_rpm") && has("sidespin_rpm");
    let rate_axis = has("spin_rate_rpm") && has("spin_axis_deg");
    let launch_any = ["ball_speed_mph", "launch_angle_deg", "azimuth_deg"]
        .iter()
        .any(|c| has(c))
        || has("backspin_rpm")
        || has("sidespin_rpm")
        || has("spin_rate_rpm")
        || has("spin_axis_deg");
    let launch_all = ["ball_speed_mph", "launch_angle_deg", "azimuth_deg"]
        .iter()
        .all(|c| has(c))
        && (spin_pair || rate_axis);
    if launch_any && !launch_all {
        return Err(DataError::at(
            path,
            Some(header_line),
            None,
            "measured launch is incomplete: ball speed, launch angle, launch direction and either back and side spin \
             or spin rate and spin axis are all needed (or none of them)",
        ));
    }
    let use_rate_axis = launch_all && !spin_pair;

    // Output columns.
    let text_col = |name: &str| resolved.iter().find(|r| r.spec.target == name);
    let id_col = text_col("shot_id");
    let group_col = text_col("group");
    let golfer_col = text_col("golfer");
    let status_col = text_col("status");
    let mut out_numeric: Vec<&str> = NUMERIC
        .iter()
        .map(|(c, _)| *c)
        .filter(|c| {
            has(c)
                || (*c == "impact_z_mm" && has("impact_offset_mm"))
                || (use_rate_axis && (*c == "backspin_rpm" || *c == "sidespin_rpm"))
        })
        .collect();
    if !launch_all {
        out_numeric.retain(|c| {
            !matches!(
                *c,
                "ball_speed_mph"
                    | "launch_angle_deg"
                    | "azimuth_deg"
                    | "backspin_rpm"
                    | "sidespin_rpm"
            )
        });
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut head: Vec<&str> = vec!["shot_id"];
    if group_col.is_some() {
        head.push("group");
    }
    if golfer_col.is_some() {
        head.push("golfer");
    }
    head.extend(&out_numeric);
    w.write_record(&head).expect("writing to memory");

    let mut skipped_by_rule: Vec<(String, Vec<usize>)> = Vec::new();
    let mut flagged: Vec<(usize, String)> = Vec::new();
    let mut ids = HashSet::new();
    let mut n_shots = 0usize;
    'rows: for (line, cells) in &rows {
        let cell = |i: usize| cells.get(i).map_or("", String::as_str);
        for rule in &mapping.export.skip_rows {
            let hit = |c: &str| rule.values.iter().any(|v| v.eq_ignore_ascii_case(c.trim()));
            let matched = match &rule.column {
                Some(col) => {
                    let want = split_header(col).0;
                    headers
                        .iter()
                        .position(|(h, _)| *h == want)
                        .is_some_and(|i| hit(cell(i)))
                }
                None => cells.iter().any(|c| hit(c)),
            };
            if matched {
                let label = rule.label.clone().unwrap_or_else(|| "summary".into());
                match skipped_by_rule.iter_mut().find(|(l, _)| *l == label) {
                    Some((_, v)) => v.push(*line),
                    None => skipped_by_rule.push((label, vec![*line])),
                }
                continue 'rows;
            }
        }
        if let Some(st) = status_col {
            let v = cell(st.index).trim();
            let ok = if st.spec.ok.is_empty() {
                v.is_empty()
            } else {
                st.spec.ok.iter().any(|o| o.eq_ignore_ascii_case(v))
            };
            if !ok {
                flagged.push((*line, format!("{} = '{v}'", st.header)));
                continue;
            }
        }
        let mut values: Vec<(&str, Option<f64>)> = Vec::new();
        for r in &resolved {
            let Some(to) = r.target.unit() else { continue };
            let raw = cell(r.index);
            let here = |m: String| {
                DataError::at(path, Some(*line), Some(format!("column '{}'", r.header)), m)
            };
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
                return Err(here(format!("'{raw}' is not a finite number")));
            }
            values.push((r.spec.target.as_str(), Some(v)));
        }
        let get = |name: &str| {
            values
                .iter()
                .find(|(n, _)| *n == name)
                .and_then(|(_, v)| *v)
        };
        let id = match id_col {
            Some(c) => cell(c.index).trim().to_owned(),
            None => format!("row{line}"),
        };
        if id.is_empty() {
            return Err(DataError::at(
                path,
                Some(*line),
                id_col.map(|c| format!("column '{}'", c.header)),
                "empty shot id",
            ));
        }
        if !ids.insert(id.clone()) {
            return Err(DataError::at(
                path,
                Some(*line),
                id_col.map(|c| format!("column '{}'", c.header)),
                format!("shot id '{id}' is used twice; ids must be unique (drop the shot_id mapping to number rows instead)"),
            ));
        }
        let mut rec: Vec<String> = vec![id];
        for col in [group_col, golfer_col].into_iter().flatten() {
            let v = cell(col.index).trim();
            if v.is_empty() && col.spec.target == "group" {
                return Err(DataError::at(
                    path,
                    Some(*line),
                    Some(format!("column '{}'", col.header)),
                    "empty group (club) name",
                ));
            }
            rec.push(v.to_owned());
        }
        let (back, side) = if use_rate_axis {
            let rate = get("spin_rate_rpm").expect("core");
            let axis = get("spin_axis_deg").expect("core").to_radians();
            (Some(rate * axis.cos()), Some(rate * axis.sin()))
        } else {
            (get("backspin_rpm"), get("sidespin_rpm"))
        };
        for c in &out_numeric {
            let v = match *c {
                "impact_z_mm" if has("impact_offset_mm") => {
                    get("impact_offset_mm").map(|o| match offset_side.expect("checked above") {
                        OffsetSide::Toe => o,
                        OffsetSide::Heel => -o,
                    })
                }
                "backspin_rpm" => back,
                "sidespin_rpm" => side,
                c => get(c),
            };
            rec.push(v.map(fmt_f64).unwrap_or_default());
        }
        w.write_record(&rec).expect("writing to memory");
        n_shots += 1;
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
    if n_shots == 0 {
        return Err(DataError::file(
            path,
            format!("no shots: the {vendor} export has no usable rows"),
        ));
    }
    Ok(Imported {
        csv: w.into_inner().expect("flushing memory"),
        shots: n_shots,
        notes,
    })
}

/// Columns an empty cell may not leave empty even when the column itself may be absent.
fn is_core(target: &str) -> bool {
    !matches!(
        target,
        "carry_yd" | "apex_yd" | "total_yd" | "offline_yd" | "land_angle_deg" | "dynamic_lie_deg"
    )
}

fn list_lines(lines: &[usize]) -> String {
    let shown: Vec<String> = lines.iter().take(10).map(usize::to_string).collect();
    if lines.len() > 10 {
        format!("{}, …", shown.join(", "))
    } else {
        shown.join(", ")
    }
}

/// Parse one cell: a number, optionally with an L/R letter before or after it (when the column
/// takes directions) or the column's own unit after it. Returns the value in the column's unit.
fn parse_cell(raw: &str, unit: Unit, direction: Option<&str>) -> Result<f64, String> {
    let s = raw.trim();
    let mut letter: Option<char> = None;
    let mut rest = s;
    if let Some(c) = s.chars().next() {
        if matches!(c, 'L' | 'R' | 'l' | 'r')
            && s[1..]
                .trim_start()
                .starts_with(|d: char| d.is_ascii_digit() || d == '.')
        {
            letter = Some(c.to_ascii_uppercase());
            rest = s[1..].trim_start();
        }
    }
    // The numeric prefix.
    let bytes = rest.as_bytes();
    let mut end = 0;
    while end < bytes.len() {
        let b = bytes[end];
        let ok = b.is_ascii_digit()
            || b == b'.'
            || ((b == b'-' || b == b'+') && (end == 0 || matches!(bytes[end - 1], b'e' | b'E')))
            || ((b == b'e' || b == b'E')
                && end > 0
                && bytes
                    .get(end + 1)
                    .is_some_and(|n| n.is_ascii_digit() || *n == b'-' || *n == b'+'));
        if !ok {
            break;
        }
        end += 1;
    }
    let number = &rest[..end];
    let v: f64 = number
        .parse()
        .map_err(|_| format!("'{raw}' is not a number"))?;
    let tail = rest[end..].trim();
    if !tail.is_empty() {
        if letter.is_none() && matches!(tail, "L" | "R" | "l" | "r") {
            letter = Some(tail.chars().next().expect("one").to_ascii_uppercase());
        } else {
            match Unit::parse(tail) {
                Some(u) if u.name == unit.name => {}
                Some(u) => {
                    return Err(format!(
                        "mixed units: '{raw}' is in {} but the column is in {}",
                        u.name, unit.name
                    ))
                }
                None => return Err(format!("'{raw}' is not a number")),
            }
        }
    }
    match (letter, direction) {
        (None, _) => Ok(v),
        (Some(_), None) => Err(format!("'{raw}': this column does not take L/R directions")),
        (Some(_), Some(_)) if number.starts_with(['-', '+']) => {
            Err(format!("'{raw}': both a sign and an L/R letter; write one"))
        }
        (Some(l), Some(d)) => {
            let positive = if d == "R+" { 'R' } else { 'L' };
            Ok(if l == positive { v } else { -v })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deg() -> Unit {
        Unit::parse("deg").unwrap()
    }

    #[test]
    fn directions_and_units_in_cells() {
        assert_eq!(parse_cell("5.4 L", deg(), Some("R+")), Ok(-5.4));
        assert_eq!(parse_cell("5.4R", deg(), Some("R+")), Ok(5.4));
        assert_eq!(parse_cell("L5.4", deg(), Some("R+")), Ok(-5.4));
        assert_eq!(parse_cell("R 5.4", deg(), Some("L+")), Ok(-5.4));
        assert_eq!(parse_cell("-2.5", deg(), Some("R+")), Ok(-2.5));
        assert_eq!(parse_cell("1e-3", deg(), None), Ok(1e-3));
        assert!(parse_cell("-5.4 L", deg(), Some("R+")).is_err());
        assert!(parse_cell("5.4 L", deg(), None).is_err());
        let mph = Unit::parse("mph").unwrap();
        assert_eq!(parse_cell("152.5 mph", mph, None), Ok(152.5));
        let e = parse_cell("245 km/h", mph, None).unwrap_err();
        assert!(e.contains("mixed units"), "{e}");
        assert!(parse_cell("fast", mph, None).is_err());
    }

    #[test]
    fn headers_split_units() {
        assert_eq!(
            split_header("Ball Speed (mph)"),
            ("ball speed".into(), Some("mph".into()))
        );
        assert_eq!(
            split_header("Carry[yd]"),
            ("carry".into(), Some("yd".into()))
        );
        assert_eq!(split_header("Dyn.  Loft"), ("dyn. loft".into(), None));
        assert_eq!(split_header("Club (name)"), ("club (name)".into(), None));
    }

    #[test]
    fn presets_parse() {
        for (name, _) in PRESETS {
            load_mapping(name).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        assert!(load_mapping("gcquad").is_ok());
        let e = load_mapping("nosuch").unwrap_err().to_string();
        assert!(e.contains("unknown format"), "{e}");
    }
}
