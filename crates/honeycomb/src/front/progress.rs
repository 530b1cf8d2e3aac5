//! What long work tells its caller, and how the caller stops it.

pub use crate::pipeline::Step;
use crate::solve::Cancel;

/// The callback that steps go to.
type Report<'a> = Box<dyn FnMut(Step<'_>) + 'a>;

/// Where a solve is ([`Step`]s, to a callback) and whether to stop it: the work ends before its
/// next iteration with [`crate::Error::Cancelled`] once its [`Cancel`] flag is set (from a
/// Ctrl-C handler, another thread, or the callback itself).
///
/// ```
/// use honeycomb::generate::{lifted_hex_patch, Shape};
/// use honeycomb::{optimize, BaseMesh, Cancel, Error, Options, Progress, Step, Surface};
/// let (base, surface) = lifted_hex_patch(Shape::Dome, 300);
/// let (base, surface) = (BaseMesh::from_mesh(base)?, Surface::new(surface)?);
/// // Stop after two iterations, from inside the callback.
/// let stop = Cancel::new();
/// let inside = stop.clone();
/// let mut iterations = 0;
/// let mut progress = Progress::new(move |step| {
///     if let Step::Iteration(..) = step {
///         iterations += 1;
///         if iterations == 2 {
///             inside.cancel();
///         }
///     }
/// })
/// .with_cancel(stop);
/// let result = optimize(&base, &surface, &Options::default(), &mut progress);
/// assert!(matches!(result, Err(Error::Cancelled)));
/// # Ok::<(), Error>(())
/// ```
pub struct Progress<'a> {
    report: Option<Report<'a>>,
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

    /// Reads `cancel` to know when to stop (made before the callback, so that the callback can
    /// hold a clone of it).
    pub fn with_cancel(mut self, cancel: Cancel) -> Progress<'a> {
        self.cancel = cancel;
        self
    }

    /// A handle that stops the work: keep it, give it to a signal handler or a thread.
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
