//! The text `smash run` and `smash merge` print: the first variants' headline metrics and the
//! optimiser's result, from a [`StudyReport`]. Prose is wrapped to the width given; the table
//! is as wide as its columns (about 70 columns).

use std::fmt::Write as _;

use super::{StudyReport, HEADLINE};
use crate::report::wrap::wrap;
use crate::report::TextTable;
use crate::study::output::cell;

/// Variants listed in the text (all are in `variants.csv`, the JSON and the HTML).
pub const TEXT_VARIANTS: usize = 5;

/// Every line of `text` longer than `width` wrapped at spaces.
fn wrap_long(text: &str, width: usize) -> String {
    text.split_inclusive('\n')
        .map(|l| {
            let body = l.strip_suffix('\n').unwrap_or(l);
            if body.chars().count() > width {
                wrap(body, width, 2)
            } else {
                l.to_owned()
            }
        })
        .collect()
}

/// The summary: a line naming the study, the first variants' headline metrics (`wide`: one
/// line per variant with each metric's name and four decimals; else the designs listed, then
/// a table with short headers) and the optimiser's result; prose wrapped to `width`.
pub fn summary(r: &StudyReport, wide: bool, width: usize) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "study '{}' ({}, group {}): {} variant(s)",
        r.name,
        r.club,
        r.group,
        r.variants.len()
    );
    text = wrap_long(&text, width);
    text.push_str(&variants_text(r, wide, width));
    if r.variants.len() > TEXT_VARIANTS {
        text.push_str("  … see variants.csv\n");
    }
    if let Some(o) = &r.optimiser {
        let gain = o.best_objective - o.base_objective;
        text.push_str(&wrap_long(
            &format!(
                "optimum: {} — objective {} -> {} (change {}, {:.3} %), {} iterations, {} \
                 evaluations, {}\n",
                o.best,
                cell(o.base_objective),
                cell(o.best_objective),
                cell(gain),
                100.0 * gain / o.base_objective.abs().max(f64::MIN_POSITIVE),
                o.iterations,
                o.evaluations,
                o.termination
            ),
            width,
        ));
    }
    text
}

/// The first variants' headline metrics.
fn variants_text(r: &StudyReport, wide: bool, width: usize) -> String {
    let cols: Vec<(usize, &str, &str, usize)> = HEADLINE
        .iter()
        .filter_map(|&(k, h, dp)| r.metric_index(k).map(|j| (j, k, h, dp)))
        .collect();
    let shown = r.variants.iter().take(TEXT_VARIANTS);
    let mut text = String::new();
    if wide {
        for v in shown {
            let mut line = format!("  variant {} ({}):", v.id, v.changes);
            for &(j, k, _, _) in &cols {
                let _ = write!(line, " {k} = {:.4}", v.metrics[j]);
            }
            text.push_str(&line);
            text.push('\n');
        }
        return text;
    }
    let mut header = vec!["  variant".to_owned()];
    header.extend(cols.iter().map(|c| c.2.to_owned()));
    let mut t = TextTable::new(header);
    for v in shown {
        text.push_str(&wrap_long(
            &format!("  variant {}: {}\n", v.id, v.changes),
            width,
        ));
        let mut row = vec![format!("  {}", v.id)];
        row.extend(
            cols.iter()
                .map(|&(j, _, _, dp)| format!("{:.*}", dp, v.metrics[j])),
        );
        t.row(row);
    }
    text.push_str(&wrap_long(
        "  ball speed at the face centre (CoF, mph); speed lost per mm toward the toe, heel, \
         crown, sole (mph/mm); gear effect, sidespin and backspin per mm (rpm/mm); \
         every metric: variants.csv, or --wide\n",
        width,
    ));
    text.push_str(&t.render());
    text
}
