//! The `smash` binary: parse arguments, run the library, map errors to exit codes.

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = smash::cli::Cli::parse();
    match smash::cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", smash::cli::error_chain(&e));
            ExitCode::FAILURE
        }
    }
}
