//! Ctrl-C (SIGINT), SIGTERM and SIGHUP end a command after removing its own temporaries (a study's
//! half-written output folder, a flight's half-written file: tens to hundreds of MB), instead of
//! leaving them for the next run into the same place to find.
//!
//! Why a crate: `signal-hook` (maintained, the usual choice) turns the signals into messages on
//! an ordinary thread, where removing files is safe; a raw handler may only call the few
//! async-signal-safe functions, which `remove_dir_all` is not.

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};

/// Start the thread that waits for the signals. On the first one it removes this process's
/// registered temporaries ([`smash::data::output_plan::remove_live_temporaries`], which waits
/// for a commit in progress) and exits with the shell's status for that signal (128 + its
/// number). Outputs already moved into place are kept.
pub fn clean_up_on_signals() {
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    let _ = std::thread::Builder::new()
        .name("smash-signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                smash::data::output_plan::remove_live_temporaries();
                std::process::exit(128 + signal);
            }
        });
}
