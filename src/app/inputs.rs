//! What the commands that read shots share: where the shots come from ([`ShotsInput`]: a file,
//! or CSV text from memory), how they are read ([`ShotsFormat`]: a shots file, or a
//! launch-monitor export converted on the fly exactly as `smash import` would), the check
//! that they are the club's, their conversion to the model's delivery convention, and the
//! impact-location noise setting.

use std::io::Read as _;
use std::path::{Path, PathBuf};

use anyhow::bail;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::Notes;
use crate::club::ClubSpec;
use crate::data::import::{Imported, OffsetSide};
use crate::data::shots::{ReadOptions, ShotTable};
use crate::measurement::ImpactNoise;
use crate::model::Shot;

/// How a shots input is read: a shots file (the default) or a launch-monitor export.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ShotsFormat {
    /// `shots` (or unset: a shots file), `auto` (the layout recognised from the header or the
    /// JSON keys), a launch-monitor preset (`trackman`, `flightscope`, …) or a mapping file
    /// `NAME.toml` (`docs/import.md`).
    pub format: Option<String>,
    /// Which way a positive heel–toe impact offset points in the export, where the vendor does
    /// not say.
    pub impact_offset_positive: Option<OffsetSide>,
    /// Drop export columns the format does not know instead of refusing the file.
    pub ignore_unknown_columns: bool,
    /// Refuse the whole file at the first bad or incomplete row (by default such rows are left
    /// out and counted).
    pub strict: bool,
    /// Use shots whose spin or club data the monitor estimated.
    pub include_estimated: bool,
    /// The project file `format` came from, when it did (named in the hint that a shots file
    /// needs `--format shots`).
    #[serde(skip)]
    pub format_from: Option<PathBuf>,
}

/// Where a shots table comes from.
#[derive(Debug, Clone)]
pub enum ShotsInput {
    /// A file, read as its format says.
    File(PathBuf),
    /// A shots file's CSV text from memory (a DataFrame), named `label` in messages.
    Csv {
        /// The name of the text in messages.
        label: PathBuf,
        /// The CSV text.
        bytes: Vec<u8>,
    },
}

impl ShotsInput {
    /// The name of the shots in messages.
    pub fn label(&self) -> &Path {
        match self {
            Self::File(p) => p,
            Self::Csv { label, .. } => label,
        }
    }
}

impl ShotsFormat {
    /// The shots reader's options these settings give.
    pub fn read_options(&self) -> ReadOptions {
        ReadOptions {
            strict: self.strict,
            include_estimated: self.include_estimated,
        }
    }

    /// Read `input` as shots in this format; the import's notes and the rows left out go to
    /// `notes`. CSV text from memory is a shots file (an export is read from its file).
    pub fn read(&self, input: &ShotsInput, notes: &mut dyn Notes) -> anyhow::Result<ShotTable> {
        let opts = self.read_options();
        let table = match (input, self.format.as_deref()) {
            (ShotsInput::File(path), None | Some("shots")) => {
                crate::data::shots::read_shots_with(path, opts)?
            }
            (ShotsInput::File(path), Some(format)) => {
                let imported = self
                    .import(path, format, notes)
                    .map_err(|e| shots_hint(path, format, self.format_from.as_deref(), e))?;
                imported.read_back_with(path, opts)?
            }
            (ShotsInput::Csv { label, bytes }, None | Some("shots")) => {
                crate::data::shots::parse_shots_with(label, &bytes[..], opts)?
            }
            (ShotsInput::Csv { .. }, Some(f)) => bail!(
                "format '{f}': a launch-monitor export is read from its file; give its path (or \
                 convert it first with read_export)"
            ),
        };
        for note in table.left_out_notes() {
            notes.note("shots", &note);
        }
        Ok(table)
    }

