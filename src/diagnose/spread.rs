//! Scoring impact-location noise by the *spread* of model − measured, when the instruments'
//! noise is known.
//!
//! Noise on the measured impact location barely moves the model's mean prediction (regression
//! calibration flattens the location slopes by a few per cent), but it scatters the errors in
//! a shape of its own: a heel-toe error `δz` moves every launch component of a shot along the
//! model's location sensitivity `J_z` (azimuth and sidespin together, with the gear effect's
//! sign), by an amount that grows where the sensitivity does (ball speed off the sweet spot).
//! So a location-noise level is scored by the Gaussian likelihood of the errors with per-shot
//! covariances (file units)
//!
//! ```text
//! V_i(σ) = diag(σ_c²) + Σ_j s_j²·J_ij J_ijᵀ + Σ_a (1 − k_a)·σ²·J_ia J_iaᵀ
//! ```
//!
//! (launch monitor; delivery noise through the model's Jacobian `J_ij` at the measured delivery,
//! `j` over the non-location variables; the location noise that a model averaging over it with
//! noise `σ` leaves, the posterior variance of axis `a`, see [`super::noise_floor`]). The base
//! (no location noise) is `σ = 0`; the instrument's own location figure is not used here, since
//! the location noise is the question the candidates ask.
//!
//! A known instrument noise is rarely exactly right, and while effects are missing the errors
//! carry biases and trends beyond it. Both are absorbed, in every hypothesis alike, by a free
//! mean per component (the errors are centred) and a free scale per component
//! (`V_i → D V_i D`, `D = diag(√λ_c)`), profiled out: with `u_c = 1/√λ_c` and
//! `A = Σ_i V_i⁻¹ ∘ (r_i r_iᵀ)` (element-wise product),
//!
//! ```text
//! −2 ln L = min_u [uᵀ A u − 2n·Σ_c ln u_c] + Σ_i ln det V_i   (+ constants)
//! ```
//!
//! (convex in `u > 0`; solved by Newton's method). A noise level therefore wins only by the
//! *shape* it gives the covariance — the correlation between components along `J_loc` and the
//! shot-to-shot growth of the spread — not by inflating a component's overall spread, which a
//! missing effect could equally explain. Its gain is `−2 ln L(base) + 2 ln L(σ)` on the
//! all-shots fits: the base effects are refitted under `σ` (as many parameters as in the base),
//! so the in-sample optimism is the same on both sides and the level pays the penalty of one
//! parameter, `ln n`.
//!
//! The effects' score is on the same scale: the cross-validated χ² with weights fixed at the
//! base's noise scales `ŝ_c` is the first-order expansion of the same profile likelihood
//! (`n·ln(ŝ_c²/s_c²) ≈ (RSS_base − RSS_cand)/ŝ_c²` per component), taken out of sample.

use nalgebra::{DVector, Matrix5, Vector5};
use rayon::prelude::*;

use super::noise_floor::{
    corrected_location_variance, delivery_jacobians, measured_location_variance, InstrumentNoise,
};
use crate::club::ClubSpec;
use crate::fit::{FitData, FitError, FitProblem, ParamLayout, Weighting};
use crate::measurement::ImpactNoise;
use crate::model::{DeliveryVar, Shot};

/// Step (mm) of the central differences of the launch in the impact location: the size of the
/// location noise levels diagnose tries (`DEFAULT_IMPACT_NOISE_CANDIDATES_MM`), halved.
const LOCATION_STEP_MM: f64 = 1.0;

/// The per-shot covariance model of one diagnose step (the base model's sensitivities).
pub(super) struct SpreadModel {
    /// Per shot: the launch monitor's and the non-location delivery noise's covariance.
    fixed: Vec<Matrix5<f64>>,
    /// Per shot: the launch's sensitivity to the impact location, `[y, z]`, per mm.
    location: Vec<[Vector5<f64>; 2]>,
    /// Variance of the measured location on each axis, mm².
    var_measured: [f64; 2],
}

impl SpreadModel {
    /// The covariance model of `club` (the base model) on `shots` with instrument noise `inst`.
    pub(super) fn new(
        club: &ClubSpec,
        shots: &[Shot],
        inst: &InstrumentNoise,
    ) -> Result<Self, FitError> {
        let loc = [DeliveryVar::ImpactY.index(), DeliveryVar::ImpactZ.index()];
        let mut steps = inst.delivery_sd.map(|sd| 0.5 * sd);
        for j in loc {
            steps[j] = LOCATION_STEP_MM;
        }
        let jac = delivery_jacobians(club, shots, &steps)?;
        let launch = Matrix5::from_diagonal(&Vector5::from(inst.launch_sd.map(|s| s * s)));
        let fixed = jac
            .iter()
            .map(|jac| {
                let mut v = launch;
                for (j, col) in jac.iter().enumerate() {
                    if !loc.contains(&j) {
                        let g = Vector5::from(*col);
                        v += g * g.transpose() * inst.delivery_sd[j].powi(2);
                    }
                }
                v
            })
            .collect();
        Ok(Self {
            fixed,
            location: jac
                .iter()
                .map(|jac| loc.map(|j| Vector5::from(jac[j])))
                .collect(),
            var_measured: measured_location_variance(shots),
        })
    }

