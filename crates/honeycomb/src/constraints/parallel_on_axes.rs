//! Parallel meshes M, M' on the walls of a finished honeycomb (paper section 4, Fig. 9). The
//! walls stay as they are; every vertex slides along its node axis, `v_i = p_i + s_i a_i`, and
//! its twin sits at depth `d_i` below it, `v'_i = v_i + d_i a_i`. Both lie on the node axis,
//! so every node keeps its 120 degrees and every wall its plane, and the unknowns are two
//! scalars per vertex.
//!
//! Both edges `v_a v_b` and `v'_a v'_b` lie in the wall of normal `n`, so they are parallel
//! when `n . ((v_a - v_b) x (v'_a - v'_b)) = 0`, that is
//! `n . ((p_a - p_b + s_a a_a - s_b a_b) x (d_a a_a - d_b a_b)) = 0`: one bilinear row per
//! edge, scaled by `1 / (|p_a - p_b| D)` (D the nominal depth) to read as the sine of the
//! angle between the edges.

use crate::geometry::Vec3;
use crate::solve::Constraint;

/// Where the slides live in the unknown vector: `s_i` at `start + i`, `d_i` at
/// `start + vertices + i`.
#[derive(Clone, Copy, Debug)]
pub struct AxisSlides {
    pub start: usize,
    pub vertices: usize,
}

impl AxisSlides {
    pub fn shift(&self, v: usize) -> usize {
        self.start + v
    }
    pub fn depth(&self, v: usize) -> usize {
        self.start + self.vertices + v
    }
}

pub struct ParallelOnAxes {
    pub slides: AxisSlides,
    /// The vertices where the slides start from (`p_i`).
    pub anchors: Vec<Vec3>,
    /// Unit node axes (`a_i`).
    pub axes: Vec<Vec3>,
    pub edges: Vec<[usize; 2]>,
    /// Unit wall normals, one per edge.
    pub normals: Vec<Vec3>,
    /// The nominal depth D.
    pub depth: f64,
    pub weight: f64,
}

impl Constraint for ParallelOnAxes {
    fn name(&self) -> &str {
        "parallel_on_axes"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.edges.len()
    }
    fn arity(&self) -> usize {
        4
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let [a, b] = self.edges[row];
        vars.copy_from_slice(&[
            self.slides.shift(a),
            self.slides.shift(b),
            self.slides.depth(a),
            self.slides.depth(b),
        ]);
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (row, &[a, b]) in self.edges.iter().enumerate() {
            let (aa, ab, n) = (self.axes[a], self.axes[b], self.normals[row]);
            let (sa, sb) = (x[self.slides.shift(a)], x[self.slides.shift(b)]);
            let (da, db) = (x[self.slides.depth(a)], x[self.slides.depth(b)]);
            let chord = self.anchors[a] - self.anchors[b];
            let scale = 1.0 / (chord.norm() * self.depth).max(f64::MIN_POSITIVE);
            let edge = chord + aa * sa - ab * sb;
            let across = n.dot(aa.cross(ab));
            res[row] = scale * n.dot(edge.cross(aa * da - ab * db));
            let j = &mut jac[4 * row..4 * row + 4];
            j[0] = -scale * db * across;
            j[1] = scale * da * across;
            j[2] = scale * n.dot(edge.cross(aa));
            j[3] = -scale * n.dot(edge.cross(ab));
        }
    }
}

/// Soft targets for single unknowns, `w (x_k - t_k) / unit = 0`: one row each.
pub struct ScalarTargets {
    pub name: &'static str,
    pub start: usize,
    pub targets: Vec<f64>,
    /// What a residual of 1 means, in the unknowns' units.
    pub unit: f64,
    pub weight: f64,
}

impl Constraint for ScalarTargets {
    fn name(&self) -> &str {
        self.name
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.targets.len()
    }
    fn arity(&self) -> usize {
        1
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        vars[0] = self.start + row;
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (row, &t) in self.targets.iter().enumerate() {
            res[row] = (x[self.start + row] - t) / self.unit;
            jac[row] = 1.0 / self.unit;
        }
    }
}
