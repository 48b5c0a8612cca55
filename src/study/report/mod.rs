//! The report of a study run, as one typed value ([`StudyReport`]) built from the run's results
//! in memory (the prepared study, each variant's metrics and coarse face maps, the
//! sensitivities, the optimiser's and the yard part's results), never from its output files;
//! and its renderers beside it: text for the terminal ([`text`]), the HTML page of
//! `smash run --report` ([`html`]), and JSON (serde of the same value, `smash run --json`).
//!
//! Variants keep the integer ids of the output files (`variants.csv`, `maps/v<id>_…`). The
//! base is the variant with every design variable at its neutral value (the club as given);
//! a study whose variants all change the club compares against variant 0 and says so.

pub mod html;
mod render;
pub mod text;
pub mod whatif;

pub use render::StudyContext;

use std::fmt::Write as _;

use serde::Serialize;

use super::design::DesignVar;
use super::metrics::{metric_names, metric_unit, Metric, Output};
use super::optimise::OptimiseResult;
use super::sensitivity::Sensitivity;
use super::spec::Goal;
use super::sweep::Prepared;
use super::yards_run::YardsResult;
use super::yards_variants::{delta, QUANTITIES};
use crate::report::heatmap::{shared_limits, BlockMeans, Scale};

/// Version of the JSON form of [`StudyReport`] (`schema_version`, as every command's JSON);
/// raised when a field changes meaning or goes away (`docs/json.md`).
pub const SCHEMA_VERSION: u32 = 1;

/// Most variants drawn as small multiples: the base and the variants whose maps differ most
/// from it (a meeting reads two dozen maps; every map is in the output folder).
pub const MAX_MULTIPLES: usize = 24;

/// The headline metrics of the summary and the text table: name, short header, decimals in text.
pub const HEADLINE: [(&str, &str, usize); 7] = [
    ("cof_ball_speed_mph", "CoF mph", 3),
    ("speed_loss_toe_mph_per_mm", "toe", 3),
    ("speed_loss_heel_mph_per_mm", "heel", 3),
    ("speed_loss_crown_mph_per_mm", "crown", 3),
    ("speed_loss_sole_mph_per_mm", "sole", 3),
    ("gear_sidespin_rpm_per_mm", "side", 2),
    ("gear_backspin_rpm_per_mm", "back", 2),
];

/// Everything a study run reports.
#[derive(Debug, Clone, Serialize)]
pub struct StudyReport {
    /// [`SCHEMA_VERSION`].
    pub schema_version: u32,
    /// `"run"` (a merge of shards reports the unsharded run).
    pub command: &'static str,
    /// The study's name.
    pub name: String,
    /// The club's name.
    pub club: String,
    /// The club's group whose calibration effects apply.
    pub group: String,
    /// The question the study answers, in a sentence.
    pub question: String,
    /// The design variables the variants change: key and unit.
    pub axes: Vec<Axis>,
    /// The id of the variant the others are compared with.
    pub base_id: usize,
    /// Whether that variant is the club as given (every variable neutral).
    pub base_is_club: bool,
    /// Summary metrics: name and unit, in the order of each variant's `metrics`.
    pub metrics: Vec<Axis>,
    /// Decimals that tell each metric's variants apart (same order as `metrics`).
    pub metric_decimals: Vec<usize>,
    /// Every variant, by id.
    pub variants: Vec<Variant>,
    /// Per headline metric, the variants with the lowest and highest change from the base.
    pub highlights: Vec<Highlight>,
    /// Face maps per output, for the variants shown.
    pub face_maps: Vec<OutputMaps>,
    /// d metric / d variable at the base design, per variable.
    pub sensitivities: Vec<SensitivityRow>,
    /// The optimiser's result, when the study has an `[optimise]` table.
    pub optimiser: Option<OptimiserReport>,
    /// The yard part, when the study has a `[yards]` table.
    pub yards: Option<YardsReport>,
}

/// A named quantity with its unit.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Axis {
    /// Name as in the files (`com_dx_mm`, `cof_ball_speed_mph`).
    pub name: String,
    /// Unit (`mm`, `mph/mm`, `1`).
    pub unit: String,
}

