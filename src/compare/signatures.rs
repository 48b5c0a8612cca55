//! Which library effects produce which error pattern, used to hint at the missing physics
//! behind a finding. The rows are the effects' own (`SIGNATURE` in each file of
//! `src/effects/`, read off the model: an effect's derivative of the launch over typical driver
//! shots) plus one for noisy impact locations; `smash diagnose` tests them quantitatively.

use std::fmt;

use crate::effects::user::UserEffect;
use crate::effects::EffectKind;
pub use crate::effects::Pattern;
use crate::physics::LaunchComponent;

/// What a signature points at: a library effect (checked by the compiler), the effect per group
/// of shots, noise in the measured impact location, or a user-defined effect whose measured
/// signature matches ([`super::user_hints`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hint {
    /// A library effect, for all shots.
    Effect(EffectKind),
    /// A library effect fitted per group (`name@group`).
    PerGroup(EffectKind),
    /// Impact-location measurement noise (`--impact-noise-mm`).
    ImpactNoise,
    /// A user-defined effect, for all shots.
    User(&'static UserEffect),
    /// A user-defined effect fitted per group (`name@group`).
    UserPerGroup(&'static UserEffect),
}

impl fmt::Display for Hint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Effect(k) => f.write_str(k.name()),
            Self::PerGroup(k) => write!(f, "{}@group", k.name()),
            Self::ImpactNoise => f.write_str("impact_noise"),
            Self::User(u) => f.write_str(u.name),
            Self::UserPerGroup(u) => write!(f, "{}@group", u.name),
        }
    }
}

/// One row of the table: a component's error pattern, what produces it and why.
#[derive(Debug, Clone, Copy)]
pub struct Signature {
    /// Error component.
    pub component: LaunchComponent,
    /// Pattern.
    pub pattern: Pattern,
    /// The effect (or measurement noise) that produces it.
    pub hint: Hint,
    /// Why, in a few words.
    pub why: &'static str,
}

/// Noisy measured impact locations leave a ball-speed trend with the distance from the centre:
/// the model is charged for strikes measured farther out than they were.
const IMPACT_NOISE: Signature = Signature {
    component: LaunchComponent::BallSpeed,
    pattern: Pattern::Trend("impact_r_mm"),
    hint: Hint::ImpactNoise,
    why: "noisy impact locations: falling with r, the model is charged for strikes measured \
          farther out than they were; try --impact-noise-mm",
};

/// The table: every library effect's own rows, in registration order (a `GroupBias` row is the
/// effect fitted per group), then the impact-noise row.
pub fn signatures() -> impl Iterator<Item = Signature> {
    EffectKind::ALL
        .into_iter()
        .flat_map(|k| {
            k.signature().iter().map(move |r| Signature {
                component: r.component,
                pattern: r.pattern,
                hint: match r.pattern {
                    Pattern::GroupBias => Hint::PerGroup(k),
                    _ => Hint::Effect(k),
                },
                why: r.why,
            })
        })
        .chain([IMPACT_NOISE])
}

/// Hints for a pattern of one component: `effect (why)` for every matching row.
pub fn hints_for(component: LaunchComponent, pattern: &Pattern) -> Vec<String> {
    signatures()
        .filter(|s| s.component == component && s.pattern == *pattern)
        .map(|s| format!("{} ({})", s.hint, s.why))
        .collect()
}

/// The hint text of a user-defined effect: its name and its own description.
pub fn user_hint_text(h: &Hint) -> String {
    match h {
        Hint::User(u) | Hint::UserPerGroup(u) if !u.doc.is_empty() => {
            format!("{h} (user-defined: {})", u.doc)
        }
        _ => format!("{h} (user-defined)"),
    }
}
