//! Design optimisation: an argmin cost function over bounded design variables, solved by
//! Nelder–Mead.
//!
//! The objective is `Σ wᵢ·metricᵢ` over the study's metrics (see `metrics`), maximised or
//! minimised. Bounds are enforced by reparametrisation: the optimiser moves a free variable `u`
//! and the design variable is `x = c + h·sin u` with `c` the middle and `h` the half-width of
//! `[lower, upper]`, so every evaluated design lies inside its bounds. The total clubhead mass
//! is a hard constraint: mass moves (`mass_*`) relocate the discretionary mass without changing
//! the total, and no design variable adds or removes mass. The search starts at the base design
//! (every variable neutral) with an initial simplex of steps of 0.4 rad in `u`.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use argmin::core::observers::{Observe, ObserverMode};
use argmin::core::{CostFunction, Executor, IterState, State, KV};
use argmin::solver::neldermead::NelderMead;

use super::design::Design;
use super::evaluate::evaluate;
use super::metrics::metric_names;
use super::spec::{Goal, OptimiseSpec};
use super::sweep::{design_model, Prepared};
use super::StudyError;

/// The optimisation problem: design variables in `u` space → cost (argmin minimises).
pub struct DesignProblem<'a> {
    prepared: &'a Prepared,
    spec: &'a OptimiseSpec,
    weights: Vec<(usize, f64)>,
    evaluations: AtomicUsize,
}

/// One recorded iteration: iteration number, best objective so far, best design.
#[derive(Debug, Clone, PartialEq)]
pub struct PathPoint {
    /// Iteration (0 = the initial simplex).
    pub iteration: u64,
    /// Objective of the best design so far.
    pub objective: f64,
    /// Best design so far.
    pub design: Design,
}

/// What the optimiser found.
#[derive(Debug, Clone, PartialEq)]
pub struct OptimiseResult {
    /// The base design's objective.
    pub base_objective: f64,
    /// The optimum's objective.
    pub best_objective: f64,
    /// The optimum design.
    pub best: Design,
    /// Base metrics, `metric_names` order.
    pub base_metrics: Vec<f64>,
    /// Optimum metrics.
    pub best_metrics: Vec<f64>,
    /// The path: best design per iteration.
    pub path: Vec<PathPoint>,
    /// Objective evaluations.
    pub evaluations: usize,
    /// Why the solver stopped.
    pub termination: String,
}

impl<'a> DesignProblem<'a> {
    /// The problem for the prepared study's `[optimise]`.
    pub fn new(prepared: &'a Prepared, spec: &'a OptimiseSpec) -> Self {
        let names = metric_names(prepared.study.distribution.is_some());
        let weights = spec
            .objective
            .iter()
            .map(|(n, w)| {
                let i = names.iter().position(|m| m == n).expect("validated metric");
                (i, *w)
            })
            .collect();
        Self {
            prepared,
            spec,
            weights,
            evaluations: AtomicUsize::new(0),
        }
    }

