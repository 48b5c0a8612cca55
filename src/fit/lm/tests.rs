//! Tests of the bounded Levenberg–Marquardt solver on small problems with known solutions.

use super::*;
use approx::assert_relative_eq;
use argmin::core::Executor;

/// `y = a·exp(−b·t)` sampled without noise: a nonlinear least-squares test problem.
#[derive(Clone)]
struct Decay {
    t: Vec<f64>,
    y: Vec<f64>,
}

impl Operator for Decay {
    type Param = DVector<f64>;
    type Output = DVector<f64>;
    fn apply(&self, p: &DVector<f64>) -> Result<DVector<f64>, ArgminError> {
        Ok(DVector::from_iterator(
            self.t.len(),
            self.t
                .iter()
                .zip(&self.y)
                .map(|(t, y)| p[0] * (-p[1] * t).exp() - y),
        ))
    }
}

impl Jacobian for Decay {
    type Param = DVector<f64>;
    type Jacobian = DMatrix<f64>;
    fn jacobian(&self, p: &DVector<f64>) -> Result<DMatrix<f64>, ArgminError> {
        Ok(DMatrix::from_fn(self.t.len(), 2, |i, k| {
            let e = (-p[1] * self.t[i]).exp();
            if k == 0 {
                e
            } else {
                -p[0] * self.t[i] * e
            }
        }))
    }
}

fn decay() -> Decay {
    let t: Vec<f64> = (0..20).map(|i| i as f64 * 0.25).collect();
    let y = t.iter().map(|t| 3.0 * (-0.7 * t).exp()).collect();
    Decay { t, y }
}

/// [`decay`] with measurements off the curve (χ² has a positive minimum).
fn noisy_decay() -> Decay {
    let mut d = decay();
    for (i, y) in d.y.iter_mut().enumerate() {
        *y += 0.01 * (5.0 * i as f64).cos();
    }
    d
}

/// A solver for [`Decay`]'s parameters within `a ∈ [−10, 10]`, `b ∈ [0, 5]`.
fn bounded() -> LevenbergMarquardt {
    LevenbergMarquardt::new(
        DVector::from_vec(vec![-10.0, 0.0]),
        DVector::from_vec(vec![10.0, 5.0]),
    )
    .unwrap()
}

/// `solver` started with the evaluation of `inner` at `start` given to it.
fn given_start(
    solver: LevenbergMarquardt,
    inner: &Decay,
    start: &DVector<f64>,
) -> LevenbergMarquardt {
    solver.with_start_evaluation(inner.apply(start).unwrap(), inner.jacobian(start).unwrap())
}

/// What a run of [`run_counted`] ended with.
struct Outcome {
    p: DVector<f64>,
    cost: f64,
    iters: u64,
    jacobians: u32,
    why: Option<Converged>,
}

/// `solver` run on `inner` from `start` (at most 100 iterations), counting its Jacobians.
fn run_counted(inner: Decay, solver: LevenbergMarquardt, start: &DVector<f64>) -> Outcome {
    let problem = Counted {
        inner,
        jacobians: std::cell::Cell::new(0),
    };
    let res = Executor::new(problem, solver)
        .configure(|s| s.param(start.clone()).max_iters(100))
        .run()
        .unwrap();
    Outcome {
        p: res.state().get_best_param().unwrap().clone(),
        cost: res.state().get_cost(),
        iters: res.state().get_iter(),
        jacobians: res.problem.problem.as_ref().unwrap().jacobians.get(),
        why: res.solver().converged(),
    }
}

#[test]
fn solves_a_nonlinear_problem_through_the_executor() {
    let solver = LevenbergMarquardt::new(
        DVector::from_vec(vec![-10.0, 0.0]),
        DVector::from_vec(vec![10.0, 5.0]),
    )
    .unwrap();
    let res = Executor::new(decay(), solver)
        .configure(|s| s.param(DVector::from_vec(vec![1.0, 2.0])).max_iters(100))
        .run()
        .unwrap();
    let p = res.state().get_best_param().unwrap();
    assert_relative_eq!(p[0], 3.0, epsilon = 1e-7);
    assert_relative_eq!(p[1], 0.7, epsilon = 1e-7);
    assert!(res.solver().converged().is_some());
}

