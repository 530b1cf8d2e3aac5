//! The samples the fields live on: S's triangles, with edges split until none is longer than
//! a fraction of the lattice spacing, so that every lattice point has mesh vertices near it.
//! Split points are edge midpoints, so every sample lies on S exactly; their normals blend
//! S's vertex normals, so the fields see a smooth surface rather than flat facets.

use super::tangent::{unit_tangent, usable_normal};
use crate::error::{Error, Result};
use crate::geometry::Vec3;
use crate::surface::Surface;
use std::collections::HashMap;

/// Refinement stops with an error beyond this many samples (memory, not accuracy).
pub const MAX_SAMPLES: usize = 12_000_000;

pub struct Sampling {
    pub points: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Oriented like S (counter-clockwise seen from the normals).
    pub triangles: Vec<[u32; 3]>,
    /// A third of the area of the triangles around each sample.
    pub areas: Vec<f64>,
    /// For samples on S's boundary, the boundary's direction there (with S on its left).
    pub boundary_tangents: Vec<Option<Vec3>>,
}

impl Sampling {
    /// S's triangles, refined until no edge is longer than `longest`.
    pub fn new(surface: &Surface, longest: f64) -> Result<Sampling> {
        let mut points = surface.vertices().to_vec();
        let mut normals = surface.vertex_normals().to_vec();
        let mut triangles: Vec<[u32; 3]> = surface
            .triangles()
            .iter()
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
            .map(|t| t.map(|v| v as u32))
            .collect();
        if points.len() > u32::MAX as usize / 2 {
            return Err(Error::Mesh(format!(
                "the surface has {} vertices; at most {} are supported",
                points.len(),
                u32::MAX / 2
            )));
        }
        fill_missing_normals(&points, &triangles, &mut normals);
        while refine(&mut points, &mut normals, &mut triangles, longest)? {}
        let areas = vertex_areas(&points, &triangles);
        let boundary_tangents = boundary_tangents(&points, &normals, &triangles);
        Ok(Sampling {
            points,
            normals,
            triangles,
            areas,
            boundary_tangents,
        })
    }
}

/// Vertices without a normal (only in degenerate triangles) borrow their triangles' normals.
fn fill_missing_normals(points: &[Vec3], triangles: &[[u32; 3]], normals: &mut [Vec3]) {
    let mut borrowed = vec![Vec3::ZERO; points.len()];
    for t in triangles {
        let [a, b, c] = t.map(|v| points[v as usize]);
        let n = (b - a).cross(c - a);
        for &v in t {
            borrowed[v as usize] += n;
        }
    }
    for (n, b) in normals.iter_mut().zip(borrowed) {
        let unit = n.norm_squared() > 0.5;
        if !unit {
            *n = usable_normal(b);
        }
    }
}