/// One design variant.
#[derive(Debug, Clone, Serialize)]
pub struct Variant {
    /// Integer id, as in the output files.
    pub id: usize,
    /// The value of each design variable (same order as [`StudyReport::axes`]).
    pub design: Vec<f64>,
    /// What it changes, `key = value, …` (`base` when nothing).
    pub changes: String,
    /// Summary metrics (same order as [`StudyReport::metrics`]).
    pub metrics: Vec<f64>,
    /// Each metric minus the base's.
    pub deltas: Vec<f64>,
}

/// The extremes of one metric's change across the variants.
#[derive(Debug, Clone, Serialize)]
pub struct Highlight {
    /// The metric.
    pub metric: String,
    /// Its unit.
    pub unit: String,
    /// The base's value.
    pub base: f64,
    /// Id and change of the variant with the lowest change.
    pub lowest: (usize, f64),
    /// Id and change of the variant with the highest change.
    pub highest: (usize, f64),
}

/// The face maps of one output: one per shown variant on one shared colour scale, and each
/// shown variant's difference from the base on one symmetric scale.
#[derive(Debug, Clone, Serialize)]
pub struct OutputMaps {
    /// Output column (`ball_speed_mph`).
    pub column: String,
    /// Label (`Ball speed`).
    pub label: String,
    /// Unit.
    pub unit: String,
    /// Whether the values are signed (a diverging scale).
    pub signed: bool,
    /// Block centres toward the toe, mm.
    pub zs_mm: Vec<f64>,
    /// Block centres up the face, mm.
    pub ys_mm: Vec<f64>,
    /// The ids of the variants shown, ascending (the base among them).
    pub ids: Vec<usize>,
    /// Their maps (block means, row-major over `ys_mm × zs_mm`; NaN, in JSON `null`: no value).
    pub values: Vec<Vec<f64>>,
    /// Colour limits shared by every map of `values`.
    pub limits: (f64, f64),
    /// Each shown variant's map minus the base's, the base's own left out (same order as
    /// `ids` without the base).
    pub diffs: Vec<Vec<f64>>,
    /// Symmetric colour limits `(−m, m)` shared by every difference map.
    pub diff_limits: (f64, f64),
    /// Largest |difference| on the face per shown variant (same order as `diffs`).
    pub max_abs_diff: Vec<f64>,
}

/// The sensitivities to one design variable.
#[derive(Debug, Clone, Serialize)]
pub struct SensitivityRow {
    /// The variable and its unit.
    pub variable: Axis,
    /// Central-difference step.
    pub step: f64,
    /// d metric / d variable (same order as [`StudyReport::metrics`]).
    pub metrics: Vec<f64>,
}

/// What the optimiser found.
#[derive(Debug, Clone, Serialize)]
pub struct OptimiserReport {
    /// `minimise` or `maximise`.
    pub goal: &'static str,
    /// The objective: weight and metric per term.
    pub objective: Vec<(f64, String)>,
    /// The base design's objective.
    pub base_objective: f64,
    /// The optimum's objective.
    pub best_objective: f64,
    /// The optimum's changes, `key = value, …`.
    pub best: String,
    /// The optimum's changed design variables: key and value (unit in the key).
    pub best_design: Vec<(String, f64)>,
    /// Iterations run.
    pub iterations: u64,
    /// Objective evaluations.
    pub evaluations: usize,
    /// Why the solver stopped.
    pub termination: String,
    /// The best objective after each iteration: `(iteration, objective)`.
    pub path: Vec<(u64, f64)>,
    /// Base and optimum metrics (same order as [`StudyReport::metrics`]).
    pub base_metrics: Vec<f64>,
    /// The optimum's metrics.
    pub best_metrics: Vec<f64>,
}

/// The yard part: every head against the base, and the head constraints.
#[derive(Debug, Clone, Serialize)]
pub struct YardsReport {
    /// The compared quantities: column and unit.
    pub quantities: Vec<Axis>,
    /// Per head (the base first): label, design, values, changes and their uncertainties.
    pub rows: Vec<YardsRow>,
    /// The constraints at the base design.
    pub constraints: Vec<ConstraintRow>,
}

/// One head of the yard part.
#[derive(Debug, Clone, Serialize)]
pub struct YardsRow {
    /// `base`, `variant 3`, `optimum (…)`.
    pub label: String,
    /// Its changes.
    pub design: String,
    /// Each quantity.
    pub values: Vec<f64>,
    /// Each quantity's change from the base.
    pub deltas: Vec<f64>,
    /// The changes' quadrature uncertainty, where there is one.
    pub uncertainties: Vec<Option<f64>>,
}

