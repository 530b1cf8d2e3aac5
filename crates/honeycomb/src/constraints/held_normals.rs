//! Wall normals held near where they started (soft): `n_e - m_e = 0`, three rows per edge.
//! It holds the walls, and so the node axes, where a fit put them while another family
//! reshapes the cells. A fairness term, fading with the regularization.

use super::layout::Layout;
use crate::geometry::Vec3;
use crate::solve::{Constraint, Role};

pub struct HeldNormals {
    pub layout: Layout,
    /// Per edge, the normal it is held near.
    pub normals: Vec<Vec3>,
    pub weight: f64,
}

impl Constraint for HeldNormals {
    fn name(&self) -> &str {
        "held_normals"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn role(&self) -> Role {
        Role::Fairness
    }
    fn num_rows(&self) -> usize {
        3 * self.normals.len()
    }
    fn arity(&self) -> usize {
        1
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        vars[0] = self.layout.normal(row / 3) + row % 3;
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (e, m) in self.normals.iter().enumerate() {
            let d = (self.layout.normal_at(x, e) - *m).to_array();
            for k in 0..3 {
                res[3 * e + k] = d[k];
                jac[3 * e + k] = 1.0;
            }
        }
    }
}
