//! The quads that cap a honeycomb (`quads.obj`) as a picture: each filled by its planarity
//! (`delta_face`), calm up to the flatness asked of a cover and red beyond, so that a designer
//! sees where the cover is not yet flat enough to be glazed.

use super::view::Camera;
use super::walls::{polygons_scene, Coloring};
use super::Scene;
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use crate::structure::{four_sided, quad_planarities, FLAT_QUAD};

/// The four-sided faces of `cover` (a quad cover: its split quads, and its unsplit cells, which
/// are not drawn), coloured by planarity, titled `title`; and the verdict line.
pub fn quads_scene(cover: &PolyMesh, title: String, camera: Camera, width: u32) -> (Scene, String) {
    let quads = four_sided(&cover.faces);
    let planarity = quad_planarities(&cover.vertices, &quads);
    let corners: Vec<Vec<Vec3>> = (quads.iter())
        .map(|q| q.iter().map(|&v| cover.vertices[v]).collect())
        .collect();
    let coloring = Coloring {
        title,
        measure: "delta_face",
        meaning: "quad planarity: diagonals' distance / mean side",
        unit: "",
        items: "quads",
        values: &planarity,
        tolerance: Some(FLAT_QUAD),
    };
    (
        polygons_scene(&corners, "quad", &coloring, camera, width),
        coloring.verdict(),
    )
}
