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

    /// Fan triangulation of every face (faces are assumed convex enough for a fan).
    pub fn triangulated(&self) -> Vec<[usize; 3]> {
        let mut tris = Vec::with_capacity(self.faces.len() * 2);
        for f in &self.faces {
            for k in 1..f.len().saturating_sub(1) {
                tris.push([f[0], f[k], f[k + 1]]);
            }
        }
        tris
    }
}
