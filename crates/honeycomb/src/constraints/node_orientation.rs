//! Orientation guard at nodes. The valence-2 node condition `n_ij . n_ik = -1/2` holds for two
//! walls meeting at 120 degrees, but also for walls meeting at 60 degrees with one normal turned
//! over: nothing in the normals alone tells the two apart. A trivalent node can likewise end with
//! one wall turned over (its three planes are 60 degrees apart either way). What tells them apart
//! is the side of wall ij on which another edge ik lies: `n_ij . (v_k - v_i)` keeps the sign it
//! has for the initial normals (edges rotated about the surface normal). One row per wall of a
//! guarded node, `sigma n_ij . (v_k - v_i) = mu^2` with a dummy `mu`: an inequality as an
//! equation, as for the minimum edge length. `optimize` guards every node when prescribed axes
//! (shading) turn the walls far from where they start, which is when walls were seen to turn
//! over. Not otherwise: the rows add fill, and on hexagonalminimal (non-convex cells) guarding
//! the boundary nodes held omega at 0.75 degrees instead of 3e-4.

use super::layout::{put, triple, Layout};
use crate::solve::Constraint;

/// One row: (edge of the wall, its sign seen from the node, the node i, the other neighbour
/// k, the sign sigma of `n_ij . (v_k - v_i)` to keep).
pub type OrientationRow = (usize, f64, usize, usize, f64);

pub struct NodeOrientation {
    pub layout: Layout,
    pub rows: Vec<OrientationRow>,
    /// Index of the first dummy in the unknown vector.
    pub dummy_start: usize,
    pub weight: f64,
}

impl NodeOrientation {
    /// One row per wall of each node in `nodes` (its walls as (edge, sign seen from the node)),
    /// against the other wall's edge; the signs to keep are read off `x`.
    pub fn rows(
        layout: Layout,
        edges: &[[usize; 2]],
        nodes: &[&[(usize, f64)]],
        x: &[f64],
    ) -> Vec<OrientationRow> {
        let far_end = |(e, s): (usize, f64)| if s > 0.0 { edges[e][1] } else { edges[e][0] };
        let mut rows = Vec::new();
        for walls in nodes {
            // The node is the end of the first edge that its sign names.
            let (e0, s0) = walls[0];
            let i = if s0 > 0.0 { edges[e0][0] } else { edges[e0][1] };
            for (w, &(e, s)) in walls.iter().enumerate() {
                let k = far_end(walls[(w + 1) % walls.len()]);
                let side = s * layout
                    .normal_at(x, e)
                    .dot(layout.vertex_at(x, k) - layout.vertex_at(x, i));
                rows.push((e, s, i, k, if side < 0.0 { -1.0 } else { 1.0 }));
            }
        }
        rows
    }

    /// Dummies that satisfy `rows` at `x`, kept away from 0 (where their derivative vanishes).
    /// Computed before the family is made: they are the block whose start it is given.
    pub fn initial_dummies(layout: Layout, rows: &[OrientationRow], x: &[f64]) -> Vec<f64> {
        rows.iter()
            .map(|&row| side(layout, row, x).max(0.0).sqrt().max(0.1))
            .collect()
    }
}

/// `sigma n_ij . (v_k - v_i)` for `row`.
fn side(l: Layout, (e, s, i, k, sigma): OrientationRow, x: &[f64]) -> f64 {
    sigma * s * l.normal_at(x, e).dot(l.vertex_at(x, k) - l.vertex_at(x, i))
}

impl Constraint for NodeOrientation {
    fn name(&self) -> &str {
        "node_orientation_valence2"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.rows.len()
    }
    fn arity(&self) -> usize {
        10
    }
    fn row_variables(&self, r: usize, vars: &mut [usize]) {
        let (e, _, i, k, _) = self.rows[r];
        triple(&mut vars[0..3], self.layout.normal(e));
        triple(&mut vars[3..6], self.layout.vertex(i));
        triple(&mut vars[6..9], self.layout.vertex(k));
        vars[9] = self.dummy_start + r;
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        let l = &self.layout;
        for r in 0..self.rows.len() {
            let (e, s, i, k, sigma) = self.rows[r];
            let mu = x[self.dummy_start + r];
            let c = sigma * s;
            let n = l.normal_at(x, e);
            let d = l.vertex_at(x, k) - l.vertex_at(x, i);
            res[r] = c * n.dot(d) - mu * mu;
            let j = &mut jac[10 * r..10 * r + 10];
            put(&mut j[0..3], d * c);
            put(&mut j[3..6], n * -c);
            put(&mut j[6..9], n * c);
            j[9] = -2.0 * mu;
        }
    }
}