    /// Convert the export at `path` with `format` (`auto`: the layout recognised), the notes
    /// to `notes`.
    pub fn import(
        &self,
        path: &Path,
        format: &str,
        notes: &mut dyn Notes,
    ) -> anyhow::Result<Imported> {
        use crate::data::import::{detect, import, load_mapping, preset_for, ImportOptions};
        crate::data::safe_write::note_input(path);
        let bytes = std::fs::read(path)
            .map_err(|e| crate::data::DataError::file(path, format!("cannot read: {e}")))?;
        let format = if format.eq_ignore_ascii_case("auto") {
            let d = detect(path, &bytes)?;
            notes.note("import", &d.note);
            d.preset.to_owned()
        } else {
            preset_for(format, &bytes)
        };
        let mapping = load_mapping(&format)?;
        let opts = ImportOptions {
            impact_offset_positive: self.impact_offset_positive,
            ignore_unknown_columns: self.ignore_unknown_columns,
            strict: self.strict,
        };
        let imported = import(path, &bytes, &mapping, &opts)?;
        for note in &imported.notes {
            notes.note(&format!("import ({})", mapping.export.name), note);
        }
        Ok(imported)
    }
}

/// `e`, the refusal of an import of `path` as `format`, with a hint when `path` is a shots file
/// already (its header has every required shots column): such a file is read with `--format
/// shots`, which a project file's `format` (or a habit of typing `--format`) easily hides.
/// `format_from`: the project file that set `format`, when one did. A format that is not one
/// (a typo) keeps its own error: that is the thing to fix, not the file.
fn shots_hint(
    path: &Path,
    format: &str,
    format_from: Option<&Path>,
    e: anyhow::Error,
) -> anyhow::Error {
    let mut head = Vec::new();
    let read = std::fs::File::open(path).and_then(|f| f.take(1 << 16).read_to_end(&mut head));
    let text = String::from_utf8_lossy(&head);
    let line = text
        .trim_start_matches('\u{feff}')
        .lines()
        .next()
        .unwrap_or("");
    let header: Vec<&str> = line
        .split(',')
        .map(|h| h.trim().trim_matches('"'))
        .collect();
    let required = crate::data::shots::required_columns();
    let known =
        format.eq_ignore_ascii_case("auto") || crate::data::import::load_mapping(format).is_ok();
    if read.is_err() || !known || !required.iter().all(|c| header.contains(c)) {
        return e;
    }
    let from = match format_from {
        Some(p) => format!(" (format = {format} is the project file {}'s)", p.display()),
        None => String::new(),
    };
    anyhow::anyhow!(
        "{e:#}; {} looks like a shots file already (its header has {}): read it with \
         --format shots{from}",
        path.display(),
        required.join(", ")
    )
}

/// Bring the shots of `table` to the model's own delivery convention with `club`
/// ([`crate::conventions::to_model`]), in place and once: the table's conventions are the
/// model's afterwards. With `say`, what was converted goes to `notes`, a line each (commands
/// whose report prints the summary pass `false`); the summary is returned. With `fit`, shots
/// whose face angle the monitor derived from the launch are left out first and counted in
/// `notes` (`ShotTable::leave_out_derived`: `diagnose`, `calibrate`).
pub fn to_model_convention(
    club: &ClubSpec,
    table: &mut ShotTable,
    (say, fit): (bool, bool),
    notes: &mut dyn Notes,
) -> anyhow::Result<crate::conventions::ConventionSummary> {
    if fit {
        let total = table.shots.len();
        let n = table.leave_out_derived();
        if n > 0 {
            let l = table.left_out.last().expect("just pushed");
            let shown: Vec<String> = l.lines.iter().take(5).map(usize::to_string).collect();
            let more = if l.lines.len() > 5 { ", …" } else { "" };
            notes.note(
                "shots",
                &format!("left out {n} of {total} shots: {}", l.reason),
            );
            notes.line(&format!(
                "  line(s) {}{more}: a fit on them would fit the monitor's formula",
                shown.join(", ")
            ));
        }
        if table.shots.is_empty() {
            bail!(
                "{}: every shot's face angle is derived from the launch: there is no measured \
                 face angle to fit with (`smash compare` reports such shots)",
                table.path.display()
            );
        }
    }
    let (shots, summary) = crate::conventions::to_model(club, &table.shots, &table.conventions)
        .map_err(|e| {
            let line = table.lines.get(e.index).copied();
            crate::data::DataError::at(
                &table.path,
                line,
                None,
                format!("shot '{}': {}", e.shot_id, e.source),
            )
        })?;
    table.shots = shots;
    table.conventions = vec![Default::default(); table.shots.len()];
    if say {
        for l in summary.lines() {
            notes.line(&l);
        }
    }
    Ok(summary)
}

