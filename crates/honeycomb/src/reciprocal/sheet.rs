//! The combinatorics of the reciprocal sheet: one point per cell, one per run of boundary edges
//! outside the mesh (a ghost cell), one triangle per node.

use crate::error::{Error, Result};
use crate::geometry::Vec3;
use crate::mesh::{Connectivity, PolyMesh};

/// The sheet of a base mesh. Points `0..cells` are its cells, the rest ghosts.
#[derive(Clone, Debug)]
pub struct Sheet {
    pub cells: usize,
    /// Ghost cells outside the boundary.
    pub ghosts: usize,
    /// Per edge `[a, b]` of the connectivity: the points on its left and on its right (the
    /// cell holding `a -> b` and the other), so that the wall normal seen from `a` is
    /// `p_left - p_right`.
    pub sides: Vec<[usize; 2]>,
    /// Per vertex: its three points counterclockwise around it (seen from the side the faces
    /// turn counterclockwise about).
    pub triangles: Vec<[usize; 3]>,
    /// Per node of valence 2: its two ghosts `[g_in, g_out]`, the pair of its third, virtual
    /// wall.
    pub virtual_pairs: Vec<[usize; 2]>,
}

impl Sheet {
    /// The sheet of a valid base mesh (every vertex of valence 2 or 3). Fails on a boundary
    /// loop with exactly one node of valence 2, whose ghost would meet itself.
    pub fn new(mesh: &PolyMesh, conn: &Connectivity) -> Result<Sheet> {
        let cells = mesh.faces.len();
        let mut sides = vec![[usize::MAX; 2]; conn.num_edges()];
        for (f, face) in mesh.faces.iter().enumerate() {
            for (k, &e) in conn.face_edges[f].iter().enumerate() {
                let slot = if conn.edges[e][0] == face[k] { 0 } else { 1 };
                sides[e][slot] = f;
            }
        }
        // Ghosts: walking a boundary loop, a new one starts at every node of valence 2 (there
        // the boundary turns away from the mesh); along a node of valence 3 the two boundary
        // edges border the same cell outside.
        let mut ghosts = 0;
        for lp in &conn.boundary_loops {
            let corners = lp.iter().filter(|&&v| conn.valence(v) == 2).count();
            if corners == 1 {
                return Err(Error::Mesh(format!(
                    "boundary loop through vertex {} has one vertex of valence 2 only; the \
                     reciprocal sheet needs none or at least two",
                    lp[0]
                )));
            }
            let first = lp.iter().position(|&v| conn.valence(v) == 2).unwrap_or(0);
            let n = lp.len();
            for k in 0..n {
                let (u, w) = (lp[(first + k) % n], lp[(first + k + 1) % n]);
                if k == 0 || conn.valence(u) == 2 {
                    ghosts += 1;
                }
                let e = conn.vertex_edges[u]
                    .iter()
                    .copied()
                    .find(|&e| conn.edges[e].contains(&w) && conn.is_boundary_edge(e))
                    .ok_or_else(|| {
                        Error::Mesh(format!("boundary loop step {u}-{w} is not an edge"))
                    })?;
                let slot = sides[e]
                    .iter()
                    .position(|&p| p == usize::MAX)
                    .ok_or_else(|| {
                        Error::Mesh(format!("boundary edge {u}-{w} has cells on both sides"))
                    })?;
                sides[e][slot] = cells + ghosts - 1;
            }
        }
        if let Some(e) = sides.iter().position(|s| s.contains(&usize::MAX)) {
            let [a, b] = conn.edges[e];
            return Err(Error::Mesh(format!(
                "edge {a}-{b} has no cell on one side and is on no boundary loop"
            )));
        }
        let mut triangles = Vec::with_capacity(mesh.vertices.len());
        let mut virtual_pairs = Vec::new();
        for v in 0..mesh.vertices.len() {
            // Around v counterclockwise, each wall passes from the point on the right of its
            // edge (seen leaving v) to the point on its left.
            let steps: Vec<[usize; 2]> = conn.vertex_edges[v]
                .iter()
                .map(|&e| {
                    let [l, r] = sides[e];
                    if conn.edges[e][0] == v {
                        [r, l]
                    } else {
                        [l, r]
                    }
                })
                .collect();
            let mut order = vec![steps[0][0], steps[0][1]];
            while order.len() < 3 {
                let last = order[order.len() - 1];
                match steps.iter().find(|s| s[0] == last) {
                    Some(s) => order.push(s[1]),
                    // Valence 2: the chain is ghost -> cell -> ghost (or it starts mid-way).
                    None => break,
                }
            }
            if order.len() < 3 {
                let next = steps.iter().find(|s| s[1] == order[0]).map(|s| s[0]);
                match next {
                    Some(p) => order.insert(0, p),
                    None => return Err(Error::Mesh(format!("vertex {v}: its walls do not close"))),
                }
            }
            let t = [order[0], order[1], order[2]];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                return Err(Error::Mesh(format!(
                    "vertex {v}: two of its walls border the same cells"
                )));
            }
            if steps.len() == 2 {
                // The chain runs ghost, cell, ghost: the virtual wall closes it.
                let cell = t.iter().position(|&p| p < cells).unwrap_or(1);
                virtual_pairs.push([t[(cell + 1) % 3], t[(cell + 2) % 3]]);
            }
            triangles.push(t);
        }
        Ok(Sheet {
            cells,
            ghosts,
            sides,
            triangles,
            virtual_pairs,
        })
    }

    pub fn points(&self) -> usize {
        self.cells + self.ghosts
    }

    /// Every pair at unit distance in a honeycomb's sheet: the walls, then the virtual walls.
    pub fn unit_pairs(&self) -> Vec<[usize; 2]> {
        self.sides
            .iter()
            .chain(&self.virtual_pairs)
            .copied()
            .collect()
    }

    /// The unit wall normal of edge `e` (seen from its first vertex) for points `p`.
    pub fn wall_normal(&self, p: &[Vec3], e: usize) -> Vec3 {
        let [l, r] = self.sides[e];
        (p[l] - p[r]).normalized()
    }

    #[cfg(test)]
    /// The unit node axis of vertex `v` for points `p`: its triangle's normal.
    pub fn axis(&self, p: &[Vec3], v: usize) -> Vec3 {
        let [a, b, c] = self.triangles[v];
        (p[b] - p[a]).cross(p[c] - p[a]).normalized()
    }

    /// The points whose differences best reproduce wall normals `normals` (one per edge, as
    /// seen from its first vertex): cells by least squares over the walls between two cells,
    /// each ghost from the cells across its walls.
    pub fn points_of(&self, normals: &[Vec3]) -> Result<Vec<Vec3>> {
        let inner: Vec<(usize, usize, Vec3)> = (self.sides.iter().zip(normals))
            .filter(|(s, _)| s[0] < self.cells && s[1] < self.cells)
            .map(|(&[l, r], &n)| (l, r, n))
            .collect();
        let cells = crate::geometry::differences::integrated(self.cells, &inner)?;
        Ok(self.with_ghosts(cells, |e| normals[e]))
    }

    /// The points of `cells` followed by each ghost's: the mean over its walls of the cell
    /// inside across the wall, one `wall_normal(e)` away.
    fn with_ghosts(&self, mut points: Vec<Vec3>, wall_normal: impl Fn(usize) -> Vec3) -> Vec<Vec3> {
        let mut sums = vec![(Vec3::ZERO, 0usize); self.ghosts];
        for (e, &[l, r]) in self.sides.iter().enumerate() {
            let guess = match (l >= self.cells, r >= self.cells) {
                (false, true) => Some((r, points[l] - wall_normal(e))),
                (true, false) => Some((l, points[r] + wall_normal(e))),
                _ => None,
            };
            if let Some((g, p)) = guess {
                let s = &mut sums[g - self.cells];
                *s = (s.0 + p, s.1 + 1);
            }
        }
        points.extend(sums.iter().map(|&(s, k)| s / k.max(1) as f64));
        points
    }

    /// Sheet units per model unit for `mesh`: neighbouring cells' centroids one apart on
    /// average.
    pub fn scale(&self, mesh: &PolyMesh) -> f64 {
        let inner: Vec<f64> = self
            .sides
            .iter()
            .filter(|s| s[0] < self.cells && s[1] < self.cells)
            .map(|&[l, r]| (mesh.face_centroid(l) - mesh.face_centroid(r)).norm())
            .collect();
        let spacing = inner.iter().sum::<f64>() / inner.len().max(1) as f64;
        if spacing > 0.0 {
            1.0 / spacing
        } else {
            1.0
        }
    }

    /// Starting points for `mesh` on a surface with normal `normal_at`: the cells' centroids
    /// scaled so that neighbouring cells are one apart, and each ghost across its boundary
    /// edges from the cells inside, one along the edges' initial wall normals.
    pub fn initial_points(
        &self,
        mesh: &PolyMesh,
        conn: &Connectivity,
        normal_at: impl Fn(Vec3) -> Vec3,
    ) -> Vec<Vec3> {
        let centroids: Vec<Vec3> = (0..self.cells).map(|f| mesh.face_centroid(f)).collect();
        let scale = self.scale(mesh);
        let points: Vec<Vec3> = centroids.iter().map(|&c| c * scale).collect();
        self.with_ghosts(points, |e| {
            let [a, b] = conn.edges[e];
            let (pa, pb) = (mesh.vertices[a], mesh.vertices[b]);
            (pa - pb).normalized().cross(normal_at((pa + pb) * 0.5))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::hex_disk;
    use crate::mesh::validate_base_mesh;

    /// On a flat hex disk the starting sheet is the unit triangular lattice: every wall and
    /// virtual wall one long, every node's triangle counterclockwise (its normal up) and each
    /// wall normal pointing from the right cell to the left one, perpendicular to its edge.
    #[test]
    fn a_flat_disk_starts_as_the_unit_lattice() {
        let mesh = hex_disk(4.0);
        let conn = validate_base_mesh(&mesh).unwrap();
        let sheet = Sheet::new(&mesh, &conn).unwrap();
        let up = Vec3::new(0.0, 0.0, 1.0);
        let p = sheet.initial_points(&mesh, &conn, |_| up);
        assert_eq!(p.len(), sheet.points());
        assert!(sheet.ghosts > 0);
        for [a, b] in sheet.unit_pairs() {
            let d = (p[a] - p[b]).norm();
            assert!((d - 1.0).abs() < 1e-9, "pair {a}-{b} is {d} apart");
        }
        for v in 0..mesh.vertices.len() {
            assert!(sheet.axis(&p, v).dot(up) > 1.0 - 1e-12, "node {v}");
        }
        for (e, &[a, b]) in conn.edges.iter().enumerate() {
            let n = sheet.wall_normal(&p, e);
            let initial = (mesh.vertices[a] - mesh.vertices[b]).normalized().cross(up);
            assert!(n.dot(initial) > 1.0 - 1e-9, "edge {e}");
        }
        let corners = (0..mesh.vertices.len()).filter(|&v| conn.valence(v) == 2);
        assert_eq!(sheet.virtual_pairs.len(), corners.count());
    }

    /// The points of a sheet's wall normals are the sheet's points, moved as one: every cell
    /// and ghost keeps its place relative to the others, on a folded sheet as on a flat one.
    #[test]
    fn the_points_of_wall_normals_are_the_sheet() {
        let mesh = hex_disk(4.0);
        let conn = validate_base_mesh(&mesh).unwrap();
        let sheet = Sheet::new(&mesh, &conn).unwrap();
        let flat = sheet.initial_points(&mesh, &conn, |_| Vec3::new(0.0, 0.0, 1.0));
        // Folded along x = 0: each half turned by 20 degrees about the y axis.
        let (c, s) = (20f64.to_radians().cos(), 20f64.to_radians().sin());
        let folded: Vec<Vec3> = flat
            .iter()
            .map(|p| Vec3::new(p.x * c, p.y, p.x.abs() * s))
            .collect();
        let normals: Vec<Vec3> = (0..conn.num_edges())
            .map(|e| folded[sheet.sides[e][0]] - folded[sheet.sides[e][1]])
            .collect();
        let again = sheet.points_of(&normals).unwrap();
        let shift = again[0] - folded[0];
        for (k, (&a, &p)) in again.iter().zip(&folded).enumerate() {
            assert!((a - p - shift).norm() < 1e-6, "point {k}: {a:?} for {p:?}");
        }
    }
}
