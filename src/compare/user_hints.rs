//! Hints at user-defined effects: which error patterns a `[[define_effect]]` can produce on
//! these shots, read off the model rather than off its text.
//!
//! The library's effects have a table ([`super::signatures`]), each row read off the model once.
//! A user-defined effect has none, so its signature is measured on the shots being compared:
//! each parameter is stepped from its default (into its bounds) and the model's change of every
//! launch component is taken shot by shot (a forward difference through the compiled
//! expressions: [`UserSignature::measure`]). Scaled to the parameter's plausible range, that
//! change says which components the effect moves and how:
//!
//! - a **bias** of a component, when the change has one sign over the shots (its mean is at
//!   least half its root mean square) and a plausible step moves it by at least
//!   [`NOTICEABLE_OF_NOISE`] of the launch monitor's noise;
//! - a **trend** with a delivery variable, when the change correlates with the variable
//!   (|r| ≥ [`TREND_R`]) and is as noticeable;
//! - a **group bias**, fitted per group (`NAME@group`), wherever it produces a bias.
//!
//! A hint is given only when the effect can move the error the right way: its parameter can
//! step that way from the default (within its bounds), and the change it makes has the sign
//! that cancels the finding (a bias of `+m` needs a change of `−m`).

use super::signatures::Hint;
use super::{Pattern, VARIABLES};
use crate::club::ClubSpec;
use crate::effects::user::UserEffect;
use crate::effects::{Effect, EffectId};
use crate::model::{default_launch_noise, Shot};
use crate::physics::LaunchComponent;
use crate::stats::{mean, pearson};

/// Fraction of the default launch-monitor noise (`crate::model::default_launch_noise`) that a
/// step of a parameter across its plausible range must move a component by, root mean square
/// over the shots, for the effect to count as moving it: a quarter of the noise of one shot is
/// visible in the mean of a few dozen shots.
pub const NOTICEABLE_OF_NOISE: f64 = 0.25;

/// Smallest |Pearson r| between an effect's change of a component and a delivery variable for
/// the effect to count as producing a trend with that variable.
pub const TREND_R: f64 = 0.3;

/// Forward-difference step of a parameter, as a fraction of its physical bounds' width.
const STEP_OF_RANGE: f64 = 1e-3;

/// What one parameter of a user-defined effect does to one launch component over the shots,
/// for a step of the parameter across its plausible range in the direction it may move.
#[derive(Debug, Clone, PartialEq)]
struct Move {
    /// Mean change of the component, file units.
    mean: f64,
    /// Root mean square of the change, file units.
    rms: f64,
    /// Pearson r of the change with each of [`VARIABLES`] (`None` when undefined).
    r: Vec<Option<f64>>,
}

/// The measured signature of one user-defined effect: per parameter and direction, the
/// [`Move`] of each launch component.
#[derive(Debug, Clone, PartialEq)]
pub struct UserSignature {
    /// The effect.
    pub effect: &'static UserEffect,
    /// `moves[k][c]`: one direction of one parameter (`k`), component `c`, for a step across
    /// the parameter's plausible range that way.
    moves: Vec<[Move; 5]>,
}

/// The signatures of every user-defined effect on a set of shots.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct UserHints {
    signatures: Vec<UserSignature>,
}

