//! What long work tells its caller, and how the caller stops it.

pub use crate::pipeline::Step;
use crate::solve::Cancel;

/// Where a solve is ([`Step`]s, to a callback) and whether to stop it. A callback may stop the
/// work by calling [`Progress::cancel`] on a handle it holds (from [`Progress::cancel_handle`]):
/// the work then ends before its next iteration with [`crate::Error::Cancelled`].
///
/// ```
/// use honeycomb::{Progress, Step};
/// let mut iterations = 0;
/// let mut progress = Progress::new(|step| {
///     if let Step::Iteration(_, _, _) = step {
///         iterations += 1;
///     }
/// });
/// let stop = progress.cancel_handle();
/// stop.cancel(); // From a Ctrl-C handler, another thread, or the callback itself.
/// assert!(progress.is_cancelled());
/// # drop(progress);
/// # assert_eq!(iterations, 0);
/// ```
pub struct Progress<'a> {
    report: Option<Box<dyn FnMut(Step<'_>) + 'a>>,
    cancel: Cancel,
}

impl<'a> Progress<'a> {
    /// Reports every step to `report`.
    pub fn new(report: impl FnMut(Step<'_>) + 'a) -> Progress<'a> {
        Progress {
            report: Some(Box::new(report)),
            cancel: Cancel::new(),
        }
    }

    /// Reports nothing (it can still be cancelled).
    pub fn silent() -> Progress<'a> {
        Progress {
            report: None,
            cancel: Cancel::new(),
        }
    }

    /// A handle that stops the work: keep it, give it to a signal handler or a thread, or move
    /// it into the callback.
    pub fn cancel_handle(&self) -> Cancel {
        self.cancel.clone()
    }

    pub fn is_cancelled(&self) -> bool {
        self.cancel.is_cancelled()
    }

    pub(crate) fn step(&mut self, step: Step<'_>) {
        if let Some(report) = &mut self.report {
            report(step);
        }
    }
}

impl Default for Progress<'_> {
    fn default() -> Self {
        Progress::silent()
    }
}
