//! `smash merge`: combine the shards of a study into exactly the unsharded outputs.

use std::path::{Path, PathBuf};

use clap::Args;

use super::run::TableFormatArg;
use crate::data::write_folder_atomic_with;
use crate::study::metrics::metric_names;
use crate::study::optimise::OptimiseResult;
use crate::study::output::{cell, write_study};
use crate::study::shard::merge_shards;
use crate::study::{finish, Prepared};

/// Arguments of `smash merge`.
#[derive(Debug, Args)]
#[command(
    after_help = "Example:\n  smash merge shards/0 shards/1 shards/2 --out results/com_sweep"
)]
pub struct MergeArgs {
    /// Shard folders written by `smash run --shard k/N` (all N of them, any order).
    #[arg(value_name = "SHARD_DIR", required = true)]
    pub shards: Vec<PathBuf>,

    /// Output folder for the merged result.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,

    /// Format of the long table: `csv` (maps_long.csv, the default) or `parquet`
    /// (maps_long.parquet: typed, compressed, nulls for invalid cells; for large studies,
    /// read with pandas, polars or Arrow). Matrices and pictures are the same either way.
    #[arg(long, value_enum, default_value = "csv")]
    pub format: TableFormatArg,
}

/// Run `smash merge`.
pub fn run(args: MergeArgs) -> anyhow::Result<()> {
    let canon = |p: &std::path::Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_owned());
    if args.shards.iter().any(|s| canon(s) == canon(&args.out)) {
        anyhow::bail!(
            "--out {} is one of the shard folders; write the merged result to another folder",
            args.out.display()
        );
    }
    let inputs: Vec<(&str, &Path)> = args
        .shards
        .iter()
        .map(|s| ("a SHARD_DIR", s.as_path()))
        .collect();
    crate::data::safe_write::refuse_inputs(&[("--out", &args.out, true)], &inputs)?;
    crate::data::safe_write::clean_stale_temporaries(&args.out);
    crate::data::safe_write::check_replaceable(&args.out)?;
    // The shards' face maps go to a scratch file beside the output folder (named as the
    // temporaries a later run cleans up if this one is killed) and are streamed from it.
    let name = args
        .out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "merged".into());
    let parent = match args.out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent)
        .map_err(|e| anyhow::anyhow!("{}: cannot create: {e}", parent.display()))?;
    let scratch = parent.join(format!(".{name}.{}.tmp", std::process::id()));
    let (prepared, metrics, grids) = merge_shards(&args.shards, &scratch)?;
    let (sens, opt) = finish(&prepared, &metrics)?;
    let n_files = write_folder_atomic_with(&args.out, "study.toml", |tmp| {
        write_study(
            tmp,
            &prepared,
            &grids,
            &metrics,
            &sens,
            opt.as_ref(),
            args.format.into(),
        )
    })?;
    print_summary(&prepared, &metrics, opt.as_ref(), &args.out, n_files)?;
    eprintln!("merged {} shard(s)", args.shards.len());
    Ok(())
}

/// A short human summary on stdout: speed retention and gear effect of the first variants, and
/// the optimiser's result.
pub fn print_summary(
    p: &Prepared,
    metrics: &[Vec<f64>],
    opt: Option<&OptimiseResult>,
    dir: &Path,
    n_files: usize,
) -> Result<(), crate::cli::stdout::StdoutError> {
    use std::fmt::Write;
    let mut text = String::new();
    let names = metric_names(p.study.distribution.is_some());
    let pick = [
        "cof_ball_speed_mph",
        "speed_loss_toe_mph_per_mm",
        "speed_loss_heel_mph_per_mm",
        "speed_loss_crown_mph_per_mm",
        "speed_loss_sole_mph_per_mm",
        "gear_sidespin_rpm_per_mm",
        "gear_backspin_rpm_per_mm",
    ];
    // Writing to a String cannot fail.
    let _ = writeln!(
        text,
        "study '{}' ({}, group {}): {} variant(s)",
        p.study.name,
        p.study.club.name,
        p.study.group,
        metrics.len()
    );
    for (i, (d, m)) in p.variants.iter().zip(metrics).enumerate().take(5) {
        let mut line = format!("  variant {i} ({}):", d.describe());
        for k in pick {
            if let Some(j) = names.iter().position(|n| n == k) {
                line.push_str(&format!(" {k} = {:.4}", m[j]));
            }
        }
        let _ = writeln!(text, "{line}");
    }
    if metrics.len() > 5 {
        let _ = writeln!(text, "  … see variants.csv");
    }
    if let Some(o) = opt {
        let gain = o.best_objective - o.base_objective;
        let _ = writeln!(
            text,
            "optimum: {} — objective {} -> {} (change {}, {:.3} %), {} iterations, {} evaluations, {}",
            o.best.describe(),
            cell(o.base_objective),
            cell(o.best_objective),
            cell(gain),
            100.0 * gain / o.base_objective.abs().max(f64::MIN_POSITIVE),
            o.path.last().map_or(0, |p| p.iteration),
            o.evaluations,
            o.termination
        );
    }
    let _ = writeln!(text, "wrote {n_files} file(s) to {}", dir.display());
    crate::cli::stdout::print(text)
}
