//! Aerodynamic coefficient models: drag `C_D`, lift `C_L` and spin-decay moment `C_M` of a
//! golf ball as functions of the spin factor `S = R·|ω|/|v|` and the Reynolds number
//! `Re = ρ·|v|·2R/μ` (air-relative speed).
//!
//! Forces and moment use the frontal area `A = πR²` and dynamic pressure `q = ½ρ|v|²`:
//! drag `q·A·C_D` against the air-relative velocity, lift `q·A·C_L` along `ω × v`, and a moment
//! `q·A·2R·C_M` against the spin.
//!
//! Built in, selected by name:
//! - `fmm2022`: Ferguson, McNally & McPhee (2022), "Predicting the flight of a golf
//!   ball: comparing a physics-based aerodynamic model to a neural network", ISEA 2022
//!   (Engineering of Sport 14), Purdue University, doi:10.5703/1288284317493. Quadratics in `S`
//!   fitted (with the moment coefficient) to GCQuad launch and FlightScope X3 carry, apex and
//!   offline of 1,040 shots of a 2021 Titleist Pro V1, driver to wedge, launch `S` 0.02–0.75.
//!   No Reynolds dependence. `S` is held at the end of the fitted range beyond it.
//! - `fmm2022-re` (default): `fmm2022` with its drag split into a spin part and a low-Reynolds
//!   part, `C_D = C_D,fmm(S) − 0.20·S + 0.20·r(Re)` with `r` = 1 below `Re` = 4·10⁴ falling
//!   smoothly to 0 at `Re` = 1.5·10⁵; lift and moment as `fmm2022` ([`Fmm2022Re`]). The
//!   constants are fitted to TrackMan's 2023 LPGA Tour averages, not to the PGA Tour table it
//!   is validated on (`examples/trackman_refit.rs` reproduces the fit).
//! - `nathan-lyu`: a Reynolds-dependent law with a drag crisis: `C_D` 0.500 below
//!   `Re` = 5·10⁴ falling linearly to 0.212 at `Re` = 10⁵ (and above), plus 0.15·`S`;
//!   `C_L = 1.99·S − 3.25·S²` up to `S` = 0.3, 0.305 above. This is the form of A. M. Nathan's
//!   golf trajectory calculator (University of Illinois) and of the libgolf C++ library, built
//!   on the still-air measurements of B. Lyu, J. Kensrud et al., "Aerodynamics of golf balls in
//!   still air", Proceedings 2 (2018) 238 (ISEA 2018). Moment as Smits & Smith below.
//! - a table (`table:PATH`): the user's own `C_D`, `C_L` (and optionally `C_M`) at spin factors
//!   (and optionally Reynolds numbers), CSV, interpolated linearly ([`TableModel`]).
//!
//! Where a model has no moment law of its own, `C_M = 0.01·S`: the moment coefficient of
//! A. J. Smits & D. R. Smith, "A new aerodynamic model of a golf ball in flight", Science and
//! Golf II (1994) 340–347, which is also where Ferguson et al.'s fit settled (their lower
//! bound).

use std::path::Path;

use crate::lanes::{V, W};

/// Drag, lift and moment coefficients (dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// Drag coefficient.
    pub cd: f64,
    /// Lift coefficient.
    pub cl: f64,
    /// Spin-decay moment coefficient.
    pub cm: f64,
}

/// A coefficient model: `(S, Re) → (C_D, C_L, C_M)`. Implement [`coefficients`] for a new
/// model; [`coefficients_v`] (the lanes form the batched integrator calls) defaults to it lane
/// by lane.
///
/// [`coefficients`]: CoefficientModel::coefficients
/// [`coefficients_v`]: CoefficientModel::coefficients_v
pub trait CoefficientModel: Send + Sync {
    /// Coefficients at spin factor `s` and Reynolds number `re`.
    fn coefficients(&self, s: f64, re: f64) -> Coefficients;

    /// Whether the coefficients depend on `re` (if not, the integrator skips computing it).
    fn uses_reynolds(&self) -> bool {
        true
    }

    /// The same, [`W`] lanes at once: `(C_D, C_L, C_M)`.
    #[inline(always)]
    fn coefficients_v(&self, s: V, re: V) -> (V, V, V) {
        let (mut cd, mut cl, mut cm) = ([0.0; W], [0.0; W], [0.0; W]);
        for i in 0..W {
            let c = self.coefficients(s.0[i], re.0[i]);
            cd[i] = c.cd;
            cl[i] = c.cl;
            cm[i] = c.cm;
        }
        (V(cd), V(cl), V(cm))
    }
}

