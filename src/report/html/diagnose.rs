//! The page of `smash diagnose --report`, from its [`DiagnoseReport`], and the estimates table
//! and charts it shares with calibrate's page.

use std::fmt::Write as _;

use super::figures::table2_figures;
use super::{esc, Figure, Page, Section};
use crate::compare::sig3;
use crate::diagnose::honest;
use crate::diagnose::strata::StrataCheck;
use crate::diagnose::Diagnosis;
use crate::fit::ParamEstimate;
use crate::report::charts::ChartError;
use crate::report::diagnose::DiagnoseReport;

/// A table of the estimates `params` (a stand-in marked as one) and their charts, one per
/// unit, each captioned `what in UNIT: …` (diagnose's final values, calibrate's fit).
pub(super) fn estimates_html(
    params: &[ParamEstimate],
    what: &str,
) -> Result<(String, Vec<Figure>), ChartError> {
    use crate::report::charts::{estimates_svg, Estimate};
    let mut table = String::from(
        "<table class=\"params\"><tr><th class=\"l\">parameter</th><th>value</th><th>SE</th><th>unit</th><th>plausible</th></tr>",
    );
    let mut rows: Vec<(String, Estimate)> = Vec::new();
    for p in params {
        let (value, se) = (p.value, p.stderr.filter(|s| s.is_finite()));
        if !value.is_finite() {
            continue;
        }
        let unit = p.unit.to_owned();
        let label = p.label();
        let plausible = honest::spec_of(p).map(|s| s.plausible);
        let stand_in = match honest::stand_in(p) {
            Some(w) => format!(
                " <small>(implausible: a stand-in; behaves like {})</small>",
                esc(w)
            ),
            None => String::new(),
        };
        let _ = write!(
            table,
            "<tr><td class=\"l\">{}{stand_in}</td><td data-key=\"{}\" data-value=\"{value:?}\">{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(&label),
            esc(&label),
            sig3(value),
            se.map(sig3).unwrap_or_else(|| "–".into()),
            esc(&unit),
            plausible.map(|(a, b)| format!("{} to {}", sig3(a), sig3(b))).unwrap_or_default()
        );
        if let Some(pl) = plausible {
            rows.push((
                unit,
                Estimate {
                    label,
                    value,
                    interval: se.map(|s| (value - 2.0 * s, value + 2.0 * s)),
                    plausible: pl,
                },
            ));
        }
    }
    table.push_str("</table>");
    let mut units: Vec<String> = rows.iter().map(|(u, _)| u.clone()).collect();
    units.sort();
    units.dedup();
    let mut figs = Vec::new();
    for u in &units {
        let r: Vec<Estimate> = rows
            .iter()
            .filter(|(x, _)| x == u)
            .map(|(_, e)| e.clone())
            .collect();
        figs.push(Figure {
            kind: "estimates",
            caption: format!(
                "{what} in {u}: value ± 2 standard errors against the range a real driver plausibly shows (docs/plausible-ranges.md)."
            ),
            svg: estimates_svg(&format!("Estimates, {u}"), &format!("value, {u}"), &r)?,
        });
    }
    Ok((table, figs))
}

/// The page of `smash diagnose --report`: per step, the cross-validated gain of every
/// candidate against its penalty; the errors before and after the selected effects; the final
/// estimates with their plausible ranges; the strata check.
pub fn diagnose_page(r: &DiagnoseReport, title: &str) -> Result<String, ChartError> {
    let d = &r.diagnosis;
    let mut steps = Vec::new();
    for (i, s) in d.steps.iter().enumerate() {
        let step = i + 1;
        let labels: Vec<String> = s.candidates.iter().map(|c| c.label.clone()).collect();
        let gains: Vec<f64> = s.candidates.iter().map(|c| c.gain).collect();
        let penalties: Vec<f64> = s.candidates.iter().map(|c| c.penalty).collect();
        let chosen = match &s.swap {
            Some(swap) => format!("none (a swap step: {})", swap.text()),
            None => s.selected.clone().unwrap_or_else(|| "none".to_owned()),
        };
        let svg = crate::report::charts::bars_with_line_svg(
            &format!("Step {step}: cross-validated gain per candidate"),
            "CV χ² gain",
            &labels,
            &gains,
            Some((&penalties, "penalty k·ln n")),
        )?;
        let base = if s.base.is_empty() {
            "nominal".to_owned()
        } else {
            s.base.join(", ")
        };
        steps.push(Figure {
            kind: "steps",
            caption: format!(
                "Step {step} (base: {base}): gain in cross-validated χ² of each candidate; a candidate is selected only when its gain beats its penalty (red). Selected: {chosen}."
            ),
            svg,
        });
    }
    let (table, est_figs) = estimates_html(&d.estimates, "Estimates")?;
    let page = Page {
        title: "smash diagnose".into(),
        subtitle: format!(
            "{title} — {} shots, {} folds by {}; selected: {}.",
            d.n_shots,
            d.folds,
            d.fold_by.name(),
            if d.selected.is_empty() {
                "none".to_owned()
            } else {
                d.selected.join(", ")
            }
        ),
        sections: vec![
            Section {
                heading: "Forward selection".into(),
                html: vec![notes_html(r)],
                figures: steps,
            },
            Section {
                heading: "Errors before and after the selected effects".into(),
                html: Vec::new(),
                figures: table2_figures(&[
                    ("before (nominal)", &d.before),
                    ("after (selected)", &d.after),
                ])?,
            },
            Section {
                heading: "Estimates of the selected effects".into(),
                html: vec![table],
                figures: est_figs,
            },
            floor_section(r),
            Section {
                heading: "Stability across strata".into(),
                html: vec![strata_html(d)],
                figures: Vec::new(),
            },
        ],
    };
    Ok(page.render())
}

