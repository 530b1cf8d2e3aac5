//! Parallel meshes M, M' (paper section 4, Fig. 9). The second mesh's vertices `v'_i` are a block
//! of unknowns of their own (3 per vertex, from `offset_start`). Three families:
//! - `OffsetOnAxis`: `n_ij . (v'_i - v_i) = 0` at both ends of every edge, so `v'_i` lies on the
//!   node axis (the line common to the walls at i) and every wall stays a planar quad;
//! - `EdgeParallelity`: `(v_i - v_j) x (v'_i - v'_j) = 0`, three rows per edge;
//! - `ConstantDepth`: `|v_i - v'_i|^2 - C^2 = 0`, one soft row per vertex.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;

/// Where the second mesh's vertices live in the unknown vector.
#[derive(Clone, Copy, Debug)]
pub struct OffsetBlock {
    pub start: usize,
}

impl OffsetBlock {
    pub fn vertex(&self, v: usize) -> usize {
        self.start + 3 * v
    }
    pub fn vertex_at(&self, x: &[f64], v: usize) -> Vec3 {
        Vec3::from_slice(&x[self.vertex(v)..])
    }
}

pub struct OffsetOnAxis {
    pub layout: Layout,
    pub offset: OffsetBlock,
    pub edges: Vec<[usize; 2]>,
    pub weight: f64,
}

impl OffsetOnAxis {
    /// Row `2e + k`: edge `e` seen from its end `k` (0: a, sign +1; 1: b, sign -1).
    fn end(&self, row: usize) -> (usize, usize, f64) {
        let e = row / 2;
        match row % 2 {
            0 => (e, self.edges[e][0], 1.0),
            _ => (e, self.edges[e][1], -1.0),
        }
    }
}

impl Constraint for OffsetOnAxis {
    fn name(&self) -> &str {
        "offset_on_axis"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        2 * self.edges.len()
    }
    fn arity(&self) -> usize {
        9
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let (e, v, _) = self.end(row);
        triple(&mut vars[0..3], self.layout.normal(e));
        triple(&mut vars[3..6], self.layout.vertex(v));
        triple(&mut vars[6..9], self.offset.vertex(v));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for row in 0..self.num_rows() {
            let (e, v, s) = self.end(row);
            let n = self.layout.normal_at(x, e) * s;
            let d = self.offset.vertex_at(x, v) - self.layout.vertex_at(x, v);
            res[row] = n.dot(d);
            let j = &mut jac[9 * row..9 * row + 9];
            put(&mut j[0..3], d * s);
            put(&mut j[3..6], -n);
            put(&mut j[6..9], n);
        }
    }
}

pub struct EdgeParallelity {
    pub layout: Layout,
    pub offset: OffsetBlock,
    pub edges: Vec<[usize; 2]>,
    pub weight: f64,
}

impl Constraint for EdgeParallelity {
    fn name(&self) -> &str {
        "edge_parallelity"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        3 * self.edges.len()
    }
    fn arity(&self) -> usize {
        12
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let [a, b] = self.edges[row / 3];
        triple(&mut vars[0..3], self.layout.vertex(a));
        triple(&mut vars[3..6], self.layout.vertex(b));
        triple(&mut vars[6..9], self.offset.vertex(a));
        triple(&mut vars[9..12], self.offset.vertex(b));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (e, &[a, b]) in self.edges.iter().enumerate() {
            // c = d x d' with d = v_a - v_b, d' = v'_a - v'_b. Row k is c_k = d . (d' x e_k)
            // = d' . (e_k x d), so dc_k/dd = d' x e_k and dc_k/dd' = e_k x d.
            let d = self.layout.vertex_at(x, a) - self.layout.vertex_at(x, b);
            let dp = self.offset.vertex_at(x, a) - self.offset.vertex_at(x, b);
            let c = d.cross(dp);
            let axes = [
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0),
            ];
            for (k, ek) in axes.into_iter().enumerate() {
                let row = 3 * e + k;
                res[row] = c.to_array()[k];
                let (gd, gdp) = (dp.cross(ek), ek.cross(d));
                let j = &mut jac[12 * row..12 * row + 12];
                put(&mut j[0..3], gd);
                put(&mut j[3..6], -gd);
                put(&mut j[6..9], gdp);
                put(&mut j[9..12], -gdp);
            }
        }
    }
}

pub struct ConstantDepth {
    pub layout: Layout,
    pub offset: OffsetBlock,
    /// C, in the solver's (normalized) units.
    pub depth: f64,
    pub weight: f64,
}

impl Constraint for ConstantDepth {
    fn name(&self) -> &str {
        "constant_depth"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.layout.num_vertices
    }
    fn arity(&self) -> usize {
        6
    }
    fn row_variables(&self, v: usize, vars: &mut [usize]) {
        triple(&mut vars[0..3], self.layout.vertex(v));
        triple(&mut vars[3..6], self.offset.vertex(v));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for v in 0..self.num_rows() {
            let d = self.offset.vertex_at(x, v) - self.layout.vertex_at(x, v);
            res[v] = d.norm_squared() - self.depth * self.depth;
            put(&mut jac[6 * v..6 * v + 3], d * -2.0);
            put(&mut jac[6 * v + 3..6 * v + 6], d * 2.0);
        }
    }
}
