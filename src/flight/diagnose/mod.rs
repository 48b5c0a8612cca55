//! Flight diagnosis: which aerodynamic term of the flight model do measured flights ask for?
//!
//! The candidates: the **drag level** (`C_D` scaled), the **lift slope** (`C_L` scaled), the
//! **drag crisis** (a drag `ΔC_D·r(Re)` added across the Reynolds window of the crisis,
//! [`fit::crisis_weight`]), the **spin decay** (`C_M` scaled) and a **ball-dependent drag**
//! (`C_D` scaled per `ball_type`, offered with two or more ball types; it replaces the drag
//! level when that is already in). Forward selection with cross-validation, as the impact
//! diagnosis does (`crate::diagnose`):
//!
//! 1. Start from the model as given (no free parameter).
//! 2. Each step, estimate noise scales of carry, apex and land angle from the current model's
//!    errors on all shots (1.4826 × median absolute deviation: a bias does not inflate them)
//!    and divide the errors by them.
//! 3. For every candidate not yet in, fit the current terms plus it on all shots (the values
//!    and standard errors reported) and on each training fold, and sum the held-out folds' χ²:
//!    `CV(B ∪ C)`; the current model `B` is cross-validated the same way.
//! 4. The gain `CV(B) − CV(B ∪ C)` must beat `k·ln n + 2·ln m` (`k` added parameters, `n`
//!    shots, `m` candidates offered: a useless parameter raises the held-out χ² by about one,
//!    and the best of `m` useless ones clears a threshold about `m` times as often). The best
//!    candidate with a positive margin whose parameters are all determined is added; the
//!    selection stops when none is left.
//!
//! Folds hold whole sessions when the shots have them (the shots of one day share swing,
//! ball and air, so a term must predict another day to win), else they are by shot. Pure: no
//! I/O.

pub mod fit;

use serde::Serialize;

use crate::flight::calibrate::{bound_reached, reported_se, MeasuredFlight};
use crate::flight::{FlightConfig, M_PER_YD};
use crate::stats::{grouped_folds, item_folds};
use fit::{robust_sigma, Data, FitOut, Layout};

/// A candidate term.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Term {
    /// `C_D` scaled.
    Drag,
    /// `C_L` scaled.
    Lift,
    /// `ΔC_D` across the drag-crisis window.
    DragCrisis,
    /// `C_M` scaled.
    SpinDecay,
    /// `C_D` scaled per ball type.
    DragByBall,
}

/// Every candidate, in the order they are offered.
pub const TERMS: [Term; 5] = [
    Term::Drag,
    Term::Lift,
    Term::DragCrisis,
    Term::SpinDecay,
    Term::DragByBall,
];

impl Term {
    /// Its name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Drag => "drag",
            Self::Lift => "lift",
            Self::DragCrisis => "drag_crisis",
            Self::SpinDecay => "spin_decay",
            Self::DragByBall => "drag@ball",
        }
    }
}

/// What [`diagnose`] is given.
#[derive(Debug, Clone, Copy)]
pub struct DiagnoseInput<'a> {
    /// The measured flights.
    pub shots: &'a [MeasuredFlight],
    /// Ball type of each shot (`None`: not stated).
    pub balls: Option<&'a [String]>,
    /// Session of each shot (a date; `None`: not stated).
    pub sessions: Option<&'a [String]>,
    /// Cross-validation folds (capped at the sessions or shots).
    pub folds: usize,
}

/// One parameter's value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Value {
    /// `drag`, `lift`, `drag_crisis`, `spin_decay`, `drag@BALL`.
    pub name: String,
    /// Scale (or, for `drag_crisis`, `ΔC_D`).
    pub value: f64,
    /// Standard error; `None` at a bound (`at_bound`) or when not determined.
    pub se: Option<f64>,
    /// The bound of the term (scales a third to three times the model's, the crisis drag
    /// −0.15 to +0.40) the fit stopped at: `"lower"`, `"upper"` (in JSON `true`), else `None`
    /// (`false`).
    #[serde(serialize_with = "crate::flight::calibrate::serialize_at_bound")]
    pub at_bound: Option<&'static str>,
}

/// One candidate at one step.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Candidate {
    /// The term.
    pub term: &'static str,
    /// Parameters it adds.
    pub n_params: usize,
    /// The current terms plus it, fitted on all shots.
    pub values: Vec<Value>,
    /// Cross-validated χ² with it.
    pub cv_chi2: f64,
    /// `CV(base) − CV(base + it)`.
    pub gain: f64,
    /// `k·ln n + 2·ln m`.
    pub penalty: f64,
    /// Every parameter determined.
    pub identified: bool,
    /// Why it could not be fitted.
    pub failure: Option<String>,
}

