//! `smash merge`: combine the shards of a study into exactly the unsharded outputs.

use std::path::{Path, PathBuf};

use clap::Args;

use crate::study_output::{print_summary, TableFormatArg};
use smash::data::output_plan::OutputPlan;
use smash::study::finish;
use smash::study::output::write_study_maps;
use smash::study::report::{RunResults, StudyReport};
use smash::study::shard::merge_shards;

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

    /// `--wide`: one line per variant with every metric.
    #[command(flatten)]
    pub wide: crate::text::WideArgs,

    /// Print the merged study's report as one JSON object on stdout (as `smash run --json`)
    /// instead of the text summary (which goes to stderr).
    #[arg(long)]
    pub json: bool,

    /// The user-defined effects the shards were run with (`smash run --effect-defs`).
    #[command(flatten)]
    pub effect_defs: super::EffectDefsArgs,
}

/// Run `smash merge`.
pub fn run(args: MergeArgs) -> anyhow::Result<()> {
    args.effect_defs.load()?;
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
    let plan = OutputPlan::new(&inputs).folder("--out", Some(&args.out));
    plan.check()?;
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
    smash::data::output_plan::register_temporary(&scratch);
    let merged = merge_shards(&args.shards, &scratch);
    smash::data::output_plan::forget_temporary(&scratch);
    // A failure of the scratch file (a full disk) is a failure to write the output folder:
    // name that, not the hidden file beside it.
    let hidden = |e: anyhow::Error| {
        anyhow::anyhow!(super::error_chain(&e).replace(
            &scratch.display().to_string(),
            &format!("{} (its scratch file)", args.out.display())
        ))
    };
    let (prepared, metrics, grids) = merged.map_err(|e| hidden(e.into()))?;
    let (sens, opt) = finish(&prepared, &metrics)?;
    let mut staging = plan.stage();
    let mut face_maps = Vec::new();
    let n_files = staging
        .folder_with(&args.out, |tmp| {
            let (n, maps) = write_study_maps(
                tmp,
                &prepared,
                &grids,
                (&metrics, &sens, opt.as_ref()),
                args.format.into(),
            )?;
            face_maps = maps;
            Ok(n)
        })
        .map_err(|e| hidden(e.into()))?;
    staging.commit()?;
    let report = StudyReport::new(
        &prepared,
        &RunResults {
            metrics: &metrics,
            face_maps: &face_maps,
            sensitivities: &sens,
            optimiser: opt.as_ref(),
            yards: None,
        },
    );
    print_summary(&report, &args.out, n_files, args.wide.wide, args.json)?;
    eprintln!("merged {} shard(s)", args.shards.len());
    Ok(())
}