/// Counts Jacobian evaluations of [`Decay`].
struct Counted {
    inner: Decay,
    jacobians: std::cell::Cell<u32>,
}

impl Operator for Counted {
    type Param = DVector<f64>;
    type Output = DVector<f64>;
    fn apply(&self, p: &DVector<f64>) -> Result<DVector<f64>, ArgminError> {
        self.inner.apply(p)
    }
}

impl Jacobian for Counted {
    type Param = DVector<f64>;
    type Jacobian = DMatrix<f64>;
    fn jacobian(&self, p: &DVector<f64>) -> Result<DMatrix<f64>, ArgminError> {
        self.jacobians.set(self.jacobians.get() + 1);
        self.inner.jacobian(p)
    }
}

#[test]
fn skipping_the_final_jacobian_keeps_the_solution_and_saves_one() {
    let run = |skip: bool| {
        let mut solver = bounded().with_ftol(1e-6).unwrap();
        if skip {
            solver = solver.without_final_jacobian();
        }
        // Measurements off the curve, so that χ² stops falling at a positive minimum.
        let mut inner = decay();
        for (i, y) in inner.y.iter_mut().enumerate() {
            *y += 0.01 * (7.0 * i as f64).sin();
        }
        let o = run_counted(inner, solver, &DVector::from_vec(vec![1.0, 2.0]));
        (o.p, o.why, o.iters, o.jacobians)
    };
    let (p_full, why_full, it_full, j_full) = run(false);
    let (p_skip, why_skip, it_skip, j_skip) = run(true);
    assert_eq!(why_full, Some(Converged::CostChange));
    assert_eq!(why_skip, why_full);
    assert_eq!(it_skip, it_full);
    assert_eq!(p_skip, p_full);
    assert_eq!(j_skip + 1, j_full);
}

#[test]
fn a_start_evaluation_given_gives_the_same_fit_one_evaluation_cheaper() {
    let start = DVector::from_vec(vec![1.0, 2.0]);
    let run = |given: bool| {
        let inner = noisy_decay();
        let solver = if given {
            given_start(bounded(), &inner, &start)
        } else {
            bounded()
        };
        let o = run_counted(inner, solver, &start);
        ((o.p, o.cost, o.iters), o.jacobians)
    };
    let (plain, j_plain) = run(false);
    let (given, j_given) = run(true);
    assert_eq!(given, plain);
    assert_eq!(j_given + 1, j_plain);
}

/// Keeping the start's Jacobian (chord steps) from a start near the solution, as a
/// cross-validation fold starts: no Jacobian is computed and the fit ends far closer to the
/// solution than it started (second order: the excess χ² falls by more than 10⁴); from a
/// start far away the kept Jacobian fails, the fit computes its own, keeps that one in its
/// turn (refreshed chord steps) and ends where the plain fit does to second order, with fewer
/// Jacobians than the plain fit takes from there.
#[test]
fn a_kept_start_jacobian_reaches_the_solution_from_near_and_far() {
    let inner = noisy_decay();
    let run = |start: &DVector<f64>, kept: bool| {
        let solver = if kept {
            given_start(bounded(), &inner, start).with_kept_start_jacobian()
        } else {
            bounded()
        };
        let o = run_counted(inner.clone(), solver, start);
        assert!(o.why.is_some());
        (o.p, o.cost, o.jacobians)
    };
    let far = DVector::from_vec(vec![1.0, 2.0]);
    let (p_full, cost_full, j_full) = run(&far, false);
    let near = &p_full + DVector::from_vec(vec![0.02, -0.01]);
    let cost_near = inner.apply(&near).unwrap().norm_squared();
    let (p_kept, cost_kept, jacobians) = run(&near, true);
    assert_eq!(jacobians, 0);
    assert!(cost_kept >= cost_full * (1.0 - 1e-12));
    assert!(
        cost_kept - cost_full <= 1e-4 * (cost_near - cost_full),
        "{cost_kept} {cost_full} {cost_near}"
    );
    assert_relative_eq!(p_kept, p_full, max_relative = 1e-4);
    let (p_far, cost_far, jacobians) = run(&far, true);
    assert!(jacobians > 0);
    assert!(jacobians < j_full, "{jacobians} Jacobians, plain {j_full}");
    assert_relative_eq!(p_far, p_full, max_relative = 1e-6);
    assert!(cost_far >= cost_full * (1.0 - 1e-12));
    assert_relative_eq!(cost_far, cost_full, max_relative = 1e-9);
}

