//! `smash infer-club`: the head's effective properties estimated from the shots, with honest
//! uncertainty (issue 40).
//!
//! The parameters ([`head`]): the CoM (depth, height, heel–toe), the moments of inertia about
//! the vertical and heel–toe axes through it, the bulge and roll radii, the COR at the centre
//! and its radial falloff (`cor_radial`), and the monitor's loft and face-angle biases — each a
//! library effect's parameter, so no physics is written here. The start club is a stated,
//! weak Gaussian prior on each ([`problem`]: one residual row `(θ − θ0)/σ` a parameter).
//!
//! The flow of [`run`]:
//!
//! 1. the measurement model: each shot's delivery at its expected true value and the model
//!    averaged over the likely impact locations, given the instruments' delivery noise
//!    (regression calibration, as `smash calibrate --delivery-noise --impact-noise-mm`);
//! 2. **before fitting**, the Fisher information of the shots at the start head with the
//!    instruments' noise ([`plan::instrument_covs`]) and what it determines ([`ident`]);
//! 3. the fit: bounded Levenberg–Marquardt on data and prior rows, the launch errors whitened by
//!    their full 5 × 5 covariance estimated robustly from the start head's errors, then again
//!    from the first fit's errors and the fit repeated from its solution;
//! 4. at the fit: the Fisher information again, the posterior covariance `(F + P)⁻¹` and the
//!    reported standard errors from its sandwich with the shots' own scores
//!    ([`ident::sandwich_cov`]: a shot far off-centre carries more noise than the average), each
//!    parameter's data-only standard error, whether it is determined, the prior's share, and
//!    profile-likelihood intervals of the determined ones (the others refitted with it fixed on
//!    a grid of its standard error; the `Δχ² = 1` crossings of the posterior's `−2 ln`).

pub mod head;
pub mod ident;
pub mod plan;
pub mod problem;
pub mod report;

use argmin::core::{Executor, State};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::club::ClubSpec;
use crate::diagnose::noise_floor::InstrumentClass;
use crate::fit::{FitData, FitError, FitProblem, LevenbergMarquardt, LmState, Weighting};
use crate::measurement::{DeliveryNoise, ImpactNoise};
use crate::model::Shot;
use crate::physics::delivery_vars::{DeliveryVar, N_DELIVERY};

use head::{head_layout, inferred_club, reported, start_values, HEAD_PARAMS};
use ident::{data_variances, identifiability, posterior_cov, prior_shares};
use problem::{HeadProblem, NoiseCov};

pub use report::{NoiseReport, ParamReport, PlanReport, Report};

/// The version of infer-club's JSON schema.
pub const SCHEMA_VERSION: u32 = 1;

/// How `smash infer-club` works; every field has a default ([`Settings::default`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// A parameter is determined when its data-only SE is below this fraction of its prior
    /// width (1/3: the data hold ≥ 90 % of the information on it; [`ident`]).
    pub determined_fraction: f64,
    /// Factor on every prior width of [`head::HEAD_PARAMS`] (1: the documented widths).
    pub prior_scale: f64,
    /// The launch monitor's noise, 1σ per launch component, file units (camera class).
    pub launch_noise_sd: [f64; 5],
    /// The delivery measurement's noise, 1σ per delivery variable in
    /// [`DeliveryVar::ALL`] order, file units (camera class; impact location included).
    pub delivery_noise_sd: [f64; N_DELIVERY],
    /// Correct the fit for that delivery noise (regression calibration of the deliveries and
    /// the impact locations).
    pub correct_measurement: bool,
    /// Iteration limit of each solver run.
    pub max_iters: u64,
    /// Profile grid, in posterior standard errors from the estimate (empty: no profiles).
    pub profile_grid_se: Vec<f64>,
}

impl Default for Settings {
    fn default() -> Self {
        let camera = InstrumentClass::Camera.noise();
        Self {
            determined_fraction: 1.0 / 3.0,
            prior_scale: 1.0,
            launch_noise_sd: camera.launch_sd,
            delivery_noise_sd: camera.delivery_sd,
            correct_measurement: true,
            max_iters: 100,
            profile_grid_se: vec![-2.0, -1.0, 1.0, 2.0],
        }
    }
}

