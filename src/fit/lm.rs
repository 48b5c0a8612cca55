//! A bounded Levenberg–Marquardt solver implementing argmin's [`Solver`] trait.
//!
//! Minimises `χ²(θ) = ‖r(θ)‖²` for an [`Operator`] (residuals `r`) with a [`Jacobian`] `J`.
//! Each iteration solves the damped normal equations with Marquardt's diagonal scaling,
//!
//! ```text
//! (JᵀJ + λ·diag(JᵀJ)) δ = −Jᵀr,
//! ```
//!
//! projects the trial point onto the box `[lower, upper]` (the physical bounds of the effect
//! library), and accepts it when `χ²` falls. A parameter on a bound whose descent direction
//! `−(Jᵀr)_j` points out of the box is *held* for the iteration: its row and column of the
//! system are replaced by the identity's and its gradient by 0, so the step is the free
//! parameters' own (with nothing held the system is exactly the one above). Without this, a
//! fit whose optimum lies on a bound (`cor_radial`, `contact_time` or the gear restitution at
//! 0) computes each step as if the held parameter could move, then projects it back: the free
//! parameters' steps are wrong by the coupling and the fit crawls, often for all its iterations. The gain ratio
//! `ρ = (χ²(θ) − χ²(θ+δ)) / (χ²(θ) − ‖r + Jδ‖²)` updates `λ` as in Nielsen (1999):
//! accepted → `λ·max(1/3, 1 − (2ρ − 1)³)`, rejected → `λ·ν`, `ν ← 2ν`.
//!
//! It stops, converged, when the gradient is orthogonal to the residual to within `gtol`
//! (`max_j |J_jᵀ r| / (‖J_j‖‖r‖) ≤ gtol` over the parameters not held: the bounded problem's
//! first-order condition), when an accepted step changes `χ²` by less than
//! `ftol` relative (actual and predicted), when a step is below `xtol` of each parameter's
//! range, or when no step along the damped direction lowers `χ²` (`λ` past 10¹⁶: a minimum to
//! numerical precision). Running out of iterations is *not* convergence.

use argmin::core::{
    Error as ArgminError, IterState, Jacobian, Operator, Problem, Solver, State, TerminationReason,
    TerminationStatus, KV,
};
use nalgebra::{DMatrix, DVector};

/// The argmin state this solver works with: parameters, Jacobian and residuals as nalgebra
/// vectors and matrices.
pub type LmState = IterState<DVector<f64>, (), DMatrix<f64>, (), DVector<f64>, f64>;

/// Why the solver stopped, when it converged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Converged {
    /// Gradient orthogonal to the residuals.
    Gradient,
    /// Relative change of χ² below `ftol`.
    CostChange,
    /// Step below `xtol` of every parameter's range.
    Step,
    /// No step with the kept starting Jacobian lowers χ² any more
    /// ([`LevenbergMarquardt::with_kept_start_jacobian`]).
    KeptJacobian,
    /// No step lowers χ² any more (a minimum to numerical precision).
    NoDescent,
}

impl Converged {
    /// Human explanation.
    pub fn text(self) -> &'static str {
        match self {
            Self::Gradient => "converged: gradient orthogonal to the residuals (gtol)",
            Self::CostChange => "converged: relative change of chi2 below ftol",
            Self::Step => "converged: step below xtol of every parameter's range",
            Self::KeptJacobian => {
                "converged: no step with the kept starting Jacobian lowers chi2 further"
            }
            Self::NoDescent => "converged: no step lowers chi2 further (minimum to precision)",
        }
    }
}