/// The kept Jacobian's chord steps taken to the fit's own minimum
/// ([`LevenbergMarquardt::to_own_minimum`], without the final Jacobian, as diagnose's effect
/// candidates fit): from a near start it ends at the plain fit's minimum to the solver's
/// tolerances (not the chord's point, which the same start without it stops at) with one
/// Jacobian where the plain fit takes one a step; from a far start too.
#[test]
fn chord_steps_taken_to_the_own_minimum_end_where_the_plain_fit_does() {
    let inner = noisy_decay();
    let run = |start: &DVector<f64>, own: bool| {
        let mut solver = given_start(bounded().without_final_jacobian(), &inner, start);
        if own {
            solver = solver.with_kept_start_jacobian().to_own_minimum();
        }
        run_counted(inner.clone(), solver, start)
    };
    let far = DVector::from_vec(vec![1.0, 2.0]);
    let plain = run(&far, false);
    let near = &plain.p + DVector::from_vec(vec![0.02, -0.01]);
    let near_plain = run(&near, false);
    let own = run(&near, true);
    assert!(
        own.why.is_some() && own.why != Some(Converged::KeptJacobian),
        "{:?}",
        own.why
    );
    assert!(
        own.jacobians < near_plain.jacobians,
        "{} Jacobians, plain {}",
        own.jacobians,
        near_plain.jacobians
    );
    assert!(
        own.jacobians >= 1,
        "the chord's point is not taken for the minimum"
    );
    assert_relative_eq!(own.p, near_plain.p, max_relative = 1e-7);
    assert_relative_eq!(own.cost, plain.cost, max_relative = 1e-9);
    // The chord alone stops off the minimum, measurably farther than the own-minimum fit.
    let chord = run_counted(
        inner.clone(),
        given_start(bounded(), &inner, &near).with_kept_start_jacobian(),
        &near,
    );
    assert!((&chord.p - &plain.p).norm() > 10.0 * (&own.p - &plain.p).norm());
    let far_own = run(&far, true);
    assert!(far_own.why.is_some());
    assert_relative_eq!(far_own.p, plain.p, max_relative = 1e-7);
    assert_relative_eq!(far_own.cost, plain.cost, max_relative = 1e-9);
}

/// Broyden's update ([`LevenbergMarquardt::secant_update`]) makes the kept Jacobian map the
/// step to the change of the residuals (the secant equation), leaves a direction orthogonal to
/// the step in the ranges' metric as it was, and leaves a held (unmoved) parameter's column.
#[test]
fn the_secant_update_satisfies_the_secant_equation() {
    let solver = bounded();
    let (lo, hi): (DVector<f64>, DVector<f64>) = (
        DVector::from_vec(vec![-10.0, 0.0]),
        DVector::from_vec(vec![10.0, 5.0]),
    );
    let j = DMatrix::from_row_slice(3, 2, &[1.0, 2.0, -0.5, 0.25, 3.0, -1.0]);
    let s = DVector::from_vec(vec![0.3, -0.1]);
    let y = DVector::from_vec(vec![0.7, -0.2, 0.05]);
    let updated = solver.secant_update(j.clone(), &s, &y);
    assert_relative_eq!(&updated * &s, y, max_relative = 1e-12);
    // Orthogonal to s in the metric W = diag(1/range²): W s · t = 0.
    let w: Vec<f64> = (0..2).map(|k| 1.0 / (hi[k] - lo[k]).powi(2)).collect();
    let t = DVector::from_vec(vec![s[1] * w[1], -s[0] * w[0]]);
    assert_relative_eq!(&updated * &t, &j * &t, max_relative = 1e-12);
    let held = DVector::from_vec(vec![0.3, 0.0]);
    let updated = solver.secant_update(j.clone(), &held, &y);
    assert_eq!(updated.column(1), j.column(1));
    // A zero step changes nothing.
    assert_eq!(solver.secant_update(j.clone(), &DVector::zeros(2), &y), j);
}

