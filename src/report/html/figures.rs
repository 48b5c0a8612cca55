//! The figures and tables the compare, calibrate and diagnose pages share: Table 2 as HTML and
//! as bars, residual trends against the delivery, residual maps over the face, the findings.

use std::fmt::Write as _;

use super::{esc, Figure, ShotResiduals};
use crate::compare::{sig3, CompareReport};
use crate::physics::LaunchComponent;
use crate::report::charts::{
    fit_line, grouped_bars_svg, scatter_trend_svg, Bar, BarSeries, ChartError, Trend, BLUE_C,
    ORANGE_C,
};
use crate::report::heatmap::{heatmap_svg, Heatmap, Scale};
use crate::stats::error_table::ErrorTable;

pub(super) fn component_title(c: LaunchComponent) -> String {
    format!("{} error, {}", c.label(), c.unit())
}

pub(super) fn variable_label(name: &str, unit: &str) -> String {
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
pub(super) fn table2_html(report: &CompareReport) -> String {
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

/// Bars of mean error ± SE per group (the shots' SD as a band) for each component, one chart per component, with one
/// or two series (before / after).
pub(super) fn table2_figures(tables: &[(&str, &ErrorTable)]) -> Result<Vec<Figure>, ChartError> {
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
                            Bar::of(ms.mean, ms.std, x.n)
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
                "{}: mean error per group (bar) ± its standard error (black); the grey band is ± one \
                 standard deviation of the shots.",
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
pub(super) fn trend_figures(
    report: &CompareReport,
    res: &ShotResiduals,
) -> Result<Vec<Figure>, ChartError> {
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
pub(super) fn face_figures(report: &CompareReport) -> Vec<Figure> {
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

pub(super) fn findings_html(report: &CompareReport) -> String {
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