impl Candidate {
    /// `gain − penalty`.
    pub fn margin(&self) -> f64 {
        self.gain - self.penalty
    }
    fn eligible(&self) -> bool {
        self.failure.is_none() && self.identified && self.margin() > 0.0
    }
}

/// One step of the selection.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Step {
    /// Noise scales the errors were divided by: carry yd, apex yd, land angle °.
    pub sigma: [f64; 3],
    /// Cross-validated χ² of the model before the step.
    pub base_cv_chi2: f64,
    /// The candidates, best margin first.
    pub candidates: Vec<Candidate>,
    /// The term selected, if any.
    pub selected: Option<&'static str>,
}

/// The diagnosis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FlightDiagnosis {
    /// Model diagnosed.
    pub model: String,
    /// Shots.
    pub shots: usize,
    /// `session` or `shot`.
    pub folds_by: &'static str,
    /// Folds.
    pub folds: usize,
    /// Ball types (sorted; empty when not stated).
    pub balls: Vec<String>,
    /// The steps.
    pub steps: Vec<Step>,
    /// Terms selected, in order.
    pub selected: Vec<&'static str>,
    /// Their values fitted together on all shots, with standard errors.
    pub values: Vec<Value>,
    /// RMS error of carry (yd), apex (yd) and land angle (°), model as given (NaN, `null` in
    /// JSON, for a quantity not measured).
    pub rmse_before: [f64; 3],
    /// The same with the selected terms.
    pub rmse_after: [f64; 3],
    #[serde(skip)]
    layout: Layout,
    #[serde(skip)]
    params: Vec<f64>,
    #[serde(skip)]
    ball_index: Vec<usize>,
    /// Flights flown to make the diagnosis (its cost, for the tests; not reported).
    #[serde(skip)]
    pub flights_flown: usize,
}

/// Most steps (there are five candidates).
const MAX_STEPS: usize = 5;

/// Why a flight diagnosis cannot be made ([`diagnose`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FlightDiagnoseError {
    /// Fewer than three shots.
    #[error("{n} shot(s): flight diagnosis needs at least 3")]
    TooFewShots {
        /// Shots given.
        n: usize,
    },
    /// Ball types or sessions not one per shot.
    #[error("{what} for {given} shots, not {n}")]
    Lengths {
        /// `ball types` or `sessions`.
        what: &'static str,
        /// How many were given.
        given: usize,
        /// Shots.
        n: usize,
    },
    /// A flight that cannot be flown.
    #[error(transparent)]
    Flight(#[from] crate::flight::FlightError),
    /// A fit that did not converge.
    #[error("the fit did not converge in 100 iterations")]
    NotConverged,
    /// Fewer measured values than parameters.
    #[error("{values} measured value(s) for {params} parameter(s)")]
    TooFewValues {
        /// Measured values.
        values: usize,
        /// Parameters.
        params: usize,
    },
    /// The solver's words.
    #[error("{0}")]
    Solver(String),
}

impl FlightDiagnoseError {
    fn solver(e: impl std::fmt::Display) -> Self {
        Self::Solver(e.to_string())
    }
}

/// Diagnose the flight model of `cfg` against measured flights (see the module documentation).
/// Errors: no shots, lengths that do not match, or a flight that fails.
pub fn diagnose(
    cfg: &FlightConfig,
    input: DiagnoseInput<'_>,
) -> Result<FlightDiagnosis, FlightDiagnoseError> {
    let n = input.shots.len();
    if n < 3 {
        return Err(FlightDiagnoseError::TooFewShots { n });
    }
    for (what, v) in [("ball types", input.balls), ("sessions", input.sessions)] {
        if v.is_some_and(|v| v.len() != n) {
            return Err(FlightDiagnoseError::Lengths {
                what,
                given: v.map_or(0, <[_]>::len),
                n,
            });
        }
    }
    let (balls, ball_index) = index_balls(input.balls, n);
    // Sessions of one shot each are folds by shot, and are named so.
    let (folds_by, fold) = match input.sessions {
        Some(s) if (2..n).contains(&distinct(s)) => ("session", grouped_folds(s, input.folds)),
        _ => ("shot", item_folds(n, input.folds)),
    };
    let k_folds = fold.iter().max().map_or(1, |m| m + 1);
    let all: Vec<usize> = (0..n).collect();
    let mut data = Data {
        cfg,
        shots: input.shots,
        ball: &ball_index,
        sigma: crate::flight::calibrate::SIGMA,
        flown: std::sync::atomic::AtomicUsize::new(0),
    };
    let mut layout = Layout {
        terms: Vec::new(),
        balls: balls.len(),
    };
    let mut params: Vec<f64> = Vec::new();
    let mut steps = Vec::new();
    for _ in 0..MAX_STEPS {
        data.sigma = robust_sigma(&fit::errors(&data, &layout, &params, &all)?);
        let step = select_step(&data, &layout, &params, &fold, k_folds, &balls)?;
        let chosen = step.selected;
        steps.push(step.step);
        match chosen {
            Some((l, p)) => (layout, params) = (l, p),
            None => break,
        }
    }
    let final_fit = fit::fit(&data, &layout, &all, &params)?;
    let flown = &data.flown;
    let values = named_values(&layout, &balls, &final_fit);
    let rmse = |l: &Layout, p: &[f64]| fit::errors(&data, l, p, &all).map(|e| rmse_of(&e));
    let none = Layout {
        terms: Vec::new(),
        balls: balls.len(),
    };
    Ok(FlightDiagnosis {
        model: cfg.aero.name(),
        shots: n,
        folds_by,
        folds: k_folds,
        balls,
        steps,
        selected: layout.terms.iter().map(|t| t.name()).collect(),
        values,
        rmse_before: rmse(&none, &[])?,
        rmse_after: rmse(&layout, &final_fit.p)?,
        params: final_fit.p,
        layout,
        flights_flown: flown.load(std::sync::atomic::Ordering::Relaxed),
        ball_index,
    })
}

