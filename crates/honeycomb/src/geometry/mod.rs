//! Geometric primitives shared by every module.

mod vec3;

pub use vec3::Vec3;
