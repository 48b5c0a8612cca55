//! Swap and prune after forward selection (stepwise refinement, `docs/diagnose-selection.md`):
//! greedy forward selection cannot undo a step, so an effect that won early as a stand-in
//! (e.g. a 3-parameter `com_offset` soaking up a mass at the hosel) keeps its place even after
//! later effects make a plausible 1-parameter reading the better model. Each round tries, for
//! every selected physical effect, removing it and replacing it with every unselected
//! candidate (the rest refitted, warm-started), and makes the one change that lowers the
//! cross-validated χ² plus penalty most. Measurement candidates (impact- and delivery-noise
//! levels) stay as chosen.

use nalgebra::DVector;
use rayon::prelude::*;

use super::super::evaluate::{self, cv_chi2, EffectFit, StepBase};
use super::super::{select, CandidateResult, Step, Swap};
use super::Search;
use crate::fit::calibrate::noise_scales;
use crate::fit::{fit_quietly, EffectRequest, FitError, ParamLayout, Weighting};
use crate::stats::launch_error_table;

/// The model without one selected effect: its layout, warm start, errors on all shots and
/// cross-validated χ².
struct Reduced {
    layout: ParamLayout,
    theta: DVector<f64>,
    errors: Vec<[f64; 5]>,
    cv: f64,
    /// Parameters the removed effect had.
    k_out: usize,
}

/// One option of a round: remove selected effect `out`, and add `inn` if any.
struct Option_ {
    out: usize,
    inn: Option<EffectRequest>,
    result: CandidateResult,
    fit: Option<EffectFit>,
}

