//! Stand-in or finding by what it predicts (issue 43): does a *rival family* explain the same
//! held-out gain as a selected effect?
//!
//! A stand-in takes structure another family of explanations also takes. For every selected
//! effect `E` of the final model the check asks how much held-out χ² `E` gains over its rival
//! family — the other selected effects plus impact-location structure — and compares it with
//! what `E` gains over the other selected effects alone:
//!
//! - `t`: the whitened errors (model − measured over the final model's robust noise scales) of
//!   the final club with `E` taken out, nothing refitted;
//! - `J_E`, `J_O`: the signals of `E`'s and the other selected parameters (the change of every
//!   shot's launch per unit of the parameter at the final club, [`super::shared`]), whitened;
//! - `L`: impact-location structure, per launch component the columns `y, z, y², z², y·z`
//!   (measured location in cm, *uncentred* and without an intercept: structure that vanishes
//!   at the face centre, so a level shift of the whole face is not location structure);
//! - the gains are linear, cross-validated over the diagnosis's own folds:
//!   `own = CV(t ~ J_O) − CV(t ~ J_O + J_E)`, `over_family = CV(t ~ J_O + L) −
//!   CV(t ~ J_O + L + J_E)`.
//!
//! When `own` beats `E`'s penalty `k·ln n` and `over_family` does not, `E` only absorbs what
//! the location family absorbs as well: a stand-in, not a finding (its estimates are
//! provisional, the failed check naming the family). An effect whose own signal *is* location
//! structure (the shot-to-shot variation of every parameter's signal within the span of `L`
//! and a level per component, R² ≥ [`LOCATION_FORM_R2`]: `cor_spot`, `cor_radial`,
//! `face_curvature`) cannot be told from `L` by construction; its family is the other selected
//! effects only, and it is asked instead whether `L`, on the components its signal moves,
//! gains beyond it (`ln n` a column): then the location structure in the data has another
//! shape than its form, and it is a stand-in for that. A location form is also asked for its
//! gain over the other selected effects and a constant per launch component its signal moves
//! (`over_level`): its average over the face is a level, which an added mass or a COR level
//! makes as well, so when only its own gain beats `k·ln n` how it varies over the face is not
//! seen, and it is a stand-in for a face-wide shift (`hosel_mass` taking the paper world's
//! added mass).
//!
//! When the location family takes more than one parameter's worth of `E`'s gain
//! (`own − over_family > ln n`), `E`'s kin (candidates whose fit changed the predictions like
//! `E`'s at its step) are read again with `L` beside them: a kin whose reading is then
//! plausible and whose margin comes within [`super::select::RIVAL_MARGIN`] of `E`'s is a
//! rival ([`super::honest::Rival`]); this is how a per-shaft added mass that a COR level
//! absorbed together with a COR map the library lacks is named again.
//!
//! Everything is linear least squares on signals already computed for the report: no fit is
//! refitted. Its design worlds, seeds and rates are in `docs/rival-families.md`.

use rayon::prelude::*;

use crate::club::ClubSpec;
use crate::effects::Effect;
use crate::fit::calibrate::noise_scales;
use crate::fit::{EffectRequest, FitData, FitError, ParamEstimate};
use crate::model::Shot;

use super::honest::Rival;
use super::noise_floor::launch_errors_of;
use super::select::RIVAL_MARGIN;
use super::shared::signal_of;

/// Share of a signal's sum of squares within the span of the location columns above which an
/// effect's signal is itself impact-location structure (fixed before any world was run).
pub const LOCATION_FORM_R2: f64 = 0.9;

/// The check of one selected effect.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyCheck {
    /// The selected effect (`name` or `name@group`).
    pub label: String,
    /// Held-out gain over the other selected effects alone.
    pub own_gain: f64,
    /// Held-out gain over the rival family (the other effects plus location structure).
    pub gain_over_family: f64,
    /// `k·ln n` of the effect.
    pub penalty: f64,
    /// Was location structure part of the family (false for a location form)?
    pub location_in_family: bool,
    /// For a location form: the held-out gain of location structure beyond it, on the
    /// components its signal moves, with that structure's penalty (`ln n` a column).
    pub form: Option<(f64, f64)>,
    /// For a location form: its own held-out gain over the other selected effects and a
    /// constant per launch component its signal moves (its penalty is [`FamilyCheck::penalty`]).
    pub over_level: Option<f64>,
}

