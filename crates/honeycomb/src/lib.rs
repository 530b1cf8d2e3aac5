//! Freeform honeycomb structures (Jiang, Tang, Wallner, Pottmann et al.): hexagonal meshes on a
//! design surface whose walls are planar and meet at exactly 120 degrees at every node.
//!
//! The library is the product; the `honeycomb` binary is a thin front over it.

pub mod analysis;
pub mod constraints;
pub mod edit;
pub mod error;
mod front;
pub mod export;
pub mod fabrication;
pub mod generate;
pub mod geometry;
pub mod init;
pub mod interactive;
pub mod limits;
pub mod mesh;
pub mod optimize;
pub mod parallel;
pub mod pipeline;
pub mod reciprocal;
pub mod render;
pub mod report;
pub mod solve;
pub mod structure;
pub mod surface;

pub use error::{Error, Result};
pub use front::{
    optimize, pipeline, BaseMesh, Options, Outcome, PipelineOptions, Progress, Step, Variant,
    Verdict,
};
pub use geometry::Vec3;
pub use pipeline::Walls;
pub use solve::Cancel;
pub use structure::{Honeycomb, Measures};
pub use surface::Surface;
