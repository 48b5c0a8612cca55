//! Scoring one step: the base's cross-validation and every open candidate (effects, impact-noise
//! levels, delivery-noise levels) fitted and cross-validated against it, side by side.

use rayon::prelude::*;

use super::super::evaluate::{self, cv_chi2, EffectFit, NoiseFit, StepBase};
use super::super::spread::SpreadModel;
use super::super::CandidateResult;
use super::Search;
use crate::fit::{EffectRequest, FitError, Weighting};

/// The scored candidates of one step: effects first (`n_effects` of them), then noise levels.
pub(super) struct Scored {
    pub(super) results: Vec<CandidateResult>,
    pub(super) explained: Vec<Option<Vec<f64>>>,
    pub(super) fits: Vec<EffectFit>,
    pub(super) noise_fits: Vec<NoiseFit>,
    pub(super) n_effects: usize,
    /// Impact-noise levels among the measurement candidates (the rest are delivery levels).
    pub(super) n_impact: usize,
    pub(super) base_cv: f64,
}

impl Search<'_> {
    /// Fit, score and cross-validate every open effect and (while no level is chosen) every
    /// impact-noise level against the base model.
    pub(super) fn score(
        &self,
        step_index: usize,
        open: &[&EffectRequest],
        base_errors: &[[f64; 5]],
        sigma: [f64; 5],
    ) -> Result<Scored, FitError> {
        let w = Weighting::launch(&sigma);
        let n_folds = self.folds.train.len();
        let n_noise = if self.chosen_noise.is_none() {
            self.noise_options.len()
        } else {
            0
        };
        let n_delivery = self.open_delivery_options().len();
        if let Some(p) = self.progress {
            p.step(
                step_index + 1,
                n_folds * (1 + open.len() + n_noise + n_delivery) + open.len(),
            );
        }
        // One evaluation on all shots at the base point serves every fold's start.
        let at_base =
            evaluate::all_shots_at(self.club, &self.base, &self.data, w, &self.theta_base);
        // With known instrument noise, impact-noise levels are scored by the spread
        // (`super::spread`); the base is the same model with exact locations.
        let spread = match &self.opts.noise_floor {
            Some(inst) if n_noise > 0 => {
                Some(SpreadModel::new(&self.base_club()?, self.shots, inst)?)
            }
            _ => None,
        };
        let spread_base = spread
            .as_ref()
            .and_then(|m| Some((m, m.deviance(base_errors, None)?)));
        // The base's cross-validation runs beside the candidates' (no barrier between them on
        // two cores): the candidates score against a base χ² not yet known (`cv` NaN) and
        // their gains are completed below, the same subtraction as before.
        let b = StepBase {
            club: self.club,
            data: &self.data,
            folds: &self.folds,
            layout: &self.base,
            theta: &self.theta_base,
            errors: base_errors,
            sigma,
            w,
            rms: evaluate::rms_per_component(base_errors),
            cv: f64::NAN,
            at: at_base.as_ref().map(|(r, j)| (r, j)),
            max_iters: self.opts.max_iters,
            progress: self.progress,
            cancel: self.opts.cancel.as_ref(),
            spread: spread_base,
        };
        let (base_cv, (mut fits, mut noise, mut delivery)) = rayon::join(
            || {
                cv_chi2(
                    b.club,
                    b.layout,
                    b.folds,
                    b.w,
                    b.theta,
                    b.at,
                    b.max_iters,
                    b.progress,
                    b.cancel,
                )
            },
            || self.candidates(&b, open, n_noise),
        );
        if crate::cancel::cancelled(b.cancel) {
            return Err(FitError::Cancelled);
        }
        let base_cv = base_cv?;
        let complete = |r: &mut CandidateResult| {
            if r.spread_gain.is_none() && !r.cv_chi2.is_nan() {
                r.gain = base_cv - r.cv_chi2;
            }
        };
        fits.iter_mut().for_each(|f| complete(&mut f.result));
        noise
            .iter_mut()
            .chain(delivery.iter_mut())
            .for_each(|(r, _)| complete(r));
        let mut results: Vec<CandidateResult> = fits.iter().map(|f| f.result.clone()).collect();
        let explained = fits.iter().map(|f| f.explained.clone()).collect();
        let mut noise_fits = Vec::new();
        for (r, f) in noise.into_iter().chain(delivery) {
            results.push(r);
            noise_fits.push(f);
        }
        Ok(Scored {
            n_effects: fits.len(),
            n_impact: n_noise,
            results,
            explained,
            fits,
            noise_fits,
            base_cv,
        })
    }

    /// The open effects, the first `n_noise` impact-noise levels and the open delivery-noise
    /// levels fitted and cross-validated against the base `b`, all at once.
    #[allow(clippy::type_complexity)]
    fn candidates(
        &self,
        b: &StepBase,
        open: &[&EffectRequest],
        n_noise: usize,
    ) -> (
        Vec<EffectFit>,
        Vec<(CandidateResult, NoiseFit)>,
        Vec<(CandidateResult, NoiseFit)>,
    ) {
        // Choosing the best of `m` physical candidates: a useless candidate's out-of-sample
        // gain has an upper tail of about e^(−g/2), so the best of m clears a threshold c with
        // probability about m·e^(−c/2); adding 2·ln m to every physical candidate's penalty
        // keeps that what a single candidate has (a Bonferroni correction of the BIC penalty,
        // docs/diagnose-selection.md). The impact-noise levels are one measurement question
        // asked at several sizes, not m physical claims, and keep the plain penalty.
        let multiplicity = 2.0 * (open.len().max(1) as f64).ln();
        let penalty = self.penalty_per_param;
        let (fits, (noise, delivery)) = rayon::join(
            || {
                open.par_iter()
                    .map(|c| evaluate::evaluate_effect(b, c, penalty, multiplicity))
                    .collect()
            },
            || {
                rayon::join(
                    || {
                        self.noise_options[..n_noise]
                            .par_iter()
                            .enumerate()
                            .map(|(j, (n, d, f))| {
                                evaluate::noise_candidate(b, (j, n, d, f), penalty)
                            })
                            .collect()
                    },
                    || self.score_delivery(b),
                )
            },
        );
        (fits, noise, delivery)
    }
}
