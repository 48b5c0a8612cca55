//! The pages of `smash compare --report` and `smash calibrate --report`, from their reports.

use super::figures::{face_figures, findings_html, table2_figures, table2_html, trend_figures};
use super::{Page, Section, ShotResiduals};
use crate::compare::CompareReport;
use crate::report::charts::ChartError;

/// The page of `smash compare --report`.
pub fn compare_page(
    report: &CompareReport,
    residuals: &ShotResiduals,
    title: &str,
) -> Result<String, ChartError> {
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
    r: &crate::report::calibrate::CalibrateReport,
    after: &CompareReport,
    residuals: &ShotResiduals,
    title: &str,
) -> Result<String, ChartError> {
    let cal = &r.calibration;
    let (table, est_figs) = super::diagnose::estimates_html(&cal.params, "Fitted parameters")?;
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
