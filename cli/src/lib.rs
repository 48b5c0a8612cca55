//! The `smash` command line: argument parsing and dispatch. Each subcommand lives in its own
//! file, loads files, calls the library and prints; no physics here.

use clap::{Parser, Subcommand};

pub mod calibrate;
pub mod compare;
/// `--delivery-noise SPEC` (the library's).
pub use smash::app::delivery_noise;
pub mod diagnose;
pub mod effects;
pub mod flight;
pub mod import;
pub mod infer_club;
pub mod likelihood;
pub mod measured;
pub mod merge;
pub mod predict;
pub mod progress;
pub mod project;
pub mod run;
pub mod signals;
pub mod stdout;
pub mod study_output;
pub mod synth;
pub mod text;
pub mod whatif;

/// Golf clubhead–ball impact engine: predict launch, compare with measurements, find the
/// missing physics, calibrate, and run design studies.
#[derive(Debug, Parser)]
#[command(name = "smash", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Predict ball launch for a shots file, or for one delivery given on the command line.
    Predict(predict::PredictArgs),
    /// List the effect library: names, parameters, units, defaults and physical bounds.
    Effects(effects::EffectsArgs),
    /// Generate a synthetic experiment (shots with measured launch) from a configured world.
    Synth(synth::SynthArgs),
    /// Compare the model with measured launch: Table 2, bias significance, face maps, trends
    /// and ranked findings with hints at the missing physics.
    Compare(compare::CompareArgs),
    /// Run a design study: face maps over design variants, summaries, sensitivities,
    /// optimisation (or one shard of it with --shard k/N).
    Run(run::RunArgs),
    /// Merge the shards of a study into exactly the unsharded result.
    Merge(merge::MergeArgs),
    /// Fly launch conditions (measured or predicted) to landing: carry, offline, apex, flight
    /// time, land angle (and total with --total), in a given atmosphere.
    Flight(flight::FlightArgs),
    /// Fit named effects' parameters to measured launch (values ± standard errors,
    /// correlations, chi2, AIC/BIC, before/after error tables).
    Calibrate(calibrate::CalibrateArgs),
    /// Rank the library's effects by how much each explains (cross-validated by golfer) and
    /// select them forward until the improvement is not significant.
    Diagnose(diagnose::DiagnoseArgs),
    /// Convert a launch-monitor export (TrackMan, Foresight, FlightScope, Uneekor or a mapping
    /// file) to a shots file.
    Import(import::ImportArgs),
    /// Answer one design change (a mass moved, the CoM shifted, the MOI scaled, loft, bulge
    /// or roll changed) in yards against the base head, for a stated golfer and mishits.
    Whatif(whatif::WhatIfArgs),
    /// Infer the head's effective properties (CoM, moments, face radii, COR and its falloff,
    /// loft and face biases) from the shots, with the start club as a stated weak prior, what
    /// the shots determine, and a plan of the shots needed (--plan).
    InferClub(infer_club::InferClubArgs),
}

/// Run a parsed command line, its unset options first taken from the project file, if any
/// ([`project`]).
pub fn run(mut cli: Cli) -> anyhow::Result<()> {
    let here = std::env::current_dir().unwrap_or_default();
    if let Some(path) = project::find(&here) {
        let taken = project::read(&path)?.apply(cli.command.layered());
        if !taken.is_empty() {
            eprintln!("defaults from {}: {}", path.display(), taken.join(", "));
        }
    }
    match cli.command {
        Command::Predict(args) => predict::run(args),
        Command::Effects(args) => effects::run(args),
        Command::Synth(args) => synth::run(args),
        Command::Compare(args) => compare::run(args),
        Command::Run(args) => run::run(args),
        Command::Merge(args) => merge::run(args),
        Command::Flight(args) => flight::run(args),
        Command::Calibrate(args) => calibrate::run(args),
        Command::Diagnose(args) => diagnose::run(args),
        Command::Import(args) => import::run(args),
        Command::Whatif(args) => whatif::run(args),
        Command::InferClub(args) => infer_club::run(args),
    }
}

