//! `smash run`: run a design study (or one shard of it) and write its outputs.

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::study_output::TableFormatArg;
use smash::data::output_plan::OutputPlan;
use smash::study::output::write_study_maps;
use smash::study::report::{RunResults, StudyReport};
use smash::study::shard::{parse_shard_spec, shard_files};
use smash::study::{finish, read_study, Prepared, Study, StudyError};

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

/// A swing that does not reach the ball is a problem of the study's `[delivery]` table: name the
/// file and the table's line.
fn locate_swing_error(study: &Path, e: StudyError) -> anyhow::Error {
    let StudyError::Swing { problem } = &e else {
        return e.into();
    };
    let line = std::fs::read_to_string(study).ok().and_then(|text| {
        text.lines()
            .position(|l| l.trim_start().starts_with("[delivery]"))
            .map(|i| i + 1)
    });
    smash::data::DataError::at(
        study,
        line,
        Some("table [delivery]".into()),
        problem.clone(),
    )
    .into()
}

/// Run `smash run`.
pub fn run(args: RunArgs) -> anyhow::Result<()> {
    args.effect_defs.load()?;
    let study = read_study(&args.study)?;
    let (k, n) = args.shard.unwrap_or((0, 1));
    let dir = match (&args.out, args.shard) {
        (Some(d), _) => d.clone(),
        (None, Some(_)) => study.output_dir.join("shards").join(format!("{k}_of_{n}")),
        (None, None) => study.output_dir.clone(),
    };
    let plan = refuse_outputs(&args, &study, &dir)?;
    let prepared = Prepared::new(study).map_err(|e| locate_swing_error(&args.study, e))?;
    // Start the worker threads before the clock: the closing line states the sweep's rate, not
    // the thread pool's start-up.
    rayon::broadcast(|_| ());
    match args.shard {
        Some((k, n)) => run_shard(&args, &prepared, &plan, &dir, (k, n)),
        None => run_whole(&args, &prepared, &plan, &dir),
    }
}

