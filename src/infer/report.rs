//! The infer-club report: plain data (serialised as `--json`) and its text.

use std::fmt::Write;

use serde::Serialize;

use super::head::HEAD_PARAMS;
use super::ident::Identifiability;
use super::plan::PlanParam;
use super::problem::NoiseCov;
use super::Settings;
use crate::club::ClubSpec;
use crate::model::Shot;
use crate::physics::LaunchComponent;
use crate::stats;

/// One head parameter's estimate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParamReport {
    /// The club file's key (`com_mm[0]`, `inertia_gcm2[1][1]`, `bulge_mm`, `cor`, …).
    pub name: String,
    /// In words.
    pub words: &'static str,
    /// Unit of the value.
    pub unit: &'static str,
    /// The estimate (posterior mode).
    pub value: f64,
    /// Its standard error: the sandwich `H⁻¹(M + P)H⁻¹` of the shots' own scores, prior
    /// included (`ident::sandwich_cov`).
    pub stderr: f64,
    /// The model's posterior standard error `√((F + P)⁻¹)_jj` (every shot as noisy as the
    /// average the weights assume).
    pub stderr_model: f64,
    /// The start club's value (the prior's centre).
    pub start: f64,
    /// Do the data determine it (data-only SE below the determined fraction of the prior)?
    pub determined: bool,
    /// Data-only standard error (`None`: the shots do not see it).
    pub data_stderr: Option<f64>,
    /// Prior 1σ.
    pub prior_sd: f64,
    /// The prior's share of the estimate, `1 − Var_post/Var_data`.
    pub prior_share: f64,
    /// Profile-likelihood interval (`Δχ² = 1`), determined parameters only.
    pub profile: Option<[f64; 2]>,
    /// Did the fit stop on a physical bound?
    pub at_bound: bool,
}

/// A noise covariance as reported.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NoiseReport {
    /// 1σ per launch component (file units).
    pub sd: [f64; 5],
    /// The components' names.
    pub components: [&'static str; 5],
    /// Correlation matrix.
    pub correlation: [[f64; 5]; 5],
}

impl NoiseReport {
    /// From a covariance.
    pub fn of(n: &NoiseCov) -> Self {
        Self {
            sd: n.sd,
            components: LaunchComponent::ALL.map(|c| c.column()),
            correlation: std::array::from_fn(|a| std::array::from_fn(|b| n.corr[(a, b)])),
        }
    }
}

/// Everything `smash infer-club` found.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// [`super::SCHEMA_VERSION`].
    pub schema_version: u32,
    /// `infer-club`.
    pub command: &'static str,
    /// Shots fitted.
    pub n_shots: usize,
    /// The settings used.
    pub settings: Settings,
    /// The prior, stated.
    pub prior: String,
    /// The rule for "determined".
    pub determined_rule: String,
    /// SD of the measured impact locations (up, toe), mm: what limits the off-centre physics.
    pub impact_spread_mm: [f64; 2],
    /// Per head parameter.
    pub params: Vec<ParamReport>,
    /// What the shots determine at the start head (instruments' noise), before fitting.
    pub before: Identifiability,
    /// What they determine at the inferred head (the fit's noise).
    pub after: Identifiability,
    /// Correlation matrix of the estimates (from the reported covariance), in `params` order.
    pub correlation: Vec<Vec<f64>>,
    /// The errors' noise covariance the fit whitened by (estimated from its errors).
    pub noise: NoiseReport,
    /// The instruments' noise carried through the start head (the before-fit analysis).
    pub instrument_noise: NoiseReport,
    /// χ² of the data rows at the estimate.
    pub chi2_data: f64,
    /// χ² of the prior rows at the estimate.
    pub chi2_prior: f64,
    /// Data rows.
    pub n_residuals: usize,
    /// Solver iterations, both stages.
    pub iterations: u64,
    /// Why the last stage stopped.
    pub termination: String,
    /// The inferred club.
    #[serde(skip)]
    pub club: ClubSpec,
    /// The fitted effect values (fit vector).
    #[serde(skip)]
    pub theta: Vec<f64>,
}