impl Command {
    /// The options of this command a project file may set.
    pub fn layered(&mut self) -> project::Layered<'_> {
        use project::Layered;
        let noise = |i, n| Some((i, n));
        match self {
            Command::Compare(a) => a.inputs.layered(None, false),
            Command::Calibrate(a) => a
                .inputs
                .layered(noise(&mut a.instrument, &mut a.noise), false),
            Command::Diagnose(a) => a.inputs.layered(
                noise(&mut a.instrument, &mut a.noise),
                a.exact_impact_locations,
            ),
            Command::Predict(a) => Layered {
                effect_defs: Some(&mut a.effect_defs),
                shots_format: Some(&mut a.shots_format),
                ..Layered::default()
            },
            Command::Import(a) => Layered {
                shots_format: Some(&mut a.format),
                ..Layered::default()
            },
            Command::Effects(effects::EffectsArgs { effect_defs, .. })
            | Command::Synth(synth::SynthArgs { effect_defs, .. })
            | Command::Run(run::RunArgs { effect_defs, .. })
            | Command::Merge(merge::MergeArgs { effect_defs, .. }) => Layered {
                effect_defs: Some(effect_defs),
                ..Layered::default()
            },
            Command::InferClub(a) => Layered {
                shots_format: Some(&mut a.shots_format),
                ..Layered::default()
            },
            Command::Flight(_) | Command::Whatif(_) => Layered::default(),
        }
    }
}

pub use smash::app::predict::locate_shot_error;

pub use smash::app::inputs::mismatch_comment;
pub use smash::app::{error_chain, thread_pool, WORKER_STACK_BYTES};

/// The flag that runs `compare`, `calibrate` or `diagnose` on shots that do not match the club.
#[derive(Debug, Clone, Copy, clap::Args)]
pub struct ClubCheckArgs {
    /// Run even when the shots do not match the club file (another club's loft or speed, or
    /// several clubs named in `group`); the output then reports no findings about this club.
    #[arg(long)]
    pub ignore_club_mismatch: bool,
}

impl ClubCheckArgs {
    /// Compare the shots with the club ([`smash::club_match::check`]) before anything is
    /// fitted: refuse a mismatch in one line, or under `--ignore-club-mismatch` warn and return
    /// the reason (the caller then reports no findings).
    pub fn check(
        self,
        club_path: &std::path::Path,
        club: &smash::club::ClubSpec,
        shots_path: &std::path::Path,
        shots: &[smash::model::Shot],
    ) -> anyhow::Result<Option<String>> {
        smash::app::inputs::club_check(
            self.ignore_club_mismatch,
            smash::app::inputs::NamedClub {
                spec: club,
                path: club_path,
            },
            shots_path,
            shots,
            &mut smash::app::StderrNotes,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn command_line_is_well_formed() {
        Cli::command().debug_assert();
    }
}

pub use smash::report::text::counted;

/// Measurement-noise options shared by the commands that compare the model with measurements.
#[derive(Debug, Clone, clap::Args)]
pub struct MeasurementArgs {
    /// 1σ noise of the measured impact location, mm, vertical then heel–toe (e.g. `3,2.5`).
    /// The model is then averaged over where the ball was most likely struck (regression
    /// calibration), so location noise is not mistaken for physics.
    #[arg(
        long,
        value_name = "SY,SZ",
        value_parser = parse_impact_noise,
        allow_hyphen_values = true,
        help_heading = "Measurement noise"
    )]
    pub impact_noise_mm: Option<smash::measurement::ImpactNoise>,
}

/// `--max-iters N`: a whole number of at least 1 (0 iterations fits nothing, and every fit
/// would be reported as not converged).
pub(crate) fn parse_iterations(s: &str) -> Result<u64, String> {
    match s.trim().parse::<u64>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "'{s}': the solver's iteration limit is a whole number of at least 1"
        )),
    }
}

fn parse_impact_noise(s: &str) -> Result<smash::measurement::ImpactNoise, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [y, z] = parts.as_slice() else {
        return Err(format!(
            "expected two numbers 'SY,SZ' in mm (e.g. 3,2.5), got '{s}'"
        ));
    };
    let num = |t: &str| {
        t.parse::<f64>()
            .map_err(|_| format!("'{t}' is not a number (mm)"))
    };
    impact_noise_from_mm(num(y)?, num(z)?).map_err(|e| e.to_string())
}

pub use smash::app::inputs::impact_noise_from_mm;

