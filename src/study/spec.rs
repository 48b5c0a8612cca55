//! Study files (TOML): what to sweep, summarise, differentiate and optimise.
//!
//! The format is documented in `configs/README.md` ("Design studies"). Parsing is strict:
//! unknown keys, wrong types and unphysical values are errors naming the file, line, key and
//! what is allowed. [`Study`] is the resolved study (every default filled in); [`resolved_toml`]
//! writes it back as a study file that parses to the same [`Study`], so a run can be repeated
//! from the `study.toml` written beside its outputs.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use nalgebra::Vector3;
use serde::Deserialize;
use toml::Spanned;

use super::design::{Design, DesignVar, DiscretionaryMass};
use super::distribution::{Distribution, Method, SwingSpec};
use super::metrics::{metric_names, Output};
use crate::club::ClubSpec;
use crate::data::club_file::read_club;
use crate::data::{parse_toml, read_text, toml_key_error, DataError, Num};
use crate::limits::{self, count_product, PhysicalRange};
use crate::units::{g, mm};

/// Values of one axis: an explicit list, or `count` evenly spaced values from `from` to `to`.
#[derive(Debug, Clone, PartialEq)]
pub enum Axis {
    /// Explicit values.
    List(Vec<f64>),
    /// `count` values from `from` to `to` inclusive (`count = 1` gives `from`).
    Range {
        /// First value.
        from: f64,
        /// Last value.
        to: f64,
        /// Number of values (≥ 1).
        count: usize,
    },
}

impl Axis {
    /// The values.
    pub fn values(&self) -> Vec<f64> {
        match self {
            Axis::List(v) => v.clone(),
            Axis::Range { from, to, count } => {
                if *count == 1 {
                    return vec![*from];
                }
                let n = (*count - 1) as f64;
                (0..*count)
                    .map(|i| {
                        if i + 1 == *count {
                            *to
                        } else {
                            from + (to - from) * (i as f64 / n)
                        }
                    })
                    .collect()
            }
        }
    }

    /// Number of values, without building them.
    pub fn len(&self) -> usize {
        match self {
            Axis::List(v) => v.len(),
            Axis::Range { count, .. } => *count,
        }
    }

    /// Whether the axis has no values (never, once parsed).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn to_toml(&self) -> String {
        match self {
            Axis::List(v) => {
                let items: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
                format!("[{}]", items.join(", "))
            }
            Axis::Range { from, to, count } => {
                format!("{{ from = {from:?}, to = {to:?}, count = {count} }}")
            }
        }
    }
}

/// The grid of impact locations, mm in the CoF tangent plane.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Heights up the face (rows), strictly ascending.
    pub y_mm: Axis,
    /// Positions toward the toe (columns), strictly ascending.
    pub z_mm: Axis,
}

/// The design variants: the cartesian product of the listed variable axes.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignSpace {
    /// Variable axes, in [`DesignVar::ALL`] order (the first is the outermost loop).
    pub axes: Vec<(DesignVar, Axis)>,
    /// The movable mass, when any `mass_*` variable is used.
    pub discretionary_mass: Option<DiscretionaryMass>,
}

impl DesignSpace {
    /// All variants, in order: the last axis varies fastest.
    pub fn variants(&self) -> Vec<Design> {
        let mut out = vec![Design::default()];
        for (var, axis) in &self.axes {
            let vals = axis.values();
            out = out
                .into_iter()
                .flat_map(|d| vals.iter().map(move |&x| d.with(*var, x)))
                .collect();
        }
        out
    }
}

/// Probe lines for the speed-retention and gear-effect summaries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    /// Half-length of each cross-section through the CoF, mm (> 0).
    pub half_width_mm: f64,
    /// Spacing of the probe points, mm (> 0, at most the half-width).
    pub step_mm: f64,
}

/// Minimise or maximise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Goal {
    /// Make the objective as small as possible.
    Minimise,
    /// Make the objective as large as possible.
    Maximise,
}

/// The design optimisation.
#[derive(Debug, Clone, PartialEq)]
pub struct OptimiseSpec {
    /// Direction.
    pub goal: Goal,
    /// Objective = Σ weight · metric, metrics by name (see `metrics`).
    pub objective: Vec<(String, f64)>,
    /// Design variables with their bounds `[lower, upper]` (the base design lies inside).
    pub bounds: Vec<(DesignVar, f64, f64)>,
    /// Largest number of Nelder–Mead iterations.
    pub max_iters: u64,
    /// Stop when the standard deviation of the simplex's objective values falls below this.
    pub tolerance: f64,
}