/// The `--plan` report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanReport {
    /// [`super::SCHEMA_VERSION`].
    pub schema_version: u32,
    /// `infer-club --plan`.
    pub command: &'static str,
    /// Shots of the session whose design is planned from.
    pub n_session: usize,
    /// Shots planned for.
    pub n_planned: usize,
    /// SD of the design's impact locations (up, toe), mm.
    pub impact_spread_mm: [f64; 2],
    /// The rule for "determined".
    pub determined_rule: String,
    /// The instruments' noise carried through the start head.
    pub noise: NoiseReport,
    /// Per head parameter.
    pub params: Vec<PlanParam>,
    /// Directions the planned shots leave weak, in words.
    pub weak_directions: Vec<String>,
}

/// The prior in one sentence.
pub fn prior_statement(s: &Settings) -> String {
    let widths: Vec<String> = HEAD_PARAMS
        .iter()
        .map(|h| match h.mapping {
            super::head::Mapping::Add => {
                format!(
                    "{} {} {}",
                    h.key,
                    fmt_num(h.prior_sd * s.prior_scale),
                    h.unit
                )
            }
            super::head::Mapping::Scale => {
                format!(
                    "{} {:.0} % of the start's",
                    h.key,
                    100.0 * h.prior_sd * s.prior_scale
                )
            }
        })
        .collect();
    format!(
        "independent Gaussians centred on the start club's values, 1 sigma: {} \
         (docs/plausible-ranges.md); in the fit as one residual row (value - start)/sigma each",
        widths.join(", ")
    )
}

/// The determined rule in one sentence.
pub fn determined_statement(f: f64) -> String {
    format!(
        "determined: data-only SE (Fisher information of the shots at the estimate, other \
         parameters free) below {f:.3} of the prior width, i.e. the data hold at least {:.0} % \
         of the information on the parameter",
        100.0 / (1.0 + f * f)
    )
}

/// SD of the measured impact locations, mm.
pub fn impact_spread_mm(shots: &[Shot]) -> [f64; 2] {
    let ys: Vec<f64> = shots.iter().map(|s| s.delivery.impact_y_m * 1e3).collect();
    let zs: Vec<f64> = shots.iter().map(|s| s.delivery.impact_z_m * 1e3).collect();
    [stats::std_dev(&ys), stats::std_dev(&zs)]
}

/// A number in few characters (4 significant digits).
pub fn fmt_num(v: f64) -> String {
    if v == 0.0 {
        return "0".to_owned();
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        format!("{v:.3e}")
    } else {
        let digits = (3 - a.log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    }
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or("-".to_owned(), fmt_num)
}

/// The report as text.
pub fn render(r: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "infer-club: {} shots; impact spread {:.1} mm up, {:.1} mm heel-toe (SD)",
        r.n_shots, r.impact_spread_mm[0], r.impact_spread_mm[1]
    );
    prose(&mut s, &format!("Prior: {}.", r.prior), 2);
    prose(&mut s, &format!("Rule: {}.", r.determined_rule), 2);
    let _ = writeln!(s, "\nBefore fitting (start head, instruments' noise):");
    render_ident(&mut s, &r.before, &[]);
    let _ = writeln!(
        s,
        "\nEstimates (posterior mode +- SE; prior share = 1 - Var_post/Var_data):"
    );
    let _ = writeln!(
        s,
        "{:<22} {:>12} {:>10} {:>12} {:>10} {:>7} {:>6}  profile (dchi2 = 1)",
        "parameter", "value", "SE", "start", "data SE", "prior%", "det."
    );
    for p in &r.params {
        let prof = p.profile.map_or("-".to_owned(), |[a, b]| {
            format!("[{}, {}]", fmt_num(a), fmt_num(b))
        });
        let _ = writeln!(
            s,
            "{:<22} {:>12} {:>10} {:>12} {:>10} {:>7.1} {:>6}  {}{}",
            p.name,
            fmt_num(p.value),
            fmt_num(p.stderr),
            fmt_num(p.start),
            fmt_opt(p.data_stderr),
            100.0 * p.prior_share,
            if p.determined { "yes" } else { "no" },
            prof,
            if p.at_bound {
                "  (at a physical bound)"
            } else {
                ""
            }
        );
    }
    let _ = writeln!(s, "\nAt the estimate:");
    let bound: Vec<&str> = r
        .params
        .iter()
        .filter(|p| p.at_bound)
        .map(|p| p.name.as_str())
        .collect();
    render_ident(&mut s, &r.after, &bound);
    let _ = writeln!(
        s,
        "\nchi2: data {:.1} over {} rows, prior {:.2}; {} iterations, {}",
        r.chi2_data, r.n_residuals, r.chi2_prior, r.iterations, r.termination
    );
    s
}