/// One head constraint at the base design.
#[derive(Debug, Clone, Serialize)]
pub struct ConstraintRow {
    /// What is constrained (with unit).
    pub name: String,
    /// The value.
    pub value: f64,
    /// The limit.
    pub limit: f64,
    /// ≥ 0 when it holds.
    pub margin: f64,
}

/// The results of a run that the report is built from.
#[derive(Debug, Clone, Copy)]
pub struct RunResults<'a> {
    /// Each variant's summary metrics.
    pub metrics: &'a [Vec<f64>],
    /// Each variant's face maps (one per output), as written ([`super::output::write_study_maps`]).
    pub face_maps: &'a [Vec<BlockMeans>],
    /// Sensitivities at the base design.
    pub sensitivities: &'a [Sensitivity],
    /// The optimiser's result.
    pub optimiser: Option<&'a OptimiseResult>,
    /// The yard part's result.
    pub yards: Option<&'a YardsResult>,
}

/// Decimals that show the smallest non-zero difference between `values` to two significant
/// digits (0 to 8).
pub fn decimals_apart(values: &[f64]) -> usize {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    let scale = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let smallest = v
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > scale * 1e-12)
        .fold(f64::INFINITY, f64::min);
    if !smallest.is_finite() {
        return if scale >= 100.0 { 1 } else { 3 };
    }
    (1.0 - smallest.log10().floor()).clamp(0.0, 8.0) as usize
}

impl StudyReport {
    /// The report of `p`'s run.
    pub fn new(p: &Prepared, r: &RunResults<'_>) -> Self {
        let s = &p.study;
        let names = metric_names(s.distribution.is_some());
        let base_id = p
            .variants
            .iter()
            .position(|d| DesignVar::ALL.iter().all(|v| d.get(*v) == v.neutral()));
        let base = base_id.unwrap_or(0);
        let axes: Vec<DesignVar> = s.design.axes.iter().map(|(v, _)| *v).collect();
        let variants: Vec<Variant> = p
            .variants
            .iter()
            .zip(r.metrics)
            .enumerate()
            .map(|(id, (d, m))| Variant {
                id,
                design: axes.iter().map(|v| d.get(*v)).collect(),
                changes: d.describe(),
                metrics: m.clone(),
                deltas: m.iter().zip(&r.metrics[base]).map(|(a, b)| a - b).collect(),
            })
            .collect();
        let metric_decimals = (0..names.len())
            .map(|j| {
                let v: Vec<f64> = r.metrics.iter().map(|m| m[j]).collect();
                decimals_apart(&v)
            })
            .collect();
        Self {
            schema_version: SCHEMA_VERSION,
            command: "run",
            name: s.name.clone(),
            club: s.club.name.clone(),
            group: s.group.clone(),
            question: question(p),
            axes: axes
                .iter()
                .map(|v| Axis {
                    name: v.key().into(),
                    unit: v.unit().into(),
                })
                .collect(),
            base_id: base,
            base_is_club: base_id.is_some(),
            highlights: highlights(&names, &variants, base),
            face_maps: face_maps(p, r.face_maps, base),
            metrics: names
                .iter()
                .map(|n| Axis {
                    name: n.clone(),
                    unit: metric_unit(n),
                })
                .collect(),
            metric_decimals,
            variants,
            sensitivities: r
                .sensitivities
                .iter()
                .map(|x| SensitivityRow {
                    variable: Axis {
                        name: x.var.key().into(),
                        unit: x.var.unit().into(),
                    },
                    step: x.step,
                    metrics: x.metrics.clone(),
                })
                .collect(),
            optimiser: r.optimiser.map(|o| optimiser(p, o)),
            yards: r.yards.map(yards),
        }
    }

    /// The position of metric `name` in [`StudyReport::metrics`].
    pub fn metric_index(&self, name: &str) -> Option<usize> {
        self.metrics.iter().position(|m| m.name == name)
    }
}

