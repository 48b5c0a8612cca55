//! `compare`: the model against measurements, as a diagnosis (Table 2, significance, face
//! maps, findings).

use anyhow::bail;
use serde::{Deserialize, Serialize};

use super::inputs::{self, NamedClub, Prepared, ShotsFormat, ShotsInput};
use super::Notes;
use crate::compare::{compare_with_hints, CompareOptions, CompareReport};
use crate::limits::fmt_value;
use crate::measurement::ImpactNoise;
use crate::physics::{Launch, LaunchComponent};
use crate::predict::expected_launches;

/// Smallest `alpha` accepted: a significance level far below any multiple-testing correction
/// a comparison of a few components needs (and printed short in the report's header).
const MIN_ALPHA: f64 = 1e-9;
/// Largest `alpha` accepted: above one half, a test flags an unbiased component more often
/// than not.
const MAX_ALPHA: f64 = 0.5;

/// Settings of `compare`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CompareSettings {
    /// How the shots are read.
    #[serde(flatten)]
    pub shots: ShotsFormat,
    /// 1σ noise of the measured impact location (vertical, heel–toe), mm.
    #[serde(with = "inputs::impact_noise_mm")]
    pub impact_noise_mm: Option<ImpactNoise>,
    /// Significance level of the flags.
    pub alpha: f64,
    /// Side of a face bin, mm.
    pub bin_mm: f64,
    /// Face bins with fewer shots are left empty.
    pub min_bin_count: usize,
    /// Run on shots that do not match the club (the report then has no findings).
    pub ignore_club_mismatch: bool,
}

impl Default for CompareSettings {
    fn default() -> Self {
        Self {
            shots: ShotsFormat::default(),
            impact_noise_mm: None,
            alpha: 0.01,
            bin_mm: 5.0,
            min_bin_count: 5,
            ignore_club_mismatch: false,
        }
    }
}

/// What `compare` found: the report and the model's launch of every shot (the HTML page's
/// residuals).
pub struct CompareRun {
    /// The report.
    pub report: CompareReport,
    /// The model's launch of every shot.
    pub launches: Vec<Launch>,
}

impl CompareSettings {
    /// Refuse a significance level or face bin outside their ranges (before any file is read).
    pub fn check(&self) -> anyhow::Result<()> {
        if !(self.alpha >= MIN_ALPHA && self.alpha <= MAX_ALPHA) {
            bail!(
                "--alpha {}: must be within [{}, {}] (a level above one half flags unbiased \
                 components half the time; one below 1e-9 flags no bias a launch monitor can \
                 show)",
                fmt_value(self.alpha),
                fmt_value(MIN_ALPHA),
                fmt_value(MAX_ALPHA)
            );
        }
        if !crate::compare::FACE_BIN_MM.contains(&self.bin_mm) {
            bail!(
                "--bin-mm {}: must be within [0.5, 100] mm (impact locations are measured to \
                 about a millimetre, and a bin larger than the face holds every shot)",
                fmt_value(self.bin_mm)
            );
        }
        Ok(())
    }
}

/// Compare `club` with the shots of `input`: the settings checked, the shots read and
/// prepared ([`inputs::prepare`]), then [`run_prepared`].
pub fn run(
    settings: &CompareSettings,
    club: NamedClub,
    input: &ShotsInput,
    notes: &mut dyn Notes,
) -> anyhow::Result<(CompareRun, Prepared)> {
    settings.check()?;
    let prepared = inputs::prepare(club, input, &settings.shots, (false, false), notes)?;
    let run = run_prepared(settings, club, input.label(), &prepared, notes)?;
    Ok((run, prepared))
}

/// The comparison of the prepared shots (named `shots_path` in messages) with `club`, after
/// the club check (which refuses shots of another club unless `ignore_club_mismatch`; the
/// report then says why and has no findings). Findings that would describe a monitor's
/// derived face angle rather than the head are dropped.
pub fn run_prepared(
    settings: &CompareSettings,
    club: NamedClub,
    shots_path: &std::path::Path,
    prepared: &Prepared,
    notes: &mut dyn Notes,
) -> anyhow::Result<CompareRun> {
    settings.check()?;
    let table = &prepared.table;
    let mismatch = inputs::club_check(
        settings.ignore_club_mismatch,
        club,
        shots_path,
        &table.shots,
        notes,
    )?;
    if !table.has_measurements() {
        let cols: Vec<&str> = LaunchComponent::ALL.iter().map(|c| c.column()).collect();
        bail!(
            "{}: no measured launch columns ({}); compare needs measurements (to predict only, \
             use `smash predict`)",
            shots_path.display(),
            cols.join(", ")
        );
    }
    let launches = expected_launches(club.spec, &table.shots, settings.impact_noise_mm)
        .map_err(|e| super::predict::locate_shot_error(table, e))?;
    if let Some((shot, _)) = table
        .shots
        .iter()
        .zip(&launches)
        .find(|(_, l)| !l.is_finite())
    {
        bail!(
            "{}: shot '{}': the model's launch is not a finite number; check its delivery and \
             the club {}",
            shots_path.display(),
            shot.id,
            club.path.display()
        );
    }
    let options = CompareOptions {
        alpha: settings.alpha,
        face_bin_mm: settings.bin_mm,
        min_bin_count: settings.min_bin_count,
        ..CompareOptions::default()
    };
    // Hints at the user-defined effects (of the effects file and the club file, not a synth
    // world's hidden ones), from their signatures measured on these shots.
    let user = crate::compare::UserHints::measure(
        club.spec,
        &table.shots,
        &crate::effects::user::offered(),
    );
    let report = compare_with_hints(&table.shots, &launches, &options, &user)?;
    let mut report = match mismatch {
        Some(why) => report.mismatched(why),
        None => report,
    };
    report.warnings = table.left_out_notes();
    if prepared.conventions.derived_face > 0 {
        // Those shots' face angles are the model's for their measured launch direction: an
        // azimuth finding, or a trend against that face angle, would describe the monitor's
        // formula and the launch's noise, not the head.
        crate::conventions::drop_derived_findings(&mut report.findings);
    }
    Ok(CompareRun { report, launches })
}

/// The report's title: `CLUB vs SHOTS (N groups)`.
pub fn title(club_name: &str, shots_path: &std::path::Path, groups: usize) -> String {
    format!(
        "{club_name} vs {} ({})",
        shots_path.display(),
        crate::report::text::counted(groups, "group")
    )
}

pub use crate::report::compare::report_text as text;