/// Smits & Smith (1994) moment coefficient per unit spin factor (dimensionless).
pub const SMITS_SMITH_CM_PER_S: f64 = 0.01;

/// Ferguson, McNally & McPhee (2022) quadratics (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Fmm2022;

impl Fmm2022 {
    /// `C_D = a + b·S + c·S²` (their constants a, b, c).
    pub const CD: [f64; 3] = [0.1304, 0.9287, -0.8259];
    /// `C_L = d + e·S + f·S²` (their constants d, e, f).
    pub const CL: [f64; 3] = [0.0504, 1.2031, -1.1490];
    /// `C_M = g·S` (their constant g).
    pub const CM_PER_S: f64 = 0.01;
    /// Upper end of the fitted spin factors (their wedge launches); `S` is held here beyond.
    pub const S_MAX: f64 = 0.75;
}

impl CoefficientModel for Fmm2022 {
    #[inline]
    fn coefficients(&self, s: f64, _re: f64) -> Coefficients {
        let s = s.min(Self::S_MAX);
        Coefficients {
            cd: Self::CD[0] + s * (Self::CD[1] + s * Self::CD[2]),
            cl: Self::CL[0] + s * (Self::CL[1] + s * Self::CL[2]),
            cm: Self::CM_PER_S * s,
        }
    }

    fn uses_reynolds(&self) -> bool {
        false
    }

    #[inline(always)]
    fn coefficients_v(&self, s: V, _re: V) -> (V, V, V) {
        let cap = V::splat(Self::S_MAX);
        let s = s.gt(cap).select(cap, s);
        (
            Self::CD[0] + s * (Self::CD[1] + s * Self::CD[2]),
            Self::CL[0] + s * (Self::CL[1] + s * Self::CL[2]),
            Self::CM_PER_S * s,
        )
    }
}

/// [`Fmm2022`] with a low-Reynolds drag rise (the `fmm2022-re` model, the default).
///
/// Why: every ball lands at `Re` ≈ 5–8·10⁴, where dimpled balls' drag rises as the flow
/// nears the drag crisis (P. W. Bearman & J. K. Harvey, "Golf ball aerodynamics", Aeronautical
/// Quarterly 27 (1976) 112–122; B. Lyu, J. Kensrud et al., ISEA 2018, Proceedings 2, 238).
/// `fmm2022` has no Reynolds term, so its steep drag slope in spin factor (0.93 per unit `S`,
/// where still-air measurements give about 0.15) stands in for it: high `S` and low speed come
/// together late in flight. Here part of that slope is moved onto `Re`:
/// `C_D = C_D,fmm(S) + DS·S + DR·r(Re)`, with `r = 3t² − 2t³` (a smoothstep, so that the
/// force has a continuous slope and fixed-step RK4 keeps its accuracy through the window) of
/// `t = clamp((RE_HIGH − Re)/(RE_HIGH − RE_LOW), 0, 1)`.
///
/// The constants are a least-squares fit (grid search over 1.3 million candidates: `DR`
/// 0–0.40 by 0.01, `DS` −0.40–0.40 by 0.05, a lift loss `C_L·(1 − LL·r)` with `LL` 0–1 by 0.05
/// that came out 0, `RE_LOW` 2–8·10⁴ and `RE_HIGH` 8·10⁴–2·10⁵ by 10⁴; the optimum is inside
/// the grid) to the 11 rows of TrackMan's 2023 LPGA Tour averages
/// ([`super::trackman::LPGA_TOUR_2023`]; ball speeds 88–143 mph, so lower Reynolds numbers than
/// the PGA rows), in the default atmosphere, minimising Σ (carry error %)² + (land-angle error
/// °/2)² + (apex error yd/2)². The PGA Tour table is not used by the fit; it validates it
/// (README, "Ball flight"). `examples/trackman_refit.rs` repeats the fit and
/// `tests/flight.rs` checks these constants are a minimum of that objective.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Fmm2022Re;

impl Fmm2022Re {
    /// `DR`: drag added below [`Self::RE_LOW`] (fitted, see the type documentation).
    pub const CD_LOW_RE: f64 = 0.20;
    /// `DS`: change of the drag slope per unit spin factor (fitted).
    pub const CD_PER_S: f64 = -0.20;
    /// Reynolds number below which the whole rise applies (fitted).
    pub const RE_LOW: f64 = 4.0e4;
    /// Reynolds number above which there is no rise (fitted).
    pub const RE_HIGH: f64 = 1.5e5;
}

