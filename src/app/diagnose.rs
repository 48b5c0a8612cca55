//! `diagnose`: which effects does the data ask for? Forward selection with grouped
//! cross-validation ([`crate::diagnose`]), its noise floor and the signals its effects share.

use std::path::{Path, PathBuf};

use anyhow::Context;
use serde::{Deserialize, Serialize};

use super::inputs::{self, NamedClub, ShotsFormat, ShotsInput};
use super::Notes;
use crate::data::noise_file::read_noise_file;
use crate::data::shots::ShotTable;
use crate::diagnose::noise_floor::{noise_floor, InstrumentClass};
use crate::diagnose::{
    diagnose, DiagnoseOptions, DiagnoseProgress, DEFAULT_IMPACT_NOISE_CANDIDATES_MM,
};
use crate::fit::{parse_effect_list, FitError};
use crate::measurement::ImpactNoise;
use crate::report::diagnose::DiagnoseReport;
use crate::ClubSpec;

/// Settings of `diagnose`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct DiagnoseSettings {
    /// How the shots are read.
    #[serde(flatten)]
    pub shots: ShotsFormat,
    /// 1σ noise of the measured impact location (vertical, heel–toe), mm: given, the
    /// locations are averaged over and no impact-noise level is selected.
    #[serde(with = "inputs::impact_noise_mm")]
    pub impact_noise_mm: Option<ImpactNoise>,
    /// Cross-validation folds (grouped by golfer, else by session, time block or club).
    pub folds: usize,
    /// Most effects to select.
    pub max_steps: usize,
    /// Candidates (default: every library effect, plus `added_mass@group` and
    /// `hosel_mass@group`), as an effect list.
    pub candidates: Option<String>,
    /// Every default candidate except these (an effect list).
    pub without: Option<String>,
    /// Iteration limit of each fit.
    pub max_iters: u64,
    /// Take the measured impact locations as exact (offer no impact-noise candidate).
    pub exact_impact_locations: bool,
    /// Instrument class whose documented noise sets the noise floor.
    pub instrument: Option<InstrumentClass>,
    /// Instrument noise file (overrides `instrument`).
    pub noise: Option<PathBuf>,
    /// Run on shots that do not match the club (the report then has no findings).
    pub ignore_club_mismatch: bool,
}

impl Default for DiagnoseSettings {
    fn default() -> Self {
        Self {
            shots: ShotsFormat::default(),
            impact_noise_mm: None,
            folds: 5,
            max_steps: 10,
            candidates: None,
            without: None,
            max_iters: 100,
            exact_impact_locations: false,
            instrument: None,
            noise: None,
            ignore_club_mismatch: false,
        }
    }
}

impl DiagnoseSettings {
    /// Refuse settings that contradict each other (the command line's parser refuses them
    /// first).
    pub fn check(&self) -> anyhow::Result<()> {
        if self.candidates.is_some() && self.without.is_some() {
            anyhow::bail!("--candidates and --without cannot be given together: give one list");
        }
        if self.exact_impact_locations && self.impact_noise_mm.is_some() {
            anyhow::bail!(
                "--exact-impact-locations and --impact-noise-mm cannot be given together: the \
                 locations are either exact or noisy"
            );
        }
        Ok(())
    }
}

/// Diagnose `club` on the shots of `input` (read and prepared): what the Python package calls.
/// `progress` sees the fits; `cancel`, checked between fits, stops the run with
/// [`FitError::Cancelled`].
pub fn run(
    settings: &DiagnoseSettings,
    club: NamedClub,
    input: &ShotsInput,
    notes: &mut dyn Notes,
    (progress, cancel): (
        Option<&dyn DiagnoseProgress>,
        Option<&crate::cancel::Cancel>,
    ),
) -> anyhow::Result<(DiagnoseReport, ShotTable)> {
    settings.check()?;
    let prepared = inputs::prepare(club, input, &settings.shots, (true, true), notes)?;
    let report = run_prepared(
        settings,
        club,
        (input.label(), &prepared.table),
        notes,
        (progress, cancel),
    )?;
    Ok((report, prepared.table))
}

/// The diagnosis of `table` (prepared, named `shots_path` in messages) with `club`, after the
/// club check, with its noise floor and shared signals.
pub fn run_prepared(
    settings: &DiagnoseSettings,
    club: NamedClub,
    (shots_path, table): (&Path, &ShotTable),
    notes: &mut dyn Notes,
    (progress, cancel): (
        Option<&dyn DiagnoseProgress>,
        Option<&crate::cancel::Cancel>,
    ),
) -> anyhow::Result<DiagnoseReport> {
    settings.check()?;
    let spec: &ClubSpec = club.spec;
    let mismatch = inputs::club_check(
        settings.ignore_club_mismatch,
        club,
        shots_path,
        &table.shots,
        notes,
    )?;
    let known_noise = match (&settings.noise, settings.instrument) {
        (Some(p), _) => Some(read_noise_file(p)?),
        (None, Some(c)) => Some(c.noise()),
        (None, None) => None,
    };
    let assumed = known_noise.is_none();
    let instrument = known_noise
        .clone()
        .unwrap_or_else(|| InstrumentClass::Camera.noise());
    if !table.has_measurements() {
        return Err(FitError::NoMeasurements).context(shots_path.display().to_string());
    }
    if settings.folds < 2 {
        anyhow::bail!("--folds must be at least 2, got {}", settings.folds);
    }
    inputs::check_max_iters(settings.max_iters)?;
    let candidates = match (&settings.candidates, &settings.without) {
        (Some(list), _) => Some(parse_effect_list(list)?),
        (None, Some(list)) => Some(
            crate::diagnose::default_candidates_without(&table.shots, &parse_effect_list(list)?)
                .context("--without")?,
        ),
        (None, None) => None,
    };
    let opts = DiagnoseOptions {
        folds: settings.folds,
        max_steps: settings.max_steps,
        max_iters: settings.max_iters,
        candidates,
        impact_noise: settings.impact_noise_mm,
        impact_noise_candidates_mm: if settings.exact_impact_locations {
            Vec::new()
        } else {
            DEFAULT_IMPACT_NOISE_CANDIDATES_MM.to_vec()
        },
        noise_floor: known_noise,
        // Without golfers, whole sessions (dates), time blocks or clubs form the folds.
        fold_keys: crate::data::sessions::fold_keys(table, settings.folds)?,
        cancel: cancel.cloned(),
        ..DiagnoseOptions::default()
    };
    let mut d = diagnose(spec, &table.shots, &opts, progress)
        .with_context(|| shots_path.display().to_string())?;
    if crate::cancel::cancelled(cancel) {
        return Err(FitError::Cancelled.into());
    }
    d.club_mismatch = mismatch;
    // The rows the shots reader left out (said as it read them), in the report.
    d.warnings.extend(table.left_out_notes());
    let mut floor = noise_floor(&d, &table.shots, &instrument)?;
    floor.assumed = assumed;
    d.shared_signals = crate::diagnose::shared::shared_signals(&d, &table.shots, &floor)?;
    Ok(DiagnoseReport {
        diagnosis: d,
        floor,
    })
}
