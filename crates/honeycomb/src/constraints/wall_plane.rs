//! The wall plane of edge `ab`, `n_e . p = d_e` with its own offset `d_e`, passes through both
//! ends: `n_e . v_a - d_e = 0` and `n_e . v_b - d_e = 0`, two rows per edge. The same walls as
//! [`super::WallConsistency`], but no row touches two vertices, so the vertices' block of the
//! normal matrix is block diagonal (3 x 3 per vertex) and can be eliminated exactly.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;

pub struct WallPlane {
    pub layout: Layout,
    pub edges: Vec<[usize; 2]>,
    /// The unknown of each edge's offset.
    pub offsets: Vec<usize>,
    /// A point per wall that the offset is measured from (the edge's midpoint at the start):
    /// offsets from the origin gave a wall's turn a lever as long as the mesh is wide, and
    /// nodes flipped (omega_max 60 degrees after 5 iterations at 8.5k vertices, where the
    /// anchored offsets give 3.5e-9).
    pub anchors: Vec<Vec3>,
    pub weight: f64,
}

impl WallPlane {
    pub fn offset(&self, e: usize) -> usize {
        self.offsets[e]
    }
}

impl Constraint for WallPlane {
    fn name(&self) -> &str {
        "wall_plane"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        2 * self.edges.len()
    }
    fn arity(&self) -> usize {
        7
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let e = row / 2;
        triple(&mut vars[0..3], self.layout.normal(e));
        triple(&mut vars[3..6], self.layout.vertex(self.edges[e][row % 2]));
        vars[6] = self.offset(e);
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        let l = &self.layout;
        for (e, ends) in self.edges.iter().enumerate() {
            let n = l.normal_at(x, e);
            for (k, &v) in ends.iter().enumerate() {
                let row = 2 * e + k;
                let p = l.vertex_at(x, v) - self.anchors[e];
                res[row] = n.dot(p) - x[self.offset(e)];
                let j = &mut jac[7 * row..7 * row + 7];
                put(&mut j[0..3], p);
                put(&mut j[3..6], n);
                j[6] = -1.0;
            }
        }
    }
}
