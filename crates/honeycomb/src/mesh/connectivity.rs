//! Edge, face and boundary adjacency of a polygon mesh, with manifoldness checks.

use super::PolyMesh;
use crate::error::{Error, Result};

/// Adjacency of a manifold, consistently oriented polygon mesh.
///
/// Every edge is stored once as `(a, b)` with `a < b`; the wall normal of that edge seen from
/// `a` is the stored one, seen from `b` its negative (see [`Connectivity::edge_sign`]).
#[derive(Clone, Debug)]
pub struct Connectivity {
    pub edges: Vec<[usize; 2]>,
    /// The faces on each side of an edge (at most two).
    pub edge_faces: Vec<[Option<usize>; 2]>,
    /// Incident edges of each vertex.
    pub vertex_edges: Vec<Vec<usize>>,
    /// `face_edges[f][k]` is the edge from `faces[f][k]` to `faces[f][k + 1]`.
    pub face_edges: Vec<Vec<usize>>,
    /// Boundary loops as vertex sequences.
    pub boundary_loops: Vec<Vec<usize>>,
    pub is_boundary_vertex: Vec<bool>,
}

impl Connectivity {
    /// Builds the adjacency; fails on out-of-range indices, degenerate faces, edges shared by
    /// more than two faces, inconsistent orientation and non-manifold vertices.
    pub fn build(mesh: &PolyMesh) -> Result<Connectivity> {
        let nv = mesh.vertices.len();
        let mut edges: Vec<[usize; 2]> = Vec::new();
        let mut edge_faces: Vec<[Option<usize>; 2]> = Vec::new();
        // Per edge: its direction in its first face, to detect orientation flips and to run
        // the boundary. Edges are found through the short incidence lists of their lower end
        // (no hashing: this runs on surfaces of hundreds of thousands of triangles).
        let mut first_direction: Vec<[usize; 2]> = Vec::new();
        let mut vertex_edges: Vec<Vec<usize>> = vec![Vec::new(); nv];
        let mut face_edges = Vec::with_capacity(mesh.faces.len());
        for (fi, f) in mesh.faces.iter().enumerate() {
            if f.len() < 3 {
                return Err(Error::Mesh(format!(
                    "face {fi} has {} vertices; a face needs at least 3",
                    f.len()
                )));
            }
            for (k, &v) in f.iter().enumerate() {
                if v >= nv {
                    return Err(Error::Mesh(format!(
                        "face {fi} refers to vertex {v}, but the mesh has {nv} vertices"
                    )));
                }
                if f[..k].contains(&v) {
                    return Err(Error::Mesh(format!("face {fi} visits vertex {v} twice")));
                }
            }
            let mut fe = Vec::with_capacity(f.len());
            for k in 0..f.len() {
                let (a, b) = (f[k], f[(k + 1) % f.len()]);
                let key = [a.min(b), a.max(b)];
                let found = vertex_edges[key[0]].iter().find(|&&e| edges[e] == key);
                let e = match found {
                    Some(&e) => e,
                    None => {
                        let e = edges.len();
                        edges.push(key);
                        edge_faces.push([None, None]);
                        first_direction.push([a, b]);
                        vertex_edges[key[0]].push(e);
                        vertex_edges[key[1]].push(e);
                        e
                    }
                };
                let slot = &mut edge_faces[e];
                if slot[0].is_none() {
                    slot[0] = Some(fi);
                } else if slot[1].is_none() {
                    if first_direction[e] == [a, b] {
                        return Err(Error::Mesh(format!(
                            "edge {a}-{b} is used in the same direction by faces {} and {fi}: \
                             the faces are not consistently oriented",
                            slot[0].unwrap()
                        )));
                    }
                    slot[1] = Some(fi);
                } else {
                    return Err(Error::Mesh(format!(
                        "non-manifold edge {a}-{b}: shared by more than two faces ({}, {}, {fi})",
                        slot[0].unwrap(),
                        slot[1].unwrap()
                    )));
                }
                fe.push(e);
            }
            face_edges.push(fe);
        }

        // Boundary: edges of one face. A manifold vertex has at most one outgoing one.
        let mut next_on_boundary: Vec<Option<usize>> = vec![None; nv];
        let mut is_boundary_vertex = vec![false; nv];
        for (e, &[a, b]) in first_direction.iter().enumerate() {
            if edge_faces[e][1].is_none() {
                // Boundary runs opposite to the face orientation: b -> a.
                if next_on_boundary[b].is_some() {
                    return Err(Error::Mesh(format!(
                        "non-manifold vertex {b}: it lies on the boundary more than once \
                         (two cells touch only at this vertex)"
                    )));
                }
                next_on_boundary[b] = Some(a);
                is_boundary_vertex[a] = true;
                is_boundary_vertex[b] = true;
            }
        }
        let mut boundary_loops = Vec::new();
        let mut visited = vec![false; nv];
        for start in 0..nv {
            if visited[start] || next_on_boundary[start].is_none() {
                continue;
            }
            let mut lp = Vec::new();
            let mut v = start;
            while !visited[v] {
                visited[v] = true;
                lp.push(v);
                v = next_on_boundary[v].expect("boundary half-edges form closed loops");
            }
            boundary_loops.push(lp);
        }

        let conn = Connectivity {
            edges,
            edge_faces,
            vertex_edges,
            face_edges,
            boundary_loops,
            is_boundary_vertex,
        };
        conn.check_vertex_fans(mesh)?;
        Ok(conn)
    }