    /// `−2 ln L` (up to a constant) of `errors` (model − measured per shot, file units, in
    /// the order of the shots the model was made from) when the impact locations carry noise
    /// `noise` and the model averages over it (`None`: exact locations), with the means and
    /// per-component scales profiled out. `None` when a covariance is not positive definite.
    pub(super) fn deviance(&self, errors: &[[f64; 5]], noise: Option<ImpactNoise>) -> Option<f64> {
        let n = errors.len();
        if n != self.fixed.len() || n < 2 {
            return None;
        }
        let loc_var = noise.map_or([0.0; 2], |m| {
            [m.sigma_y_m, m.sigma_z_m]
                .iter()
                .zip(self.var_measured)
                .map(|(s, v)| corrected_location_variance(s * 1e3, v))
                .collect::<Vec<_>>()
                .try_into()
                .unwrap_or([0.0; 2])
        });
        let mean: Vector5<f64> = errors
            .iter()
            .map(|e| Vector5::from(*e))
            .sum::<Vector5<f64>>()
            / n as f64;
        let mut a = Matrix5::zeros();
        let mut log_det = 0.0;
        for ((e, fixed), loc) in errors.iter().zip(&self.fixed).zip(&self.location) {
            let mut v = *fixed;
            for (g, s2) in loc.iter().zip(loc_var) {
                v += g * g.transpose() * s2;
            }
            let chol = v.cholesky()?;
            log_det += 2.0 * chol.l().diagonal().map(f64::ln).sum();
            let r = Vector5::from(*e) - mean;
            a += chol.inverse().component_mul(&(r * r.transpose()));
        }
        let quad = profile_scales(&a, n as f64)?;
        let dev = quad + log_det;
        dev.is_finite().then_some(dev)
    }
}

/// Resolution (mm) to which a selected impact-noise level is refined.
pub(super) const REFINE_STEP_MM: f64 = 0.1;

/// The interval (mm) over which a selected level is refined: from half the smallest level
/// offered to one and a half times the largest (0.5–4.5 mm for the default levels).
pub(super) fn refine_interval(levels_mm: &[f64]) -> (f64, f64) {
    let lo = levels_mm.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = levels_mm.iter().copied().fold(0.0, f64::max);
    (0.5 * lo, 1.5 * hi)
}

/// A selected impact-noise level refined by the spread ([`super::spread`]): the isotropic
/// noise on a [`REFINE_STEP_MM`] grid over [`refine_interval`] of the levels offered
/// (`levels_mm`) whose errors (the base model at `theta`, averaged over that noise; not
/// refitted at each) have the smallest `−2 ln L` under `model`. `None` when none can be
/// evaluated.
fn refine_noise(
    b: (&ClubSpec, &ParamLayout, &DVector<f64>),
    exact: &FitData,
    model: &SpreadModel,
    levels_mm: &[f64],
) -> Option<ImpactNoise> {
    let (club, layout, theta) = b;
    let (lo, hi) = refine_interval(levels_mm);
    let steps = ((hi - lo) / REFINE_STEP_MM).round() as usize;
    (0..=steps)
        .into_par_iter()
        .filter_map(|k| {
            // In whole tenths of a millimetre, so the level is what it prints (2.4, not
            // 2.4000000000000004).
            let mm = ((lo / REFINE_STEP_MM).round() + k as f64) / (1.0 / REFINE_STEP_MM).round();
            let noise = ImpactNoise::from_mm(mm, mm).ok()?;
            let data = exact.clone().with_impact_noise(Some(noise)).ok()?;
            let errs = FitProblem::new(club, layout.clone(), &data, Weighting::launch(&[1.0; 5]))
                .launch_errors(theta.as_slice())
                .ok()?;
            Some((model.deviance(&errs, Some(noise))?, noise))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, n)| n)
}