/// Bounded Levenberg–Marquardt (see the module docs).
#[derive(Debug, Clone)]
pub struct LevenbergMarquardt {
    lower: DVector<f64>,
    upper: DVector<f64>,
    tau: f64,
    ftol: f64,
    xtol: f64,
    gtol: f64,
    lambda: f64,
    nu: f64,
    converged: Option<Converged>,
    /// Compute the Jacobian at the point where it stops on [`Converged::CostChange`] (the
    /// covariance of the estimates needs it; a fit that only wants the point does not).
    final_jacobian: bool,
    /// Residuals and Jacobian at the starting point, when the caller already has them
    /// ([`LevenbergMarquardt::with_start_evaluation`]); taken by the first `init`.
    at_start: Option<(DVector<f64>, DMatrix<f64>)>,
    /// Steps left that keep the starting Jacobian ([`LevenbergMarquardt::with_kept_start_jacobian`]);
    /// 0: every accepted point gets its own.
    keep_start_jacobian: u32,
    /// The point has moved since the kept Jacobian was evaluated (it is no longer the point's
    /// own).
    kept_moved: bool,
    /// The kept Jacobian's steps end at the point's own Jacobian, never a stop
    /// ([`LevenbergMarquardt::to_own_minimum`]).
    own_minimum: bool,
    /// `JᵀJ` of the Jacobian the state holds, while that Jacobian is carried to the next
    /// iteration unchanged (a rejected step, a kept Jacobian): made once, not every iteration.
    gram: Option<DMatrix<f64>>,
    /// A kept Jacobian that has to be given up is replaced by the point's own, which is then
    /// kept in its turn for up to [`KEPT_JACOBIAN_STEPS`] accepted steps (the chord method
    /// with refreshed Jacobians), instead of going on as plain Levenberg–Marquardt
    /// ([`LevenbergMarquardt::with_kept_start_jacobian`] without
    /// [`LevenbergMarquardt::to_own_minimum`]).
    refresh: bool,
    /// Kept Jacobians of [`LevenbergMarquardt::to_own_minimum`] fits get Broyden's update
    /// after each accepted step ([`LevenbergMarquardt::secant_update`]).
    secant: bool,
}

/// A step with a kept Jacobian ([`LevenbergMarquardt::with_kept_start_jacobian`]) that is
/// rejected although it predicted a fall of `χ²` below this (relative) ends the fit: the point
/// is the kept Jacobian's solution, where the predicted fall is its error `(J − J₀)ᵀr` and not
/// a step still to take. A rejected step that predicted more takes the point's own Jacobian.
const KEPT_JACOBIAN_STOP: f64 = 1e-6;

/// Most accepted steps a fit takes with its starting Jacobian
/// ([`LevenbergMarquardt::with_kept_start_jacobian`]) before it computes its own again: near
/// the solution the chord steps shrink by a constant factor each, so more would mean the
/// starting point was not close enough for them to pay.
const KEPT_JACOBIAN_STEPS: u32 = 8;

impl LevenbergMarquardt {
    /// A solver for parameters within `[lower, upper]` (finite, `lower < upper`).
    pub fn new(lower: DVector<f64>, upper: DVector<f64>) -> Result<Self, ArgminError> {
        if lower.len() != upper.len()
            || lower
                .iter()
                .zip(upper.iter())
                .any(|(l, u)| !(l.is_finite() && u.is_finite() && l < u))
        {
            return Err(ArgminError::msg(
                "Levenberg-Marquardt: bounds must be finite with lower < upper",
            ));
        }
        Ok(Self {
            lower,
            upper,
            tau: 1e-3,
            ftol: 1e-10,
            xtol: 1e-10,
            gtol: 1e-10,
            lambda: 0.0,
            nu: 2.0,
            converged: None,
            final_jacobian: true,
            at_start: None,
            keep_start_jacobian: 0,
            kept_moved: false,
            own_minimum: false,
            gram: None,
            refresh: false,
            secant: true,
        })
    }

    /// Set the relative χ² change at which it stops (default 1e-10).
    pub fn with_ftol(mut self, ftol: f64) -> Result<Self, ArgminError> {
        if !(ftol > 0.0) {
            return Err(ArgminError::msg("Levenberg-Marquardt: ftol must be > 0"));
        }
        self.ftol = ftol;
        Ok(self)
    }

    /// Skip the Jacobian at the last accepted point when the fit stops there on a small change
    /// of `χ²` ([`Converged::CostChange`]): the state then keeps the Jacobian of the point before
    /// it. The point, `χ²`, the residuals and the iterations are the same as with it; use it
    /// when only the solution is wanted (cross-validation folds), which saves one Jacobian a fit.
    pub fn without_final_jacobian(mut self) -> Self {
        self.final_jacobian = false;
        self
    }

    /// Start from residuals `r` and Jacobian `j` already computed at the starting point (which
    /// must lie inside the bounds) instead of evaluating them there. Every later step is the
    /// same, so the fit gives the same bits as without, one residual and one Jacobian
    /// evaluation cheaper: a cross-validation fold started from the all-shots solution takes
    /// its rows of the all-shots fit's residuals and Jacobian (each shot's rows are computed
    /// independently of the others).
    pub fn with_start_evaluation(mut self, r: DVector<f64>, j: DMatrix<f64>) -> Self {
        self.at_start = Some((r, j));
        self
    }

