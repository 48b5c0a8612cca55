//! The `smash` binary: parse arguments, run the library, map errors to exit codes.

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = smash_cli::Cli::parse();
    smash_cli::signals::clean_up_on_signals();
    // Fails only if a pool was already installed, which nothing before this line does.
    let _ = smash_cli::thread_pool().build_global();
    match smash_cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        // A reader that closed the pipe (`smash effects | head -n 1`) ends us silently, with the
        // status a shell shows for a tool ended by SIGPIPE (128 + 13).
        Err(e) if smash_cli::stdout::is_broken_pipe(&e) => ExitCode::from(141),
        Err(e) => {
            eprintln!("error: {}", smash_cli::error_chain(&e));
            ExitCode::FAILURE
        }
    }
}