    /// Design for free variables `u`.
    pub fn design(&self, u: &[f64]) -> Design {
        let mut d = Design::default();
        for ((var, lo, hi), ui) in self.spec.bounds.iter().zip(u) {
            let (c, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            d.set(*var, (c + h * ui.sin()).clamp(*lo, *hi));
        }
        d
    }

    /// Free variables of the base design.
    pub fn base_u(&self) -> Vec<f64> {
        self.spec
            .bounds
            .iter()
            .map(|(var, lo, hi)| {
                let (c, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
                ((var.neutral() - c) / h).clamp(-1.0, 1.0).asin()
            })
            .collect()
    }

    /// Metrics and objective of a design.
    pub fn objective(&self, d: &Design) -> Result<(f64, Vec<f64>), StudyError> {
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        let model = design_model(&self.prepared.study, d)?;
        let m = evaluate(&model, &self.prepared.study, &self.prepared.groups);
        let obj: f64 = self.weights.iter().map(|(i, w)| w * m[*i]).sum();
        if !obj.is_finite() {
            return Err(StudyError::Optimise(format!(
                "the objective is not defined for design ({}): an impact of the distribution or \
                 the summary probes is off the face",
                d.describe()
            )));
        }
        Ok((obj, m))
    }

    fn sign(&self) -> f64 {
        match self.spec.goal {
            Goal::Minimise => 1.0,
            Goal::Maximise => -1.0,
        }
    }
}

impl CostFunction for DesignProblem<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    /// A design that is not physical (an inertia tensor breaking the triangle inequality, say)
    /// or cannot be evaluated is infeasible: its cost is +∞, so the simplex moves away from it
    /// instead of the run stopping.
    fn cost(&self, u: &Self::Param) -> Result<f64, argmin::core::Error> {
        Ok(match self.objective(&self.design(u)) {
            Ok((obj, _)) if obj.is_finite() => self.sign() * obj,
            _ => f64::INFINITY,
        })
    }
}

type NmState = IterState<Vec<f64>, (), (), (), (), f64>;

/// Records the best point after every iteration.
type SharedPath = Arc<Mutex<Vec<(u64, f64, Vec<f64>)>>>;

struct PathRecorder(SharedPath);

impl PathRecorder {
    fn push(&self, state: &NmState) {
        if let Some(p) = state.get_best_param() {
            self.0.lock().expect("path lock").push((
                state.get_iter(),
                state.get_best_cost(),
                p.clone(),
            ));
        }
    }
}

impl Observe<NmState> for PathRecorder {
    fn observe_init(
        &mut self,
        _: &str,
        state: &NmState,
        _: &KV,
    ) -> Result<(), argmin::core::Error> {
        self.push(state);
        Ok(())
    }
    fn observe_iter(&mut self, state: &NmState, _: &KV) -> Result<(), argmin::core::Error> {
        self.push(state);
        Ok(())
    }
}

/// Run the study's optimisation (`None` if it has no `[optimise]`).
pub fn optimise(p: &Prepared) -> Result<Option<OptimiseResult>, StudyError> {
    let Some(spec) = &p.study.optimise else {
        return Ok(None);
    };
    let problem = DesignProblem::new(p, spec);
    let u0 = problem.base_u();
    let (base_objective, base_metrics) = problem.objective(&Design::default())?;
    let mut simplex = vec![u0.clone()];
    for i in 0..u0.len() {
        let mut u = u0.clone();
        // Step toward the interior when the base sits at an upper bound.
        u[i] += if u0[i] > 1.0 { -0.4 } else { 0.4 };
        simplex.push(u);
    }
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(spec.tolerance)
        .map_err(|e| StudyError::Optimise(e.to_string()))?;
    let path = Arc::new(Mutex::new(Vec::new()));
    let sign = problem.sign();
    let result = Executor::new(problem, solver)
        .configure(|s| s.max_iters(spec.max_iters))
        .add_observer(PathRecorder(Arc::clone(&path)), ObserverMode::Always)
        .run()
        .map_err(|e| match e.downcast::<StudyError>() {
            Ok(se) => se,
            Err(e) => StudyError::Optimise(e.to_string()),
        })?;
    let problem = result
        .problem
        .problem
        .as_ref()
        .expect("problem is returned");
    let state = result.state();
    let best_u = state.get_best_param().cloned().unwrap_or(u0);
    let mut best = problem.design(&best_u);
    let (mut best_objective, mut best_metrics) = problem.objective(&best)?;
    // The base design is a candidate too: never report a design worse than the base.
    if sign * best_objective > sign * base_objective {
        best = Design::default();
        best_objective = base_objective;
        best_metrics = base_metrics.clone();
    }
    let path = path
        .lock()
        .expect("path lock")
        .iter()
        .enumerate()
        // Row 0 is the initial simplex, row k the state after iteration k.
        .map(|(k, (_, cost, u))| PathPoint {
            iteration: k as u64,
            objective: sign * cost,
            design: problem.design(u),
        })
        .collect();
    Ok(Some(OptimiseResult {
        base_objective,
        best_objective,
        best,
        base_metrics,
        best_metrics,
        path,
        evaluations: problem.evaluations.load(Ordering::Relaxed),
        termination: state.get_termination_status().to_string(),
    }))
}
