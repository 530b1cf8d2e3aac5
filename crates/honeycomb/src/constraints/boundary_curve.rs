//! Boundary vertices stay on the boundary curve of S (soft): the vertex's offset from the
//! closest boundary point `p*` has no component across the tangent `t` there. Two rows per
//! vertex, `u_k . (v - p*) = 0` with `u_1, u_2` spanning the plane normal to `t`; refreshed
//! every iteration (tangent-line linearization).

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;
use crate::surface::Surface;
use std::ops::Deref;

/// `S` holds S as for [`super::Closeness`].
pub struct BoundaryCurve<S> {
    pub layout: Layout,
    pub surface: S,
    pub weight: f64,
    pub vertices: Vec<usize>,
    /// Per constrained vertex: (foot point, u_1, u_2).
    frames: Vec<(Vec3, Vec3, Vec3)>,
}

impl<S: Deref<Target = Surface>> BoundaryCurve<S> {
    pub fn new(layout: Layout, surface: S, weight: f64, vertices: Vec<usize>) -> Self {
        let frames = vec![(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO); vertices.len()];
        BoundaryCurve {
            layout,
            surface,
            weight,
            vertices,
            frames,
        }
    }
}

impl<S: Deref<Target = Surface> + Send + Sync> Constraint for BoundaryCurve<S> {
    fn name(&self) -> &str {
        "boundary_curve"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        2 * self.vertices.len()
    }
    fn arity(&self) -> usize {
        3
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        triple(vars, self.layout.vertex(self.vertices[row / 2]));
    }
    fn refresh(&mut self, x: &[f64]) {
        for (frame, &v) in self.frames.iter_mut().zip(&self.vertices) {
            let p = self.layout.vertex_at(x, v);
            // A surface with boundary-constrained vertices always has a boundary.
            if let Some(b) = self.surface.closest_boundary_point(p) {
                let u1 = b.tangent.any_orthogonal();
                *frame = (b.point, u1, b.tangent.cross(u1));
            }
        }
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (k, (&(p, u1, u2), &v)) in self.frames.iter().zip(&self.vertices).enumerate() {
            let d = self.layout.vertex_at(x, v) - p;
            res[2 * k] = u1.dot(d);
            res[2 * k + 1] = u2.dot(d);
            put(&mut jac[6 * k..], u1);
            put(&mut jac[6 * k + 3..], u2);
        }
    }
}
