//! Re-selection, the last resort of the swap rounds (`docs/diagnose-selection.md`), tried at
//! most once: when no single or pair change pays but the selection still has questioned
//! effects (stand-ins, or effects aliased with another selected one), those are all taken out
//! together and forward selection is run again from what is left, by its own rule (penalty, multiplicity, noise-floor
//! stop). The new model replaces the current one only when it fits the held-out golfers better
//! by more than its extra parameters cost: `CV(new) + k_new·ln n < CV(current) + k_now·ln n`,
//! both CV χ² with the current model's noise scales and folds, and selects other effects (the
//! same effects re-selected in another order are the same model, not a change).
//!
//! Why: a stand-in chosen early (a 2-parameter `ball_offset` taking the place of the compression
//! lever and the COR's speed dependence at step 2) is later propped up by another stand-in it
//! is aliased with (`loft_bias`), and the two can only leave together with a third; no exchange
//! of one or two effects reaches the model a different order would have found.

use super::super::{CandidateResult, Step, Swap};
use super::Search;
use crate::fit::calibrate::noise_scales;
use crate::fit::{EffectRequest, FitError, Weighting};
use crate::stats::launch_error_table;

impl Search<'_> {
    fn labels_of(&self, reqs: &[&EffectRequest]) -> String {
        reqs.iter()
            .map(|r| r.label())
            .collect::<Vec<_>>()
            .join(" + ")
    }

    /// Try a re-selection without the questioned effects; on success the search becomes the
    /// new model and the steps to report are returned (the decision, then the new forward
    /// steps). `first_index` is the index the first reported step will have.
    pub(in crate::diagnose) fn reselect(
        &mut self,
        candidates: &[EffectRequest],
        first_index: usize,
    ) -> Result<Option<Vec<Step>>, FitError> {
        if self.selected.is_empty() || self.reselected {
            return Ok(None);
        }
        self.reselected = true;
        let errors = self.errors_of(&self.base, self.theta_base.as_slice())?;
        let sigma = noise_scales(&errors);
        let w = Weighting::launch(&sigma);
        let (questioned, _) = self.questioned(w);
        if questioned.is_empty() {
            return Ok(None);
        }
        let mut trial = self.clone();
        trial.progress = None;
        (trial.base, trial.theta_base) = self.refit_without(&questioned, w)?;
        let out_kinds: Vec<_> = questioned
            .iter()
            .map(|&o| self.selected[o].kind())
            .collect();
        trial.selected.retain(|s| !out_kinds.contains(&s.kind()));
        trial
            .kin_of
            .retain(|(_, r, _)| !out_kinds.contains(&r.kind()));
        let mut steps = Vec::new();
        for _ in 0..self.opts.max_steps {
            let Some(step) = trial.step(first_index + 1 + steps.len(), candidates)? else {
                break;
            };
            if step.selected.is_none() {
                // The stop is reported by the forward step that follows (the same model).
                break;
            }
            steps.push(step);
        }
        let cv_of = |s: &Search| s.cv_at(&s.base, &s.theta_base, w);
        let (cv_now, cv_new) = (cv_of(self)?, cv_of(&trial)?);
        let k_net = trial.base.len() as f64 - self.base.len() as f64;
        let gain = cv_now - cv_new;
        let penalty = k_net * self.penalty_per_param;
        // The same effects in another order are the same model (its CV χ² moves only by the
        // fits' tolerance): no change to make.
        let same_effects = trial.selected.len() == self.selected.len()
            && trial.selected.iter().all(|r| self.selected.contains(r));
        if !gain.is_finite() || gain - penalty <= 0.0 || same_effects {
            return Ok(None);
        }
        let decision = self.decision(
            &trial,
            &questioned,
            (sigma, cv_now, cv_new),
            (gain, penalty),
        )?;
        *self = trial;
        Ok(Some(std::iter::once(decision).chain(steps).collect()))
    }

    /// The reported step of an accepted re-selection from this model to `trial`.
    fn decision(
        &self,
        trial: &Search,
        questioned: &[usize],
        (sigma, cv_now, cv_new): ([f64; 5], f64, f64),
        (gain, penalty): (f64, f64),
    ) -> Result<Step, FitError> {
        let kind_in = |s: &Search, r: &EffectRequest| s.selected.iter().any(|x| x == r);
        let gone: Vec<&EffectRequest> = self
            .selected
            .iter()
            .filter(|r| !kind_in(trial, r))
            .collect();
        let new: Vec<&EffectRequest> = trial
            .selected
            .iter()
            .filter(|r| !kind_in(self, r))
            .collect();
        let candidate = CandidateResult {
            label: format!(
                "re-select without {}",
                self.labels_of(
                    &questioned
                        .iter()
                        .map(|&o| &self.selected[o])
                        .collect::<Vec<_>>()
                )
            ),
            n_params: trial.base.len(),
            params: Vec::new(),
            cv_chi2: cv_new,
            gain,
            spread_gain: None,
            penalty,
            rms_reduction: [0.0; 5],
            unidentified: Vec::new(),
            converged: true,
            failure: None,
        };
        let swap = Swap {
            out: self.labels_of(&gone),
            inn: (!new.is_empty()).then(|| self.labels_of(&new)),
            cv_before: cv_now,
            cv_after: cv_new,
        };
        let base = self.selected.iter().map(EffectRequest::label).collect();
        trial.swap_step(base, sigma, vec![candidate], swap)
    }

    /// The reported step of a change `swap` already made to this model (a swap round's or a
    /// re-selection's): `base` the effects before it, `candidates` the options weighed, and the
    /// errors after it.
    pub(in crate::diagnose) fn swap_step(
        &self,
        base: Vec<String>,
        noise_scales: [f64; 5],
        candidates: Vec<CandidateResult>,
        swap: Swap,
    ) -> Result<Step, FitError> {
        let after_errors = self.errors_of(&self.base, self.theta_base.as_slice())?;
        Ok(Step {
            base,
            noise_scales,
            base_cv_chi2: Some(swap.cv_before),
            candidates,
            selected: None,
            after: launch_error_table(&self.groups, &after_errors),
            fit: self.likelihood_of(&after_errors),
            at_noise_floor: false,
            alias: None,
            rivals: Vec::new(),
            alike: Vec::new(),
            swap: Some(swap),
        })
    }
}
