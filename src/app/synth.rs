//! `synth`: a synthetic experiment with hidden effects, and its truth.

use std::path::Path;

use anyhow::Context;

use crate::data::club_file::read_club_as;
use crate::effects::user::Offer;
use crate::synth::{generate, read_config, SynthConfig, SynthRun};

/// The world of the configuration file `config` (its seed replaced by `seed` when given):
/// the configuration and the run.
pub fn generate_world(config: &Path, seed: Option<u64>) -> anyhow::Result<(SynthConfig, SynthRun)> {
    let mut cfg = read_config(config)?;
    if let Some(seed) = seed {
        cfg.seed = seed;
    }
    let club = read_club_as(&cfg.club, Offer::WorldOnly)
        .with_context(|| format!("base club of {}", config.display()))?;
    let run = generate(&cfg, &club).with_context(|| config.display().to_string())?;
    Ok((cfg, run))
}