    /// With a start evaluation given ([`LevenbergMarquardt::with_start_evaluation`]), keep its
    /// Jacobian `J₀` for the steps instead of computing one at every accepted point (the chord,
    /// or simplified Gauss–Newton, method), for at most [`KEPT_JACOBIAN_STEPS`] accepted steps.
    /// The first step is the plain one (`J₀` is the start's own). Once the point has moved, a
    /// rejected step that predicted a fall of `χ²` below [`KEPT_JACOBIAN_STOP`] (relative) ends
    /// the fit ([`Converged::KeptJacobian`]); a rejected step that predicted more, or running
    /// out of kept steps, computes the Jacobian at the point and keeps that one in its turn
    /// (the chord method with refreshed Jacobians, Shamanskii's method), for at most
    /// [`KEPT_JACOBIAN_STEPS`] accepted steps again. Going on as plain Levenberg–Marquardt
    /// instead, a Jacobian at every accepted point, cost a 2,200-shot real-format season's
    /// diagnose about 2,500 Jacobians in its cross-validation folds alone, where the fold starts
    /// far from its solution along a weakly determined direction; refreshed, most such folds
    /// take one.
    ///
    /// For a fit started close to its solution whose point alone is wanted (a cross-validation
    /// fold started from the all-shots solution), this saves the `2p` shifted model evaluations
    /// of every step after the first. The kept steps head for where the residuals are
    /// orthogonal to `J₀`'s columns, which is off the fit's own minimum by
    /// `(JᵀJ)⁻¹ (J − J₀)ᵀ r`: first order in the distance from the start, so `χ²` there exceeds
    /// the minimum by a second-order amount. It is not the same point as without, only as good
    /// to that order.
    pub fn with_kept_start_jacobian(mut self) -> Self {
        self.keep_start_jacobian = KEPT_JACOBIAN_STEPS;
        self.refresh = true;
        self
    }

    /// With a kept starting Jacobian ([`LevenbergMarquardt::with_kept_start_jacobian`]): its
    /// steps end, never the fit. When a kept step is rejected, or accepted with a change of `χ²`
    /// below `ftol` (the chord's own convergence, off the fit's minimum by a second-order
    /// amount), the point's Jacobian is taken and kept in its turn (refreshed chord steps, as
    /// above); the fit stops only by a test passed on the point's own Jacobian, at its own
    /// minimum to the tolerances. Between refreshes each accepted step corrects the kept
    /// Jacobian by Broyden's rank-one (secant) update, so that it maps the step to the change
    /// of the residuals the model gave; the chord steps then follow the fit's own curvature
    /// instead of heading for the kept Jacobian's solution, and fewer refreshes are needed (on
    /// a 2,244-shot shaft-fitting season, 4.9 → 3.9 Jacobians a candidate fit). For a fit
    /// whose solution and covariance are wanted, started from an evaluation mostly made already
    /// (a diagnose candidate started from the step base's residuals and Jacobian): the chord
    /// steps replace the Jacobians of every step but the last, and with
    /// [`LevenbergMarquardt::without_final_jacobian`] the fit typically evaluates one Jacobian
    /// in all.
    pub fn to_own_minimum(mut self) -> Self {
        self.own_minimum = true;
        self
    }

    /// [`LevenbergMarquardt::to_own_minimum`] without the secant update of the kept Jacobian
    /// (the comparison its test makes).
    #[cfg(test)]
    pub(crate) fn without_secant(mut self) -> Self {
        self.secant = false;
        self
    }

    /// Why it stopped, when it converged (`None` when it ran out of iterations).
    pub fn converged(&self) -> Option<Converged> {
        self.converged
    }

    fn project(&self, x: &mut DVector<f64>) {
        for ((v, l), u) in x.iter_mut().zip(self.lower.iter()).zip(self.upper.iter()) {
            *v = v.clamp(*l, *u);
        }
    }

