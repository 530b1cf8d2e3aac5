//! An undulating roof: the subject of the quad-cover tests and benchmark (the paper's Figure 11).

use super::hex_disk;
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;

/// The "roof": an undulating rectangular sheet, twice as long as wide, in the spirit of the
/// Cour Visconti roof (Fig. 1): one and a half waves along its length, a half wave across, so
/// that it has both dome-like and saddle-like regions (|V| about `vertices`, edge length 1).
/// The amplitude of `Shape::Roof` (the demo's and the zigzag benchmark's roof).
pub const ROOF_AMPLITUDE: f64 = 0.08;

/// The roof's height over (x, y) for half-length `a` (half-width a / 2).
pub(crate) fn roof_height(x: f64, y: f64, a: f64, amplitude: f64) -> f64 {
    let (u, v) = (x / a, 2.0 * y / a);
    let pi = std::f64::consts::PI;
    amplitude * a * (1.5 * pi * u).sin() * (0.5 * pi * v).cos() - 0.05 * a * u * v
}

/// The height is `amplitude` times the half-length a; the smallest curvature radius, along the
/// length, is a / (2.25 pi^2 amplitude): at 3.5k vertices 27 edge lengths for amplitude 0.08,
/// 18 for 0.12.
pub fn roof(vertices: usize, amplitude: f64) -> (PolyMesh, PolyMesh) {
    // A hexagon of edge 1 has area 3 sqrt(3) / 2 and about two vertices.
    let area = vertices as f64 / 2.0 * 1.5 * 3f64.sqrt();
    let (a, b) = ((area / 2.0).sqrt(), (area / 8.0).sqrt());
    let height = |x: f64, y: f64| roof_height(x, y, a, amplitude);
    let disk = hex_disk(1.05 * (a * a + b * b).sqrt());
    let inside = |f: &Vec<usize>| {
        let c = f.iter().fold(Vec3::ZERO, |s, &v| s + disk.vertices[v]) / f.len() as f64;
        c.x.abs() <= a && c.y.abs() <= b
    };
    let mut index = vec![usize::MAX; disk.vertices.len()];
    let mut vs = Vec::new();
    let mut faces = Vec::new();
    for f in disk.faces.iter().filter(|f| inside(f)) {
        faces.push(
            f.iter()
                .map(|&v| {
                    if index[v] == usize::MAX {
                        index[v] = vs.len();
                        let p = disk.vertices[v];
                        vs.push(Vec3::new(p.x, p.y, height(p.x, p.y)));
                    }
                    index[v]
                })
                .collect(),
        );
    }
    // The design surface: a fine grid over the sheet with a margin, counter-clockwise from +z.
    let n = 200;
    let (ha, hb) = (1.1 * a + 2.0, 1.1 * b + 2.0);
    let mut sv = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let x = -ha + 2.0 * ha * i as f64 / n as f64;
            let y = -hb + 2.0 * hb * j as f64 / n as f64;
            sv.push(Vec3::new(x, y, height(x, y)));
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            tris.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push(vec![id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (PolyMesh::new(vs, faces), PolyMesh::new(sv, tris))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{lifted_hex_patch, HeightField, Shape};

    #[test]
    fn the_roof_shape_is_the_roof_and_twice_as_long_as_wide() {
        let (base, surface) = lifted_hex_patch(Shape::Roof, 3500);
        assert_eq!(base.vertices, roof(3500, ROOF_AMPLITUDE).0.vertices);
        assert!((base.vertices.len() as f64 - 3500.0).abs() < 0.1 * 3500.0);
        let a = (3500.0 / 2.0 * 1.5 * 3f64.sqrt() / 2.0).sqrt();
        let field = HeightField {
            shape: Shape::Roof,
            d: a,
        };
        for p in base.vertices.iter().chain(&surface.vertices) {
            assert!((p.z - field.height(p.x, p.y)).abs() < 1e-12);
        }
        let (lo, hi) = base
            .vertices
            .iter()
            .fold((base.vertices[0], base.vertices[0]), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let (length, width) = (hi.x - lo.x, hi.y - lo.y);
        assert!((length / width - 2.0).abs() < 0.15, "{length} x {width}");
        // It undulates: heights of both signs, up to about amplitude times the half-length.
        assert!(hi.z > 0.05 * a && lo.z < -0.05 * a, "{} {}", lo.z, hi.z);
    }
}
