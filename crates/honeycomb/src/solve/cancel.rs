//! Stopping a solve from outside: a flag the solver reads before every step.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A shared stop flag. Clones share it: the caller keeps one (to set from a Ctrl-C handler, a
/// progress callback or another thread) and the solve reads another. The default is a flag
/// of its own that nobody else holds, so it never stops a solve.
#[derive(Clone, Debug, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    pub fn new() -> Cancel {
        Cancel::default()
    }

    /// Asks every solve that reads this flag to stop before its next step.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}
