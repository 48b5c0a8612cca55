//! `smash diagnose`: which effects does the data ask for? Forward selection with grouped
//! cross-validation (see [`smash::diagnose`]).
//!
//! The report ([`smash::report::diagnose::DiagnoseReport`]) and its text, JSON and HTML are
//! the library's; this file holds the arguments, the files and the layout of the text.

use std::path::PathBuf;

use clap::Args;
use indicatif::ProgressBar;

use smash::app::diagnose::DiagnoseSettings;
use smash::app::inputs::{prepare_table, NamedClub, Prepared};
use smash::data::club_file::club_toml_checked;
use smash::diagnose::noise_floor::InstrumentClass;
use smash::diagnose::DiagnoseProgress;
use smash::report::diagnose::text::Layout;
use smash::report::render::{DiagnoseContext, Render};
use smash::report::text::shell_word;

use super::progress::job_bar;

/// Arguments of `smash diagnose`.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    smash diagnose --club configs/clubs/paper_driver.toml --shots shots.csv\n  \
    smash diagnose --club club.toml --shots shots.csv --json --out-club diagnosed.toml")]
pub struct DiagnoseArgs {
    /// Club, shots, measurement noise, report formats.
    #[command(flatten)]
    pub inputs: crate::measured::MeasuredArgs,

    /// Write the club with the selected effects, only after success.
    #[arg(long, value_name = "OUT.toml")]
    pub out_club: Option<PathBuf>,

    /// Cross-validation folds (grouped by golfer).
    #[arg(
        long,
        default_value_t = 5,
        value_name = "K",
        help_heading = "Selection",
        allow_negative_numbers = true
    )]
    pub folds: usize,

    /// Most effects to select.
    #[arg(
        long,
        default_value_t = 10,
        value_name = "N",
        help_heading = "Selection",
        allow_negative_numbers = true
    )]
    pub max_steps: usize,

    /// Candidates (default: every library effect, plus added_mass@group and
    /// hosel_mass@group), same syntax as calibrate --effects.
    #[arg(long, value_name = "LIST", help_heading = "Selection")]
    pub candidates: Option<String>,

    /// Every default candidate except these (e.g. face_curvature,added_mass@group): what
    /// diagnose concludes when the library lacks them.
    #[arg(
        long,
        value_name = "LIST",
        help_heading = "Selection",
        conflicts_with = "candidates"
    )]
    pub without: Option<String>,

    /// Iteration limit of each fit.
    #[arg(
        long,
        default_value_t = 100,
        value_name = "N",
        help_heading = "Selection",
        allow_negative_numbers = true,
        value_parser = crate::parse_iterations
    )]
    pub max_iters: u64,

    /// Take the measured impact locations as exact (offer no impact-noise candidate).
    #[arg(
        long,
        conflicts_with = "impact_noise_mm",
        help_heading = "Measurement noise"
    )]
    pub exact_impact_locations: bool,

    /// Instrument class whose documented noise sets the noise floor (camera: camera launch
    /// monitor with marker-based delivery capture; radar: Doppler launch monitor).
    /// Given (or with --noise), selection also stops once the errors are at the noise floor;
    /// without either, the floor is reported for the camera class and only the penalty stops.
    #[arg(
        long,
        value_name = "CLASS",
        value_parser = super::likelihood::parse_instrument,
        help_heading = "Noise floor"
    )]
    pub instrument: Option<InstrumentClass>,

    /// Instrument noise file ([noise] table: instrument, [noise.delivery], [noise.launch]);
    /// overrides --instrument.
    #[arg(long, value_name = "NOISE.toml", help_heading = "Noise floor")]
    pub noise: Option<PathBuf>,
}

struct Bar(ProgressBar);

impl DiagnoseProgress for Bar {
    fn step(&self, step: usize, jobs: usize) {
        self.0.set_length(jobs as u64);
        self.0.set_position(0);
        self.0.set_message(format!("fits of step {step}"));
    }
    fn job_done(&self) {
        self.0.inc(1);
    }
}