/// The question of the study, in a sentence.
fn question(p: &Prepared) -> String {
    let s = &p.study;
    let vars: Vec<&str> = s.design.axes.iter().map(|(v, _)| v.key()).collect();
    let outputs: Vec<String> = s.outputs.iter().map(|o| o.label().to_lowercase()).collect();
    let mut q = if vars.is_empty() {
        format!("What are the {} over the face", outputs.join(", "))
    } else {
        format!(
            "How do {} ({} variants) change the {} over the face",
            vars.join(", "),
            p.variants.len(),
            outputs.join(", ")
        )
    };
    q.push_str(&format!(
        " of {} at {} mph",
        s.club.name, s.swing.club_speed_mph
    ));
    if s.distribution.is_some() {
        q.push_str(", and the mean and spread over the impact distribution");
    }
    if let Some(o) = &s.optimise {
        let goal = match o.goal {
            Goal::Minimise => "minimises",
            Goal::Maximise => "maximises",
        };
        q.push_str(&format!(
            "; and which design within the bounds {goal} {}",
            objective_text(o.objective.iter().map(|(m, w)| (*w, m.as_str())))
        ));
    }
    if s.yards.is_some() {
        q.push_str("; and what each design does in yards");
    }
    q.push('?');
    q
}

/// An objective `Σ weight · metric` as text: `1 × a − 0.001 × b`.
pub fn objective_text<'a>(terms: impl IntoIterator<Item = (f64, &'a str)>) -> String {
    let mut s = String::new();
    for (k, (w, m)) in terms.into_iter().enumerate() {
        let sign = match (k, w < 0.0) {
            (0, true) => "−",
            (0, false) => "",
            (_, true) => " − ",
            (_, false) => " + ",
        };
        let _ = write!(s, "{sign}{} × {m}", crate::limits::fmt_value(w.abs()));
    }
    s
}

/// Per headline metric the study computes (and `mean_*`/`std_*` of ball speed with a
/// distribution), the variants with the lowest and highest change from the base.
fn highlights(names: &[String], variants: &[Variant], base: usize) -> Vec<Highlight> {
    let mut picked: Vec<&str> = HEADLINE.iter().map(|h| h.0).collect();
    picked.extend(["mean_ball_speed_mph", "std_ball_speed_mph"]);
    let mut out = Vec::new();
    for name in picked {
        let Some(j) = names.iter().position(|n| n == name) else {
            continue;
        };
        let by = |pick: fn(f64, f64) -> bool| {
            variants.iter().fold((base, 0.0), |(bi, bd), v| {
                if pick(v.deltas[j], bd) {
                    (v.id, v.deltas[j])
                } else {
                    (bi, bd)
                }
            })
        };
        out.push(Highlight {
            metric: name.into(),
            unit: Metric::from_name(name).map_or("1", Metric::unit).into(),
            base: variants[base].metrics[j],
            lowest: by(|d, best| d < best),
            highest: by(|d, best| d > best),
        });
    }
    out
}

/// The block means of every variant's maps as [`OutputMaps`]: the base and the variants most
/// different from it on the first output, at most [`MAX_MULTIPLES`].
fn face_maps(p: &Prepared, blocks: &[Vec<BlockMeans>], base: usize) -> Vec<OutputMaps> {
    let cells = |i: usize, o: usize| blocks[i][o].cells(&p.zs_mm, &p.ys_mm);
    let outputs: Vec<Output> = p.study.outputs.clone();
    if blocks.len() != p.variants.len() || outputs.is_empty() {
        return Vec::new();
    }
    let diff = |a: &[f64], b: &[f64]| -> Vec<f64> { a.iter().zip(b).map(|(x, y)| x - y).collect() };
    let rms = |d: &[f64]| {
        let f: Vec<f64> = d.iter().copied().filter(|x| x.is_finite()).collect();
        (f.iter().map(|x| x * x).sum::<f64>() / f.len().max(1) as f64).sqrt()
    };
    let base0 = cells(base, 0).2;
    let mut ranked: Vec<(f64, usize)> = (0..blocks.len())
        .filter(|i| *i != base)
        .map(|i| (rms(&diff(&cells(i, 0).2, &base0)), i))
        .collect();
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut ids: Vec<usize> = ranked.iter().take(MAX_MULTIPLES - 1).map(|r| r.1).collect();
    ids.push(base);
    ids.sort_unstable();
    outputs
        .iter()
        .enumerate()
        .map(|(o, out)| {
            let (zs, ys, base_values) = cells(base, o);
            let values: Vec<Vec<f64>> = ids.iter().map(|&i| cells(i, o).2).collect();
            let diffs: Vec<Vec<f64>> = ids
                .iter()
                .filter(|&&i| i != base)
                .map(|&i| diff(&cells(i, o).2, &base_values))
                .collect();
            let scale = if out.signed() {
                Scale::Diverging
            } else {
                Scale::Sequential
            };
            OutputMaps {
                column: out.column().into(),
                label: out.label().into(),
                unit: out.unit().into(),
                signed: out.signed(),
                zs_mm: zs,
                ys_mm: ys,
                limits: shared_limits(values.iter().flatten(), scale).unwrap_or((0.0, 1.0)),
                diff_limits: shared_limits(diffs.iter().flatten(), Scale::Diverging)
                    .unwrap_or((-1.0, 1.0)),
                max_abs_diff: diffs
                    .iter()
                    .map(|d| {
                        d.iter()
                            .filter(|x| x.is_finite())
                            .fold(0.0, |m, x| x.abs().max(m))
                    })
                    .collect(),
                ids: ids.clone(),
                values,
                diffs,
            }
        })
        .collect()
}