impl CoefficientModel for Fmm2022Re {
    #[inline]
    fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        let mut c = Fmm2022.coefficients(s, re);
        let s = s.min(Fmm2022::S_MAX);
        let t = ((Self::RE_HIGH - re) / (Self::RE_HIGH - Self::RE_LOW)).clamp(0.0, 1.0);
        let r = t * t * (3.0 - 2.0 * t);
        c.cd += Self::CD_PER_S * s + Self::CD_LOW_RE * r;
        c
    }

    #[inline(always)]
    fn coefficients_v(&self, s: V, re: V) -> (V, V, V) {
        let (cd, cl, cm) = Fmm2022.coefficients_v(s, re);
        let cap = V::splat(Fmm2022::S_MAX);
        let s = s.gt(cap).select(cap, s);
        let t = (Self::RE_HIGH - re) * (1.0 / (Self::RE_HIGH - Self::RE_LOW));
        let (zero, one) = (V::splat(0.0), V::splat(1.0));
        let t = t.lt(zero).select(zero, t);
        let t = t.gt(one).select(one, t);
        let r = t * t * (3.0 - 2.0 * t);
        (cd + Self::CD_PER_S * s + Self::CD_LOW_RE * r, cl, cm)
    }
}

/// The Reynolds-dependent drag-crisis law (Nathan's calculator / libgolf, after Lyu et al.
/// 2018; see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NathanLyu;

impl NathanLyu {
    /// Sub-critical drag coefficient (below [`Self::RE_LOW`]).
    pub const CD_LOW: f64 = 0.500;
    /// Super-critical drag coefficient (above [`Self::RE_HIGH`]).
    pub const CD_HIGH: f64 = 0.212;
    /// Reynolds number where the drag crisis starts.
    pub const RE_LOW: f64 = 0.5e5;
    /// Reynolds number where it ends.
    pub const RE_HIGH: f64 = 1.0e5;
    /// Added drag per unit spin factor.
    pub const CD_PER_S: f64 = 0.15;
    /// Lift: `C_L = a·S + b·S²` up to [`Self::S_LIFT_MAX`].
    pub const CL: [f64; 2] = [1.99, -3.25];
    /// Spin factor above which lift is constant.
    pub const S_LIFT_MAX: f64 = 0.3;
    /// Lift above [`Self::S_LIFT_MAX`].
    pub const CL_MAX: f64 = 0.305;
}

impl CoefficientModel for NathanLyu {
    #[inline]
    fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        let t = ((re - Self::RE_LOW) / (Self::RE_HIGH - Self::RE_LOW)).clamp(0.0, 1.0);
        let cd = Self::CD_LOW + t * (Self::CD_HIGH - Self::CD_LOW) + Self::CD_PER_S * s;
        let cl = if s < Self::S_LIFT_MAX {
            s * (Self::CL[0] + s * Self::CL[1])
        } else {
            Self::CL_MAX
        };
        Coefficients {
            cd,
            cl,
            cm: SMITS_SMITH_CM_PER_S * s,
        }
    }

    #[inline(always)]
    fn coefficients_v(&self, s: V, re: V) -> (V, V, V) {
        let t = (re - Self::RE_LOW) * (1.0 / (Self::RE_HIGH - Self::RE_LOW));
        let (zero, one) = (V::splat(0.0), V::splat(1.0));
        let t = t.lt(zero).select(zero, t);
        let t = t.gt(one).select(one, t);
        let cd = Self::CD_LOW + t * (Self::CD_HIGH - Self::CD_LOW) + Self::CD_PER_S * s;
        let cl = s
            .lt(V::splat(Self::S_LIFT_MAX))
            .select(s * (Self::CL[0] + s * Self::CL[1]), V::splat(Self::CL_MAX));
        (cd, cl, SMITS_SMITH_CM_PER_S * s)
    }
}

/// One Reynolds-number slice of a table: spin factors ascending with their coefficients.
#[derive(Debug, Clone, PartialEq)]
struct Slice {
    re: f64,
    s: Vec<f64>,
    c: Vec<Coefficients>,
}

