//! Planning: how many shots, and which impact spread, give a chosen standard error on each head
//! parameter. The Fisher information of independent shots adds, so with the per-shot
//! information of a session's design (its deliveries and impact locations, at the start head,
//! with the instruments' noise) `n` such shots carry `(n/n0)·F0`: the data-only standard error
//! falls as `1/√n`, and the posterior's is `√((n/n0·F0 + P)⁻¹)_jj`.
//!
//! The noise is the instruments' (not the session's errors, which at the start head hold the
//! head's own misfit): each shot's launch errors have the covariance
//! `Σ_i = diag(σ_launch²) + Σ_j g_ij g_ijᵀ·s_j²·(1 − s_j²/var_j)`, with `g_ij` the launch's
//! derivative in delivery variable `j` (the model's own, central differences), `s_j` its
//! measurement noise and `var_j` the spread of its measured values: the error that remains
//! after the regression calibration the fit applies (`crate::measurement`; pooled over golfers,
//! so slightly more than remains when golfers differ). The shots' average covariance whitens the
//! rows, as the fit's does; each shot's own covariance `Σ_i` enters the planned standard error
//! through the sandwich `H⁻¹(Σ_i J_iᵀ W Σ_i Wᵀ J_i + P)H⁻¹` (`W` the whitening), since a shot
//! far off-centre carries more noise than the average (its location error moves speed and
//! spin more).

use nalgebra::{DMatrix, Matrix5, Vector5};
use serde::Serialize;

use super::head::{reported, start_values, HEAD_PARAMS};
use super::ident::{data_variances, posterior_cov, sandwich_cov};
use super::problem::NoiseCov;
use crate::club::ClubSpec;
use crate::diagnose::noise_floor::delivery_jacobians;
use crate::fit::FitError;
use crate::model::Shot;
use crate::physics::delivery_vars::{DeliveryVar, N_DELIVERY};
use crate::stats;

/// Each shot's launch-error covariance (file units) a right model leaves under the
/// instruments' noise (module docs), at the model `club`.
pub fn instrument_covs(
    club: &ClubSpec,
    shots: &[Shot],
    launch_sd: &[f64; 5],
    delivery_sd: &[f64; N_DELIVERY],
    corrected: bool,
) -> Result<Vec<Matrix5<f64>>, FitError> {
    let remaining: [f64; N_DELIVERY] = std::array::from_fn(|j| {
        let s2 = delivery_sd[j].powi(2);
        if !(s2.is_finite() && s2 > 0.0) {
            return 0.0;
        }
        if !corrected {
            return s2;
        }
        let x: Vec<f64> = shots
            .iter()
            .map(|s| DeliveryVar::ALL[j].file_value(&s.delivery))
            .collect();
        let var = stats::std_dev(&x).powi(2);
        s2 * (1.0 - s2 / var.max(f64::MIN_POSITIVE)).max(0.0)
    });
    let steps = delivery_sd.map(|s| if s > 0.0 { 0.5 * s } else { 0.0 });
    let launch = Matrix5::from_diagonal(&Vector5::from(launch_sd.map(|s| s * s)));
    Ok(delivery_jacobians(club, shots, &steps)?
        .iter()
        .map(|g| {
            let mut cov = launch;
            for (j, rem) in remaining.iter().enumerate() {
                if *rem > 0.0 {
                    let v = Vector5::from(g[j]);
                    cov += v * v.transpose() * *rem;
                }
            }
            cov
        })
        .collect())
}

/// The shots' average of [`instrument_covs`]: the covariance the rows are whitened by.
pub fn average_cov(covs: &[Matrix5<f64>]) -> NoiseCov {
    let sum: Matrix5<f64> = covs.iter().sum();
    NoiseCov::from_matrix(&(sum / covs.len().max(1) as f64))
}

/// Shots with the measured impact locations spread about their mean to `sd_mm` (y, z) instead
/// of the session's: the design a stated impact spread asks about.
pub fn with_impact_spread(shots: &[Shot], sd_mm: [f64; 2]) -> Vec<Shot> {
    let ys: Vec<f64> = shots.iter().map(|s| s.delivery.impact_y_m).collect();
    let zs: Vec<f64> = shots.iter().map(|s| s.delivery.impact_z_m).collect();
    let (my, mz) = (stats::mean(&ys), stats::mean(&zs));
    let (sy, sz) = (stats::std_dev(&ys), stats::std_dev(&zs));
    let ky = if sy > 0.0 { sd_mm[0] * 1e-3 / sy } else { 1.0 };
    let kz = if sz > 0.0 { sd_mm[1] * 1e-3 / sz } else { 1.0 };
    shots
        .iter()
        .map(|s| {
            let mut t = s.clone();
            t.delivery.impact_y_m = my + ky * (s.delivery.impact_y_m - my);
            t.delivery.impact_z_m = mz + kz * (s.delivery.impact_z_m - mz);
            t
        })
        .collect()
}

