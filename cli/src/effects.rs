//! `smash effects`: the effect library, with parameters, units, defaults and bounds.

use clap::Args;

use std::fmt::Write;

use crate::stdout;
use smash::effects::{EffectId, EffectKind};

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
    let all: Vec<EffectId> = EffectKind::ALL
        .into_iter()
        .map(EffectId::from)
        .chain(
            smash::effects::user::registered()
                .into_iter()
                .map(EffectId::User),
        )
        .collect();
    if args.json {
        let list: Vec<serde_json::Value> = all
            .iter()
            .map(|k| {
                serde_json::json!({
                    "name": k.name(),
                    "user_defined": k.user().is_some(),
                    "description": k.description(),
                    "params": k.params().iter().map(|p| serde_json::json!({
                        "key": p.key, "unit": p.unit, "default": p.default,
                        "lower": p.lower, "upper": p.upper, "doc": p.doc,
                    })).collect::<Vec<_>>(),
                })
            })
            .collect();
        stdout::println(serde_json::to_string_pretty(
            &serde_json::json!({ "effects": list }),
        )?)?;
        return Ok(());
    }
    let mut text = String::new();
    writeln!(
        text,
        "{:<24} {:<11} {:>7} {:>22}  meaning",
        "effect", "parameter", "default", "physical range"
    )?;
    for k in all {
        for (i, p) in k.params().iter().enumerate() {
            let name = if i == 0 { k.name() } else { "" };
            writeln!(
                text,
                "{:<24} {:<11} {:>7} {:>22}  {}",
                name,
                p.key,
                p.default,
                format!("[{}, {}] {}", p.lower, p.upper, p.unit),
                p.doc
            )?;
        }
    }
    writeln!(text, "\nIn a club file: [[effect]] name = \"added_mass\", dm_g = 2.54, group = \"A\" (group optional).")?;
    writeln!(
        text,
        "On the command line: name for one global value, name@group for one value per group."
    )?;
    stdout::print(text)?;
    Ok(())
}
