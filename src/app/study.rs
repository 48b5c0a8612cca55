//! `run`: a design study (or one shard of it) computed and its outputs written: the maps,
//! summaries, sensitivities, optimiser and yard part into its output folder, and the HTML
//! report.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::data::output_plan::OutputPlan;
use crate::study::output::{write_study_maps, TableFormat};
use crate::study::report::{RunResults, StudyReport};
use crate::study::shard::shard_files;
use crate::study::{finish, read_study, Prepared, Study, StudyError};

/// Settings of `run`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudySettings {
    /// The study file (TOML).
    pub study: PathBuf,
    /// Output folder (default: the study's `output_dir`; for a shard, `<that>/shards/<k>_of_<N>`).
    #[serde(default)]
    pub out: Option<PathBuf>,
    /// Run only shard `k` of `N` (0-based `k`).
    #[serde(default)]
    pub shard: Option<(usize, usize)>,
    /// Format of the long table.
    #[serde(default)]
    pub format: TableFormat,
    /// The HTML report to write beside the output folder.
    #[serde(default)]
    pub report: Option<PathBuf>,
}

/// What a study run wrote.
pub enum StudyRun {
    /// The whole study.
    Whole {
        /// The report (what `--json` prints).
        report: Box<StudyReport>,
        /// The output folder.
        dir: PathBuf,
        /// How many files it holds.
        n_files: usize,
        /// The yard part's text summary, when the study has one.
        yards_summary: Option<String>,
        /// The closing line: impacts, files and time.
        timing: String,
    },
    /// One shard.
    Shard {
        /// What it wrote and how fast, a line each.
        lines: String,
    },
}

/// What a finished run (or a merge) says: the report's text summary, then where its `n_files`
/// files went (`dir`); `wide`: one line per variant with every metric.
pub fn summary_text(report: &StudyReport, dir: &Path, n_files: usize, wide: bool) -> String {
    use crate::report::render::Render;
    let mut text = report.text(&crate::study::report::StudyContext { wide });
    text.push_str(&crate::report::text::wrap_long(&format!(
        "wrote {n_files} file(s) to {}\n",
        dir.display()
    )));
    text
}

/// The long work of a study, for a progress display: [`Progress::start`] once with the work
/// items and impacts, [`Progress::item_done`] after each item, [`Progress::finish`] at the end.
pub trait Progress: Sync {
    /// The work begins: `items` work items of `impacts` impacts in all.
    fn start(&self, items: usize, impacts: usize);
    /// One work item is done.
    fn item_done(&self);
    /// The work is over.
    fn finish(&self);
}

/// No progress display.
pub struct Quiet;

impl Progress for Quiet {
    fn start(&self, _: usize, _: usize) {}
    fn item_done(&self) {}
    fn finish(&self) {}
}

/// Run the study of `settings` (its user effects registered before), writing its outputs.
pub fn run(
    settings: &StudySettings,
    wide: bool,
    progress: &dyn Progress,
) -> anyhow::Result<StudyRun> {
    let study = read_study(&settings.study)?;
    let (k, n) = settings.shard.unwrap_or((0, 1));
    let dir = match (&settings.out, settings.shard) {
        (Some(d), _) => d.clone(),
        (None, Some(_)) => study.output_dir.join("shards").join(format!("{k}_of_{n}")),
        (None, None) => study.output_dir.clone(),
    };
    let plan = refuse_outputs(settings, &study, &dir)?;
    let prepared = Prepared::new(study).map_err(|e| locate_swing_error(&settings.study, e))?;
    // Start the worker threads before the clock: the closing line states the sweep's rate, not
    // the thread pool's start-up.
    rayon::broadcast(|_| ());
    match settings.shard {
        Some((k, n)) => run_shard(settings, &prepared, &plan, &dir, (k, n), progress),
        None => run_whole(settings, &prepared, &plan, &dir, wide),
    }
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
    crate::data::DataError::at(
        study,
        line,
        Some("table [delivery]".into()),
        problem.clone(),
    )
    .into()
}