fn distinct(keys: &[String]) -> usize {
    let mut v: Vec<&String> = keys.iter().collect();
    v.sort_unstable();
    v.dedup();
    v.len()
}

/// Sorted distinct ball types (none when fewer than two) and each shot's index among them.
fn index_balls(balls: Option<&[String]>, n: usize) -> (Vec<String>, Vec<usize>) {
    let Some(b) = balls else {
        return (Vec::new(), vec![0; n]);
    };
    let mut names: Vec<String> = b.to_vec();
    names.sort_unstable();
    names.dedup();
    if names.len() < 2 {
        return (Vec::new(), vec![0; n]);
    }
    let idx = b
        .iter()
        .map(|x| names.binary_search(x).expect("listed"))
        .collect();
    (names, idx)
}

struct StepOut {
    step: Step,
    selected: Option<(Layout, Vec<f64>)>,
}

/// The terms a step offers given the current ones.
fn offered(layout: &Layout, balls: usize) -> Vec<Term> {
    TERMS
        .iter()
        .copied()
        .filter(|t| !layout.terms.contains(t))
        .filter(|&t| t != Term::DragByBall || balls >= 2)
        .filter(|&t| t != Term::Drag || !layout.terms.contains(&Term::DragByBall))
        .collect()
}

/// The current terms with `t` added (the ball-dependent drag replaces the drag level) and the
/// starting parameters.
fn extended(layout: &Layout, params: &[f64], t: Term) -> (Layout, Vec<f64>) {
    let mut terms = Vec::new();
    let mut start = Vec::new();
    let mut k = 0;
    for &old in &layout.terms {
        let np = layout.term_params(old);
        if !(t == Term::DragByBall && old == Term::Drag) {
            terms.push(old);
            start.extend_from_slice(&params[k..k + np]);
        }
        k += np;
    }
    terms.push(t);
    let l = Layout {
        terms,
        balls: layout.balls,
    };
    let add = Layout {
        terms: vec![t],
        balls: layout.balls,
    };
    start.extend(add.start());
    (l, start)
}

/// Cross-validated χ²: each fold's held-out shots at the parameters fitted without them.
fn cv_chi2(
    data: &Data<'_>,
    layout: &Layout,
    start: &[f64],
    fold: &[usize],
    k_folds: usize,
) -> Result<f64, FlightDiagnoseError> {
    let mut total = 0.0;
    for f in 0..k_folds {
        let train: Vec<usize> = (0..fold.len()).filter(|&i| fold[i] != f).collect();
        let test: Vec<usize> = (0..fold.len()).filter(|&i| fold[i] == f).collect();
        let p = if layout.n_params() == 0 {
            Vec::new()
        } else {
            fit::fit(data, layout, &train, start)?.p
        };
        total += fit::residuals(data, layout, &p, &test)?.norm_squared();
    }
    Ok(total)
}

