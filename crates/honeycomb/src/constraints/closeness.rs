//! Closeness to the reference surface S (soft): `N* . (v - p*) = 0`, with `p*` the closest point
//! of S to the current vertex and `N*` the normal there, refreshed every iteration.
//! One row per vertex: the vertex may slide in the tangent plane, which is where a honeycomb's
//! freedom lies.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;
use crate::surface::Surface;

pub struct Closeness<'a> {
    pub layout: Layout,
    pub surface: &'a Surface,
    pub weight: f64,
    /// Per vertex: (closest point, unit normal) at the last refresh.
    foot: Vec<(Vec3, Vec3)>,
}

impl<'a> Closeness<'a> {
    pub fn new(layout: Layout, surface: &'a Surface, weight: f64) -> Self {
        Closeness {
            layout,
            surface,
            weight,
            foot: vec![(Vec3::ZERO, Vec3::ZERO); layout.num_vertices],
        }
    }
}

impl Constraint for Closeness<'_> {
    fn name(&self) -> &str {
        "closeness"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.layout.num_vertices
    }
    fn arity(&self) -> usize {
        3
    }
    fn row_variables(&self, v: usize, vars: &mut [usize]) {
        triple(vars, self.layout.vertex(v));
    }
    fn refresh(&mut self, x: &[f64]) {
        for (v, foot) in self.foot.iter_mut().enumerate() {
            let c = self.surface.closest_point(self.layout.vertex_at(x, v));
            *foot = (c.point, c.normal);
        }
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (v, &(p, n)) in self.foot.iter().enumerate() {
            res[v] = n.dot(self.layout.vertex_at(x, v) - p);
            put(&mut jac[3 * v..], n);
        }
    }
}