/// Read a settings file (TOML with the keys of [`Settings`]; the others default), checked.
pub fn read_settings(path: &std::path::Path) -> Result<Settings, crate::data::DataError> {
    use crate::data::DataError;
    let text = std::fs::read_to_string(path)
        .map_err(|e| DataError::file(path, format!("cannot read: {e}")))?;
    let s: Settings = toml::from_str(&text).map_err(|e| {
        DataError::file(
            path,
            format!(
                "{} (the keys are determined_fraction, prior_scale, launch_noise_sd, \
                 delivery_noise_sd, correct_measurement, max_iters, profile_grid_se)",
                e.message()
            ),
        )
    })?;
    s.check()
        .map_err(|e| DataError::file(path, e.to_string()))?;
    Ok(s)
}

/// Why the head cannot be inferred.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InferError {
    /// The fit machinery refused or failed.
    #[error(transparent)]
    Fit(#[from] FitError),
    /// A setting is out of its range.
    #[error("setting {key}: {why}")]
    Setting {
        /// The setting.
        key: &'static str,
        /// What is allowed.
        why: String,
    },
    /// The inferred head is not a club the model accepts.
    #[error("the inferred head is not a valid club: {0}")]
    Club(head::ClubError),
}

impl Settings {
    /// Check the ranges.
    pub fn check(&self) -> Result<(), InferError> {
        let bad = |key, why: &str| {
            Err(InferError::Setting {
                key,
                why: why.to_owned(),
            })
        };
        if !(self.determined_fraction > 0.0 && self.determined_fraction < 1.0) {
            return bad("determined_fraction", "must be in (0, 1)");
        }
        if !(self.prior_scale.is_finite() && self.prior_scale > 0.0) {
            return bad("prior_scale", "must be finite and > 0");
        }
        if !self
            .launch_noise_sd
            .iter()
            .all(|s| s.is_finite() && *s > 0.0)
        {
            return bad("launch_noise_sd", "each must be finite and > 0");
        }
        if !self
            .delivery_noise_sd
            .iter()
            .all(|s| s.is_finite() && *s >= 0.0)
        {
            return bad("delivery_noise_sd", "each must be finite and >= 0");
        }
        if !self
            .profile_grid_se
            .iter()
            .all(|k| k.is_finite() && *k != 0.0)
        {
            return bad("profile_grid_se", "each must be finite and not 0");
        }
        Ok(())
    }

    /// Prior widths in the fitted units.
    pub fn prior_sd(&self) -> Vec<f64> {
        HEAD_PARAMS
            .iter()
            .map(|h| h.prior_sd * self.prior_scale)
            .collect()
    }

    fn impact_noise(&self) -> Option<ImpactNoise> {
        let (y, z) = (
            self.delivery_noise_sd[DeliveryVar::ImpactY.index()],
            self.delivery_noise_sd[DeliveryVar::ImpactZ.index()],
        );
        (self.correct_measurement && (y > 0.0 || z > 0.0))
            .then(|| ImpactNoise::from_mm(y, z).expect("checked finite and >= 0"))
    }

    fn delivery_noise(&self) -> Option<DeliveryNoise> {
        let n = DeliveryNoise::new(self.delivery_noise_sd);
        (self.correct_measurement && n.is_active()).then_some(n)
    }
}

/// The shots as the fit sees them: measured, under the settings' measurement model.
pub fn fit_data(settings: &Settings, shots: &[Shot]) -> Result<FitData, FitError> {
    FitData::from_shots(shots)?
        .with_delivery_noise(settings.delivery_noise())
        .with_impact_noise(settings.impact_noise())
}

/// A solver run's end.
struct Solved {
    theta: DVector<f64>,
    cost: f64,
    iterations: u64,
    termination: String,
    converged: bool,
}

/// Bounded LM on `problem` from full `start` (only the active entries move).
fn solve(
    problem: HeadProblem<'_>,
    start: &DVector<f64>,
    max_iters: u64,
) -> Result<Solved, FitError> {
    let inner = problem.inner().clone();
    let solver = LevenbergMarquardt::new(inner.active_lower(), problem.active_upper())
        .map_err(|e| FitError::Solver(e.into()))?
        .without_final_jacobian();
    let init = inner.active_part(start);
    let fixed_prior = problem.fixed_prior_chi2(start);
    let result = Executor::new(problem, solver)
        .configure(|s: LmState| s.param(init).max_iters(max_iters))
        .run()
        .map_err(|e| match e.downcast::<crate::fit::EvalError>() {
            Ok(eval) => FitError::Start(eval),
            Err(other) => FitError::Solver(other.into()),
        })?;
    let converged = result.solver().converged().is_some();
    let state = result.state();
    let active = state
        .get_param()
        .cloned()
        .expect("the solver keeps its point");
    Ok(Solved {
        theta: inner.full_theta(active.as_slice()),
        cost: state.get_cost() + fixed_prior,
        iterations: state.get_iter(),
        termination: state.get_termination_status().to_string(),
        converged,
    })
}

