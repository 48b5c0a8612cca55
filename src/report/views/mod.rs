//! The parts the JSON reports of `diagnose` and `calibrate` share, as view models: plain
//! `Serialize` values filled once from the domain (with their verdicts: plausibility, stand-in,
//! ambiguity, spread band), which the JSON writes as they are. The schema: `docs/json.md`.
//!
//! A report's JSON is its view serialised in the canonical key order of `report::json::canonical`
//! (`schema_version` and `command` first, then every object's keys in byte order), so a view
//! declares its fields in the order that reads best.
//!
//! Here the small shared parts (component maps, error tables, likelihoods, estimates with their
//! plausibility); the readings of a diagnosis (aliases, rivals, ambiguities, the unresolved
//! candidate, rival families) in `readings.rs`; the strata check in `strata.rs`; the noise floor
//! and the shapes of the errors in `noise_floor.rs`. Their types are re-exported here.

mod noise_floor;
mod readings;
mod strata;

pub use noise_floor::*;
pub use readings::*;
pub use strata::*;

use std::collections::BTreeMap;

use serde::Serialize;

use crate::diagnose::honest;
use crate::fit::{Likelihood, ParamEstimate};
use crate::measurement::DeliveryNoise;
use crate::model::DeliveryVar;
use crate::physics::LaunchComponent;
use crate::stats::ErrorTable;

/// One value per launch component, keyed by its column name.
pub type ComponentMap = BTreeMap<&'static str, f64>;

/// `v` keyed by the launch components' column names.
pub fn components(v: &[f64; 5]) -> ComponentMap {
    LaunchComponent::ALL
        .iter()
        .map(|c| (c.column(), v[c.index()]))
        .collect()
}

/// Mean and standard deviation of one component's errors in one group.
#[derive(Debug, Clone, Serialize)]
pub struct MeanStd {
    /// Mean error, file units.
    pub mean: f64,
    /// Standard deviation of the errors, file units.
    pub std: f64,
}

/// An error table in JSON: `{group: {component: {mean, std}}}`.
pub type ErrorTableView = BTreeMap<String, BTreeMap<&'static str, MeanStd>>;

/// `t` as `{group: {component: {mean, std}}}`.
pub fn error_table(t: &ErrorTable) -> ErrorTableView {
    t.groups
        .iter()
        .map(|g| {
            let comps = LaunchComponent::ALL
                .iter()
                .zip(&g.components)
                .map(|(c, ms)| {
                    (
                        c.column(),
                        MeanStd {
                            mean: ms.mean,
                            std: ms.std,
                        },
                    )
                })
                .collect();
            (g.group.clone(), comps)
        })
        .collect()
}

/// A delivery noise as `{column: sd}` for the noisy variables (file units).
pub fn delivery_noise(noise: &DeliveryNoise) -> BTreeMap<&'static str, f64> {
    DeliveryVar::ALL
        .into_iter()
        .filter(|&v| crate::report::delivery_noise::settable(v) && noise.sd[v.index()] > 0.0)
        .map(|v| (v.column(), noise.sd[v.index()]))
        .collect()
}

/// A likelihood score's scale-free numbers.
#[derive(Debug, Clone, Serialize)]
pub struct Score {
    /// Parameters.
    pub k: usize,
    /// `−2 ln L`.
    pub minus_2_ln_l: f64,
    /// AIC.
    pub aic: f64,
    /// BIC.
    pub bic: f64,
    /// The scales per component, file units.
    pub scales: ComponentMap,
}

impl Score {
    /// The score of `l`.
    pub fn of(l: &Likelihood) -> Self {
        Self {
            k: l.k,
            minus_2_ln_l: l.minus_2_ln_l,
            aic: l.aic(),
            bic: l.bic(),
            scales: components(&l.scales),
        }
    }
}

/// How the models were scored, with the scores of the fitted model (under its own name) and of
/// the nominal one.
#[derive(Debug, Clone, Serialize)]
pub struct LikelihoodView {
    /// `profiled` or `given`.
    pub scales: &'static str,
    /// What gave the scales (a noise file or class), when given.
    pub given_by: Option<String>,
    /// Residuals scored.
    pub n_residuals: usize,
    /// The nominal model's score.
    pub nominal: Score,
    /// The fitted model's score, under its name (`final`, `calibrated`).
    #[serde(flatten)]
    pub fitted: BTreeMap<&'static str, Score>,
}

