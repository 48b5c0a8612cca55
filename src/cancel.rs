//! A cancellation token: a caller that runs long work on another thread (the Python package,
//! whose user presses Ctrl-C) asks the work to stop, and the work checks the token between its
//! fits and returns [`crate::fit::FitError::Cancelled`]. Cloning shares the token. Work given
//! no token runs to its end.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A shared flag: [`Cancel::cancel`] once, and every clone sees [`Cancel::is_cancelled`].
#[derive(Debug, Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// A token not cancelled.
    pub fn new() -> Self {
        Self::default()
    }

    /// Ask the work holding a clone of this token to stop.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Has [`Cancel::cancel`] been called on this token or a clone?
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

/// Two tokens are equal when they are clones of one another (options holding them compare
/// equal only when they would be stopped together).
impl PartialEq for Cancel {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// Whether an optional token is cancelled (no token: never).
pub fn cancelled(token: Option<&Cancel>) -> bool {
    token.is_some_and(Cancel::is_cancelled)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clones_share_the_flag() {
        let a = Cancel::new();
        let b = a.clone();
        assert!(!cancelled(Some(&b)) && !cancelled(None));
        a.cancel();
        assert!(b.is_cancelled() && cancelled(Some(&b)));
        assert_eq!(a, b);
        assert_ne!(a, Cancel::new());
    }
}