impl FamilyCheck {
    /// A stand-in: it earns its penalty over the other effects, not over the family.
    pub fn is_stand_in(&self) -> bool {
        self.form.is_some_and(|(gain, penalty)| gain > penalty)
            || (self.own_gain > self.penalty && self.gain_over_family <= self.penalty)
            || self.level_only()
    }

    /// A location form whose gain is a face-wide level's: it earns its penalty over the other
    /// effects, not once a constant per component it moves is beside them.
    fn level_only(&self) -> bool {
        self.own_gain > self.penalty && self.over_level.is_some_and(|g| g <= self.penalty)
    }

    /// The failed check, as text.
    pub fn text(&self) -> String {
        if let Some((gain, penalty)) = self.form.filter(|(g, p)| g > p) {
            return format!(
                "impact-location structure gains {gain:.1} held out beyond its form (penalty \
                 {penalty:.1}): the location structure in the data has another shape, and it \
                 stands in for it"
            );
        }
        if let Some(level) = self.over_level.filter(|_| self.level_only()) {
            return format!(
                "its held-out gain ({:.1}) is a face-wide level's: over the other selected \
                 effects and a constant per launch component it moves it gains {level:.1} \
                 (penalty {:.1}), so how it varies over the face is not seen; a stand-in for a \
                 shift another effect (an added mass, a COR level) makes as well",
                self.own_gain, self.penalty
            );
        }
        format!(
            "its held-out gain ({:.1}) is explained as well by impact-location structure and the \
             other selected effects (gain left over them {:.1}, penalty {:.1}): a stand-in for \
             structure another family absorbs",
            self.own_gain, self.gain_over_family, self.penalty
        )
    }
}

/// What [`check`] needs of the final model.
pub(super) struct FinalModel<'a> {
    /// The final club: the club file's effects, then the selected ones.
    pub club: &'a ClubSpec,
    /// How many of `club.effects` come from the club file (the rest are selected).
    pub n_file_effects: usize,
    /// The shots as the final model sees them.
    pub data: &'a FitData,
    /// The shots (for the measured impact location).
    pub shots: &'a [Shot],
    /// Final estimates.
    pub estimates: &'a [ParamEstimate],
    /// Fold of every shot.
    pub fold_of: &'a [usize],
    /// `ln n`.
    pub penalty_per_param: f64,
}

mod columns;
use columns::{
    cv_sse, level_columns, location_columns, moved_components, varies_with_location, whiten, Column,
};

/// Does `effect` (a selected club effect) belong to the selected label `label`?
fn belongs(effect: &Effect, label: &str) -> bool {
    let (name, group) = label.split_once('@').unwrap_or((label, ""));
    effect.kind().name() == name
        && match group {
            "" => effect.group().is_none(),
            "group" => effect.group().is_some(),
            g => effect.group() == Some(g),
        }
}

/// Does estimate `p` belong to the selected label `label` (`name`, `name@group`, `name@A`)?
pub fn estimate_of(p: &ParamEstimate, label: &str) -> bool {
    let (name, group) = label.split_once('@').unwrap_or((label, ""));
    p.effect == name
        && match group {
            "" => p.group.is_none(),
            "group" => p.group.is_some(),
            g => p.group.as_deref() == Some(g),
        }
}

/// The club of `m` without the selected effect `label`.
fn club_without(m: &FinalModel, label: &str) -> Result<ClubSpec, FitError> {
    let effects: Vec<Effect> = m
        .club
        .effects
        .iter()
        .enumerate()
        .filter(|(i, e)| *i < m.n_file_effects || !belongs(e, label))
        .map(|(_, e)| e.clone())
        .collect();
    m.club
        .with_effects(effects)
        .map_err(|source| FitError::ClubNotPhysical {
            which: "rival family",
            source,
        })
}

/// One selected effect's check and, when location structure took a share of its gain, the
/// kin that read plausibly beside it.
pub(super) struct EffectCheck {
    pub check: FamilyCheck,
    pub rivals: Vec<Rival>,
}

/// The selected labels of `m` (in the order of the club's effects).
fn selected_labels(m: &FinalModel) -> Vec<String> {
    let mut labels: Vec<String> = Vec::new();
    for e in &m.club.effects[m.n_file_effects..] {
        let label = match e.group() {
            Some(_)
                if m.estimates
                    .iter()
                    .any(|p| p.effect == e.kind().name() && p.group.is_some()) =>
            {
                format!("{}@group", e.kind().name())
            }
            _ => e.kind().name().to_owned(),
        };
        if !labels.contains(&label) {
            labels.push(label);
        }
    }
    labels
}

