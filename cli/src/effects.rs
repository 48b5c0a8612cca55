//! `smash effects`: the effect library, with parameters, units, defaults and bounds.

use clap::Args;

use std::fmt::Write;

use crate::stdout;
use smash::effects::{EffectId, EffectKind};
use smash::report::wrap::wrap;

/// The widest line of the table, in columns (the text reports' width, `cli/tests/docs_run.rs`).
const TEXT_COLUMNS: usize = 120;
/// Where the meaning starts: after the effect (24), parameter (11), default (7) and physical
/// range (22) columns and their separators.
const MEANING_COLUMN: usize = 24 + 1 + 11 + 1 + 7 + 1 + 22 + 2;

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
            let range = format!("[{}, {}] {}", p.lower, p.upper, p.unit);
            // The meaning wrapped in its own column, so that a line fits the report width.
            let meaning = wrap(p.doc, TEXT_COLUMNS - MEANING_COLUMN, 0);
            for (j, line) in meaning.lines().enumerate() {
                if j == 0 {
                    let (key, default) = (p.key, p.default);
                    writeln!(
                        text,
                        "{name:<24} {key:<11} {default:>7} {range:>22}  {line}"
                    )?;
                } else {
                    writeln!(text, "{:MEANING_COLUMN$}{line}", "")?;
                }
            }
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
