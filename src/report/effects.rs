//! What `smash effects` reports, as one value: [`EffectsReport`], the effect library (and the
//! user-defined effects registered) with each parameter's key, unit, neutral value and physical
//! bounds. Its text is [`EffectsReport::text`], its JSON its `Serialize` (`docs/json.md`).

use std::fmt::Write;

use serde::{Serialize, Serializer};

use crate::effects::{EffectId, EffectKind};
use crate::wrap::wrap;

/// The widest line of the table, in columns (the text reports' width).
const TEXT_COLUMNS: usize = 120;
/// Where the meaning starts: after the effect (24), parameter (11), default (7) and physical
/// range (22) columns and their separators.
const MEANING_COLUMN: usize = 24 + 1 + 11 + 1 + 7 + 1 + 22 + 2;

/// One parameter of an effect.
#[derive(Debug, Clone, Serialize)]
pub struct ParamView {
    /// Key in club files.
    pub key: &'static str,
    /// Unit.
    pub unit: &'static str,
    /// Neutral value (the effect does nothing).
    pub default: f64,
    /// Lower physical bound.
    pub lower: f64,
    /// Upper physical bound.
    pub upper: f64,
    /// What it means.
    pub doc: &'static str,
}

/// One effect.
#[derive(Debug, Clone, Serialize)]
pub struct EffectView {
    /// Name in files and on the command line.
    pub name: &'static str,
    /// Defined by the user (an effects file), not the library.
    pub user_defined: bool,
    /// One-line description.
    pub description: &'static str,
    /// Its parameters.
    pub params: Vec<ParamView>,
}

/// The effect library and the user-defined effects registered, in that order.
#[derive(Debug, Clone)]
pub struct EffectsReport {
    /// Every effect.
    pub effects: Vec<EffectView>,
}

/// The version of effects' JSON schema (`schema_version`); raised when a key changes meaning
/// or goes away (a new key does not raise it).
pub const SCHEMA_VERSION: u32 = 1;

/// The JSON of [`EffectsReport`].
#[derive(Serialize)]
struct EffectsJson<'a> {
    schema_version: u32,
    command: &'static str,
    effects: &'a [EffectView],
}

impl Serialize for EffectsReport {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        super::json::canonical(
            &EffectsJson {
                schema_version: SCHEMA_VERSION,
                command: "effects",
                effects: &self.effects,
            },
            s,
        )
    }
}

impl EffectsReport {
    /// The library's effects and then the user-defined ones registered now.
    pub fn now() -> Self {
        let effects = EffectKind::ALL
            .into_iter()
            .map(EffectId::from)
            .chain(
                crate::effects::user::registered()
                    .into_iter()
                    .map(EffectId::User),
            )
            .map(|k| EffectView {
                name: k.name(),
                user_defined: k.user().is_some(),
                description: k.description(),
                params: k
                    .params()
                    .iter()
                    .map(|p| ParamView {
                        key: p.key,
                        unit: p.unit,
                        default: p.default,
                        lower: p.lower,
                        upper: p.upper,
                        doc: p.doc,
                    })
                    .collect(),
            })
            .collect();
        Self { effects }
    }

    /// The table: a line per parameter (effect, key, default, physical range, meaning wrapped
    /// in its own column so that a line fits 120 columns), then how to name an effect.
    pub fn text(&self) -> String {
        let mut text = String::new();
        let _ = writeln!(
            text,
            "{:<24} {:<11} {:>7} {:>22}  meaning",
            "effect", "parameter", "default", "physical range"
        );
        for k in &self.effects {
            for (i, p) in k.params.iter().enumerate() {
                let name = if i == 0 { k.name } else { "" };
                let range = format!("[{}, {}] {}", p.lower, p.upper, p.unit);
                let meaning = wrap(p.doc, TEXT_COLUMNS - MEANING_COLUMN, 0);
                for (j, line) in meaning.lines().enumerate() {
                    if j == 0 {
                        let (key, default) = (p.key, p.default);
                        let _ = writeln!(
                            text,
                            "{name:<24} {key:<11} {default:>7} {range:>22}  {line}"
                        );
                    } else {
                        let _ = writeln!(text, "{:MEANING_COLUMN$}{line}", "");
                    }
                }
            }
        }
        let _ = writeln!(
            text,
            "\nIn a club file: [[effect]] name = \"added_mass\", dm_g = 2.54, group = \"A\" (group \
             optional)."
        );
        let _ = writeln!(
            text,
            "On the command line: name for one global value, name@group for one value per group."
        );
        text
    }
}
