//! The options `compare`, `calibrate` and `diagnose` share, as one struct each flattens: the
//! club and shots they read (and how), the noise of the measurements, the club check, and
//! the report formats (`--json`, `--report`, `--wide`); and the steps every one of them takes
//! before its own work: user effects loaded, outputs checked against the inputs, club and
//! shots read. Values a project file states fill what the flags leave unset
//! ([`crate::project`]).

use std::path::{Path, PathBuf};

use smash::data::club_file::read_club;
use smash::data::output_plan::OutputPlan;
use smash::data::shots::ShotTable;
use smash::ClubSpec;

/// The shared options.
#[derive(Debug, Clone, clap::Args)]
pub struct MeasuredArgs {
    /// User-defined effects.
    #[command(flatten)]
    pub effect_defs: crate::EffectDefsArgs,

    /// Club file (TOML); its own [[effect]] tables stay as they are.
    #[arg(long, value_name = "CLUB.toml")]
    pub club: PathBuf,

    /// Shots file (CSV) with measured launch columns (and a golfer column for grouped
    /// cross-validation), or a launch-monitor export with --format.
    #[arg(long, value_name = "SHOTS.csv")]
    pub shots: PathBuf,

    /// Format of --shots (a launch-monitor export is converted on the fly).
    #[command(flatten)]
    pub shots_format: crate::ShotsFormatArgs,

    /// Write a self-contained HTML report of what the text reports (charts legible in print).
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,

    /// Print the report as one JSON object on stdout (prose and progress go to stderr;
    /// docs/json.md).
    #[arg(long)]
    pub json: bool,

    /// Print the full tables instead of the ones that fit 100 columns.
    #[command(flatten)]
    pub wide: crate::text::WideArgs,

    /// Measurement noise of the inputs.
    #[command(flatten)]
    pub measurement: crate::MeasurementArgs,

    /// What to do when the shots do not match the club.
    #[command(flatten)]
    pub club_check: crate::ClubCheckArgs,
}

/// What [`MeasuredArgs::load`] read.
pub struct Loaded {
    /// The outputs, checked against the inputs.
    pub plan: OutputPlan,
    /// The club.
    pub club: ClubSpec,
    /// The shots, in the file's conventions.
    pub table: ShotTable,
}

impl MeasuredArgs {
    /// These options for the project file's layer, with the command's noise-class flags
    /// (`--instrument`, `--noise`) and whether `--exact-impact-locations` was given.
    pub fn layered<'a>(
        &'a mut self,
        noise: Option<(
            &'a mut Option<smash::diagnose::noise_floor::InstrumentClass>,
            &'a mut Option<PathBuf>,
        )>,
        exact_locations: bool,
    ) -> crate::project::Layered<'a> {
        crate::project::Layered {
            effect_defs: Some(&mut self.effect_defs),
            shots_format: Some(&mut self.shots_format),
            measurement: Some((&mut self.measurement, exact_locations)),
            noise,
        }
    }

    /// Load the user effects, check the outputs (`--report` and `outputs`) against the
    /// inputs (`--club`, `--shots` and `inputs`), run `check` (the command's own option
    /// checks), read the club and the shots, check the outputs again (a `--format` mapping
    /// file is an input known once read). Nothing is written.
    pub fn load(
        &self,
        inputs: &[(&str, &Path)],
        outputs: impl FnOnce(OutputPlan) -> OutputPlan,
        check: impl FnOnce() -> anyhow::Result<()>,
    ) -> anyhow::Result<Loaded> {
        self.effect_defs.load()?;
        let mut all = vec![("--club", self.club.as_path()), ("--shots", &self.shots)];
        all.extend_from_slice(inputs);
        let plan = outputs(OutputPlan::new(&all)).file("--report", self.report.as_deref());
        plan.check()?;
        check()?;
        let club = read_club(&self.club)?;
        let table = self.shots_format.read(&self.shots)?;
        plan.check()?;
        Ok(Loaded { plan, club, table })
    }

    /// [`Self::load`] for the commands that fit and may write a club (`calibrate`,
    /// `diagnose`): `--noise` is an input, `--out-club` an output.
    pub fn load_for_fit(
        &self,
        noise: Option<&Path>,
        out_club: Option<&Path>,
    ) -> anyhow::Result<Loaded> {
        let noise: Vec<(&str, &Path)> = noise.map(|n| ("--noise", n)).into_iter().collect();
        self.load(&noise, |p| p.file("--out-club", out_club), || Ok(()))
    }
}
