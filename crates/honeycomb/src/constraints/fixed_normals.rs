//! Pairs of vertices held across given directions: `n . (v_a - v_b) = 0` with `n` data, not
//! an unknown. One linear row per pair. With the wall normals of a finished honeycomb it keeps
//! every edge in its wall (the walls, and so the nodes' 120 degrees, stay as they are); with a
//! wall normal and a straight polyline's next edge it keeps the polyline from turning sideways.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::{Constraint, Role};

/// One row: `normal . (v_a - v_b) = 0`.
#[derive(Clone, Copy, Debug)]
pub struct FixedNormalRow {
    pub normal: Vec3,
    pub a: usize,
    pub b: usize,
}

pub struct FixedNormals {
    pub name: &'static str,
    pub layout: Layout,
    pub rows: Vec<FixedNormalRow>,
    pub weight: f64,
    pub role: Role,
}

impl Constraint for FixedNormals {
    fn name(&self) -> &str {
        self.name
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn role(&self) -> Role {
        self.role
    }
    fn num_rows(&self) -> usize {
        self.rows.len()
    }
    fn arity(&self) -> usize {
        6
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let r = self.rows[row];
        triple(&mut vars[0..3], self.layout.vertex(r.a));
        triple(&mut vars[3..6], self.layout.vertex(r.b));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (row, r) in self.rows.iter().enumerate() {
            let d = self.layout.vertex_at(x, r.a) - self.layout.vertex_at(x, r.b);
            res[row] = r.normal.dot(d);
            put(&mut jac[6 * row..6 * row + 3], r.normal);
            put(&mut jac[6 * row + 3..6 * row + 6], -r.normal);
        }
    }
}
