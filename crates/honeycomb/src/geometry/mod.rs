//! Geometric primitives shared by every module.

mod direction;
pub mod rotation;
mod segment;
mod sym3;
mod vec3;
mod vector_file;

pub use direction::parse_direction;
pub use segment::segment_distance;
pub use sym3::{smallest_eigenvector, sum_of_outer_products};
pub use vec3::Vec3;
pub use vector_file::{read_axes, read_vectors};