impl Slice {
    fn at(&self, s: f64) -> Coefficients {
        let n = self.s.len();
        if !(s > self.s[0]) {
            return self.c[0];
        }
        if s >= self.s[n - 1] {
            return self.c[n - 1];
        }
        let k = self.s.partition_point(|&x| x <= s) - 1;
        let f = (s - self.s[k]) / (self.s[k + 1] - self.s[k]);
        lerp(self.c[k], self.c[k + 1], f)
    }
}

fn lerp(a: Coefficients, b: Coefficients, f: f64) -> Coefficients {
    Coefficients {
        cd: a.cd + f * (b.cd - a.cd),
        cl: a.cl + f * (b.cl - a.cl),
        cm: a.cm + f * (b.cm - a.cm),
    }
}

/// A user's table of coefficients (CSV with a header): columns `spin_factor`, `cd`, `cl`, and
/// optionally `cm` (default Smits & Smith `0.01·S`) and `reynolds`. Without `reynolds` the
/// coefficients depend on `S` only. With it, rows are grouped by Reynolds number; the
/// coefficients are interpolated linearly in `S` within each Reynolds number and then linearly
/// in `Re` between the two nearest. Outside the tabulated range the end values are held (the
/// table's own range is reported by [`TableModel::describe`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TableModel {
    slices: Vec<Slice>,
    source: String,
}

impl TableModel {
    /// Read a table from a CSV file; errors name the file, line and column.
    pub fn from_path(path: &Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("{}: cannot read the coefficient table: {e}", path.display()))?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parse a table from CSV text; `source` names it in errors.
    pub fn parse(text: &str, source: &str) -> Result<Self, String> {
        let mut rdr = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        let headers = rdr.headers().map_err(|e| format!("{source}: {e}"))?.clone();
        let col = |name: &str| headers.iter().position(|h| h == name);
        for h in headers.iter() {
            if !["spin_factor", "reynolds", "cd", "cl", "cm"].contains(&h) {
                return Err(format!(
                    "{source}: unknown column '{h}' (allowed: spin_factor, reynolds, cd, cl, cm)"
                ));
            }
        }
        let need =
            |name: &str| col(name).ok_or_else(|| format!("{source}: missing column '{name}'"));
        let (is, icd, icl) = (need("spin_factor")?, need("cd")?, need("cl")?);
        let (icm, ire) = (col("cm"), col("reynolds"));
        let mut rows: Vec<(f64, f64, Coefficients)> = Vec::new();
        for (k, rec) in rdr.records().enumerate() {
            let line = k + 2;
            let rec = rec.map_err(|e| format!("{source}: line {line}: {e}"))?;
            let num = |i: usize, name: &str, lo: f64, hi: f64| -> Result<f64, String> {
                let t = rec.get(i).unwrap_or("");
                let v: f64 = t.parse().map_err(|_| {
                    format!("{source}: line {line}, column {name}: '{t}' is not a number")
                })?;
                if !(v >= lo && v <= hi) {
                    return Err(format!(
                        "{source}: line {line}, column {name}: {v} is outside [{lo}, {hi}]"
                    ));
                }
                Ok(v)
            };
            let s = num(is, "spin_factor", 0.0, 5.0)?;
            let re = match ire {
                Some(i) => num(i, "reynolds", 1.0, 1e7)?,
                None => 0.0,
            };
            let c = Coefficients {
                cd: num(icd, "cd", 0.0, 2.0)?,
                cl: num(icl, "cl", -1.0, 2.0)?,
                cm: match icm {
                    Some(i) => num(i, "cm", 0.0, 1.0)?,
                    None => SMITS_SMITH_CM_PER_S * s,
                },
            };
            rows.push((re, s, c));
        }
        if rows.is_empty() {
            return Err(format!("{source}: the coefficient table has no rows"));
        }
        rows.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        let mut slices: Vec<Slice> = Vec::new();
        for (re, s, c) in rows {
            match slices.last_mut() {
                Some(sl) if sl.re == re => {
                    if sl.s.last() == Some(&s) {
                        return Err(format!(
                            "{source}: spin_factor {s} appears twice{}",
                            if ire.is_some() {
                                format!(" at reynolds {re}")
                            } else {
                                String::new()
                            }
                        ));
                    }
                    sl.s.push(s);
                    sl.c.push(c);
                }
                _ => slices.push(Slice {
                    re,
                    s: vec![s],
                    c: vec![c],
                }),
            }
        }
        Ok(Self {
            slices,
            source: source.to_string(),
        })
    }

