//! Calibration: fit the parameters of named effects to measured launch conditions.
//!
//! Two methods:
//!
//! - [`Method::Lm`] (default): whitened least squares on all five launch components. Noise
//!   scales `σ_c` are the robust scale (1.4826·MAD) of the nominal model's errors; after a first
//!   fit they are re-estimated from that fit's errors and the fit is repeated from its solution.
//! - [`Method::Paper`]: the procedure of Danaei et al. Their cost (Eq. 11) is
//!   `J = Σ_i [ W·|v_sim,i − v_exp,i|² + |ω_sim,i − ω_exp,i|² ]`; it is minimised in alternating
//!   stages with `W = ∞` (ball velocity only) and `W = 0` (spin only; the measured axes `ω_y`,
//!   `ω_z`). Each parameter is assigned, as the paper's sensitivity analysis did, to the stage
//!   where its relative sensitivity `‖∂r_stage/∂θ_j‖ / ‖r_stage‖` at the nominal model is larger.
//!   Stages alternate until a round changes no parameter by more than 1e-9 of its range.
//!
//! Both report values with standard errors from the whitened launch residuals at the solution
//! (see [`super::covariance`]), so their results are comparable.

use std::sync::Arc;

use nalgebra::{DMatrix, DVector};

use super::covariance::{covariance, Covariance, Identifiability};
use super::likelihood::{GivenScales, Likelihood};
use super::problem::{FitData, FitProblem, Weighting};
use super::run::{execute, FitRun, Progress};
use super::spec::{EffectRequest, ParamLayout};
use super::FitError;
use crate::club::ClubSpec;
use crate::effects::EffectKind;
use crate::measurement::{DeliveryNoise, ImpactNoise};
use crate::model::Shot;
use crate::stats::{self, launch_error_table, ErrorTable, LineFit};

mod paper;

/// Correlation magnitude beyond which a pair of estimates is flagged.
pub const STRONG_CORRELATION: f64 = 0.9;

/// Rounds of the paper's alternating procedure before giving up.
pub const PAPER_MAX_ROUNDS: usize = 30;

/// Smallest noise scale used for whitening, in file units (guards noiseless data).
const MIN_NOISE_SCALE: f64 = 1e-12;

/// Which procedure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Whitened Levenberg–Marquardt on the five launch components.
    #[default]
    Lm,
    /// The paper's alternating `W = ∞` / `W = 0` stages.
    Paper,
}

impl Method {
    /// Name on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Lm => "lm",
            Self::Paper => "paper",
        }
    }
}

/// Options of [`calibrate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CalibrateOptions {
    /// Procedure.
    pub method: Method,
    /// Iteration limit of each solver run.
    pub max_iters: u64,
    /// Compute Jacobian columns in parallel.
    pub parallel: bool,
    /// Noise of the measured impact locations, corrected by regression calibration.
    pub impact_noise: Option<ImpactNoise>,
    /// Noise of the other measured delivery variables (club speed, angles, the head's
    /// rotation), corrected by regression calibration ([`FitData::with_delivery_noise`]).
    pub delivery_noise: Option<DeliveryNoise>,
}

impl Default for CalibrateOptions {
    fn default() -> Self {
        Self {
            method: Method::Lm,
            max_iters: 100,
            parallel: true,
            impact_noise: None,
            delivery_noise: None,
        }
    }
}

/// One fitted parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamEstimate {
    /// Effect name.
    pub effect: &'static str,
    /// Group, `None` for a global effect.
    pub group: Option<String>,
    /// Parameter key (`dm_g`, …).
    pub param: &'static str,
    /// Unit.
    pub unit: &'static str,
    /// Fitted value.
    pub value: f64,
    /// Standard error (`None` when not identifiable).
    pub stderr: Option<f64>,
    /// Did the fit stop on a physical bound?
    pub at_bound: bool,
}

impl ParamEstimate {
    /// `effect@group.param`.
    pub fn label(&self) -> String {
        match &self.group {
            Some(g) => format!("{}@{g}.{}", self.effect, self.param),
            None => format!("{}.{}", self.effect, self.param),
        }
    }
}

/// A strongly correlated pair of estimates (indices into the parameter list).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CorrelatedPair {
    /// First parameter.
    pub a: usize,
    /// Second parameter.
    pub b: usize,
    /// Correlation.
    pub r: f64,
}

/// Stage of the paper's procedure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// `W = ∞`: ball velocity.
    Linear,
    /// `W = 0`: ball spin.
    Angular,
}

