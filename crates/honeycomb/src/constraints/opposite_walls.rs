//! Fairness of hexagonal cells (paper Fig. 7b): opposite walls of a hexagon are parallel,
//! `m_k + m_(k+3) = 0` with `m_k` the wall normal of the cell's k-th edge seen from its start.
//! A soft term: its weight fades with the regularization.

use super::layout::Layout;
use crate::solve::{Constraint, Role};

pub struct OppositeWalls {
    pub layout: Layout,
    /// Pairs of opposite walls: (edge, sign as seen from the cell) twice.
    pub pairs: Vec<[(usize, f64); 2]>,
    pub weight: f64,
}

impl Constraint for OppositeWalls {
    fn name(&self) -> &str {
        "fairness_opposite_walls"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn role(&self) -> Role {
        Role::Fairness
    }
    fn num_rows(&self) -> usize {
        3 * self.pairs.len()
    }
    fn arity(&self) -> usize {
        2
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let (pair, c) = (row / 3, row % 3);
        let [(e1, _), (e2, _)] = self.pairs[pair];
        vars[0] = self.layout.normal(e1) + c;
        vars[1] = self.layout.normal(e2) + c;
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (pair, &[(e1, s1), (e2, s2)]) in self.pairs.iter().enumerate() {
            for c in 0..3 {
                let row = 3 * pair + c;
                res[row] = s1 * x[self.layout.normal(e1) + c] + s2 * x[self.layout.normal(e2) + c];
                jac[2 * row] = s1;
                jac[2 * row + 1] = s2;
            }
        }
    }
}