/// The data rows' Jacobian of `problem` at full `theta` and their Fisher information `JᵀJ`.
fn fisher(
    problem: &HeadProblem<'_>,
    theta: &DVector<f64>,
) -> Result<(DMatrix<f64>, DMatrix<f64>), FitError> {
    let j = problem.data_jacobian(theta).map_err(FitError::Start)?;
    let f = j.transpose() * &j;
    Ok((j, f))
}

/// Model − measured errors (file units) of full `theta`.
fn errors(problem: &FitProblem<'_>, theta: &DVector<f64>) -> Result<Vec<[f64; 5]>, FitError> {
    problem
        .launch_errors(theta.as_slice())
        .map_err(FitError::Start)
}

/// Profile-likelihood interval of parameter `j` (fitted units), `None` when a refit fails.
fn profile(
    settings: &Settings,
    base: &HeadProblem<'_>,
    theta: &DVector<f64>,
    min_cost: f64,
    j: usize,
    se: f64,
) -> Option<[f64; 2]> {
    let (lo, hi) = (base.inner().layout().lower()[j], base.upper_of(j));
    let points: Vec<(f64, f64)> = settings
        .profile_grid_se
        .par_iter()
        .filter_map(|&k| {
            let mut t = theta.clone();
            t[j] = (theta[j] + k * se).clamp(lo, hi);
            let active: Vec<usize> = (0..theta.len()).filter(|&i| i != j).collect();
            let pr = base.clone().with_active(active, t.clone());
            let s = solve(pr, &t, settings.max_iters).ok()?;
            Some((t[j] - theta[j], (s.cost - min_cost).max(0.0)))
        })
        .collect();
    if points.len() != settings.profile_grid_se.len() {
        return None;
    }
    let side = |sign: f64| -> Option<f64> {
        let mut p: Vec<(f64, f64)> = points
            .iter()
            .filter(|(d, _)| d * sign > 0.0)
            .cloned()
            .collect();
        p.sort_by(|a, b| a.0.abs().total_cmp(&b.0.abs()));
        // √Δχ² is close to linear in the offset: interpolate it, from (0, 0), to 1.
        let mut prev = (0.0, 0.0);
        for &(d, dc) in &p {
            let r = dc.sqrt();
            if r >= 1.0 {
                let (d0, r0) = prev;
                return Some(d0 + (1.0 - r0) * (d - d0) / (r - r0));
            }
            prev = (d, r);
        }
        let (d, r) = prev;
        (r > 0.0).then(|| d / r)
    };
    Some([theta[j] + side(-1.0)?, theta[j] + side(1.0)?])
}

/// What the fit stages produce.
struct FitResult {
    theta: DVector<f64>,
    cost: f64,
    noise: NoiseCov,
    iterations: u64,
    termination: String,
}

fn fit_stages(
    settings: &Settings,
    club: &ClubSpec,
    data: &FitData,
    theta0: &DVector<f64>,
    sd: &DVector<f64>,
) -> Result<FitResult, FitError> {
    let base = FitProblem::new(club, head_layout(), data, Weighting::launch(&[1.0; 5]));
    let mut theta = theta0.clone();
    let mut iterations = 0;
    let mut last = None;
    for stage in 1..=2 {
        let noise = NoiseCov::from_errors(&errors(&base, &theta)?);
        let pr = HeadProblem::new(base.clone(), &noise, theta0.clone(), sd.clone())
            .with_upper(&head::upper_bounds(club));
        let s = solve(pr, &theta, settings.max_iters)?;
        iterations += s.iterations;
        if !s.converged {
            return Err(FitError::NotConverged {
                iterations: s.iterations,
                chi2: s.cost,
                stage: format!("infer-club fit {stage}/2"),
            });
        }
        theta = s.theta.clone();
        last = Some((s, noise));
    }
    let (s, noise) = last.expect("two stages ran");
    Ok(FitResult {
        theta,
        cost: s.cost,
        noise,
        iterations,
        termination: s.termination,
    })
}