/// How the paper's procedure assigned one parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct PaperStageAssignment {
    /// Parameter index.
    pub param: usize,
    /// Relative sensitivity of the ball velocity error, 1/unit.
    pub linear_sensitivity: f64,
    /// Relative sensitivity of the spin error, 1/unit.
    pub angular_sensitivity: f64,
    /// Stage chosen.
    pub stage: Stage,
}

/// Per-group added mass against shaft mass (the paper's Figure 3).
#[derive(Debug, Clone, PartialEq)]
pub struct ShaftRelation {
    /// `(group, shaft mass g, added mass g, stderr g)`, by group.
    pub points: Vec<(String, f64, f64, Option<f64>)>,
    /// `dm = intercept + slope·shaft_mass`, with the correlation.
    pub line: LineFit,
}

/// Everything a calibration produced.
#[derive(Debug, Clone)]
pub struct Calibration {
    /// Procedure used.
    pub method: Method,
    /// The free effects.
    pub layout: ParamLayout,
    /// Fitted parameters in layout order.
    pub params: Vec<ParamEstimate>,
    /// Correlation matrix of the estimates (`None` when not identifiable).
    pub correlation: Option<DMatrix<f64>>,
    /// Pairs with |correlation| > [`STRONG_CORRELATION`].
    pub strongly_correlated: Vec<CorrelatedPair>,
    /// Identifiability at the solution.
    pub identifiability: Identifiability,
    /// χ² of the whitened launch residuals.
    pub chi2: f64,
    /// Residual rows `N`.
    pub n_residuals: usize,
    /// Degrees of freedom `N − p`.
    pub dof: usize,
    /// `χ²/(N − p)`.
    pub reduced_chi2: f64,
    /// `−2 ln L + 2k` of [`Self::likelihood`] (comparable across calibrations of the same
    /// shots with the same scale source, see [`super::likelihood`]).
    pub aic: f64,
    /// `−2 ln L + k·ln N` of [`Self::likelihood`].
    pub bic: f64,
    /// The calibrated model's likelihood score.
    pub likelihood: Likelihood,
    /// The nominal model's likelihood score, on the same scale (its `k`: no fitted parameter).
    pub likelihood_nominal: Likelihood,
    /// χ² of the nominal model whitened with this fit's noise scales (which another fit
    /// estimates differently: compare models by [`Self::likelihood`]).
    pub chi2_before: f64,
    /// Residual evaluations, all stages (a Jacobian counts two per parameter).
    pub evaluations: u64,
    /// Solver iterations, all stages.
    pub iterations: u64,
    /// Why the last stage stopped.
    pub termination: String,
    /// Noise scales `σ_c` the residuals were whitened with (robust, from this fit's errors),
    /// file units, launch component order.
    pub noise_scales: [f64; 5],
    /// Errors of the nominal model, Table-2 layout.
    pub before: ErrorTable,
    /// Errors of the calibrated model.
    pub after: ErrorTable,
    /// Per-group added mass against shaft mass, when both are known.
    pub shaft_relation: Option<ShaftRelation>,
    /// The paper procedure's stage assignment.
    pub paper_stages: Vec<PaperStageAssignment>,
    /// The calibrated club: the input club's effects plus the fitted ones.
    pub club: ClubSpec,
    /// The measurement model's impact-location noise (`None`: locations as measured).
    pub impact_noise: Option<ImpactNoise>,
    /// The measurement model's delivery noise (`None`: deliveries as measured).
    pub delivery_noise: Option<DeliveryNoise>,
}

/// Noise scale of each launch component: the robust scale of the errors (falling back to the
/// standard deviation when more than half the errors are equal), floored at a tiny positive
/// value.
pub fn noise_scales(errors: &[[f64; 5]]) -> [f64; 5] {
    std::array::from_fn(|c| {
        let col: Vec<f64> = errors.iter().map(|e| e[c]).collect();
        let s = stats::robust_scale(&col);
        let s = if s > 0.0 { s } else { stats::std_dev(&col) };
        if s.is_finite() {
            s.max(MIN_NOISE_SCALE)
        } else {
            1.0
        }
    })
}

fn group_names(data: &FitData) -> Vec<&str> {
    data.group_of
        .iter()
        .map(|&g| data.groups[g].as_str())
        .collect()
}

fn ensure_converged(run: &FitRun, stage: &str) -> Result<(), FitError> {
    if run.converged {
        Ok(())
    } else {
        Err(FitError::NotConverged {
            iterations: run.iterations,
            chi2: run.cost,
            stage: stage.to_owned(),
        })
    }
}

