//! Everything the CLI prints on standard output goes through [`print`], which returns write
//! errors instead of panicking (as `println!` does).
//!
//! A full disk or a closed terminal is an error: one line on stderr and a non-zero exit. A pipe
//! closed by the reader (`smash effects | head -n 3`) is the reader's choice, not an error: the
//! binary then exits silently with status 141, what a shell reports for a tool ended by SIGPIPE,
//! as standard Unix tools are (see `main.rs`).

use std::io::Write;

/// Writing to standard output failed.
#[derive(Debug, thiserror::Error)]
#[error("cannot write to standard output: {0}")]
pub struct StdoutError(pub std::io::Error);

impl StdoutError {
    /// The reader closed the pipe (EPIPE).
    pub fn is_broken_pipe(&self) -> bool {
        self.0.kind() == std::io::ErrorKind::BrokenPipe
    }
}

/// Write `text` to standard output and flush it.
pub fn print(text: impl std::fmt::Display) -> Result<(), StdoutError> {
    let mut out = std::io::stdout().lock();
    write!(out, "{text}").map_err(StdoutError)?;
    out.flush().map_err(StdoutError)
}

/// Write `text` and a newline to standard output and flush it.
pub fn println(text: impl std::fmt::Display) -> Result<(), StdoutError> {
    print(format_args!("{text}\n"))
}

/// Whether `e` (or any of its causes) is a closed pipe on standard output.
pub fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<StdoutError>()
            .is_some_and(StdoutError::is_broken_pipe)
    })
}