fn select_step(
    data: &Data<'_>,
    layout: &Layout,
    params: &[f64],
    fold: &[usize],
    k_folds: usize,
    names: &[String],
) -> Result<StepOut, FlightDiagnoseError> {
    let base_cv = cv_chi2(data, layout, params, fold, k_folds)?;
    let terms = offered(layout, names.len());
    let n = data.shots.len() as f64;
    let m = terms.len() as f64;
    let mut cands = Vec::new();
    let mut fits = Vec::new();
    for t in terms {
        let (l, start) = extended(layout, params, t);
        let k_added = l.n_params() as f64 - layout.n_params() as f64;
        let penalty = k_added * n.ln() + 2.0 * m.ln();
        let all: Vec<usize> = (0..data.shots.len()).collect();
        let outcome = fit::fit(data, &l, &all, &start)
            .and_then(|f| cv_chi2(data, &l, &start, fold, k_folds).map(|cv| (f, cv)));
        let cand = match &outcome {
            Ok((f, cv)) => Candidate {
                term: t.name(),
                n_params: k_added as usize,
                values: named_values(&l, names, f),
                cv_chi2: *cv,
                gain: base_cv - cv,
                penalty,
                identified: f.identified,
                failure: None,
            },
            Err(e) => Candidate {
                term: t.name(),
                n_params: k_added as usize,
                values: Vec::new(),
                cv_chi2: f64::NAN,
                gain: f64::NAN,
                penalty,
                identified: false,
                failure: Some(e.to_string()),
            },
        };
        fits.push(outcome.ok().map(|(f, _)| (l, f.p)));
        cands.push(cand);
    }
    let best = (0..cands.len())
        .filter(|&i| cands[i].eligible())
        .max_by(|&a, &b| cands[a].margin().total_cmp(&cands[b].margin()));
    let selected = best.and_then(|i| fits[i].clone());
    let chosen = best.map(|i| cands[i].term);
    let mut order: Vec<usize> = (0..cands.len()).collect();
    order.sort_by(|&a, &b| {
        let key = |c: &Candidate| {
            if c.margin().is_nan() {
                f64::NEG_INFINITY
            } else {
                c.margin()
            }
        };
        key(&cands[b]).total_cmp(&key(&cands[a]))
    });
    let s = data.sigma;
    Ok(StepOut {
        step: Step {
            sigma: [s[0] / M_PER_YD, s[1] / M_PER_YD, s[2].to_degrees()],
            base_cv_chi2: base_cv,
            candidates: order.into_iter().map(|i| cands[i].clone()).collect(),
            selected: chosen,
        },
        selected,
    })
}

/// Each parameter of `layout` named, with its value and standard error.
fn named_values(layout: &Layout, balls: &[String], f: &FitOut) -> Vec<Value> {
    let mut out = Vec::new();
    let (lo, hi) = layout.bounds();
    let mut k = 0;
    for &t in &layout.terms {
        for b in 0..layout.term_params(t) {
            let name = match t {
                Term::DragByBall => format!("drag@{}", balls.get(b).map_or("?", String::as_str)),
                _ => t.name().to_string(),
            };
            let at_bound = bound_reached(f.p[k], (lo[k], hi[k]));
            out.push(Value {
                name,
                value: f.p[k],
                se: reported_se(f.se[k], at_bound),
                at_bound,
            });
            k += 1;
        }
    }
    out
}

/// RMS of the carry (yd), apex (yd) and land-angle (°) errors.
fn rmse_of(e: &[[Option<f64>; 3]]) -> [f64; 3] {
    let mut out = [f64::NAN; 3];
    let unit = [1.0 / M_PER_YD, 1.0 / M_PER_YD, 180.0 / std::f64::consts::PI];
    for q in 0..3 {
        let v: Vec<f64> = e.iter().filter_map(|x| x[q]).collect();
        if !v.is_empty() {
            out[q] = (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt() * unit[q];
        }
    }
    out
}

impl FlightDiagnosis {
    /// Fly `shots` (ordered as diagnosed) with the selected terms.
    pub fn fly(
        &self,
        cfg: &FlightConfig,
        shots: &[crate::flight::FlightLaunch],
    ) -> Vec<Result<crate::flight::Flight, crate::flight::FlightError>> {
        let mut out: Vec<Result<crate::flight::Flight, crate::flight::FlightError>> =
            Vec::with_capacity(shots.len());
        let ball = |i: usize| self.ball_index.get(i).copied().unwrap_or(0);
        let mut groups: Vec<usize> = (0..shots.len()).map(ball).collect();
        groups.sort_unstable();
        groups.dedup();
        let mut slots = vec![None; shots.len()];
        for g in groups {
            let idx: Vec<usize> = (0..shots.len()).filter(|&i| ball(i) == g).collect();
            let launches: Vec<_> = idx.iter().map(|&i| shots[i]).collect();
            let model = self.layout.model(&cfg.aero, &self.params, g);
            let flown = crate::flight::integrate::fly_with(cfg, &model, &launches);
            for (i, f) in idx.into_iter().zip(flown) {
                slots[i] = Some(f);
            }
        }
        out.extend(slots.into_iter().map(|f| f.expect("every shot flown")));
        out
    }

    /// The diagnosis as text: one table per step, then the terms selected (lines under 100
    /// columns).
    pub fn text(&self) -> String {
        text::render(self)
    }
}

mod text;

#[cfg(test)]
mod tests;