    /// Which parameters the gradient `g = Jᵀr` holds at a bound (descent `−g` points out of
    /// the box: they do not move this iteration and their gradient is not a reason to go on),
    /// and the largest cosine between a free parameter's column and the residuals (`a = JᵀJ`).
    fn held_and_cosine(
        &self,
        theta: &DVector<f64>,
        a: &DMatrix<f64>,
        g: &DVector<f64>,
        cost: f64,
    ) -> (Vec<bool>, f64) {
        let n = theta.len();
        let held: Vec<bool> = (0..n)
            .map(|k| {
                (theta[k] <= self.lower[k] && g[k] > 0.0)
                    || (theta[k] >= self.upper[k] && g[k] < 0.0)
            })
            .collect();
        let r_norm = cost.sqrt();
        let cosine = (0..n)
            .filter(|&k| !held[k])
            .map(|k| {
                let cn = a[(k, k)].sqrt();
                if cn > 0.0 && r_norm > 0.0 {
                    g[k].abs() / (cn * r_norm)
                } else {
                    0.0
                }
            })
            .fold(0.0, f64::max);
        (held, cosine)
    }

    /// The damped normal matrix `JᵀJ + λ·diag(JᵀJ)` with the `held` parameters' rows and
    /// columns made the identity's and their gradient entries in `g` zeroed.
    fn damped_system(&self, a: &DMatrix<f64>, g: &mut DVector<f64>, held: &[bool]) -> DMatrix<f64> {
        let n = a.nrows();
        // Marquardt scaling; a column with no sensitivity gets a unit scale so the step
        // along it stays zero instead of the system becoming singular.
        let diag_max = (0..n).map(|k| a[(k, k)]).fold(0.0, f64::max);
        let scale: Vec<f64> = (0..n)
            .map(|k| a[(k, k)].max(1e-12 * diag_max).max(f64::MIN_POSITIVE))
            .collect();
        let mut damped = a.clone();
        for (k, s) in scale.iter().enumerate() {
            damped[(k, k)] += self.lambda * s;
        }
        // A held parameter's row and column become the identity's, its gradient 0: the step
        // solves for the free parameters alone (with none held, the system is untouched).
        for k in (0..n).filter(|&k| held[k]) {
            damped.row_mut(k).fill(0.0);
            damped.column_mut(k).fill(0.0);
            damped[(k, k)] = 1.0;
            g[k] = 0.0;
        }
        damped
    }

    /// The Jacobian at `theta`, the point's own, ending the kept Jacobian's steps: the fit
    /// goes on as plain Levenberg–Marquardt, or, refreshed, keeps this one in its turn.
    fn own_jacobian<O>(
        &mut self,
        problem: &mut Problem<O>,
        theta: &DVector<f64>,
    ) -> Result<DMatrix<f64>, ArgminError>
    where
        O: Jacobian<Param = DVector<f64>, Jacobian = DMatrix<f64>>,
    {
        self.keep_start_jacobian = if self.refresh { KEPT_JACOBIAN_STEPS } else { 0 };
        self.kept_moved = false;
        self.gram = None;
        problem.jacobian(theta)
    }

    /// The Jacobian an accepted step's point `trial` goes on with: the point's own (`None`: the
    /// state's, kept). `chord_done`: the kept Jacobian's steps converged; `small`: the step
    /// changed `χ²` by less than `ftol`; `keep`: kept steps are left.
    fn accepted_jacobian<O>(
        &mut self,
        problem: &mut Problem<O>,
        trial: &DVector<f64>,
        chord_done: bool,
        small: bool,
        keep: bool,
    ) -> Result<Option<DMatrix<f64>>, ArgminError>
    where
        O: Jacobian<Param = DVector<f64>, Jacobian = DMatrix<f64>>,
    {
        if chord_done {
            return Ok(Some(self.own_jacobian(problem, trial)?));
        }
        if (small && !self.final_jacobian) || keep {
            self.keep_start_jacobian = self.keep_start_jacobian.saturating_sub(1);
            self.kept_moved = keep;
            return Ok(None);
        }
        // The point's own: the kept Jacobian (if any) is given up, or, refreshed, kept in its
        // turn.
        self.kept_moved = false;
        if self.refresh {
            self.keep_start_jacobian = KEPT_JACOBIAN_STEPS;
        }
        Ok(Some(problem.jacobian(trial)?))
    }

