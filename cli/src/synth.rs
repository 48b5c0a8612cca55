//! `smash synth`: generate a synthetic experiment from a configuration.

use std::path::{Path, PathBuf};

use clap::Args;

use smash::data::write_files_atomic;
use smash::synth::files::{synth_shots_csv, truth_toml};

/// Arguments of `smash synth`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  smash synth --config configs/synth/paper_world.toml --out paper_world.csv --truth paper_world.truth.toml\n  \
                  smash synth --config configs/synth/null_world.toml --out null.csv --seed 7"
)]
pub struct SynthArgs {
    /// User-defined effects.
    #[command(flatten)]
    pub effect_defs: super::EffectDefsArgs,

    /// Synthetic-experiment configuration (TOML; see configs/synth/README.md).
    #[arg(long, value_name = "CONFIG.toml")]
    pub config: PathBuf,

    /// Shots file to write (CSV: delivery as measured, launch as measured).
    #[arg(long, value_name = "SHOTS.csv")]
    pub out: PathBuf,

    /// Truth file to write (TOML: hidden effects, world physics, seed, resolved configuration).
    #[arg(long, value_name = "TRUTH.toml")]
    pub truth: Option<PathBuf>,

    /// Random seed (overrides the configuration's `seed`): 0 to 2^63 − 1, the range a TOML
    /// integer holds, so that the truth file records it and regenerates the same shots.
    #[arg(long, value_name = "N", allow_negative_numbers = true,
          value_parser = clap::value_parser!(u64).range(0..=i64::MAX as u64))]
    pub seed: Option<u64>,
}

/// Run `smash synth`.
pub fn run(args: SynthArgs) -> anyhow::Result<()> {
    args.effect_defs.load()?;
    let mut outputs = vec![("--out", args.out.as_path(), false)];
    if let Some(t) = &args.truth {
        outputs.push(("--truth", t.as_path(), false));
    }
    smash::data::safe_write::refuse_inputs(&outputs, &[("--config", &args.config)])?;
    let (cfg, run) = generate_world(&args.config, args.seed)?;
    smash::data::safe_write::refuse_inputs(&outputs, &[("the configuration's club", &cfg.club)])?;
    let csv = synth_shots_csv(&run);
    let truth = args
        .truth
        .as_ref()
        .map(|_| truth_toml(&cfg, &run, &args.config.display().to_string()));
    // Both outputs appear together or not at all.
    let mut files: Vec<(&Path, &[u8])> = vec![(&args.out, &csv)];
    if let (Some(path), Some(text)) = (&args.truth, &truth) {
        files.push((path, text.as_bytes()));
    }
    write_files_atomic(&files)?;
    // One sentence, wrapped to fit a terminal as the reports' prose is.
    eprint!(
        "{}",
        smash::report::text::wrap_long(&format!(
            "synth: {} ({} × {} × {}), seed {}, {} swing(s) redrawn, \
             {} hidden effect(s){} -> {}\n",
            super::counted(run.shots.len(), "shot"),
            super::counted(cfg.groups.len(), "group"),
            super::counted(cfg.golfers, "golfer"),
            super::counted(cfg.swings_per_golfer, "swing"),
            cfg.seed,
            run.redrawn,
            cfg.hidden.len(),
            if cfg.world.is_active() {
                " + world-only physics"
            } else {
                ""
            },
            args.out.display()
        ))
    );
    Ok(())
}

pub use smash::app::synth::generate_world;
