//! Has each selected effect earned its place in the final model? (`docs/diagnose-selection.md`,
//! "Earned its place": backward elimination by forward selection's own criterion.)
//!
//! Forward selection admits an effect by its gain over the model of its step. Effects selected
//! later, a swap, or the impact-noise level refined since can take that gain over, and nothing
//! re-asks the question: the 3000-shot `compliant_driver` world keeps `added_mass` (4.7 g at
//! its step) whose signal `hosel_mass`, selected three steps later, carries; taken out of the
//! final model the held-out χ² rises by 1.1, less than its penalty `ln n` = 8.0. So when the
//! selection stands, each selected effect is taken out of the current model, the rest refitted
//! (warm-started from the current values) and cross-validated with the current noise scales and
//! folds. An effect keeps its place when the held-out χ² rises by more than its parameters'
//! penalty `k·ln n`, less `ln n` for each stand-in the removal creates (a value pushed outside
//! its plausible range carries the removed effect's signal as a proxy, so the smaller model
//! claims that physics too: the accounting of `alias.rs`); the one that falls shortest is removed (a removal step, like a swap
//! round's), and the question is asked again of the smaller model. The criterion is forward
//! selection's (CV χ² + `k·ln n`), so a removal lowers it and can neither add an effect nor
//! undo itself by a forward step (which would need the same gain plus `2·ln m`).

use nalgebra::DVector;
use rayon::prelude::*;

use super::super::evaluate::{self, cv_chi2};
use super::super::select::by_margin;
use super::super::{CandidateResult, Step, Swap};
use super::Search;
use crate::fit::calibrate::noise_scales;
use crate::fit::{FitError, ParamLayout, Weighting};

/// The test of one selected effect against the current model.
#[derive(Debug, Clone)]
pub(in crate::diagnose) struct Earned {
    /// Index into `selected`.
    index: usize,
    /// Rise of the cross-validated χ² when the effect is taken out (the rest refitted).
    cv_loss: f64,
    /// Its parameters' penalty, `k·ln n`.
    penalty: f64,
    /// The model without it, refitted on all shots.
    without: (ParamLayout, DVector<f64>),
    /// Its cross-validated χ².
    cv_without: f64,
}

/// The effect that has not earned its place (held-out χ² rise at most its penalty) and falls
/// shortest of it, if any: `(cv_loss, penalty)` per selected effect, in selection order; ties
/// keep the earlier one.
pub(in crate::diagnose) fn least_earned(tests: &[(f64, f64)]) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (i, &(loss, penalty)) in tests.iter().enumerate() {
        let short = loss - penalty;
        if short.is_finite() && short <= 0.0 && best.is_none_or(|(_, b)| short < b) {
            best = Some((i, short));
        }
    }
    best.map(|(i, _)| i)
}

/// What a removal must beat: the removed parameters' `k_out·ln n`, less `ln n` for each new
/// stand-in of the smaller model (see the module docs).
pub(in crate::diagnose) fn removal_penalty(
    k_out: usize,
    new_stand_ins: usize,
    penalty_per_param: f64,
) -> f64 {
    (k_out as f64 - new_stand_ins as f64) * penalty_per_param
}