    /// Broyden's rank-one update of a kept Jacobian `j` after the step `s` changed the
    /// residuals by `y`: `J + (y − J s) (W s)ᵀ / (sᵀ W s)`, with `W` the inverse squares of the
    /// parameters' ranges, so that the updated Jacobian satisfies the secant equation
    /// `J s = y` and changes least, in that metric, in the directions the step did not probe
    /// (Broyden 1965, "A class of methods for solving nonlinear simultaneous equations", Math.
    /// Comp. 19; the scaled form of Dennis & Schnabel 1983, *Numerical Methods for
    /// Unconstrained Optimization and Nonlinear Equations*, §8.1). A held parameter's step is
    /// 0, so its column is left as it was.
    pub(crate) fn secant_update(
        &self,
        mut j: DMatrix<f64>,
        s: &DVector<f64>,
        y: &DVector<f64>,
    ) -> DMatrix<f64> {
        let ws = DVector::from_iterator(
            s.len(),
            s.iter()
                .zip(self.lower.iter().zip(self.upper.iter()))
                .map(|(v, (l, u))| v / ((u - l) * (u - l))),
        );
        let denom = s.dot(&ws);
        if !(denom > 0.0 && denom.is_finite()) {
            return j;
        }
        let miss = y - &j * s;
        j.ger(1.0 / denom, &miss, &ws, 1.0);
        j
    }

    /// The largest `|step_j|` relative to its parameter's range.
    fn step_of_range(&self, step: &DVector<f64>) -> f64 {
        step.iter()
            .zip(self.lower.iter().zip(self.upper.iter()))
            .map(|(s, (l, u))| s.abs() / (u - l))
            .fold(0.0, f64::max)
    }

    fn stop(&mut self, state: LmState, why: Converged) -> LmState {
        self.converged = Some(why);
        state.terminate_with(TerminationReason::SolverExit(why.text().to_owned()))
    }
}

fn norm2(r: &DVector<f64>) -> f64 {
    r.norm_squared()
}