/// One parameter's plan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanParam {
    /// Club-file key.
    pub name: String,
    /// Unit.
    pub unit: &'static str,
    /// Start value.
    pub start: f64,
    /// Prior 1σ.
    pub prior_sd: f64,
    /// Standard error of the estimate with the planned number of shots (sandwich: the noise of
    /// each shot through the fit's weights, prior included).
    pub stderr: f64,
    /// The model's posterior standard error `√((F + P)⁻¹)_jj`, which assumes every shot as
    /// noisy as the average.
    pub stderr_model: f64,
    /// Data-only standard error with the planned number of shots (`None`: the design does not
    /// determine it at any number of shots).
    pub data_stderr: Option<f64>,
    /// Determined with the planned shots?
    pub determined: bool,
    /// Shots needed to determine it (data-only SE below the determined fraction of the prior
    /// width; `None`: never with this design).
    pub shots_to_determine: Option<u64>,
    /// The target standard error asked for, if any.
    pub target_stderr: Option<f64>,
    /// Shots needed for the target (posterior SE; `None`: never with this design, or no target).
    pub shots_for_target: Option<u64>,
}

/// Shots needed for a data-only variance `v0` at `n0` shots to fall to `want` (variance).
fn shots_for(v0: f64, n0: usize, want: f64) -> Option<u64> {
    (v0.is_finite() && want > 0.0).then(|| (n0 as f64 * v0 / want).ceil().max(1.0) as u64)
}

/// The plan for `n` shots from the Fisher information `fisher0` and the score covariance
/// `meat0` (the shots' own noise through the fit's weights: [`super::ident::sandwich_cov`]) of
/// a design of `n0` shots (fitted units) at the start `club`, prior widths `sd` (fitted
/// units), determined fraction `f`, optional targets (reported units) per parameter. Both scale
/// as `n/n0`.
pub fn plan_params(
    club: &ClubSpec,
    (fisher0, meat0): (&DMatrix<f64>, &DMatrix<f64>),
    (n0, n): (usize, usize),
    sd: &[f64],
    f: f64,
    targets: &[Option<f64>],
) -> Vec<PlanParam> {
    let k = n as f64 / n0 as f64;
    let fisher = fisher0 * k;
    let var = data_variances(&fisher, sd);
    let post = posterior_cov(&fisher, sd);
    let robust = sandwich_cov(&fisher, &(meat0 * k), sd);
    let var0 = data_variances(fisher0, sd);
    let start = start_values(club);
    HEAD_PARAMS
        .iter()
        .enumerate()
        .map(|(j, h)| {
            let unit_k = reported(j, start[j], 1.0).1;
            // The sandwich's inflation of the variance over the model's, applied to the data
            // variance a target needs.
            let inflation = (robust[(j, j)] / post[(j, j)]).max(1.0);
            let target = targets.get(j).copied().flatten();
            let prior = sd[j];
            // Posterior variance t² = 1/(1/v_data + 1/σ²) → v_data = 1/(1/t² − 1/σ²).
            let for_target = target.and_then(|t| {
                let t = t / unit_k;
                let inv = 1.0 / (t * t) - 1.0 / (prior * prior);
                if inv <= 0.0 {
                    Some(0)
                } else {
                    shots_for(var0[j] * inflation, n0, 1.0 / inv)
                }
            });
            PlanParam {
                name: h.key.to_owned(),
                unit: h.unit,
                start: start[j],
                prior_sd: prior * unit_k,
                stderr: robust[(j, j)].sqrt() * unit_k,
                stderr_model: post[(j, j)].sqrt() * unit_k,
                data_stderr: var[j].is_finite().then(|| var[j].sqrt() * unit_k),
                determined: var[j].is_finite() && var[j].sqrt() < f * prior,
                shots_to_determine: shots_for(var0[j], n0, (f * prior).powi(2)),
                target_stderr: target,
                shots_for_target: for_target,
            }
        })
        .collect()
}
