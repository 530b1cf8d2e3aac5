//! Vertices a file repeats at one position, joined into one. Many exports write each face
//! with corners of its own (an "unwelded" mesh, as STL does): read as they are, its faces
//! share no edge and S comes apart into as many pieces as it has faces.

use super::PolyMesh;
use std::collections::HashMap;

impl PolyMesh {
    /// Joins the vertices at exactly one position into the first of them, and drops the
    /// others; returns how many were dropped. Two of them in one face stay apart: that face
    /// has an edge of zero length, which validation names.
    pub fn join_coincident_vertices(&mut self) -> usize {
        let Some(into) = self.coincident_targets() else {
            return 0;
        };
        let dropped = into.iter().enumerate().filter(|&(v, &w)| v != w).count();
        let mut index = vec![usize::MAX; self.vertices.len()];
        let mut kept = Vec::with_capacity(self.vertices.len() - dropped);
        for (v, &w) in into.iter().enumerate() {
            if v == w {
                index[v] = kept.len();
                kept.push(self.vertices[v]);
            }
        }
        for face in &mut self.faces {
            for v in face.iter_mut() {
                // Indices beyond the vertices are left for validation to name.
                if let Some(&w) = into.get(*v) {
                    *v = index[w];
                }
            }
        }
        self.vertices = kept;
        dropped
    }

    /// Whether [`PolyMesh::join_coincident_vertices`] would join any.
    pub fn has_coincident_vertices(&self) -> bool {
        self.coincident_targets().is_some()
    }

    /// Per vertex, the vertex it is joined into (itself when kept); `None` when none is joined.
    fn coincident_targets(&self) -> Option<Vec<usize>> {
        // Adding 0.0 makes -0.0 and 0.0 one key.
        let key = |v: usize| self.vertices[v].to_array().map(|c| (c + 0.0).to_bits());
        let mut first: HashMap<[u64; 3], usize> = HashMap::with_capacity(self.vertices.len());
        let mut into: Vec<usize> = (0..self.vertices.len())
            .map(|v| *first.entry(key(v)).or_insert(v))
            .collect();
        for face in &self.faces {
            for (k, &a) in face.iter().enumerate() {
                for &b in &face[k + 1..] {
                    if a != b && into.get(a) == into.get(b) && into.get(a).is_some() {
                        into[a] = a;
                        into[b] = b;
                    }
                }
            }
        }
        into.iter()
            .enumerate()
            .any(|(v, &w)| v != w)
            .then_some(into)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vec3;

    /// Two triangles of a square, each with corners of its own, become one square with a
    /// shared diagonal.
    #[test]
    fn an_unwelded_square_is_joined_along_its_diagonal() {
        let p = |x: f64, y: f64| Vec3::new(x, y, 0.0);
        let mut m = PolyMesh::new(
            vec![
                p(0., 0.),
                p(1., 0.),
                p(1., 1.),
                p(0., 0.),
                p(1., 1.),
                p(-0., 1.),
            ],
            vec![vec![0, 1, 2], vec![3, 4, 5]],
        );
        assert_eq!(m.join_coincident_vertices(), 2);
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.faces, vec![vec![0, 1, 2], vec![0, 2, 3]]);
        assert_eq!(m.join_coincident_vertices(), 0);
    }

    /// A face with two corners at one point keeps both (its zero-length edge is an error to
    /// report, not to hide), and an index beyond the vertices stays as it was.
    #[test]
    fn corners_of_one_face_stay_apart() {
        let p = |x: f64| Vec3::new(x, 0.0, 0.0);
        let mut m = PolyMesh::new(
            vec![p(0.), p(1.), p(1.), p(2.)],
            vec![vec![0, 1, 2], vec![2, 3, 9]],
        );
        assert_eq!(m.join_coincident_vertices(), 0);
        assert_eq!(m.faces, vec![vec![0, 1, 2], vec![2, 3, 9]]);
    }
}
