//! A diagnosis stops when its caller cancels it (issue 41, item D: the Python package's
//! Ctrl-C): with a token cancelled before it starts it returns `FitError::Cancelled` without a
//! fit; cancelled after its first fit, it starts none but the few its checks had let through,
//! and returns the same error. Counted in fits, not timed. Without a token, or with one never
//! cancelled, it runs as before (the token changes nothing it computes).

#[path = "../benches/support/worlds.rs"]
mod worlds;

use std::sync::atomic::{AtomicUsize, Ordering};

use smash::cancel::Cancel;
use smash::diagnose::{diagnose, DiagnoseOptions, DiagnoseProgress};
use smash::fit::FitError;

/// Counts the fits; cancels `token` when the `at`-th is done.
struct CancelAt {
    token: Cancel,
    at: usize,
    done: AtomicUsize,
}

impl DiagnoseProgress for CancelAt {
    fn step(&self, _: usize, _: usize) {}
    fn job_done(&self) {
        if self.done.fetch_add(1, Ordering::Relaxed) + 1 == self.at {
            self.token.cancel();
        }
    }
}

#[test]
fn a_cancelled_diagnosis_stops_between_fits() {
    let club = worlds::paper_club();
    let shots = worlds::paper_world(20);
    let opts = |cancel: Option<Cancel>| DiagnoseOptions {
        max_steps: 2,
        max_iters: 30,
        cancel,
        ..DiagnoseOptions::default()
    };
    // The whole run, with a token never cancelled, counting its fits.
    let whole = CancelAt {
        token: Cancel::new(),
        at: usize::MAX,
        done: AtomicUsize::new(0),
    };
    let d = diagnose(
        &club,
        &shots,
        &opts(Some(whole.token.clone())),
        Some(&whole),
    )
    .unwrap();
    let plain = diagnose(&club, &shots, &opts(None), None).unwrap();
    // (Compared as printed: a failed candidate's χ² is NaN.)
    assert_eq!(
        format!("{:?}", d.steps),
        format!("{:?}", plain.steps),
        "a token changes what is computed"
    );
    let fits = whole.done.load(Ordering::Relaxed);
    assert!(fits > 40, "{fits} fits: too short a run to stop in");

    let before = Cancel::new();
    before.cancel();
    let counted = CancelAt {
        token: before.clone(),
        at: usize::MAX,
        done: AtomicUsize::new(0),
    };
    let e = diagnose(&club, &shots, &opts(Some(before)), Some(&counted)).unwrap_err();
    assert_eq!(e, FitError::Cancelled);
    assert_eq!(counted.done.load(Ordering::Relaxed), 0);

    let after_first = CancelAt {
        token: Cancel::new(),
        at: 1,
        done: AtomicUsize::new(0),
    };
    let o = opts(Some(after_first.token.clone()));
    let e = diagnose(&club, &shots, &o, Some(&after_first)).unwrap_err();
    assert_eq!(e, FitError::Cancelled);
    // The fits in progress when it was cancelled finish (one a worker thread at most, and the
    // folds of a candidate already fitting); no step after it starts.
    let n = after_first.done.load(Ordering::Relaxed);
    let threads = rayon::current_num_threads();
    assert!(
        n <= 1 + 6 * threads,
        "{n} of {fits} fits done after the cancel"
    );
}
