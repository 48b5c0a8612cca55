//! Progress on stderr with indicatif: one updating line per solver iteration, or a counter of
//! finished fits. Hidden when stderr is not a terminal.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use smash::fit::{IterInfo, Progress};

/// A spinner whose message is the latest iteration.
pub struct IterationLine {
    bar: ProgressBar,
}

impl IterationLine {
    /// A spinner on stderr.
    pub fn new() -> Self {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
                .expect("valid template"),
        );
        Self { bar }
    }

    /// Remove the line.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Default for IterationLine {
    fn default() -> Self {
        Self::new()
    }
}

impl Progress for IterationLine {
    fn iteration(&self, info: &IterInfo<'_>) {
        self.bar.set_message(format!(
            "{} | iter {:>3} | chi2 {:.6e} | lambda {:.1e} | {} evaluations",
            info.stage, info.iter, info.cost, info.lambda, info.evaluations
        ));
        self.bar.tick();
    }
}

/// A bar counting finished jobs (fits) of a known total.
pub fn job_bar(total: u64, what: &str) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} {msg} [{elapsed_precise}]")
            .expect("valid template"),
    );
    bar.set_message(what.to_owned());
    bar
}
