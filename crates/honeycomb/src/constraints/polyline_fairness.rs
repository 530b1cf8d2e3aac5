//! Soft fairness of the polylines of a quad-capped honeycomb (paper section 4, Fig. 11):
//! - `ZigzagFairness`: along a zigzag `v1 v2 v3 v4` every other edge repeats,
//!   `(v1 - v2) - (v3 - v4) = 0` (three linear rows);
//! - `StraightFairness`: a straight polyline `v_i v_j v_k` does not turn sideways,
//!   `n_ij . (v_j - v_k) = 0`, with `n_ij = s n_e` the wall normal of edge `ij` seen from `i`
//!   (the wall contains the edge and the node axis, so its normal is the sideways direction).
//!
//! Both are small-weight wishes, not conditions: on a curved surface neither vanishes exactly.

use super::layout::{put, triple, Layout};
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

/// One row `s n_e . (v_j - v_k)`: edge `e` (with the sign of its normal seen from the run's
/// first vertex) continued at `j` towards `k`.
#[derive(Clone, Copy, Debug)]
pub struct LateralRun {
    pub edge: usize,
    pub sign: f64,
    pub j: usize,
    pub k: usize,
}

pub struct StraightFairness {
    pub layout: Layout,
    pub runs: Vec<LateralRun>,
    pub weight: f64,
    pub role: Role,
}

impl Constraint for StraightFairness {
    fn name(&self) -> &str {
        "fairness_straight"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn role(&self) -> Role {
        self.role
    }
    fn num_rows(&self) -> usize {
        self.runs.len()
    }
    fn arity(&self) -> usize {
        9
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let r = self.runs[row];
        triple(&mut vars[0..3], self.layout.normal(r.edge));
        triple(&mut vars[3..6], self.layout.vertex(r.j));
        triple(&mut vars[6..9], self.layout.vertex(r.k));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (row, r) in self.runs.iter().enumerate() {
            let n = self.layout.normal_at(x, r.edge) * r.sign;
            let d = self.layout.vertex_at(x, r.j) - self.layout.vertex_at(x, r.k);
            res[row] = n.dot(d);
            let j = &mut jac[9 * row..9 * row + 9];
            put(&mut j[0..3], d * r.sign);
            put(&mut j[3..6], n);
            put(&mut j[6..9], -n);
        }
    }
}
