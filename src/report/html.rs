//! Self-contained HTML reports (`--report FILE.html`): one page with inline SVG charts and CSS,
//! no scripts, fonts or anything else fetched; readable offline and printable. Built from the
//! same data the JSON output holds. Builds strings only.

use std::fmt::Write as _;

use crate::compare::{sig3, CompareReport, VARIABLES};
use crate::physics::LaunchComponent;
use crate::report::charts::{
    fit_line, grouped_bars_svg, scatter_trend_svg, BarSeries, Trend, BLUE_C, ORANGE_C,
};
use crate::report::heatmap::{heatmap_svg, Heatmap, Scale};
use crate::stats::error_table::ErrorTable;

/// Escape text for HTML.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// One chart with its caption.
#[derive(Debug, Clone)]
pub struct Figure {
    /// Kind, for tests and styling (`table2`, `trend`, `face`, `estimates`, …).
    pub kind: &'static str,
    /// Caption (text).
    pub caption: String,
    /// The SVG.
    pub svg: String,
}

/// A section of a page.
#[derive(Debug, Clone, Default)]
pub struct Section {
    /// Heading.
    pub heading: String,
    /// Paragraphs of HTML (already escaped).
    pub html: Vec<String>,
    /// Charts.
    pub figures: Vec<Figure>,
}

/// A whole report page.
#[derive(Debug, Clone, Default)]
pub struct Page {
    /// Title.
    pub title: String,
    /// One line under the title.
    pub subtitle: String,
    /// Sections in order.
    pub sections: Vec<Section>,
}

const CSS: &str = "body{font-family:sans-serif;color:#222;margin:0 auto;max-width:1240px;padding:16px 24px;line-height:1.4}\
h1{font-size:1.5em;margin:.2em 0}h2{font-size:1.2em;border-bottom:1px solid #ccc;margin-top:1.6em}\
.sub{color:#555}.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(480px,1fr));gap:12px}\
figure{margin:0;border:1px solid #e4e4e4;padding:6px;background:#fff}figure svg{width:100%;height:auto;display:block}\
figcaption{font-size:.85em;color:#444;margin-top:4px}\
table{border-collapse:collapse;font-size:.9em;margin:.6em 0}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}\
th{background:#f3f3f3}td.l,th.l{text-align:left}.sig{font-weight:bold}ol li{margin:.3em 0}\
@media print{body{max-width:none;padding:0}.grid{grid-template-columns:1fr 1fr}figure,table{break-inside:avoid}h2{break-after:avoid}}";

impl Page {
    /// The HTML document.
    pub fn render(&self) -> String {
        let mut s = String::new();
        let _ = write!(
            s,
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
             <link rel=\"icon\" href=\"data:,\"><title>{}</title><style>{CSS}</style></head><body>\n",
            esc(&self.title)
        );
        let _ = writeln!(
            s,
            "<h1>{}</h1><p class=\"sub\">{}</p>",
            esc(&self.title),
            esc(&self.subtitle)
        );
        for sec in &self.sections {
            let _ = writeln!(s, "<section><h2>{}</h2>", esc(&sec.heading));
            for h in &sec.html {
                s.push_str(h);
                s.push('\n');
            }
            if !sec.figures.is_empty() {
                s.push_str("<div class=\"grid\">\n");
                for f in &sec.figures {
                    let _ = writeln!(
                        s,
                        "<figure class=\"chart\" data-kind=\"{}\">{}<figcaption>{}</figcaption></figure>",
                        f.kind,
                        f.svg,
                        esc(&f.caption)
                    );
                }
                s.push_str("</div>\n");
            }
            s.push_str("</section>\n");
        }
        let _ = writeln!(
            s,
            "<p class=\"sub\">Written by smash {}. Errors are model − measured.</p></body></html>",
            env!("CARGO_PKG_VERSION")
        );
        s
    }
}

/// Per-shot residuals against the delivery, for the trend charts.
#[derive(Debug, Clone)]
pub struct ShotResiduals {
    /// Delivery variable name (a [`VARIABLES`] name) → value per shot, file units.
    pub variables: Vec<(&'static str, &'static str, Vec<f64>)>,
    /// Model − measured per shot, file units, launch component order.
    pub errors: Vec<[f64; 5]>,
}