/// The secant update of the kept Jacobian in a fit taken to its own minimum: the same minimum
/// to the solver's tolerances, from near and far starts, with no more Jacobians than the
/// refreshed chord without it, and fewer from the far start.
#[test]
fn secant_updates_reach_the_same_minimum_with_fewer_jacobians() {
    let inner = noisy_decay();
    let run = |start: &DVector<f64>, secant: bool| {
        let mut solver = given_start(bounded().without_final_jacobian(), &inner, start)
            .with_kept_start_jacobian()
            .to_own_minimum();
        if !secant {
            solver = solver.without_secant();
        }
        run_counted(inner.clone(), solver, start)
    };
    let far = DVector::from_vec(vec![1.0, 2.0]);
    let plain = run_counted(inner.clone(), bounded(), &far);
    for start in [far.clone(), &plain.p + DVector::from_vec(vec![0.02, -0.01])] {
        let with = run(&start, true);
        let without = run(&start, false);
        assert!(with.why.is_some() && with.why != Some(Converged::KeptJacobian));
        assert_relative_eq!(with.p, plain.p, max_relative = 1e-7);
        assert_relative_eq!(with.cost, plain.cost, max_relative = 1e-9);
        assert!(
            with.jacobians <= without.jacobians,
            "{} > {}",
            with.jacobians,
            without.jacobians
        );
    }
    let (with, without) = (run(&far, true), run(&far, false));
    assert!(
        with.jacobians < without.jacobians,
        "{} vs {}",
        with.jacobians,
        without.jacobians
    );
}

/// `y ≈ a·t + b·t²` with `b ≥ 0` and data whose unconstrained optimum has `b < 0`.
struct Coupled {
    t: Vec<f64>,
    y: Vec<f64>,
}

impl Operator for Coupled {
    type Param = DVector<f64>;
    type Output = DVector<f64>;
    fn apply(&self, p: &DVector<f64>) -> Result<DVector<f64>, ArgminError> {
        Ok(DVector::from_iterator(
            self.t.len(),
            self.t
                .iter()
                .zip(&self.y)
                .map(|(t, y)| p[0] * t + p[1] * t * t - y),
        ))
    }
}

impl Jacobian for Coupled {
    type Param = DVector<f64>;
    type Jacobian = DMatrix<f64>;
    fn jacobian(&self, _: &DVector<f64>) -> Result<DMatrix<f64>, ArgminError> {
        Ok(DMatrix::from_fn(self.t.len(), 2, |i, k| {
            self.t[i].powi(k as i32 + 1)
        }))
    }
}

