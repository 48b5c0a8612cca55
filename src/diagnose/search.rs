//! The state of forward selection and its named steps: folds and candidates offered, then per
//! step the noise-floor check, scoring every open candidate ([`super::evaluate`]), choosing
//! ([`super::select`]), adopting the winner, and at the end the calibration of what was selected.
//! The measurement candidates' data (impact- and delivery-noise levels) are in [`measure`].

use super::evaluate::{make_folds, Folds};
use super::{
    default_candidates, honest, noise_floor, select, DiagnoseOptions, DiagnoseProgress, Diagnosis,
    FoldBy, Step,
};
use crate::club::ClubSpec;
use crate::fit::calibrate::{noise_scales, Calibration};
use crate::fit::{
    EffectRequest, FitData, FitError, FitProblem, GivenScales, Likelihood, ParamLayout, Weighting,
};
use crate::measurement::{DeliveryNoise, ImpactNoise};
use crate::model::Shot;
use crate::stats::{self, launch_error_table, ErrorTable};
use nalgebra::DVector;
use score::Scored;

mod alias;
mod earned;
mod final_fit;
mod measure;
mod readings;
mod reselect;
mod score;
mod swap;
mod unresolved;

fn group_names(data: &FitData) -> Vec<String> {
    data.group_of
        .iter()
        .map(|&g| data.groups[g].clone())
        .collect()
}

/// Fold of every shot and how the folds were formed: by golfer when there are at least two,
/// else by the given keys (sessions, time blocks, clubs) when they hold at least two, else by
/// shot (with a warning).
pub(super) fn fold_assignment(
    data: &FitData,
    folds: usize,
    keys: Option<&stats::FoldKeys>,
    warnings: &mut Vec<String>,
) -> (Vec<usize>, FoldBy) {
    let golfers: Vec<&str> = data
        .golfers
        .iter()
        .map(|g| g.as_deref().unwrap_or(""))
        .collect();
    let mut distinct = golfers.clone();
    distinct.sort_unstable();
    distinct.dedup();
    if data.has_golfers() && distinct.len() >= 2 {
        return (stats::grouped_folds(&golfers, folds), FoldBy::Golfer);
    }
    if let Some(k) = keys.filter(|k| k.keys.len() == data.len()) {
        let mut distinct: Vec<&String> = k.keys.iter().collect();
        distinct.sort_unstable();
        distinct.dedup();
        if distinct.len() >= 2 {
            let by = match k.kind {
                stats::KeyKind::Session => FoldBy::Session,
                stats::KeyKind::TimeBlock => FoldBy::TimeBlock,
                stats::KeyKind::Club => FoldBy::Club,
            };
            if distinct.len() == k.keys.len() {
                warnings.push(format!(
                    "column '{}' gives every shot a {} of its own ({} of one shot): folds by {} \
                     are folds by shot; if the column holds each shot's time rather than its \
                     session, name the sessions in a `session` column",
                    k.column,
                    by.name(),
                    k.keys.len(),
                    by.name()
                ));
            }
            return (stats::grouped_folds(&k.keys, folds), by);
        }
    }
    warnings.push(if data.has_golfers() {
        format!(
            "every shot is from one golfer ('{}'): cross-validation folds cannot be grouped by \
             golfer, so they are by shot, and an effect may win by fitting that golfer's habits",
            distinct.first().copied().unwrap_or_default()
        )
    } else {
        "no golfer column and no date or time column: cross-validation folds are by shot, so a \
         golfer's or a session's shots can be in both training and test folds"
            .to_owned()
    });
    (stats::item_folds(data.len(), folds), FoldBy::Shot)
}