impl Search<'_> {
    fn reduced(&self, out: usize, w: Weighting) -> Result<Reduced, FitError> {
        let kind = self.selected[out].kind();
        let mut effects = Vec::new();
        let mut theta = Vec::new();
        let mut k_out = 0;
        for (i, e) in self.base.effects().iter().enumerate() {
            let vals = &self.theta_base.as_slice()[self.base.range(i)];
            if e.kind == kind {
                k_out += vals.len();
            } else {
                effects.push(e.clone());
                theta.extend_from_slice(vals);
            }
        }
        let layout = ParamLayout::new(effects)?;
        let theta = DVector::from_vec(theta);
        let errors = self.errors_of(&layout, theta.as_slice())?;
        let cv = cv_chi2(
            self.club,
            &layout,
            &self.folds,
            w,
            &theta,
            None,
            self.opts.max_iters,
            None,
        )?;
        Ok(Reduced {
            layout,
            theta,
            errors,
            cv,
            k_out,
        })
    }

    /// Score every removal and replacement against the current model (CV χ² `current_cv`,
    /// weighting `w`): gain `current_cv − CV(new)`, penalty `(k_in − k_out)·ln n` plus, for a
    /// replacement, `2·ln m` over the `m` replacements offered (forward selection's rule).
    fn swap_options(
        &self,
        candidates: &[EffectRequest],
        (current_cv, sigma, w): (f64, [f64; 5], Weighting),
        rms_now: [f64; 5],
    ) -> Result<Vec<Option_>, FitError> {
        let reduced: Vec<Reduced> = (0..self.selected.len())
            .into_par_iter()
            .map(|o| self.reduced(o, w))
            .collect::<Result<_, _>>()?;
        let unselected: Vec<&EffectRequest> = candidates
            .iter()
            .filter(|c| !self.selected.iter().any(|s| s.kind() == c.kind()))
            .collect();
        let n_replace = self.selected.len() * unselected.len();
        let multiplicity = 2.0 * (n_replace.max(1) as f64).ln();
        let pairs: Vec<(usize, &EffectRequest)> = (0..self.selected.len())
            .flat_map(|o| unselected.iter().map(move |c| (o, *c)))
            .collect();
        let replaced: Vec<Option_> = pairs
            .par_iter()
            .map(|&(o, c)| {
                let r = &reduced[o];
                let b = StepBase {
                    club: self.club,
                    data: &self.data,
                    folds: &self.folds,
                    layout: &r.layout,
                    theta: &r.theta,
                    errors: &r.errors,
                    sigma,
                    w,
                    rms: evaluate::rms_per_component(&r.errors),
                    cv: r.cv,
                    max_iters: self.opts.max_iters,
                    progress: None,
                    spread: None,
                };
                let f = evaluate::evaluate_effect(&b, c, self.penalty_per_param, multiplicity);
                let mut result = f.result.clone();
                result.label = format!("{} → {}", self.selected[o].label(), c.label());
                result.gain = current_cv - result.cv_chi2;
                result.penalty = (result.n_params as f64 - r.k_out as f64) * self.penalty_per_param
                    + multiplicity;
                Option_ {
                    out: o,
                    inn: Some(c.clone()),
                    result,
                    fit: Some(f),
                }
            })
            .collect();
        let removals = reduced.iter().enumerate().map(|(o, r)| {
            let mut result = CandidateResult {
                label: format!("remove {}", self.selected[o].label()),
                n_params: 0,
                params: Vec::new(),
                cv_chi2: r.cv,
                gain: current_cv - r.cv,
                spread_gain: None,
                penalty: -(r.k_out as f64) * self.penalty_per_param,
                rms_reduction: [0.0; 5],
                unidentified: Vec::new(),
                converged: true,
                failure: None,
            };
            let rms = evaluate::rms_per_component(&r.errors);
            result.rms_reduction = std::array::from_fn(|c| (rms_now[c] - rms[c]) / rms_now[c]);
            Option_ {
                out: o,
                inn: None,
                result,
                fit: None,
            }
        });
        Ok(removals.chain(replaced).collect())
    }

    /// One round of swaps: the change that lowers CV χ² + penalty most, made and reported as a
    /// step; `None` when no removal or replacement improves (or nothing is selected).
    pub(in crate::diagnose) fn swap_round(
        &mut self,
        candidates: &[EffectRequest],
    ) -> Result<Option<Step>, FitError> {
        if self.selected.is_empty() {
            return Ok(None);
        }
        let base_labels: Vec<String> = self.selected.iter().map(|r| r.label()).collect();
        let errors = self.errors_of(&self.base, self.theta_base.as_slice())?;
        let sigma = noise_scales(&errors);
        let w = Weighting::launch(&sigma);
        let current_cv = cv_chi2(
            self.club,
            &self.base,
            &self.folds,
            w,
            &self.theta_base,
            None,
            self.opts.max_iters,
            None,
        )?;
        let rms_now = evaluate::rms_per_component(&errors);
        let mut options = self.swap_options(candidates, (current_cv, sigma, w), rms_now)?;
        let results: Vec<CandidateResult> = options.iter().map(|o| o.result.clone()).collect();
        let order = select::by_margin(&results);
        let Some(&best) = order
            .iter()
            .find(|&&i| results[i].eligible() && results[i].margin() > 0.0)
        else {
            return Ok(None);
        };
        let chosen = options.swap_remove(best);
        let out_label = self.selected[chosen.out].label();
        let out_kind = self.selected[chosen.out].kind();
        match (&chosen.inn, chosen.fit) {
            (
                Some(inn),
                Some(EffectFit {
                    fit: Some((layout, run)),
                    ..
                }),
            ) => {
                self.base = layout;
                self.theta_base = run.theta;
                self.selected[chosen.out] = inn.clone();
                self.kin_of.push((inn.label(), inn.clone(), Vec::new()));
            }
            _ => {
                let r = self.reduced(chosen.out, w)?;
                let run = fit_quietly(
                    self.club,
                    &r.layout,
                    &self.data,
                    w,
                    &r.theta,
                    self.opts.max_iters,
                )?;
                self.base = r.layout;
                self.theta_base = run.theta;
                self.selected.remove(chosen.out);
            }
        }
        self.kin_of.retain(|(_, req, _)| req.kind() != out_kind);
        let after_errors = self.errors_of(&self.base, self.theta_base.as_slice())?;
        Ok(Some(Step {
            base: base_labels,
            noise_scales: sigma,
            base_cv_chi2: current_cv,
            candidates: order.iter().map(|&i| results[i].clone()).collect(),
            selected: None,
            after: launch_error_table(&self.groups, &after_errors),
            at_noise_floor: false,
            alias: None,
            rivals: Vec::new(),
            swap: Some(Swap {
                out: out_label,
                inn: chosen.inn.as_ref().map(EffectRequest::label),
                cv_before: current_cv,
                cv_after: results[best].cv_chi2,
            }),
        }))
    }
}