/// How a shots argument is read: a shots file (default) or a launch-monitor export converted on
/// the fly, exactly as `smash import` would.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ShotsFormatArgs {
    /// Format of the shots input: `shots` (default; `auto` for `smash import`), `auto` (the
    /// layout recognised from the header or the JSON keys), a launch-monitor preset (trackman,
    /// flightscope, foresight, foresight-session, uneekor, garmin-r10, rapsodo, skytrak,
    /// awesome-golf, square-golf, gspro) or a mapping file NAME.toml (docs/import.md).
    #[arg(long, value_name = "FORMAT", help_heading = "Input format")]
    pub format: Option<String>,

    /// Which way a positive heel–toe impact offset points in the export, where the vendor does
    /// not say (the import refuses to guess).
    #[arg(long, value_name = "SIDE", value_enum, help_heading = "Input format")]
    pub impact_offset_positive: Option<OffsetSideArg>,

    /// Drop export columns the format does not know instead of refusing the file.
    #[arg(long, help_heading = "Input format")]
    pub ignore_unknown_columns: bool,

    /// Refuse the whole file at the first bad or incomplete row. By default such rows are
    /// left out (or a shot is kept without its impact location) and counted in one summary.
    #[arg(long, help_heading = "Input format")]
    pub strict: bool,

    /// Use shots whose spin or club data the monitor estimated instead of measured
    /// (`spin_estimated`/`club_estimated` = 1); by default they are left out and counted.
    #[arg(long, help_heading = "Input format")]
    pub include_estimated: bool,

    /// The project file `format` came from, when it did (named in the hint that a shots file
    /// needs `--format shots`).
    #[arg(skip)]
    pub format_from: Option<std::path::PathBuf>,
}

impl ShotsFormatArgs {
    /// The settings these flags give.
    pub fn settings(&self) -> smash::app::inputs::ShotsFormat {
        smash::app::inputs::ShotsFormat {
            format: self.format.clone(),
            impact_offset_positive: self.impact_offset_positive.map(Into::into),
            ignore_unknown_columns: self.ignore_unknown_columns,
            strict: self.strict,
            include_estimated: self.include_estimated,
            format_from: self.format_from.clone(),
        }
    }

    /// Read `path` as shots in this format. Import notes (skipped rows, assumed units) and the
    /// rows left out go to stderr.
    pub fn read(&self, path: &std::path::Path) -> anyhow::Result<smash::data::shots::ShotTable> {
        self.settings().read(
            &smash::app::inputs::ShotsInput::File(path.to_owned()),
            &mut smash::app::StderrNotes,
        )
    }

    /// Convert the export at `path` with `format`, printing the notes.
    pub fn import(
        &self,
        path: &std::path::Path,
        format: &str,
    ) -> anyhow::Result<smash::data::import::Imported> {
        self.settings()
            .import(path, format, &mut smash::app::StderrNotes)
    }
}

/// Which way a positive heel–toe impact offset points (the command-line face of
/// [`smash::data::import::OffsetSide`], which stays free of clap).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum OffsetSideArg {
    /// Positive offsets are toward the toe (the shots file's `impact_z_mm` sign).
    Toe,
    /// Positive offsets are toward the heel.
    Heel,
}

impl OffsetSideArg {
    /// The value as the flag and a project file write it (`toe`, `heel`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Toe => "toe",
            Self::Heel => "heel",
        }
    }
}

impl From<OffsetSideArg> for smash::data::import::OffsetSide {
    fn from(side: OffsetSideArg) -> Self {
        match side {
            OffsetSideArg::Toe => Self::Toe,
            OffsetSideArg::Heel => Self::Heel,
        }
    }
}

impl From<smash::data::import::OffsetSide> for OffsetSideArg {
    fn from(side: smash::data::import::OffsetSide) -> Self {
        match side {
            smash::data::import::OffsetSide::Toe => Self::Toe,
            smash::data::import::OffsetSide::Heel => Self::Heel,
        }
    }
}

/// `--effect-defs FILE`: user-defined effects (`[[define_effect]]` tables) the command may name
/// like library effects.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct EffectDefsArgs {
    /// Effects file (TOML) of [[define_effect]] tables: user-defined effects, named like the
    /// library's (docs/user-effects.md).
    #[arg(long, value_name = "EFFECTS.toml")]
    pub effect_defs: Option<std::path::PathBuf>,
}

impl EffectDefsArgs {
    /// Read and register the definitions (before any effect list, club, study or synth file
    /// that names them is read).
    pub fn load(&self) -> anyhow::Result<()> {
        if let Some(path) = &self.effect_defs {
            smash::data::effect_defs::read_effect_defs(path)?;
        }
        Ok(())
    }
}