/// The check of every selected effect of `m`; `kin(label)` gives the kin of a selected effect
/// with their correlations.
pub(super) fn check(
    m: &FinalModel,
    kin: &(dyn Fn(&str) -> Vec<(EffectRequest, f64)> + Sync),
) -> Result<Vec<EffectCheck>, FitError> {
    if m.estimates.is_empty() {
        return Ok(Vec::new());
    }
    let errors = launch_errors_of(m.club, m.data)?;
    let sigma = noise_scales(&errors);
    let signals: Vec<Option<Column>> = m
        .estimates
        .iter()
        .map(|p| Ok(signal_of(m.club, m.data, p)?.map(|s| whiten(&s, &sigma))))
        .collect::<Result<_, FitError>>()?;
    let location = location_columns(m.shots);
    let loc_refs: Vec<&Column> = location.iter().collect();
    let levels = level_columns(m.shots.len());
    let with_levels: Vec<&Column> = loc_refs.iter().copied().chain(&levels).collect();
    // Each selected effect's check is independent of the others': checked side by side,
    // collected in the selection's order.
    let ctx = CheckContext {
        signals: &signals,
        sigma: &sigma,
        location: &location,
        levels: &levels,
        with_levels: &with_levels,
    };
    let checks: Vec<Option<EffectCheck>> = selected_labels(m)
        .into_par_iter()
        .map(|label| check_one(m, kin, &ctx, label))
        .collect::<Result<_, FitError>>()?;
    Ok(checks.into_iter().flatten().collect())
}

/// What every selected effect's check reads: the estimates' whitened signals, the noise
/// scales, the impact-location columns, a level per component, and the two together.
struct CheckContext<'c> {
    signals: &'c [Option<Column>],
    sigma: &'c [f64; 5],
    location: &'c [Column],
    levels: &'c [Column],
    with_levels: &'c [&'c Column],
}

/// The rival-family check of the selected effect `label` (`None` without a signal).
fn check_one(
    m: &FinalModel,
    kin: &(dyn Fn(&str) -> Vec<(EffectRequest, f64)> + Sync),
    ctx: &CheckContext,
    label: String,
) -> Result<Option<EffectCheck>, FitError> {
    let CheckContext {
        signals,
        sigma,
        location,
        levels,
        with_levels,
    } = *ctx;
    let loc_refs: Vec<&Column> = location.iter().collect();
    let (mine, others): (Vec<usize>, Vec<usize>) =
        (0..m.estimates.len()).partition(|&i| estimate_of(&m.estimates[i], &label));
    let j_e: Vec<&Column> = mine.iter().filter_map(|&i| signals[i].as_ref()).collect();
    if j_e.is_empty() {
        return Ok(None);
    }
    let j_o: Vec<&Column> = others.iter().filter_map(|&i| signals[i].as_ref()).collect();
    let location_form = j_e
        .iter()
        .all(|s| varies_with_location(s, with_levels) >= LOCATION_FORM_R2);
    let t = whiten(&launch_errors_of(&club_without(m, &label)?, m.data)?, sigma);
    let gain = |base: &[&Column], extra: &[&Column]| {
        let with: Vec<&Column> = base.iter().chain(extra).copied().collect();
        cv_sse(base, &t, m.fold_of).0 - cv_sse(&with, &t, m.fold_of).0
    };
    let own_gain = gain(&j_o, &j_e);
    let family: Vec<&Column> = if location_form {
        j_o.clone()
    } else {
        j_o.iter().chain(&loc_refs).copied().collect()
    };
    let gain_over_family = if location_form {
        own_gain
    } else {
        gain(&family, &j_e)
    };
    let penalty = mine.len() as f64 * m.penalty_per_param;
    let moved = moved_components(&j_e);
    let over_level = location_form.then(|| {
        let base: Vec<&Column> = j_o
            .iter()
            .copied()
            .chain(
                levels
                    .iter()
                    .enumerate()
                    .filter(|(c, _)| moved[*c])
                    .map(|(_, l)| l),
            )
            .collect();
        gain(&base, &j_e)
    });
    let form = location_form.then(|| {
        let beyond: Vec<&Column> = location
            .iter()
            .enumerate()
            .filter(|(i, _)| moved[i / 5])
            .map(|(_, c)| c)
            .collect();
        let base: Vec<&Column> = j_o.iter().chain(&j_e).copied().collect();
        (
            gain(&base, &beyond),
            beyond.len() as f64 * m.penalty_per_param,
        )
    });
    let check = FamilyCheck {
        label: label.clone(),
        own_gain,
        gain_over_family,
        penalty,
        location_in_family: !location_form,
        form,
        over_level,
    };
    let rivals = if !location_form && own_gain - gain_over_family > m.penalty_per_param {
        let base_margin = gain_over_family - penalty;
        kin(&label)
            .iter()
            .filter_map(|(req, r)| {
                kin_reading(m, &label, req, (&t, sigma), &family)
                    .ok()
                    .flatten()
                    .and_then(|(params, g)| {
                        let margin = g - params.len() as f64 * m.penalty_per_param;
                        let gap = base_margin - margin;
                        (gap <= RIVAL_MARGIN).then(|| Rival::new(req.label(), params, gap, *r))
                    })
            })
            .collect()
    } else {
        Vec::new()
    };
    Ok(Some(EffectCheck { check, rivals }))
}

