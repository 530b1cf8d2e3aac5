//! Planar capping quads (paper section 4, "Quadrangulation"): each quad gets a unit normal of
//! its own, a block of unknowns after the honeycomb's (3 per quad, from `start`), with the same
//! two conditions as a wall:
//! - `QuadNormalization`: `n_q . n_q - 1 = 0`, one row per quad;
//! - `QuadPlanarity`: `n_q . (p_(k+1) - p_k) = 0` for edges of the quad: the normal is
//!   orthogonal to the quad's sides, so its corners lie in one plane.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;

/// Where the quad normals live in the unknown vector.
#[derive(Clone, Copy, Debug)]
pub struct QuadNormalBlock {
    pub start: usize,
}

impl QuadNormalBlock {
    pub fn normal(&self, q: usize) -> usize {
        self.start + 3 * q
    }
    pub fn normal_at(&self, x: &[f64], q: usize) -> Vec3 {
        Vec3::from_slice(&x[self.normal(q)..])
    }
}

pub struct QuadNormalization {
    pub block: QuadNormalBlock,
    pub num_quads: usize,
    pub weight: f64,
}

impl Constraint for QuadNormalization {
    fn name(&self) -> &str {
        "quad_normalization"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.num_quads
    }
    fn arity(&self) -> usize {
        3
    }
    fn row_variables(&self, q: usize, vars: &mut [usize]) {
        triple(vars, self.block.normal(q));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for q in 0..self.num_quads {
            let n = self.block.normal_at(x, q);
            res[q] = n.norm_squared() - 1.0;
            put(&mut jac[3 * q..], 2.0 * n);
        }
    }
}

pub struct QuadPlanarity {
    pub layout: Layout,
    pub block: QuadNormalBlock,
    /// Corners of each quad (vertices of M).
    pub quads: Vec<[usize; 4]>,
    /// Which sides `k -> k+1` get a row. Three suffice (the four sides sum to zero); all four
    /// weigh the sides alike.
    pub sides: Vec<usize>,
    pub weight: f64,
}

impl QuadPlanarity {
    fn side(&self, row: usize) -> (usize, usize, usize) {
        let (q, s) = (row / self.sides.len(), self.sides[row % self.sides.len()]);
        (q, self.quads[q][s], self.quads[q][(s + 1) % 4])
    }
}

impl Constraint for QuadPlanarity {
    fn name(&self) -> &str {
        "quad_planarity"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.sides.len() * self.quads.len()
    }
    fn arity(&self) -> usize {
        9
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let (q, a, b) = self.side(row);
        triple(&mut vars[0..3], self.block.normal(q));
        triple(&mut vars[3..6], self.layout.vertex(a));
        triple(&mut vars[6..9], self.layout.vertex(b));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for row in 0..self.num_rows() {
            let (q, a, b) = self.side(row);
            let n = self.block.normal_at(x, q);
            let d = self.layout.vertex_at(x, b) - self.layout.vertex_at(x, a);
            res[row] = n.dot(d);
            let j = &mut jac[9 * row..9 * row + 9];
            put(&mut j[0..3], d);
            put(&mut j[3..6], -n);
            put(&mut j[6..9], n);
        }
    }
}
