//! Minimum edge length (paper section 4, remark; Tang et al. 2014): `|v_a - v_b|^2 = L^2 + d_e^2`
//! with one dummy unknown `d_e` per edge, so that the inequality `|v_a - v_b| >= L` becomes an
//! equation. The dummies are a block of their own after the honeycomb's unknowns.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;

pub struct MinEdgeLength {
    pub layout: Layout,
    pub edges: Vec<[usize; 2]>,
    /// L, in the solver's (normalized) units.
    pub length: f64,
    /// Index of the first dummy in the unknown vector.
    pub dummy_start: usize,
    pub weight: f64,
}

impl MinEdgeLength {
    /// Dummies that satisfy the rows where an edge is already long enough, and never below
    /// L/10: the dummy enters squared, so at 0 its derivative vanishes and a short edge would be
    /// pinned to exactly L instead of being free to grow past it.
    pub fn initial_dummies(&self, vertices: &[Vec3]) -> Vec<f64> {
        self.edges
            .iter()
            .map(|&[a, b]| {
                let l2 = (vertices[a] - vertices[b]).norm_squared();
                (l2 - self.length * self.length)
                    .max(0.0)
                    .sqrt()
                    .max(0.1 * self.length)
            })
            .collect()
    }
}

impl Constraint for MinEdgeLength {
    fn name(&self) -> &str {
        "min_edge_length"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.edges.len()
    }
    fn arity(&self) -> usize {
        7
    }
    fn row_variables(&self, e: usize, vars: &mut [usize]) {
        let [a, b] = self.edges[e];
        triple(&mut vars[0..3], self.layout.vertex(a));
        triple(&mut vars[3..6], self.layout.vertex(b));
        vars[6] = self.dummy_start + e;
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (e, &[a, b]) in self.edges.iter().enumerate() {
            let d = self.layout.vertex_at(x, a) - self.layout.vertex_at(x, b);
            let dummy = x[self.dummy_start + e];
            res[e] = d.norm_squared() - self.length * self.length - dummy * dummy;
            let j = &mut jac[7 * e..7 * e + 7];
            put(&mut j[0..3], d * 2.0);
            put(&mut j[3..6], d * -2.0);
            j[6] = -2.0 * dummy;
        }
    }
}