impl LikelihoodView {
    /// The scoring of `first` (named `name`) and `nominal`.
    pub fn new(name: &'static str, first: &Likelihood, nominal: &Likelihood) -> Self {
        Self {
            scales: first.source.kind(),
            given_by: first.source.name().map(str::to_owned),
            n_residuals: first.n_residuals,
            nominal: Score::of(nominal),
            fitted: BTreeMap::from([(name, Score::of(first))]),
        }
    }
}

/// An estimate's plausibility: whether its value lies in the plausible range of a real head,
/// that range, and what an implausible value behaves like.
#[derive(Debug, Clone, Serialize)]
pub struct Plausibility {
    /// In the plausible range (`None`: the parameter has none).
    pub plausible: Option<bool>,
    /// `[low, high]` in the parameter's unit.
    pub plausible_range: Option<[f64; 2]>,
    /// What an implausible value stands in for.
    pub stand_in: Option<&'static str>,
}

impl Plausibility {
    /// The plausibility of `p`.
    pub fn of(p: &ParamEstimate) -> Self {
        Self {
            plausible: honest::is_plausible(p),
            plausible_range: honest::spec_of(p).map(|s| [s.plausible.0, s.plausible.1]),
            stand_in: honest::stand_in(p),
        }
    }
}

/// An estimate with its effect, group, value, standard error, unit and plausibility: what
/// diagnose's and calibrate's JSON say of every fitted parameter (each adds its own keys).
#[derive(Debug, Clone, Serialize)]
pub struct Estimate {
    /// The effect.
    pub effect: &'static str,
    /// The parameter's key.
    pub param: &'static str,
    /// The group, for a per-group effect.
    pub group: Option<String>,
    /// Value, in `unit`.
    pub value: f64,
    /// Standard error (`None`: not estimable).
    pub stderr: Option<f64>,
    /// Unit.
    pub unit: &'static str,
    /// Its plausibility.
    #[serde(flatten)]
    pub plausibility: Plausibility,
}

impl Estimate {
    /// The view of `p`.
    pub fn of(p: &ParamEstimate) -> Self {
        Self {
            effect: p.effect,
            param: p.param,
            group: p.group.clone(),
            value: p.value,
            stderr: p.stderr,
            unit: p.unit,
            plausibility: Plausibility::of(p),
        }
    }
}

/// An estimate in a list of values: its label, value, unit and plausibility.
#[derive(Debug, Clone, Serialize)]
pub struct Brief {
    /// `effect[@group].param`.
    pub param: String,
    /// Value, in `unit`.
    pub value: f64,
    /// Unit.
    pub unit: &'static str,
    /// In the plausible range (`None`: the parameter has none).
    pub plausible: Option<bool>,
}

impl Brief {
    /// `p` in brief.
    pub fn of(p: &ParamEstimate) -> Self {
        Self {
            param: p.label(),
            value: p.value,
            unit: p.unit,
            plausible: honest::is_plausible(p),
        }
    }
}

/// Estimates in brief.
pub(super) fn briefs(ps: &[ParamEstimate]) -> Vec<Brief> {
    ps.iter().map(Brief::of).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::launch_error_table;

    /// An error table in JSON: per group and component its mean and spread; a group of one shot
    /// has no spread, which the JSON says with `null` (never NaN).
    #[test]
    fn error_tables_key_groups_and_components_and_say_null_for_no_spread() {
        let t = launch_error_table(&["B", "A", "B"], &[[1.0; 5], [2.0; 5], [3.0; 5]]);
        let j = serde_json::to_value(error_table(&t)).unwrap();
        assert_eq!(j["B"]["ball_speed_mph"]["mean"], 2.0);
        assert!(j["A"]["ball_speed_mph"]["std"].is_null());
        assert_eq!(j["A"]["ball_speed_mph"]["mean"], 2.0);
    }
}
