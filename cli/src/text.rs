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
