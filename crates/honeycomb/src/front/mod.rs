//! The library's front door: a base mesh or a design surface in, a judged honeycomb out.
//!
//! [`BaseMesh`] and [`Surface`](crate::Surface) are checked once when made; [`Options`] is
//! plain data (serde) with the command line's names; [`optimize`] and [`pipeline`] return an
//! [`Outcome`] (the honeycomb, its measures, the verdict and the report) and report to a
//! [`Progress`], which can also stop them.

mod base_mesh;
mod options;
mod outcome;
mod progress;
mod run;

pub use base_mesh::BaseMesh;
pub use options::{Options, Variant};
pub use outcome::{Outcome, Verdict};
pub use progress::{Progress, Step};
pub use run::{optimize, pipeline, PipelineOptions};