impl UserHints {
    /// Measure the signatures of `effects` on `shots` with `club` (its own effects applied).
    /// An effect whose steps make the club unphysical, or that no shot can be computed with, is
    /// left out (it gets no hints).
    pub fn measure(club: &ClubSpec, shots: &[Shot], effects: &[&'static UserEffect]) -> Self {
        Self {
            signatures: effects
                .iter()
                .filter_map(|u| UserSignature::measure(club, shots, u))
                .collect(),
        }
    }

    /// The measured signatures.
    pub fn signatures(&self) -> &[UserSignature] {
        &self.signatures
    }

    /// The user-defined effects that can cancel a finding of `pattern` on component `c` whose
    /// sign is `sign` (the mean error for a bias, the correlation for a trend; ignored for a
    /// group bias).
    pub fn hints(&self, c: LaunchComponent, pattern: &Pattern, sign: f64) -> Vec<Hint> {
        self.signatures
            .iter()
            .filter(|s| s.matches(c, pattern, sign))
            .map(|s| match pattern {
                Pattern::GroupBias => Hint::UserPerGroup(s.effect),
                _ => Hint::User(s.effect),
            })
            .collect()
    }
}

impl UserSignature {
    /// Measure `u`'s signature on `shots` (see the module docs); `None` when no step of it can
    /// be computed.
    pub fn measure(club: &ClubSpec, shots: &[Shot], u: &'static UserEffect) -> Option<Self> {
        let base = launches(club, shots)?;
        let defaults: Vec<f64> = u.params.iter().map(|s| s.default).collect();
        let mut moves = Vec::new();
        for (j, spec) in u.params.iter().enumerate() {
            for direction in [1.0, -1.0] {
                let room = if direction > 0.0 {
                    spec.upper - spec.default
                } else {
                    spec.default - spec.lower
                };
                let h = STEP_OF_RANGE * (spec.upper - spec.lower);
                if !(room >= h) {
                    continue;
                }
                let mut values = defaults.clone();
                values[j] += direction * h;
                let effect = Effect::new(EffectId::User(u), &values, None).ok()?;
                let mut effects = club.effects.clone();
                effects.push(effect);
                let Some(stepped) = club
                    .with_effects(effects)
                    .ok()
                    .and_then(|c| launches(&c, shots))
                else {
                    continue;
                };
                let (lo, hi) = spec.plausible;
                let scale = direction * (hi - lo) / h;
                moves.push(LaunchComponent::ALL.map(|c| {
                    let change: Vec<(usize, f64)> = base
                        .iter()
                        .zip(&stepped)
                        .enumerate()
                        .filter_map(|(i, (a, b))| {
                            Some((i, (b.as_ref()?[c.index()] - a.as_ref()?[c.index()]) * scale))
                        })
                        .collect();
                    summarise(shots, &change)
                }));
            }
        }
        (!moves.is_empty()).then_some(Self { effect: u, moves })
    }

    /// Can the effect cancel a finding of `pattern` on `c` with sign `sign`?
    fn matches(&self, c: LaunchComponent, pattern: &Pattern, sign: f64) -> bool {
        let noticeable = NOTICEABLE_OF_NOISE * default_launch_noise(c);
        self.moves.iter().any(|m| {
            let m = &m[c.index()];
            if !(m.rms >= noticeable) {
                return false;
            }
            let consistent = m.mean.abs() >= 0.5 * m.rms;
            match pattern {
                Pattern::Bias => consistent && m.mean * sign < 0.0,
                Pattern::GroupBias => consistent,
                Pattern::Trend(v) => VARIABLES
                    .iter()
                    .position(|x| x.name() == *v)
                    .and_then(|k| m.r[k])
                    .is_some_and(|r| r.abs() >= TREND_R && r * sign < 0.0),
            }
        })
    }
}

/// Mean, root mean square and correlations of the per-shot `change` (shot index, value).
fn summarise(shots: &[Shot], change: &[(usize, f64)]) -> Move {
    let y: Vec<f64> = change.iter().map(|&(_, v)| v).collect();
    let rms = (y.iter().map(|v| v * v).sum::<f64>() / y.len().max(1) as f64).sqrt();
    Move {
        mean: mean(&y),
        rms,
        r: VARIABLES
            .iter()
            .map(|v| {
                let x: Vec<f64> = change.iter().map(|&(i, _)| v.get(&shots[i])).collect();
                pearson(&x, &y).map(|k| k.r)
            })
            .collect(),
    }
}

/// The launch of every shot in file units with `club` (`None` for a shot that cannot be
/// computed); `None` when a group's model is not physical.
fn launches(club: &ClubSpec, shots: &[Shot]) -> Option<Vec<Option<[f64; 5]>>> {
    let groups = club
        .models_for_groups(shots.iter().map(|s| s.group.as_str()))
        .ok()?;
    Some(
        shots
            .iter()
            .map(|s| {
                let l = groups[&s.group].solve(&s.delivery).ok()?.launch();
                Some(LaunchComponent::ALL.map(|c| l.get_file(c)))
            })
            .collect(),
    )
}
