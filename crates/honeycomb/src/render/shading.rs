//! A shading device as a picture: each cell of M filled by the light it lets through against
//! the same cell along S's normals (the shading's reference), calm up to the share asked and
//! red beyond, so that a designer sees where the light leaks.

use super::view::Camera;
use super::walls::{polygons_scene, Coloring};
use super::Scene;
use crate::analysis::{extruded_along_normals, light_share, DEFAULT_LIGHT_SAMPLES, SHADING_GOAL};
use crate::error::rounded;
use crate::geometry::Vec3;
use crate::mesh::Connectivity;
use crate::structure::Honeycomb;
use crate::surface::Surface;

/// A cell's light is drawn over its reference's, with a reference share below this counted as
/// this: a cell the light barely reaches either way stays calm, one that opens to light its
/// reference shuts out shows.
const FAINT: f64 = 0.05;

/// What a shading device was made for: the light (either sense) and the depth its walls were
/// asked to have, which its reference has too.
#[derive(Clone, Copy, Debug)]
pub struct DesignLight {
    pub direction: Vec3,
    pub depth: f64,
}

/// The cells of `h` (whose edges are `conn`'s) on `surface`, each by the light it lets through
/// against its reference, titled `title`; and the verdict line, with the whole device's shares.
pub fn shading_scene(
    h: &Honeycomb,
    conn: &Connectivity,
    surface: &Surface,
    light: DesignLight,
    title: String,
    camera: Camera,
    width: u32,
) -> (Scene, String) {
    let reference = extruded_along_normals(&h.base, conn, surface, light.depth);
    let after = light_share(h, light.direction, DEFAULT_LIGHT_SAMPLES);
    let before = light_share(&reference, light.direction, DEFAULT_LIGHT_SAMPLES);
    let ratios: Vec<f64> = (after.per_cell.iter().zip(&before.per_cell))
        .map(|(a, b)| a / b.max(FAINT))
        .collect();
    let cells: Vec<Vec<Vec3>> = (h.base.faces.iter())
        .map(|f| f.iter().map(|&v| h.base.vertices[v]).collect())
        .collect();
    let coloring = Coloring {
        title,
        measure: "light ratio",
        meaning: "light through the cell / through it along S's normals",
        unit: "",
        items: "cells",
        values: &ratios,
        tolerance: Some(SHADING_GOAL),
    };
    let verdict = format!(
        "{}; all cells let through {} of the light, against {} along S's normals",
        coloring.verdict(),
        rounded(after.share, 3),
        rounded(before.share, 3)
    );
    (
        polygons_scene(&cells, "cell", &coloring, camera, width),
        verdict,
    )
}
