//! The measurement candidates' data: impact-location noise levels and, while the instruments'
//! noise is unknown, delivery-noise levels (regression calibration of club speed, loft, path,
//! face, ... for a multiple of the camera class's delivery SDs, [`DeliveryNoise`]). Each level
//! is the same model on its own copy of the data; adopting one makes that copy the data, so
//! the other kind's levels are rebuilt from it.

use nalgebra::DVector;
use rayon::prelude::*;

use super::super::evaluate::{self, make_folds, Folds, NoiseFit, StepBase};
use super::super::noise_floor::InstrumentClass;
use super::super::{CandidateResult, DiagnoseOptions};
use super::Search;
use crate::fit::{FitData, FitError};
use crate::measurement::{DeliveryNoise, ImpactNoise};

/// One delivery-noise level offered as a candidate: the multiple of the camera class's delivery
/// SDs, the noise, and the data calibrated for it with its folds.
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
    DeliveryNoise::new(InstrumentClass::Camera.noise().delivery_sd.map(|s| s * scale))
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
    let mut out = Vec::new();
    for &s_mm in &opts.impact_noise_candidates_mm {
        let noise = ImpactNoise::from_mm(s_mm, s_mm)?;
        match data.clone().with_impact_noise(Some(noise)) {
            Ok(d) => {
                let f = make_folds(&d, fold_of, n_folds);
                out.push((noise, d, f));
            }
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
        .iter()
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

    /// Make delivery-noise level `j` (base parameters `theta` refitted under it) the model's.
    pub(super) fn adopt_delivery(&mut self, j: usize, theta: DVector<f64>) {
        let o = self.delivery_options.swap_remove(j);
        self.delivery_options.clear();
        self.data = o.data;
        self.folds = o.folds;
        self.chosen_delivery = Some(o.noise);
        self.theta_base = theta;
        if self.chosen_noise.is_none() {
            let plan = (self.fold_of.as_slice(), self.folds.train.len());
            self.noise_options =
                impact_options(&self.data, self.opts, plan, &mut Vec::new()).unwrap_or_default();
        }
    }

    /// After an impact-noise level is adopted: the open delivery levels, rebuilt on the new data.
    pub(super) fn rebuild_delivery_options(&mut self) {
        if self.chosen_delivery.is_none() && !self.delivery_options.is_empty() {
            let plan = (self.fold_of.as_slice(), self.folds.train.len());
            self.delivery_options = delivery_options(&self.data, self.opts, plan);
        }
    }
}
