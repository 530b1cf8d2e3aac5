//! The 120-degree node condition.
//!
//! At a trivalent node the three wall normals seen from the node form an equilateral triangle:
//! `n_ij + n_ik + n_il = 0` (three linear rows) says both that the walls meet at 120 degrees
//! and that they share one axis. At a boundary node of valence 2 the two walls meet at 120
//! degrees: `n_ij . n_ik + 1/2 = 0` (one bilinear row).
//! `n_ij = s n_e` with `s = +1` when the node is the edge's first endpoint, else `-1`.

use super::layout::{put, Layout};
use crate::solve::Constraint;

/// Trivalent nodes: three rows (x, y, z) per node.
pub struct Node3 {
    pub layout: Layout,
    /// Per node: its three edges and the sign of each edge's normal as seen from the node.
    pub nodes: Vec<[(usize, f64); 3]>,
    pub weight: f64,
}

impl Constraint for Node3 {
    fn name(&self) -> &str {
        "node_120_valence3"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        3 * self.nodes.len()
    }
    fn arity(&self) -> usize {
        3
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let (node, c) = (row / 3, row % 3);
        for (k, &(e, _)) in self.nodes[node].iter().enumerate() {
            vars[k] = self.layout.normal(e) + c;
        }
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (node, edges) in self.nodes.iter().enumerate() {
            for c in 0..3 {
                let row = 3 * node + c;
                res[row] = edges
                    .iter()
                    .map(|&(e, s)| s * x[self.layout.normal(e) + c])
                    .sum();
                for (k, &(_, s)) in edges.iter().enumerate() {
                    jac[3 * row + k] = s;
                }
            }
        }
    }
}

/// Boundary nodes of valence 2: one row per node.
pub struct Node2 {
    pub layout: Layout,
    pub nodes: Vec<[(usize, f64); 2]>,
    pub weight: f64,
}

impl Constraint for Node2 {
    fn name(&self) -> &str {
        "node_120_valence2"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.nodes.len()
    }
    fn arity(&self) -> usize {
        6
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let [(e1, _), (e2, _)] = self.nodes[row];
        super::layout::triple(&mut vars[0..3], self.layout.normal(e1));
        super::layout::triple(&mut vars[3..6], self.layout.normal(e2));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (row, &[(e1, s1), (e2, s2)]) in self.nodes.iter().enumerate() {
            let s = s1 * s2;
            let (n1, n2) = (self.layout.normal_at(x, e1), self.layout.normal_at(x, e2));
            res[row] = s * n1.dot(n2) + 0.5;
            put(&mut jac[6 * row..], s * n2);
            put(&mut jac[6 * row + 3..], s * n1);
        }
    }
}