/// Run `smash diagnose`.
pub fn run(args: DiagnoseArgs) -> anyhow::Result<()> {
    let crate::measured::Loaded { plan, club, table } = args
        .inputs
        .load_for_fit(args.noise.as_deref(), args.out_club.as_deref())?;
    let named = NamedClub {
        spec: &club,
        path: &args.inputs.club,
    };
    let Prepared { table, conventions } = prepare_table(
        named,
        table,
        (args.inputs.json, true),
        &mut smash::app::StderrNotes,
    )?;
    let bar = Bar(job_bar(1, "fits"));
    let result = smash::app::diagnose::run_prepared(
        &args.settings(),
        named,
        (&args.inputs.shots, &table),
        &mut smash::app::StderrNotes,
        (Some(&bar), None),
    );
    bar.0.finish_and_clear();
    let report = result?;
    let d = &report.diagnosis;
    let left_out = table.left_out_notes();
    for w in d.warnings.iter().filter(|w| !left_out.contains(w)) {
        crate::text::print_note("warning", &smash::data::escape(w));
    }
    let mut staging = plan.stage();
    if let Some(out) = &args.out_club {
        let comment = format!(
            "Club with the effects selected by smash diagnose on {} ({} shots): {}{}",
            args.inputs.shots.display(),
            d.n_shots,
            if d.selected.is_empty() {
                "none".to_owned()
            } else {
                d.selected.join(", ")
            },
            super::mismatch_comment(d.club_mismatch.as_deref())
        );
        staging.file(out, club_toml_checked(&d.club, &comment, out)?.as_bytes())?;
    }
    let cx = DiagnoseContext {
        layout: layout(&args),
        title: format!("{} on {}", club.name, args.inputs.shots.display()),
    };
    if let (Some(path), Some(html)) = (&args.inputs.report, report.html(&cx)) {
        staging.file(path, html?.as_bytes())?;
    }
    staging.commit()?;
    if let Some(out) = &args.out_club {
        eprintln!("club with selected effects -> {}", out.display());
    }
    if let Some(path) = &args.inputs.report {
        eprintln!("report -> {}", path.display());
    }
    match report.json().filter(|_| args.inputs.json) {
        Some(json) => crate::stdout::println(json)?,
        None => crate::stdout::print(format!("{conventions}{}", report.text(&cx)))?,
    }
    Ok(())
}

impl DiagnoseArgs {
    /// The settings these arguments give.
    pub fn settings(&self) -> DiagnoseSettings {
        DiagnoseSettings {
            shots: self.inputs.shots_format.settings(),
            impact_noise_mm: self.inputs.measurement.impact_noise_mm,
            folds: self.folds,
            max_steps: self.max_steps,
            candidates: self.candidates.clone(),
            without: self.without.clone(),
            max_iters: self.max_iters,
            exact_impact_locations: self.exact_impact_locations,
            instrument: self.instrument,
            noise: self.noise.clone(),
            ignore_club_mismatch: self.inputs.club_check.ignore_club_mismatch,
        }
    }
}

/// The layout of `args`' text report.
fn layout(args: &DiagnoseArgs) -> Layout {
    let path = |p: &std::path::Path| shell_word(&p.display().to_string());
    let mut words = vec!["smash".to_owned(), "calibrate".into()];
    if let Some(defs) = &args.inputs.effect_defs.effect_defs {
        words.extend(["--effect-defs".to_owned(), path(defs)]);
    }
    words.extend(["--club".to_owned(), path(&args.inputs.club)]);
    words.extend(["--shots".to_owned(), path(&args.inputs.shots)]);
    let f = &args.inputs.shots_format;
    if let Some(format) = &f.format {
        words.extend(["--format".to_owned(), shell_word(format)]);
    }
    if let Some(side) = f.impact_offset_positive {
        words.extend(["--impact-offset-positive".to_owned(), side.name().into()]);
    }
    for (on, flag) in [
        (f.ignore_unknown_columns, "--ignore-unknown-columns"),
        (f.strict, "--strict"),
        (f.include_estimated, "--include-estimated"),
    ] {
        if on {
            words.push(flag.to_owned());
        }
    }
    if args.inputs.club_check.ignore_club_mismatch {
        words.push("--ignore-club-mismatch".to_owned());
    }
    Layout {
        wide: args.inputs.wide.wide,
        calibrate: words,
    }
}