/// The optimiser's result as reported.
fn optimiser(p: &Prepared, o: &OptimiseResult) -> OptimiserReport {
    let spec = p.study.optimise.as_ref();
    OptimiserReport {
        goal: match spec.map(|s| s.goal) {
            Some(Goal::Minimise) => "minimise",
            _ => "maximise",
        },
        objective: spec.map_or_else(Vec::new, |s| {
            s.objective.iter().map(|(m, w)| (*w, m.clone())).collect()
        }),
        base_objective: o.base_objective,
        best_objective: o.best_objective,
        best: o.best.describe(),
        best_design: DesignVar::ALL
            .iter()
            .filter(|v| o.best.get(**v) != v.neutral())
            .map(|v| (v.key().to_owned(), o.best.get(*v)))
            .collect(),
        iterations: o.path.last().map_or(0, |p| p.iteration),
        evaluations: o.evaluations,
        termination: o.termination.clone(),
        path: o.path.iter().map(|p| (p.iteration, p.objective)).collect(),
        base_metrics: o.base_metrics.clone(),
        best_metrics: o.best_metrics.clone(),
    }
}

/// The yard part as reported.
fn yards(r: &YardsResult) -> YardsReport {
    YardsReport {
        quantities: QUANTITIES
            .iter()
            .map(|q| Axis {
                name: q.column.into(),
                unit: q.unit.into(),
            })
            .collect(),
        rows: r
            .rows
            .iter()
            .map(|row| {
                let d: Vec<(f64, Option<f64>)> = QUANTITIES
                    .iter()
                    .map(|q| delta(q, &r.base_head, &row.head))
                    .collect();
                YardsRow {
                    label: row.label.clone(),
                    design: row.design.clone(),
                    values: QUANTITIES
                        .iter()
                        .map(|q| (q.get)(&row.head.metrics))
                        .collect(),
                    deltas: d.iter().map(|x| x.0).collect(),
                    uncertainties: d.iter().map(|x| x.1).collect(),
                }
            })
            .collect(),
        constraints: r
            .base_constraints
            .iter()
            .map(|c| ConstraintRow {
                name: c.name.clone(),
                value: c.value,
                limit: c.limit,
                margin: c.margin,
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals_tell_the_closest_values_apart() {
        // 146.21 and 146.24 differ by 0.03: three decimals show it to two digits.
        let d = decimals_apart(&[146.21, 146.24, 147.0]);
        assert_eq!(d, 3);
        assert_ne!(format!("{:.d$}", 146.21), format!("{:.d$}", 146.24));
        // Three significant figures (what the page once showed) print both as 146.
        assert_eq!(format!("{:.0}", 146.21), format!("{:.0}", 146.24));
        assert_eq!(decimals_apart(&[1.0, 3.0]), 1);
        // Equal values: a fixed default; NaN is ignored.
        assert_eq!(decimals_apart(&[146.0, 146.0, f64::NAN]), 1);
        assert_eq!(decimals_apart(&[0.5]), 3);
    }

    #[test]
    fn objectives_read_with_their_signs() {
        let t = objective_text([(1.0, "a"), (-0.001, "b"), (2.5, "c")]);
        assert_eq!(t, "1 × a − 0.001 × b + 2.5 × c");
        assert_eq!(objective_text([(-1.0, "a")]), "−1 × a");
    }
}
