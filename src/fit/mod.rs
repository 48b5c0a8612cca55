//! Fitting effect parameters to measured launch conditions.
//!
//! The flow: shots with measurements → [`FitData`]; the effects to free → [`ParamLayout`];
//! both with a club → [`FitProblem`], an argmin problem (residual [`argmin::core::Operator`]
//! and finite-difference [`argmin::core::Jacobian`]); handed with the bounded
//! [`LevenbergMarquardt`] solver to an argmin `Executor` ([`run_lm`]); the solution's
//! Jacobian → [`covariance`]; everything → a [`Calibration`] report (plain data: the CLI prints
//! it, `report` formats it).
//!
//! Statistics, with `r` the whitened residuals (`(model − measured)/σ_c`, `σ_c` the noise
//! scale of launch component `c`, estimated from the data as the normal-consistent MAD of the
//! residuals and re-estimated after a first fit), `N` residual rows and `p` parameters:
//! `χ² = Σ r²`, reduced `χ²/(N − p)`, standard errors `√diag((JᵀJ)⁻¹·χ²/(N − p))` from the
//! undamped Jacobian at the solution. Models are compared on one scale, not by this χ²
//! (whose scales each fit estimates for itself): by the Gaussian likelihood of the errors with
//! given or profiled noise scales, `AIC = −2 ln L + 2k`, `BIC = −2 ln L + k·ln N`
//! ([`likelihood`]).

pub mod calibrate;
pub mod covariance;
mod data;
pub mod likelihood;
pub mod lm;
pub mod problem;
pub mod run;
pub mod spec;
pub mod variation;

pub use calibrate::{
    calibrate, calibrate_scored, noise_scales, CalibrateOptions, Calibration, CorrelatedPair,
    Method, PaperStageAssignment, ParamEstimate, ShaftRelation, Stage,
};
pub use covariance::{covariance, Covariance, Identifiability};
pub(crate) use data::distinct_groups;
pub use likelihood::{GivenScales, Likelihood, ScaleSource};
pub use lm::{Converged, LevenbergMarquardt, LmState};
pub use problem::{
    scalar_path_counts, EvalError, FitData, FitProblem, ScalarPathCounts, Weighting,
    FD_STEP_OF_RANGE,
};
pub use run::{
    fit_quietly, fit_quietly_chord_from, fit_quietly_from, run_lm, run_lm_point, run_lm_point_from,
    run_lm_point_near, FitPoint, FitRun, IterInfo, Progress,
};
pub use spec::{parse_effect_list, parse_request, EffectRequest, FreeEffect, ParamLayout};

use crate::effects::EffectError;
use crate::physics::LaunchComponent;

/// argmin's error, shared so that a [`FitError`] can be cloned, and compared by its message.
#[derive(Debug, Clone)]
pub struct SolverError(pub std::sync::Arc<argmin::core::Error>);

impl std::fmt::Display for SolverError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl std::error::Error for SolverError {}

impl PartialEq for SolverError {
    fn eq(&self, other: &Self) -> bool {
        self.to_string() == other.to_string()
    }
}

impl From<argmin::core::Error> for SolverError {
    fn from(e: argmin::core::Error) -> Self {
        Self(std::sync::Arc::new(e))
    }
}

/// Why a fit cannot be done or did not succeed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// The shots have no measured launch columns.
    #[error(
        "the shots have no measured launch columns ({}); fitting compares the model with \
         measurements, so the shots file needs them",
        LaunchComponent::ALL.map(|c| c.column()).join(", ")
    )]
    NoMeasurements,
    /// The impact-location noise model cannot be applied.
    #[error(transparent)]
    Measurement(#[from] crate::measurement::MeasurementError),
    /// An effect name is not in the library.
    #[error(transparent)]
    Effect(#[from] EffectError),
    /// The effect list is malformed.
    #[error("effect list: {0}")]
    BadEffectList(String),
    /// `name@group` with a single group of shots.
    #[error(
        "'{effect}@group' fits one value per group, but the shots have only one group ('{}'); \
         use the global form '{effect}'",
        groups.join("', '")
    )]
    PerGroupNeedsGroups {
        /// Effect name.
        effect: &'static str,
        /// The groups present.
        groups: Vec<String>,
    },
    /// `name@A` with no shot in group `A`.
    #[error(
        "'{effect}@{group}': no shot is in group '{group}' (groups present: {})",
        groups.join(", ")
    )]
    UnknownGroup {
        /// Effect name.
        effect: &'static str,
        /// The group asked for.
        group: String,
        /// The groups present.
        groups: Vec<String>,
    },
    /// Not enough shots for the parameters.
    #[error(
        "{shots} shot(s) cannot determine {params} parameter(s): a fit needs more shots than \
         parameters"
    )]
    TooFewShots {
        /// Shots given.
        shots: usize,
        /// Parameters asked for.
        params: usize,
    },
    /// The shots cannot tell effects apart (no variation, or too little for the effects).
    #[error("degenerate data: {0}")]
    Degenerate(String),
    /// The model cannot be evaluated at the starting values.
    #[error("cannot evaluate the model at the starting values: {0}")]
    Start(#[from] EvalError),
    /// The solver ran out of iterations.
    #[error(
        "the fit did not converge within {iterations} iteration(s) (chi2 = {chi2:.6}, stage \
         '{stage}'); raise --max-iters, fit fewer effects, or check the data"
    )]
    NotConverged {
        /// Iterations done in the failing stage.
        iterations: u64,
        /// χ² reached.
        chi2: f64,
        /// Which stage of the procedure.
        stage: String,
    },
    /// The caller cancelled the work ([`crate::cancel::Cancel`]).
    #[error("cancelled: the work was stopped on request before its end")]
    Cancelled,
    /// The solver itself failed (argmin's error: bounds it refuses, an operator failure).
    #[error("solver: {0}")]
    Solver(#[source] SolverError),
    /// Given noise variances that are not one row a shot.
    #[error(
        "the given noise variances have {rows} row(s) for {shots} shot(s): one row a shot is \
         needed"
    )]
    ScalesPerShot {
        /// Rows of variances given.
        rows: usize,
        /// Shots fitted.
        shots: usize,
    },
    /// Fitted (or base) values that do not make effects: outside an effect's bounds.
    #[error("{which} values out of bounds: {source}")]
    ValuesOutOfBounds {
        /// Whose values: `fitted` or `base`.
        which: &'static str,
        /// Why.
        #[source]
        source: EffectError,
    },
    /// The club with the fitted (or base) effects is not physical.
    #[error("{which} club is not physical: {source}")]
    ClubNotPhysical {
        /// Which club: `calibrated` or `base`.
        which: &'static str,
        /// Why.
        #[source]
        source: crate::physics::ParamError,
    },
    /// A group's model cannot be made from the club (the noise floor's per-group models).
    #[error("noise floor: the model of group '{group}': {source}")]
    GroupModel {
        /// The group.
        group: String,
        /// Why.
        #[source]
        source: crate::physics::ParamError,
    },
    /// A shot the model cannot solve at its measured delivery (the noise floor's propagation).
    #[error("noise floor: shot '{shot_id}' cannot be solved at its measured delivery")]
    Unsolvable {
        /// The shot's id.
        shot_id: String,
    },
}