/// Infer the head from `shots` (with measured launch) with the start club `club` as prior.
pub fn run(settings: &Settings, club: &ClubSpec, shots: &[Shot]) -> Result<Report, InferError> {
    settings.check()?;
    let layout = head_layout();
    let data = fit_data(settings, shots)?;
    if data.len() <= layout.len() {
        return Err(FitError::TooFewShots {
            shots: data.len(),
            params: layout.len(),
        }
        .into());
    }
    let theta0 = layout.defaults();
    let sd = DVector::from_vec(settings.prior_sd());
    let f = settings.determined_fraction;
    // Before fitting: the start head, the instruments' noise.
    let inst = plan::average_cov(&plan::instrument_covs(
        club,
        shots,
        &settings.launch_noise_sd,
        &settings.delivery_noise_sd,
        settings.correct_measurement,
    )?);
    let base = FitProblem::new(club, layout.clone(), &data, Weighting::launch(&[1.0; 5]));
    let before_pr = HeadProblem::new(base.clone(), &inst, theta0.clone(), sd.clone());
    let (_, fisher0) = fisher(&before_pr, &theta0)?;
    let before = identifiability(&fisher0, sd.as_slice(), f);
    // The fit.
    let fit = fit_stages(settings, club, &data, &theta0, &sd)?;
    let pr = HeadProblem::new(base.clone(), &fit.noise, theta0.clone(), sd.clone())
        .with_upper(&head::upper_bounds(club));
    let (jac1, fisher1) = fisher(&pr, &fit.theta)?;
    let after = identifiability(&fisher1, sd.as_slice(), f);
    let post = posterior_cov(&fisher1, sd.as_slice());
    // The standard errors: the sandwich of the shots' own scores (each shot's errors as they
    // are, not as noisy as the average the weights assume).
    let r1 = pr
        .data_residuals(fit.theta.as_slice())
        .map_err(FitError::Start)?;
    let meat = ident::block_meat(&jac1, |i| {
        let v = r1.fixed_rows::<5>(5 * i).into_owned();
        v * v.transpose()
    });
    let robust = ident::sandwich_cov(&fisher1, &meat, sd.as_slice());
    let data_var = data_variances(&fisher1, sd.as_slice());
    let shares = prior_shares(&post, &data_var);
    let profiles: Vec<Option<[f64; 2]>> = (0..layout.len())
        .into_par_iter()
        .map(|j| {
            (after.determined[j] && !settings.profile_grid_se.is_empty())
                .then(|| profile(settings, &pr, &fit.theta, fit.cost, j, post[(j, j)].sqrt()))
                .flatten()
        })
        .collect();
    let inferred = inferred_club(club, &fit.theta).map_err(InferError::Club)?;
    let start = start_values(club);
    let (lower, upper) = (layout.lower(), head::upper_bounds(club));
    let params = HEAD_PARAMS
        .iter()
        .enumerate()
        .map(|(j, h)| {
            let (mut value, k) = reported(j, start[j], fit.theta[j]);
            // The moments as the inferred club holds them (`inertia_axes` floors the heel-toe
            // spread far outside the plausible range, where I_yy is not start × factor).
            if let Some(axis) = [3, 4].iter().position(|&i| i == j) {
                value = inferred.nominal.club_inertia_kgm2[(axis + 1, axis + 1)] * 1e7;
            }
            let at = |b: f64| (fit.theta[j] - b).abs() <= 1e-9 * (upper[j] - lower[j]);
            ParamReport {
                name: h.key.to_owned(),
                words: h.words,
                unit: h.unit,
                value,
                stderr: robust[(j, j)].sqrt() * k,
                stderr_model: post[(j, j)].sqrt() * k,
                start: start[j],
                determined: after.determined[j],
                data_stderr: after.data_se[j].map(|s| s * k),
                prior_sd: sd[j] * k,
                prior_share: shares[j],
                profile: profiles[j].map(|p| p.map(|t| reported(j, start[j], t).0)),
                at_bound: at(lower[j]) || at(upper[j]),
            }
        })
        .collect();
    let chi2_prior = pr.prior_chi2(&fit.theta);
    Ok(Report {
        schema_version: SCHEMA_VERSION,
        command: "infer-club",
        n_shots: shots.len(),
        settings: settings.clone(),
        prior: report::prior_statement(settings),
        determined_rule: report::determined_statement(f),
        impact_spread_mm: report::impact_spread_mm(shots),
        params,
        before,
        after,
        correlation: (0..layout.len())
            .map(|a| {
                (0..layout.len())
                    .map(|b| robust[(a, b)] / (robust[(a, a)] * robust[(b, b)]).sqrt())
                    .collect()
            })
            .collect(),
        noise: NoiseReport::of(&fit.noise),
        instrument_noise: NoiseReport::of(&inst),
        chi2_data: fit.cost - chi2_prior,
        chi2_prior,
        n_residuals: data.len() * 5,
        iterations: fit.iterations,
        termination: fit.termination,
        club: inferred,
        theta: fit.theta.iter().cloned().collect(),
    })
}

