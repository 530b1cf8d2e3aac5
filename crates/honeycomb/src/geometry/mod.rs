//! Geometric primitives shared by every module.

pub(crate) mod differences;
mod direction;
pub(crate) mod rotation;
mod segment;
mod sym3;
mod vec3;
mod vector_file;

pub use direction::parse_direction;
pub(crate) use segment::segment_distance;
pub(crate) use sym3::{smallest_eigenvector, solve_symmetric, sum_of_outer_products};
pub use vec3::Vec3;
pub use vector_file::read_axes;
pub(crate) use vector_file::read_vectors;
