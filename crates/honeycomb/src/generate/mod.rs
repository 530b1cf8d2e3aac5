//! Meshes and surfaces built in code: the demo's default input and the tests' subjects.

mod height_field;
mod hex_patch;

pub use height_field::{HeightField, Shape};
pub use hex_patch::{hex_disk, radius_for_vertices};

use crate::mesh::PolyMesh;

/// A hexagonal base mesh of about `vertices` vertices lifted onto `shape`, and the design
/// surface it lies on (a fine triangulation reaching past the patch).
pub fn lifted_hex_patch(shape: Shape, vertices: usize) -> (PolyMesh, PolyMesh) {
    let d = radius_for_vertices(vertices);
    let field = HeightField { shape, d };
    let mut base = hex_disk(d);
    field.lift(&mut base);
    (base, field.triangulate(160))
}
