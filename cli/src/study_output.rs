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

/// A short human summary on stdout: speed retention and gear effect of the first variants, and
/// the optimiser's result.
pub fn print_summary(
    p: &Prepared,
    metrics: &[Vec<f64>],
    opt: Option<&OptimiseResult>,
    dir: &Path,
    n_files: usize,
) -> Result<(), crate::stdout::StdoutError> {
    use std::fmt::Write;
    let mut text = String::new();
    let names = metric_names(p.study.distribution.is_some());
    let pick = [
        "cof_ball_speed_mph",
        "speed_loss_toe_mph_per_mm",
        "speed_loss_heel_mph_per_mm",
        "speed_loss_crown_mph_per_mm",
        "speed_loss_sole_mph_per_mm",
        "gear_sidespin_rpm_per_mm",
        "gear_backspin_rpm_per_mm",
    ];
    // Writing to a String cannot fail.
    let _ = writeln!(
        text,
        "study '{}' ({}, group {}): {} variant(s)",
        p.study.name,
        p.study.club.name,
        p.study.group,
        metrics.len()
    );
    for (i, (d, m)) in p.variants.iter().zip(metrics).enumerate().take(5) {
        let mut line = format!("  variant {i} ({}):", d.describe());
        for k in pick {
            if let Some(j) = names.iter().position(|n| n == k) {
                line.push_str(&format!(" {k} = {:.4}", m[j]));
            }
        }
        let _ = writeln!(text, "{line}");
    }
    if metrics.len() > 5 {
        let _ = writeln!(text, "  … see variants.csv");
    }
    if let Some(o) = opt {
        let gain = o.best_objective - o.base_objective;
        let _ = writeln!(
            text,
            "optimum: {} — objective {} -> {} (change {}, {:.3} %), {} iterations, {} evaluations, {}",
            o.best.describe(),
            cell(o.base_objective),
            cell(o.best_objective),
            cell(gain),
            100.0 * gain / o.base_objective.abs().max(f64::MIN_POSITIVE),
            o.path.last().map_or(0, |p| p.iteration),
            o.evaluations,
            o.termination
        );
    }
    let _ = writeln!(text, "wrote {n_files} file(s) to {}", dir.display());
    crate::stdout::print(text)
}
