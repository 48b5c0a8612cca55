//! The fits flight diagnosis makes: a set of aerodynamic terms (scalings of the model's drag,
//! lift and spin-decay moment, an added drag across the drag-crisis window, a drag scaling per
//! ball type) fitted to measured flights by the project's bounded Levenberg–Marquardt, with
//! standard errors from `s²·(JᵀJ)⁻¹`. Pure: no I/O.

use argmin::core::{Error as ArgminError, Executor, Jacobian, Operator, State};
use nalgebra::{DMatrix, DVector};

use super::{FlightDiagnoseError, Term};
use crate::fit::lm::{LevenbergMarquardt, LmState};
use crate::flight::aero::{CoefficientModel, Coefficients, Fmm2022Tour};
use crate::flight::calibrate::{MeasuredFlight, SIGMA};
use crate::flight::integrate::fly_with;
use crate::flight::{AeroModel, FlightConfig, FlightLaunch};

/// A coefficient model with its drag, lift and moment scaled and a drag added across the
/// drag-crisis window: `C_D·drag + crisis_cd·r(Re)`, `C_L·lift`, `C_M·moment`.
#[derive(Debug, Clone, Copy)]
pub struct Adjusted<'a> {
    /// The model adjusted.
    pub inner: &'a AeroModel,
    /// Drag scale.
    pub drag: f64,
    /// Lift scale.
    pub lift: f64,
    /// Spin-decay moment scale.
    pub moment: f64,
    /// Drag coefficient added below the crisis window (`r` = 1), none above it.
    pub crisis_cd: f64,
}

/// The drag-crisis weight: 1 below `Re` = 7·10⁴, a smoothstep to 0 at 10⁵ (the window where
/// still-air and wind-tunnel measurements put the crisis: Lyu et al., ISEA 2018; Bearman &
/// Harvey 1976; the window of [`Fmm2022Tour`]). The Reynolds number is the one the adjusted
/// model is given (for the built-in models, in their reference air).
pub fn crisis_weight(re: f64) -> f64 {
    let (lo, hi) = (Fmm2022Tour::RE_LOW, Fmm2022Tour::RE_HIGH);
    let t = ((hi - re) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl CoefficientModel for Adjusted<'_> {
    fn reynolds_at_reference_air(&self) -> bool {
        self.inner.reynolds_at_reference_air()
    }

    fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        let c = self.inner.coefficients(s, re);
        Coefficients {
            cd: c.cd * self.drag + self.crisis_cd * crisis_weight(re),
            cl: c.cl * self.lift,
            cm: c.cm * self.moment,
        }
    }
}

/// The terms of a model and where their parameters sit in the parameter vector.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// The terms, in order.
    pub terms: Vec<Term>,
    /// Ball types (for [`Term::DragByBall`], one parameter each).
    pub balls: usize,
}

impl Layout {
    /// Parameters of one term.
    pub fn term_params(&self, t: Term) -> usize {
        match t {
            Term::DragByBall => self.balls,
            _ => 1,
        }
    }
    /// Parameters of all terms.
    pub fn n_params(&self) -> usize {
        self.terms.iter().map(|&t| self.term_params(t)).sum()
    }
    /// Where every parameter starts: the unadjusted model.
    pub fn start(&self) -> Vec<f64> {
        let mut p = Vec::new();
        for &t in &self.terms {
            let v = if t == Term::DragCrisis { 0.0 } else { 1.0 };
            p.extend(std::iter::repeat_n(v, self.term_params(t)));
        }
        p
    }
    /// Bounds: scales from a third to three times the model's coefficient; the crisis drag
    /// from −0.15 to +0.40 (about the 0.29 of the still-air crisis itself, Lyu et al. 2018,
    /// with room either way).
    pub(super) fn bounds(&self) -> (DVector<f64>, DVector<f64>) {
        let (mut lo, mut hi) = (Vec::new(), Vec::new());
        for &t in &self.terms {
            let (l, h) = if t == Term::DragCrisis {
                (-0.15, 0.40)
            } else {
                (1.0 / 3.0, 3.0)
            };
            for _ in 0..self.term_params(t) {
                lo.push(l);
                hi.push(h);
            }
        }
        (DVector::from_vec(lo), DVector::from_vec(hi))
    }
    /// The adjusted model at parameters `p` for a shot of ball type `ball`.
    pub fn model<'a>(&self, inner: &'a AeroModel, p: &[f64], ball: usize) -> Adjusted<'a> {
        let mut m = Adjusted {
            inner,
            drag: 1.0,
            lift: 1.0,
            moment: 1.0,
            crisis_cd: 0.0,
        };
        let mut k = 0;
        for &t in &self.terms {
            match t {
                Term::Drag => m.drag *= p[k],
                Term::Lift => m.lift = p[k],
                Term::SpinDecay => m.moment = p[k],
                Term::DragCrisis => m.crisis_cd = p[k],
                Term::DragByBall => m.drag *= p[k + ball],
            }
            k += self.term_params(t);
        }
        m
    }
    /// Whether the model differs between ball types.
    fn per_ball(&self) -> bool {
        self.terms.contains(&Term::DragByBall)
    }
    /// The ball type parameter `k` belongs to, when it is one of the ball-dependent drag's
    /// (it changes the flights of that ball type's shots only).
    fn ball_of_param(&self, k: usize) -> Option<usize> {
        let mut start = 0;
        for &t in &self.terms {
            let np = self.term_params(t);
            if (start..start + np).contains(&k) {
                return (t == Term::DragByBall).then_some(k - start);
            }
            start += np;
        }
        None
    }
}