    /// One line: where the table came from and its range.
    pub fn describe(&self) -> String {
        let smin = self
            .slices
            .iter()
            .map(|s| s.s[0])
            .fold(f64::INFINITY, f64::min);
        let smax = self
            .slices
            .iter()
            .map(|s| s.s[s.s.len() - 1])
            .fold(f64::NEG_INFINITY, f64::max);
        if self.slices.len() > 1 {
            format!(
                "table {} (S {smin}–{smax}, Re {}–{})",
                self.source,
                self.slices[0].re,
                self.slices[self.slices.len() - 1].re
            )
        } else {
            format!("table {} (S {smin}–{smax})", self.source)
        }
    }
}

impl CoefficientModel for TableModel {
    fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        let n = self.slices.len();
        if n == 1 || !(re > self.slices[0].re) {
            return self.slices[0].at(s);
        }
        if re >= self.slices[n - 1].re {
            return self.slices[n - 1].at(s);
        }
        let k = self.slices.partition_point(|sl| sl.re <= re) - 1;
        let (a, b) = (&self.slices[k], &self.slices[k + 1]);
        lerp(a.at(s), b.at(s), (re - a.re) / (b.re - a.re))
    }

    fn uses_reynolds(&self) -> bool {
        self.slices.len() > 1
    }
}

/// A coefficient model chosen by name (what files and the command line select).
#[derive(Debug, Clone, PartialEq, Default)]
pub enum AeroModel {
    /// [`Fmm2022Re`] (the default).
    #[default]
    Fmm2022Re,
    /// [`Fmm2022`].
    Fmm2022,
    /// [`NathanLyu`].
    NathanLyu,
    /// A user's [`TableModel`].
    Table(std::sync::Arc<TableModel>),
}

/// Names of the built-in models.
pub const MODEL_NAMES: [&str; 3] = ["fmm2022-re", "fmm2022", "nathan-lyu"];

impl AeroModel {
    /// `fmm2022-re`, `fmm2022`, `nathan-lyu`, or `table:PATH` (a CSV file, see [`TableModel`]).
    pub fn from_name(name: &str) -> Result<Self, String> {
        match name {
            "fmm2022-re" => Ok(Self::Fmm2022Re),
            "fmm2022" => Ok(Self::Fmm2022),
            "nathan-lyu" => Ok(Self::NathanLyu),
            _ => match name.strip_prefix("table:") {
                Some(p) => Ok(Self::Table(std::sync::Arc::new(TableModel::from_path(
                    Path::new(p),
                )?))),
                None => Err(format!(
                    "unknown aerodynamic model '{name}' (allowed: fmm2022-re, fmm2022, nathan-lyu, table:PATH)"
                )),
            },
        }
    }

    /// The name as selected (tables: `table:` and a description).
    pub fn name(&self) -> String {
        match self {
            Self::Fmm2022Re => "fmm2022-re".into(),
            Self::Fmm2022 => "fmm2022".into(),
            Self::NathanLyu => "nathan-lyu".into(),
            Self::Table(t) => t.describe(),
        }
    }

