//! Solver glue: hand a [`FitProblem`] and the [`LevenbergMarquardt`] solver to an argmin
//! `Executor`, report each iteration to an optional [`Progress`] sink, and collect the result.

use std::sync::Arc;

use argmin::core::observers::{Observe, ObserverMode};
use argmin::core::{Error as ArgminError, Executor, State, KV};
use nalgebra::{DMatrix, DVector};

use super::lm::{LevenbergMarquardt, LmState};
use super::problem::{EvalError, FitProblem};
use super::FitError;

/// One iteration, as reported to a [`Progress`] sink.
#[derive(Debug, Clone, Copy)]
pub struct IterInfo<'a> {
    /// Stage of the procedure (`fit 1/2`, `paper W=inf round 1`, …).
    pub stage: &'a str,
    /// Iteration within the stage (from 1).
    pub iter: u64,
    /// χ² (or the paper's cost) after the iteration.
    pub cost: f64,
    /// Levenberg–Marquardt damping after the iteration.
    pub lambda: f64,
    /// Residual evaluations so far in the stage (Jacobian columns count two each).
    pub evaluations: u64,
}

/// Receives one call per solver iteration (the CLI draws a progress line; the library prints
/// nothing).
pub trait Progress: Send + Sync {
    /// Called after each iteration.
    fn iteration(&self, info: &IterInfo<'_>);
}

/// Result of one solver run.
#[derive(Debug, Clone)]
pub struct FitRun {
    /// Full parameter vector `θ` at the end (file units).
    pub theta: DVector<f64>,
    /// χ² (sum of squared residuals) at `θ`.
    pub cost: f64,
    /// Residuals at `θ`.
    pub residuals: DVector<f64>,
    /// Jacobian of the residuals in the active parameters at `θ`.
    pub jacobian: DMatrix<f64>,
    /// Iterations done.
    pub iterations: u64,
    /// Residual evaluations (each Jacobian counts `2 × active parameters`).
    pub evaluations: u64,
    /// Why it stopped.
    pub termination: String,
    /// Did it converge (rather than run out of iterations)?
    pub converged: bool,
}

fn evaluations(state: &LmState, n_active: usize) -> u64 {
    let counts = state.get_func_counts();
    let ops = counts.get("operator_count").copied().unwrap_or(0);
    let jacs = counts.get("jacobian_count").copied().unwrap_or(0);
    ops + jacs * 2 * n_active as u64
}

struct Observer {
    sink: Arc<dyn Progress>,
    stage: String,
    n_active: usize,
}

impl Observe<LmState> for Observer {
    fn observe_iter(&mut self, state: &LmState, kv: &KV) -> Result<(), ArgminError> {
        let lambda = kv
            .get("lambda")
            .and_then(|v| v.get_float())
            .unwrap_or(f64::NAN);
        self.sink.iteration(&IterInfo {
            stage: &self.stage,
            iter: state.get_iter() + 1,
            cost: state.get_cost(),
            lambda,
            evaluations: evaluations(state, self.n_active),
        });
        Ok(())
    }
}

fn map_err(e: ArgminError) -> FitError {
    match e.downcast::<EvalError>() {
        Ok(eval) => FitError::Start(eval),
        Err(other) => FitError::Solver(other.into()),
    }
}

/// Friction coefficients tried before a fit (within the effect's bounds).
pub const FRICTION_SCAN: [f64; 11] = [0.02, 0.035, 0.05, 0.07, 0.1, 0.15, 0.2, 0.3, 0.4, 0.6, 1.0];

/// Starting point for the solver. The friction limit is not smooth: where no shot slips, χ² does
/// not depend on `mu` at all and a gradient method cannot move. So each active friction
/// coefficient is first set to the best of [`FRICTION_SCAN`] (and the given start) by χ².
pub fn scan_nonsmooth_starts(problem: &FitProblem<'_>, start: &DVector<f64>) -> DVector<f64> {
    let layout = problem.layout();
    let mut theta = start.clone();
    let friction: Vec<usize> = layout
        .params()
        .enumerate()
        .filter(|(j, (i, _))| layout.effects()[*i].is_nonsmooth() && problem.active().contains(j))
        .map(|(j, _)| j)
        .collect();
    let chi2 = |t: &DVector<f64>| {
        problem
            .residuals(t.as_slice())
            .map_or(f64::INFINITY, |r| r.norm_squared())
    };
    for j in friction {
        let (lo, hi) = (layout.lower()[j], layout.upper()[j]);
        let mut best = (chi2(&theta), theta[j]);
        for &mu in FRICTION_SCAN.iter().filter(|&&m| (lo..=hi).contains(&m)) {
            theta[j] = mu;
            let c = chi2(&theta);
            if c < best.0 {
                best = (c, mu);
            }
        }
        theta[j] = best.1;
    }
    theta
}

/// Run Levenberg–Marquardt on `problem` from the full parameter vector `start` (only the
/// problem's active entries move), for at most `max_iters` iterations.
/// Active friction coefficients start from the best of [`FRICTION_SCAN`].
pub fn run_lm(
    problem: FitProblem<'_>,
    start: &DVector<f64>,
    max_iters: u64,
    progress: Option<(&Arc<dyn Progress>, &str)>,
) -> Result<FitRun, FitError> {
    execute(problem, start, max_iters, progress, true, None)
}

/// [`run_lm`] of the problem `(club, layout, data, w)` from `start`, without progress reports:
/// the fit diagnose's candidates, folds and refinements all make.
pub fn fit_quietly(
    club: &crate::club::ClubSpec,
    layout: &super::ParamLayout,
    data: &super::FitData,
    w: super::Weighting,
    start: &DVector<f64>,
    max_iters: u64,
) -> Result<FitRun, FitError> {
    fit_quietly_from(club, layout, data, w, start, max_iters, None)
}

/// [`fit_quietly`] given the residuals and Jacobian at `start` (all parameters active) when the
/// caller has them (`at_start`): used unless the friction scan moves the start or `start` lies
/// outside the bounds, and the fit is then the same, one residual and one Jacobian evaluation
/// cheaper ([`LevenbergMarquardt::with_start_evaluation`]).
pub fn fit_quietly_from(
    club: &crate::club::ClubSpec,
    layout: &super::ParamLayout,
    data: &super::FitData,
    w: super::Weighting,
    start: &DVector<f64>,
    max_iters: u64,
    at_start: Option<(DVector<f64>, DMatrix<f64>)>,
) -> Result<FitRun, FitError> {
    let pr = FitProblem::new(club, layout.clone(), data, w);
    execute(pr, start, max_iters, None, true, at_start)
}

/// The solution of a fit without what only its covariance needs.
#[derive(Debug, Clone)]
pub struct FitPoint {
    /// Full parameter vector `θ` at the end (file units).
    pub theta: DVector<f64>,
    /// χ² at `θ`.
    pub cost: f64,
    /// Iterations done.
    pub iterations: u64,
    /// Did it converge (rather than run out of iterations)?
    pub converged: bool,
}

impl From<FitRun> for FitPoint {
    /// The solution of a run, without its covariance.
    fn from(run: FitRun) -> Self {
        Self {
            theta: run.theta,
            cost: run.cost,
            iterations: run.iterations,
            converged: run.converged,
        }
    }
}

/// [`run_lm`] when only the solution is wanted (cross-validation folds): the same point,
/// iterations and `χ²`, without the Jacobian at the solution when the fit stops on a small
/// change of `χ²` ([`LevenbergMarquardt::without_final_jacobian`]).
pub fn run_lm_point(
    problem: FitProblem<'_>,
    start: &DVector<f64>,
    max_iters: u64,
) -> Result<FitPoint, FitError> {
    run_lm_point_from(problem, start, max_iters, None)
}

/// [`run_lm_point`] given the residuals and Jacobian (active columns) at `start` when they are
/// known already (`at_start`): they are used unless the friction scan
/// ([`scan_nonsmooth_starts`]) moves the start or `start` lies outside the bounds, and the fit
/// is then the same, one residual and one Jacobian evaluation cheaper.
pub fn run_lm_point_from(
    problem: FitProblem<'_>,
    start: &DVector<f64>,
    max_iters: u64,
    at_start: Option<(DVector<f64>, DMatrix<f64>)>,
) -> Result<FitPoint, FitError> {
    execute(problem, start, max_iters, None, false, at_start).map(FitPoint::from)
}

/// [`run_lm_point_from`] keeping the Jacobian given at the start for the steps
/// ([`LevenbergMarquardt::with_kept_start_jacobian`]): for a fit started close to its solution
/// (a cross-validation fold started from the all-shots solution) it saves the `2p` shifted
/// model evaluations of each step, and stops at a point whose `χ²` is above the fit's own
/// minimum by a second-order amount (not the same point as [`run_lm_point_from`]). With
/// `at_start` it starts at `start` without the friction scan ([`scan_nonsmooth_starts`]: the
/// fit that found `start` scanned); without `at_start` (or when `start` lies outside the
/// bounds) it is [`run_lm_point_from`].
pub fn run_lm_point_near(
    problem: FitProblem<'_>,
    start: &DVector<f64>,
    max_iters: u64,
    at_start: Option<(DVector<f64>, DMatrix<f64>)>,
) -> Result<FitPoint, FitError> {
    execute_with(
        problem,
        start,
        max_iters,
        None,
        (false, Steps::KeptNear),
        at_start,
    )
    .map(FitPoint::from)
}

/// [`fit_quietly_from`] with the chord steps of a kept start Jacobian
/// ([`LevenbergMarquardt::to_own_minimum`]) and the covariance's Jacobian from the point before
/// the last step when that step changed `χ²` by less than `ftol`
/// ([`LevenbergMarquardt::without_final_jacobian`], as MINPACK returns it): the fit's own
/// minimum to its tolerances, typically with one Jacobian evaluated where plain
/// Levenberg–Marquardt evaluates one a step. Diagnose's effect candidates, started from the
/// step base's evaluation (`at_start`), fit this way. Without `at_start` (or when the friction
/// scan moves the start) it is [`fit_quietly_from`] without the final Jacobian.
pub fn fit_quietly_chord_from(
    club: &crate::club::ClubSpec,
    layout: &super::ParamLayout,
    data: &super::FitData,
    w: super::Weighting,
    start: &DVector<f64>,
    max_iters: u64,
    at_start: Option<(DVector<f64>, DMatrix<f64>)>,
) -> Result<FitRun, FitError> {
    let pr = FitProblem::new(club, layout.clone(), data, w);
    execute_with(
        pr,
        start,
        max_iters,
        None,
        (false, Steps::KeptToOwn),
        at_start,
    )
}

/// The relative change of `χ²` at which the fits of [`run_lm_point_near`] and
/// [`fit_quietly_chord_from`] stop (diagnose's candidates and cross-validation folds, whether or
/// not a start evaluation lets them keep a Jacobian), where the solver's default is 1e-10. Those fits are compared by differences of `χ²` against a
/// penalty of `ln n` a parameter (at least 4.6 for 100 shots); at 1e-8 a 2,200-shot season's
/// `χ²` of about 16,000 is settled to 2e-4, and each chord refresh the tighter default asks for
/// costs a Jacobian (on that season it was a tenth of diagnose's CPU time).
const CHORD_FTOL: f64 = 1e-8;

/// How a fit given its start evaluation uses that Jacobian.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Steps {
    /// A Jacobian at every accepted point.
    Own,
    /// The start's kept for the steps, stopping near the fit's minimum
    /// ([`LevenbergMarquardt::with_kept_start_jacobian`]).
    KeptNear,
    /// The start's kept for the steps, then the point's own to the fit's minimum
    /// ([`LevenbergMarquardt::to_own_minimum`]).
    KeptToOwn,
}