/// The measured flights, their ball types and the noise scales residuals are divided by.
#[derive(Debug)]
pub struct Data<'a> {
    /// Flight configuration (its model the one adjusted).
    pub cfg: &'a FlightConfig,
    /// The shots.
    pub shots: &'a [MeasuredFlight],
    /// Ball type index of each shot (all 0 without ball types).
    pub ball: &'a [usize],
    /// Noise scale of carry (m), apex (m), land angle (rad).
    pub sigma: [f64; 3],
    /// Flights flown so far (every evaluation of the model counts its shots), for the tests of
    /// the diagnosis's cost.
    pub flown: std::sync::atomic::AtomicUsize,
}

/// Predicted − measured carry (m), apex (m) and land angle (rad) of shots `idx` at `p`
/// (`None`: not measured).
pub fn errors(
    data: &Data<'_>,
    layout: &Layout,
    p: &[f64],
    idx: &[usize],
) -> Result<Vec<[Option<f64>; 3]>, FlightDiagnoseError> {
    let mut out = vec![[None; 3]; idx.len()];
    let groups: Vec<usize> = if layout.per_ball() {
        let mut g: Vec<usize> = idx.iter().map(|&i| data.ball[i]).collect();
        g.sort_unstable();
        g.dedup();
        g
    } else {
        vec![0]
    };
    for g in groups {
        let pos: Vec<usize> = (0..idx.len())
            .filter(|&j| !layout.per_ball() || data.ball[idx[j]] == g)
            .collect();
        let launches: Vec<FlightLaunch> = pos.iter().map(|&j| data.shots[idx[j]].launch).collect();
        data.flown
            .fetch_add(launches.len(), std::sync::atomic::Ordering::Relaxed);
        let model = layout.model(&data.cfg.aero, p, g);
        for (&j, f) in pos.iter().zip(fly_with(data.cfg, &model, &launches)) {
            let f = f?;
            let s = &data.shots[idx[j]];
            out[j] = [
                s.carry_m.map(|m| f.carry_m - m),
                s.apex_m.map(|m| f.apex_m - m),
                s.land_angle_rad.map(|m| f.land_angle_rad - m),
            ];
        }
    }
    Ok(out)
}

/// The errors of shots `idx` at `p` divided by the noise scales, measured values only.
pub fn residuals(
    data: &Data<'_>,
    layout: &Layout,
    p: &[f64],
    idx: &[usize],
) -> Result<DVector<f64>, FlightDiagnoseError> {
    let e = errors(data, layout, p, idx)?;
    Ok(weighted(data, &e))
}

/// Errors divided by the noise scales, measured values only, shot by shot.
fn weighted(data: &Data<'_>, e: &[[Option<f64>; 3]]) -> DVector<f64> {
    let r: Vec<f64> = e
        .iter()
        .flat_map(|q| {
            q.iter()
                .zip(data.sigma)
                .filter_map(|(x, s)| x.map(|x| x / s))
        })
        .collect();
    DVector::from_vec(r)
}

#[derive(Clone)]
struct Problem<'a> {
    data: &'a Data<'a>,
    layout: &'a Layout,
    idx: &'a [usize],
}

impl Operator for Problem<'_> {
    type Param = DVector<f64>;
    type Output = DVector<f64>;
    fn apply(&self, p: &Self::Param) -> Result<Self::Output, ArgminError> {
        residuals(self.data, self.layout, p.as_slice(), self.idx).map_err(ArgminError::msg)
    }
}

impl Jacobian for Problem<'_> {
    type Param = DVector<f64>;
    type Jacobian = DMatrix<f64>;
    fn jacobian(&self, p: &Self::Param) -> Result<Self::Jacobian, ArgminError> {
        jacobian(self.data, self.layout, p.as_slice(), self.idx).map_err(ArgminError::msg)
    }
}