/// Variables the trend charts show: speed, loft and the two impact coordinates.
pub const TREND_VARIABLES: [&str; 4] = [
    "club_speed_mph",
    "dynamic_loft_deg",
    "impact_y_mm",
    "impact_z_mm",
];

impl ShotResiduals {
    /// From shots and their expected launches (same order).
    pub fn new(shots: &[crate::model::Shot], launches: &[crate::physics::Launch]) -> Self {
        let variables = VARIABLES
            .iter()
            .filter(|v| TREND_VARIABLES.contains(&v.name))
            .map(|v| (v.name, v.unit, shots.iter().map(|s| (v.get)(s)).collect()))
            .collect();
        let errors = shots
            .iter()
            .zip(launches)
            .map(|(s, l)| {
                let m = s.measured.expect("compared shots are measured");
                std::array::from_fn(|c| {
                    let c = LaunchComponent::ALL[c];
                    l.get_file(c) - m.get_file(c)
                })
            })
            .collect();
        Self { variables, errors }
    }
}

fn component_title(c: LaunchComponent) -> String {
    format!("{} error, {}", c.label(), c.unit())
}

fn variable_label(name: &str, unit: &str) -> String {
    let base = match name {
        "club_speed_mph" => "club speed",
        "dynamic_loft_deg" => "dynamic loft",
        "impact_y_mm" => "impact height (up the face)",
        "impact_z_mm" => "impact heel–toe (toward toe)",
        n => n,
    };
    format!("{base}, {unit}")
}

/// The Table-2 HTML table: mean (STD) per component and group, each number also in a
/// `data-value` attribute at full precision (the JSON's numbers).
fn table2_html(report: &CompareReport) -> String {
    let mut s =
        String::from("<table class=\"table2\"><tr><th class=\"l\">component</th><th>unit</th>");
    for g in &report.table2 {
        let _ = write!(s, "<th>{} mean</th><th>STD</th>", esc(&g.group));
    }
    s.push_str("</tr>");
    for c in LaunchComponent::ALL {
        let _ = write!(
            s,
            "<tr><td class=\"l\">{}</td><td>{}</td>",
            c.label(),
            c.unit()
        );
        for g in &report.table2 {
            let e = &g.components[c.index()];
            for (what, v) in [("mean", e.summary.mean), ("std", e.summary.std)] {
                let class = if what == "mean" && e.significant {
                    " class=\"sig\""
                } else {
                    ""
                };
                match v {
                    Some(v) => {
                        let _ = write!(
                            s,
                            "<td{class} data-key=\"{}/{}/{what}\" data-value=\"{v:?}\">{}</td>",
                            esc(&g.group),
                            c.column(),
                            sig3(v)
                        );
                    }
                    None => s.push_str("<td>–</td>"),
                }
            }
        }
        s.push_str("</tr>");
    }
    s.push_str("</table>");
    s
}

/// Bars of mean error ± STD per group for each component, one chart per component, with one
/// or two series (before / after).
fn table2_figures(tables: &[(&str, &ErrorTable)]) -> Result<Vec<Figure>, String> {
    let groups: Vec<String> = tables
        .first()
        .map(|(_, t)| t.groups.iter().map(|g| g.group.clone()).collect())
        .unwrap_or_default();
    let mut out = Vec::new();
    for c in LaunchComponent::ALL {
        let series: Vec<BarSeries> = tables
            .iter()
            .enumerate()
            .map(|(k, (label, t))| BarSeries {
                label: (*label).to_owned(),
                colour: if k == 0 { BLUE_C } else { ORANGE_C },
                values: groups
                    .iter()
                    .map(|g| {
                        t.groups.iter().find(|x| &x.group == g).map(|x| {
                            let ms = x.components[c.index()];
                            (ms.mean, if ms.std.is_finite() { ms.std } else { 0.0 })
                        })
                    })
                    .collect(),
            })
            .collect();
        let svg = grouped_bars_svg(
            &format!("{} by group", c.label()),
            &component_title(c),
            &groups,
            &series,
        )?;
        out.push(Figure {
            kind: "table2",
            caption: format!(
                "{}: mean error per group (bar) ± one standard deviation of the shots (error bar).",
                c.label()
            ),
            svg,
        });
    }
    Ok(out)
}