/// The noise floor's verdict per component and the face map of what remains in each
/// component where structure remains or a shape over the face is found.
fn floor_section(r: &DiagnoseReport) -> Section {
    use crate::report::diagnose::face_map::face_map_svg;
    let html = r
        .floor
        .components
        .iter()
        .map(|c| format!("<p>{}</p>", esc(&c.verdict())))
        .collect();
    let figures = r
        .floor
        .components
        .iter()
        .filter_map(|c| {
            face_map_svg(c).map(|svg| Figure {
                kind: "face",
                caption: format!(
                    "Face map of what remains in {}: the mean error (model − measured) of the \
                     shots in each bin of impact location, bins by quantiles so each holds \
                     about the same number of shots; white is no error (docs/noise-floor.md).",
                    c.component.column()
                ),
                svg,
            })
        })
        .collect();
    Section {
        heading: "Noise floor: what remains".into(),
        html,
        figures,
    }
}

/// The conclusion, aliases and warnings of the diagnosis, as paragraphs.
fn notes_html(r: &DiagnoseReport) -> String {
    let d = &r.diagnosis;
    let mut html = format!("<p><b>Conclusion:</b> {}</p>", esc(&r.conclusion()));
    for a in &d.aliases {
        let _ = write!(
            html,
            "<p><b>Alias:</b> {} and {} (r = {:+.2}): the data cannot tell them apart; to separate them: {}</p>",
            esc(&a.a),
            esc(&a.b),
            a.r,
            esc(&a.separate_by)
        );
    }
    for w in &d.warnings {
        let _ = write!(html, "<p><b>Warning:</b> {}</p>", esc(w));
    }
    html
}

/// The strata table (the final model refitted on each stratum of each family, value ± SE per
/// parameter, and per family whether each parameter holds one value), then the provisional
/// values with their failed checks.
fn strata_html(d: &Diagnosis) -> String {
    let mut html = match &d.strata {
        Some(c) if !c.params.is_empty() && !c.families.is_empty() => strata_table(c),
        _ => "<p>No effect selected: nothing to refit on strata.</p>".to_owned(),
    };
    for p in &d.estimates {
        if let Some(why) = d.provisional(p) {
            let _ = write!(
                html,
                "<p><b>Provisional, not a finding:</b> {}</p>",
                esc(&why)
            );
        }
    }
    html
}

fn strata_table(c: &StrataCheck) -> String {
    let mut html = format!(
        "<p>The final model refitted on parts of the shots. A value that differs between \
         the parts of a family beyond its uncertainty (p below {:.1e} = 1 % over the checks \
         made) is provisional, not a finding.</p><table><tr><th>family</th><th>stratum</th>\
         <th>n</th>",
        c.alpha_each
    );
    for p in &c.params {
        let _ = write!(html, "<th>{}</th>", esc(p));
    }
    html.push_str("</tr>");
    for f in &c.families {
        for st in &f.strata {
            let _ = write!(
                html,
                "<tr><td>{}</td><td>{}</td><td>{}</td>",
                esc(&f.name),
                esc(&st.label),
                st.n
            );
            for v in &st.values {
                let cell = match v {
                    Some(_) => crate::report::strata::value_text(*v),
                    None => "–".into(),
                };
                let _ = write!(html, "<td>{cell}</td>");
            }
            html.push_str("</tr>");
        }
        let _ = write!(
            html,
            "<tr><td>{}</td><td><i>one value?</i></td><td></td>",
            esc(&f.name)
        );
        for k in &f.checks {
            let cell = match k {
                Some(k) if k.stable => format!("yes (p = {:.2e})", k.p_value),
                Some(k) => format!("<b>no</b> (p = {:.2e})", k.p_value),
                None => "–".into(),
            };
            let _ = write!(html, "<td>{cell}</td>");
        }
        html.push_str("</tr>");
    }
    html.push_str("</table>");
    html
}
