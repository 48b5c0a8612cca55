//! `smash compare`: the model against measurements, as a diagnosis.

use std::path::PathBuf;

use clap::Args;

use smash::app::compare::{title, CompareRun, CompareSettings};
use smash::app::inputs::{prepare_table, NamedClub, Prepared};
use smash::report::compare::compare_files;
use smash::report::render::{CompareContext, Render};

/// Arguments of `smash compare`.
#[derive(Debug, Args)]
#[command(
    after_help = "Example:\n  smash compare --club configs/clubs/paper_driver.toml --shots paper_world.csv --out-dir compare/"
)]
pub struct CompareArgs {
    /// Club, shots, measurement noise, report formats.
    #[command(flatten)]
    pub inputs: crate::measured::MeasuredArgs,

    /// Folder for the tables, face pictures and JSON (created). Nothing is written without it.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,

    /// Significance level of the flags.
    #[arg(
        long,
        default_value_t = 0.01,
        value_name = "P",
        help_heading = "Statistics",
        allow_negative_numbers = true
    )]
    pub alpha: f64,

    /// Side of a face bin, mm.
    #[arg(
        long,
        default_value_t = 5.0,
        value_name = "MM",
        help_heading = "Statistics",
        allow_negative_numbers = true
    )]
    pub bin_mm: f64,

    /// Face bins with fewer shots are left empty.
    #[arg(
        long,
        default_value_t = 5,
        value_name = "N",
        help_heading = "Statistics",
        allow_negative_numbers = true
    )]
    pub min_bin_count: usize,
}

impl CompareArgs {
    /// The settings these arguments give.
    pub fn settings(&self) -> CompareSettings {
        CompareSettings {
            shots: self.inputs.shots_format.settings(),
            impact_noise_mm: self.inputs.measurement.impact_noise_mm,
            alpha: self.alpha,
            bin_mm: self.bin_mm,
            min_bin_count: self.min_bin_count,
            ignore_club_mismatch: self.inputs.club_check.ignore_club_mismatch,
        }
    }
}

/// Run `smash compare`.
pub fn run(args: CompareArgs) -> anyhow::Result<()> {
    let settings = args.settings();
    let crate::measured::Loaded { plan, club, table } = args.inputs.load(
        &[],
        |p| p.folder("--out-dir", args.out_dir.as_deref()),
        || settings.check(),
    )?;
    let named = NamedClub {
        spec: &club,
        path: &args.inputs.club,
    };
    let prepared = prepare_table(named, table, (false, false), &mut smash::app::StderrNotes)?;
    let CompareRun { report, launches } = smash::app::compare::run_prepared(
        &settings,
        named,
        &args.inputs.shots,
        &prepared,
        &mut smash::app::StderrNotes,
    )?;
    let Prepared { table, conventions } = prepared;
    let cx = CompareContext {
        title: title(&club.name, &args.inputs.shots, table.groups().len()),
        wide: args.inputs.wide.wide,
        residuals: args
            .inputs
            .report
            .as_ref()
            .map(|_| smash::report::html::ShotResiduals::new(&table.shots, &launches)),
    };
    let mut text = report.text(&cx);
    if !conventions.is_native() {
        text = format!("{}{text}", conventions);
    }
    let files = args.out_dir.as_ref().map(|_| compare_files(&report, &text));
    match report.json().filter(|_| args.inputs.json) {
        Some(json) => {
            eprint!("{text}");
            crate::stdout::println(json)?;
        }
        None => crate::stdout::print(&text)?,
    }
    let mut staging = plan.stage();
    if let (Some(path), Some(html)) = (&args.inputs.report, report.html(&cx)) {
        staging.file(path, html?.as_bytes())?;
    }
    let n_files = files.as_ref().map_or(0, Vec::len);
    if let (Some(dir), Some(files)) = (&args.out_dir, files) {
        let files: Vec<(PathBuf, Vec<u8>)> = files
            .into_iter()
            .map(|(n, b)| (PathBuf::from(n), b))
            .collect();
        staging.folder(dir, &files)?;
    }
    staging.commit()?;
    if let Some(path) = &args.inputs.report {
        eprintln!("report -> {}", path.display());
    }
    if let Some(dir) = &args.out_dir {
        eprintln!("wrote {n_files} files to {}", dir.display());
    }
    Ok(())
}
