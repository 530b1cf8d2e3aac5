//! Unit wall normals: `n_e . n_e - 1 = 0`, one row per edge.

use super::layout::{put, triple, Layout};
use crate::solve::Constraint;

pub struct Normalization {
    pub layout: Layout,
    pub weight: f64,
}

impl Constraint for Normalization {
    fn name(&self) -> &str {
        "normalization"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.layout.num_edges
    }
    fn arity(&self) -> usize {
        3
    }
    fn row_variables(&self, e: usize, vars: &mut [usize]) {
        triple(vars, self.layout.normal(e));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for e in 0..self.layout.num_edges {
            let n = self.layout.normal_at(x, e);
            res[e] = n.norm_squared() - 1.0;
            put(&mut jac[3 * e..], 2.0 * n);
        }
    }
}
