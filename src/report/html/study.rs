//! The page of `smash run --report`: a study's tables and the optimiser's path, from its files.

use std::fmt::Write as _;

use super::{esc, Figure, Page, Section};
use crate::compare::sig3;
use crate::report::charts::scatter_trend_svg;

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