/// The Jacobian of [`residuals`] by forward differences. A ball type's drag changes only that
/// ball type's flights: its column is made by flying those shots alone (the others' entries
/// are 0, as flying them would give), so the columns of `B` ball types cost one evaluation of
/// the shots together, not `B` (with 500 ball types a diagnosis took more than 16 minutes).
pub fn jacobian(
    data: &Data<'_>,
    layout: &Layout,
    p: &[f64],
    idx: &[usize],
) -> Result<DMatrix<f64>, FlightDiagnoseError> {
    let e0 = errors(data, layout, p, idx)?;
    let r0 = weighted(data, &e0);
    // Each shot's first row in the residuals (its measured values, in order).
    let mut first_row = Vec::with_capacity(idx.len());
    let mut rows = 0;
    for q in &e0 {
        first_row.push(rows);
        rows += q.iter().flatten().count();
    }
    let mut j = DMatrix::zeros(r0.len(), p.len());
    for k in 0..p.len() {
        // Forward difference, 1e-6 of the parameter's scale (as in the calibration: the
        // landing is interpolated, so a flight is smooth in every parameter).
        let h = 1e-6 * p[k].abs().max(1.0);
        let mut q = p.to_vec();
        q[k] += h;
        let Some(ball) = layout.ball_of_param(k) else {
            j.set_column(k, &((residuals(data, layout, &q, idx)? - &r0) / h));
            continue;
        };
        let shots: Vec<usize> = (0..idx.len())
            .filter(|&s| data.ball[idx[s]] == ball)
            .collect();
        let sub: Vec<usize> = shots.iter().map(|&s| idx[s]).collect();
        let e = errors(data, layout, &q, &sub)?;
        for (&s, es) in shots.iter().zip(&e) {
            let mut row = first_row[s];
            for (c, x) in es.iter().enumerate() {
                if let (Some(x), Some(x0)) = (x, e0[s][c]) {
                    j[(row, k)] = (x / data.sigma[c] - x0 / data.sigma[c]) / h;
                    row += 1;
                }
            }
        }
    }
    Ok(j)
}

/// A fit's result.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOut {
    /// Parameters.
    pub p: Vec<f64>,
    /// Their standard errors (`NaN` when not identified).
    pub se: Vec<f64>,
    /// χ² of the weighted residuals at `p`.
    pub chi2: f64,
    /// Whether every parameter is determined (`JᵀJ` invertible, finite standard errors).
    pub identified: bool,
}

/// Fit `layout` to shots `idx` from `start`. Errors: a flight that fails, a fit that does not
/// converge in 100 iterations, or fewer measured values than parameters.
pub fn fit(
    data: &Data<'_>,
    layout: &Layout,
    idx: &[usize],
    start: &[f64],
) -> Result<FitOut, FlightDiagnoseError> {
    let problem = Problem { data, layout, idx };
    let p0 = DVector::from_column_slice(start);
    let n = layout.n_params();
    if n == 0 {
        let chi2 = problem
            .apply(&p0)
            .map_err(FlightDiagnoseError::solver)?
            .norm_squared();
        return Ok(FitOut {
            p: Vec::new(),
            se: Vec::new(),
            chi2,
            identified: true,
        });
    }
    let (lo, hi) = layout.bounds();
    let solver = LevenbergMarquardt::new(lo, hi).map_err(FlightDiagnoseError::solver)?;
    let result = Executor::new(problem.clone(), solver)
        .configure(|s: LmState| s.param(p0).max_iters(100))
        .run()
        .map_err(FlightDiagnoseError::solver)?;
    if result.solver().converged().is_none() {
        return Err(FlightDiagnoseError::NotConverged);
    }
    let p = result
        .state()
        .get_best_param()
        .expect("the solver keeps its point")
        .clone();
    let r = problem.apply(&p).map_err(FlightDiagnoseError::solver)?;
    let m = r.len();
    if m <= n {
        return Err(FlightDiagnoseError::TooFewValues {
            values: m,
            params: n,
        });
    }
    let j = jacobian(data, layout, p.as_slice(), idx)?;
    let chi2 = r.norm_squared();
    let s2 = chi2 / (m - n) as f64;
    let cov = (j.transpose() * &j).try_inverse();
    let se: Vec<f64> = match &cov {
        Some(c) => (0..n).map(|k| (c[(k, k)] * s2).sqrt()).collect(),
        None => vec![f64::NAN; n],
    };
    let identified = se.iter().all(|s| s.is_finite() && *s > 0.0);
    Ok(FitOut {
        p: p.iter().copied().collect(),
        se,
        chi2,
        identified,
    })
}

/// Robust noise scale per quantity of the errors `e`: 1.4826 × the median absolute deviation
/// from the median (the normal distribution's σ; a bias or a few wild shots do not inflate
/// it). A quantity with fewer than 3 measured values, or no scatter, keeps its nominal scale
/// ([`SIGMA`]), so no residual is divided by zero.
pub fn robust_sigma(e: &[[Option<f64>; 3]]) -> [f64; 3] {
    let mut out = SIGMA;
    for (q, slot) in out.iter_mut().enumerate() {
        let mut v: Vec<f64> = e.iter().filter_map(|x| x[q]).collect();
        if v.len() < 3 {
            continue;
        }
        let med = median(&mut v);
        let mut dev: Vec<f64> = v.iter().map(|x| (x - med).abs()).collect();
        let mad = 1.4826 * median(&mut dev);
        if mad > 1e-3 * SIGMA[q] {
            *slot = mad;
        }
    }
    out
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}
