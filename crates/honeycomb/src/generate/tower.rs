//! Tubes round the z axis, open at both ends: a straight one (a cylinder) and a cooling tower
//! (a hyperboloid of one sheet). No flattening of a whole tube lays it in the plane; a lattice
//! runs round it once it is cut open from end to end (see `init::seam`).

use crate::geometry::Vec3;
use crate::mesh::PolyMesh;

/// The waist's radius and the hyperboloid's other semi-axis, as shares of `d`: the radius at
/// height z is `WAIST d sqrt(1 + (z / (NECK d))^2)`.
const WAIST: f64 = 0.5;
const NECK: f64 = 1.6;
/// The tower runs from `BASE d` below its waist to `TOP d` above it: a cooling tower's
/// proportions, its base 1.65 times as wide as its waist, its top 1.09 times, its waist at
/// three quarters of its height.
const BASE: f64 = 2.1;
const TOP: f64 = 0.7;

/// The tower's radius at height `z` (its waist at z = 0).
pub fn tower_radius(z: f64, d: f64) -> f64 {
    WAIST * d * (1.0 + (z / (NECK * d)).powi(2)).sqrt()
}

/// The tower of scale `d` triangulated in rows of `around` quads split in two, about square at
/// the waist; triangles counter-clockwise seen from outside.
pub fn cooling_tower(d: f64, around: usize) -> PolyMesh {
    tube_of_revolution(
        |z| tower_radius(z, d),
        (-BASE * d, TOP * d),
        WAIST * d,
        around,
    )
}

/// A cylinder of `radius` round the z axis from z = 0 to `height`, triangulated likewise.
pub fn tube(radius: f64, height: f64, around: usize) -> PolyMesh {
    tube_of_revolution(|_| radius, (0.0, height), radius, around)
}

/// The surface of revolution of `radius(z)` from `z.0` to `z.1` in rows of `around` quads split
/// in two, the rows as far apart as the quads are wide at `narrowest`.
fn tube_of_revolution(
    radius: impl Fn(f64) -> f64,
    (bottom, top): (f64, f64),
    narrowest: f64,
    around: usize,
) -> PolyMesh {
    let step = std::f64::consts::TAU * narrowest / around as f64;
    let rows = ((top - bottom) / step).ceil() as usize;
    let mut vertices = Vec::with_capacity((rows + 1) * around);
    for j in 0..=rows {
        let z = bottom + (top - bottom) * j as f64 / rows as f64;
        let r = radius(z);
        for i in 0..around {
            let t = std::f64::consts::TAU * i as f64 / around as f64;
            vertices.push(Vec3::new(r * t.cos(), r * t.sin(), z));
        }
    }
    PolyMesh::new(vertices, super::split_quads(around, rows, around))
}
