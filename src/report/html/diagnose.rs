//! The page of `smash diagnose --report`, from the diagnosis's JSON form, and the estimates
//! chart it shares with calibrate.

use std::fmt::Write as _;

use super::figures::table2_figures;
use super::{esc, Figure, Page, Section};
use crate::compare::sig3;
use crate::physics::LaunchComponent;
use crate::stats::error_table::ErrorTable;

/// An [`ErrorTable`] back from its JSON form (`{group: {component: {mean, std}}}`); `null`
/// becomes NaN (not drawn).
fn error_table_from_json(v: &serde_json::Value) -> ErrorTable {
    let groups = v
        .as_object()
        .map(|m| {
            m.iter()
                .map(|(g, comps)| crate::stats::error_table::GroupErrors {
                    group: g.clone(),
                    n: 0,
                    components: std::array::from_fn(|i| {
                        let c = &comps[LaunchComponent::ALL[i].column()];
                        crate::stats::error_table::MeanStd {
                            mean: c["mean"].as_f64().unwrap_or(f64::NAN),
                            std: c["std"].as_f64().unwrap_or(f64::NAN),
                        }
                    }),
                })
                .collect()
        })
        .unwrap_or_default();
    ErrorTable { groups }
}

/// The plausible range of `effect.param`: the JSON's own `plausible` when it has one, else the
/// library's.
fn plausible_of(p: &serde_json::Value) -> Option<(f64, f64)> {
    for key in ["plausible_range", "plausible"] {
        if let Some([a, b]) = p[key].as_array().map(Vec::as_slice) {
            if let (Some(a), Some(b)) = (a.as_f64(), b.as_f64()) {
                return Some((a, b));
            }
        }
    }
    let kind = crate::effects::EffectId::from_name(p["effect"].as_str()?)?;
    let key = p["param"].as_str()?;
    kind.params()
        .iter()
        .find(|s| s.key == key)
        .map(|s| s.plausible)
}

fn param_label(p: &serde_json::Value) -> String {
    let e = p["effect"].as_str().unwrap_or("?");
    let k = p["param"].as_str().unwrap_or("?");
    match p["group"].as_str() {
        Some(g) => format!("{e}@{g}.{k}"),
        None => format!("{e}.{k}"),
    }
}

/// Estimate charts (one per unit) and a table, from JSON parameter objects
/// (`effect`, `param`, `group`, `value`, `stderr`, `unit`).
fn estimates_from_json(params: &[serde_json::Value]) -> Result<(String, Vec<Figure>), String> {
    use crate::report::charts::{estimates_svg, Estimate};
    let mut table = String::from(
        "<table class=\"params\"><tr><th class=\"l\">parameter</th><th>value</th><th>SE</th><th>unit</th><th>plausible</th></tr>",
    );
    let mut rows: Vec<(String, Estimate)> = Vec::new();
    for p in params {
        let Some(value) = p["value"].as_f64() else {
            continue;
        };
        let se = p["stderr"].as_f64();
        let unit = p["unit"].as_str().unwrap_or("").to_owned();
        let label = param_label(p);
        let plausible = plausible_of(p);
        let stand_in = match p["stand_in"].as_str() {
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
                "Estimates in {u}: value ± 2 standard errors against the range a real driver plausibly shows (docs/plausible-ranges.md)."
            ),
            svg: estimates_svg(&format!("Estimates, {u}"), &format!("value, {u}"), &r)?,
        });
    }
    Ok((table, figs))
}

/// The page of `smash diagnose --report`, built from its JSON: per step, the cross-validated
/// gain of every candidate against its penalty; the errors before and after the selected
/// effects; the final estimates with their plausible ranges.
pub fn diagnose_page(d: &serde_json::Value, title: &str) -> Result<String, String> {
    let selected: Vec<&str> = d["selected"]
        .as_array()
        .map(|a| a.iter().filter_map(|s| s.as_str()).collect())
        .unwrap_or_default();
    let mut steps = Vec::new();
    for s in d["steps"].as_array().map(Vec::as_slice).unwrap_or_default() {
        let cands = s["candidates"]
            .as_array()
            .map(Vec::as_slice)
            .unwrap_or_default();
        let labels: Vec<String> = cands
            .iter()
            .map(|c| c["effect"].as_str().unwrap_or("?").to_owned())
            .collect();
        let gains: Vec<f64> = cands
            .iter()
            .map(|c| c["gain"].as_f64().unwrap_or(f64::NAN))
            .collect();
        let penalties: Vec<f64> = cands
            .iter()
            .map(|c| c["penalty"].as_f64().unwrap_or(f64::NAN))
            .collect();
        let step = s["step"].as_u64().unwrap_or(0);
        let chosen = match s["swap"]["text"].as_str() {
            Some(swap) => format!("none (a swap step: {swap})"),
            None => s["selected"].as_str().unwrap_or("none").to_owned(),
        };
        let svg = crate::report::charts::bars_with_line_svg(
            &format!("Step {step}: cross-validated gain per candidate"),
            "CV χ² gain",
            &labels,
            &gains,
            Some((&penalties, "penalty k·ln n")),
        )?;
        steps.push(Figure {
            kind: "steps",
            caption: format!(
                "Step {step} (base: {}): gain in cross-validated χ² of each candidate; a candidate is selected only when its gain beats its penalty (red). Selected: {chosen}.",
                s["base"]
                    .as_array()
                    .map(|a| a.iter().filter_map(|x| x.as_str()).collect::<Vec<_>>().join(", "))
                    .filter(|x| !x.is_empty())
                    .unwrap_or_else(|| "nominal".into())
            ),
            svg,
        });
    }
    let before = error_table_from_json(&d["before"]);
    let after = error_table_from_json(&d["after"]);
    let (table, est_figs) = estimates_from_json(
        d["estimates"]
            .as_array()
            .map(Vec::as_slice)
            .unwrap_or_default(),
    )?;
    let warn_html = notes_html(d);
    let page = Page {
        title: "smash diagnose".into(),
        subtitle: format!(
            "{title} — {} shots, {} folds by {}; selected: {}.",
            d["n_shots"].as_u64().unwrap_or(0),
            d["folds"].as_u64().unwrap_or(0),
            d["fold_by"].as_str().unwrap_or("?"),
            if selected.is_empty() {
                "none".to_owned()
            } else {
                selected.join(", ")
            }
        ),
        sections: vec![
            Section {
                heading: "Forward selection".into(),
                html: vec![warn_html],
                figures: steps,
            },
            Section {
                heading: "Errors before and after the selected effects".into(),
                html: Vec::new(),
                figures: table2_figures(&[
                    ("before (nominal)", &before),
                    ("after (selected)", &after),
                ])?,
            },
            Section {
                heading: "Estimates of the selected effects".into(),
                html: vec![table],
                figures: est_figs,
            },
            Section {
                heading: "Stability across strata".into(),
                html: vec![strata_html(d)],
                figures: Vec::new(),
            },
        ],
    };
    Ok(page.render())
}