/// Residual-against-delivery charts: for each trend variable, the component whose error
/// correlates most strongly with it (the trend a finding would name), with the least-squares
/// line and, for speed and loft, the binned means.
fn trend_figures(report: &CompareReport, res: &ShotResiduals) -> Result<Vec<Figure>, String> {
    let mut out = Vec::new();
    for (name, unit, xs) in &res.variables {
        let Some(best) = report
            .correlations
            .iter()
            .filter(|e| e.variable == *name)
            .max_by(|a, b| a.t.abs().total_cmp(&b.t.abs()))
        else {
            continue;
        };
        let Some(c) = LaunchComponent::ALL
            .into_iter()
            .find(|c| c.column() == best.component)
        else {
            continue;
        };
        let points: Vec<(f64, f64)> = xs
            .iter()
            .zip(&res.errors)
            .map(|(&x, e)| (x, e[c.index()]))
            .collect();
        let trend = fit_line(&points).map(|(slope, intercept)| Trend {
            slope,
            intercept,
            label: format!(
                "trend: r = {:.2}{}",
                best.r,
                if best.significant {
                    format!(", p < {}", report.alpha)
                } else {
                    String::from(", not significant")
                }
            ),
        });
        let bins: Vec<(f64, f64)> = report
            .binned
            .iter()
            .find(|b| b.variable == *name)
            .map(|b| {
                b.rows
                    .iter()
                    .filter_map(|r| r.mean[c.index()].map(|m| (0.5 * (r.lo + r.hi), m)))
                    .collect()
            })
            .unwrap_or_default();
        let svg = scatter_trend_svg(
            &format!(
                "{} vs {}",
                c.label(),
                variable_label(name, unit).split(',').next().unwrap_or(name)
            ),
            &variable_label(name, unit),
            &component_title(c),
            &points,
            trend.as_ref(),
            &bins,
        )?;
        let named = report.findings.iter().position(|f| {
            f.component == best.component
                && matches!(f.pattern, crate::compare::signatures::Pattern::Trend(v) if v == *name)
        });
        out.push(Figure {
            kind: "trend",
            caption: format!(
                "{} error of every shot against {}; r = {:.3}, t = {:.1}{}.",
                c.label(),
                variable_label(name, unit),
                best.r,
                best.t,
                match named {
                    Some(i) => format!(" — finding {}", i + 1),
                    None => String::new(),
                }
            ),
            svg,
        });
    }
    Ok(out)
}

/// Face maps of the mean error per component.
fn face_figures(report: &CompareReport) -> Vec<Figure> {
    let f = &report.face;
    if f.ys_mm.len() < 2 || f.zs_mm.len() < 2 {
        return Vec::new();
    }
    LaunchComponent::ALL
        .iter()
        .filter_map(|&c| {
            let grid = f.grid(c);
            if !grid.iter().any(|v| v.is_finite()) {
                return None;
            }
            let title = format!("{} error over the face", c.label());
            let value_label = component_title(c);
            let svg = heatmap_svg(&Heatmap {
                title: &title,
                x_label: "impact z (toward toe), mm",
                y_label: "impact y (up), mm",
                value_label: &value_label,
                xs: &f.zs_mm,
                ys: &f.ys_mm,
                values: &grid,
                marker: Some((0.0, 0.0)),
                scale: Scale::Diverging,
            });
            Some(Figure {
                kind: "face",
                caption: format!(
                    "Mean {} error in {} mm bins (bins with fewer than {} shots left blank); + marks the face centre.",
                    c.label(),
                    f.bin_mm,
                    f.min_count
                ),
                svg,
            })
        })
        .collect()
}

fn findings_html(report: &CompareReport) -> String {
    if report.findings.is_empty() {
        return format!(
            "<p>No bias or strong trend is significant at {}%.</p>",
            report.alpha * 100.0
        );
    }
    let mut s = String::from("<ol class=\"findings\">");
    for f in &report.findings {
        let hints = if f.hints.is_empty() {
            "no library effect has this signature".to_owned()
        } else {
            format!("try: {}", f.hints.join("; "))
        };
        let _ = write!(
            s,
            "<li>{}<br><small>{}</small></li>",
            esc(&f.text),
            esc(&hints)
        );
    }
    s.push_str("</ol>");
    s
}

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
            "{title} — {} parameter(s), method {}; χ² {:.1} → {:.1} (nominal → calibrated), reduced χ² {:.3}.",
            cal.params.len(),
            cal.method.name(),
            cal.chi2_before,
            cal.chi2,
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
        let chosen = s["selected"].as_str().unwrap_or("none");
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
        ],
    };
    Ok(page.render())
}

