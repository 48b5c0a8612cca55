//! The `--wide` flag the commands with text reports share; the rest of what the text reports
//! share is the library's [`smash::report::text`].

pub use smash::report::text::*;

/// `--wide`, shared by the commands with text reports.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct WideArgs {
    /// Print the full tables (every column, rows as long as they need) instead of the ones
    /// that fit 100 columns; --json and --report always hold everything.
    #[arg(long)]
    pub wide: bool,
}

/// One note of a command on stderr (what an import or a shots file left out, what it assumed):
/// `prefix: note`, wrapped at [`WIDTH`] with its continuation lines indented two spaces, so that
/// a note quoting a long cell still fits the terminal the reports fit. Tests that look for a
/// note's text read stderr through `cli_support::unwrapped`.
pub fn print_note(prefix: &str, note: &str) {
    eprintln!("{}", wrap_long(&format!("{prefix}: {note}")));
}