/// A resolved study.
#[derive(Debug, Clone)]
pub struct Study {
    /// Name (also the default output folder `results/<name>`).
    pub name: String,
    /// Base club file, absolute.
    pub club_path: PathBuf,
    /// The base club.
    pub club: ClubSpec,
    /// Group whose effects apply.
    pub group: String,
    /// Outputs to map.
    pub outputs: Vec<Output>,
    /// Output folder (relative to the working directory unless absolute).
    pub output_dir: PathBuf,
    /// The fixed swing used for the maps and summaries.
    pub swing: SwingSpec,
    /// Distribution of swings and impact locations, for `mean_*` and `std_*` metrics.
    pub distribution: Option<Distribution>,
    /// The face grid.
    pub grid: Grid,
    /// Design variants.
    pub design: DesignSpace,
    /// Sensitivities: variables and central-difference steps.
    pub sensitivity: Option<Vec<(DesignVar, f64)>>,
    /// Probe lines of the summaries.
    pub probe: Probe,
    /// Optimisation.
    pub optimise: Option<OptimiseSpec>,
    /// The study in yards (`[yards]`, see [`super::yards_spec`]).
    pub yards: Option<super::yards_spec::YardsSpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    study: RawHeader,
    delivery: RawDelivery,
    distribution: Option<Spanned<RawDistribution>>,
    grid: RawGrid,
    design: Option<BTreeMap<Spanned<String>, Spanned<toml::Value>>>,
    sensitivity: Option<Spanned<RawSensitivity>>,
    summary: Option<RawSummary>,
    optimise: Option<Spanned<RawOptimise>>,
    /// Parsed on its own by [`super::yards_spec`].
    #[allow(dead_code)]
    yards: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHeader {
    name: Spanned<String>,
    club: Spanned<String>,
    group: Option<Spanned<String>>,
    outputs: Option<Vec<Spanned<String>>>,
    output_dir: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDelivery {
    club_speed_mph: Spanned<f64>,
    dynamic_loft_deg: Spanned<f64>,
    attack_angle_deg: Option<Spanned<f64>>,
    club_path_deg: Option<Spanned<f64>>,
    face_angle_deg: Option<Spanned<f64>>,
    lie_tilt_deg: Option<Spanned<f64>>,
    club_omega_rad_s: Option<Spanned<[f64; 3]>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDistribution {
    method: Option<Spanned<String>>,
    nodes: Option<Spanned<i64>>,
    samples: Option<Spanned<i64>>,
    seed: Option<Spanned<i64>>,
    impact_centre_mm: Option<Spanned<[f64; 2]>>,
    sigma_y_mm: Option<Spanned<f64>>,
    sigma_z_mm: Option<Spanned<f64>>,
    sigma_club_speed_mph: Option<Spanned<f64>>,
    sigma_attack_angle_deg: Option<Spanned<f64>>,
    sigma_club_path_deg: Option<Spanned<f64>>,
    sigma_dynamic_loft_deg: Option<Spanned<f64>>,
    sigma_face_angle_deg: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    y_mm: Spanned<toml::Value>,
    z_mm: Spanned<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSensitivity {
    variables: Option<Vec<Spanned<String>>>,
    steps: Option<BTreeMap<Spanned<String>, Spanned<f64>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSummary {
    half_width_mm: Option<Spanned<f64>>,
    step_mm: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOptimise {
    goal: Spanned<String>,
    objective: Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>,
    bounds: Spanned<BTreeMap<Spanned<String>, Spanned<[f64; 2]>>>,
    max_iters: Option<Spanned<i64>>,
    tolerance: Option<Spanned<f64>>,
}

/// Defaults, in one place.
pub mod defaults {
    /// Group.
    pub const GROUP: &str = "all";
    /// Quadrature nodes per dimension.
    pub const NODES: usize = 5;
    /// Samples.
    pub const SAMPLES: usize = 256;
    /// Random seed.
    pub const SEED: u64 = 1;
    /// Probe half-width, mm.
    pub const HALF_WIDTH_MM: f64 = 20.0;
    /// Probe step, mm.
    pub const STEP_MM: f64 = 2.0;
    /// Optimiser iterations.
    pub const MAX_ITERS: u64 = 200;
    /// Optimiser tolerance (objective units).
    pub const TOLERANCE: f64 = 1e-6;
    /// Largest number of impacts per quadrature distribution.
    pub const MAX_QUADRATURE_POINTS: usize = crate::limits::MAX_QUADRATURE_POINTS;
}

struct Ctx<'a> {
    path: &'a Path,
    text: &'a str,
}

impl Ctx<'_> {
    fn err(&self, span: std::ops::Range<usize>, key: &str, msg: impl Into<String>) -> DataError {
        toml_key_error(self.path, self.text, span.start, key, msg)
    }

    fn finite(&self, v: &Spanned<f64>, key: &str, unit: &str) -> Result<f64, DataError> {
        let x = *v.get_ref();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.err(
                v.span(),
                key,
                format!("must be a finite number ({unit}), got {}", Num(x)),
            ))
        }
    }

    fn positive(&self, v: &Spanned<f64>, key: &str, unit: &str) -> Result<f64, DataError> {
        let x = *v.get_ref();
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(self.err(
                v.span(),
                key,
                format!("must be a finite number > 0 ({unit}), got {}", Num(x)),
            ))
        }
    }

    /// A value in its physical range (see [`crate::limits`]).
    fn ranged(&self, v: &Spanned<f64>, key: &str, range: PhysicalRange) -> Result<f64, DataError> {
        range
            .check(*v.get_ref())
            .map_err(|m| self.err(v.span(), key, m))
    }

    fn opt_ranged(
        &self,
        v: &Option<Spanned<f64>>,
        key: &str,
        range: PhysicalRange,
        default: f64,
    ) -> Result<f64, DataError> {
        v.as_ref()
            .map_or(Ok(default), |v| self.ranged(v, key, range))
    }

    fn count(&self, v: &Spanned<i64>, key: &str, lo: i64, hi: i64) -> Result<usize, DataError> {
        let x = *v.get_ref();
        if (lo..=hi).contains(&x) {
            Ok(x as usize)
        } else {
            Err(self.err(
                v.span(),
                key,
                format!("must be an integer from {lo} to {hi}, got {x}"),
            ))
        }
    }

    fn number(
        &self,
        v: &toml::Value,
        span: std::ops::Range<usize>,
        key: &str,
    ) -> Result<f64, DataError> {
        let x = match v {
            toml::Value::Float(f) => *f,
            toml::Value::Integer(i) => *i as f64,
            other => {
                return Err(self.err(
                    span,
                    key,
                    format!("must be a number, got {}", other.type_str()),
                ))
            }
        };
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.err(span, key, format!("must be finite, got {}", Num(x))))
        }
    }

    /// A number, a list of numbers, or `{ from, to, count }` / `{ from, to, step }`.
    fn axis(
        &self,
        v: &Spanned<toml::Value>,
        key: &str,
        range: PhysicalRange,
    ) -> Result<Axis, DataError> {
        let axis = self.axis_values(v, key)?;
        let span = v.span();
        let (lo, hi) = match &axis {
            Axis::List(vals) => {
                if vals.len() > limits::MAX_AXIS_VALUES {
                    return Err(self.err(
                        span,
                        key,
                        format!(
                            "{} values; at most {} an axis",
                            vals.len(),
                            limits::MAX_AXIS_VALUES
                        ),
                    ));
                }
                let bad = vals.iter().find(|x| !range.contains(**x));
                if let Some(x) = bad {
                    return Err(self.err(span, key, range.refusal(*x)));
                }
                return Ok(axis);
            }
            Axis::Range { from, to, .. } => (*from, *to),
        };
        for (x, k) in [(lo, "from"), (hi, "to")] {
            if !range.contains(x) {
                return Err(self.err(span.clone(), &format!("{key}.{k}"), range.refusal(x)));
            }
        }
        Ok(axis)
    }

    fn axis_values(&self, v: &Spanned<toml::Value>, key: &str) -> Result<Axis, DataError> {
        let span = v.span();
        let allowed =
            "a number, a list of numbers, or a range { from, to, count } or { from, to, step }";
        match v.get_ref() {
            toml::Value::Float(_) | toml::Value::Integer(_) => {
                Ok(Axis::List(vec![self.number(v.get_ref(), span, key)?]))
            }
            toml::Value::Array(items) => {
                if items.is_empty() {
                    return Err(self.err(span, key, format!("the list is empty; give {allowed}")));
                }
                let vals = items
                    .iter()
                    .map(|x| self.number(x, span.clone(), key))
                    .collect::<Result<Vec<_>, _>>()?;
                Ok(Axis::List(vals))
            }
            toml::Value::Table(t) => {
                for k in t.keys() {
                    if !["from", "to", "count", "step"].contains(&k.as_str()) {
                        return Err(self.err(
                            span,
                            key,
                            format!(
                                "unknown range key `{k}`; a range has from, to and count or step"
                            ),
                        ));
                    }
                }
                let get = |k: &str| {
                    t.get(k)
                        .ok_or_else(|| self.err(span.clone(), key, format!("range: missing `{k}`")))
                        .and_then(|x| self.number(x, span.clone(), &format!("{key}.{k}")))
                };
                let (from, to) = (get("from")?, get("to")?);
                let count = match (t.get("count"), t.get("step")) {
                    (Some(_), Some(_)) | (None, None) => {
                        return Err(self.err(
                            span,
                            key,
                            "range: give exactly one of `count` or `step`",
                        ))
                    }
                    (Some(toml::Value::Integer(c)), None)
                        if *c >= 1 && *c <= limits::MAX_AXIS_VALUES as i64 =>
                    {
                        *c as usize
                    }
                    (Some(c), None) => {
                        return Err(self.err(
                            span,
                            format!("{key}.count").as_str(),
                            format!(
                                "must be an integer from 1 to {}, got {c}",
                                limits::MAX_AXIS_VALUES
                            ),
                        ))
                    }
                    (None, Some(_)) => {
                        let step = get("step")?;
                        let n = (to - from) / step;
                        if !(step > 0.0) || !(n >= 0.0) || (n - n.round()).abs() > 1e-9 * n.max(1.0)
                        {
                            return Err(self.err(
                                span,
                                &format!("{key}.step"),
                                format!(
                                    "must be > 0 and divide to − from = {} into whole steps, got {step}",
                                    to - from
                                ),
                            ));
                        }
                        if n.round() + 1.0 > limits::MAX_AXIS_VALUES as f64 {
                            return Err(self.err(
                                span,
                                &format!("{key}.step"),
                                format!(
                                    "{step} gives {} points; at most {} points an axis",
                                    n.round() + 1.0,
                                    limits::MAX_AXIS_VALUES
                                ),
                            ));
                        }
                        n.round() as usize + 1
                    }
                };
                if count == 1 && to != from {
                    return Err(self.err(
                        span,
                        &format!("{key}.count"),
                        format!("count = 1 needs from = to (got from = {from}, to = {to})"),
                    ));
                }
                if count > 1 && !(to > from) {
                    return Err(self.err(
                        span,
                        key,
                        format!("range: `to` ({to}) must exceed `from` ({from})"),
                    ));
                }
                Ok(Axis::Range { from, to, count })
            }
            other => Err(self.err(
                span,
                key,
                format!("got {}; give {allowed}", other.type_str()),
            )),
        }
    }
}

