//! `smash compare`: the model against measurements, as a diagnosis.

use std::path::PathBuf;

use anyhow::bail;
use clap::Args;
use smash::limits::fmt_value;

use smash::compare::CompareReport;
use smash::compare::{compare_with_hints, CompareOptions};
use smash::data::shots::ShotTable;
use smash::physics::{Launch, LaunchComponent};
use smash::predict::expected_launches;
use smash::report::compare::{compare_files, compare_json, compare_text};
use smash::ClubSpec;

/// Smallest `--alpha` accepted: a significance level far below any multiple-testing correction
/// a comparison of a few components needs (and printed short in the report's header).
const MIN_ALPHA: f64 = 1e-9;
/// Largest `--alpha` accepted: above one half, a test flags an unbiased component more often
/// than not.
const MAX_ALPHA: f64 = 0.5;

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

/// Run `smash compare`.
pub fn run(args: CompareArgs) -> anyhow::Result<()> {
    let crate::measured::Loaded {
        plan,
        club,
        mut table,
    } = args.inputs.load(
        &[],
        |p| p.folder("--out-dir", args.out_dir.as_deref()),
        || check_options(&args),
    )?;
    let conventions = super::to_model_convention(&club, &mut table, false, false)?;
    super::warn_groups_without_effects(&args.inputs.club, &club, &table.shots);
    let (mut report, launches) = compute(&args, &club, &table)?;
    if conventions.derived_face > 0 {
        // Those shots' face angles are the model's for their measured launch direction: an
        // azimuth finding, or a trend against that face angle, would describe the monitor's
        // formula and the launch's noise, not the head.
        smash::conventions::drop_derived_findings(&mut report.findings);
    }
    let title = format!(
        "{} vs {} ({})",
        club.name,
        args.inputs.shots.display(),
        super::counted(table.groups().len(), "group")
    );
    let mut text = text(&report, &title, args.inputs.wide.wide);
    if !conventions.is_native() {
        text = format!("{}{text}", conventions);
    }
    let files = args.out_dir.as_ref().map(|_| compare_files(&report, &text));
    if args.inputs.json {
        eprint!("{text}");
        crate::stdout::println(compare_json(&report))?;
    } else {
        crate::stdout::print(&text)?;
    }
    let mut staging = plan.stage();
    if let Some(path) = &args.inputs.report {
        let residuals = smash::report::html::ShotResiduals::new(&table.shots, &launches);
        let html = smash::report::html::compare_page(&report, &residuals, &title)
            .map_err(anyhow::Error::msg)?;
        staging.file(path, html.as_bytes())?;
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

/// The text report, headed by `NO FINDINGS` when the shots do not match the club; `wide`: Table
/// 2 in one block however many groups.
pub fn text(report: &CompareReport, title: &str, wide: bool) -> String {
    let title = crate::text::wrap_long(title);
    let text = compare_text(report, title.trim_end(), wide);
    match &report.club_mismatch {
        Some(why) => {
            crate::text::wrap_long(&format!(
                "NO FINDINGS: the shots do not match the club ({why}); the tables below describe \
             errors of another club's shots, not of this head\n"
            )) + &text
        }
        None => text,
    }
}

/// The comparison of `table` with `club` under `args`' options (its `--club` and `--shots`
/// only name them in messages) and the model's launch of every shot, after the club check
/// (which refuses shots of another club unless `--ignore-club-mismatch`; the report then says
/// why and has no findings). What `run` reports.
pub fn compute(
    args: &CompareArgs,
    club: &ClubSpec,
    table: &ShotTable,
) -> anyhow::Result<(CompareReport, Vec<Launch>)> {
    check_options(args)?;
    let mismatch =
        args.inputs
            .club_check
            .check(&args.inputs.club, club, &args.inputs.shots, &table.shots)?;
    if !table.has_measurements() {
        let cols: Vec<&str> = LaunchComponent::ALL.iter().map(|c| c.column()).collect();
        bail!(
            "{}: no measured launch columns ({}); compare needs measurements (to predict only, use `smash predict`)",
            args.inputs.shots.display(),
            cols.join(", ")
        );
    }
    let launches = expected_launches(club, &table.shots, args.inputs.measurement.impact_noise_mm)
        .map_err(|e| super::locate_shot_error(table, e))?;
    if let Some((shot, _)) = table
        .shots
        .iter()
        .zip(&launches)
        .find(|(_, l)| !l.is_finite())
    {
        bail!(
            "{}: shot '{}': the model's launch is not a finite number; check its delivery and \
             the club {}",
            args.inputs.shots.display(),
            shot.id,
            args.inputs.club.display()
        );
    }
    let options = CompareOptions {
        alpha: args.alpha,
        face_bin_mm: args.bin_mm,
        min_bin_count: args.min_bin_count,
        ..CompareOptions::default()
    };
    // Hints at the user-defined effects (of --effect-defs and the club file), from their
    // signatures measured on these shots.
    let user =
        smash::compare::UserHints::measure(club, &table.shots, &smash::effects::user::registered());
    let report = compare_with_hints(&table.shots, &launches, &options, &user)?;
    let mut report = match mismatch {
        Some(why) => report.mismatched(why),
        None => report,
    };
    report.warnings = table.left_out_notes();
    Ok((report, launches))
}

/// Refuse a significance level or face bin outside their ranges (before any file is read).
pub fn check_options(args: &CompareArgs) -> anyhow::Result<()> {
    if !(args.alpha >= MIN_ALPHA && args.alpha <= MAX_ALPHA) {
        bail!(
            "--alpha {}: must be within [{}, {}] (a level above one half flags unbiased \
             components half the time; one below 1e-9 flags no bias a launch monitor can show)",
            fmt_value(args.alpha),
            fmt_value(MIN_ALPHA),
            fmt_value(MAX_ALPHA)
        );
    }
    if !smash::compare::FACE_BIN_MM.contains(&args.bin_mm) {
        bail!(
            "--bin-mm {}: must be within [0.5, 100] mm (impact locations are measured to about a \
             millimetre, and a bin larger than the face holds every shot)",
            fmt_value(args.bin_mm)
        );
    }
    Ok(())
}
