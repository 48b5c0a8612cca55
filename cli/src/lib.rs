//! The `smash` command line: argument parsing and dispatch. Each subcommand lives in its own
//! file, loads files, calls the library and prints; no physics here.

use clap::{Parser, Subcommand};

pub mod calibrate;
pub mod compare;
pub mod delivery_noise;
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
pub mod shots_hint;
pub mod signals;
pub mod stdout;
pub mod study_output;
pub mod synth;
pub mod text;
pub mod whatif;
pub mod whatif_page;

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

/// A shot that cannot be predicted, located in its file: `FILE:LINE: columns …: shot 'ID': …`,
/// the same form as the shots reader's own errors.
pub fn locate_shot_error(
    table: &smash::data::shots::ShotTable,
    e: smash::predict::PredictError,
) -> anyhow::Error {
    use smash::physics::ImpactError;
    use smash::predict::PredictError;
    let PredictError::Shot {
        shot_id,
        row,
        source,
    } = e
    else {
        return anyhow::Error::new(e).context(table.path.display().to_string());
    };
    let line = row.checked_sub(1).and_then(|i| table.lines.get(i)).copied();
    let place = match source {
        ImpactError::OffFace(_) => Some("columns impact_y_mm, impact_z_mm".to_owned()),
        ImpactError::NotApproaching { .. } => Some(
            "columns club_speed_mph, attack_angle_deg, club_path_deg, dynamic_loft_deg, \
             face_angle_deg, club_omega_*_rad_s"
                .to_owned(),
        ),
        _ => None,
    };
    smash::data::DataError::at(
        &table.path,
        line,
        place,
        format!("shot '{shot_id}': {source}"),
    )
    .into()
}

/// Stack of each worker thread, bytes. Rayon's default is the platform's 2 MiB; unoptimised
/// (`cargo run`, dev profile), the face-map kernel's row function, whose SIMD variants are
/// inlined into one frame for speed, needs about 2 MiB of stack by itself, and `smash run
/// configs/studies/face_map.toml` overflowed it. The stack is reserved address space, touched
/// only as deep as it is used.
pub const WORKER_STACK_BYTES: usize = 16 << 20;

/// The worker threads every command runs its parallel work on (installed as the global pool by
/// the binary's `main`).
pub fn thread_pool() -> rayon::ThreadPoolBuilder {
    rayon::ThreadPoolBuilder::new()
        .stack_size(WORKER_STACK_BYTES)
        .thread_name(|i| format!("smash-worker-{i}"))
}

/// The message for shots whose group none of the club's per-group effects (`group = "A"`) names,
/// or `None`. Such shots get the nominal club with only the effects that name no group: right
/// for a new group measured with a club calibrated on others (so a warning, not a refusal), but
/// easy to miss when a group was renamed or a file has no `group` column.
pub fn groups_without_effects(
    club_path: &std::path::Path,
    club: &smash::club::ClubSpec,
    shots: &[smash::model::Shot],
) -> Option<String> {
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

/// Print [`groups_without_effects`]' warning, if any, once on stderr.
pub fn warn_groups_without_effects(
    club_path: &std::path::Path,
    club: &smash::club::ClubSpec,
    shots: &[smash::model::Shot],
) {
    if let Some(w) = groups_without_effects(club_path, club, shots) {
        eprintln!("{}", smash::data::escape(&w));
    }
}

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
        let loft_deg = club.static_loft_rad.map(f64::to_degrees);
        let check = smash::club_match::check(loft_deg, shots);
        if check.is_match() {
            return Ok(None);
        }
        let why = format!(
            "{} does not match the club {}: {}",
            shots_path.display(),
            club_path.display(),
            check.summary()
        );
        if !self.ignore_club_mismatch {
            anyhow::bail!("{why} (--ignore-club-mismatch runs anyway and reports no findings)");
        }
        eprintln!(
            "warning: {}; running under --ignore-club-mismatch: no findings are reported",
            smash::data::escape(&why)
        );
        Ok(Some(check.summary()))
    }
}

/// The comment line a written club file carries when the fit ran under
/// `--ignore-club-mismatch` (`mismatch`: why the shots are not this club's), else nothing: the
/// file itself then says that its values were fitted to another club's shots.
pub fn mismatch_comment(mismatch: Option<&str>) -> String {
    mismatch.map_or(String::new(), |why| {
        format!(
            "\nWARNING: fitted under --ignore-club-mismatch: the shots do not match this club \
             ({}); the values describe those shots, not this club.",
            smash::data::escape(why)
        )
    })
}

/// One line: the error and its causes, joined by `: `, with control characters from the input
/// (ESC, CR, …) escaped so that they cannot act on the terminal.
pub fn error_chain(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        let s = cause.to_string();
        if !parts.iter().any(|p| p.contains(&s)) {
            parts.push(s);
        }
    }
    smash::data::escape(&parts.join(": ").replace('\n', " ")).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn command_line_is_well_formed() {
        Cli::command().debug_assert();
    }

    /// A frame the size of the unoptimised face-map kernel's (about 2 MiB) and then some fits
    /// on every worker: on rayon's default 2 MiB stacks this aborts the test binary.
    #[test]
    fn workers_have_room_for_the_unoptimised_kernel() {
        fn deep(n: usize) -> u8 {
            let buf = std::hint::black_box([n as u8; 3 << 20]);
            buf[n % buf.len()]
        }
        let pool = thread_pool().num_threads(2).build().unwrap();
        let got = pool.broadcast(|c| deep(c.index() + 7));
        assert_eq!(got, [7, 8]);
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
    impact_noise_from_mm(num(y)?, num(z)?)
}