/// Read and resolve a study file. The club path is relative to the study file.
pub fn read_study(path: &Path) -> Result<Study, DataError> {
    let text = read_text(path)?;
    parse_study(path, &text)
}

/// Parse and resolve study text (`path` locates the club and names the file in messages).
pub fn parse_study(path: &Path, text: &str) -> Result<Study, DataError> {
    let ctx = Ctx { path, text };
    let raw: RawStudy = parse_toml(path, text, "a study file has [study], [delivery], [grid] and optional [distribution], [design], [sensitivity], [summary], [optimise], [yards]; see configs/README.md")?;

    // [study]
    let h = &raw.study;
    let name = h.name.get_ref().clone();
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.')
        || name.starts_with('.')
    {
        return Err(ctx.err(
            h.name.span(),
            "study.name",
            format!("'{name}' must be a non-empty folder name of letters, digits, '_', '-', '.'"),
        ));
    }
    let club_rel = PathBuf::from(h.club.get_ref());
    let base = path.parent().unwrap_or(Path::new("."));
    let club_file = if club_rel.is_absolute() {
        club_rel
    } else {
        base.join(club_rel)
    };
    let club_path = std::fs::canonicalize(&club_file).map_err(|e| {
        ctx.err(
            h.club.span(),
            "study.club",
            format!(
                "cannot open club file {}: {e} (paths are relative to the study file)",
                club_file.display()
            ),
        )
    })?;
    let club = read_club(&club_path)?;
    let group = h
        .group
        .as_ref()
        .map_or(defaults::GROUP.to_string(), |g| g.get_ref().clone());
    if group.is_empty() {
        return Err(ctx.err(
            h.group.as_ref().unwrap().span(),
            "study.group",
            "must not be empty",
        ));
    }
    let outputs = match &h.outputs {
        None => Output::ALL.to_vec(),
        Some(list) => {
            let mut out = Vec::new();
            for s in list {
                let o = Output::from_column(s.get_ref()).ok_or_else(|| {
                    ctx.err(
                        s.span(),
                        "study.outputs",
                        format!(
                            "unknown output '{}'; allowed: {}",
                            s.get_ref(),
                            Output::all_columns()
                        ),
                    )
                })?;
                if out.contains(&o) {
                    return Err(ctx.err(
                        s.span(),
                        "study.outputs",
                        format!("'{}' is listed twice", s.get_ref()),
                    ));
                }
                out.push(o);
            }
            if out.is_empty() {
                return Err(DataError::at(
                    path,
                    None,
                    Some("key study.outputs".into()),
                    format!("the list is empty; allowed: {}", Output::all_columns()),
                ));
            }
            out.sort();
            out
        }
    };
    let output_dir = h
        .output_dir
        .as_ref()
        .map_or_else(|| PathBuf::from("results").join(&name), PathBuf::from);

    // [delivery]
    let d = &raw.delivery;
    let angle = limits::DELIVERY_ANGLE_DEG;
    let swing = SwingSpec {
        club_speed_mph: ctx.ranged(
            &d.club_speed_mph,
            "delivery.club_speed_mph",
            limits::CLUB_SPEED_MPH,
        )?,
        dynamic_loft_deg: ctx.ranged(
            &d.dynamic_loft_deg,
            "delivery.dynamic_loft_deg",
            limits::DYNAMIC_LOFT_DEG,
        )?,
        attack_angle_deg: ctx.opt_ranged(
            &d.attack_angle_deg,
            "delivery.attack_angle_deg",
            angle,
            0.0,
        )?,
        club_path_deg: ctx.opt_ranged(&d.club_path_deg, "delivery.club_path_deg", angle, 0.0)?,
        face_angle_deg: ctx.opt_ranged(&d.face_angle_deg, "delivery.face_angle_deg", angle, 0.0)?,
        lie_tilt_deg: ctx.opt_ranged(&d.lie_tilt_deg, "delivery.lie_tilt_deg", angle, 0.0)?,
        club_omega_rad_s: match &d.club_omega_rad_s {
            None => [0.0; 3],
            Some(w) => {
                for x in w.get_ref() {
                    limits::CLUB_OMEGA_RAD_S
                        .check(*x)
                        .map_err(|m| ctx.err(w.span(), "delivery.club_omega_rad_s", m))?;
                }
                *w.get_ref()
            }
        },
    };

    // [distribution]
    let distribution = match &raw.distribution {
        None => None,
        Some(sd) => {
            let r = sd.get_ref();
            let method_name = r
                .method
                .as_ref()
                .map_or("quadrature", |m| m.get_ref().as_str());
            let method = match method_name {
                "quadrature" => {
                    if let Some(s) = &r.samples {
                        return Err(ctx.err(s.span(), "distribution.samples", "goes with method = \"samples\"; quadrature uses `nodes`"));
                    }
                    Method::Quadrature {
                        nodes: r.nodes.as_ref().map_or(Ok(defaults::NODES), |n| ctx.count(n, "distribution.nodes", 1, 20))?,
                    }
                }
                "samples" => {
                    if let Some(n) = &r.nodes {
                        return Err(ctx.err(n.span(), "distribution.nodes", "goes with method = \"quadrature\"; samples uses `samples` and `seed`"));
                    }
                    Method::Samples {
                        samples: r.samples.as_ref().map_or(Ok(defaults::SAMPLES), |n| ctx.count(n, "distribution.samples", 1, 1_000_000))?,
                        seed: r.seed.as_ref().map_or(Ok(defaults::SEED), |s| ctx.count(s, "distribution.seed", 0, i64::MAX).map(|x| x as u64))?,
                    }
                }
                other => {
                    return Err(ctx.err(
                        r.method.as_ref().unwrap().span(),
                        "distribution.method",
                        format!("unknown method '{other}'; allowed: quadrature (Gauss–Hermite, deterministic), samples (fixed seed)"),
                    ))
                }
            };
            if let (Method::Quadrature { .. }, Some(s)) = (&method, &r.seed) {
                return Err(ctx.err(
                    s.span(),
                    "distribution.seed",
                    "goes with method = \"samples\"",
                ));
            }
            let centre = match &r.impact_centre_mm {
                None => [0.0, 0.0],
                Some(c) => {
                    for x in c.get_ref() {
                        limits::IMPACT_LOCATION_MM
                            .check(*x)
                            .map_err(|m| ctx.err(c.span(), "distribution.impact_centre_mm", m))?;
                    }
                    *c.get_ref()
                }
            };
            let dist = Distribution {
                method,
                impact_centre_mm: centre,
                sigma_y_mm: ctx.opt_ranged(
                    &r.sigma_y_mm,
                    "distribution.sigma_y_mm",
                    limits::SIGMA_LOCATION_MM,
                    0.0,
                )?,
                sigma_z_mm: ctx.opt_ranged(
                    &r.sigma_z_mm,
                    "distribution.sigma_z_mm",
                    limits::SIGMA_LOCATION_MM,
                    0.0,
                )?,
                sigma_club_speed_mph: ctx.opt_ranged(
                    &r.sigma_club_speed_mph,
                    "distribution.sigma_club_speed_mph",
                    limits::SIGMA_CLUB_SPEED_MPH,
                    0.0,
                )?,
                sigma_attack_angle_deg: ctx.opt_ranged(
                    &r.sigma_attack_angle_deg,
                    "distribution.sigma_attack_angle_deg",
                    limits::SIGMA_ANGLE_DEG,
                    0.0,
                )?,
                sigma_club_path_deg: ctx.opt_ranged(
                    &r.sigma_club_path_deg,
                    "distribution.sigma_club_path_deg",
                    limits::SIGMA_ANGLE_DEG,
                    0.0,
                )?,
                sigma_dynamic_loft_deg: ctx.opt_ranged(
                    &r.sigma_dynamic_loft_deg,
                    "distribution.sigma_dynamic_loft_deg",
                    limits::SIGMA_ANGLE_DEG,
                    0.0,
                )?,
                sigma_face_angle_deg: ctx.opt_ranged(
                    &r.sigma_face_angle_deg,
                    "distribution.sigma_face_angle_deg",
                    limits::SIGMA_ANGLE_DEG,
                    0.0,
                )?,
            };
            if let Method::Quadrature { nodes } = dist.method {
                let dims: Vec<(&str, usize)> = [
                    ("sigma_y_mm", dist.sigma_y_mm),
                    ("sigma_z_mm", dist.sigma_z_mm),
                    ("sigma_club_speed_mph", dist.sigma_club_speed_mph),
                    ("sigma_attack_angle_deg", dist.sigma_attack_angle_deg),
                    ("sigma_club_path_deg", dist.sigma_club_path_deg),
                    ("sigma_dynamic_loft_deg", dist.sigma_dynamic_loft_deg),
                    ("sigma_face_angle_deg", dist.sigma_face_angle_deg),
                ]
                .into_iter()
                .filter(|(_, s)| *s > 0.0)
                .map(|(k, _)| (k, nodes))
                .collect();
                count_product(
                    "quadrature points (nodes for each σ > 0)",
                    &dims,
                    defaults::MAX_QUADRATURE_POINTS,
                    "use fewer nodes or method = \"samples\"",
                )
                .map_err(|e| ctx.err(sd.span(), "distribution", e.to_string()))?;
            }
            Some(dist)
        }
    };

    // [grid]
    let grid = Grid {
        y_mm: ctx.axis(&raw.grid.y_mm, "grid.y_mm", limits::GRID_LOCATION_MM)?,
        z_mm: ctx.axis(&raw.grid.z_mm, "grid.z_mm", limits::GRID_LOCATION_MM)?,
    };
    for (axis, v, key) in [
        (&grid.y_mm, &raw.grid.y_mm, "grid.y_mm"),
        (&grid.z_mm, &raw.grid.z_mm, "grid.z_mm"),
    ] {
        let vals = axis.values();
        if vals.windows(2).any(|w| !(w[1] > w[0])) {
            return Err(ctx.err(v.span(), key, "values must be strictly ascending"));
        }
    }

    // [design]
    let mut axes = Vec::new();
    let mut discretionary_mass = None;
    if let Some(table) = &raw.design {
        for (k, v) in table {
            let key = k.get_ref().as_str();
            if key == "discretionary_mass" {
                discretionary_mass = Some(parse_mass(&ctx, v, &club)?);
                continue;
            }
            let var = DesignVar::from_key(key).ok_or_else(|| {
                ctx.err(
                    k.span(),
                    &format!("design.{key}"),
                    format!(
                        "unknown design variable; allowed: {}, discretionary_mass",
                        DesignVar::all_keys()
                    ),
                )
            })?;
            axes.push((var, ctx.axis(v, &format!("design.{key}"), var.range())?));
        }
    }
    axes.sort_by_key(|(v, _)| *v);
    let design = DesignSpace {
        axes,
        discretionary_mass,
    };
    if discretionary_mass.is_none() {
        if let Some((var, _)) = design
            .axes
            .iter()
            .find(|(v, _)| v.needs_discretionary_mass())
        {
            return Err(DataError::at(
                path,
                None,
                Some(format!("key design.{}", var.key())),
                "moving the discretionary mass needs design.discretionary_mass = { mass_g = …, at_mm = [x, y, z] }",
            ));
        }
    }
    let whole = |key: &str, e: limits::CapError| {
        DataError::at(path, None, Some(format!("key {key}")), e.to_string())
    };
    let axis_counts: Vec<(&str, usize)> = design
        .axes
        .iter()
        .map(|(v, a)| (v.key(), a.len()))
        .collect();
    let n_variants = count_product(
        "design variants",
        &axis_counts,
        limits::MAX_DESIGN_VARIANTS,
        "use fewer [design] values",
    )
    .map_err(|e| whole("design", e))?;
    let n_points = count_product(
        "grid points",
        &[
            ("design variants", n_variants),
            ("grid.y_mm values", grid.y_mm.len()),
            ("grid.z_mm values", grid.z_mm.len()),
        ],
        super::MAX_SWEEP_POINTS as usize,
        "a run's time and disk grow with it; use a coarser [grid] or fewer [design] values",
    )
    .map_err(|e| whole("grid", e))?;

    // [sensitivity]
    let sensitivity = match &raw.sensitivity {
        None => None,
        Some(s) => {
            let r = s.get_ref();
            let mut vars: Vec<DesignVar> = match &r.variables {
                Some(list) => list
                    .iter()
                    .map(|n| {
                        DesignVar::from_key(n.get_ref()).ok_or_else(|| {
                            ctx.err(
                                n.span(),
                                "sensitivity.variables",
                                format!(
                                    "unknown design variable '{}'; allowed: {}",
                                    n.get_ref(),
                                    DesignVar::all_keys()
                                ),
                            )
                        })
                    })
                    .collect::<Result<_, _>>()?,
                None => design.axes.iter().map(|(v, _)| *v).collect(),
            };
            vars.sort();
            vars.dedup();
            if vars.is_empty() {
                return Err(ctx.err(
                    s.span(),
                    "sensitivity.variables",
                    format!(
                        "no variables: list some, or give [design] axes; allowed: {}",
                        DesignVar::all_keys()
                    ),
                ));
            }
            let mut steps: Vec<(DesignVar, f64)> =
                vars.iter().map(|v| (*v, v.default_step())).collect();
            if let Some(map) = &r.steps {
                for (k, v) in map {
                    let key = format!("sensitivity.steps.{}", k.get_ref());
                    let slot = steps
                        .iter_mut()
                        .find(|(var, _)| var.key() == k.get_ref())
                        .ok_or_else(|| {
                            ctx.err(k.span(), &key, "not one of the sensitivity variables")
                        })?;
                    slot.1 = ctx.positive(v, &key, slot.0.unit())?;
                    let r = slot.0.range();
                    let n = slot.0.neutral();
                    if !(r.contains(n - slot.1) && r.contains(n + slot.1)) {
                        return Err(ctx.err(
                            v.span(),
                            &key,
                            format!(
                                "the central difference evaluates {n} ± {}, outside the physical \
                                 range {r}",
                                limits::fmt_value(slot.1)
                            ),
                        ));
                    }
                    let is_scale = matches!(
                        slot.0,
                        DesignVar::InertiaScale
                            | DesignVar::IxxScale
                            | DesignVar::IyyScale
                            | DesignVar::IzzScale
                    );
                    if is_scale && slot.1 >= 0.5 {
                        return Err(ctx.err(
                            v.span(),
                            &key,
                            format!(
                                "a scale's central difference evaluates 1 ± step; the step must be \
                                 below 0.5 (typically 0.01), got {}",
                                slot.1
                            ),
                        ));
                    }
                }
            }
            if discretionary_mass.is_none() {
                if let Some((v, _)) = steps.iter().find(|(v, _)| v.needs_discretionary_mass()) {
                    return Err(ctx.err(
                        s.span(),
                        "sensitivity.variables",
                        format!("{} needs design.discretionary_mass", v.key()),
                    ));
                }
            }
            Some(steps)
        }
    };

    // [summary]
    let probe = match &raw.summary {
        None => Probe {
            half_width_mm: defaults::HALF_WIDTH_MM,
            step_mm: defaults::STEP_MM,
        },
        Some(s) => {
            let half_width_mm = s
                .half_width_mm
                .as_ref()
                .map_or(Ok(defaults::HALF_WIDTH_MM), |v| {
                    ctx.ranged(v, "summary.half_width_mm", limits::PROBE_HALF_WIDTH_MM)
                })?;
            let step_mm = match &s.step_mm {
                None => defaults::STEP_MM.min(half_width_mm),
                Some(v) => {
                    let st = ctx.positive(v, "summary.step_mm", "mm")?;
                    if st > half_width_mm {
                        return Err(ctx.err(
                            v.span(),
                            "summary.step_mm",
                            format!("must not exceed half_width_mm ({half_width_mm})"),
                        ));
                    }
                    let points = (half_width_mm / st).floor() + 1.0;
                    if points > limits::MAX_PROBE_POINTS as f64 {
                        return Err(ctx.err(
                            v.span(),
                            "summary.step_mm",
                            format!(
                                "half_width_mm / step_mm gives {} points a probe line, more than \
                                 the limit of {}; use a larger step",
                                limits::fmt_value(points),
                                limits::MAX_PROBE_POINTS
                            ),
                        ));
                    }
                    st
                }
            };
            Probe {
                half_width_mm,
                step_mm,
            }
        }
    };
    // The probe lines must lie on the face, or the speed-retention and gear-effect summaries
    // cannot be computed.
    let face = crate::physics::FaceGeometry::new(club.nominal.bulge_m, club.nominal.roll_m)
        .map_err(|m| DataError::file(&club_path, m))?;
    let hw = mm(probe.half_width_mm);
    if [(hw, 0.0), (-hw, 0.0), (0.0, hw), (0.0, -hw)]
        .iter()
        .any(|&(y, z)| face.contact(y, z).is_err())
    {
        return Err(DataError::at(
            path,
            None,
            Some("key summary.half_width_mm".into()),
            format!(
                "the probe lines reach {} mm from the centre, off the face of {} (bulge {:.1} mm, \
                 roll {:.1} mm); use a smaller half_width_mm",
                probe.half_width_mm,
                club_path.display(),
                club.nominal.bulge_m * 1e3,
                club.nominal.roll_m * 1e3
            ),
        ));
    }
    let probe_points = (probe.half_width_mm / probe.step_mm + 1e-9).floor() as usize + 1;
    let per_variant = limits::count_sum(
        "impacts per design variant",
        &[
            ("grid points", n_points / n_variants.max(1)),
            ("summary probes", 4 * probe_points),
            (
                "distribution points",
                distribution.as_ref().map_or(0, |d| d.point_count()),
            ),
        ],
        limits::MAX_STUDY_IMPACTS,
        "",
    )
    .map_err(|e| whole("grid", e))?;
    count_product(
        "impact evaluations",
        &[
            ("design variants", n_variants),
            ("impacts per variant", per_variant),
        ],
        limits::MAX_STUDY_IMPACTS,
        "use fewer [design] values, a coarser [grid] or fewer distribution points",
    )
    .map_err(|e| whole("design", e))?;

    // [optimise]
    let optimise = match &raw.optimise {
        None => None,
        Some(o) => {
            let r = o.get_ref();
            let goal = match r.goal.get_ref().as_str() {
                "maximise" | "maximize" => Goal::Maximise,
                "minimise" | "minimize" => Goal::Minimise,
                other => {
                    return Err(ctx.err(
                        r.goal.span(),
                        "optimise.goal",
                        format!("'{other}'; allowed: maximise, minimise"),
                    ))
                }
            };
            let names = metric_names(distribution.is_some());
            let mut objective = Vec::new();
            for (k, w) in r.objective.get_ref() {
                let key = format!("optimise.objective.{}", k.get_ref());
                if !names.iter().any(|n| n == k.get_ref()) {
                    let hint =
                        if k.get_ref().starts_with("mean_") || k.get_ref().starts_with("std_") {
                            " (mean_* and std_* need a [distribution])"
                        } else {
                            ""
                        };
                    return Err(ctx.err(
                        k.span(),
                        &key,
                        format!("unknown metric{hint}; allowed: {}", names.join(", ")),
                    ));
                }
                let w = ctx.finite(w, &key, "weight")?;
                if w != 0.0 {
                    objective.push((k.get_ref().clone(), w));
                }
            }
            if objective.is_empty() {
                return Err(ctx.err(r.objective.span(), "optimise.objective", format!("give at least one metric with a non-zero weight, e.g. {{ mean_ball_speed_mph = 1.0 }}; allowed: {}", names.join(", "))));
            }
            let mut bounds = Vec::new();
            for (k, b) in r.bounds.get_ref() {
                let key = format!("optimise.bounds.{}", k.get_ref());
                let var = DesignVar::from_key(k.get_ref()).ok_or_else(|| {
                    ctx.err(
                        k.span(),
                        &key,
                        format!(
                            "unknown design variable; allowed: {}",
                            DesignVar::all_keys()
                        ),
                    )
                })?;
                let [lo, hi] = *b.get_ref();
                let n = var.neutral();
                if !(lo.is_finite() && hi.is_finite() && lo < hi && lo <= n && n <= hi) {
                    return Err(ctx.err(b.span(), &key, format!("must be [lower, upper], finite, lower < upper, containing the base value {n}; got [{}, {}]", limits::fmt_value(lo), limits::fmt_value(hi))));
                }
                for x in [lo, hi] {
                    var.range()
                        .check(x)
                        .map_err(|m| ctx.err(b.span(), &key, m))?;
                }
                if var.needs_discretionary_mass() && discretionary_mass.is_none() {
                    return Err(ctx.err(k.span(), &key, "needs design.discretionary_mass"));
                }
                bounds.push((var, lo, hi));
            }
            if bounds.is_empty() {
                return Err(ctx.err(
                    r.bounds.span(),
                    "optimise.bounds",
                    format!(
                        "give at least one design variable with [lower, upper]; allowed: {}",
                        DesignVar::all_keys()
                    ),
                ));
            }
            bounds.sort_by_key(|b| b.0);
            Some(OptimiseSpec {
                goal,
                objective,
                bounds,
                max_iters: r.max_iters.as_ref().map_or(Ok(defaults::MAX_ITERS), |m| {
                    ctx.count(m, "optimise.max_iters", 1, 100_000)
                        .map(|x| x as u64)
                })?,
                tolerance: r.tolerance.as_ref().map_or(Ok(defaults::TOLERANCE), |t| {
                    ctx.positive(t, "optimise.tolerance", "objective units")
                })?,
            })
        }
    };

    let yards = super::yards_spec::parse_yards(path, text, &club, distribution.is_some())?;

    Ok(Study {
        name,
        club_path,
        club,
        group,
        outputs,
        output_dir,
        swing,
        distribution,
        grid,
        design,
        sensitivity,
        probe,
        optimise,
        yards,
    })
}

