//! What `smash calibrate` reports, as one value: [`CalibrateReport`]. Its text is [`text`],
//! its JSON its `Serialize` (the schema: `docs/json.md`), its HTML page
//! [`crate::report::html::calibrate_page`].

pub mod text;

use serde::{Serialize, Serializer};

use crate::diagnose::honest;
use crate::fit::Calibration;
use crate::report::views::{
    components, delivery_noise, error_table, AliasView, ComponentMap, ErrorTableView, Estimate,
    LikelihoodView,
};
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
        super::json::canonical(&view(self), s)
    }
}

/// A fitted parameter with its standard error, t statistic and plausibility.
#[derive(Debug, Clone, Serialize)]
struct ParamView {
    #[serde(flatten)]
    estimate: Estimate,
    t: Option<f64>,
    at_bound: bool,
}

/// The correlation matrix of the estimates.
#[derive(Debug, Clone, Serialize)]
struct CorrelationView {
    labels: Vec<String>,
    matrix: Vec<Vec<f64>>,
}

/// A strongly correlated pair of estimates.
#[derive(Debug, Clone, Serialize)]
struct PairView {
    a: String,
    b: String,
    r: f64,
}

/// One group's added mass against its shaft's mass.
#[derive(Debug, Clone, Serialize)]
struct ShaftPointView {
    group: String,
    shaft_mass_g: f64,
    dm_g: f64,
    stderr: Option<f64>,
}

/// The added mass against the shaft's mass across groups.
#[derive(Debug, Clone, Serialize)]
struct ShaftView {
    points: Vec<ShaftPointView>,
    slope_g_per_g: f64,
    intercept_g: f64,
    r: f64,
}

/// The stage of the paper's procedure a parameter was fitted in.
#[derive(Debug, Clone, Serialize)]
struct StageView {
    param: String,
    stage: &'static str,
    linear_sensitivity: f64,
    angular_sensitivity: f64,
}

/// The impact-location noise the fit assumed, mm.
#[derive(Debug, Clone, Serialize)]
struct LocationNoiseView {
    y: f64,
    z: f64,
}

/// The measurement model of the fit.
#[derive(Debug, Clone, Serialize)]
struct MeasurementView {
    impact_noise_mm: Option<LocationNoiseView>,
    delivery_noise: Option<std::collections::BTreeMap<&'static str, f64>>,
}

/// What `smash calibrate --json` prints (`docs/json.md`), filled once from the calibration.
#[derive(Debug, Clone, Serialize)]
struct CalibrateView {
    schema_version: u32,
    command: &'static str,
    method: &'static str,
    params: Vec<ParamView>,
    correlation: Option<CorrelationView>,
    strongly_correlated: Vec<PairView>,
    aliases: Vec<AliasView>,
    unidentifiable: Vec<String>,
    chi2: f64,
    chi2_nominal: f64,
    n_residuals: usize,
    dof: usize,
    reduced_chi2: f64,
    aic: f64,
    bic: f64,
    evaluations: u64,
    iterations: u64,
    termination: String,
    noise_scales: ComponentMap,
    before: ErrorTableView,
    after: ErrorTableView,
    shaft_relation: Option<ShaftView>,
    paper_stages: Vec<StageView>,
    measurement_model: MeasurementView,
    likelihood: LikelihoodView,
    club_mismatch: Option<String>,
    warnings: Vec<String>,
}

/// The view of the report (the JSON of [`CalibrateReport`]).
fn view(r: &CalibrateReport) -> CalibrateView {
    let cal = &r.calibration;
    let labels: Vec<String> = cal.params.iter().map(|p| p.label()).collect();
    let params = cal
        .params
        .iter()
        .map(|p| ParamView {
            estimate: Estimate::of(p),
            t: p.stderr.map(|s| t_statistic(p.value, s)),
            at_bound: p.at_bound,
        })
        .collect();
    let correlation = cal.correlation.as_ref().map(|c| CorrelationView {
        labels: labels.clone(),
        matrix: (0..c.nrows())
            .map(|i| (0..c.ncols()).map(|j| c[(i, j)]).collect())
            .collect(),
    });
    let shaft_relation = cal.shaft_relation.as_ref().map(|s| ShaftView {
        points: s
            .points
            .iter()
            .map(|(g, m, dm, se)| ShaftPointView {
                group: g.clone(),
                shaft_mass_g: *m,
                dm_g: *dm,
                stderr: *se,
            })
            .collect(),
        slope_g_per_g: s.line.slope,
        intercept_g: s.line.intercept,
        r: s.line.r,
    });
    CalibrateView {
        schema_version: SCHEMA_VERSION,
        command: "calibrate",
        method: cal.method.name(),
        params,
        correlation,
        strongly_correlated: cal
            .strongly_correlated
            .iter()
            .map(|p| PairView {
                a: labels[p.a].clone(),
                b: labels[p.b].clone(),
                r: p.r,
            })
            .collect(),
        aliases: honest::aliases(&cal.params, cal.correlation.as_ref())
            .iter()
            .map(AliasView::of)
            .collect(),
        unidentifiable: cal
            .identifiability
            .unidentified()
            .into_iter()
            .map(|j| labels[j].clone())
            .collect(),
        chi2: cal.chi2,
        chi2_nominal: cal.chi2_before,
        n_residuals: cal.n_residuals,
        dof: cal.dof,
        reduced_chi2: cal.reduced_chi2,
        aic: cal.aic,
        bic: cal.bic,
        evaluations: cal.evaluations,
        iterations: cal.iterations,
        termination: cal.termination.clone(),
        noise_scales: components(&cal.noise_scales),
        before: error_table(&cal.before),
        after: error_table(&cal.after),
        shaft_relation,
        paper_stages: cal
            .paper_stages
            .iter()
            .map(|a| StageView {
                param: labels[a.param].clone(),
                stage: match a.stage {
                    crate::fit::Stage::Linear => "W=inf",
                    crate::fit::Stage::Angular => "W=0",
                },
                linear_sensitivity: a.linear_sensitivity,
                angular_sensitivity: a.angular_sensitivity,
            })
            .collect(),
        measurement_model: MeasurementView {
            impact_noise_mm: cal.impact_noise.map(|n| LocationNoiseView {
                y: super::location_mm(n.sigma_y_m),
                z: super::location_mm(n.sigma_z_m),
            }),
            delivery_noise: cal.delivery_noise.as_ref().map(delivery_noise),
        },
        likelihood: LikelihoodView::new("calibrated", &cal.likelihood, &cal.likelihood_nominal),
        club_mismatch: r.club_mismatch.clone(),
        warnings: r.warnings.clone(),
    }
}
