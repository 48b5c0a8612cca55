//! What `smash calibrate` reports, as one value: [`CalibrateReport`]. Its text is [`text`],
//! its JSON its `Serialize` (the schema: `docs/json.md`), its HTML page
//! [`crate::report::html::calibrate_page`].

pub mod text;

use serde::{Serialize, Serializer};
use serde_json::json;

use crate::diagnose::honest;
use crate::fit::Calibration;
use crate::physics::LaunchComponent;
use crate::stats::t_statistic;

/// The version of calibrate's JSON schema (`schema_version`); raised when a key changes
/// meaning or goes away (a new key does not raise it).
pub const SCHEMA_VERSION: u32 = 1;

/// What `smash calibrate` reports: the calibration, on how many shots, and whether the shots
/// are another club's. Text, JSON and HTML all render this one value.
#[derive(Debug, Clone)]
pub struct CalibrateReport {
    /// The fit, its statistics and the errors before and after.
    pub calibration: Calibration,
    /// Shots fitted.
    pub n_shots: usize,
    /// Why the shots do not match the club, when they do not (the fit then describes another
    /// club's shots: no findings).
    pub club_mismatch: Option<String>,
    /// What the run warned about: rows of the shots file left out, one note per reason.
    pub warnings: Vec<String>,
}

impl Serialize for CalibrateReport {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut json = to_json(&self.calibration);
        json["club_mismatch"] = json!(self.club_mismatch);
        json["warnings"] = json!(self.warnings);
        super::json::head_first(&json, s)
    }
}

fn opt(v: Option<f64>) -> serde_json::Value {
    v.filter(|x| x.is_finite())
        .map_or(serde_json::Value::Null, |x| json!(x))
}

/// The machine-readable report (the JSON of [`CalibrateReport`]).
fn to_json(cal: &Calibration) -> serde_json::Value {
    let labels: Vec<String> = cal.params.iter().map(|p| p.label()).collect();
    let params: Vec<serde_json::Value> = cal
        .params
        .iter()
        .map(|p| {
            json!({
                "effect": p.effect,
                "param": p.param,
                "group": p.group,
                "value": p.value,
                "stderr": opt(p.stderr),
                "unit": p.unit,
                "t": opt(p.stderr.map(|s| t_statistic(p.value, s))),
                "at_bound": p.at_bound,
                "plausible": honest::is_plausible(p),
                "plausible_range": honest::spec_of(p).map(|s| [s.plausible.0, s.plausible.1]),
                "stand_in": honest::stand_in(p),
            })
        })
        .collect();
    let correlation = cal.correlation.as_ref().map(|c| {
        let rows: Vec<Vec<f64>> = (0..c.nrows())
            .map(|i| (0..c.ncols()).map(|j| c[(i, j)]).collect())
            .collect();
        json!({"labels": labels, "matrix": rows})
    });
    let flagged: Vec<serde_json::Value> = cal
        .strongly_correlated
        .iter()
        .map(|p| json!({"a": labels[p.a], "b": labels[p.b], "r": p.r}))
        .collect();
    let unidentified: Vec<&String> = cal
        .identifiability
        .unidentified()
        .into_iter()
        .map(|j| &labels[j])
        .collect();
    let noise: serde_json::Map<String, serde_json::Value> = LaunchComponent::ALL
        .iter()
        .map(|c| (c.column().to_owned(), json!(cal.noise_scales[c.index()])))
        .collect();
    let shaft = cal.shaft_relation.as_ref().map(|s| {
        json!({
            "points": s.points.iter().map(|(g, m, dm, se)| json!({
                "group": g, "shaft_mass_g": m, "dm_g": dm, "stderr": opt(*se)
            })).collect::<Vec<_>>(),
            "slope_g_per_g": s.line.slope,
            "intercept_g": s.line.intercept,
            "r": s.line.r,
        })
    });
    let stages: Vec<serde_json::Value> = cal
        .paper_stages
        .iter()
        .map(|a| {
            json!({
                "param": labels[a.param],
                "stage": match a.stage { crate::fit::Stage::Linear => "W=inf", crate::fit::Stage::Angular => "W=0" },
                "linear_sensitivity": a.linear_sensitivity,
                "angular_sensitivity": a.angular_sensitivity,
            })
        })
        .collect();
    json!({
        "schema_version": SCHEMA_VERSION,
        "command": "calibrate",
        "method": cal.method.name(),
        "params": params,
        "correlation": correlation,
        "strongly_correlated": flagged,
        "aliases": honest::aliases(&cal.params, cal.correlation.as_ref()).iter().map(honest::Alias::to_json).collect::<Vec<_>>(),
        "unidentifiable": unidentified,
        "chi2": cal.chi2,
        "chi2_nominal": cal.chi2_before,
        "n_residuals": cal.n_residuals,
        "dof": cal.dof,
        "reduced_chi2": cal.reduced_chi2,
        "aic": cal.aic,
        "bic": cal.bic,
        "evaluations": cal.evaluations,
        "iterations": cal.iterations,
        "termination": cal.termination,
        "noise_scales": noise,
        "before": cal.before.to_json(),
        "after": cal.after.to_json(),
        "shaft_relation": shaft,
        "paper_stages": stages,
        "measurement_model": measurement_json(cal),
        "likelihood": crate::report::likelihood::to_json("calibrated", &cal.likelihood, &cal.likelihood_nominal),
    })
}

/// The impact-location (mm, to 1e-6) and delivery noise the fit assumed (`null`: as measured).
fn measurement_json(cal: &Calibration) -> serde_json::Value {
    json!({
        "impact_noise_mm": cal.impact_noise.map(|n| json!({
            "y": super::location_mm(n.sigma_y_m),
            "z": super::location_mm(n.sigma_z_m),
        })),
        "delivery_noise": cal.delivery_noise.as_ref().map(crate::report::delivery_noise::to_json),
    })
}