fn parse_mass(
    ctx: &Ctx<'_>,
    v: &Spanned<toml::Value>,
    club: &ClubSpec,
) -> Result<DiscretionaryMass, DataError> {
    let key = "design.discretionary_mass";
    let form =
        "{ mass_g = …, at_mm = [x, y, z] } (at_mm: the mass's base position from the CoF, in F)";
    let toml::Value::Table(t) = v.get_ref() else {
        return Err(ctx.err(v.span(), key, format!("must be a table {form}")));
    };
    for k in t.keys() {
        if k != "mass_g" && k != "at_mm" {
            return Err(ctx.err(
                v.span(),
                key,
                format!("unknown key `{k}`; allowed: mass_g, at_mm"),
            ));
        }
    }
    let m = t
        .get("mass_g")
        .ok_or_else(|| ctx.err(v.span(), key, format!("missing `mass_g`; {form}")))
        .and_then(|x| ctx.number(x, v.span(), "design.discretionary_mass.mass_g"))?;
    let head_g = club.nominal.club_mass_kg * 1e3;
    if !(m > 0.0 && m < head_g) {
        return Err(ctx.err(
            v.span(),
            "design.discretionary_mass.mass_g",
            format!("must be > 0 and below the head mass {head_g} g, got {m}"),
        ));
    }
    let at = match t.get("at_mm") {
        Some(toml::Value::Array(a)) if a.len() == 3 => a
            .iter()
            .map(|x| {
                let key = "design.discretionary_mass.at_mm";
                ctx.number(x, v.span(), key).and_then(|x| {
                    limits::CLUB_COM_MM
                        .check(x)
                        .map_err(|m| ctx.err(v.span(), key, m))
                })
            })
            .collect::<Result<Vec<_>, _>>()?,
        _ => {
            return Err(ctx.err(
                v.span(),
                "design.discretionary_mass.at_mm",
                format!("must be [x, y, z] in mm; {form}"),
            ))
        }
    };
    Ok(DiscretionaryMass {
        mass_kg: g(m),
        at_m: Vector3::new(mm(at[0]), mm(at[1]), mm(at[2])),
    })
}

