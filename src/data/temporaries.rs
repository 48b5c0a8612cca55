//! The temporaries this process has made (staged outputs, write probes, scratch files) and not
//! yet moved into place or removed, so that a SIGINT or SIGTERM handler can remove them before
//! the process ends ([`remove_live_temporaries`]). A bottom layer: the writers register here.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The temporaries this process has made and not yet moved in or removed.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

pub(crate) fn live() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Record a temporary file or folder of this process, to be removed if a signal ends it.
pub fn register_temporary(path: &Path) {
    live().push(path.to_owned());
}

/// The temporary was moved in or removed.
pub fn forget_temporary(path: &Path) {
    live().retain(|t| t != path);
}

/// Remove every temporary of this process (for a SIGINT or SIGTERM handler, which then ends the
/// process). Waits for a commit in progress to finish.
pub fn remove_live_temporaries() {
    let mut live = live();
    for t in live.drain(..) {
        if t.is_dir() {
            let _ = std::fs::remove_dir_all(&t);
        } else {
            let _ = std::fs::remove_file(&t);
        }
    }
    // Keep the registry locked: no new temporary is made while the process ends.
    std::mem::forget(live);
}
