//! The page of `smash run --report`, from a [`StudyReport`]: a summary first (the question, the
//! base, the variants that change most, the headline metrics as changes from the base, the
//! optimiser's and the yard part's answers), the variants' legend, then per output the face
//! maps as small multiples on one shared colour scale and their differences from the base on
//! one symmetric scale (the first output open, the others folded), and the full tables folded
//! at the end. A design study measures nothing: the page carries no note on measurements.

use std::fmt::Write as _;

use super::{OutputMaps, StudyReport};
use crate::report::charts::{path_svg, ChartError};
use crate::report::heatmap::{
    colour_bar_svg, heatmap_svg, small_map_svg, Heatmap, Scale, SmallMap,
};
use crate::report::html::{esc, CSS};

/// Metric columns per table, so that a table fits the page's width in print.
const COLUMNS_PER_TABLE: usize = 6;

/// Additions to the pages' style: the small multiples' grid and the folded details.
const STUDY_CSS: &str =
    ".multiples{display:grid;grid-template-columns:repeat(auto-fill,minmax(200px,1fr));gap:6px}\
.multiples figure{padding:2px}figure.bar{border:none;max-width:480px;margin:.4em 0}\
details{margin:.8em 0}details>summary{cursor:pointer;font-weight:bold;font-size:1.05em}\
.question{font-size:1.1em}table{max-width:100%}th{overflow-wrap:anywhere}td.l{overflow-wrap:break-word}\
@media print{.multiples{grid-template-columns:repeat(3,1fr)}}";

/// `v` with `dp` decimals; a dash when not finite.
fn num(v: f64, dp: usize) -> String {
    if v.is_finite() {
        format!("{v:.dp$}")
    } else {
        "–".into()
    }
}

/// `v` signed with `dp` decimals; a dash when not finite.
fn signed(v: f64, dp: usize) -> String {
    if v.is_finite() {
        format!("{v:+.dp$}")
    } else {
        "–".into()
    }
}

/// An HTML table: header cells, then rows (the first cell of each left-aligned). Cells are text.
fn table(header: &[String], rows: &[Vec<String>]) -> String {
    let mut s = String::from("<table><tr>");
    for (i, h) in header.iter().enumerate() {
        let class = if i == 0 { " class=\"l\"" } else { "" };
        let _ = write!(s, "<th{class}>{}</th>", esc(h));
    }
    s.push_str("</tr>");
    for r in rows {
        s.push_str("<tr>");
        for (i, c) in r.iter().enumerate() {
            let class = if i == 0 { " class=\"l\"" } else { "" };
            let _ = write!(s, "<td{class}>{}</td>", esc(c));
        }
        s.push_str("</tr>");
    }
    s.push_str("</table>\n");
    s
}

/// A variant's name on the page: its id, marked when it is the base.
fn vname(r: &StudyReport, id: usize) -> String {
    if id == r.base_id {
        format!("{id} (base)")
    } else {
        id.to_string()
    }
}

/// The page.
pub fn page(r: &StudyReport) -> Result<String, ChartError> {
    let mut s = String::new();
    let title = format!("smash run: {}", r.name);
    let _ = write!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <link rel=\"icon\" href=\"data:,\"><title>{}</title><style>{CSS}{STUDY_CSS}</style>\
         </head><body>\n<h1>{}</h1><p class=\"sub\">{}, group {}: {} variant(s), maps of {}.</p>\n",
        esc(&title),
        esc(&title),
        esc(&r.club),
        esc(&r.group),
        r.variants.len(),
        esc(&r
            .face_maps
            .iter()
            .map(|m| m.label.to_lowercase())
            .collect::<Vec<_>>()
            .join(", "))
    );
    s.push_str(&summary_section(r));
    if r.variants.len() > 1 {
        s.push_str(&legend_section(r));
    }
    for (k, m) in r.face_maps.iter().enumerate() {
        s.push_str(&maps_section(r, m, k == 0));
    }
    s.push_str(&details_section(r)?);
    let _ = writeln!(
        s,
        "<p class=\"sub\">Written by smash {}.</p></body></html>",
        env!("CARGO_PKG_VERSION")
    );
    Ok(s)
}

