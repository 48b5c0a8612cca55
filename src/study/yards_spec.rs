//! The `[yards]` table of a study file: judge the design in yards (impact, then ball flight).
//!
//! ```toml
//! [yards]
//! static_loft_deg = 10.5          # address loft: the vertical axis of the MOI limit
//! confidence = 0.95               # dispersion ellipse
//! model = "fmm2022"               # aerodynamic model (optional; as `smash flight --model`)
//! [yards.atmosphere]              # as `smash flight --atmosphere` (optional; default ISA sea level)
//! temperature_c = 20.0
//! [yards.mass]                    # the discretionary mass the optimiser moves
//! mass_g = 12.0
//! at_mm = [-70.0, -10.0, 0.0]
//! bounds_mm = [[-20.0, 40.0], [-5.0, 10.0], [-35.0, 35.0]]
//! [yards.optimise]                # optional: without it the base design is only evaluated
//! goal = "max_mean_carry"         # or "min_dispersion"
//! max_iters = 60
//! [yards.constraints]             # each optional
//! mass_g = [200.0, 210.0]
//! moi_vertical_max_gcm2 = 6000.0  # Rules of Golf 5900 + 100 test tolerance
//! com_box_mm = [[-45.0, -38.0], [-2.0, 5.0], [-3.0, 5.0]]
//! ```
//!
//! The swing, the distribution of swings and impacts, and the face grid are the study's own
//! `[delivery]`, `[distribution]` (required with `[yards]`) and `[grid]`. Parsed here, on its own,
//! so the rest of the study file's parser does not know about it; errors name the file, line and
//! key like the rest of the study file.

use std::fmt::Write as _;
use std::path::Path;

use nalgebra::Vector3;
use serde::Deserialize;
use toml::Spanned;

use super::design::DiscretionaryMass;
use super::yards::{HeadConstraints, YardGoal};
use crate::club::ClubSpec;
use crate::data::{toml_key_error, DataError};
use crate::flight::{AeroModel, Atmosphere};
use crate::limits;
use crate::units::{g, mm};

/// Default confidence level of the dispersion ellipse.
pub const DEFAULT_CONFIDENCE: f64 = 0.95;
/// Default optimiser iterations.
pub const DEFAULT_MAX_ITERS: u64 = 60;

/// The resolved `[yards]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct YardsSpec {
    /// Static loft at address, degrees (finds the vertical axis of the MOI limit).
    pub static_loft_deg: f64,
    /// Confidence level of the dispersion ellipse, in (0, 1).
    pub confidence: f64,
    /// Aerodynamic model name (`fmm2022`, `nathan-lyu`; tables are not accepted here).
    pub model: String,
    /// The air.
    pub atmosphere: Atmosphere,
    /// The movable mass and the bounds of its move along x, y, z of F, mm.
    pub mass: Option<(DiscretionaryMass, [[f64; 2]; 3])>,
    /// Optimiser goal and iterations (needs `mass`).
    pub optimise: Option<(YardGoal, u64)>,
    /// Constraints (reported at the base and the optimum; the optimiser rejects breaches).
    pub constraints: HeadConstraints,
}

impl YardsSpec {
    /// The aerodynamic model.
    pub fn aero(&self) -> AeroModel {
        AeroModel::from_name(&self.model).expect("checked when parsed")
    }
}

