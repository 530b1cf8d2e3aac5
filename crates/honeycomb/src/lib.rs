//! Freeform honeycomb structures (Jiang, Tang, Wallner, Pottmann et al.): hexagonal meshes on a
//! design surface whose walls are planar and meet at exactly 120 degrees at every node.
//!
//! The library is the product; the `honeycomb` binary, the editor's server and any binding are
//! thin fronts over its front door, at the root of the crate:
//!
//! - [`pipeline`] makes a honeycomb on a [`Surface`] from nothing else; [`optimize`] makes one
//!   from a [`BaseMesh`] of your own. Both take [`Options`] (plain data, the command line's
//!   names) and a [`Progress`] (steps to a callback, a [`Cancel`] flag), and return an
//!   [`Outcome`]: the [`Honeycomb`], its [`Measures`] from the realized meshes, the
//!   [`Verdict`] and the report, which [`Outcome::save`] writes.
//! - [`EditSession`] edits a honeycomb in the three modes of the editor.
//!
//! The modules hold what comes before and after a solve: [`init`] (hexagonal base meshes on
//! S), [`generate`] (built-in surfaces), [`mesh`] (meshes and their files), [`structure`]
//! (measures), [`analysis`] (spherical image, light), [`edit`] (wall translations, resizing,
//! subdivision), [`render`] (pictures), [`fabrication`] and [`export`] (files for the workshop
//! and other tools), [`report`], [`limits`] and [`error`].

pub mod analysis;
pub(crate) mod constraints;
pub mod edit;
pub mod error;
pub mod export;
pub mod fabrication;
mod front;
pub mod generate;
pub mod geometry;
pub mod init;
pub mod interactive;
pub mod limits;
pub mod mesh;
pub(crate) mod optimize;
pub(crate) mod parallel;
pub(crate) mod pipeline;
pub(crate) mod reciprocal;
pub mod render;
pub mod report;
pub(crate) mod solve;
pub mod structure;
pub mod surface;
#[cfg(test)]
mod tests;

pub use error::{Error, Result};
pub use front::{
    optimize, pipeline, BaseMesh, Options, Outcome, PipelineOptions, Progress, Step, Variant,
    Verdict,
};
pub use geometry::Vec3;
pub use interactive::{Edit, EditSession, SessionOptions, Workspace};
pub use optimize::WallNormals;
pub use pipeline::Walls;
pub use solve::{Cancel, IterationInfo};
pub use structure::{Honeycomb, Measures};
pub use surface::Surface;
