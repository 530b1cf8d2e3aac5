//! A polygon mesh as index arrays: the exchange type between readers, writers and algorithms.

use crate::geometry::Vec3;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct PolyMesh {
    pub vertices: Vec<Vec3>,
    /// Each face is a loop of vertex indices (3 or more), oriented consistently.
    pub faces: Vec<Vec<usize>>,
}

impl PolyMesh {
    pub fn new(vertices: Vec<Vec3>, faces: Vec<Vec<usize>>) -> PolyMesh {
        PolyMesh { vertices, faces }
    }

    /// The unit square in the plane z = 0 as one quad, for tests.
    #[cfg(test)]
    pub(crate) fn unit_square() -> PolyMesh {
        let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        PolyMesh::new(
            corners.map(|(x, y)| Vec3::new(x, y, 0.0)).to_vec(),
            vec![vec![0, 1, 2, 3]],
        )
    }

    /// The square `[-half, half]^2` in the plane z = 0 as one quad, for tests.
    #[cfg(test)]
    pub(crate) fn square(half: f64) -> PolyMesh {
        let corners = [(-half, -half), (half, -half), (half, half), (-half, half)];
        PolyMesh::new(
            corners.map(|(x, y)| Vec3::new(x, y, 0.0)).to_vec(),
            vec![vec![0, 1, 2, 3]],
        )
    }

    /// Mean length of the distinct edges (0 for a mesh without edges).
    pub fn mean_edge_length(&self) -> f64 {
        let mut seen = std::collections::HashSet::new();
        let (mut sum, mut count) = (0.0, 0usize);
        for f in &self.faces {
            for k in 0..f.len() {
                let (a, b) = (f[k], f[(k + 1) % f.len()]);
                if seen.insert((a.min(b), a.max(b))) {
                    sum += (self.vertices[a] - self.vertices[b]).norm();
                    count += 1;
                }
            }
        }
        if count == 0 {
            0.0
        } else {
            sum / count as f64
        }
    }

    /// Length of the shortest edge (infinite for a mesh without edges).
    pub fn shortest_edge_length(&self) -> f64 {
        self.faces
            .iter()
            .flat_map(|f| (0..f.len()).map(move |k| (f[k], f[(k + 1) % f.len()])))
            .map(|(a, b)| (self.vertices[a] - self.vertices[b]).norm())
            .fold(f64::INFINITY, f64::min)
    }

    /// Applies `p -> (p - center) * scale` to every vertex.
    pub fn transform(&mut self, center: Vec3, scale: f64) {
        for v in &mut self.vertices {
            *v = (*v - center) * scale;
        }
    }

    /// The centroid of the vertices.
    pub fn centroid(&self) -> Vec3 {
        let mut c = Vec3::ZERO;
        for v in &self.vertices {
            c += *v;
        }
        c / (self.vertices.len().max(1) as f64)
    }

    /// The centroid of face `f`'s corners.
    pub fn face_centroid(&self, f: usize) -> Vec3 {
        let face = &self.faces[f];
        face.iter().fold(Vec3::ZERO, |c, &v| c + self.vertices[v]) / face.len() as f64
    }

    /// The area of the surface the mesh spans: that of its star triangulation, the one S is
    /// made of (see [`PolyMesh::star_triangulated`]).
    pub fn area(&self) -> f64 {
        let (vertices, triangles) = self.star_triangulated();
        triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| vertices[v]);
                0.5 * (b - a).cross(c - a).norm()
            })
            .sum()
    }

    /// A triangulation that makes a fair surface of a polygon mesh: quads split along a
    /// diagonal, larger faces by a star of triangles around their centroid (an added vertex).
    /// Unlike a fan from a corner, the star does not fold a non-convex or twisted cell.
    pub fn star_triangulated(&self) -> (Vec<Vec3>, Vec<[usize; 3]>) {
        let mut vertices = self.vertices.clone();
        let mut faces = Vec::with_capacity(self.faces.len() * 6);
        for f in &self.faces {
            if f.len() <= 4 {
                faces.extend((1..f.len().saturating_sub(1)).map(|k| [f[0], f[k], f[k + 1]]));
                continue;
            }
            let mut c = Vec3::ZERO;
            for &i in f {
                c += self.vertices[i];
            }
            vertices.push(c / f.len() as f64);
            let center = vertices.len() - 1;
            for k in 0..f.len() {
                faces.push([f[k], f[(k + 1) % f.len()], center]);
            }
        }
        (vertices, faces)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Signed areas (along +z) of a planar triangulation's triangles.
    fn signed_areas(vertices: &[Vec3], tris: impl Iterator<Item = [usize; 3]>) -> Vec<f64> {
        tris.map(|[a, b, c]| {
            (vertices[b] - vertices[a])
                .cross(vertices[c] - vertices[a])
                .z
        })
        .collect()
    }

    #[test]
    fn star_triangulation_does_not_fold_a_non_convex_cell() {
        // A hexagon with its second corner pushed inwards, counter-clockwise: the fan from
        // the first corner crosses the dent.
        let mut corners: Vec<Vec3> = (0..6)
            .map(|k| {
                let t = std::f64::consts::FRAC_PI_3 * k as f64;
                Vec3::new(t.cos(), t.sin(), 0.0)
            })
            .collect();
        corners[1] = Vec3::new(0.3, 0.2, 0.0);
        let mesh = PolyMesh::new(corners, vec![(0..6).collect()]);
        let fan = signed_areas(&mesh.vertices, (1..5).map(|k| [0, k, k + 1]));
        assert!(fan.iter().any(|&a| a < 0.0), "the fan should fold: {fan:?}");
        let (vertices, triangles) = mesh.star_triangulated();
        assert_eq!(vertices.len(), 7);
        assert_eq!(triangles.len(), 6);
        let areas = signed_areas(&vertices, triangles.into_iter());
        assert!(areas.iter().all(|&a| a > 0.0), "{areas:?}");
    }
}
