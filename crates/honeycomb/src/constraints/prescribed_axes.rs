//! Prescribed node axes (paper section 4, Fig. 10 and 18): the walls at node `i` contain the
//! direction `a_i`, i.e. `a_i . n_ij = 0` for every edge end. One row per edge end; each row
//! touches one edge normal only, so it adds nothing to the factorization's fill.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::{Constraint, Role};

pub struct PrescribedAxes {
    pub layout: Layout,
    /// Per edge end: (edge, sign of its normal seen from the node, the node's target axis).
    pub ends: Vec<(usize, f64, Vec3)>,
    pub weight: f64,
    pub role: Role,
}

impl Constraint for PrescribedAxes {
    fn name(&self) -> &str {
        match self.role {
            Role::Condition => "prescribed_axes",
            _ => "guide_axes_along_normals",
        }
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn role(&self) -> Role {
        self.role
    }
    fn num_rows(&self) -> usize {
        self.ends.len()
    }
    fn arity(&self) -> usize {
        3
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        triple(vars, self.layout.normal(self.ends[row].0));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (row, &(e, s, a)) in self.ends.iter().enumerate() {
            res[row] = s * a.dot(self.layout.normal_at(x, e));
            put(&mut jac[3 * row..], a * s);
        }
    }
}
