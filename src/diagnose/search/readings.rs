//! The readings of the final model that change how a selection is reported, never what is
//! selected: each selected effect's rivals among its kin (swapped in, refitted) and its check
//! against its rival family ([`super::super::rival_family`]).

use rayon::prelude::*;

use super::super::evaluate::{self, StepBase};
use super::super::{honest, select};
use super::Search;
use crate::club::ClubSpec;
use crate::fit::calibrate::noise_scales;
use crate::fit::{EffectRequest, FitError, Weighting};

impl Search<'_> {
    /// Each selected effect with the kin that, swapped in for it in the final model, fit the
    /// shots nearly as well: `χ² + k·ln n` at most [`select::RIVAL_MARGIN`] above the final
    /// model's, on all shots with the final model's noise scales.
    pub(super) fn ambiguities(
        &self,
        estimates: &[crate::fit::ParamEstimate],
    ) -> Result<Vec<honest::Ambiguity>, FitError> {
        // Each selected effect's kin, and the candidates that nearly matched it at its step.
        let tried: Vec<Vec<&(EffectRequest, f64)>> = self
            .kin_of
            .iter()
            .map(|(_, req, kin)| {
                let near = self
                    .near_of
                    .iter()
                    .filter(|(r, _)| r == req)
                    .flat_map(|(_, n)| n.iter())
                    .filter(|(c, _)| !kin.iter().any(|(k, _)| k == c));
                kin.iter().chain(near).collect()
            })
            .collect();
        if tried.iter().all(Vec::is_empty) {
            return Ok(Vec::new());
        }
        let errors = self.errors_of(&self.base, self.theta_base.as_slice())?;
        let sigma = noise_scales(&errors);
        let w = Weighting::launch(&sigma);
        let final_run = crate::fit::fit_quietly(
            self.club,
            &self.base,
            &self.data,
            w,
            &self.theta_base,
            self.opts.max_iters,
        )?;
        let final_score = final_run.cost + self.base.len() as f64 * self.penalty_per_param;
        let b = StepBase {
            club: self.club,
            data: &self.data,
            folds: &self.folds,
            layout: &self.base,
            theta: &final_run.theta,
            errors: &errors,
            sigma,
            w,
            rms: evaluate::rms_per_component(&errors),
            cv: f64::NAN,
            at: None,
            max_iters: self.opts.max_iters,
            progress: None,
            cancel: self.opts.cancel.as_ref(),
            spread: None,
        };
        // Every selected effect's kin scored side by side (a selected effect has a few kin,
        // too few to keep both cores busy one effect at a time), then read effect by effect.
        let jobs: Vec<(usize, &EffectRequest, &(EffectRequest, f64))> = self
            .kin_of
            .iter()
            .zip(&tried)
            .enumerate()
            .flat_map(|(i, ((_, req, _), kin))| kin.iter().map(move |&k| (i, req, k)))
            .collect();
        let scored: Vec<(usize, Option<honest::Rival>)> = jobs
            .par_iter()
            .map(|&(i, req, (c, r))| {
                let rival = evaluate::swap_score(&b, req, c, self.penalty_per_param, final_score)
                    .and_then(|(params, gap)| {
                        (gap <= select::RIVAL_MARGIN)
                            .then(|| honest::Rival::new(c.label(), params, gap, *r))
                    });
                (i, rival)
            })
            .collect();
        let mut out = Vec::new();
        for (i, (label, _, _)) in self.kin_of.iter().enumerate() {
            let rivals: Vec<honest::Rival> = scored
                .iter()
                .filter(|(j, _)| *j == i)
                .filter_map(|(_, r)| r.clone())
                .collect();
            if rivals.is_empty() {
                continue;
            }
            let effect = label.split('@').next().unwrap_or(label);
            out.push(honest::Ambiguity {
                selected: label.clone(),
                estimates: estimates
                    .iter()
                    .filter(|p| p.effect == effect)
                    .cloned()
                    .collect(),
                rivals,
            });
        }
        Ok(out)
    }

    /// Each selected effect's check against its rival family ([`super::rival_family`]); the
    /// kin it names as plausible rivals join `ambiguities`.
    pub(super) fn rival_families(
        &self,
        out_club: &ClubSpec,
        estimates: &[crate::fit::ParamEstimate],
        ambiguities: &mut Vec<honest::Ambiguity>,
    ) -> Result<Vec<super::super::rival_family::FamilyCheck>, FitError> {
        let model = super::super::rival_family::FinalModel {
            club: out_club,
            n_file_effects: self.club.effects.len(),
            data: &self.data,
            shots: self.shots,
            estimates,
            fold_of: &self.fold_of,
            penalty_per_param: self.penalty_per_param,
        };
        let kin = |label: &str| {
            self.kin_of
                .iter()
                .find(|(l, _, _)| l == label)
                .map(|(_, _, k)| k.clone())
                .unwrap_or_default()
        };
        let checks = super::super::rival_family::check(&model, &kin)?;
        for c in &checks {
            let fresh: Vec<honest::Rival> =
                c.rivals.iter().filter(|r| r.plausible).cloned().collect();
            if fresh.is_empty() {
                continue;
            }
            let label = &c.check.label;
            match ambiguities.iter_mut().find(|a| &a.selected == label) {
                Some(a) => {
                    // The reading beside the location family replaces an implausible one.
                    for r in fresh {
                        a.rivals.retain(|old| old.label != r.label || old.plausible);
                        if !a.rivals.iter().any(|old| old.label == r.label) {
                            a.rivals.push(r);
                        }
                    }
                }
                None => ambiguities.push(honest::Ambiguity {
                    selected: label.clone(),
                    estimates: estimates
                        .iter()
                        .filter(|p| super::super::rival_family::estimate_of(p, label))
                        .cloned()
                        .collect(),
                    rivals: fresh,
                }),
            }
        }
        Ok(checks.into_iter().map(|c| c.check).collect())
    }
}
