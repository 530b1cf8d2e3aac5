//! Soft fairness of the zigzag polylines of a quad-capped honeycomb (paper section 4, Fig. 11):
//! along a zigzag `v1 v2 v3 v4` every other edge repeats, `(v1 - v2) - (v3 - v4) = 0` (three
//! linear rows). The straight polylines' fairness, `n_ij . (v_j - v_k) = 0` with the wall
//! normal of edge `ij` kept, is a [`super::FixedNormals`] family.
//!
//! A small-weight wish, not a condition: on a curved surface it does not vanish exactly.

use super::layout::Layout;
use crate::solve::{Constraint, Role};

pub struct ZigzagFairness {
    pub layout: Layout,
    /// `[v1, v2, v3, v4]`: three consecutive edges of a zigzag.
    pub runs: Vec<[usize; 4]>,
    pub weight: f64,
    pub role: Role,
}

impl Constraint for ZigzagFairness {
    fn name(&self) -> &str {
        "fairness_zigzag"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn role(&self) -> Role {
        self.role
    }
    fn num_rows(&self) -> usize {
        3 * self.runs.len()
    }
    fn arity(&self) -> usize {
        4
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let (run, c) = (row / 3, row % 3);
        for (slot, &v) in self.runs[run].iter().enumerate() {
            vars[slot] = self.layout.vertex(v) + c;
        }
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        const SIGNS: [f64; 4] = [1.0, -1.0, -1.0, 1.0];
        for (run, vs) in self.runs.iter().enumerate() {
            for c in 0..3 {
                let row = 3 * run + c;
                res[row] = vs
                    .iter()
                    .zip(SIGNS)
                    .map(|(&v, s)| s * x[self.layout.vertex(v) + c])
                    .sum();
                jac[4 * row..4 * row + 4].copy_from_slice(&SIGNS);
            }
        }
    }
}