/// The summary: question, base, the most changed variants, the headline changes, the optimum
/// and the yards.
fn summary_section(r: &StudyReport) -> String {
    let mut s = String::from("<section id=\"summary\"><h2>Summary</h2>\n");
    let _ = writeln!(s, "<p class=\"question\">{}</p>", esc(&r.question));
    let base = &r.variants[r.base_id];
    let _ = writeln!(
        s,
        "<p>{}</p>",
        esc(&if r.variants.len() == 1 {
            match r.base_is_club {
                true => "One design: the club as given.".to_owned(),
                false => format!("One design: {}.", base.changes),
            }
        } else if r.base_is_club {
            format!(
                "The base is variant {}, the club as given; every change below is a variant \
                 minus the base.",
                r.base_id
            )
        } else {
            format!(
                "No variant is the club as given: changes are against variant 0 ({}).",
                base.changes
            )
        })
    );
    if let Some(m) = r.face_maps.first().filter(|m| !m.diffs.is_empty()) {
        let mut most: Vec<(f64, usize)> = m
            .ids
            .iter()
            .filter(|&&i| i != r.base_id)
            .zip(&m.max_abs_diff)
            .map(|(&i, &d)| (d, i))
            .collect();
        most.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let listed: Vec<String> = most
            .iter()
            .take(3)
            .map(|(d, i)| {
                format!(
                    "variant {i} ({}): up to {} {}",
                    r.variants[*i].changes,
                    num(*d, 3),
                    m.unit
                )
            })
            .collect();
        let _ = writeln!(
            s,
            "<p>Most different from the base in {} on the face: {}.</p>",
            esc(&m.label.to_lowercase()),
            esc(&listed.join("; "))
        );
    }
    s.push_str(&key_numbers(r));
    if let Some(o) = &r.optimiser {
        s.push_str(&optimum(r, o));
    }
    if let Some(y) = &r.yards {
        s.push_str("<h3>In yards, against the base</h3>\n");
        s.push_str(&yards_table(y, &[0, 1, 2, 3]));
    }
    s.push_str("</section>\n");
    s
}

/// The key numbers: each headline metric's base value and its lowest and highest change (a
/// study of one design: every metric's value).
fn key_numbers(r: &StudyReport) -> String {
    if !r.highlights.is_empty() && r.variants.len() > 1 {
        let rows: Vec<Vec<String>> = r
            .highlights
            .iter()
            .map(|h| {
                let dp = r
                    .metric_index(&h.metric)
                    .map_or(3, |j| r.metric_decimals[j]);
                vec![
                    h.metric.clone(),
                    h.unit.clone(),
                    num(h.base, dp),
                    format!("{} (variant {})", signed(h.lowest.1, dp), h.lowest.0),
                    format!("{} (variant {})", signed(h.highest.1, dp), h.highest.0),
                ]
            })
            .collect();
        let header =
            ["metric", "unit", "base", "lowest change", "highest change"].map(String::from);
        table(&header, &rows)
    } else if r.variants.len() == 1 {
        let v = &r.variants[0];
        let rows: Vec<Vec<String>> = r
            .metrics
            .iter()
            .enumerate()
            .map(|(j, m)| {
                vec![
                    m.name.clone(),
                    m.unit.clone(),
                    num(v.metrics[j], r.metric_decimals[j]),
                ]
            })
            .collect();
        table(&["metric", "unit", "value"].map(String::from), &rows)
    } else {
        String::new()
    }
}