/// The selected impact-noise level `noise` refined by the spread ([`refine_noise`], with the
/// instruments' noise `inst`: the known one, or the camera class's, which the reported noise
/// floor assumes too), with its data and the base (`layout` at `theta`) refitted at it.
/// `club` is the club as given, `base_club` it with the base effects; `exact` the data with the
/// locations as measured. `None` when the level stays as offered.
pub(super) fn refine_selected(
    (club, base_club, shots): (&ClubSpec, &ClubSpec, &[Shot]),
    inst: InstrumentNoise,
    (layout, theta, w, max_iters): (&ParamLayout, &DVector<f64>, Weighting, u64),
    exact: &FitData,
    levels_mm: &[f64],
    noise: ImpactNoise,
) -> Result<Option<(ImpactNoise, FitData, DVector<f64>)>, FitError> {
    let model = SpreadModel::new(base_club, shots, &inst)?;
    let Some(refined) =
        refine_noise((club, layout, theta), exact, &model, levels_mm).filter(|r| r != &noise)
    else {
        return Ok(None);
    };
    let data = exact.clone().with_impact_noise(Some(refined))?;
    let theta = if layout.is_empty() {
        theta.clone()
    } else {
        match crate::fit::fit_quietly(club, layout, &data, w, theta, max_iters) {
            Ok(run) if run.converged => run.theta,
            _ => return Ok(None),
        }
    };
    Ok(Some((refined, data, theta)))
}

/// `min_{u > 0} uᵀ A u − 2n·Σ ln u_c` for a positive semi-definite `A` with a positive
/// diagonal, by Newton's method from the diagonal solution (exact when `A` is diagonal).
fn profile_scales(a: &Matrix5<f64>, n: f64) -> Option<f64> {
    let f = |u: &Vector5<f64>| (u.transpose() * a * u)[0] - 2.0 * n * u.map(f64::ln).sum();
    if a.diagonal().iter().any(|&d| d.is_nan() || d <= 0.0) {
        return None;
    }
    let mut u = a.diagonal().map(|d| (n / d).sqrt());
    let mut fu = f(&u);
    for _ in 0..50 {
        let grad = 2.0 * a * u - u.map(|x| 2.0 * n / x);
        let hess = 2.0 * a + Matrix5::from_diagonal(&u.map(|x| 2.0 * n / (x * x)));
        let step = hess.cholesky()?.solve(&grad);
        // Halve the step until it stays positive and does not go uphill.
        let mut t = 1.0;
        let next = loop {
            let cand = u - step * t;
            if cand.iter().all(|&x| x > 0.0) && f(&cand) <= fu {
                break Some(cand);
            }
            t *= 0.5;
            if t < 1e-12 {
                break None;
            }
        };
        let Some(next) = next else { break };
        let fn_ = f(&next);
        let done = (fu - fn_).abs() <= 1e-12 * fu.abs().max(1.0);
        u = next;
        fu = fn_;
        if done {
            break;
        }
    }
    Some(fu)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refinement_spans_the_levels_offered() {
        assert_eq!(refine_interval(&[1.5, 1.0, 3.0, 2.0]), (0.5, 4.5));
    }

    /// The profiled minimum agrees with a brute-force search, and with the closed form
    /// `n·Σ (1 − ln(n/A_cc))` for a diagonal `A`.
    #[test]
    fn profiled_scales_reach_the_minimum() {
        let n: f64 = 50.0;
        let diag = Matrix5::from_diagonal(&Vector5::new(40.0, 55.0, 61.0, 12.0, 90.0));
        let closed: f64 = diag
            .diagonal()
            .iter()
            .map(|&d| n * (1.0 - (n / d).ln()))
            .sum();
        let got = profile_scales(&diag, n).unwrap();
        assert!(
            (got - closed).abs() < 1e-9 * closed.abs(),
            "{got} vs {closed}"
        );
        // A correlated A: the Newton minimum is at most any point of a grid around it.
        let b = Matrix5::from_fn(|i, j| ((i * 7 + j * 3) % 5) as f64 * 0.3 + 1.0);
        let a = b * b.transpose() + diag;
        let min = profile_scales(&a, n).unwrap();
        let f = |u: &Vector5<f64>| (u.transpose() * a * u)[0] - 2.0 * n * u.map(f64::ln).sum();
        let mut u0 = a.diagonal().map(|d| (n / d).sqrt());
        // Coordinate descent on a fine grid as the independent check.
        for _ in 0..200 {
            for c in 0..5 {
                let best = (1..400)
                    .map(|k| u0[c] * (0.8 + 0.001 * k as f64))
                    .min_by(|x, y| {
                        let mut ux = u0;
                        ux[c] = *x;
                        let mut uy = u0;
                        uy[c] = *y;
                        f(&ux).total_cmp(&f(&uy))
                    })
                    .unwrap();
                u0[c] = best;
            }
        }
        assert!(min <= f(&u0) + 1e-6, "{min} vs grid {}", f(&u0));
        assert!(f(&u0) - min < 1e-3 * min.abs(), "{min} vs grid {}", f(&u0));
    }
}