/// Refuse before the sweep, not after it: the output folder may not hold the inputs or files
/// smash did not write, and the report may not lie inside the output folder. Returns the checked
/// plan of the outputs.
fn refuse_outputs(
    settings: &StudySettings,
    study: &Study,
    dir: &Path,
) -> anyhow::Result<OutputPlan> {
    let inputs = [
        ("STUDY.toml", settings.study.as_path()),
        ("the study's club", study.club_path.as_path()),
    ];
    let out_name = if settings.out.is_some() {
        "--out"
    } else {
        "the study's output folder"
    };
    if let Some(report) = &settings.report {
        // The output folder is replaced as a whole and holds only what smash lists in it.
        if crate::data::safe_write::canonical(report)
            .starts_with(crate::data::safe_write::canonical(dir))
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
        .file("--report", settings.report.as_deref());
    plan.check()?;
    Ok(plan)
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
    settings: &StudySettings,
    prepared: &Prepared,
    plan: &OutputPlan,
    dir: &Path,
    (k, n): (usize, usize),
    progress: &dyn Progress,
) -> anyhow::Result<StudyRun> {
    if prepared.study.yards.is_some() {
        anyhow::bail!(
            "{}: a study with [yards] cannot be sharded (its yard maps and optimisation run \
             once over the whole grid); run it without --shard",
            settings.study.display()
        );
    }
    // Shards are only useful if they can be merged: refuse before computing any.
    crate::study::shard::check_mergeable(prepared)?;
    let items = prepared.shard_range(k, n);
    let impacts = prepared.impacts_in(items.clone());
    let nz = prepared.zs_mm.len() as u128;
    let points = items.len() as u128 * nz; // at most one metrics item per variant besides rows
    if points > crate::study::MAX_SHARD_POINTS {
        let total = prepared.work_len() as u128 * nz;
        return Err(StudyError::ShardTooLarge {
            k,
            n,
            points,
            min_shards: total.div_ceil(crate::study::MAX_SHARD_POINTS),
        }
        .into());
    }
    progress.start(items.len(), impacts);
    // The output slots are allocated (and their pages touched) before the clock.
    let mut results = prepared.allocate(items.clone());
    let start = Instant::now();
    prepared.compute_into(&mut results, &|| progress.item_done());
    let seconds = start.elapsed().as_secs_f64();
    progress.finish();
    let mut staging = plan.stage();
    staging.folder(dir, &shard_files(prepared, k, n, &results)?)?;
    staging.commit()?;
    Ok(StudyRun::Shard {
        lines: format!(
            "shard {k} of {n}: work items {}..{} -> {}\n\
             swept {impacts} impact evaluations ({}, shard {k} of {n})\n  in {seconds:.3} s: \
             {:.0} impacts/s\n",
            items.start,
            items.end,
            dir.display(),
            grid_text(prepared),
            impacts as f64 / seconds.max(1e-9)
        ),
    })
}

/// The whole study: the maps computed band by band as they are written (bounded memory), the
/// yard part, the report.
fn run_whole(
    settings: &StudySettings,
    prepared: &Prepared,
    plan: &OutputPlan,
    dir: &Path,
    wide: bool,
) -> anyhow::Result<StudyRun> {
    let impacts = prepared.impacts_in(0..prepared.work_len());
    let start = Instant::now();
    let metrics = prepared.all_metrics();
    let (sens, opt) = finish(prepared, &metrics)?;
    let yards = match &prepared.study.yards {
        Some(_) => Some(
            crate::study::yards_run::run_yards(&prepared.study, opt.as_ref().map(|o| &o.best))
                .map_err(|e| anyhow::anyhow!("{}: {e}", settings.study.display()))?,
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
            settings.format,
        )?;
        face_maps = maps;
        Ok(n + match &yards {
            Some(r) => write_yards(tmp, prepared, r)?,
            None => 0,
        })
    })?;
    let yards_summary = yards
        .as_ref()
        .map(|r| crate::study::yards_run::yards_summary(&prepared.study, r, wide));
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
    if let Some(path) = &settings.report {
        use crate::report::render::Render;
        let cx = crate::study::report::StudyContext { wide };
        if let Some(html) = report.html(&cx) {
            staging.file(path, html?.as_bytes())?;
        }
    }
    staging.commit()?;
    let timing = format!(
        "swept {impacts} impact evaluations ({})\n  and wrote {n_files} file(s) in {seconds:.3} s \
         (face-map kernel: {} impacts in {:.3} s, {:.0} impacts/s)\n",
        grid_text(prepared),
        kernels.points(),
        kernels.seconds(),
        kernels.points() as f64 / kernels.seconds().max(1e-9)
    );
    Ok(StudyRun::Whole {
        report: Box::new(report),
        dir: dir.to_owned(),
        n_files,
        yards_summary,
        timing,
    })
}

/// The yard part's files under `tmp`; returns how many.
fn write_yards(
    tmp: &Path,
    prepared: &Prepared,
    r: &crate::study::yards_run::YardsResult,
) -> std::io::Result<usize> {
    let files = crate::study::yards_run::yards_files(&prepared.study, r);
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
