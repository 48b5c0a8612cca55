//! Flight calibration: scale the drag, the lift and the spin-decay moment of a coefficient
//! model so that its flights match measured ones, with a standard error on each scale.
//!
//! The scaled model is `C_D·k_D`, `C_L·k_L`, `C_M·k_M` ([`Scaled`]). The scales are a bounded
//! Levenberg–Marquardt fit (the project's solver, [`crate::fit::lm`]) of the residuals
//! `(predicted − measured)/σ` of every measured carry, apex and land angle, with `σ` a nominal
//! measurement error per quantity ([`SIGMA`]); the Jacobian by forward differences of whole
//! flights (the landing is interpolated, so a flight is smooth in the scales). Standard errors
//! from the covariance `s²·(JᵀJ)⁻¹` at the fit, `s² = χ²/(m − p)` (the residuals' own scatter,
//! so a wrong `σ` does not make the errors wrong). Pure: no I/O.

use argmin::core::{Error as ArgminError, Executor, Jacobian, Operator, State};
use nalgebra::{DMatrix, DVector};

use super::aero::{CoefficientModel, Coefficients};
use super::integrate::fly_with;
use super::{FlightConfig, FlightLaunch};
use crate::fit::lm::{LevenbergMarquardt, LmState};

/// A coefficient model with its drag, lift and moment scaled.
#[derive(Debug, Clone, Copy)]
pub struct Scaled<'a> {
    /// The model scaled.
    pub inner: &'a super::AeroModel,
    /// Drag scale.
    pub drag: f64,
    /// Lift scale.
    pub lift: f64,
    /// Spin-decay moment scale.
    pub moment: f64,
}

impl CoefficientModel for Scaled<'_> {
    fn reynolds_at_reference_air(&self) -> bool {
        self.inner.reynolds_at_reference_air()
    }

    fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        let c = self.inner.coefficients(s, re);
        Coefficients {
            cd: c.cd * self.drag,
            cl: c.cl * self.lift,
            cm: c.cm * self.moment,
        }
    }
}

/// A term calibration may scale.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Term {
    /// The drag coefficient.
    Drag,
    /// The lift coefficient.
    Lift,
    /// The spin-decay moment coefficient.
    SpinDecay,
}

impl Term {
    /// From its name: `drag`, `lift`, `spin_decay`.
    pub fn from_name(name: &str) -> Result<Self, CalibrationError> {
        match name {
            "drag" => Ok(Self::Drag),
            "lift" => Ok(Self::Lift),
            "spin_decay" => Ok(Self::SpinDecay),
            _ => Err(CalibrationError::UnknownTerm {
                name: name.to_owned(),
            }),
        }
    }
    /// Its name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Drag => "drag",
            Self::Lift => "lift",
            Self::SpinDecay => "spin_decay",
        }
    }
}

/// Nominal measurement errors the residuals are divided by: carry 1.5 yd (in m), apex 1 yd
/// (in m), land angle 1° (in rad) — of the order of a radar monitor's stated accuracy, so that
/// each quantity counts about equally; the standard errors do not depend on them (see the
/// module documentation).
pub const SIGMA: [f64; 3] = [1.5 * 0.9144, 0.9144, 0.017_453_292_519_943_295];

/// One measured flight: its launch and what was measured (SI; `None`: not measured).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredFlight {
    /// The launch.
    pub launch: FlightLaunch,
    /// Measured carry, m.
    pub carry_m: Option<f64>,
    /// Measured apex, m.
    pub apex_m: Option<f64>,
    /// Measured land angle, rad.
    pub land_angle_rad: Option<f64>,
}

/// A calibration's result.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// The terms scaled, in the order asked.
    pub terms: Vec<Term>,
    /// Each term's scale.
    pub scale: Vec<f64>,
    /// Each scale's standard error.
    pub se: Vec<f64>,
    /// Root mean square of the weighted residuals before (all scales 1) and after.
    pub rms_before: f64,
    /// After the fit.
    pub rms_after: f64,
    /// Residuals (measured values) fitted.
    pub residuals: usize,
}