/// Kin `req` of the selected `label`, read with the rival family beside it: its values (its
/// defaults moved by the least-squares coefficients of its signals at the defaults) and its
/// held-out gain over the family. `None` when it cannot be evaluated.
fn kin_reading(
    m: &FinalModel,
    label: &str,
    req: &EffectRequest,
    (t, sigma): (&Column, &[f64; 5]),
    family: &[&Column],
) -> Result<Option<(Vec<ParamEstimate>, f64)>, FitError> {
    let without = club_without(m, label)?;
    let mut effects = without.effects.clone();
    let free = req.expand(&m.data.groups)?;
    for f in &free {
        effects.push(Effect::with_defaults(f.kind, f.group.clone()));
    }
    let Ok(club) = without.with_effects(effects) else {
        return Ok(None);
    };
    let mut params = Vec::new();
    let mut cols = Vec::new();
    for f in &free {
        for s in f.kind.params() {
            let p = ParamEstimate {
                effect: f.kind.name(),
                group: f.group.clone(),
                param: s.key,
                unit: s.unit,
                value: s.default,
                stderr: None,
                at_bound: false,
            };
            let Some(sig) = signal_of(&club, m.data, &p)? else {
                return Ok(None);
            };
            cols.push(whiten(&sig, sigma));
            params.push(p);
        }
    }
    let with: Vec<&Column> = family.iter().copied().chain(cols.iter()).collect();
    let (sse_with, coef) = cv_sse(&with, t, m.fold_of);
    let g = cv_sse(family, t, m.fold_of).0 - sse_with;
    let k0 = family.len();
    // The signal is d(model − measured)/dθ and `t` is model − measured without the effect:
    // the coefficient that cancels `t` moves the parameter by minus itself.
    for (j, p) in params.iter_mut().enumerate() {
        p.value -= coef[k0 + j];
    }
    Ok(Some((params, g)))
}

#[cfg(test)]
mod tests {
    use super::super::noise_floor::delivery_to_file_units;
    use super::*;
    use crate::model::DeliveryVar;
    use nalgebra::DVector;
    use rand::{Rng, SeedableRng};
    use rand_distr::StandardNormal;

    fn column(mut f: impl FnMut(usize) -> f64, rows: usize) -> Column {
        DVector::from_fn(rows, |r, _| f(r))
    }