/// The lists of `id`; a determined parameter the fit holds at a physical bound (`bound`) is
/// named so: the data push it against the bound, and its SE does not describe it.
fn render_ident(s: &mut String, id: &Identifiability, bound: &[&str]) {
    let determined: Vec<String> = id
        .determined_params
        .iter()
        .map(|k| {
            if bound.contains(&k.as_str()) {
                format!("{k} (at a physical bound)")
            } else {
                k.clone()
            }
        })
        .collect();
    prose(s, &format!("  determined: {}", list(&determined)), 2);
    prose(
        s,
        &format!("  not determined: {}", list(&id.undetermined_params)),
        2,
    );
    for d in id.directions.iter().filter(|d| d.weak) {
        prose(s, &format!("  weak: {}", d.text), 2);
    }
}

/// The widest line of the text report, in columns (the text reports' width).
const TEXT_COLUMNS: usize = 120;

/// `text` onto `s`, wrapped at [`TEXT_COLUMNS`] with continuation lines indented `indent` more.
fn prose(s: &mut String, text: &str, indent: usize) {
    s.push_str(&crate::wrap::wrap(text, TEXT_COLUMNS, indent));
}

fn list(v: &[String]) -> String {
    if v.is_empty() {
        "none".to_owned()
    } else {
        v.join(", ")
    }
}

/// The plan as text.
pub fn render_plan(r: &PlanReport) -> String {
    let mut s = String::new();
    let head = format!(
        "infer-club plan: the session's design ({} shots; impact spread {:.1} mm up, {:.1} mm \
         heel-toe) at the start head, planned for {} shots",
        r.n_session, r.impact_spread_mm[0], r.impact_spread_mm[1], r.n_planned
    );
    prose(&mut s, &head, 2);
    prose(&mut s, &format!("Rule: {}.", r.determined_rule), 2);
    let _ = writeln!(
        s,
        "{:<22} {:>12} {:>10} {:>10} {:>10} {:>6} {:>12} {:>10} {:>12}",
        "parameter",
        "start",
        "prior SD",
        "SE",
        "data SE",
        "det.",
        "n to det.",
        "target",
        "n for target"
    );
    for p in &r.params {
        let n = |v: Option<u64>| v.map_or("never".to_owned(), |n| n.to_string());
        let _ = writeln!(
            s,
            "{:<22} {:>12} {:>10} {:>10} {:>10} {:>6} {:>12} {:>10} {:>12}",
            p.name,
            fmt_num(p.start),
            fmt_num(p.prior_sd),
            fmt_num(p.stderr),
            fmt_opt(p.data_stderr),
            if p.determined { "yes" } else { "no" },
            n(p.shots_to_determine),
            fmt_opt(p.target_stderr),
            if p.target_stderr.is_some() {
                n(p.shots_for_target)
            } else {
                "-".to_owned()
            },
        );
    }
    for w in &r.weak_directions {
        prose(&mut s, &format!("weak: {w}"), 2);
    }
    s
}