/// The resolved study as a study file: every default written out. Parses back to the same study.
pub fn resolved_toml(s: &Study) -> String {
    let mut t = String::new();
    let q = |x: &str| toml::Value::String(x.to_owned()).to_string();
    let _ = writeln!(
        t,
        "# Resolved study: every default filled in. `smash run` on this file repeats the run."
    );
    let _ = writeln!(t, "[study]");
    let _ = writeln!(t, "name = {}", q(&s.name));
    let _ = writeln!(t, "club = {}", q(&s.club_path.to_string_lossy()));
    let _ = writeln!(t, "group = {}", q(&s.group));
    let outs: Vec<String> = s.outputs.iter().map(|o| q(o.column())).collect();
    let _ = writeln!(t, "outputs = [{}]", outs.join(", "));
    let _ = writeln!(t, "output_dir = {}", q(&s.output_dir.to_string_lossy()));
    let w = &s.swing;
    let _ = writeln!(t, "\n[delivery]");
    let _ = writeln!(t, "club_speed_mph = {:?}", w.club_speed_mph);
    let _ = writeln!(t, "dynamic_loft_deg = {:?}", w.dynamic_loft_deg);
    let _ = writeln!(t, "attack_angle_deg = {:?}", w.attack_angle_deg);
    let _ = writeln!(t, "club_path_deg = {:?}", w.club_path_deg);
    let _ = writeln!(t, "face_angle_deg = {:?}", w.face_angle_deg);
    let _ = writeln!(t, "lie_tilt_deg = {:?}", w.lie_tilt_deg);
    let o = w.club_omega_rad_s;
    let _ = writeln!(t, "club_omega_rad_s = [{:?}, {:?}, {:?}]", o[0], o[1], o[2]);
    if let Some(d) = &s.distribution {
        let _ = writeln!(t, "\n[distribution]");
        match d.method {
            Method::Quadrature { nodes } => {
                let _ = writeln!(t, "method = \"quadrature\"\nnodes = {nodes}");
            }
            Method::Samples { samples, seed } => {
                let _ = writeln!(
                    t,
                    "method = \"samples\"\nsamples = {samples}\nseed = {seed}"
                );
            }
        }
        let c = d.impact_centre_mm;
        let _ = writeln!(t, "impact_centre_mm = [{:?}, {:?}]", c[0], c[1]);
        let _ = writeln!(t, "sigma_y_mm = {:?}", d.sigma_y_mm);
        let _ = writeln!(t, "sigma_z_mm = {:?}", d.sigma_z_mm);
        let _ = writeln!(t, "sigma_club_speed_mph = {:?}", d.sigma_club_speed_mph);
        let _ = writeln!(t, "sigma_attack_angle_deg = {:?}", d.sigma_attack_angle_deg);
        let _ = writeln!(t, "sigma_club_path_deg = {:?}", d.sigma_club_path_deg);
        let _ = writeln!(t, "sigma_dynamic_loft_deg = {:?}", d.sigma_dynamic_loft_deg);
        let _ = writeln!(t, "sigma_face_angle_deg = {:?}", d.sigma_face_angle_deg);
    }
    let _ = writeln!(t, "\n[grid]");
    let _ = writeln!(t, "y_mm = {}", s.grid.y_mm.to_toml());
    let _ = writeln!(t, "z_mm = {}", s.grid.z_mm.to_toml());
    if !s.design.axes.is_empty() || s.design.discretionary_mass.is_some() {
        let _ = writeln!(t, "\n[design]");
        for (v, a) in &s.design.axes {
            let _ = writeln!(t, "{} = {}", v.key(), a.to_toml());
        }
        if let Some(m) = &s.design.discretionary_mass {
            let a = m.at_m * 1e3;
            let _ = writeln!(
                t,
                "discretionary_mass = {{ mass_g = {:?}, at_mm = [{:?}, {:?}, {:?}] }}",
                m.mass_kg * 1e3,
                a.x,
                a.y,
                a.z
            );
        }
    }
    if let Some(sens) = &s.sensitivity {
        let _ = writeln!(t, "\n[sensitivity]");
        let vars: Vec<String> = sens.iter().map(|(v, _)| q(v.key())).collect();
        let _ = writeln!(t, "variables = [{}]", vars.join(", "));
        let steps: Vec<String> = sens
            .iter()
            .map(|(v, h)| format!("{} = {h:?}", v.key()))
            .collect();
        let _ = writeln!(t, "steps = {{ {} }}", steps.join(", "));
    }
    let _ = writeln!(t, "\n[summary]");
    let _ = writeln!(t, "half_width_mm = {:?}", s.probe.half_width_mm);
    let _ = writeln!(t, "step_mm = {:?}", s.probe.step_mm);
    if let Some(o) = &s.optimise {
        let _ = writeln!(t, "\n[optimise]");
        let goal = match o.goal {
            Goal::Maximise => "maximise",
            Goal::Minimise => "minimise",
        };
        let _ = writeln!(t, "goal = \"{goal}\"");
        let obj: Vec<String> = o
            .objective
            .iter()
            .map(|(k, w)| format!("{k} = {w:?}"))
            .collect();
        let _ = writeln!(t, "objective = {{ {} }}", obj.join(", "));
        let b: Vec<String> = o
            .bounds
            .iter()
            .map(|(v, lo, hi)| format!("{} = [{lo:?}, {hi:?}]", v.key()))
            .collect();
        let _ = writeln!(t, "bounds = {{ {} }}", b.join(", "));
        let _ = writeln!(t, "max_iters = {}", o.max_iters);
        let _ = writeln!(t, "tolerance = {:?}", o.tolerance);
    }
    if let Some(y) = &s.yards {
        t.push_str(&super::yards_spec::yards_toml(y));
    }
    t
}