/// The plan for `n` shots (the session's number when `None`) of the session's design, or with
/// its impact locations spread to `impact_sd_mm`, at the start head; `targets` per parameter
/// (club-file key → wanted SE in the reported unit).
pub fn run_plan(
    settings: &Settings,
    club: &ClubSpec,
    shots: &[Shot],
    n: Option<usize>,
    impact_sd_mm: Option<[f64; 2]>,
    targets: &[(String, f64)],
) -> Result<PlanReport, InferError> {
    settings.check()?;
    if n == Some(0) {
        return Err(InferError::Setting {
            key: "plan_shots",
            why: "0 shots: a plan needs at least 1".to_owned(),
        });
    }
    let mut wanted = vec![None; HEAD_PARAMS.len()];
    for (key, t) in targets {
        let Some(j) = HEAD_PARAMS.iter().position(|h| h.key == key) else {
            return Err(InferError::Setting {
                key: "target",
                why: format!(
                    "'{key}' is not a head parameter; the parameters are {}",
                    HEAD_PARAMS.map(|h| h.key).join(", ")
                ),
            });
        };
        if !(t.is_finite() && *t > 0.0) {
            return Err(InferError::Setting {
                key: "target",
                why: format!("'{key}={t}': a target SE must be finite and > 0"),
            });
        }
        wanted[j] = Some(*t);
    }
    if let Some(sd) = impact_sd_mm.filter(|s| !s.iter().all(|v| v.is_finite() && *v > 0.0)) {
        return Err(InferError::Setting {
            key: "impact_spread_mm",
            why: format!(
                "'{},{}': an impact spread (σ up the face, toward the toe) must be finite and > 0 \
                 mm on both axes",
                sd[0], sd[1]
            ),
        });
    }
    let design = match impact_sd_mm {
        Some(s) => plan::with_impact_spread(shots, s),
        None => shots.to_vec(),
    };
    let layout = head_layout();
    let data = fit_data(settings, &design)?;
    let theta0 = layout.defaults();
    let sd = DVector::from_vec(settings.prior_sd());
    let covs = plan::instrument_covs(
        club,
        &design,
        &settings.launch_noise_sd,
        &settings.delivery_noise_sd,
        settings.correct_measurement,
    )?;
    let inst = plan::average_cov(&covs);
    let base = FitProblem::new(club, layout, &data, Weighting::launch(&[1.0; 5]));
    let pr = HeadProblem::new(base, &inst, theta0.clone(), sd.clone());
    let (jac0, fisher0) = fisher(&pr, &theta0)?;
    let w = inst.whitening();
    let meat0 = ident::block_meat(&jac0, |i| w * covs[i] * w.transpose());
    let n0 = design.len();
    let n = n.unwrap_or(n0).max(1);
    let params = plan::plan_params(
        club,
        (&fisher0, &meat0),
        (n0, n),
        sd.as_slice(),
        settings.determined_fraction,
        &wanted,
    );
    let at = identifiability(
        &(fisher0 * (n as f64 / n0 as f64)),
        sd.as_slice(),
        settings.determined_fraction,
    );
    Ok(PlanReport {
        schema_version: SCHEMA_VERSION,
        command: "infer-club --plan",
        n_session: n0,
        n_planned: n,
        impact_spread_mm: report::impact_spread_mm(&design),
        determined_rule: report::determined_statement(settings.determined_fraction),
        noise: NoiseReport::of(&inst),
        params,
        weak_directions: at
            .directions
            .iter()
            .filter(|d| d.weak)
            .map(|d| d.text.clone())
            .collect(),
    })
}