/// The conclusion, aliases and warnings of the diagnosis JSON, as paragraphs.
fn notes_html(d: &serde_json::Value) -> String {
    let mut warn_html = String::new();
    if let Some(c) = d["conclusion"].as_str() {
        let _ = write!(warn_html, "<p><b>Conclusion:</b> {}</p>", esc(c));
    }
    for a in d["aliases"]
        .as_array()
        .map(Vec::as_slice)
        .unwrap_or_default()
    {
        let _ = write!(
            warn_html,
            "<p><b>Alias:</b> {} and {} (r = {}): the data cannot tell them apart; to separate them: {}</p>",
            esc(a["a"].as_str().unwrap_or("?")),
            esc(a["b"].as_str().unwrap_or("?")),
            a["r"].as_f64().map(|r| format!("{r:+.2}")).unwrap_or_default(),
            esc(a["separate_by"].as_str().unwrap_or(""))
        );
    }
    for w in d["warnings"]
        .as_array()
        .map(Vec::as_slice)
        .unwrap_or_default()
    {
        if let Some(w) = w.as_str() {
            let _ = write!(warn_html, "<p><b>Warning:</b> {}</p>", esc(w));
        }
    }
    warn_html
}

/// The strata table of the diagnosis JSON (`strata`: the final model refitted on each stratum
/// of each family, value ± SE per parameter, and per family whether each parameter holds one
/// value), then the provisional values with their failed checks.
fn strata_html(d: &serde_json::Value) -> String {
    fn list(v: &serde_json::Value) -> &[serde_json::Value] {
        v.as_array().map(Vec::as_slice).unwrap_or_default()
    }
    let mut html = String::new();
    let strata = &d["strata"];
    let families = list(&strata["families"]);
    let params: Vec<String> = families
        .first()
        .and_then(|f| f["checks"].as_object())
        .map(|c| c.keys().cloned().collect())
        .unwrap_or_default();
    if params.is_empty() {
        html.push_str("<p>No effect selected: nothing to refit on strata.</p>");
    } else {
        let _ = write!(
            html,
            "<p>The final model refitted on parts of the shots. A value that differs between \
             the parts of a family beyond its uncertainty (p below {} = 1 % over the checks \
             made) is provisional, not a finding.</p><table><tr><th>family</th><th>stratum</th>\
             <th>n</th>",
            strata["alpha_each"]
                .as_f64()
                .map_or("?".into(), |a| format!("{a:.1e}"))
        );
        for p in &params {
            let _ = write!(html, "<th>{}</th>", esc(p));
        }
        html.push_str("</tr>");
        for f in families {
            for st in list(&f["strata"]) {
                let _ = write!(
                    html,
                    "<tr><td>{}</td><td>{}</td><td>{}</td>",
                    esc(f["name"].as_str().unwrap_or("?")),
                    esc(st["label"].as_str().unwrap_or("?")),
                    st["n"].as_u64().unwrap_or(0)
                );
                for p in &params {
                    let v = &st["values"][p.as_str()];
                    let cell = match (v["value"].as_f64(), v["stderr"].as_f64()) {
                        (Some(x), Some(se)) => format!("{x:.4} ± {se:.4}"),
                        (Some(x), None) => format!("{x:.4}"),
                        _ => "–".into(),
                    };
                    let _ = write!(html, "<td>{cell}</td>");
                }
                html.push_str("</tr>");
            }
            let _ = write!(
                html,
                "<tr><td>{}</td><td><i>one value?</i></td><td></td>",
                esc(f["name"].as_str().unwrap_or("?"))
            );
            for p in &params {
                let c = &f["checks"][p.as_str()];
                let cell = match (c["p_value"].as_f64(), c["stable"].as_bool()) {
                    (Some(pv), Some(true)) => format!("yes (p = {pv:.2e})"),
                    (Some(pv), Some(false)) => format!("<b>no</b> (p = {pv:.2e})"),
                    _ => "–".into(),
                };
                let _ = write!(html, "<td>{cell}</td>");
            }
            html.push_str("</tr>");
        }
        html.push_str("</table>");
    }
    for p in list(&d["provisional"]) {
        let _ = write!(
            html,
            "<p><b>Provisional, not a finding:</b> {}</p>",
            esc(p["failed_check"].as_str().unwrap_or("?"))
        );
    }
    html
}