impl Search<'_> {
    /// The cross-validated χ² of `layout` at `theta` (its all-shots fit) with weights `w`, the
    /// folds started from their rows of one evaluation on all shots there, as a forward step
    /// cross-validates its base ([`cv_chi2`]; their own fits when it cannot be made).
    pub(in crate::diagnose) fn cv_at(
        &self,
        layout: &ParamLayout,
        theta: &DVector<f64>,
        w: Weighting,
    ) -> Result<f64, FitError> {
        let at = evaluate::all_shots_at(self.club, layout, &self.data, w, theta);
        self.cv_given(layout, theta, w, at.as_ref().map(|(r, j)| (r, j)))
    }

    /// [`Self::cv_at`] given the residuals and Jacobian on all shots at `theta` (`at`, `None`
    /// when they cannot be evaluated there).
    pub(in crate::diagnose) fn cv_given(
        &self,
        layout: &ParamLayout,
        theta: &DVector<f64>,
        w: Weighting,
        at: Option<evaluate::AllShots>,
    ) -> Result<f64, FitError> {
        cv_chi2(
            self.club,
            layout,
            &self.folds,
            w,
            theta,
            at,
            self.opts.max_iters,
            None,
            self.opts.cancel.as_ref(),
        )
    }

    /// Every selected effect tested against the current model (see the module docs), and the
    /// current model's CV χ².
    fn earned_places(&self, w: Weighting) -> Result<(f64, Vec<Earned>), FitError> {
        let cv_of = |layout: &ParamLayout, theta: &DVector<f64>| self.cv_at(layout, theta, w);
        let cv_now = cv_of(&self.base, &self.theta_base)?;
        let before = Self::implausible_kinds(&self.base, &self.theta_base);
        let tests = (0..self.selected.len())
            .into_par_iter()
            .map(|o| {
                let (layout, theta) = self.refit_without(&[o], w)?;
                let cv_without = cv_of(&layout, &theta)?;
                // A stand-in the removal creates carries the removed effect's signal as a
                // proxy: the smaller model claims that physics too, one parameter each.
                let new_stand_ins = Self::implausible_kinds(&layout, &theta)
                    .iter()
                    .filter(|k| !before.contains(k))
                    .count();
                let k_out = self.base.len() - layout.len();
                Ok(Earned {
                    index: o,
                    cv_loss: cv_without - cv_now,
                    penalty: removal_penalty(k_out, new_stand_ins, self.penalty_per_param),
                    without: (layout, theta),
                    cv_without,
                })
            })
            .collect::<Result<Vec<_>, FitError>>()?;
        Ok((cv_now, tests))
    }

    /// Remove the selected effect that has least earned its place, if one has not, and report
    /// the removal as a step (every effect's test is its candidate table).
    pub(in crate::diagnose) fn prune(&mut self) -> Result<Option<Step>, FitError> {
        if self.selected.is_empty() {
            return Ok(None);
        }
        let errors = self.errors_of(&self.base, self.theta_base.as_slice())?;
        let sigma = noise_scales(&errors);
        let w = Weighting::launch(&sigma);
        let (cv_now, tests) = self.earned_places(w)?;
        let pairs: Vec<(f64, f64)> = tests.iter().map(|t| (t.cv_loss, t.penalty)).collect();
        let Some(worst) = least_earned(&pairs) else {
            return Ok(None);
        };
        let rms = evaluate::rms_per_component(&errors);
        let mut candidates = Vec::with_capacity(tests.len());
        for t in &tests {
            let after = self.errors_of(&t.without.0, t.without.1.as_slice())?;
            let rms_after = evaluate::rms_per_component(&after);
            candidates.push(CandidateResult::removal(
                &self.selected[t.index].label(),
                (t.cv_without, -t.cv_loss, -t.penalty),
                &rms,
                &rms_after,
            ));
        }
        let order = by_margin(&candidates);
        let base_labels: Vec<String> = self.selected.iter().map(|r| r.label()).collect();
        let t = &tests[worst];
        let out = self.selected[t.index].clone();
        (self.base, self.theta_base) = t.without.clone();
        self.selected.retain(|s| s.kind() != out.kind());
        self.kin_of.retain(|(_, r, _)| r.kind() != out.kind());
        let swap = Swap {
            out: out.label(),
            inn: None,
            cv_before: cv_now,
            cv_after: t.cv_without,
        };
        let table = order.into_iter().map(|i| candidates[i].clone()).collect();
        self.swap_step(base_labels, sigma, table, swap).map(Some)
    }
}

#[cfg(test)]
mod tests {
    use super::{least_earned, removal_penalty};

    /// The 600-shot `compliant_location_noise` world: taking `contact_time` (0.21 ms) out
    /// raises the held-out χ² by 5.0 against `ln 600` = 6.4, but pushes `loft_bias` to 3.3°
    /// (a stand-in): the smaller model reads the contact's signal as an implausible launch
    /// bias, so it is charged for it and `contact_time` keeps its place.
    #[test]
    fn a_removal_that_creates_a_stand_in_is_charged_for_it() {
        let ln_n = 600f64.ln();
        assert!(least_earned(&[(5.0, removal_penalty(1, 0, ln_n))]).is_some());
        assert_eq!(least_earned(&[(5.0, removal_penalty(1, 1, ln_n))]), None);
        // A removal that helps out of sample still goes when it creates a stand-in.
        assert!(least_earned(&[(-3.0, removal_penalty(1, 1, ln_n))]).is_some());
        assert_eq!(removal_penalty(3, 1, 2.0), 4.0);
    }

    /// The 3000-shot `compliant_driver` final model (held-out χ² rise without each effect,
    /// penalty): `cor_radial` (0.0 against 8.0, on its no-effect bound) and `added_mass` (1.1)
    /// have not earned their places; `cor_radial` falls shortest and goes first.
    #[test]
    fn the_effect_that_falls_shortest_of_its_penalty_is_removed_first() {
        let driver = [
            (45988.5, 24.0),
            (2147.4, 8.0),
            (8218.9, 8.0),
            (127.0, 24.0),
            (1.1, 8.0),
            (693.3, 8.0),
            (0.0, 8.0),
            (78.0, 8.0),
            (37.1, 8.0),
        ];
        assert_eq!(least_earned(&driver), Some(6));
        // Every effect earns its place: nothing is removed.
        assert_eq!(least_earned(&[(143.6, 8.0), (280.3, 16.0)]), None);
        // A rise equal to the penalty has not earned it (the criterion does not drop).
        assert_eq!(least_earned(&[(100.0, 8.0), (8.0, 8.0)]), Some(1));
        // A failed cross-validation (NaN) is not a reason to remove.
        assert_eq!(least_earned(&[(f64::NAN, 8.0)]), None);
    }
}