/// A small CSV as an HTML table (at most `max_rows` rows).
fn csv_table_html(name: &str, bytes: &[u8], max_rows: usize) -> String {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(bytes);
    let mut s = format!("<h3>{}</h3><table class=\"csv\">", esc(name));
    let mut n = 0;
    for (i, rec) in rdr.records().enumerate() {
        let Ok(rec) = rec else { break };
        if i > max_rows {
            s.push_str("<tr><td class=\"l\">…</td></tr>");
            break;
        }
        let tag = if i == 0 { "th" } else { "td" };
        s.push_str("<tr>");
        for c in rec.iter() {
            let shown = c
                .parse::<f64>()
                .ok()
                .filter(|_| i > 0)
                .map(sig3)
                .unwrap_or_else(|| c.to_owned());
            let _ = write!(s, "<{tag}>{}</{tag}>", esc(&shown));
        }
        s.push_str("</tr>");
        n += 1;
    }
    s.push_str("</table>");
    if n == 0 {
        return String::new();
    }
    s
}

/// The optimiser's path: the objective after each iteration (`iteration, objective, …`).
fn optimiser_path_figure(bytes: &[u8]) -> Result<Option<Figure>, String> {
    let mut rdr = csv::Reader::from_reader(bytes);
    let Ok(h) = rdr.headers().cloned() else {
        return Ok(None);
    };
    let (Some(ii), Some(io)) = (
        h.iter().position(|c| c == "iteration"),
        h.iter().position(|c| c == "objective"),
    ) else {
        return Ok(None);
    };
    let pts: Vec<(f64, f64)> = rdr
        .records()
        .filter_map(Result::ok)
        .filter_map(|r| Some((r.get(ii)?.parse().ok()?, r.get(io)?.parse().ok()?)))
        .collect();
    if pts.is_empty() {
        return Ok(None);
    }
    let svg = scatter_trend_svg(
        "Optimiser path",
        "Nelder–Mead iteration",
        "objective (best design so far)",
        &pts,
        None,
        &pts,
    )?;
    Ok(Some(Figure {
        kind: "optimiser",
        caption: "The objective of the best design after each iteration of the optimiser.".into(),
        svg,
    }))
}

/// The page of `smash run --report`: the study's face maps (its own SVG outputs) and its
/// summary, sensitivity and optimiser tables.
pub fn study_page(name: &str, files: &[(std::path::PathBuf, Vec<u8>)]) -> Result<String, String> {
    let mut maps = Vec::new();
    let mut tables = Vec::new();
    for (path, bytes) in files {
        let p = path.to_string_lossy();
        if p.ends_with(".svg") {
            let svg = String::from_utf8_lossy(bytes);
            // Drop any XML prolog: the SVG is inlined.
            let start = svg.find("<svg").unwrap_or(0);
            maps.push(Figure {
                kind: "face",
                caption: p.into_owned(),
                svg: svg[start..].to_owned(),
            });
        } else if p.ends_with("path.csv") && p.contains("optimise") {
            if let Some(fig) = optimiser_path_figure(bytes)? {
                maps.insert(0, fig);
            }
            tables.push(csv_table_html(&p, bytes, 60));
        } else if p.ends_with(".csv")
            && ["summary", "sensitiv", "optim", "variants"]
                .iter()
                .any(|k| p.contains(k))
        {
            tables.push(csv_table_html(&p, bytes, 60));
        }
    }
    let page = Page {
        title: format!("smash run: {name}"),
        subtitle: format!("{} output files; {} face maps.", files.len(), maps.len()),
        sections: vec![
            Section {
                heading: "Face maps".into(),
                html: Vec::new(),
                figures: maps,
            },
            Section {
                heading: "Summaries, sensitivities and optimisation".into(),
                html: tables,
                figures: Vec::new(),
            },
        ],
    };
    Ok(page.render())
}
