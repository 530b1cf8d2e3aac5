//! Edges of a prescribed shape (soft): `v_b - v_a - t_e = 0`, three rows per edge, each
//! touching one coordinate of both ends. With `t_e` the edge of a regular cell it asks for
//! cells of one size and shape; it fixes nothing but their differences, so the mesh may shift.

use super::layout::Layout;
use crate::geometry::Vec3;
use crate::solve::Constraint;

pub struct EdgeVectors {
    pub layout: Layout,
    /// Per edge: its ends `[a, b]` and the vector `t_e` from a to b.
    pub edges: Vec<([usize; 2], Vec3)>,
    pub weight: f64,
}

impl Constraint for EdgeVectors {
    fn name(&self) -> &str {
        "edge_vectors"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        3 * self.edges.len()
    }
    fn arity(&self) -> usize {
        2
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let [a, b] = self.edges[row / 3].0;
        vars[0] = self.layout.vertex(a) + row % 3;
        vars[1] = self.layout.vertex(b) + row % 3;
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (e, &([a, b], t)) in self.edges.iter().enumerate() {
            let d = (self.layout.vertex_at(x, b) - self.layout.vertex_at(x, a) - t).to_array();
            for k in 0..3 {
                res[3 * e + k] = d[k];
                jac[6 * e + 2 * k] = -1.0;
                jac[6 * e + 2 * k + 1] = 1.0;
            }
        }
    }
}