/// An impact-location noise of `sy` (vertical) and `sz` (heel–toe) mm, refused outside its
/// limits.
pub fn impact_noise_from_mm(sy: f64, sz: f64) -> Result<smash::measurement::ImpactNoise, String> {
    for v in [sy, sz] {
        smash::limits::SIGMA_LOCATION_MM
            .check(v)
            .map_err(|e| e.to_string())?;
    }
    smash::measurement::ImpactNoise::from_mm(sy, sz).map_err(|e| e.to_string())
}

/// How a shots argument is read: a shots file (default) or a launch-monitor export converted on
/// the fly, exactly as `smash import` would.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ShotsFormatArgs {
    /// Format of the shots input: `shots` (default; `auto` for `smash import`), `auto` (the
    /// layout recognised from the header or the JSON keys), a launch-monitor preset (trackman,
    /// flightscope, foresight, foresight-session, uneekor, garmin-r10, rapsodo, skytrak, gspro)
    /// or a mapping file NAME.toml (docs/import.md).
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
    /// Read `path` as shots in this format. Import notes (skipped rows, assumed units) go to
    /// stderr.
    pub fn read(&self, path: &std::path::Path) -> anyhow::Result<smash::data::shots::ShotTable> {
        let opts = self.read_options();
        let table = match self.format.as_deref() {
            None | Some("shots") => smash::data::shots::read_shots_with(path, opts)?,
            Some(format) => {
                let imported = self
                    .import(path, format)
                    .map_err(|e| shots_hint::add(path, format, self.format_from.as_deref(), e))?;
                imported.read_back_with(path, opts)?
            }
        };
        report_left_out(&table);
        Ok(table)
    }

    /// The shots reader's options these flags give.
    pub fn read_options(&self) -> smash::data::shots::ReadOptions {
        smash::data::shots::ReadOptions {
            strict: self.strict,
            include_estimated: self.include_estimated,
        }
    }

    /// Convert the export at `path` with `format`, printing the notes.
    pub fn import(
        &self,
        path: &std::path::Path,
        format: &str,
    ) -> anyhow::Result<smash::data::import::Imported> {
        use smash::data::import::{detect, import, load_mapping, preset_for, ImportOptions};
        smash::data::safe_write::note_input(path);
        let bytes = std::fs::read(path)
            .map_err(|e| smash::data::DataError::file(path, format!("cannot read: {e}")))?;
        let format = if format.eq_ignore_ascii_case("auto") {
            let d = detect(path, &bytes)?;
            crate::text::print_note("import", &d.note);
            d.preset.to_owned()
        } else {
            preset_for(format, &bytes)
        };
        let mapping = load_mapping(&format)?;
        let opts = ImportOptions {
            impact_offset_positive: self.impact_offset_positive.map(Into::into),
            ignore_unknown_columns: self.ignore_unknown_columns,
            strict: self.strict,
        };
        let imported = import(path, &bytes, &mapping, &opts)?;
        for note in &imported.notes {
            crate::text::print_note(&format!("import ({})", mapping.export.name), note);
        }
        Ok(imported)
    }
}

/// Bring the shots of `table` to the model's own delivery convention with `club`
/// ([`smash::conventions::to_model`]), in place and once: the table's conventions are the
/// model's afterwards. With `to_stderr`, what was converted goes to stderr, one line each
/// (commands whose report prints the summary pass `false`); the summary is returned. With
/// `fit`, shots whose face angle the monitor derived from the launch are left out first and
/// counted on stderr (`ShotTable::leave_out_derived`: `diagnose`, `calibrate`).
pub fn to_model_convention(
    club: &smash::club::ClubSpec,
    table: &mut smash::data::shots::ShotTable,
    to_stderr: bool,
    fit: bool,
) -> anyhow::Result<smash::conventions::ConventionSummary> {
    if fit {
        let total = table.shots.len();
        let n = table.leave_out_derived();
        if n > 0 {
            let l = table.left_out.last().expect("just pushed");
            let shown: Vec<String> = l.lines.iter().take(5).map(usize::to_string).collect();
            let more = if l.lines.len() > 5 { ", …" } else { "" };
            crate::text::print_note(
                "shots",
                &format!("left out {n} of {total} shots: {}", l.reason),
            );
            eprintln!(
                "  line(s) {}{more}: a fit on them would fit the monitor's formula",
                shown.join(", ")
            );
        }
        if table.shots.is_empty() {
            anyhow::bail!(
                "{}: every shot's face angle is derived from the launch: there is no measured \
                 face angle to fit with (`smash compare` reports such shots)",
                table.path.display()
            );
        }
    }
    let (shots, summary) = smash::conventions::to_model(club, &table.shots, &table.conventions)
        .map_err(|e| {
            let line = table.lines.get(e.index).copied();
            smash::data::DataError::at(
                &table.path,
                line,
                None,
                format!("shot '{}': {}", e.shot_id, e.source),
            )
        })?;
    table.shots = shots;
    table.conventions = vec![Default::default(); table.shots.len()];
    if to_stderr {
        for l in summary.lines() {
            eprintln!("{l}");
        }
    }
    Ok(summary)
}

/// One line on stderr per reason the shots reader left rows out: how many, of how many rows,
/// and their first lines.
pub fn report_left_out(table: &smash::data::shots::ShotTable) {
    for note in table.left_out_notes() {
        crate::text::print_note("shots", &note);
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
