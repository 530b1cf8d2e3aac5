//! The wall plane of edge `ab` contains the edge: `n_e . (v_a - v_b) = 0`, one row per edge.

use super::layout::{put, triple, Layout};
use crate::solve::Constraint;

pub struct WallConsistency {
    pub layout: Layout,
    pub edges: Vec<[usize; 2]>,
    pub weight: f64,
}

impl Constraint for WallConsistency {
    fn name(&self) -> &str {
        "wall_consistency"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.edges.len()
    }
    fn arity(&self) -> usize {
        9
    }
    fn row_variables(&self, e: usize, vars: &mut [usize]) {
        let [a, b] = self.edges[e];
        triple(&mut vars[0..3], self.layout.normal(e));
        triple(&mut vars[3..6], self.layout.vertex(a));
        triple(&mut vars[6..9], self.layout.vertex(b));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        let l = &self.layout;
        for (e, &[a, b]) in self.edges.iter().enumerate() {
            let n = l.normal_at(x, e);
            let d = l.vertex_at(x, a) - l.vertex_at(x, b);
            res[e] = n.dot(d);
            let j = &mut jac[9 * e..9 * e + 9];
            put(&mut j[0..3], d);
            put(&mut j[3..6], n);
            put(&mut j[6..9], -n);
        }
    }
}
