//! The pages of `smash compare --report` and `smash calibrate --report`, from their reports.

use std::fmt::Write as _;

use super::figures::{face_figures, findings_html, table2_figures, table2_html, trend_figures};
use super::{esc, Figure, Page, Section, ShotResiduals};
use crate::compare::{sig3, CompareReport};

/// The page of `smash compare --report`.
pub fn compare_page(
    report: &CompareReport,
    residuals: &ShotResiduals,
    title: &str,
) -> Result<String, String> {
    let before = crate::stats::error_table::ErrorTable {
        groups: report
            .table2
            .iter()
            .map(|g| crate::stats::error_table::GroupErrors {
                group: g.group.clone(),
                n: g.n,
                components: std::array::from_fn(|i| crate::stats::error_table::MeanStd {
                    mean: g.components[i].summary.mean.unwrap_or(f64::NAN),
                    std: g.components[i].summary.std.unwrap_or(f64::NAN),
                }),
            })
            .collect(),
    };
    let page = Page {
        title: "smash compare".into(),
        subtitle: format!(
            "{title} — {} shots; {} of {} tests flagged at {}% ({:.1} expected by chance if the model were right).",
            report.n_shots,
            report.flags,
            report.tests,
            report.alpha * 100.0,
            report.expected_false_flags
        ),
        sections: vec![
            Section {
                heading: "Errors by group (the paper's Table 2 layout)".into(),
                html: vec![
                    table2_html(report),
                    "<p>Bold means differ from zero at the significance level.</p>".into(),
                ],
                figures: table2_figures(&[("model − measured", &before)])?,
            },
            Section {
                heading: "Findings".into(),
                html: vec![findings_html(report)],
                figures: Vec::new(),
            },
            Section {
                heading: "Errors against the delivery".into(),
                html: vec!["<p>For club speed, dynamic loft and the impact location, the launch component whose error changes most with it.</p>".into()],
                figures: trend_figures(report, residuals)?,
            },
            Section {
                heading: "Errors over the face".into(),
                html: Vec::new(),
                figures: face_figures(report),
            },
        ],
    };
    Ok(page.render())
}

/// The page of `smash calibrate --report`: before/after bars, the estimates with their plausible
/// ranges, and the calibrated model's residuals against the delivery and over the face.
pub fn calibrate_page(
    cal: &crate::fit::Calibration,
    after: &CompareReport,
    residuals: &ShotResiduals,
    title: &str,
) -> Result<String, String> {
    use crate::report::charts::{estimates_svg, Estimate};
    let mut est_rows: Vec<(String, Estimate)> = Vec::new();
    let mut table = String::from(
        "<table class=\"params\"><tr><th class=\"l\">parameter</th><th>value</th><th>SE</th><th>unit</th><th>plausible</th></tr>",
    );
    for p in &cal.params {
        let plausible = crate::effects::EffectId::from_name(p.effect).and_then(|k| {
            k.params()
                .iter()
                .find(|s| s.key == p.param)
                .map(|s| s.plausible)
        });
        let _ = write!(
            table,
            "<tr><td class=\"l\">{}</td><td data-key=\"{}\" data-value=\"{:?}\">{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(&p.label()),
            esc(&p.label()),
            p.value,
            sig3(p.value),
            p.stderr.map(sig3).unwrap_or_else(|| "–".into()),
            esc(p.unit),
            plausible.map(|(a, b)| format!("{} to {}", sig3(a), sig3(b))).unwrap_or_default()
        );
        if let Some(pl) = plausible {
            est_rows.push((
                p.unit.to_owned(),
                Estimate {
                    label: p.label(),
                    value: p.value,
                    interval: p.stderr.map(|s| (p.value - 2.0 * s, p.value + 2.0 * s)),
                    plausible: pl,
                },
            ));
        }
    }
    table.push_str("</table>");
    let mut units: Vec<String> = est_rows.iter().map(|(u, _)| u.clone()).collect();
    units.dedup();
    units.sort();
    units.dedup();
    let mut est_figs = Vec::new();
    for u in &units {
        let rows: Vec<Estimate> = est_rows
            .iter()
            .filter(|(x, _)| x == u)
            .map(|(_, e)| e.clone())
            .collect();
        est_figs.push(Figure {
            kind: "estimates",
            caption: format!(
                "Fitted parameters in {u}: estimate ± 2 standard errors against the range a real driver plausibly shows (docs/plausible-ranges.md)."
            ),
            svg: estimates_svg(&format!("Estimates, {u}"), &format!("value, {u}"), &rows)?,
        });
    }
    let page = Page {
        title: "smash calibrate".into(),
        subtitle: format!(
            "{title} — {} parameter(s), method {}; −2 ln L {:.1} → {:.1}, AIC {:.1} → {:.1} (nominal → calibrated; noise scales {}{}); reduced χ² {:.3} (whitened by the fit's own scales).",
            cal.params.len(),
            cal.method.name(),
            cal.likelihood_nominal.minus_2_ln_l,
            cal.likelihood.minus_2_ln_l,
            cal.likelihood_nominal.aic(),
            cal.likelihood.aic(),
            cal.likelihood.source.kind(),
            cal.likelihood.source.name().map_or(String::new(), |n| format!(", {n}")),
            cal.reduced_chi2
        ),
        sections: vec![
            Section {
                heading: "Errors before and after calibration (Table 2 layout)".into(),
                html: vec!["<p>Blue: the nominal model; orange: the calibrated model. Bars are mean errors, error bars one standard deviation of the shots.</p>".into()],
                figures: table2_figures(&[("before (nominal)", &cal.before), ("after (calibrated)", &cal.after)])?,
            },
            Section {
                heading: "Estimates".into(),
                html: vec![table],
                figures: est_figs,
            },
            Section {
                heading: "Calibrated model: errors against the delivery".into(),
                html: Vec::new(),
                figures: trend_figures(after, residuals)?,
            },
            Section {
                heading: "Calibrated model: errors over the face".into(),
                html: Vec::new(),
                figures: face_figures(after),
            },
        ],
    };
    Ok(page.render())
}
