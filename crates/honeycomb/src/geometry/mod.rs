//! Geometric primitives shared by every module.

mod segment;
mod sym3;
mod vec3;

pub use segment::segment_distance;
pub use sym3::{smallest_eigenvector, sum_of_outer_products};
pub use vec3::Vec3;
