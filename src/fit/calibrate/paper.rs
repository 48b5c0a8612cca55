//! The paper's alternating `W = ∞` / `W = 0` procedure ([`super::Method::Paper`]; see the
//! module docs of [`super`]).

use std::sync::Arc;

use nalgebra::DVector;

use super::{ensure_converged, PaperStageAssignment, Stage, PAPER_MAX_ROUNDS};
use crate::fit::problem::{FitProblem, Weighting};
use crate::fit::run::{run_lm, Progress};
use crate::fit::FitError;

pub(super) type PaperResult = (DVector<f64>, u64, u64, Vec<PaperStageAssignment>, String);

/// The paper's alternating `W = ∞` / `W = 0` procedure (see the module docs).
pub(super) fn paper_procedure(
    problem: &FitProblem<'_>,
    start: &DVector<f64>,
    max_iters: u64,
    sink: Option<&Arc<dyn Progress>>,
) -> Result<PaperResult, FitError> {
    let p = start.len();
    let linear = problem.clone().with_weighting(Weighting::PaperLinear);
    let angular = problem.clone().with_weighting(Weighting::PaperAngular);
    let sensitivity = |pr: &FitProblem<'_>| -> Result<Vec<f64>, FitError> {
        let r = pr.residuals(start.as_slice())?.norm();
        let j = pr.jacobian_full(start)?;
        Ok((0..p).map(|k| j.column(k).norm() / r).collect())
    };
    let s_lin = sensitivity(&linear)?;
    let s_ang = sensitivity(&angular)?;
    let mut evaluations = 2 * (1 + 2 * p as u64);
    let stages: Vec<PaperStageAssignment> = (0..p)
        .map(|j| PaperStageAssignment {
            param: j,
            linear_sensitivity: s_lin[j],
            angular_sensitivity: s_ang[j],
            stage: if s_lin[j] >= s_ang[j] {
                Stage::Linear
            } else {
                Stage::Angular
            },
        })
        .collect();
    let pick = |st: Stage| -> Vec<usize> {
        stages
            .iter()
            .filter(|a| a.stage == st)
            .map(|a| a.param)
            .collect()
    };
    let (lin_idx, ang_idx) = (pick(Stage::Linear), pick(Stage::Angular));
    let lower = problem.layout().lower();
    let upper = problem.layout().upper();
    let mut theta = start.clone();
    let mut iterations = 0;
    let mut termination = String::new();
    for round in 1..=PAPER_MAX_ROUNDS {
        let before = theta.clone();
        for (idx, pr, name) in [(&lin_idx, &linear, "W=inf"), (&ang_idx, &angular, "W=0")] {
            if idx.is_empty() {
                continue;
            }
            let stage = format!("paper {name} round {round}");
            let run = run_lm(
                pr.clone().with_active(idx.clone(), theta.clone()),
                &theta,
                max_iters,
                sink.map(|s| (s, stage.as_str())),
            )?;
            ensure_converged(&run, &stage)?;
            iterations += run.iterations;
            evaluations += run.evaluations;
            termination = run.termination;
            theta = run.theta;
        }
        let change = (0..p)
            .map(|j| (theta[j] - before[j]).abs() / (upper[j] - lower[j]))
            .fold(0.0, f64::max);
        if change <= 1e-9 {
            return Ok((
                theta,
                iterations,
                evaluations,
                stages,
                format!("{termination}; stages stable after {round} round(s)"),
            ));
        }
    }
    Err(FitError::NotConverged {
        iterations,
        chi2: f64::NAN,
        stage: format!("paper: stages still moving after {PAPER_MAX_ROUNDS} rounds"),
    })
}