impl Calibration {
    /// The scales as a model over `inner` (terms not calibrated at 1).
    pub fn model<'a>(&self, inner: &'a super::AeroModel) -> Scaled<'a> {
        let mut m = Scaled {
            inner,
            drag: 1.0,
            lift: 1.0,
            moment: 1.0,
        };
        for (t, &k) in self.terms.iter().zip(&self.scale) {
            match t {
                Term::Drag => m.drag = k,
                Term::Lift => m.lift = k,
                Term::SpinDecay => m.moment = k,
            }
        }
        m
    }
}

/// Bounds of every scale: a third to three times the model's coefficient.
pub const SCALE_BOUNDS: (f64, f64) = (1.0 / 3.0, 3.0);

/// Which bound of `(lo, hi)` an estimate sits on (`"lower"`, `"upper"`; within a millionth of
/// the range): the fit stopped there, so the curvature's standard error does not describe it.
pub fn bound_reached(value: f64, (lo, hi): (f64, f64)) -> Option<&'static str> {
    let tol = 1e-6 * (hi - lo);
    if value <= lo + tol {
        Some("lower")
    } else if value >= hi - tol {
        Some("upper")
    } else {
        None
    }
}

/// An estimate's uncertainty as printed after its value: `± 0.0041`, or why there is none,
/// `(at its upper bound)` or `(not determined)` (`se` `None` or not finite).
pub fn uncertainty_text(se: Option<f64>, bound: Option<&str>) -> String {
    match (bound, se) {
        (Some(b), _) => format!("(at its {b} bound)"),
        (None, Some(se)) if se.is_finite() => format!("± {se:.4}"),
        (None, _) => "(not determined)".to_string(),
    }
}

/// Serialise a [`bound_reached`] as `true`/`false`, the JSON reports' `at_bound` (the text
/// names which bound).
pub fn serialize_at_bound<S: serde::Serializer>(
    bound: &Option<&'static str>,
    s: S,
) -> Result<S::Ok, S::Error> {
    s.serialize_bool(bound.is_some())
}

/// A standard error to report: `None` at a bound ([`bound_reached`]) or when not finite.
pub fn reported_se(se: f64, bound: Option<&str>) -> Option<f64> {
    (bound.is_none() && se.is_finite()).then_some(se)
}

#[derive(Clone)]
struct Problem<'a> {
    cfg: &'a FlightConfig,
    shots: &'a [MeasuredFlight],
    terms: &'a [Term],
}

impl Problem<'_> {
    fn calibration(&self, p: &[f64]) -> Calibration {
        Calibration {
            terms: self.terms.to_vec(),
            scale: p.to_vec(),
            se: vec![0.0; p.len()],
            rms_before: 0.0,
            rms_after: 0.0,
            residuals: 0,
        }
    }

    /// Weighted residuals at scales `p`; a flight that fails gives an error.
    fn residuals(&self, p: &[f64]) -> Result<DVector<f64>, ArgminError> {
        let cal = self.calibration(p);
        let model = cal.model(&self.cfg.aero);
        let launches: Vec<FlightLaunch> = self.shots.iter().map(|s| s.launch).collect();
        let flights = fly_with(self.cfg, &model, &launches);
        let mut r = Vec::new();
        for (s, f) in self.shots.iter().zip(flights) {
            let f = f.map_err(|e| ArgminError::msg(e.to_string()))?;
            let pairs = [
                (s.carry_m, f.carry_m),
                (s.apex_m, f.apex_m),
                (s.land_angle_rad, f.land_angle_rad),
            ];
            for ((m, pred), sigma) in pairs.iter().zip(SIGMA) {
                if let Some(m) = m {
                    r.push((pred - m) / sigma);
                }
            }
        }
        Ok(DVector::from_vec(r))
    }
}

impl Operator for Problem<'_> {
    type Param = DVector<f64>;
    type Output = DVector<f64>;
    fn apply(&self, p: &Self::Param) -> Result<Self::Output, ArgminError> {
        self.residuals(p.as_slice())
    }
}

impl Jacobian for Problem<'_> {
    type Param = DVector<f64>;
    type Jacobian = DMatrix<f64>;
    fn jacobian(&self, p: &Self::Param) -> Result<Self::Jacobian, ArgminError> {
        let r0 = self.residuals(p.as_slice())?;
        let mut j = DMatrix::zeros(r0.len(), p.len());
        for k in 0..p.len() {
            // Forward difference, 1e-6 of the scale: the flight is smooth in it and its
            // rounding (about 1e-13 relative) stays far below the step.
            let h = 1e-6 * p[k].abs().max(1.0);
            let mut q = p.clone();
            q[k] += h;
            let rk = self.residuals(q.as_slice())?;
            j.set_column(k, &((rk - &r0) / h));
        }
        Ok(j)
    }
}