/// The warning for shots whose group none of the club's per-group effects (`group = "A"`)
/// names, or `None`. Such shots get the nominal club with only the effects that name no group:
/// right for a new group measured with a club calibrated on others (so a warning, not a
/// refusal), but easy to miss when a group was renamed or a file has no `group` column.
pub fn groups_without_effects(club_path: &Path, club: &ClubSpec, shots: &[Shot]) -> Option<String> {
    let have = club.effect_groups();
    if have.is_empty() {
        return None;
    }
    let mut missing: Vec<&str> = shots
        .iter()
        .map(|s| s.group.as_str())
        .filter(|g| !have.iter().any(|h| h == g))
        .collect();
    missing.sort_unstable();
    missing.dedup();
    if missing.is_empty() {
        return None;
    }
    let quote = |v: &[&str]| {
        v.iter()
            .map(|g| format!("'{}'", g.escape_debug()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let have: Vec<&str> = have.iter().map(String::as_str).collect();
    Some(format!(
        "warning: {}: the club's per-group effects are for group(s) {}; shots of group(s) {} get \
         none of them (the nominal club with the effects that name no group){}",
        club_path.display(),
        quote(&have),
        quote(&missing),
        if missing.contains(&"all") {
            " ('all' is the group of shots in a file without a `group` column)"
        } else {
            ""
        }
    ))
}

/// A club and the name it goes by in messages (its file's path, or a label).
#[derive(Debug, Clone, Copy)]
pub struct NamedClub<'a> {
    /// The club.
    pub spec: &'a ClubSpec,
    /// Its name in messages.
    pub path: &'a Path,
}

/// The shots of a command after reading: the table (in the model's convention once
/// [`prepare`] returns) and the name they go by in messages.
pub struct Prepared {
    /// The shots.
    pub table: ShotTable,
    /// What the conversion to the model's convention did.
    pub conventions: crate::conventions::ConventionSummary,
}

/// Refuse an iteration limit of 0 (`--max-iters`): no fit would take a step, and every one
/// would be reported as not converged.
pub fn check_max_iters(max_iters: u64) -> anyhow::Result<()> {
    if max_iters == 0 {
        bail!("--max-iters must be at least 1 (the solver's iteration limit), got 0");
    }
    Ok(())
}

/// Read `input` in `format`, bring it to the model's convention (`say`: the conversion lines
/// to `notes`; `fit`: derived face angles left out) and warn about groups without the club's
/// per-group effects: what every command that compares the club with shots does first.
pub fn prepare(
    club: NamedClub,
    input: &ShotsInput,
    format: &ShotsFormat,
    (say, fit): (bool, bool),
    notes: &mut dyn Notes,
) -> anyhow::Result<Prepared> {
    let table = format.read(input, notes)?;
    prepare_table(club, table, (say, fit), notes)
}

/// A table already read, brought to the model's convention and checked for groups without the
/// club's per-group effects, as [`prepare`] does after reading (for a caller that checks its
/// outputs between reading and converting).
pub fn prepare_table(
    club: NamedClub,
    mut table: ShotTable,
    (say, fit): (bool, bool),
    notes: &mut dyn Notes,
) -> anyhow::Result<Prepared> {
    let conventions = to_model_convention(club.spec, &mut table, (say, fit), notes)?;
    if let Some(w) = groups_without_effects(club.path, club.spec, &table.shots) {
        notes.line(&w);
    }
    leave_out_unsolvable(club, &mut table, notes)?;
    Ok(Prepared { table, conventions })
}

/// Why [`leave_out_unsolvable`] leaves a shot out, before its column and kind.
const UNSOLVABLE: &str = "a shot the club cannot solve";

/// Leave out, and count like a bad row, the shots the club cannot solve at its own values: a
/// location off this club's face, a delivery that does not approach the ball, a COR law that
/// leaves (0, 1], a user-defined law with no allowed value there. One such row of a real
/// export does not sink the others (the shots reader's rule); read with `--strict` the file is
/// refused at the first, and it is refused when more than half are left out. A club whose
/// model cannot be built is left to the command, which says why.
fn leave_out_unsolvable(
    club: NamedClub,
    table: &mut ShotTable,
    notes: &mut dyn Notes,
) -> anyhow::Result<()> {
    let Ok(solved) = crate::predict::solve_each(club.spec, &table.shots) else {
        return Ok(());
    };
    let keep: Vec<bool> = solved.iter().map(Result::is_ok).collect();
    let mut left = Vec::new();
    for (i, o) in solved.into_iter().enumerate() {
        let Err(source) = o else {
            continue;
        };
        let e = table.shot_error(i + 1, &table.shots[i].id, source);
        if table.strict {
            return Err(e.into());
        }
        crate::data::left_out::push(&mut left, table.lines[i], UNSOLVABLE.to_owned(), Some(e));
    }
    if left.is_empty() {
        return Ok(());
    }
    let before = table.left_out.len();
    table.leave_out(&keep, left);
    let said = crate::data::left_out::notes(&table.left_out[before..], table.rows_read());
    // Refused (no row left, or more than half bad): the refusal's one line says it all.
    crate::data::left_out::refuse_when_unusable(&table.path, &table.left_out, table.shots.len())?;
    for note in said {
        notes.note("shots", &note);
    }
    Ok(())
}

/// Compare the shots with the club ([`crate::club_match::check`]) before anything is fitted:
/// refuse a mismatch in one line, or with `ignore_club_mismatch` warn in `notes` and return
/// the reason (the caller then reports no findings).
pub fn club_check(
    ignore_club_mismatch: bool,
    club: NamedClub,
    shots_path: &Path,
    shots: &[Shot],
    notes: &mut dyn Notes,
) -> anyhow::Result<Option<String>> {
    let loft_deg = club.spec.static_loft_rad.map(f64::to_degrees);
    let check = crate::club_match::check(loft_deg, shots);
    if check.is_match() {
        return Ok(None);
    }
    let why = format!(
        "{} does not match the club {}: {}",
        shots_path.display(),
        club.path.display(),
        check.summary()
    );
    if !ignore_club_mismatch {
        bail!("{why} (--ignore-club-mismatch runs anyway and reports no findings)");
    }
    notes.line(&format!(
        "warning: {why}; running under --ignore-club-mismatch: no findings are reported"
    ));
    Ok(Some(check.summary()))
}

/// The comment line a written club file carries when the fit ran under
/// `--ignore-club-mismatch` (`mismatch`: why the shots are not this club's), else nothing: the
/// file itself then says that its values were fitted to another club's shots.
pub fn mismatch_comment(mismatch: Option<&str>) -> String {
    mismatch.map_or(String::new(), |why| {
        format!(
            "\nWARNING: fitted under --ignore-club-mismatch: the shots do not match this club \
             ({}); the values describe those shots, not this club.",
            crate::data::escape(why)
        )
    })
}

/// An impact-location noise of `sy` (vertical) and `sz` (heel–toe) mm, refused outside its
/// limits.
pub fn impact_noise_from_mm(sy: f64, sz: f64) -> Result<ImpactNoise, NoiseValueError> {
    for v in [sy, sz] {
        crate::limits::SIGMA_LOCATION_MM
            .check(v)
            .map_err(|e| NoiseValueError(e.to_string()))?;
    }
    ImpactNoise::from_mm(sy, sz).map_err(|e| NoiseValueError(e.to_string()))
}

/// An impact-location noise refused: what was wrong and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct NoiseValueError(pub String);

/// Serde form of an optional impact-location noise: `[vertical, heel–toe]` in mm, checked
/// against its limits as it is read (`#[serde(with = "impact_noise_mm")]`).
pub mod impact_noise_mm {
    use super::*;

    /// `[sy, sz]` mm, or none.
    pub fn serialize<S: Serializer>(v: &Option<ImpactNoise>, s: S) -> Result<S::Ok, S::Error> {
        v.map(|n| [n.sigma_y_m * 1e3, n.sigma_z_m * 1e3])
            .serialize(s)
    }

    /// `[sy, sz]` mm, each within the location noise's limits.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<ImpactNoise>, D::Error> {
        match Option::<[f64; 2]>::deserialize(d)? {
            None => Ok(None),
            Some([sy, sz]) => impact_noise_from_mm(sy, sz)
                .map(Some)
                .map_err(|e| serde::de::Error::custom(format!("impact_noise_mm: {e}"))),
        }
    }
}