/// The candidates to search: the options' list or the defaults, checked against the groups and
/// without those the data cannot identify (each named in a warning).
pub(super) fn offered_candidates(
    opts: &DiagnoseOptions,
    data: &FitData,
    shots: &[Shot],
    warnings: &mut Vec<String>,
) -> Result<Vec<EffectRequest>, FitError> {
    let candidates = opts
        .candidates
        .clone()
        .unwrap_or_else(|| default_candidates(&data.groups));
    for (i, c) in candidates.iter().enumerate() {
        c.expand(&data.groups)?;
        if candidates[..i].contains(c) {
            return Err(FitError::BadEffectList(format!(
                "candidate '{}' is listed twice",
                c.label()
            )));
        }
    }
    // Degenerate data are named, not fitted (see `crate::fit::variation`).
    let unidentifiable = crate::fit::variation::check_variation(shots, &candidates)?;
    if opts.candidates.is_some() {
        if let Some((_, why)) = unidentifiable.first() {
            return Err(FitError::Degenerate(why.clone()));
        }
    }
    warnings.extend(
        unidentifiable
            .iter()
            .map(|(_, why)| format!("not tried: {why}")),
    );
    Ok(candidates
        .into_iter()
        .filter(|c| !unidentifiable.iter().any(|(u, _)| u == c))
        .collect())
}

/// A selected effect (label, request) and its kin: candidates that changed the predictions
/// alike at its step, each with that correlation.
type Kin = (String, EffectRequest, Vec<(EffectRequest, f64)>);

/// The state of forward selection between steps.
#[derive(Clone)]
pub(super) struct Search<'a> {
    club: &'a ClubSpec,
    shots: &'a [Shot],
    opts: &'a DiagnoseOptions,
    progress: Option<&'a dyn DiagnoseProgress>,
    /// Group name of every shot.
    pub(super) groups: Vec<String>,
    data: FitData,
    folds: Folds,
    /// Impact-location noise levels offered as measurement candidates, each with its data.
    noise_options: Vec<(ImpactNoise, FitData, Folds)>,
    chosen_noise: Option<ImpactNoise>,
    /// Delivery-noise levels offered as measurement candidates while the instruments' noise is
    /// unknown ([`measure`]).
    delivery_options: Vec<measure::DeliveryOption>,
    /// Delivery noise the model is calibrated for (given, or selected).
    chosen_delivery: Option<DeliveryNoise>,
    pub(super) base: ParamLayout,
    theta_base: DVector<f64>,
    selected: Vec<EffectRequest>,
    /// Each selected effect (label, request) with its kin at the step that selected it:
    /// candidates that changed the predictions alike, and the correlation.
    kin_of: Vec<Kin>,
    /// Each selected effect (request) with the candidates that nearly matched it at the step
    /// that selected it (a margin within [`select::RIVAL_MARGIN`], not kin): read only by the
    /// final model's ambiguities, never by the search.
    near_of: Vec<(EffectRequest, Vec<(EffectRequest, f64)>)>,
    penalty_per_param: f64,
    /// Fold of every shot (to make the folds again for a refined impact-noise level).
    fold_of: Vec<usize>,
    reselected: bool, // a re-selection (`reselect.rs`) has been tried: at most once
    /// The final fit made by the check of `final_fit.rs`, kept for the report (its selection).
    checked_fit: Option<(Vec<String>, Calibration)>,
    /// The instruments' noise as fixed variances per shot when it is known, for the
    /// likelihood every step's model is scored by (`None`: profiled scales).
    given: Option<std::sync::Arc<GivenScales>>,
    /// The candidates of the last step that selected nothing, at its base
    /// ([`unresolved`]).
    last_scored: Option<unresolved::LastScored>,
    /// The effects whose gain beat `k·ln n` at the last step that scored any: the only ones
    /// [`unresolved`] scores again when it must.
    promising: Vec<String>,
}