/// An optimum on a bound with the columns strongly coupled (`t` and `t²` on `[1, 2]`):
/// the fit converges, in a few iterations, to the constrained least-squares solution
/// computed independently (`b = 0`, `a = Σty/Σt²`). Projecting the unconstrained step
/// instead leaves `a` wrong by the coupling at every step and the fit crawls.
#[test]
fn an_optimum_on_a_bound_converges_to_the_constrained_solution() {
    let t: Vec<f64> = (0..21).map(|i| 1.0 + i as f64 * 0.05).collect();
    let y: Vec<f64> = t
        .iter()
        .enumerate()
        .map(|(i, t)| 3.0 * t - 0.4 * t * t + 0.01 * (3.0 * i as f64).sin())
        .collect();
    let a_want =
        t.iter().zip(&y).map(|(t, y)| t * y).sum::<f64>() / t.iter().map(|t| t * t).sum::<f64>();
    let solver = LevenbergMarquardt::new(
        DVector::from_vec(vec![-10.0, 0.0]),
        DVector::from_vec(vec![10.0, 5.0]),
    )
    .unwrap();
    let res = Executor::new(Coupled { t, y }, solver)
        .configure(|s| s.param(DVector::from_vec(vec![1.0, 1.0])).max_iters(100))
        .run()
        .unwrap();
    assert!(res.solver().converged().is_some());
    assert!(
        res.state().get_iter() <= 10,
        "{} iterations",
        res.state().get_iter()
    );
    let p = res.state().get_best_param().unwrap();
    assert_eq!(p[1], 0.0);
    assert_relative_eq!(p[0], a_want, max_relative = 1e-9);
}

#[test]
fn respects_bounds_and_reports_max_iters() {
    // The optimum b = 0.7 lies outside [0, 0.5]: the solution sits on the bound.
    let solver = LevenbergMarquardt::new(
        DVector::from_vec(vec![-10.0, 0.0]),
        DVector::from_vec(vec![10.0, 0.5]),
    )
    .unwrap();
    let res = Executor::new(decay(), solver)
        .configure(|s| s.param(DVector::from_vec(vec![1.0, 0.1])).max_iters(200))
        .run()
        .unwrap();
    let p = res.state().get_best_param().unwrap();
    assert!(p[1] <= 0.5 && p[1] > 0.49, "{p}");
    // One iteration is not enough: no convergence claimed.
    let solver = LevenbergMarquardt::new(
        DVector::from_vec(vec![-10.0, 0.0]),
        DVector::from_vec(vec![10.0, 5.0]),
    )
    .unwrap();
    let res = Executor::new(decay(), solver)
        .configure(|s| s.param(DVector::from_vec(vec![1.0, 2.0])).max_iters(1))
        .run()
        .unwrap();
    assert!(res.solver().converged().is_none());
    assert!(
        LevenbergMarquardt::new(DVector::from_vec(vec![1.0]), DVector::from_vec(vec![0.0]))
            .is_err()
    );
}

/// The symmetric `JᵀJ` gives the bits of nalgebra's `tr_mul`, on tall matrices of every
/// small width with entries of mixed signs and scales (so that rounding differs by order).
#[test]
fn gram_is_tr_mul_bit_for_bit() {
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for p in 1..=7 {
        for n in [1, 7, 8, 9, 64, 1001] {
            let j = DMatrix::from_fn(n, p, |_, c| next() * 10f64.powi(c as i32 - 3));
            let (a, b) = (super::gram(&j), j.tr_mul(&j));
            assert!(a
                .iter()
                .zip(b.iter())
                .all(|(u, v)| u.to_bits() == v.to_bits()));
        }
    }
    // Mostly zeros (the sparse path): a block per ball type as the flight diagnosis makes,
    // dense columns beside them, −0 entries among the zeros, every tail length.
    for (n, p) in [(5, 12), (8, 9), (17, 12), (250, 40), (1003, 64)] {
        let j = DMatrix::from_fn(n, p, |r, c| {
            let v = next();
            match c {
                0 | 1 => v * 10f64.powi(c as i32),
                _ if r % (p - 2) == c - 2 => v,
                _ if v > 0.45 => -0.0,
                _ => 0.0,
            }
        });
        assert!(2 * j.iter().filter(|v| **v == 0.0).count() > j.len());
        let (a, b) = (super::gram(&j), j.tr_mul(&j));
        for (u, v) in a.iter().zip(b.iter()) {
            assert_eq!(u.to_bits(), v.to_bits(), "{n}x{p}: {u} against {v}");
        }
    }
}