/// Fit `requests` (expanded over the groups of `shots`) to the measured launch of `shots`,
/// starting from the effects' defaults, on top of `club` (its own effects stay fixed). With
/// `opts.delivery_noise` and `opts.impact_noise` the model is evaluated at the expected true
/// deliveries and averaged over the likely impact locations (regression calibration,
/// [`crate::measurement`]), the measurement model `smash diagnose` selects.
pub fn calibrate(
    club: &ClubSpec,
    shots: &[Shot],
    requests: &[EffectRequest],
    opts: &CalibrateOptions,
    progress: Option<Arc<dyn Progress>>,
) -> Result<Calibration, FitError> {
    calibrate_scored(club, shots, requests, opts, None, progress)
}

/// [`calibrate`], its models scored ([`Calibration::likelihood`]) with the noise variances
/// `given` (one row a shot of `shots`) or, when `None`, with profiled scales.
pub fn calibrate_scored(
    club: &ClubSpec,
    shots: &[Shot],
    requests: &[EffectRequest],
    opts: &CalibrateOptions,
    given: Option<&GivenScales>,
    progress: Option<Arc<dyn Progress>>,
) -> Result<Calibration, FitError> {
    let data = FitData::from_shots(shots)?
        .with_delivery_noise(opts.delivery_noise)
        .with_impact_noise(opts.impact_noise)?;
    let layout = ParamLayout::from_requests(requests, &data.groups)?;
    // Fewer shots than the whole layout's parameters is reported by `calibrate_data`.
    if data.len() > layout.len() {
        if let Some((_, why)) = super::variation::check_variation(shots, requests)?.first() {
            return Err(FitError::Degenerate(why.clone()));
        }
    }
    calibrate_data_scored(club, &data, layout, opts, given, progress)
}

/// [`calibrate`] on prepared data and layout. `opts.impact_noise` and `opts.delivery_noise`
/// are not applied here (the caller prepared `data`); they are recorded in the result as the
/// measurement model the data were prepared for.
pub fn calibrate_data(
    club: &ClubSpec,
    data: &FitData,
    layout: ParamLayout,
    opts: &CalibrateOptions,
    progress: Option<Arc<dyn Progress>>,
) -> Result<Calibration, FitError> {
    calibrate_data_scored(club, data, layout, opts, None, progress)
}

/// [`calibrate_data`], scored with the variances `given` (one row a shot of `data`) or, when
/// `None`, with profiled scales ([`super::likelihood`]).
pub fn calibrate_data_scored(
    club: &ClubSpec,
    data: &FitData,
    layout: ParamLayout,
    opts: &CalibrateOptions,
    given: Option<&GivenScales>,
    progress: Option<Arc<dyn Progress>>,
) -> Result<Calibration, FitError> {
    if let Some(g) = given.filter(|g| g.variances.len() != data.len()) {
        return Err(FitError::ScalesPerShot {
            rows: g.variances.len(),
            shots: data.len(),
        });
    }
    let p = layout.len();
    if data.len() <= p {
        return Err(FitError::TooFewShots {
            shots: data.len(),
            params: p,
        });
    }
    let start = layout.defaults();
    let problem = FitProblem::new(club, layout.clone(), data, Weighting::launch(&[1.0; 5]))
        .with_parallel_jacobian(opts.parallel);
    let errors_before = problem.launch_errors(start.as_slice())?;
    let before = launch_error_table(&group_names(data), &errors_before);
    let sink = progress.as_ref();

    let solved = match opts.method {
        Method::Lm => two_lm_fits(&problem, &start, &errors_before, opts.max_iters, sink)?,
        Method::Paper => {
            let (theta, iterations, evaluations, stages, termination) =
                paper::paper_procedure(&problem, &start, opts.max_iters, sink)?;
            Solved {
                theta,
                iterations,
                evaluations,
                termination,
                paper_stages: stages,
                jacobian: None,
            }
        }
    };
    let theta = &solved.theta;

    // Statistics at the solution, with noise scales from its own errors. The whitened residuals
    // are the errors times 1/σ (the same bits as evaluating them); the Jacobian is the last
    // fit's, at this point, re-weighted to these scales, when the procedure has it.
    let errors_after = problem.launch_errors(theta.as_slice())?;
    let sigma = noise_scales(&errors_after);
    let residuals = whiten(&errors_after, &sigma);
    let mut evaluations = solved.evaluations + 1;
    let jac = match &solved.jacobian {
        Some((j, sigma_j)) => reweight(j, sigma_j, &sigma),
        None => {
            evaluations += 2 * p as u64;
            problem
                .clone()
                .with_weighting(Weighting::launch(&sigma))
                .jacobian_full(theta)?
        }
    };
    let chi2 = residuals.norm_squared();
    let chi2_before = whiten(&errors_before, &sigma).norm_squared();
    let likelihood = Likelihood::of(&errors_after, p, given);
    let nominal_errors = club_alone_errors(club, data)?;
    let likelihood_nominal = Likelihood::of(&nominal_errors, 0, given);
    let n_residuals = residuals.len();
    let dof = n_residuals - p;
    let reduced_chi2 = chi2 / dof as f64;
    let (lower, upper) = (layout.lower(), layout.upper());
    let ranges: Vec<f64> = (0..p).map(|j| upper[j] - lower[j]).collect();
    let cov = covariance(&jac, reduced_chi2, &ranges);

    let params = estimates(&layout, theta, &cov);
    let strongly_correlated = correlated_pairs(cov.correlation.as_ref());
    let shaft_relation = shaft_relation(data, &params);
    let mut effects = club.effects.clone();
    effects.extend(layout.to_effects(theta.as_slice()).map_err(|source| {
        FitError::ValuesOutOfBounds {
            which: "fitted",
            source,
        }
    })?);
    let calibrated = club
        .with_effects(effects)
        .map_err(|source| FitError::ClubNotPhysical {
            which: "calibrated",
            source,
        })?;
    Ok(Calibration {
        method: opts.method,
        params,
        correlation: cov.correlation,
        strongly_correlated,
        identifiability: cov.identifiability,
        chi2,
        n_residuals,
        dof,
        reduced_chi2,
        aic: likelihood.aic(),
        bic: likelihood.bic(),
        likelihood,
        likelihood_nominal,
        chi2_before,
        evaluations,
        iterations: solved.iterations,
        termination: solved.termination,
        noise_scales: sigma,
        before,
        after: launch_error_table(&group_names(data), &errors_after),
        shaft_relation,
        paper_stages: solved.paper_stages,
        club: calibrated,
        layout,
        impact_noise: opts.impact_noise,
        delivery_noise: opts.delivery_noise.filter(DeliveryNoise::is_active),
    })
}