/// The optimiser's answer: the optimum's design, the objective before and after, and the
/// objective's and headline metrics at the base and the optimum.
fn optimum(r: &StudyReport, o: &super::OptimiserReport) -> String {
    let gain = o.best_objective - o.base_objective;
    let dp = super::decimals_apart(&[o.base_objective, o.best_objective]).max(3);
    let design: Vec<String> = o
        .best_design
        .iter()
        .map(|(k, v)| format!("{k} = {v:.3}"))
        .collect();
    let mut s = format!(
        "<h3>Optimum</h3>\n<p>{} the objective: {}; objective {} → {} ({}, {:+.3} %) at {}; \
         {} iterations, {} evaluations, {}.</p>\n",
        match o.goal {
            "minimise" => "Minimising",
            _ => "Maximising",
        },
        esc(&super::objective_text(
            o.objective.iter().map(|(w, m)| (*w, m.as_str()))
        )),
        num(o.base_objective, dp),
        num(o.best_objective, dp),
        signed(gain, dp),
        100.0 * gain / o.base_objective.abs().max(f64::MIN_POSITIVE),
        esc(&design.join(", ")),
        o.iterations,
        o.evaluations,
        esc(&o.termination)
    );
    let mut names: Vec<&str> = o.objective.iter().map(|(_, m)| m.as_str()).collect();
    names.extend(super::HEADLINE.iter().map(|h| h.0));
    let mut seen = Vec::new();
    let rows: Vec<Vec<String>> = names
        .into_iter()
        .filter_map(|n| r.metric_index(n))
        .filter(|j| {
            let new = !seen.contains(j);
            seen.push(*j);
            new
        })
        .map(|j| {
            let (b, x) = (o.base_metrics[j], o.best_metrics[j]);
            let dp = super::decimals_apart(&[b, x]);
            vec![
                r.metrics[j].name.clone(),
                r.metrics[j].unit.clone(),
                num(b, dp),
                num(x, dp),
                signed(x - b, dp),
            ]
        })
        .collect();
    let header = ["metric", "unit", "base", "optimum", "change"].map(String::from);
    s.push_str(&table(&header, &rows));
    s
}

/// The yard table: per head its changes of the quantities `cols` (± the quadrature's error).
fn yards_table(y: &super::YardsReport, cols: &[usize]) -> String {
    let mut header = vec!["head".to_owned()];
    header.extend(
        cols.iter()
            .map(|&q| format!("Δ {}", y.quantities[q].name.replace('_', " "))),
    );
    let rows: Vec<Vec<String>> = y
        .rows
        .iter()
        .map(|row| {
            let mut r = vec![format!("{} ({})", row.label, row.design)];
            r.extend(cols.iter().map(|&q| match row.uncertainties[q] {
                Some(u) => format!("{:+.3} ± {u:.3}", row.deltas[q]),
                None => format!("{:+.3}", row.deltas[q]),
            }));
            r
        })
        .collect();
    table(&header, &rows)
}

/// The legend: each variant's id, its design values and its headline changes.
fn legend_section(r: &StudyReport) -> String {
    let mut s = String::from("<section id=\"variants\"><h2>Variants</h2>\n");
    let key: Vec<usize> = [
        "cof_ball_speed_mph",
        "mean_ball_speed_mph",
        "std_ball_speed_mph",
    ]
    .iter()
    .filter_map(|n| r.metric_index(n))
    .collect();
    let mut header = vec!["id".to_owned()];
    header.extend(r.axes.iter().map(|a| format!("{}, {}", a.name, a.unit)));
    header.extend(key.iter().map(|&j| format!("Δ {}", r.metrics[j].name)));
    let rows: Vec<Vec<String>> = r
        .variants
        .iter()
        .map(|v| {
            let mut row = vec![vname(r, v.id)];
            row.extend(v.design.iter().map(|x| crate::limits::fmt_value(*x)));
            row.extend(
                key.iter()
                    .map(|&j| signed(v.deltas[j], r.metric_decimals[j])),
            );
            row
        })
        .collect();
    s.push_str(&table(&header, &rows));
    s.push_str("</section>\n");
    s
}