/// Why flight terms cannot be calibrated ([`calibrate`], [`Term::from_name`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibrationError {
    /// A name that is no term.
    #[error("unknown flight term '{name}' (allowed: drag, lift, spin_decay)")]
    UnknownTerm {
        /// The name given.
        name: String,
    },
    /// No term given.
    #[error("no flight term to calibrate")]
    NoTerm,
    /// A term given twice.
    #[error("a flight term is named twice")]
    TermTwice,
    /// Fewer measured values than terms.
    #[error("{values} measured value(s) (carry, apex, land angle) for {terms} term(s): need more")]
    TooFewValues {
        /// Measured values.
        values: usize,
        /// Terms.
        terms: usize,
    },
    /// The fit did not converge.
    #[error("the flight calibration did not converge in 100 iterations")]
    NotConverged,
    /// The measured flights do not separate the terms.
    #[error("the measured flights do not tell the terms apart (singular JᵀJ)")]
    Singular,
    /// A flight or the solver failed (its words).
    #[error("{0}")]
    Solver(String),
}

impl CalibrationError {
    fn solver(e: impl std::fmt::Display) -> Self {
        Self::Solver(e.to_string())
    }
}

/// Fit the scales of `terms` to the measured flights `shots` flown with `cfg` (its model the
/// one scaled). Errors: no term, a repeated term, fewer measured values than terms, a flight
/// that fails, or a fit that does not converge.
pub fn calibrate(
    cfg: &FlightConfig,
    shots: &[MeasuredFlight],
    terms: &[Term],
) -> Result<Calibration, CalibrationError> {
    if terms.is_empty() {
        return Err(CalibrationError::NoTerm);
    }
    if (1..terms.len()).any(|i| terms[..i].contains(&terms[i])) {
        return Err(CalibrationError::TermTwice);
    }
    let problem = Problem { cfg, shots, terms };
    let p = terms.len();
    let ones = DVector::from_element(p, 1.0);
    let r0 = problem
        .residuals(ones.as_slice())
        .map_err(CalibrationError::solver)?;
    let m = r0.len();
    if m <= p {
        return Err(CalibrationError::TooFewValues {
            values: m,
            terms: p,
        });
    }
    let solver = LevenbergMarquardt::new(
        DVector::from_element(p, SCALE_BOUNDS.0),
        DVector::from_element(p, SCALE_BOUNDS.1),
    )
    .map_err(CalibrationError::solver)?;
    let result = Executor::new(problem.clone(), solver)
        .configure(|s: LmState| s.param(ones).max_iters(100))
        .run()
        .map_err(CalibrationError::solver)?;
    if result.solver().converged().is_none() {
        return Err(CalibrationError::NotConverged);
    }
    let state = result.state();
    let scale = state
        .get_best_param()
        .expect("the solver keeps its point")
        .clone();
    let r = problem
        .residuals(scale.as_slice())
        .map_err(CalibrationError::solver)?;
    let j = problem.jacobian(&scale).map_err(CalibrationError::solver)?;
    let chi2 = r.norm_squared();
    let s2 = chi2 / (m - p) as f64;
    let cov = (j.transpose() * &j)
        .try_inverse()
        .ok_or(CalibrationError::Singular)?
        * s2;
    Ok(Calibration {
        terms: terms.to_vec(),
        scale: scale.iter().copied().collect(),
        se: (0..p).map(|k| cov[(k, k)].max(0.0).sqrt()).collect(),
        rms_before: (r0.norm_squared() / m as f64).sqrt(),
        rms_after: (chi2 / m as f64).sqrt(),
        residuals: m,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flight::fly;

    /// Launches driver to wedge, straight and curved.
    fn launches() -> Vec<FlightLaunch> {
        let mut v = Vec::new();
        for (mph, deg, rpm) in [
            (165.0, 11.0, 2600.0),
            (150.0, 12.5, 3200.0),
            (135.0, 13.0, 4800.0),
            (120.0, 16.0, 7000.0),
            (100.0, 24.0, 9000.0),
            (85.0, 28.0, 8000.0),
        ] {
            for side in [-600.0, 0.0, 600.0] {
                v.push(FlightLaunch::from_file_units(mph, deg, 0.0, rpm, side));
            }
        }
        v
    }

    /// Measured flights made by `truth` with deterministic errors `noise(k)` (in σ units) on
    /// each measured value.
    fn measured(truth: &Scaled<'_>, noise: impl Fn(usize) -> f64) -> Vec<MeasuredFlight> {
        let cfg = FlightConfig::default();
        let ls = launches();
        let flights = fly_with(&cfg, truth, &ls);
        ls.iter()
            .zip(flights)
            .enumerate()
            .map(|(i, (l, f))| {
                let f = f.unwrap();
                MeasuredFlight {
                    launch: *l,
                    carry_m: Some(f.carry_m + SIGMA[0] * noise(3 * i)),
                    apex_m: Some(f.apex_m + SIGMA[1] * noise(3 * i + 1)),
                    land_angle_rad: Some(f.land_angle_rad + SIGMA[2] * noise(3 * i + 2)),
                }
            })
            .collect()
    }

    /// A hidden drag and lift scaling is recovered: exactly without noise, and within its
    /// standard error's reach (3 SE) with noise of the nominal size, the noise a fixed
    /// low-discrepancy sequence (no seed to choose).
    #[test]
    fn a_hidden_drag_and_lift_scaling_is_recovered() {
        let aero = crate::flight::AeroModel::default();
        let truth = Scaled {
            inner: &aero,
            drag: 1.08,
            lift: 0.93,
            moment: 1.0,
        };
        let cfg = FlightConfig::default();
        let terms = [Term::Drag, Term::Lift];
        let exact = calibrate(&cfg, &measured(&truth, |_| 0.0), &terms).unwrap();
        assert!((exact.scale[0] - 1.08).abs() < 1e-6, "{exact:?}");
        assert!((exact.scale[1] - 0.93).abs() < 1e-6, "{exact:?}");
        assert!(
            exact.rms_before > 1.0 && exact.rms_after < 1e-5,
            "{exact:?}"
        );
        // Noise: the golden-ratio sequence mapped to ±√3 (uniform, unit variance).
        let noise = |k: usize| ((k as f64 * 0.618_033_988_749_895).fract() - 0.5) * 12f64.sqrt();
        let noisy = calibrate(&cfg, &measured(&truth, noise), &terms).unwrap();
        for (k, t) in [1.08, 0.93].iter().enumerate() {
            let (est, se) = (noisy.scale[k], noisy.se[k]);
            assert!(se > 0.0 && se < 0.02, "{noisy:?}");
            assert!((est - t).abs() < 3.0 * se, "{k}: {est} ± {se} vs {t}");
        }
        assert!((noisy.rms_after - 1.0).abs() < 0.3, "{noisy:?}");
    }

    #[test]
    fn bad_term_lists_are_refused() {
        let cfg = FlightConfig::default();
        let shots = measured(
            &Scaled {
                inner: &cfg.aero,
                drag: 1.0,
                lift: 1.0,
                moment: 1.0,
            },
            |_| 0.0,
        );
        assert_eq!(calibrate(&cfg, &shots, &[]), Err(CalibrationError::NoTerm));
        let twice = calibrate(&cfg, &shots, &[Term::Drag, Term::Drag]).unwrap_err();
        assert_eq!(twice, CalibrationError::TermTwice);
        assert!(twice.to_string().contains("twice"), "{twice}");
        let few = calibrate(
            &cfg,
            &shots[..1],
            &[Term::Drag, Term::Lift, Term::SpinDecay],
        );
        assert!(few.unwrap_err().to_string().contains("need more"));
        assert!(Term::from_name("magnus").is_err());
        // The scaled model at 1 is the model.
        let one = Scaled {
            inner: &cfg.aero,
            drag: 1.0,
            lift: 1.0,
            moment: 1.0,
        };
        let ls = launches();
        let (a, b) = (fly(&cfg, &ls), fly_with(&cfg, &one, &ls));
        for (a, b) in a.iter().zip(&b) {
            let (a, b) = (a.as_ref().unwrap(), b.as_ref().unwrap());
            assert!((a.carry_m - b.carry_m).abs() < 1e-9, "{a:?} {b:?}");
        }
    }
}
