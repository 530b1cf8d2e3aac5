//! The shading system's report (paper Fig. 18): the light share of the optimized honeycomb
//! against that of the cells as they were given, extruded along the surface normals to the same
//! depth, for the design light direction and for any number of others (a day's sun path).

use super::light::{light_share, DEFAULT_LIGHT_SAMPLES};
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};
use crate::structure::Honeycomb;
use crate::surface::Surface;
use serde::Serialize;

/// The unshaded reference: the base mesh as given, each vertex extruded along S's normal.
pub fn extruded_along_normals(
    base: &PolyMesh,
    conn: &Connectivity,
    surface: &Surface,
    thickness: f64,
) -> Honeycomb {
    let axes = base
        .vertices
        .iter()
        .map(|&v| surface.normal_at(v))
        .collect();
    Honeycomb::new(base.clone(), conn, axes, thickness)
}

#[derive(Clone, Debug, Serialize)]
pub struct LightComparison {
    pub direction: [f64; 3],
    /// Share of the light that passes through the reference (before) and the result (after).
    pub before: f64,
    pub after: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct ShadingReport {
    /// What "before" is.
    pub reference: &'static str,
    pub samples_per_cell: usize,
    /// The design light direction.
    pub light: LightComparison,
    /// Every direction of a sun path, in its order (empty without one).
    pub sun_path: Vec<LightComparison>,
}

pub fn shading_report(
    before: &Honeycomb,
    after: &Honeycomb,
    light: Vec3,
    sun_path: &[Vec3],
) -> ShadingReport {
    let compare = |d: Vec3| LightComparison {
        direction: d.to_array(),
        before: light_share(before, d, DEFAULT_LIGHT_SAMPLES).share,
        after: light_share(after, d, DEFAULT_LIGHT_SAMPLES).share,
    };
    ShadingReport {
        reference: "the base mesh as given, extruded along the surface normals to the same depth",
        samples_per_cell: DEFAULT_LIGHT_SAMPLES,
        light: compare(light),
        sun_path: sun_path.iter().map(|&d| compare(d)).collect(),
    }
}