    /// A column that is the target's own structure gains about its sum of squares held out; a
    /// column of pure noise gains nothing (slightly less than nothing, out of sample).
    #[test]
    fn held_out_gain_follows_structure_not_noise() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(43);
        let shots = 400;
        let rows = shots * 5;
        let fold_of: Vec<usize> = (0..shots).map(|i| i % 5).collect();
        let x = column(|r| ((r / 5) as f64 * 0.37).sin(), rows);
        let noise = column(|_| rng.sample::<f64, _>(StandardNormal), rows);
        let useless = column(|_| rng.sample::<f64, _>(StandardNormal), rows);
        let t = &x * 0.5 + &noise;
        let base = cv_sse(&[], &t, &fold_of).0;
        let with_x = cv_sse(&[&x], &t, &fold_of).0;
        let with_useless = cv_sse(&[&useless], &t, &fold_of).0;
        let expected = 0.25 * x.norm_squared();
        assert!(
            (base - with_x - expected).abs() < 0.25 * expected,
            "gain {} against {expected}",
            base - with_x
        );
        assert!(
            base - with_useless < 3.0,
            "noise gained {}",
            base - with_useless
        );
    }

    /// A signal varying with the squared heel-toe location is location structure; one varying
    /// with something else (here the shot's index, as club speed would) is not, whatever its
    /// level.
    #[test]
    fn a_location_form_is_told_by_how_its_signal_varies() {
        let shots: Vec<Shot> = (0..200)
            .map(|i| {
                let mut d = [105.0, 0.0, 0.0, 12.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
                d[DeliveryVar::ImpactY.index()] = ((i * 7) % 23) as f64 - 11.0;
                d[DeliveryVar::ImpactZ.index()] = ((i * 5) % 31) as f64 - 15.0;
                Shot {
                    id: i.to_string(),
                    group: "all".into(),
                    golfer: None,
                    delivery: crate::model::delivery_from_file_units(&d),
                    measured: None,
                }
            })
            .collect();
        let loc = location_columns(&shots);
        let levels = level_columns(shots.len());
        let cols: Vec<&Column> = loc.iter().chain(&levels).collect();
        let z2 = column(
            |r| {
                let d = delivery_to_file_units(&shots[r / 5].delivery);
                if r % 5 == 0 {
                    3.0 - 0.01 * d[DeliveryVar::ImpactZ.index()].powi(2)
                } else {
                    0.0
                }
            },
            shots.len() * 5,
        );
        let speedlike = column(
            |r| {
                if r % 5 == 0 {
                    3.0 + ((r / 5) as f64 * 0.61).cos()
                } else {
                    0.0
                }
            },
            shots.len() * 5,
        );
        assert!(varies_with_location(&z2, &cols) > 0.999);
        assert!(varies_with_location(&speedlike, &cols) < LOCATION_FORM_R2);
    }

    /// The level check: a location form whose signal is mostly a face-wide level gains
    /// nothing once a level is beside it when the target is a level (the paper world's added
    /// mass read by `hosel_mass`), and keeps its gain when the target varies with the location
    /// as its signal does.
    #[test]
    fn a_level_is_not_a_location_form_finding() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4301);
        let shots = 600;
        let rows = shots * 5;
        let fold_of: Vec<usize> = (0..shots).map(|i| i % 10).collect();
        let z: Vec<f64> = (0..shots)
            .map(|_| rng.sample::<f64, _>(StandardNormal))
            .collect();
        let on_speed =
            |f: &dyn Fn(usize) -> f64| column(|r| if r % 5 == 0 { f(r / 5) } else { 0.0 }, rows);
        let level = &level_columns(shots)[0];
        // The effect's signal: a level with a little variation over the face.
        let signal = on_speed(&|i| 1.0 + 0.05 * z[i] * z[i]);
        let noise = column(|_| rng.sample::<f64, _>(StandardNormal), rows);
        let penalty = (shots as f64).ln();
        let gains = |t: &Column| {
            let none = cv_sse(&[], t, &fold_of).0 - cv_sse(&[&signal], t, &fold_of).0;
            let over_level =
                cv_sse(&[level], t, &fold_of).0 - cv_sse(&[level, &signal], t, &fold_of).0;
            (none, over_level)
        };
        let (own, over_level) = gains(&(on_speed(&|_| 0.3) + &noise));
        let check = |own_gain, over_level| FamilyCheck {
            label: "hosel_mass".into(),
            own_gain,
            gain_over_family: own_gain,
            penalty,
            location_in_family: false,
            form: Some((0.0, 5.0 * penalty)),
            over_level: Some(over_level),
        };
        assert!(own > penalty && over_level <= penalty, "{own} {over_level}");
        let level_only = check(own, over_level);
        assert!(level_only.is_stand_in());
        assert!(
            level_only.text().contains("face-wide level"),
            "{}",
            level_only.text()
        );
        // The same signal where the target varies over the face as the signal does.
        let (own, over_level) = gains(&(on_speed(&|i| 0.3 + 0.6 * z[i] * z[i]) + &noise));
        assert!(over_level > penalty, "{own} {over_level}");
        assert!(!check(own, over_level).is_stand_in());
    }
}
