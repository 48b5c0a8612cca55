//! The measurement candidates' data: impact-location noise levels and, while the instruments'
//! noise is unknown, delivery-noise levels (regression calibration of club speed, loft, path,
//! face, ... for a multiple of the camera class's delivery SDs, [`DeliveryNoise`]). Each level
//! is the same model on its own copy of the data; adopting one makes that copy the data, so
//! the other kind's levels are rebuilt from it.

use nalgebra::DVector;
use rayon::prelude::*;

use super::super::evaluate::{self, make_folds, Folds, NoiseFit, StepBase};
use super::super::noise_floor::{self, InstrumentClass};
use super::super::spread;
use super::super::{CandidateResult, DiagnoseOptions};
use super::Search;
use crate::fit::calibrate::noise_scales;
use crate::fit::{FitData, FitError, FitProblem, Weighting};
use crate::measurement::{DeliveryNoise, ImpactNoise};
use crate::physics::delivery_vars::DeliveryVar;

/// The delivery variables whose noise [`Search::refine_delivery`] refines: those the launch
/// depends on most (lie tilt and the head's rotation keep the level's multiple).
const REFINED: [DeliveryVar; 5] = [
    DeliveryVar::ClubSpeed,
    DeliveryVar::DynamicLoft,
    DeliveryVar::AttackAngle,
    DeliveryVar::ClubPath,
    DeliveryVar::FaceAngle,
];

/// Multiples of the camera-class SD a refined variable may take (0: measured exactly).
const REFINE_SCALES: [f64; 7] = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0];

/// `Σ_c (e_c/s_c)²`.
fn weighted(e: &[f64; 5], s: &[f64; 5]) -> f64 {
    e.iter().zip(s).map(|(e, s)| (e / s).powi(2)).sum()
}

/// One delivery-noise level offered as a candidate: the multiple of the camera class's delivery
/// SDs, the noise, and the data calibrated for it with its folds.
#[derive(Clone)]
pub(in crate::diagnose) struct DeliveryOption {
    scale: f64,
    noise: DeliveryNoise,
    data: FitData,
    folds: Folds,
}

/// Label of the measurement candidate for delivery noise `scale` × the camera class's SDs.
pub fn delivery_noise_label(scale: f64) -> String {
    format!("delivery_noise({scale}x camera)")
}

/// The delivery noise `scale` × the camera class's delivery SDs.
fn scaled_camera(scale: f64) -> DeliveryNoise {
    DeliveryNoise::new(
        InstrumentClass::Camera
            .noise()
            .delivery_sd
            .map(|s| s * scale),
    )
}

/// Fold of every shot and the number of folds.
type FoldPlan<'f> = (&'f [usize], usize);

/// The impact-noise levels of `opts` on `data`, each with its data and folds (a level the data
/// cannot take is named in `warnings`).
pub(super) fn impact_options(
    data: &FitData,
    opts: &DiagnoseOptions,
    (fold_of, n_folds): FoldPlan,
    warnings: &mut Vec<String>,
) -> Result<Vec<(ImpactNoise, FitData, Folds)>, FitError> {
    let levels = opts
        .impact_noise_candidates_mm
        .iter()
        .map(|&s_mm| Ok((s_mm, ImpactNoise::from_mm(s_mm, s_mm)?)))
        .collect::<Result<Vec<_>, FitError>>()?;
    // Each level's data (the posterior nodes of every shot) and folds made side by side; the
    // warnings in the order of the levels.
    let made: Vec<_> = levels
        .par_iter()
        .map(|&(s_mm, noise)| {
            let d = data.clone().with_impact_noise(Some(noise));
            (
                s_mm,
                noise,
                d.map(|d| (make_folds(&d, fold_of, n_folds), d)),
            )
        })
        .collect();
    let mut out = Vec::new();
    for (s_mm, noise, made) in made {
        match made {
            Ok((f, d)) => out.push((noise, d, f)),
            Err(e) => warnings.push(format!("impact noise {s_mm} mm not tried: {e}")),
        }
    }
    Ok(out)
}

/// The delivery-noise levels of `opts` on `data` (deliveries as measured).
pub(super) fn delivery_options(
    data: &FitData,
    opts: &DiagnoseOptions,
    (fold_of, n_folds): FoldPlan,
) -> Vec<DeliveryOption> {
    opts.delivery_noise_scales
        .par_iter()
        .filter(|s| s.is_finite() && **s > 0.0)
        .map(|&scale| {
            let noise = scaled_camera(scale);
            let d = data.clone().with_delivery_noise(Some(noise));
            let folds = make_folds(&d, fold_of, n_folds);
            DeliveryOption {
                scale,
                noise,
                data: d,
                folds,
            }
        })
        .collect()
}

