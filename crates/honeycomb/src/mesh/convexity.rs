//! Convexity of cells: a honeycomb's cells are convex in practice, and guided projection
//! started from non-convex cells tends to fold or collapse them.

use super::PolyMesh;
use crate::geometry::Vec3;

/// Faces that are not convex, seen along their Newell normal (a corner turning the other way).
pub fn nonconvex_faces(mesh: &PolyMesh) -> Vec<usize> {
    let p = |i: usize| mesh.vertices[i];
    mesh.faces
        .iter()
        .enumerate()
        .filter(|(_, f)| {
            let k = f.len();
            let mut normal = Vec3::ZERO;
            for i in 0..k {
                normal += p(f[i]).cross(p(f[(i + 1) % k]));
            }
            (0..k).any(|i| {
                let (a, b, c) = (p(f[(i + k - 1) % k]), p(f[i]), p(f[(i + 1) % k]));
                (b - a).cross(c - b).dot(normal) < 0.0
            })
        })
        .map(|(i, _)| i)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_regular_hexagon_is_convex_and_a_dented_one_is_not() {
        let hex: Vec<Vec3> = (0..6)
            .map(|k| {
                let t = std::f64::consts::FRAC_PI_3 * k as f64;
                Vec3::new(t.cos(), t.sin(), 0.1 * (k % 2) as f64)
            })
            .collect();
        let mut mesh = PolyMesh::new(hex, vec![(0..6).collect()]);
        assert!(nonconvex_faces(&mesh).is_empty());
        // Push one corner past the center: the cell becomes an arrow.
        mesh.vertices[0] = Vec3::new(-0.3, 0.0, 0.0);
        assert_eq!(nonconvex_faces(&mesh), vec![0]);
    }
}