#[derive(Deserialize)]
struct Outer {
    yards: Option<Spanned<RawYards>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawYards {
    static_loft_deg: Spanned<f64>,
    confidence: Option<Spanned<f64>>,
    model: Option<Spanned<String>>,
    atmosphere: Option<Spanned<Atmosphere>>,
    mass: Option<Spanned<RawMass>>,
    optimise: Option<Spanned<RawOptimise>>,
    constraints: Option<Spanned<RawConstraints>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMass {
    mass_g: Spanned<f64>,
    at_mm: Spanned<[f64; 3]>,
    bounds_mm: Spanned<[[f64; 2]; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOptimise {
    goal: Spanned<String>,
    max_iters: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConstraints {
    mass_g: Option<Spanned<[f64; 2]>>,
    moi_vertical_max_gcm2: Option<Spanned<f64>>,
    com_box_mm: Option<Spanned<[[f64; 2]; 3]>>,
}

/// Parse the `[yards]` table of a study file, if it has one. `has_distribution`: whether the
/// study has a `[distribution]` (the robust metrics need it).
pub fn parse_yards(
    path: &Path,
    text: &str,
    club: &ClubSpec,
    has_distribution: bool,
) -> Result<Option<YardsSpec>, DataError> {
    let err = |span: std::ops::Range<usize>, key: &str, msg: String| {
        toml_key_error(path, text, span.start, key, msg)
    };
    // The whole file already parsed as TOML (the study parser ran first), so an error here is
    // in the `[yards]` table's own keys or types.
    let outer: Outer = toml::from_str(text).map_err(|e| {
        let at = e.span().map_or(0, |s| s.start);
        toml_key_error(
            path,
            text,
            at,
            "yards",
            format!(
                "{} (the [yards] table has static_loft_deg, confidence, model and the tables \
                 atmosphere, mass, optimise, constraints; see configs/README.md)",
                e.message()
            ),
        )
    })?;
    let Some(raw) = outer.yards else {
        return Ok(None);
    };
    let span = raw.span();
    let raw = raw.into_inner();
    if !has_distribution {
        return Err(err(
            span,
            "yards",
            "needs the study's [distribution] table (the swing and impact scatter of the robust \
             carry and dispersion metrics)"
                .into(),
        ));
    }
    let loft = *raw.static_loft_deg.get_ref();
    if !(loft > 0.0 && loft < 90.0) {
        return Err(err(
            raw.static_loft_deg.span(),
            "yards.static_loft_deg",
            format!("must be in (0, 90) degrees, got {loft}"),
        ));
    }
    let confidence = match &raw.confidence {
        Some(c) => {
            let v = *c.get_ref();
            if !(v > 0.0 && v < 1.0) {
                return Err(err(
                    c.span(),
                    "yards.confidence",
                    format!("must be in (0, 1) (e.g. 0.95), got {v}"),
                ));
            }
            v
        }
        None => DEFAULT_CONFIDENCE,
    };
    let model = match &raw.model {
        Some(m) => {
            let name = m.get_ref().clone();
            if !crate::flight::aero::MODEL_NAMES.contains(&name.as_str()) {
                return Err(err(
                    m.span(),
                    "yards.model",
                    format!("unknown aerodynamic model '{name}' (allowed: fmm2022, nathan-lyu)"),
                ));
            }
            name
        }
        None => "fmm2022".into(),
    };
    let atmosphere = match &raw.atmosphere {
        Some(a) => {
            let atm = *a.get_ref();
            atm.air()
                .map_err(|e| err(a.span(), "yards.atmosphere", e.to_string()))?;
            atm
        }
        None => Atmosphere::default(),
    };
    let mass = match &raw.mass {
        None => None,
        Some(m) => {
            let m = m.get_ref();
            let mg = *m.mass_g.get_ref();
            let head_g = club.nominal.club_mass_kg * 1e3;
            if !(mg > 0.0 && mg < head_g) {
                return Err(err(
                    m.mass_g.span(),
                    "yards.mass.mass_g",
                    format!("must be > 0 and below the head mass {head_g} g, got {mg}"),
                ));
            }
            let at = *m.at_mm.get_ref();
            for x in at {
                limits::CLUB_COM_MM
                    .check(x)
                    .map_err(|msg| err(m.at_mm.span(), "yards.mass.at_mm", msg))?;
            }
            let b = *m.bounds_mm.get_ref();
            for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                let [lo, hi] = b[k];
                if !(lo.is_finite() && hi.is_finite() && lo <= 0.0 && 0.0 <= hi && lo < hi) {
                    return Err(err(
                        m.bounds_mm.span(),
                        "yards.mass.bounds_mm",
                        format!(
                            "the {axis} bounds [{lo}, {hi}] mm must be finite, lower < upper, \
                             and contain 0 (the base design)"
                        ),
                    ));
                }
            }
            Some((
                DiscretionaryMass {
                    mass_kg: g(mg),
                    at_m: Vector3::new(mm(at[0]), mm(at[1]), mm(at[2])),
                },
                b,
            ))
        }
    };
    let optimise = match &raw.optimise {
        None => None,
        Some(o) => {
            let o_span = o.span();
            let o = o.get_ref();
            let goal = match o.goal.get_ref().as_str() {
                "max_mean_carry" => YardGoal::MaxMeanCarry,
                "min_dispersion" => YardGoal::MinDispersion,
                other => {
                    return Err(err(
                        o.goal.span(),
                        "yards.optimise.goal",
                        format!("unknown goal '{other}' (allowed: max_mean_carry, min_dispersion)"),
                    ))
                }
            };
            let iters = match &o.max_iters {
                Some(n) => {
                    let v = *n.get_ref();
                    if !(1..=10_000).contains(&v) {
                        return Err(err(
                            n.span(),
                            "yards.optimise.max_iters",
                            format!("must be 1 to 10000, got {v}"),
                        ));
                    }
                    v as u64
                }
                None => DEFAULT_MAX_ITERS,
            };
            if mass.is_none() {
                return Err(err(
                    o_span,
                    "yards.optimise",
                    "needs [yards.mass] (the discretionary mass it moves)".into(),
                ));
            }
            Some((goal, iters))
        }
    };
    let mut constraints = HeadConstraints {
        mass_g: None,
        moi_vertical_max_gcm2: None,
        loft_deg: loft,
        com_box_mm: None,
    };
    if let Some(c) = &raw.constraints {
        let c = c.get_ref();
        if let Some(m) = &c.mass_g {
            let [lo, hi] = *m.get_ref();
            if !(lo > 0.0 && lo < hi && hi.is_finite()) {
                return Err(err(
                    m.span(),
                    "yards.constraints.mass_g",
                    format!("must be [min, max] g with 0 < min < max, got [{lo}, {hi}]"),
                ));
            }
            constraints.mass_g = Some([lo, hi]);
        }
        if let Some(m) = &c.moi_vertical_max_gcm2 {
            let v = *m.get_ref();
            if !(v > 0.0 && v.is_finite()) {
                return Err(err(
                    m.span(),
                    "yards.constraints.moi_vertical_max_gcm2",
                    format!(
                        "must be a finite number > 0 g·cm² (the Rules limit for woods is 5900 + \
                         100 tolerance), got {v}"
                    ),
                ));
            }
            constraints.moi_vertical_max_gcm2 = Some(v);
        }
        if let Some(b) = &c.com_box_mm {
            let bx = *b.get_ref();
            for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                let [lo, hi] = bx[k];
                if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                    return Err(err(
                        b.span(),
                        "yards.constraints.com_box_mm",
                        format!("the {axis} range [{lo}, {hi}] mm must be finite with min < max"),
                    ));
                }
            }
            constraints.com_box_mm = Some(bx);
        }
    }
    Ok(Some(YardsSpec {
        static_loft_deg: loft,
        confidence,
        model,
        atmosphere,
        mass,
        optimise,
        constraints,
    }))
}

/// The `[yards]` table as study-file text (every default written out), for the resolved
/// `study.toml`.
pub fn yards_toml(y: &YardsSpec) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "\n[yards]");
    let _ = writeln!(t, "static_loft_deg = {:?}", y.static_loft_deg);
    let _ = writeln!(t, "confidence = {:?}", y.confidence);
    let _ = writeln!(t, "model = {}", toml::Value::String(y.model.clone()));
    let a = &y.atmosphere;
    let _ = writeln!(t, "\n[yards.atmosphere]");
    let _ = writeln!(t, "temperature_c = {:?}", a.temperature_c);
    if let Some(p) = a.pressure_hpa {
        let _ = writeln!(t, "pressure_hpa = {p:?}");
    }
    if let Some(e) = a.elevation_m {
        let _ = writeln!(t, "elevation_m = {e:?}");
    }
    let _ = writeln!(t, "humidity_pct = {:?}", a.humidity_pct);
    let _ = writeln!(t, "wind_speed_m_s = {:?}", a.wind_speed_m_s);
    let _ = writeln!(t, "wind_direction_deg = {:?}", a.wind_direction_deg);
    let _ = writeln!(t, "wind_height_m = {:?}", a.wind_height_m);
    let _ = writeln!(t, "roughness_m = {:?}", a.roughness_m);
    if let Some((m, b)) = &y.mass {
        let _ = writeln!(t, "\n[yards.mass]");
        let _ = writeln!(t, "mass_g = {:?}", m.mass_kg * 1e3);
        let at = m.at_m * 1e3;
        let _ = writeln!(t, "at_mm = [{:?}, {:?}, {:?}]", at[0], at[1], at[2]);
        let _ = writeln!(
            t,
            "bounds_mm = [[{:?}, {:?}], [{:?}, {:?}], [{:?}, {:?}]]",
            b[0][0], b[0][1], b[1][0], b[1][1], b[2][0], b[2][1]
        );
    }
    if let Some((goal, iters)) = &y.optimise {
        let _ = writeln!(t, "\n[yards.optimise]");
        let g = match goal {
            YardGoal::MaxMeanCarry => "max_mean_carry",
            YardGoal::MinDispersion => "min_dispersion",
        };
        let _ = writeln!(t, "goal = \"{g}\"");
        let _ = writeln!(t, "max_iters = {iters}");
    }
    let c = &y.constraints;
    if c.mass_g.is_some() || c.moi_vertical_max_gcm2.is_some() || c.com_box_mm.is_some() {
        let _ = writeln!(t, "\n[yards.constraints]");
        if let Some([lo, hi]) = c.mass_g {
            let _ = writeln!(t, "mass_g = [{lo:?}, {hi:?}]");
        }
        if let Some(v) = c.moi_vertical_max_gcm2 {
            let _ = writeln!(t, "moi_vertical_max_gcm2 = {v:?}");
        }
        if let Some(b) = c.com_box_mm {
            let _ = writeln!(
                t,
                "com_box_mm = [[{:?}, {:?}], [{:?}, {:?}], [{:?}, {:?}]]",
                b[0][0], b[0][1], b[1][0], b[1][1], b[2][0], b[2][1]
            );
        }
    }
    t
}