impl Search<'_> {
    /// Delivery-noise levels still offered (none once one is chosen or given).
    pub(super) fn open_delivery_options(&self) -> &[DeliveryOption] {
        if self.chosen_delivery.is_some() {
            &[]
        } else {
            &self.delivery_options
        }
    }

    /// Score every open delivery-noise level against the step's base, by the cross-validated χ²
    /// of the mean prediction (one measurement question at several sizes: penalty `ln n`).
    pub(super) fn score_delivery(&self, b: &StepBase) -> Vec<(CandidateResult, NoiseFit)> {
        self.open_delivery_options()
            .par_iter()
            .enumerate()
            .map(|(j, o)| {
                evaluate::measurement_candidate(
                    b,
                    (j, delivery_noise_label(o.scale), &o.data, &o.folds),
                    None,
                    self.penalty_per_param,
                )
            })
            .collect()
    }

    /// Make delivery-noise level `j` (base parameters `theta` refitted under it) the model's,
    /// its noise refined variable by variable ([`Self::refine_delivery`]).
    pub(super) fn adopt_delivery(&mut self, j: usize, theta: DVector<f64>) {
        let o = self.delivery_options.swap_remove(j);
        self.delivery_options.clear();
        let exact = std::mem::replace(&mut self.data, o.data);
        self.folds = o.folds;
        self.chosen_delivery = Some(o.noise);
        self.theta_base = theta;
        if let Some(noise) = self.refine_delivery(&exact, o.noise) {
            let data = exact.with_delivery_noise(Some(noise));
            let w = Weighting::launch(&noise_scales(
                &self
                    .errors_of(&self.base, self.theta_base.as_slice())
                    .unwrap_or_default(),
            ));
            let refit = if self.base.is_empty() {
                Some(self.theta_base.clone())
            } else {
                crate::fit::fit_quietly(
                    self.club,
                    &self.base,
                    &data,
                    w,
                    &self.theta_base,
                    self.opts.max_iters,
                )
                .ok()
                .filter(|r| r.converged)
                .map(|r| r.theta)
            };
            if let Some(theta) = refit {
                self.folds = make_folds(&data, &self.fold_of, self.folds.train.len());
                self.data = data;
                self.chosen_delivery = Some(noise);
                self.theta_base = theta;
            }
        }
        if self.chosen_noise.is_none() {
            let plan = (self.fold_of.as_slice(), self.folds.train.len());
            self.noise_options =
                impact_options(&self.data, self.opts, plan, &mut Vec::new()).unwrap_or_default();
        }
    }

    /// The selected level `noise` refined one variable at a time: each variable that moves the
    /// launch ([`REFINED`]) takes the multiple of its camera-class SD in [`REFINE_SCALES`] whose
    /// calibrated data give the base model (at its current parameters, not refitted) the least
    /// χ² on all shots, weighted by the base errors' robust scales. A uniform multiple of the
    /// camera class is a coarse grid: a motion-capture rig may measure speed and loft twice as
    /// noisily and the angles no worse, and the variables it leaves over- or under-corrected
    /// bend the slopes as the noise itself does. `exact`: the deliveries as measured. `None`
    /// when nothing changes.
    fn refine_delivery(&self, exact: &FitData, noise: DeliveryNoise) -> Option<DeliveryNoise> {
        let camera = InstrumentClass::Camera.noise().delivery_sd;
        let scales = noise_scales(
            &self
                .errors_of(&self.base, self.theta_base.as_slice())
                .ok()?,
        );
        let chi2 = |n: DeliveryNoise| -> Option<f64> {
            let data = exact.clone().with_delivery_noise(Some(n));
            let errs = FitProblem::new(
                self.club,
                self.base.clone(),
                &data,
                Weighting::launch(&[1.0; 5]),
            )
            .launch_errors(self.theta_base.as_slice())
            .ok()?;
            Some(errs.iter().map(|e| weighted(e, &scales)).sum())
        };
        let mut best = noise;
        for v in REFINED {
            let i = v.index();
            let tried: Vec<(f64, f64)> = REFINE_SCALES
                .par_iter()
                .filter_map(|&k| {
                    let mut n = best;
                    n.sd[i] = k * camera[i];
                    Some((chi2(n)?, k * camera[i]))
                })
                .collect();
            if let Some(&(_, sd)) = tried.iter().min_by(|a, b| a.0.total_cmp(&b.0)) {
                best.sd[i] = sd;
            }
        }
        (best != noise).then_some(best)
    }

    /// Adopt the impact-noise level `noise` (base parameters `theta`) refined by the spread
    /// ([`spread::refine_selected`]; `exact`: the data with the locations as measured).
    pub(super) fn adopt_refined(
        &mut self,
        noise: ImpactNoise,
        exact: &FitData,
        theta: DVector<f64>,
        w: Weighting,
    ) -> Result<bool, FitError> {
        let inst = self.opts.noise_floor.clone();
        let refined = spread::refine_selected(
            (self.club, &self.base_club()?, self.shots),
            inst.unwrap_or_else(|| noise_floor::InstrumentClass::Camera.noise()),
            (&self.base, &theta, w, self.opts.max_iters),
            exact,
            &self.opts.impact_noise_candidates_mm,
            noise,
        )?;
        self.theta_base = theta;
        let Some((noise, data, theta)) = refined else {
            return Ok(false);
        };
        self.folds = make_folds(&data, &self.fold_of, self.folds.train.len());
        self.data = data;
        self.chosen_noise = Some(noise);
        self.theta_base = theta;
        Ok(true)
    }

    /// After an impact-noise level is adopted: the open delivery levels, rebuilt on the new data.
    pub(super) fn rebuild_delivery_options(&mut self) {
        if self.chosen_delivery.is_none() && !self.delivery_options.is_empty() {
            let plan = (self.fold_of.as_slice(), self.folds.train.len());
            self.delivery_options = delivery_options(&self.data, self.opts, plan);
        }
    }
}
