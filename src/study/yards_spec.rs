//! The `[yards]` table of a study file: judge the design in yards (impact, then ball flight).
//!
//! ```toml
//! [yards]
//! static_loft_deg = 10.5          # address loft: the vertical axis of the MOI limit
//! confidence = 0.95               # dispersion ellipse
//! model = "fmm2022"               # aerodynamic model (optional, this default; as `smash flight --aero`)
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

use std::path::Path;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::design::DiscretionaryMass;
use super::yards::{HeadConstraints, YardGoal};
use crate::club::ClubSpec;
use crate::data::{DataError, TomlDoc};
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
    /// Aerodynamic model name (`fmm2022`, the default, `fmm2022-tour`, `fmm2022-re`, `nathan-lyu`; tables are not accepted here).
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

#[derive(Deserialize, Serialize)]
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

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawMass {
    mass_g: Spanned<f64>,
    #[serde(deserialize_with = "crate::data::toml_check::exact")]
    at_mm: Spanned<[f64; 3]>,
    #[serde(deserialize_with = "crate::data::toml_check::exact")]
    bounds_mm: Spanned<[[f64; 2]; 3]>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawOptimise {
    goal: Spanned<String>,
    max_iters: Option<Spanned<i64>>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawConstraints {
    #[serde(default, deserialize_with = "crate::data::toml_check::exact_opt")]
    mass_g: Option<Spanned<[f64; 2]>>,
    moi_vertical_max_gcm2: Option<Spanned<f64>>,
    #[serde(default, deserialize_with = "crate::data::toml_check::exact_opt")]
    com_box_mm: Option<Spanned<[[f64; 2]; 3]>>,
}

const GOALS: [(&str, YardGoal); 2] = [
    ("max_mean_carry", YardGoal::MaxMeanCarry),
    ("min_dispersion", YardGoal::MinDispersion),
];

/// Parse the `[yards]` table of a study file, if it has one. `has_distribution`: whether the
/// study has a `[distribution]` (the robust metrics need it).
pub fn parse_yards(
    path: &Path,
    text: &str,
    club: &ClubSpec,
    has_distribution: bool,
) -> Result<Option<YardsSpec>, DataError> {
    let doc = TomlDoc::new(path, text);
    // The whole file already parsed as TOML (the study parser ran first), so an error here is
    // in the `[yards]` table's own keys or types.
    let outer: Outer = toml::from_str(text).map_err(|e| {
        let at = e.span().unwrap_or(0..0);
        let key = crate::data::toml_check::key_at(text, at.start)
            .filter(|k| k.starts_with("yards"))
            .unwrap_or_else(|| "yards".to_owned());
        doc.err(
            at,
            &key,
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
    if !has_distribution {
        return Err(doc.err(
            raw.span(),
            "yards",
            "needs the study's [distribution] table (the swing and impact scatter of the robust \
             carry and dispersion metrics)",
        ));
    }
    let raw = raw.into_inner();
    let loft = *raw.static_loft_deg.get_ref();
    if !(loft > 0.0 && loft < 90.0) {
        return Err(doc.err(
            raw.static_loft_deg.span(),
            "yards.static_loft_deg",
            format!(
                "must be in (0, 90) degrees, got {}",
                crate::limits::fmt_value(loft)
            ),
        ));
    }
    let confidence = match &raw.confidence {
        Some(c) if !(*c.get_ref() > 0.0 && *c.get_ref() < 1.0) => {
            return Err(doc.err(
                c.span(),
                "yards.confidence",
                format!(
                    "must be in (0, 1) (e.g. 0.95), got {}",
                    crate::limits::fmt_value(*c.get_ref())
                ),
            ))
        }
        Some(c) => *c.get_ref(),
        None => DEFAULT_CONFIDENCE,
    };
    let model = match &raw.model {
        Some(m) => {
            let names = crate::flight::aero::MODEL_NAMES;
            let allowed: Vec<(&str, &str)> = names.iter().map(|n| (*n, *n)).collect();
            doc.one_of(
                m.span(),
                "yards.model",
                "aerodynamic model",
                m.get_ref(),
                &allowed,
            )?
            .to_owned()
        }
        None => crate::flight::aero::MODEL_NAMES[0].into(),
    };
    let atmosphere = match &raw.atmosphere {
        Some(a) => {
            let atm = *a.get_ref();
            atm.air()
                .map_err(|e| doc.err(a.span(), "yards.atmosphere", e.to_string()))?;
            atm
        }
        None => Atmosphere::default(),
    };
    let mass = raw
        .mass
        .as_ref()
        .map(|m| parse_mass(&doc, m.get_ref(), club))
        .transpose()?;
    let optimise = match &raw.optimise {
        None => None,
        Some(o) => Some(parse_optimise(&doc, o, mass.is_some())?),
    };
    let constraints = parse_constraints(&doc, raw.constraints.as_ref(), loft)?;
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

fn parse_mass(
    doc: &TomlDoc<'_>,
    m: &RawMass,
    club: &ClubSpec,
) -> Result<(DiscretionaryMass, [[f64; 2]; 3]), DataError> {
    let mg = *m.mass_g.get_ref();
    limits::check_head_part_mass_g("the movable mass", mg, club.nominal.club_mass_kg)
        .map_err(|e| doc.err(m.mass_g.span(), "yards.mass.mass_g", e))?;
    let at = doc.each_ranged(&m.at_mm, "yards.mass.at_mm", limits::CLUB_COM_MM)?;
    limits::check_behind_face_mm("the discretionary mass", at[0])
        .map_err(|e| doc.err(m.at_mm.span(), "yards.mass.at_mm", e))?;
    let b = *m.bounds_mm.get_ref();
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        let [lo, hi] = b[k];
        if !(lo.is_finite() && hi.is_finite() && lo <= 0.0 && 0.0 <= hi && lo < hi) {
            return Err(doc.err(
                m.bounds_mm.span(),
                "yards.mass.bounds_mm",
                format!(
                    "the {axis} bounds [{lo}, {hi}] mm must be finite, lower < upper, and \
                     contain 0 (the base design)"
                ),
            ));
        }
    }
    limits::check_behind_face_mm(
        "the discretionary mass at its upper x bound",
        at[0] + b[0][1],
    )
    .map_err(|e| doc.err(m.bounds_mm.span(), "yards.mass.bounds_mm", e))?;
    let mass = DiscretionaryMass {
        mass_kg: g(mg),
        at_m: Vector3::new(mm(at[0]), mm(at[1]), mm(at[2])),
    };
    Ok((mass, b))
}

fn parse_optimise(
    doc: &TomlDoc<'_>,
    o: &Spanned<RawOptimise>,
    has_mass: bool,
) -> Result<(YardGoal, u64), DataError> {
    let r = o.get_ref();
    let goal = doc.one_of(
        r.goal.span(),
        "yards.optimise.goal",
        "goal",
        r.goal.get_ref(),
        &GOALS,
    )?;
    let iters = match &r.max_iters {
        Some(n) => doc.count(n, "yards.optimise.max_iters", (1, 10_000))? as u64,
        None => DEFAULT_MAX_ITERS,
    };
    if !has_mass {
        return Err(doc.err(
            o.span(),
            "yards.optimise",
            "needs [yards.mass] (the discretionary mass it moves)",
        ));
    }
    Ok((goal, iters))
}

fn parse_constraints(
    doc: &TomlDoc<'_>,
    c: Option<&Spanned<RawConstraints>>,
    loft_deg: f64,
) -> Result<HeadConstraints, DataError> {
    let mut constraints = HeadConstraints {
        mass_g: None,
        moi_vertical_max_gcm2: None,
        loft_deg,
        com_box_mm: None,
    };
    let Some(c) = c.map(Spanned::get_ref) else {
        return Ok(constraints);
    };
    if let Some(m) = &c.mass_g {
        let [lo, hi] = *m.get_ref();
        if !(lo > 0.0 && lo < hi && hi.is_finite()) {
            return Err(doc.err(
                m.span(),
                "yards.constraints.mass_g",
                format!("must be [min, max] g with 0 < min < max, got [{lo}, {hi}]"),
            ));
        }
        constraints.mass_g = Some([lo, hi]);
    }
    if let Some(m) = &c.moi_vertical_max_gcm2 {
        constraints.moi_vertical_max_gcm2 = Some(doc.positive(
            m,
            "yards.constraints.moi_vertical_max_gcm2",
            "g·cm²; the Rules limit for woods is 5900 + 100 tolerance",
        )?);
    }
    if let Some(b) = &c.com_box_mm {
        let bx = *b.get_ref();
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let [lo, hi] = bx[k];
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(doc.err(
                    b.span(),
                    "yards.constraints.com_box_mm",
                    format!("the {axis} range [{lo}, {hi}] mm must be finite with min < max"),
                ));
            }
        }
        constraints.com_box_mm = Some(bx);
    }
    Ok(constraints)
}

/// The `[yards]` table as a study-file value (every default written out), for the resolved
/// `study.toml`.
pub fn yards_value(y: &YardsSpec) -> toml::Value {
    let sp = |x| Spanned::new(0..0, x);
    let c = &y.constraints;
    let has_constraints =
        c.mass_g.is_some() || c.moi_vertical_max_gcm2.is_some() || c.com_box_mm.is_some();
    let raw = RawYards {
        static_loft_deg: sp(y.static_loft_deg),
        confidence: Some(sp(y.confidence)),
        model: Some(Spanned::new(0..0, y.model.clone())),
        atmosphere: Some(Spanned::new(0..0, y.atmosphere)),
        mass: y.mass.as_ref().map(|(m, b)| {
            let at = m.at_m * 1e3;
            Spanned::new(
                0..0,
                RawMass {
                    mass_g: sp(m.mass_kg * 1e3),
                    at_mm: Spanned::new(0..0, [at.x, at.y, at.z]),
                    bounds_mm: Spanned::new(0..0, *b),
                },
            )
        }),
        optimise: y.optimise.map(|(goal, iters)| {
            let name = GOALS
                .iter()
                .find(|(_, g)| *g == goal)
                .map_or("", |(n, _)| n);
            Spanned::new(
                0..0,
                RawOptimise {
                    goal: Spanned::new(0..0, name.to_owned()),
                    max_iters: Some(Spanned::new(0..0, iters as i64)),
                },
            )
        }),
        constraints: has_constraints.then(|| {
            Spanned::new(
                0..0,
                RawConstraints {
                    mass_g: c.mass_g.map(|v| Spanned::new(0..0, v)),
                    moi_vertical_max_gcm2: c.moi_vertical_max_gcm2.map(sp),
                    com_box_mm: c.com_box_mm.map(|v| Spanned::new(0..0, v)),
                },
            )
        }),
    };
    toml::Value::try_from(raw).expect("a resolved [yards] table is plain TOML data")
}