impl<'a> Search<'a> {
    pub(super) fn new(
        club: &'a ClubSpec,
        shots: &'a [Shot],
        opts: &'a DiagnoseOptions,
        progress: Option<&'a dyn DiagnoseProgress>,
        data: FitData,
        (fold_of, n_folds): (&[usize], usize),
        warnings: &mut Vec<String>,
    ) -> Result<Self, FitError> {
        let delivery_noise = opts.delivery_noise();
        // The measurement candidates' data and the folds, made side by side.
        let (noise_options, (delivery_options, folds)) = rayon::join(
            || {
                let mut said = Vec::new();
                let options = if opts.impact_noise.is_none() {
                    measure::impact_options(&data, opts, (fold_of, n_folds), &mut said)
                } else {
                    Ok(Vec::new())
                };
                options.map(|o| (o, said))
            },
            || {
                rayon::join(
                    || {
                        if delivery_noise.is_none() {
                            measure::delivery_options(&data, opts, (fold_of, n_folds))
                        } else {
                            Vec::new()
                        }
                    },
                    || make_folds(&data, fold_of, n_folds),
                )
            },
        );
        let (noise_options, said) = noise_options?;
        warnings.extend(said);
        let given = opts
            .noise_floor
            .as_ref()
            .map(|inst| noise_floor::given_scales(club, shots, inst, opts.impact_noise))
            .transpose()?
            .map(std::sync::Arc::new);
        Ok(Self {
            club,
            shots,
            opts,
            progress,
            groups: group_names(&data),
            folds,
            penalty_per_param: (data.len() as f64).ln(),
            data,
            noise_options,
            chosen_noise: opts.impact_noise,
            delivery_options,
            chosen_delivery: delivery_noise,
            base: ParamLayout::new(Vec::new())?,
            theta_base: DVector::zeros(0),
            selected: Vec::new(),
            kin_of: Vec::new(),
            near_of: Vec::new(),
            fold_of: fold_of.to_vec(),
            reselected: false,
            checked_fit: None,
            given,
            last_scored: None,
            promising: Vec::new(),
        })
    }

    /// The likelihood score of `errors` of the current model (its fitted parameters, and a
    /// noise level selected from the data counted as one more each), on the diagnosis's one
    /// scale ([`crate::fit::likelihood`]).
    pub(super) fn likelihood_of(&self, errors: &[[f64; 5]]) -> Likelihood {
        let chosen = usize::from(self.chosen_noise.is_some() && self.opts.impact_noise.is_none())
            + usize::from(self.chosen_delivery.is_some() && self.opts.delivery_noise().is_none());
        Likelihood::of(errors, self.base.len() + chosen, self.given.as_deref())
    }

    pub(super) fn errors_of(
        &self,
        layout: &ParamLayout,
        theta: &[f64],
    ) -> Result<Vec<[f64; 5]>, FitError> {
        Ok(FitProblem::new(
            self.club,
            layout.clone(),
            &self.data,
            Weighting::launch(&[1.0; 5]),
        )
        .launch_errors(theta)?)
    }

    /// The club with the base effects at their current values.
    fn base_club(&self) -> Result<ClubSpec, FitError> {
        let mut effects = self.club.effects.clone();
        effects.extend(
            self.base
                .to_effects(self.theta_base.as_slice())
                .map_err(|source| FitError::ValuesOutOfBounds {
                    which: "base",
                    source,
                })?,
        );
        self.club
            .with_effects(effects)
            .map_err(|source| FitError::ClubNotPhysical {
                which: "base",
                source,
            })
    }

    /// With a known noise floor: are the base model's errors already at it?
    fn at_noise_floor(&self, base_errors: &[[f64; 5]]) -> Result<bool, FitError> {
        let Some(inst) = &self.opts.noise_floor else {
            return Ok(false);
        };
        let base_club = self.base_club()?;
        let floor = noise_floor::noise_floor_of(
            &base_club,
            self.shots,
            base_errors,
            inst,
            self.chosen_noise,
        )?;
        Ok(!floor.structure_remains())
    }