/// The errors of the nominal model as the club alone (no free effect): the same evaluation in
/// every calibration, whatever effects it frees (at their defaults they leave the model as it
/// is, but a user-defined term evaluates along another path, equal only to rounding).
fn club_alone_errors(club: &ClubSpec, data: &FitData) -> Result<Vec<[f64; 5]>, FitError> {
    let layout = ParamLayout::new(Vec::new())?;
    Ok(FitProblem::new(club, layout, data, Weighting::launch(&[1.0; 5])).launch_errors(&[])?)
}

/// What a procedure found: the point, its work, and the Jacobian there when it has one.
struct Solved {
    theta: DVector<f64>,
    iterations: u64,
    evaluations: u64,
    termination: String,
    paper_stages: Vec<PaperStageAssignment>,
    /// Jacobian of the launch residuals at `theta` whitened with the noise scales given.
    jacobian: Option<(DMatrix<f64>, [f64; 5])>,
}

/// Whitened launch residuals `e_c / σ_c` from errors `e` (model − measured, file units): the
/// same bits as [`FitProblem::residuals`] with [`Weighting::launch`]`(sigma)`, which computes
/// `(ŷ − y)·(1/σ_c)` from the same difference.
fn whiten(errors: &[[f64; 5]], sigma: &[f64; 5]) -> DVector<f64> {
    let Weighting::Launch { inv_scale } = Weighting::launch(sigma) else {
        unreachable!("launch weighting")
    };
    DVector::from_iterator(
        errors.len() * 5,
        errors
            .iter()
            .flat_map(|e| std::array::from_fn::<f64, 5, _>(|c| e[c] * inv_scale[c])),
    )
}

/// A Jacobian of launch residuals whitened with scales `from`, re-weighted to scales `to`: row
/// `5i + c` times `σ_from,c / σ_to,c` (equal to evaluating it with `to` up to rounding).
fn reweight(j: &DMatrix<f64>, from: &[f64; 5], to: &[f64; 5]) -> DMatrix<f64> {
    let factor: [f64; 5] = std::array::from_fn(|c| from[c] / to[c]);
    DMatrix::from_fn(j.nrows(), j.ncols(), |r, k| j[(r, k)] * factor[r % 5])
}

