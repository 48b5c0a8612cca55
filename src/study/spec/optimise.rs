//! The `[optimise]` table: a weighted objective of metrics over bounded design variables.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::defaults;
use super::design::design_var;
use crate::data::toml_check::did_you_mean;
use crate::data::{DataError, TomlDoc};
use crate::limits;
use crate::study::design::{DesignVar, DiscretionaryMass};
use crate::study::metrics::metric_names;

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

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawOptimise {
    pub goal: Spanned<String>,
    pub max_iters: Option<Spanned<i64>>,
    pub tolerance: Option<Spanned<f64>>,
    pub objective: Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>,
    pub bounds: Spanned<BTreeMap<Spanned<String>, Spanned<[f64; 2]>>>,
}

pub(super) fn parse_optimise(
    doc: &TomlDoc<'_>,
    o: &RawOptimise,
    has_distribution: bool,
    mass: Option<&DiscretionaryMass>,
) -> Result<OptimiseSpec, DataError> {
    let goals = [
        ("maximise", Goal::Maximise),
        ("maximize", Goal::Maximise),
        ("minimise", Goal::Minimise),
        ("minimize", Goal::Minimise),
    ];
    let goal = doc.one_of(
        o.goal.span(),
        "optimise.goal",
        "goal",
        o.goal.get_ref(),
        &goals,
    )?;
    Ok(OptimiseSpec {
        goal,
        objective: parse_objective(doc, &o.objective, has_distribution)?,
        bounds: parse_bounds(doc, &o.bounds, mass.is_some())?,
        max_iters: o.max_iters.as_ref().map_or(Ok(defaults::MAX_ITERS), |m| {
            doc.count(m, "optimise.max_iters", (1, 100_000))
                .map(|x| x as u64)
        })?,
        tolerance: o.tolerance.as_ref().map_or(Ok(defaults::TOLERANCE), |t| {
            doc.positive(t, "optimise.tolerance", "objective units")
        })?,
    })
}

/// Largest size of an objective weight. The metrics are at most ~1e4 in their units (rpm), so
/// each term of the objective stays below ~1e10: far from overflow (a weight of 1e308 made the
/// objective infinite), and a sum of opposite-signed terms still resolves a change of the
/// smaller one.
const MAX_WEIGHT: f64 = 1e6;

fn parse_objective(
    doc: &TomlDoc<'_>,
    objective: &Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>,
    has_distribution: bool,
) -> Result<Vec<(String, f64)>, DataError> {
    let names = metric_names(has_distribution);
    let mut out = Vec::new();
    for (k, w) in objective.get_ref() {
        let name = k.get_ref();
        let key = format!("optimise.objective.{name}");
        if !names.iter().any(|n| n == name) {
            let hint = if name.starts_with("mean_") || name.starts_with("std_") {
                " (mean_* and std_* need a [distribution])".to_owned()
            } else {
                did_you_mean(name, names.iter().map(String::as_str))
                    .map_or_else(String::new, |m| format!(" (did you mean '{m}'?)"))
            };
            return Err(doc.err(
                k.span(),
                &key,
                format!("unknown metric{hint}; allowed: {}", names.join(", ")),
            ));
        }
        let span = w.span();
        let w = doc.finite(w, &key, "weight")?;
        if w.abs() > MAX_WEIGHT {
            return Err(doc.err(
                span,
                &key,
                format!(
                    "weight {} is too large: allowed within [-{max}, {max}] (the objective adds \
                     weight × metric in the metrics' own units, mph and rpm; a larger weight \
                     overflows it)",
                    crate::limits::fmt_value(w),
                    max = crate::limits::fmt_value(MAX_WEIGHT)
                ),
            ));
        }
        if w != 0.0 {
            out.push((name.clone(), w));
        }
    }
    if out.is_empty() {
        return Err(doc.err(
            objective.span(),
            "optimise.objective",
            format!(
                "give at least one metric with a non-zero weight, e.g. {{ mean_ball_speed_mph = \
                 1.0 }}; allowed: {}",
                names.join(", ")
            ),
        ));
    }
    Ok(out)
}

fn parse_bounds(
    doc: &TomlDoc<'_>,
    bounds: &Spanned<BTreeMap<Spanned<String>, Spanned<[f64; 2]>>>,
    has_mass: bool,
) -> Result<Vec<(DesignVar, f64, f64)>, DataError> {
    let mut out = Vec::new();
    for (k, b) in bounds.get_ref() {
        let key = format!("optimise.bounds.{}", k.get_ref());
        let var = design_var(doc, k, &key, false)?;
        let [lo, hi] = *b.get_ref();
        let n = var.neutral();
        if !(lo.is_finite() && hi.is_finite() && lo < hi && lo <= n && n <= hi) {
            return Err(doc.err(
                b.span(),
                &key,
                format!(
                    "must be [lower, upper], finite, lower < upper, containing the base value \
                     {n}; got [{}, {}]",
                    limits::fmt_value(lo),
                    limits::fmt_value(hi)
                ),
            ));
        }
        for x in [lo, hi] {
            var.range()
                .check(x)
                .map_err(|m| doc.err(b.span(), &key, m))?;
        }
        if var.needs_discretionary_mass() && !has_mass {
            return Err(doc.err(k.span(), &key, "needs design.discretionary_mass"));
        }
        out.push((var, lo, hi));
    }
    if out.is_empty() {
        return Err(doc.err(
            bounds.span(),
            "optimise.bounds",
            format!(
                "give at least one design variable with [lower, upper]; allowed: {}",
                DesignVar::all_keys()
            ),
        ));
    }
    out.sort_by_key(|b| b.0);
    Ok(out)
}

/// The optimisation as an `[optimise]` table.
pub(super) fn raw_optimise(o: &OptimiseSpec) -> RawOptimise {
    let s = |x: &str| Spanned::new(0..0, x.to_owned());
    let goal = match o.goal {
        Goal::Maximise => "maximise",
        Goal::Minimise => "minimise",
    };
    RawOptimise {
        goal: s(goal),
        max_iters: Some(Spanned::new(0..0, o.max_iters as i64)),
        tolerance: Some(Spanned::new(0..0, o.tolerance)),
        objective: Spanned::new(
            0..0,
            o.objective
                .iter()
                .map(|(k, w)| (s(k), Spanned::new(0..0, *w)))
                .collect(),
        ),
        bounds: Spanned::new(
            0..0,
            o.bounds
                .iter()
                .map(|(v, lo, hi)| (s(v.key()), Spanned::new(0..0, [*lo, *hi])))
                .collect(),
        ),
    }
}
