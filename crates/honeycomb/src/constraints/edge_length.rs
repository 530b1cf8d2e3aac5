//! Edges of one length (soft): `|v_b - v_a| - L = 0`, one row per edge, touching both ends.
//! Unlike [`super::EdgeVectors`] it leaves each edge's direction free: cells of one size, of
//! no one shape or orientation. A fairness term: it fades with the regularization, so that it
//! reshapes the cells without biasing the honeycomb conditions at the end.

use super::layout::Layout;
use crate::solve::{Constraint, Role};

pub struct EdgeLength {
    pub layout: Layout,
    pub edges: Vec<[usize; 2]>,
    /// The length asked of every edge.
    pub length: f64,
    pub weight: f64,
}

impl Constraint for EdgeLength {
    fn name(&self) -> &str {
        "edge_length"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn role(&self) -> Role {
        Role::Fairness
    }
    fn num_rows(&self) -> usize {
        self.edges.len()
    }
    fn arity(&self) -> usize {
        6
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let [a, b] = self.edges[row];
        for k in 0..3 {
            vars[k] = self.layout.vertex(a) + k;
            vars[3 + k] = self.layout.vertex(b) + k;
        }
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (e, &[a, b]) in self.edges.iter().enumerate() {
            let d = self.layout.vertex_at(x, b) - self.layout.vertex_at(x, a);
            let length = d.norm();
            res[e] = length - self.length;
            // A collapsed edge has no direction to lengthen it along.
            let u = if length > 0.0 { d / length } else { d };
            for (k, &c) in u.to_array().iter().enumerate() {
                jac[6 * e + k] = -c;
                jac[6 * e + 3 + k] = c;
            }
        }
    }
}