/// The whitened Levenberg–Marquardt procedure ([`Method::Lm`]): a fit with noise scales from
/// the nominal errors `errors_before`, then one with scales re-estimated from that fit's errors,
/// started from its solution, each checked for convergence. What each run starts from is known
/// already and handed to it rather than evaluated again: the first run's residuals are the
/// nominal errors whitened, the second's its own errors whitened and the first run's final
/// Jacobian (at the same point) re-weighted.
fn two_lm_fits(
    problem: &FitProblem<'_>,
    start: &DVector<f64>,
    errors_before: &[[f64; 5]],
    max_iters: u64,
    sink: Option<&Arc<dyn Progress>>,
) -> Result<Solved, FitError> {
    let p = start.len() as u64;
    let sigma0 = noise_scales(errors_before);
    let stage = "fit 1/2 (noise from nominal errors)";
    let pr1 = problem.clone().with_weighting(Weighting::launch(&sigma0));
    let j0 = pr1.jacobian_full(start)?;
    let at_start = (whiten(errors_before, &sigma0), j0);
    let run1 = execute(
        pr1,
        start,
        max_iters,
        sink.map(|s| (s, stage)),
        true,
        Some(at_start),
    )?;
    ensure_converged(&run1, stage)?;
    let errors1 = problem.launch_errors(run1.theta.as_slice())?;
    let sigma1 = noise_scales(&errors1);
    let stage = "fit 2/2 (noise re-estimated)";
    let at_start = (
        whiten(&errors1, &sigma1),
        reweight(&run1.jacobian, &sigma0, &sigma1),
    );
    let run2 = execute(
        problem.clone().with_weighting(Weighting::launch(&sigma1)),
        &run1.theta,
        max_iters,
        sink.map(|s| (s, stage)),
        true,
        Some(at_start),
    )?;
    ensure_converged(&run2, stage)?;
    Ok(Solved {
        theta: run2.theta,
        iterations: run1.iterations + run2.iterations,
        // The start evaluations handed over: the first run's Jacobian, the second's errors.
        evaluations: run1.evaluations + run2.evaluations + 2 * p + 1,
        termination: run2.termination,
        paper_stages: Vec::new(),
        jacobian: Some((run2.jacobian, sigma1)),
    })
}

/// One [`ParamEstimate`] per parameter of `layout` at `theta`, with the standard errors of
/// `cov`; a value within 1e-9 of its range from a bound is flagged as on it.
fn estimates(layout: &ParamLayout, theta: &DVector<f64>, cov: &Covariance) -> Vec<ParamEstimate> {
    let (lower, upper) = (layout.lower(), layout.upper());
    layout
        .params()
        .enumerate()
        .map(|(j, (i, s))| {
            let e = &layout.effects()[i];
            // Scaled before the difference: bounds of ±1e308 would overflow it to infinity
            // and mark every value at its bound.
            let span = 1e-9 * upper[j] - 1e-9 * lower[j];
            ParamEstimate {
                effect: e.kind.name(),
                group: e.group.clone(),
                param: s.key,
                unit: s.unit,
                value: theta[j],
                stderr: cov.stderr[j],
                at_bound: theta[j] <= lower[j] + span || theta[j] >= upper[j] - span,
            }
        })
        .collect()
}

/// The pairs of parameters whose estimates correlate beyond [`STRONG_CORRELATION`].
fn correlated_pairs(correlation: Option<&DMatrix<f64>>) -> Vec<CorrelatedPair> {
    let mut pairs = Vec::new();
    if let Some(c) = correlation {
        for a in 0..c.nrows() {
            for b in a + 1..c.ncols() {
                if c[(a, b)].abs() > STRONG_CORRELATION {
                    pairs.push(CorrelatedPair { a, b, r: c[(a, b)] });
                }
            }
        }
    }
    pairs
}

/// Added mass per group against the group's shaft mass, when at least two groups have both.
fn shaft_relation(data: &FitData, params: &[ParamEstimate]) -> Option<ShaftRelation> {
    let mut points = Vec::new();
    for pe in params {
        let Some(group) = &pe.group else { continue };
        if pe.effect != EffectKind::AddedMass.name() {
            continue;
        }
        let gi = data.groups.iter().position(|g| g == group)?;
        let masses: Vec<f64> = data
            .group_of
            .iter()
            .zip(&data.shaft_mass_g)
            .filter(|(g, _)| **g == gi)
            .filter_map(|(_, m)| *m)
            .collect();
        if masses.is_empty() {
            continue;
        }
        points.push((group.clone(), stats::mean(&masses), pe.value, pe.stderr));
    }
    let x: Vec<f64> = points.iter().map(|p| p.1).collect();
    let y: Vec<f64> = points.iter().map(|p| p.2).collect();
    let line = stats::linear_regression(&x, &y)?;
    Some(ShaftRelation { points, line })
}
