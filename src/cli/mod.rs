//! The `smash` command line: argument parsing and dispatch. Each subcommand lives in its own
//! file, loads files, calls the library and prints; no physics here.

use clap::{Parser, Subcommand};

pub mod calibrate;
pub mod diagnose;
pub mod predict;
pub mod progress;

/// Golf clubhead–ball impact engine: predict launch, compare with measurements, find the
/// missing physics, calibrate, and run design studies.
#[derive(Debug, Parser)]
#[command(name = "smash", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Predict ball launch for a shots file, or for one delivery given on the command line.
    Predict(predict::PredictArgs),
    /// Fit named effects' parameters to measured launch (values ± standard errors,
    /// correlations, chi2, AIC/BIC, before/after error tables).
    Calibrate(calibrate::CalibrateArgs),
    /// Rank the library's effects by how much each explains (cross-validated by golfer) and
    /// select them forward until the improvement is not significant.
    Diagnose(diagnose::DiagnoseArgs),
}

/// Run a parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Predict(args) => predict::run(args),
        Command::Calibrate(args) => calibrate::run(args),
        Command::Diagnose(args) => diagnose::run(args),
    }
}

/// One line: the error and its causes, joined by `: `.
pub fn error_chain(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        let s = cause.to_string();
        if !parts.iter().any(|p| p.contains(&s)) {
            parts.push(s);
        }
    }
    parts.join(": ").replace('\n', " ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn command_line_is_well_formed() {
        Cli::command().debug_assert();
    }
}