impl<O> Solver<O, LmState> for LevenbergMarquardt
where
    O: Operator<Param = DVector<f64>, Output = DVector<f64>>
        + Jacobian<Param = DVector<f64>, Jacobian = DMatrix<f64>>,
{
    fn name(&self) -> &str {
        "Levenberg-Marquardt (bounded)"
    }

    fn init(
        &mut self,
        problem: &mut Problem<O>,
        mut state: LmState,
    ) -> Result<(LmState, Option<KV>), ArgminError> {
        let mut theta = state
            .take_param()
            .ok_or_else(|| ArgminError::msg("Levenberg-Marquardt needs a starting point"))?;
        if theta.len() != self.lower.len() {
            return Err(ArgminError::msg(format!(
                "Levenberg-Marquardt: {} parameters but {} bounds",
                theta.len(),
                self.lower.len()
            )));
        }
        self.project(&mut theta);
        let (r, j) = match self.at_start.take() {
            Some(rj) => rj,
            None => {
                // Nothing given to keep: a Jacobian at every accepted point.
                self.keep_start_jacobian = 0;
                self.refresh = false;
                (problem.apply(&theta)?, problem.jacobian(&theta)?)
            }
        };
        // With Marquardt's diagonal scaling the damping is dimensionless.
        self.lambda = self.tau;
        self.nu = 2.0;
        self.converged = None;
        self.kept_moved = false;
        self.gram = None;
        let cost = norm2(&r);
        Ok((state.param(theta).residuals(r).jacobian(j).cost(cost), None))
    }

    fn next_iter(
        &mut self,
        problem: &mut Problem<O>,
        mut state: LmState,
    ) -> Result<(LmState, Option<KV>), ArgminError> {
        let theta = state.take_param().expect("set in init");
        let r = state.take_residuals().expect("set in init");
        let j = state.take_jacobian().expect("set in init");
        let cost = state.get_cost();

        let a = self.gram.take().unwrap_or_else(|| gram(&j));
        let mut g = j.tr_mul(&r);
        let (held, cosine) = self.held_and_cosine(&theta, &a, &g, cost);
        let keep = |state: LmState, theta, r, j, cost| {
            state.param(theta).residuals(r).jacobian(j).cost(cost)
        };
        // A test passed on the kept Jacobian ([`LevenbergMarquardt::to_own_minimum`]) is the
        // chord's convergence, not the fit's: the point's own Jacobian is taken instead.
        let chord_only = self.own_minimum && self.kept_moved;
        if chord_only && (cosine <= self.gtol || cost == 0.0) {
            let j_here = self.own_jacobian(problem, &theta)?;
            return Ok((keep(state, theta, r, j_here, cost), None));
        }
        if cosine <= self.gtol || cost == 0.0 {
            let state = keep(state, theta, r, j, cost);
            return Ok((self.stop(state, Converged::Gradient), None));
        }

        let damped = self.damped_system(&a, &mut g, &held);
        let step_ok = damped.cholesky().map(|ch| ch.solve(&(-&g)));
        let mut accepted = false;
        // The step's predicted fall of χ² is below [`KEPT_JACOBIAN_STOP`] (relative).
        let mut small_prediction = false;
        let mut new_state = None;
        if let Some(delta) = step_ok {
            let mut trial = &theta + &delta;
            self.project(&mut trial);
            let step = &trial - &theta;
            let step_rel = self.step_of_range(&step);
            if step_rel <= self.xtol && chord_only {
                let j_here = self.own_jacobian(problem, &theta)?;
                return Ok((keep(state, theta, r, j_here, cost), None));
            }
            if step_rel <= self.xtol {
                let state = keep(state, theta, r, j, cost);
                return Ok((self.stop(state, Converged::Step), None));
            }
            let predicted_r = &r + &j * &step;
            let predicted = cost - norm2(&predicted_r);
            small_prediction = predicted <= KEPT_JACOBIAN_STOP * cost;
            // A trial point where the model cannot be evaluated is a rejected step.
            if let Ok(r_trial) = problem.apply(&trial) {
                let cost_trial = norm2(&r_trial);
                let actual = cost - cost_trial;
                if cost_trial.is_finite() && actual > 0.0 && predicted > 0.0 {
                    let rho = actual / predicted;
                    let small = actual <= self.ftol * cost && predicted <= self.ftol * cost;
                    let keep = self.keep_start_jacobian > 0;
                    // A small step with a kept Jacobian that is no longer the point's: the
                    // chord converged, and the fit goes on from its point's own Jacobian.
                    let chord_done = small && chord_only;
                    let j_trial =
                        self.accepted_jacobian(problem, &trial, chord_done, small, keep)?;
                    self.lambda *= (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0);
                    self.nu = 2.0;
                    accepted = true;
                    new_state = Some((trial, r_trial, j_trial, cost_trial, small && !chord_done));
                }
            }
        }
        let kv = argmin::kv!("lambda" => self.lambda; "accepted" => accepted;);
        match new_state {
            Some((trial, r_trial, j_trial, cost_trial, small)) => {
                let j_trial = match j_trial {
                    Some(own) => own,
                    // A kept Jacobian on its way to the fit's own minimum: corrected along
                    // the step just taken (its `JᵀJ` is then made anew).
                    None if self.own_minimum && self.secant => {
                        self.secant_update(j, &(&trial - &theta), &(&r_trial - &r))
                    }
                    // Kept as it is, with its `JᵀJ`.
                    None => {
                        self.gram = Some(a);
                        j
                    }
                };
                let state = keep(state, trial, r_trial, j_trial, cost_trial);
                if small {
                    Ok((self.stop(state, Converged::CostChange), Some(kv)))
                } else {
                    Ok((state, Some(kv)))
                }
            }
            None if self.kept_moved && small_prediction && !self.own_minimum => {
                self.gram = Some(a);
                // At the kept Jacobian's solution, within a second-order amount of the fit's
                // own minimum: its steps no longer lower χ².
                let state = keep(state, theta, r, j, cost);
                Ok((self.stop(state, Converged::KeptJacobian), Some(kv)))
            }
            None if self.kept_moved => {
                // The kept Jacobian may be what failed: take the point's own and go on as
                // plain Levenberg–Marquardt from the same damping.
                let j_here = self.own_jacobian(problem, &theta)?;
                Ok((keep(state, theta, r, j_here, cost), Some(kv)))
            }
            None => {
                self.lambda *= self.nu;
                self.nu *= 2.0;
                self.gram = Some(a);
                let state = keep(state, theta, r, j, cost);
                if self.lambda > 1e16 {
                    Ok((self.stop(state, Converged::NoDescent), Some(kv)))
                } else {
                    Ok((state, Some(kv)))
                }
            }
        }
    }

    fn terminate(&mut self, _state: &LmState) -> TerminationStatus {
        TerminationStatus::NotTerminated
    }
}

mod gram;
#[cfg(test)]
mod tests;

pub(crate) use gram::gram;