    /// A vertex is manifold when its faces form one fan (a disk, or a half-disk at the
    /// boundary): the faces around it must be connected through shared edges.
    fn check_vertex_fans(&self, mesh: &PolyMesh) -> Result<()> {
        for (v, inc) in self.vertex_edges.iter().enumerate() {
            if inc.is_empty() {
                continue;
            }
            let faces_here: usize = inc
                .iter()
                .map(|&e| self.edge_faces[e].iter().flatten().count())
                .sum::<usize>();
            // Each face at v contributes exactly two incident edges; a single fan with k edges
            // has k faces (closed) or k - 1 faces (open). More edges than that means two fans.
            let nfaces = faces_here / 2;
            let boundary_edges = inc
                .iter()
                .filter(|&&e| self.edge_faces[e][1].is_none())
                .count();
            let expected_faces = if boundary_edges == 0 {
                inc.len()
            } else {
                inc.len() - 1
            };
            if boundary_edges > 2 || nfaces != expected_faces {
                let p = mesh.vertices[v];
                return Err(Error::Mesh(format!(
                    "non-manifold vertex {v} at ({}, {}, {}): its faces do not form a single fan",
                    p.x, p.y, p.z
                )));
            }
        }
        Ok(())
    }

    pub fn num_edges(&self) -> usize {
        self.edges.len()
    }

    pub fn valence(&self, v: usize) -> usize {
        self.vertex_edges[v].len()
    }

    /// `+1` if `v` is the first endpoint of edge `e`, else `-1`: `n_(v,other) = sign * n_e`.
    pub fn edge_sign(&self, e: usize, v: usize) -> f64 {
        if self.edges[e][0] == v {
            1.0
        } else {
            -1.0
        }
    }

    /// The endpoint of `e` that is not `v`.
    pub fn other_end(&self, e: usize, v: usize) -> usize {
        let [a, b] = self.edges[e];
        if a == v {
            b
        } else {
            a
        }
    }

    /// The faces not `gone` gathered into pieces joined through shared edges, each in the
    /// order it was reached from its lowest face.
    pub fn pieces(&self, gone: &[bool]) -> Vec<Vec<usize>> {
        let mut seen = gone.to_vec();
        let mut pieces = Vec::new();
        for root in 0..gone.len() {
            if seen[root] {
                continue;
            }
            seen[root] = true;
            let (mut stack, mut piece) = (vec![root], vec![root]);
            while let Some(f) = stack.pop() {
                for &e in &self.face_edges[f] {
                    for g in self.edge_faces[e].into_iter().flatten() {
                        if !seen[g] {
                            seen[g] = true;
                            piece.push(g);
                            stack.push(g);
                        }
                    }
                }
            }
            pieces.push(piece);
        }
        pieces
    }

    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.edge_faces[e][1].is_none()
    }

    /// Whether face `f` has an edge on the boundary.
    pub fn is_boundary_face(&self, f: usize) -> bool {
        self.face_edges[f].iter().any(|&e| self.is_boundary_edge(e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vec3;

    /// Three squares in a row, and a fourth apart.
    #[test]
    fn pieces_are_joined_through_edges_and_split_where_faces_are_gone() {
        let vertices = (0..4)
            .flat_map(|x| (0..2).map(move |y| Vec3::new(x as f64, y as f64, 0.0)))
            .chain((0..4).map(|k| Vec3::new(9.0 + (k % 2) as f64, (k / 2) as f64, 0.0)))
            .collect();
        let square = |x: usize| vec![2 * x, 2 * x + 2, 2 * x + 3, 2 * x + 1];
        let faces = vec![square(0), square(1), square(2), vec![8, 9, 11, 10]];
        let conn = Connectivity::build(&PolyMesh::new(vertices, faces)).unwrap();
        assert_eq!(conn.pieces(&[false; 4]), vec![vec![0, 1, 2], vec![3]]);
        assert_eq!(
            conn.pieces(&[false, true, false, false]),
            vec![vec![0], vec![2], vec![3]]
        );
    }
}