/// One pass of splitting every edge longer than `longest` at its midpoint (each triangle cut
/// into 2, 3 or 4 by the pattern of its split edges). False when nothing was split; an error
/// beyond [`MAX_SAMPLES`].
fn refine(
    points: &mut Vec<Vec3>,
    normals: &mut Vec<Vec3>,
    triangles: &mut Vec<[u32; 3]>,
    longest: f64,
) -> Result<bool> {
    let limit = longest * longest;
    let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
    for t in triangles.iter() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            if (points[a as usize] - points[b as usize]).norm_squared() > limit
                && !midpoints.contains_key(&key)
            {
                let (pa, pb) = (points[a as usize], points[b as usize]);
                let n = usable_normal(normals[a as usize] + normals[b as usize]);
                points.push((pa + pb) * 0.5);
                normals.push(n);
                midpoints.insert(key, (points.len() - 1) as u32);
                if points.len() > MAX_SAMPLES {
                    return Err(Error::Parameter(format!(
                        "cells this small need more than {MAX_SAMPLES} samples of the \
                         surface for the field-aligned method: choose larger cells"
                    )));
                }
            }
        }
    }
    if midpoints.is_empty() {
        return Ok(false);
    }
    let mid = |a: u32, b: u32| midpoints.get(&(a.min(b), a.max(b))).copied();
    let mut refined = Vec::with_capacity(triangles.len() * 3);
    for &t in triangles.iter() {
        let m = [mid(t[0], t[1]), mid(t[1], t[2]), mid(t[2], t[0])];
        match m.iter().filter(|x| x.is_some()).count() {
            0 => refined.push(t),
            1 => {
                // Rotate so that the split edge is t[0] t[1].
                let k = m.iter().position(Option::is_some).unwrap_or(0);
                let [a, b, c] = [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
                let ab = m[k].unwrap_or(a);
                refined.push([a, ab, c]);
                refined.push([ab, b, c]);
            }
            2 => {
                // Rotate so that the unsplit edge is t[2] t[0].
                let k = (m.iter().position(Option::is_none).unwrap_or(2) + 1) % 3;
                let [a, b, c] = [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
                let (ab, bc) = (m[k].unwrap_or(a), m[(k + 1) % 3].unwrap_or(b));
                refined.push([ab, b, bc]);
                // The quad a ab bc c, cut along its shorter diagonal.
                let p = |v: u32| points[v as usize];
                if (p(a) - p(bc)).norm_squared() <= (p(ab) - p(c)).norm_squared() {
                    refined.push([a, ab, bc]);
                    refined.push([a, bc, c]);
                } else {
                    refined.push([a, ab, c]);
                    refined.push([ab, bc, c]);
                }
            }
            _ => {
                let [ab, bc, ca] = m.map(|x| x.unwrap_or(0));
                refined.push([t[0], ab, ca]);
                refined.push([ab, t[1], bc]);
                refined.push([ca, bc, t[2]]);
                refined.push([ab, bc, ca]);
            }
        }
    }
    *triangles = refined;
    Ok(true)
}

fn vertex_areas(points: &[Vec3], triangles: &[[u32; 3]]) -> Vec<f64> {
    let mut areas = vec![0.0; points.len()];
    for t in triangles {
        let [a, b, c] = t.map(|v| points[v as usize]);
        let third = (b - a).cross(c - a).norm() / 6.0;
        for &v in t {
            areas[v as usize] += third;
        }
    }
    areas
}

/// The direction of S's boundary at each boundary sample: from its predecessor to its
/// successor along the boundary half-edges (edges of one triangle, run as that triangle runs).
fn boundary_tangents(
    points: &[Vec3],
    normals: &[Vec3],
    triangles: &[[u32; 3]],
) -> Vec<Option<Vec3>> {
    let mut directed: HashMap<(u32, u32), u32> = HashMap::with_capacity(3 * triangles.len());
    for t in triangles {
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    let mut along = vec![Vec3::ZERO; points.len()];
    let mut on_boundary = vec![false; points.len()];
    for &(a, b) in directed.keys() {
        if directed.contains_key(&(b, a)) {
            continue;
        }
        let d = (points[b as usize] - points[a as usize]).normalized();
        for v in [a, b] {
            along[v as usize] += d;
            on_boundary[v as usize] = true;
        }
    }
    (0..points.len())
        .map(|v| {
            if on_boundary[v] {
                unit_tangent(along[v], normals[v])
            } else {
                None
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::PolyMesh;

    #[test]
    fn long_edges_are_split_and_the_samples_stay_on_the_surface() {
        // Two triangles of a bent square: refined, every sample lies on one of them.
        let mesh = PolyMesh::new(
            vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.3),
                Vec3::new(0.0, 1.0, 0.0),
            ],
            vec![vec![0, 1, 2], vec![0, 2, 3]],
        );
        let surface = Surface::from_mesh(&mesh).unwrap();
        let sampling = Sampling::new(&surface, 0.1).unwrap();
        assert!(sampling.points.len() > 100);
        for t in &sampling.triangles {
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
                assert!((sampling.points[a] - sampling.points[b]).norm() <= 0.1 + 1e-12);
            }
        }
        for &p in &sampling.points {
            assert!(surface.closest_point(p).distance < 1e-12);
        }
        let area: f64 = sampling.areas.iter().sum();
        let expected = 0.5
            * (Vec3::new(1.0, 0.0, 0.0)
                .cross(Vec3::new(1.0, 1.0, 0.3))
                .norm()
                + Vec3::new(1.0, 1.0, 0.3)
                    .cross(Vec3::new(0.0, 1.0, 0.0))
                    .norm());
        assert!((area - expected).abs() < 1e-9);
        // The boundary runs counter-clockwise around the square seen from above.
        let at = |x: f64, y: f64| {
            (0..sampling.points.len())
                .find(|&v| {
                    let p = sampling.points[v];
                    (p.x - x).abs() < 1e-9 && (p.y - y).abs() < 1e-9
                })
                .unwrap()
        };
        let t = sampling.boundary_tangents[at(0.5, 0.0)].unwrap();
        assert!(t.x > 0.99, "{t:?}");
        assert!(sampling.boundary_tangents[at(0.5, 0.5)].is_none());
    }
}