/// Refuse before the sweep, not after it: the output folder may not hold the inputs or files
/// smash did not write, and the report may not lie inside the output folder. Returns the checked
/// plan of the outputs.
fn refuse_outputs(args: &RunArgs, study: &Study, dir: &Path) -> anyhow::Result<OutputPlan> {
    let inputs = [
        ("STUDY.toml", args.study.as_path()),
        ("the study's club", study.club_path.as_path()),
    ];
    let out_name = if args.out.is_some() {
        "--out"
    } else {
        "the study's output folder"
    };
    if let Some(report) = &args.report {
        // The output folder is replaced as a whole and holds only what smash lists in it.
        if smash::data::safe_write::canonical(report)
            .starts_with(smash::data::safe_write::canonical(dir))
        {
            anyhow::bail!(
                "{}: --report is inside the study's output folder {}, which each run replaces \
                 as a whole; write the report beside it",
                report.display(),
                dir.display()
            );
        }
    }
    let plan = OutputPlan::new(&inputs)
        .folder(out_name, Some(dir))
        .file("--report", args.report.as_deref());
    plan.check()?;
    Ok(plan)
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

/// `variants × rows × columns + summary metrics`, for the closing line.
fn grid_text(p: &Prepared) -> String {
    format!(
        "{} variant(s) × {}×{} grid + summary metrics",
        p.variants.len(),
        p.ys_mm.len(),
        p.zs_mm.len()
    )
}

/// Shard `k` of `n`: its work items computed in memory and written as shard files.
fn run_shard(
    args: &RunArgs,
    prepared: &Prepared,
    plan: &OutputPlan,
    dir: &Path,
    (k, n): (usize, usize),
) -> anyhow::Result<()> {
    if prepared.study.yards.is_some() {
        anyhow::bail!(
            "{}: a study with [yards] cannot be sharded (its yard maps and optimisation run \
             once over the whole grid); run it without --shard",
            args.study.display()
        );
    }
    // Shards are only useful if they can be merged: refuse before computing any.
    smash::study::shard::check_mergeable(prepared)?;
    let items = prepared.shard_range(k, n);
    let impacts = prepared.impacts_in(items.clone());
    let nz = prepared.zs_mm.len() as u128;
    let points = items.len() as u128 * nz; // at most one metrics item per variant besides rows
    if points > smash::study::MAX_SHARD_POINTS {
        let total = prepared.work_len() as u128 * nz;
        return Err(StudyError::ShardTooLarge {
            k,
            n,
            points,
            min_shards: total.div_ceil(smash::study::MAX_SHARD_POINTS),
        }
        .into());
    }
    let bar = progress_bar(items.len(), impacts);
    // The output slots are allocated (and their pages touched) before the clock.
    let mut results = prepared.allocate(items.clone());
    let start = Instant::now();
    prepared.compute_into(&mut results, &|| bar.inc(1));
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let mut staging = plan.stage();
    staging.folder(dir, &shard_files(prepared, k, n, &results)?)?;
    staging.commit()?;
    eprintln!(
        "shard {k} of {n}: work items {}..{} -> {}",
        items.start,
        items.end,
        dir.display()
    );
    eprintln!(
        "swept {impacts} impact evaluations ({}, shard {k} of {n})\n  in {seconds:.3} s: {:.0} impacts/s",
        grid_text(prepared),
        impacts as f64 / seconds.max(1e-9)
    );
    Ok(())
}

/// The whole study: the maps computed band by band as they are written (bounded memory), the
/// yard part, the report.
fn run_whole(
    args: &RunArgs,
    prepared: &Prepared,
    plan: &OutputPlan,
    dir: &Path,
) -> anyhow::Result<()> {
    let impacts = prepared.impacts_in(0..prepared.work_len());
    let start = Instant::now();
    let metrics = prepared.all_metrics();
    let (sens, opt) = finish(prepared, &metrics)?;
    let yards = match &prepared.study.yards {
        Some(_) => Some(
            smash::study::yards_run::run_yards(&prepared.study, opt.as_ref().map(|o| &o.best))
                .map_err(|e| anyhow::anyhow!("{}: {e}", args.study.display()))?,
        ),
        None => None,
    };
    let kernels = prepared.kernels();
    let mut staging = plan.stage();
    let mut face_maps = Vec::new();
    let n_files = staging.folder_with(dir, |tmp| {
        let (n, maps) = write_study_maps(
            tmp,
            prepared,
            &kernels,
            (&metrics, &sens, opt.as_ref()),
            args.format.into(),
        )?;
        face_maps = maps;
        Ok(n + match &yards {
            Some(r) => write_yards(tmp, prepared, r)?,
            None => 0,
        })
    })?;
    if let Some(r) = &yards {
        eprint!(
            "{}",
            smash::study::yards_run::yards_summary(&prepared.study, r, args.wide.wide)
        );
    }
    let seconds = start.elapsed().as_secs_f64();
    let report = StudyReport::new(
        prepared,
        &RunResults {
            metrics: &metrics,
            face_maps: &face_maps,
            sensitivities: &sens,
            optimiser: opt.as_ref(),
            yards: yards.as_ref(),
        },
    );
    if let Some(path) = &args.report {
        let html = smash::study::report::html::page(&report).map_err(anyhow::Error::msg)?;
        staging.file(path, html.as_bytes())?;
    }
    staging.commit()?;
    if let Some(path) = &args.report {
        eprintln!("report -> {}", path.display());
    }
    crate::study_output::print_summary(&report, dir, n_files, args.wide.wide, args.json)?;
    eprintln!(
        "swept {impacts} impact evaluations ({})\n  and wrote {n_files} file(s) in {seconds:.3} s \
         (face-map kernel: {} impacts in {:.3} s, {:.0} impacts/s)",
        grid_text(prepared),
        kernels.points(),
        kernels.seconds(),
        kernels.points() as f64 / kernels.seconds().max(1e-9)
    );
    Ok(())
}

/// The yard part's files under `tmp`; returns how many.
fn write_yards(
    tmp: &Path,
    prepared: &Prepared,
    r: &smash::study::yards_run::YardsResult,
) -> std::io::Result<usize> {
    let files = smash::study::yards_run::yards_files(&prepared.study, r);
    for (rel, bytes) in &files {
        let path = tmp.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)?;
        }
        std::fs::write(&path, bytes)
            .map_err(|e| std::io::Error::new(e.kind(), format!("{}: {e}", rel.display())))?;
    }
    Ok(files.len())
}
