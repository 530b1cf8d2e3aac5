//! A planar patch of regular hexagons: the cells of a triangular lattice of centers that fall
//! inside a disk. Any union of whole hexagons is a valid base mesh: every vertex has valence 2
//! (boundary corner) or 3, and two cells at a vertex always share an edge, so it is manifold.

use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use std::collections::HashMap;

/// Hexagons of edge length 1 (pointy side up, counter-clockwise seen from +z) whose centers
/// lie within `radius` of the origin, in the plane z = 0.
pub fn hex_disk(radius: f64) -> PolyMesh {
    let s3 = 3f64.sqrt();
    // Rows are 1.5 apart and a row's cells shift by half a cell per row: covering the disk
    // needs |j| <= radius / 1.5 and |i| <= radius / sqrt(3) + |j| / 2 < radius.
    let range = radius.ceil() as i64 + 2;
    let mut vertices = Vec::new();
    let mut index: HashMap<(i64, i64), usize> = HashMap::new();
    let mut faces = Vec::new();
    for j in -range..=range {
        for i in -range..=range {
            // Lattice a1 = (sqrt3, 0), a2 = (sqrt3/2, 3/2).
            let c = (s3 * (i as f64 + 0.5 * j as f64), 1.5 * j as f64);
            if c.0 * c.0 + c.1 * c.1 > radius * radius {
                continue;
            }
            let face = (0..6)
                .map(|k| {
                    let t = std::f64::consts::FRAC_PI_6 + std::f64::consts::FRAC_PI_3 * k as f64;
                    let p = (c.0 + t.cos(), c.1 + t.sin());
                    // Corners are shared by up to three cells: key them on a fine grid.
                    let key = ((p.0 * 1e6).round() as i64, (p.1 * 1e6).round() as i64);
                    *index.entry(key).or_insert_with(|| {
                        vertices.push(Vec3::new(p.0, p.1, 0.0));
                        vertices.len() - 1
                    })
                })
                .collect();
            faces.push(face);
        }
    }
    PolyMesh::new(vertices, faces)
}

/// The disk radius whose hexagon patch has about `vertices` vertices.
pub fn radius_for_vertices(vertices: usize) -> f64 {
    // A hexagon of edge 1 has area 3 sqrt(3) / 2 and owns two vertices.
    let cells = vertices as f64 / 2.0;
    (cells * 1.5 * 3f64.sqrt() / std::f64::consts::PI).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_patch_is_a_full_disk_of_the_requested_size() {
        for target in [1500, 35000] {
            let r = radius_for_vertices(target);
            let mesh = hex_disk(r);
            let n = mesh.vertices.len() as f64;
            assert!(
                (n / target as f64 - 1.0).abs() < 0.1,
                "{target}: {n} vertices"
            );
            // Round: as far up and down as left and right.
            let (lo, hi) = mesh
                .vertices
                .iter()
                .fold((Vec3::ZERO, Vec3::ZERO), |(lo, hi), &v| {
                    (lo.min(v), hi.max(v))
                });
            let (w, h) = (hi.x - lo.x, hi.y - lo.y);
            assert!((w / h - 1.0).abs() < 0.1, "{target}: {w} x {h}");
        }
    }
}