    /// Candidates still open: a kind already selected is not offered again, except that a
    /// selected global effect may be refined into one per group (replacing it).
    fn open<'c>(&self, candidates: &'c [EffectRequest]) -> Vec<&'c EffectRequest> {
        candidates
            .iter()
            .filter(|c| {
                !self.selected.iter().any(|s| {
                    s.kind() == c.kind()
                        && !(matches!(s, EffectRequest::Global(_))
                            && matches!(c, EffectRequest::PerGroup(_)))
                })
            })
            .collect()
    }

    /// Make candidate `i` of `scored` part of the model; returns its label, the errors after
    /// and the model's likelihood score.
    fn adopt(
        &mut self,
        i: usize,
        scored: &Scored,
        open: &[&EffectRequest],
        w: Weighting,
    ) -> Result<(String, ErrorTable, Likelihood), FitError> {
        // The model or the data changes: a final fit checked before is not theirs.
        self.checked_fit = None;
        if i >= scored.n_effects + scored.n_impact {
            let (j, theta) = scored.noise_fits[i - scored.n_effects]
                .clone()
                .expect("eligible means fitted");
            self.adopt_delivery(j, theta);
        } else if i >= scored.n_effects {
            let (j, theta) = scored.noise_fits[i - scored.n_effects]
                .clone()
                .expect("eligible means fitted");
            let (noise, nd, nf) = self.noise_options.swap_remove(j);
            let exact = std::mem::replace(&mut self.data, nd);
            self.folds = nf;
            self.chosen_noise = Some(noise);
            self.noise_options.clear();
            self.adopt_refined(noise, &exact, theta, w)?;
            self.rebuild_delivery_options();
        } else {
            let (layout, run) = scored.fits[i].fit.as_ref().expect("eligible means fitted");
            self.base = layout.clone();
            self.theta_base = run.theta.clone();
            let refined = self
                .selected
                .iter()
                .position(|s| s.kind() == open[i].kind());
            match refined {
                Some(pos) => self.selected[pos] = open[i].clone(),
                None => self.selected.push(open[i].clone()),
            }
        }
        let errs = FitProblem::new(self.club, self.base.clone(), &self.data, w)
            .launch_errors(self.theta_base.as_slice())?;
        Ok((
            scored.results[i].label.clone(),
            launch_error_table(&self.groups, &errs),
            self.likelihood_of(&errs),
        ))
    }

    /// One step of forward selection; `None` when nothing is left to offer.
    pub(super) fn step(
        &mut self,
        step_index: usize,
        candidates: &[EffectRequest],
    ) -> Result<Option<Step>, FitError> {
        let base_labels: Vec<String> = self.selected.iter().map(EffectRequest::label).collect();
        let base_errors = self.errors_of(&self.base, self.theta_base.as_slice())?;
        // With a known noise floor, physics is offered only while structure remains above it.
        let at_noise_floor = self.at_noise_floor(&base_errors)?;
        let open = if at_noise_floor {
            Vec::new()
        } else {
            self.open(candidates)
        };
        let impact_open = self.chosen_noise.is_none() && !self.noise_options.is_empty();
        if open.is_empty() && !impact_open && self.open_delivery_options().is_empty() {
            return Ok(at_noise_floor.then(|| Step {
                base: base_labels,
                noise_scales: noise_scales(&base_errors),
                base_cv_chi2: None,
                candidates: Vec::new(),
                selected: None,
                after: launch_error_table(&self.groups, &base_errors),
                fit: self.likelihood_of(&base_errors),
                at_noise_floor,
                alias: None,
                rivals: Vec::new(),
                alike: Vec::new(),
                swap: None,
            }));
        }
        let sigma = noise_scales(&base_errors);
        let scored = self.score(step_index, &open, &base_errors, sigma)?;
        self.promising = scored.results[..scored.n_effects]
            .iter()
            .filter(|r| r.gain > r.n_params as f64 * self.penalty_per_param)
            .map(|r| r.label.clone())
            .collect();
        let order = select::by_margin(&scored.results);
        let (winner, alias) =
            select::arbitrate(&scored.results, &scored.explained, &order, scored.n_effects);
        let (rivals, alike) = match winner {
            Some(i) if i < scored.n_effects => (
                select::rivals(
                    &scored.results,
                    &scored.explained,
                    &order,
                    i,
                    scored.n_effects,
                ),
                select::most_alike(&scored.results, &scored.explained, i, scored.n_effects),
            ),
            _ => (Vec::new(), Vec::new()),
        };
        let (chosen, after, fit) = match winner {
            Some(i) => {
                let (label, after, fit) =
                    self.adopt(i, &scored, &open, Weighting::launch(&sigma))?;
                if i < scored.n_effects {
                    let kin = select::kin(&scored.results, &scored.explained, i, scored.n_effects)
                        .into_iter()
                        .map(|(j, r)| (open[j].clone(), r))
                        .collect();
                    self.kin_of
                        .retain(|(_, req, _)| req.kind() != open[i].kind());
                    self.kin_of.push((label.clone(), open[i].clone(), kin));
                    let near =
                        select::near(&scored.results, &scored.explained, i, scored.n_effects)
                            .into_iter()
                            .map(|(j, r)| (open[j].clone(), r))
                            .collect();
                    self.near_of.retain(|(req, _)| req.kind() != open[i].kind());
                    self.near_of.push((open[i].clone(), near));
                }
                (Some(label), after, fit)
            }
            None => {
                self.last_scored = Some(unresolved::LastScored {
                    base: base_labels.clone(),
                    results: scored.results.clone(),
                    explained: scored.explained.clone(),
                    n_effects: scored.n_effects,
                });
                (
                    None,
                    launch_error_table(&self.groups, &base_errors),
                    self.likelihood_of(&base_errors),
                )
            }
        };
        Ok(Some(Step {
            base: base_labels,
            noise_scales: sigma,
            base_cv_chi2: Some(scored.base_cv),
            candidates: order.iter().map(|&i| scored.results[i].clone()).collect(),
            selected: chosen,
            after,
            fit,
            at_noise_floor,
            alias,
            rivals,
            alike,
            swap: None,
        }))
    }

    /// Calibrate the selected effects on all shots and read aliases and ambiguities.
    pub(super) fn finish(
        mut self,
        (fold_by, n_folds): (FoldBy, usize),
        steps: Vec<Step>,
        (before, nominal_fit): (ErrorTable, Likelihood),
        (warnings, candidates): (Vec<String>, &[EffectRequest]),
    ) -> Result<Diagnosis, FitError> {
        // A level selected from the data, refined once more on the final model.
        if let (Some(noise), None) = (self.chosen_noise, self.opts.impact_noise) {
            let exact = self.data.clone().with_impact_noise(None)?;
            let w = Weighting::launch(&noise_scales(
                &self.errors_of(&self.base, self.theta_base.as_slice())?,
            ));
            let theta = self.theta_base.clone();
            if self.adopt_refined(noise, &exact, theta, w)? {
                // The data and the base changed: the check's final fit is not theirs.
                self.checked_fit = None;
            }
        }
        let unresolved = self.unresolved(candidates, steps.len())?;
        let (estimates, after, out_club, aliases) = match self.take_final_calibration()? {
            None => (Vec::new(), before.clone(), self.club.clone(), Vec::new()),
            Some(cal) => {
                let aliases = honest::aliases(&cal.params, cal.correlation.as_ref());
                (cal.params, cal.after, cal.club, aliases)
            }
        };
        // The final model's score: the reported values on the base layout (the nominal
        // model's errors when nothing is selected).
        let final_theta: Vec<f64> = estimates.iter().map(|p| p.value).collect();
        let final_errors = self.errors_of(&self.base, &final_theta)?;
        let final_fit = self.likelihood_of(&final_errors);
        let strata = (!estimates.is_empty()).then(|| {
            let theta = DVector::from_vec(final_theta);
            super::strata::check(
                self.club,
                &self.data,
                (&self.base, &theta, noise_scales(&final_errors)),
                &estimates,
                super::strata::families(&self.data, self.opts.fold_keys.as_ref()),
                self.opts.max_iters,
            )
        });
        let mut ambiguities = self.ambiguities(&estimates)?;
        let rival_families = self.rival_families(&out_club, &estimates, &mut ambiguities)?;
        Ok(Diagnosis {
            fold_by,
            folds: n_folds,
            n_shots: self.data.len(),
            steps,
            selected: self.selected.iter().map(EffectRequest::label).collect(),
            estimates,
            before,
            after,
            club: out_club,
            impact_noise: self.chosen_noise,
            impact_noise_estimated: self.chosen_noise.is_some() && self.opts.impact_noise.is_none(),
            delivery_noise: self.chosen_delivery,
            delivery_noise_estimated: self.chosen_delivery.is_some()
                && self.opts.delivery_noise().is_none(),
            warnings,
            aliases,
            ambiguities,
            club_mismatch: None,
            nominal_fit,
            final_fit,
            strata,
            shared_signals: Vec::new(),
            rival_families,
            unresolved,
        })
    }
}
