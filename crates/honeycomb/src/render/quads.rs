//! The quads that cap a honeycomb (`quads.obj`) as a picture: each filled by its planarity
//! (`delta_face`), calm up to the flatness asked of a cover and red beyond, so that a designer
//! sees where the cover is not yet flat enough to be glazed.

use super::view::Camera;
use super::walls::{polygons_scene, Coloring};
use super::Scene;
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use crate::structure::{quad_planarity, FLAT_QUAD};

/// The four-sided faces of `cover` (a quad cover: its split quads, and its unsplit cells, which
/// are not drawn), coloured by planarity, titled `title`; and the verdict line.
pub fn quads_scene(cover: &PolyMesh, title: String, camera: Camera, width: u32) -> (Scene, String) {
    let quads: Vec<Vec<Vec3>> = (cover.faces.iter())
        .filter(|f| f.len() == 4)
        .map(|f| f.iter().map(|&v| cover.vertices[v]).collect())
        .collect();
    let planarity: Vec<f64> = quads
        .iter()
        .map(|q| quad_planarity([q[0], q[1], q[2], q[3]]))
        .collect();
    let coloring = Coloring {
        title,
        measure: "delta_face",
        meaning: "quad planarity: diagonals' distance / mean side",
        unit: "",
        items: "quads",
        per_wall: &planarity,
        tolerance: Some(FLAT_QUAD),
    };
    (
        polygons_scene(&quads, "quad", &coloring, camera, width),
        coloring.verdict(),
    )
}