    /// Coefficients (dispatching on the model; the integrator dispatches once per batch).
    pub fn coefficients(&self, s: f64, re: f64) -> Coefficients {
        match self {
            Self::Fmm2022Re => Fmm2022Re.coefficients(s, re),
            Self::Fmm2022 => Fmm2022.coefficients(s, re),
            Self::NathanLyu => NathanLyu.coefficients(s, re),
            Self::Table(t) => t.coefficients(s, re),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fmm_values_at_reference_points() {
        // Evaluated by hand from the published constants: S = 0.1 → C_D 0.215011, C_L 0.15922;
        // S = 0.5 → C_D 0.388275, C_L 0.3647.
        let c = Fmm2022.coefficients(0.1, 1e5);
        assert!((c.cd - 0.215_011).abs() < 1e-9 && (c.cl - 0.159_22).abs() < 1e-9);
        let c = Fmm2022.coefficients(0.5, 1e5);
        assert!((c.cd - 0.388_275).abs() < 1e-9 && (c.cl - 0.3647).abs() < 1e-9);
        // Held beyond the fitted range.
        assert_eq!(
            Fmm2022.coefficients(2.0, 0.0),
            Fmm2022.coefficients(0.75, 0.0)
        );
    }

    #[test]
    fn lanes_form_equals_scalar_form() {
        let s = V([0.0, 0.12, 0.31, 0.9]);
        let re = V([3e4, 7e4, 1.2e5, 2e5]);
        for m in [&Fmm2022 as &dyn CoefficientModel, &NathanLyu, &Fmm2022Re] {
            let (cd, cl, cm) = m.coefficients_v(s, re);
            for i in 0..W {
                let c = m.coefficients(s.0[i], re.0[i]);
                assert!((c.cd - cd.0[i]).abs() < 1e-15);
                assert!((c.cl - cl.0[i]).abs() < 1e-15);
                assert!((c.cm - cm.0[i]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn fmm2022_re_adds_drag_below_its_reynolds_window_only() {
        // Above Re 1.5e5 the drag is fmm2022's less 0.2·S; below 4e4, 0.2 more than that.
        for s in [0.05, 0.3, 0.6] {
            let (a, b) = (Fmm2022Re.coefficients(s, 2e5), Fmm2022.coefficients(s, 2e5));
            assert!((a.cd - (b.cd - 0.2 * s)).abs() < 1e-12 && a.cl == b.cl && a.cm == b.cm);
            let lo = Fmm2022Re.coefficients(s, 3e4);
            assert!((lo.cd - a.cd - 0.2).abs() < 1e-12);
            // Halfway through the window, half the rise; a quarter in, 0.84375 of it.
            let mid = Fmm2022Re.coefficients(s, 9.5e4);
            assert!((mid.cd - a.cd - 0.1).abs() < 1e-12);
            let q = Fmm2022Re.coefficients(s, 6.75e4);
            assert!((q.cd - a.cd - 0.2 * 0.843_75).abs() < 1e-12);
        }
    }

    #[test]
    fn nathan_drag_crisis() {
        assert_eq!(NathanLyu.coefficients(0.0, 4e4).cd, 0.5);
        assert!((NathanLyu.coefficients(0.0, 2e5).cd - 0.212).abs() < 1e-15);
        assert!((NathanLyu.coefficients(0.0, 0.75e5).cd - 0.356).abs() < 1e-12);
        assert_eq!(NathanLyu.coefficients(0.5, 2e5).cl, 0.305);
    }

    #[test]
    fn table_interpolates_and_reproduces_a_model() {
        // A table sampled from fmm2022 at fine S reproduces it between the nodes to the
        // interpolation error of a quadratic (h²/8·|f''| ≤ 2.9e-5 at h = 0.01).
        let mut csv = String::from("spin_factor,cd,cl,cm\n");
        for k in 0..=75 {
            let s = k as f64 * 0.01;
            let c = Fmm2022.coefficients(s, 0.0);
            csv.push_str(&format!("{s},{},{},{}\n", c.cd, c.cl, c.cm));
        }
        let t = TableModel::parse(&csv, "t.csv").unwrap();
        for s in [0.005, 0.237, 0.5, 0.749] {
            let (a, b) = (t.coefficients(s, 1e5), Fmm2022.coefficients(s, 1e5));
            assert!(
                (a.cd - b.cd).abs() < 4e-5 && (a.cl - b.cl).abs() < 4e-5,
                "{s}"
            );
        }
        assert!(!t.uses_reynolds());
        // Two Reynolds slices: halfway between them, halfway between their values.
        let t = TableModel::parse(
            "reynolds,spin_factor,cd,cl\n1e5,0,0.2,0.0\n1e5,1,0.4,0.4\n2e5,0,0.3,0.1\n2e5,1,0.5,0.5\n",
            "t2",
        )
        .unwrap();
        let c = t.coefficients(0.5, 1.5e5);
        assert!((c.cd - 0.35).abs() < 1e-12 && (c.cl - 0.25).abs() < 1e-12);
    }

    #[test]
    fn table_errors_name_line_and_column() {
        let e = TableModel::parse("spin_factor,cd,cl\n0.1,0.2,x\n", "t.csv").unwrap_err();
        assert!(e.contains("line 2") && e.contains("cl"), "{e}");
        let e = TableModel::parse("spin_factor,cd\n0.1,0.2\n", "t.csv").unwrap_err();
        assert!(e.contains("missing column 'cl'"), "{e}");
        let e = TableModel::parse("spin_factor,cd,cl,foo\n", "t.csv").unwrap_err();
        assert!(e.contains("unknown column 'foo'"), "{e}");
        let e = TableModel::parse("spin_factor,cd,cl\n0.1,-0.2,0\n", "t.csv").unwrap_err();
        assert!(e.contains("outside"), "{e}");
        assert!(AeroModel::from_name("magic").is_err());
    }
}
