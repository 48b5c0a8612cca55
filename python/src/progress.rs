//! Progress of long work reported to a Python object (the Python half makes a tqdm bar in a
//! notebook when tqdm is installed, where the CLI shows its indicatif bar). The callbacks come
//! from rayon's threads, each taking the GIL only for the call; a failing callback is ignored
//! (progress is never worth stopping the work for).

use pyo3::prelude::*;

use smash::diagnose::DiagnoseProgress;
use smash::fit::{IterInfo, Progress};

/// A Python object with `step(step, jobs)` and `job_done()` (diagnose), or
/// `iteration(stage, iter, chi2, lambda_, evaluations)` (calibrate), and the thread that looks
/// for Python's signals while the work runs, when there is one: woken after every finished job,
/// so that a Ctrl-C (or a signal the callback itself raised) is seen before the next fits
/// start, not only at the next poll.
pub struct PyProgress(pub Py<PyAny>, pub Option<std::thread::Thread>);

impl PyProgress {
    fn wake_poller(&self) {
        if let Some(t) = &self.1 {
            t.unpark();
        }
    }
}

impl DiagnoseProgress for PyProgress {
    fn step(&self, step: usize, jobs: usize) {
        Python::attach(|py| {
            let _ = self.0.call_method1(py, "step", (step, jobs));
        });
    }
    fn job_done(&self) {
        Python::attach(|py| {
            let _ = self.0.call_method0(py, "job_done");
        });
        self.wake_poller();
    }
}

impl Progress for PyProgress {
    fn iteration(&self, info: &IterInfo<'_>) {
        Python::attach(|py| {
            let _ = self.0.call_method1(
                py,
                "iteration",
                (
                    info.stage.to_string(),
                    info.iter,
                    info.cost,
                    info.lambda,
                    info.evaluations,
                ),
            );
        });
    }
}