/// One output's maps: small multiples on one scale, and the differences from the base; open
/// when `open`, else folded.
fn maps_section(r: &StudyReport, m: &OutputMaps, open: bool) -> String {
    let heading = format!("{} over the face, {}", m.label, m.unit);
    let mut s = format!(
        "<section class=\"maps\" data-output=\"{}\"><details{}><summary>{}</summary>\n",
        esc(&m.column),
        if open { " open" } else { "" },
        esc(&heading)
    );
    let value_label = format!("{}, {}", m.label.to_lowercase(), m.unit);
    if m.ids.len() == 1 {
        let map = Heatmap {
            title: &m.label,
            x_label: "impact z (toward toe), mm",
            y_label: "impact y (up the face), mm",
            value_label: &value_label,
            xs: &m.zs_mm,
            ys: &m.ys_mm,
            values: &m.values[0],
            marker: Some((0.0, 0.0)),
            scale: scale(m.signed),
        };
        let _ = writeln!(
            s,
            "<div class=\"grid\"><figure class=\"chart\" data-kind=\"face\" data-variant=\"{}\" \
             data-limits=\"{},{}\">{}<figcaption>{} at each impact location (block means); the \
             circle is the face centre.</figcaption></figure></div>",
            m.ids[0],
            m.limits.0,
            m.limits.1,
            heatmap_svg(&map),
            esc(&m.label)
        );
        s.push_str("</details></section>\n");
        return s;
    }
    let shown = if m.ids.len() < r.variants.len() {
        format!(
            "{} of {} variants: the base and those whose {} map differs most from it.",
            m.ids.len(),
            r.variants.len(),
            r.face_maps[0].label.to_lowercase()
        )
    } else {
        "Every variant.".to_owned()
    };
    let _ = writeln!(
        s,
        "<p>{} One colour scale for every map. In each map the impact \
         location runs toward the toe (z, mm) across and up the face (y, mm) upward; the \
         circle is the face centre; ids as in the legend.</p>",
        esc(&shown)
    );
    s.push_str(&multiples(r, m, false));
    s.push_str(&format!(
        "<h3>Difference from the base (variant − variant {})</h3>\n",
        r.base_id
    ));
    s.push_str(&multiples(r, m, true));
    s.push_str("</details></section>\n");
    s
}

fn scale(signed: bool) -> Scale {
    if signed {
        Scale::Diverging
    } else {
        Scale::Sequential
    }
}

/// The small multiples of `m` (`diff`: the differences from the base) and their colour bar.
fn multiples(r: &StudyReport, m: &OutputMaps, diff: bool) -> String {
    let (kind, limits, sc) = if diff {
        ("diff", m.diff_limits, Scale::Diverging)
    } else {
        ("face", m.limits, scale(m.signed))
    };
    let maps: Vec<(usize, &Vec<f64>)> = if diff {
        let others = m.ids.iter().copied().filter(|&i| i != r.base_id);
        others.zip(&m.diffs).collect()
    } else {
        m.ids.iter().copied().zip(&m.values).collect()
    };
    let mut s = String::from("<div class=\"multiples\">\n");
    for (id, values) in maps {
        let title = if diff {
            format!("{id} − base")
        } else {
            vname(r, id)
        };
        let svg = small_map_svg(&SmallMap {
            title: &title,
            xs: &m.zs_mm,
            ys: &m.ys_mm,
            values,
            limits,
            scale: sc,
        });
        let _ = writeln!(
            s,
            "<figure class=\"chart\" data-kind=\"{kind}\" data-variant=\"{id}\" \
             data-limits=\"{},{}\">{svg}</figure>",
            limits.0, limits.1
        );
    }
    s.push_str("</div>\n");
    let label = if diff {
        format!(
            "{} change from the base, {}",
            m.label.to_lowercase(),
            m.unit
        )
    } else {
        format!("{}, {}", m.label.to_lowercase(), m.unit)
    };
    let _ = writeln!(
        s,
        "<figure class=\"bar\" data-kind=\"colour-bar\">{}</figure>",
        colour_bar_svg(&label, limits, sc)
    );
    s
}