/// [`run_lm`], with the Jacobian at a solution reached by a small `χ²` change computed or not
/// (`final_jacobian`; when not, [`FitRun::jacobian`] is that of the point before).
pub(crate) fn execute(
    problem: FitProblem<'_>,
    start: &DVector<f64>,
    max_iters: u64,
    progress: Option<(&Arc<dyn Progress>, &str)>,
    final_jacobian: bool,
    at_start: Option<(DVector<f64>, DMatrix<f64>)>,
) -> Result<FitRun, FitError> {
    execute_with(
        problem,
        start,
        max_iters,
        progress,
        (final_jacobian, Steps::Own),
        at_start,
    )
}

/// [`execute`]; `steps` says how a given start's Jacobian is used ([`run_lm_point_near`],
/// [`fit_quietly_chord_from`]).
fn execute_with(
    problem: FitProblem<'_>,
    start: &DVector<f64>,
    max_iters: u64,
    progress: Option<(&Arc<dyn Progress>, &str)>,
    (final_jacobian, steps): (bool, Steps),
    at_start: Option<(DVector<f64>, DMatrix<f64>)>,
) -> Result<FitRun, FitError> {
    let n_active = problem.active().len();
    let mut solver = LevenbergMarquardt::new(problem.active_lower(), problem.active_upper())
        .map_err(|e| FitError::Solver(e.into()))?;
    if !final_jacobian {
        solver = solver.without_final_jacobian();
    }
    if steps != Steps::Own {
        solver = solver
            .with_ftol(CHORD_FTOL)
            .map_err(|e| FitError::Solver(e.into()))?;
    }
    // A fit started near its solution with the evaluation there given (a cross-validation
    // fold started from the all-shots solution, whose fit scanned the friction already) starts
    // there: a scan on the fold's shots would move a never-identifiable `mu` to a grid value
    // and crawl back along its flat valley, step by step with new Jacobians.
    let near = steps == Steps::KeptNear && at_start.is_some();
    let init = if near {
        problem.active_part(start)
    } else {
        problem.active_part(&scan_nonsmooth_starts(&problem, start))
    };
    if let Some((r, j)) = at_start {
        let (lo, hi) = (problem.active_lower(), problem.active_upper());
        let unmoved = init == problem.active_part(start)
            && init
                .iter()
                .zip(lo.iter().zip(hi.iter()))
                .all(|(v, (l, u))| l <= v && v <= u);
        if unmoved && r.len() == problem.rows() && j.shape() == (problem.rows(), n_active) {
            solver = solver.with_start_evaluation(r, j);
            match steps {
                Steps::Own => {}
                Steps::KeptNear => solver = solver.with_kept_start_jacobian(),
                Steps::KeptToOwn => solver = solver.with_kept_start_jacobian().to_own_minimum(),
            }
        }
    }
    let template = problem.clone();
    let mut exec = Executor::new(problem, solver)
        .configure(|s: LmState| s.param(init).max_iters(max_iters).counting(true));
    if let Some((sink, stage)) = progress {
        exec = exec.add_observer(
            Observer {
                sink: Arc::clone(sink),
                stage: stage.to_owned(),
                n_active,
            },
            ObserverMode::Always,
        );
    }
    let mut result = exec.run().map_err(map_err)?;
    let converged = result.solver().converged().is_some();
    let state = result.state();
    let iterations = state.get_iter();
    let evals = evaluations(state, n_active);
    let termination = state.get_termination_status().to_string();
    let state = &mut result.state;
    let cost = state.get_cost();
    let active = state.take_param().expect("solver keeps its point");
    let residuals = state.take_residuals().expect("solver keeps residuals");
    let jacobian = state.take_jacobian().expect("solver keeps the Jacobian");
    Ok(FitRun {
        theta: template.full_theta(active.as_slice()),
        cost,
        residuals,
        jacobian,
        iterations,
        evaluations: evals,
        termination,
        converged,
    })
}
