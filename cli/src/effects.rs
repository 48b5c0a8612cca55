//! `smash effects`: the effect library, with parameters, units, defaults and bounds.

use clap::Args;

use crate::stdout;
use smash::report::effects::EffectsReport;
use smash::report::render::Render;

/// Arguments of `smash effects`.
#[derive(Debug, Args)]
pub struct EffectsArgs {
    /// User-defined effects to list after the library's.
    #[command(flatten)]
    pub effect_defs: super::EffectDefsArgs,

    /// Print the library as JSON on stdout.
    #[arg(long)]
    pub json: bool,
}

/// Run `smash effects`.
pub fn run(args: EffectsArgs) -> anyhow::Result<()> {
    args.effect_defs.load()?;
    let report = EffectsReport::now();
    match report.json().filter(|_| args.json) {
        Some(json) => stdout::println(json)?,
        None => stdout::print(Render::text(&report, &()))?,
    }
    Ok(())
}