/// The metrics of the variants `ids`, in tables of at most [`COLUMNS_PER_TABLE`] metrics.
fn metrics_tables(r: &StudyReport, ids: &[usize]) -> String {
    let mut s = String::new();
    let all: Vec<usize> = (0..r.metrics.len()).collect();
    for chunk in all.chunks(COLUMNS_PER_TABLE) {
        let mut header = vec!["variant".to_owned()];
        header.extend(
            chunk
                .iter()
                .map(|&j| format!("{}, {}", r.metrics[j].name, r.metrics[j].unit)),
        );
        let rows: Vec<Vec<String>> = ids
            .iter()
            .map(|&i| {
                let v = &r.variants[i];
                let mut row = vec![vname(r, i)];
                row.extend(
                    chunk
                        .iter()
                        .map(|&j| num(v.metrics[j], r.metric_decimals[j])),
                );
                row
            })
            .collect();
        s.push_str(&table(&header, &rows));
    }
    s
}

/// The folded details: every metric, the sensitivities, the optimiser's path, the yard table.
fn details_section(r: &StudyReport) -> Result<String, ChartError> {
    let mut s = String::from("<section id=\"details\"><h2>Details</h2>\n");
    if r.variants.len() > 1 {
        let ids: Vec<usize> = (0..r.variants.len()).collect();
        let _ = writeln!(
            s,
            "<details><summary>Every metric of every variant</summary>{}</details>",
            metrics_tables(r, &ids)
        );
    }
    if !r.sensitivities.is_empty() {
        let mut t = String::new();
        let all: Vec<usize> = (0..r.metrics.len()).collect();
        for chunk in all.chunks(COLUMNS_PER_TABLE) {
            let mut header = vec!["d metric / d variable".to_owned()];
            header.extend(chunk.iter().map(|&j| r.metrics[j].name.clone()));
            let rows: Vec<Vec<String>> = r
                .sensitivities
                .iter()
                .map(|x| {
                    let mut row = vec![format!("{}, per {}", x.variable.name, x.variable.unit)];
                    row.extend(chunk.iter().map(|&j| format!("{:.4e}", x.metrics[j])));
                    row
                })
                .collect();
            t.push_str(&table(&header, &rows));
        }
        let _ = writeln!(
            s,
            "<details><summary>Sensitivities at the base design</summary><p>Central \
             differences; each metric's unit per the variable's unit.</p>{t}</details>"
        );
    }
    if let Some(o) = &r.optimiser {
        let pts: Vec<(f64, f64)> = o.path.iter().map(|(i, v)| (*i as f64, *v)).collect();
        let svg = path_svg(
            "Optimiser path",
            "Nelder–Mead iteration",
            "objective of the best design so far",
            &pts,
        )?;
        let _ = writeln!(
            s,
            "<details><summary>Optimiser path</summary><div class=\"grid\"><figure \
             class=\"chart\" data-kind=\"optimiser\">{svg}<figcaption>The objective of the best \
             design after each iteration.</figcaption></figure></div></details>"
        );
    }
    if let Some(y) = &r.yards {
        let cols: Vec<usize> = (0..y.quantities.len()).collect();
        let mut t = String::new();
        for chunk in cols.chunks(4) {
            t.push_str(&yards_table(y, chunk));
        }
        let cons: Vec<Vec<String>> = y
            .constraints
            .iter()
            .map(|c| {
                vec![
                    c.name.clone(),
                    num(c.value, 3),
                    num(c.limit, 3),
                    num(c.margin, 3),
                    if c.margin >= 0.0 { "yes" } else { "NO" }.into(),
                ]
            })
            .collect();
        let header = ["constraint", "base", "limit", "margin", "holds"].map(String::from);
        t.push_str(&table(&header, &cons));
        let _ = writeln!(
            s,
            "<details><summary>Yards per head and the head constraints</summary>{t}</details>"
        );
    }
    s.push_str("</section>\n");
    Ok(s)
}
