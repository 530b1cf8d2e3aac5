//! A difference of two points orthogonal to a given direction: `d . (p_a - p_b) = 0`. In the
//! reciprocal sheet the difference is a wall normal, so the row asks the wall to contain `d`:
//! a node axis along S's normal, or an edge of the base mesh. With a `value`, the row asks
//! `d . (p_a - p_b) = value` instead: a unit wall normal facing `d`.

use super::layout::{put, triple};
use crate::geometry::Vec3;
use crate::solve::{Constraint, Role};

pub struct OrthogonalDifference {
    pub name: &'static str,
    /// Per row: the two points (point `k` is unknowns `3k..3k + 3`) and the direction.
    pub rows: Vec<([usize; 2], Vec3)>,
    /// What every row's product is asked to be (0: orthogonal).
    pub value: f64,
    pub weight: f64,
    pub role: Role,
    /// With `Role::Guide`: the factor the weight fades by per iteration.
    pub fade: f64,
}

impl Constraint for OrthogonalDifference {
    fn name(&self) -> &str {
        self.name
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn role(&self) -> Role {
        self.role
    }
    fn guide_fade(&self) -> f64 {
        self.fade
    }

    fn num_rows(&self) -> usize {
        self.rows.len()
    }
    fn arity(&self) -> usize {
        6
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let [a, b] = self.rows[row].0;
        triple(&mut vars[..3], 3 * a);
        triple(&mut vars[3..], 3 * b);
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (row, &([a, b], d)) in self.rows.iter().enumerate() {
            let diff = Vec3::from_slice(&x[3 * a..]) - Vec3::from_slice(&x[3 * b..]);
            res[row] = d.dot(diff) - self.value;
            put(&mut jac[6 * row..], d);
            put(&mut jac[6 * row + 3..], -d);
        }
    }
}
