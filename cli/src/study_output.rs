//! What `smash run` and `smash merge` share: the `--format` values of the long table and the
//! summary printed once a study's outputs are written.

use std::path::Path;

use smash::study::metrics::metric_names;
use smash::study::optimise::OptimiseResult;
use smash::study::output::{cell, TableFormat};
use smash::study::Prepared;

/// `--format` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TableFormatArg {
    /// maps_long.csv
    Csv,
    /// maps_long.parquet
    Parquet,
}

impl From<TableFormatArg> for TableFormat {
    fn from(f: TableFormatArg) -> Self {
        match f {
            TableFormatArg::Csv => TableFormat::Csv,
            TableFormatArg::Parquet => TableFormat::Parquet,
        }
    }
}

/// The metrics of the summary: the name in `metric_names`, its header and decimals in the
/// narrow table.
const PICK: [(&str, &str, usize); 7] = [
    ("cof_ball_speed_mph", "CoF mph", 3),
    ("speed_loss_toe_mph_per_mm", "toe", 3),
    ("speed_loss_heel_mph_per_mm", "heel", 3),
    ("speed_loss_crown_mph_per_mm", "crown", 3),
    ("speed_loss_sole_mph_per_mm", "sole", 3),
    ("gear_sidespin_rpm_per_mm", "side", 2),
    ("gear_backspin_rpm_per_mm", "back", 2),
];

/// The first variants' summary metrics: `wide`, one line per variant with every metric's name
/// and four decimals; narrow, the designs listed, then a table with short headers.
fn variants_text(p: &Prepared, metrics: &[Vec<f64>], wide: bool) -> String {
    let names = metric_names(p.study.distribution.is_some());
    let shown = p.variants.iter().zip(metrics).enumerate().take(5);
    let mut text = String::new();
    if wide {
        for (i, (d, m)) in shown {
            let mut line = format!("  variant {i} ({}):", d.describe());
            for (k, _, _) in PICK {
                if let Some(j) = names.iter().position(|n| n == k) {
                    line.push_str(&format!(" {k} = {:.4}", m[j]));
                }
            }
            text.push_str(&line);
            text.push('\n');
        }
        return text;
    }
    let cols: Vec<(usize, &str, usize)> = PICK
        .iter()
        .filter_map(|&(k, h, dp)| names.iter().position(|n| n == k).map(|j| (j, h, dp)))
        .collect();
    let mut header = vec!["  variant".to_owned()];
    header.extend(cols.iter().map(|c| c.1.to_owned()));
    let mut t = smash::report::TextTable::new(header);
    for (i, (d, m)) in shown {
        text.push_str(&crate::text::wrap_long(&format!(
            "  variant {i}: {}\n",
            d.describe()
        )));
        let mut row = vec![format!("  {i}")];
        row.extend(cols.iter().map(|&(j, _, dp)| format!("{:.*}", dp, m[j])));
        t.row(row);
    }
    text.push_str(
        "  ball speed at the face centre (CoF, mph); speed lost per mm toward the toe, heel, \
         crown, sole (mph/mm); gear effect, sidespin and backspin per mm (rpm/mm); \
         every metric: variants.csv, or --wide\n",
    );
    text = crate::text::wrap_long(&text);
    text.push_str(&t.render());
    text
}

/// A short human summary on stdout: speed retention and gear effect of the first variants, and
/// the optimiser's result; `wide`: the variants' metrics one line each.
pub fn print_summary(
    p: &Prepared,
    metrics: &[Vec<f64>],
    opt: Option<&OptimiseResult>,
    dir: &Path,
    n_files: usize,
    wide: bool,
) -> Result<(), crate::stdout::StdoutError> {
    use std::fmt::Write;
    let mut text = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(
        text,
        "study '{}' ({}, group {}): {} variant(s)",
        p.study.name,
        p.study.club.name,
        p.study.group,
        metrics.len()
    );
    text = crate::text::wrap_long(&text);
    text.push_str(&variants_text(p, metrics, wide));
    if metrics.len() > 5 {
        let _ = writeln!(text, "  … see variants.csv");
    }
    if let Some(o) = opt {
        let gain = o.best_objective - o.base_objective;
        text.push_str(&crate::text::wrap_long(&format!(
            "optimum: {} — objective {} -> {} (change {}, {:.3} %), {} iterations, {} evaluations, {}\n",
            o.best.describe(),
            cell(o.base_objective),
            cell(o.best_objective),
            cell(gain),
            100.0 * gain / o.base_objective.abs().max(f64::MIN_POSITIVE),
            o.path.last().map_or(0, |p| p.iteration),
            o.evaluations,
            o.termination
        )));
    }
    text.push_str(&crate::text::wrap_long(&format!(
        "wrote {n_files} file(s) to {}\n",
        dir.display()
    )));
    crate::stdout::print(text)
}
