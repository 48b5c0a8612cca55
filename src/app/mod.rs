//! The commands as library calls: for each command a settings type (serde, no command-line
//! parser: what the command needs, with its defaults) and a `run` that takes the settings and
//! the inputs and returns the command's report. The `smash` command line turns its arguments
//! into these settings and renders what `run` returns; the Python package fills the same
//! settings from keyword arguments. Neither computes anything of its own.
//!
//! - [`inputs`]: the shots a command reads (a file, or CSV text from memory) and how (a shots
//!   file or a launch-monitor export), the club check, the conversion to the model's delivery
//!   convention.
//! - [`compare`], [`calibrate`], [`diagnose`], [`predict`], [`flight`], [`import`],
//!   [`synth`]: one module a command.
//!
//! What a command says while it runs (rows an import left out, what it converted, warnings)
//! goes to a [`Notes`] sink as it arises: the command line prints each note on stderr at once,
//! the Python package turns them into warnings. Errors are [`anyhow::Error`] chains: the
//! room's typed error with the file, option or key it concerns as context, printed on one line
//! by [`error_chain`].

pub mod calibrate;
pub mod compare;
pub mod delivery_noise;
pub mod diagnose;
pub mod flight;
pub mod import;
pub mod inputs;
pub mod predict;
pub mod study;
pub mod synth;

/// Where a command's notes go as they arise.
pub trait Notes {
    /// A note `prefix: text` (an import's skipped rows, assumed units; rows the shots reader
    /// left out).
    fn note(&mut self, prefix: &str, text: &str);
    /// A line already formed (a warning, a conversion summary line).
    fn line(&mut self, text: &str);
}

/// Notes printed on stderr as they arise: a `prefix: text` note wrapped at the reports' width
/// with its continuation lines indented, a line as it is (control characters escaped).
#[derive(Debug, Default, Clone, Copy)]
pub struct StderrNotes;

impl Notes for StderrNotes {
    fn note(&mut self, prefix: &str, text: &str) {
        eprintln!(
            "{}",
            crate::report::text::wrap_long(&format!("{prefix}: {text}"))
        );
    }
    fn line(&mut self, text: &str) {
        eprintln!("{}", crate::data::escape(text));
    }
}

/// Notes kept in order, as `prefix: text` and lines (for a caller that reports them later, as
/// the Python package's warnings).
#[derive(Debug, Default, Clone)]
pub struct CollectedNotes(pub Vec<String>);

impl Notes for CollectedNotes {
    fn note(&mut self, prefix: &str, text: &str) {
        self.0.push(format!("{prefix}: {text}"));
    }
    fn line(&mut self, text: &str) {
        self.0.push(text.to_owned());
    }
}

/// One line: the error and its causes, joined by `: ` (a cause whose text an earlier part
/// already holds is left out), with control characters from the input (ESC, CR, …) escaped so
/// that they cannot act on the terminal.
pub fn error_chain(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        let s = cause.to_string();
        if !parts.iter().any(|p| p.contains(&s)) {
            parts.push(s);
        }
    }
    crate::data::escape(&parts.join(": ").replace('\n', " ")).into_owned()
}

/// Stack of each worker thread, bytes. Rayon's default is the platform's 2 MiB; unoptimised
/// (`cargo run`, dev profile), the face-map kernel's row function, whose SIMD variants are
/// inlined into one frame for speed, needs about 2 MiB of stack by itself, and `smash run
/// configs/studies/face_map.toml` overflowed it. The stack is reserved address space, touched
/// only as deep as it is used.
pub const WORKER_STACK_BYTES: usize = 16 << 20;

/// The worker threads every command runs its parallel work on (installed as the global pool
/// by the command line's `main` and by the Python module).
pub fn thread_pool() -> rayon::ThreadPoolBuilder {
    rayon::ThreadPoolBuilder::new()
        .stack_size(WORKER_STACK_BYTES)
        .thread_name(|i| format!("smash-worker-{i}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame the size of the unoptimised face-map kernel's (about 2 MiB) and then some fits
    /// on every worker: on rayon's default 2 MiB stacks this aborts the test binary.
    #[test]
    fn workers_have_room_for_the_unoptimised_kernel() {
        fn deep(n: usize) -> u8 {
            let buf = std::hint::black_box([n as u8; 3 << 20]);
            buf[n % buf.len()]
        }
        let pool = thread_pool().num_threads(2).build().unwrap();
        let got = pool.broadcast(|c| deep(c.index() + 7));
        assert_eq!(got, [7, 8]);
    }

    /// A cause already spelled out by its context is said once.
    #[test]
    fn error_chain_is_one_line_without_repeats() {
        let e = anyhow::anyhow!("bad value").context("shots.csv: bad value");
        assert_eq!(error_chain(&e), "shots.csv: bad value");
        let e = anyhow::anyhow!("no such file").context("club.toml");
        assert_eq!(error_chain(&e), "club.toml: no such file");
    }
}
