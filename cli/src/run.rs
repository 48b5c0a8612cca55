//! `smash run`: run a design study (or one shard of it) and write its outputs.

use std::path::PathBuf;

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::study_output::TableFormatArg;
use smash::app::study::{Progress, StudyRun, StudySettings};
use smash::study::shard::parse_shard_spec;

/// Arguments of `smash run`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  smash run configs/studies/face_map.toml\n  \
                        smash run configs/studies/com_sweep.toml --out /tmp/com_sweep\n  \
                        smash run configs/studies/com_sweep.toml --shard 0/4 --out shards/0\n  \
                        smash merge shards/0 shards/1 shards/2 shards/3 --out results/com_sweep"
)]
pub struct RunArgs {
    /// User-defined effects.
    #[command(flatten)]
    pub effect_defs: super::EffectDefsArgs,

    /// Study file (TOML): base club, delivery, face grid, design variants, outputs.
    #[arg(value_name = "STUDY.toml")]
    pub study: PathBuf,

    /// Output folder [default: the study's output_dir, results/<name>; for a shard,
    /// <that>/shards/<k>_of_<N>].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Run only shard k of N (0-based k, e.g. $SLURM_ARRAY_TASK_ID/N) and write shard files;
    /// combine the shards with `smash merge`.
    #[arg(long, value_name = "k/N", value_parser = parse_shard_spec, allow_hyphen_values = true)]
    pub shard: Option<(usize, usize)>,

    /// Format of the long table: `csv` (maps_long.csv, the default) or `parquet`
    /// (maps_long.parquet: typed, compressed, nulls for invalid cells; for large studies,
    /// read with pandas, polars or Arrow). Matrices and pictures are the same either way.
    #[arg(long, value_enum, default_value = "csv")]
    pub format: TableFormatArg,
    /// Also write a self-contained HTML report of the study: a summary, the face maps of the
    /// variants on shared colour scales and their differences from the base, the tables.
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,

    /// Print the study's report as one JSON object on stdout instead of the text summary
    /// (which goes to stderr).
    #[arg(long)]
    pub json: bool,

    /// `--wide`: one line per variant with every metric, the yards table on one line per row.
    #[command(flatten)]
    pub wide: crate::text::WideArgs,
}

impl RunArgs {
    /// The settings these arguments give.
    pub fn settings(&self) -> StudySettings {
        StudySettings {
            study: self.study.clone(),
            out: self.out.clone(),
            shard: self.shard,
            format: self.format.into(),
            report: self.report.clone(),
        }
    }
}

/// A progress bar for the work items of a shard (hidden for small runs).
#[derive(Default)]
struct Bar(std::sync::OnceLock<ProgressBar>);

impl Progress for Bar {
    fn start(&self, items: usize, impacts: usize) {
        let _ = self.0.set(progress_bar(items, impacts));
    }
    fn item_done(&self) {
        if let Some(b) = self.0.get() {
            b.inc(1);
        }
    }
    fn finish(&self) {
        if let Some(b) = self.0.get() {
            b.finish_and_clear();
        }
    }
}

/// Run `smash run`.
pub fn run(args: RunArgs) -> anyhow::Result<()> {
    args.effect_defs.load()?;
    match smash::app::study::run(&args.settings(), args.wide.wide, &Bar::default())? {
        StudyRun::Shard { lines } => eprint!("{lines}"),
        StudyRun::Whole {
            report,
            dir,
            n_files,
            yards_summary,
            timing,
        } => {
            if let Some(text) = yards_summary {
                eprint!("{text}");
            }
            if let Some(path) = &args.report {
                eprintln!("report -> {}", path.display());
            }
            crate::study_output::print_summary(&report, &dir, n_files, args.wide.wide, args.json)?;
            eprint!("{timing}");
        }
    }
    Ok(())
}

/// A progress bar for `items` work items of `impacts` impacts (hidden for small runs).
fn progress_bar(items: usize, impacts: usize) -> ProgressBar {
    if items < 64 || impacts < 50_000 {
        return ProgressBar::hidden();
    }
    let b = ProgressBar::with_draw_target(Some(items as u64), ProgressDrawTarget::stderr());
    b.set_style(
        ProgressStyle::with_template(
            "{bar:40} {pos}/{len} work items, {elapsed} elapsed, ETA {eta}",
        )
        .expect("static template"),
    );
    b
}
