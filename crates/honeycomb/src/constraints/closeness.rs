//! Closeness to the reference surface S (soft): `N* . (v - p*) = 0`, with `p*` the closest point
//! of S to the current vertex and `N*` the normal there, refreshed every iteration.
//! The vertex may slide in the tangent plane, which is where a honeycomb's freedom lies, but
//! not off S's edge: when `p*` is on S's boundary the vertex is beyond it, where the tangent
//! plane would let it hover at any distance (boundary vertices of a pipeline's honeycomb ended
//! half an edge off S). A second row per vertex, `o . (v - p*) = 0` with `o` the unit offset
//! across the tangent plane, pulls it back then; elsewhere that row is zero.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::parallel::in_halves;
use crate::solve::Constraint;
use crate::surface::{Surface, PARALLEL_QUERIES_FROM};
use std::ops::Deref;

/// `S` is how the family holds S: borrowed for one solve, shared (`Arc`) by a session that
/// owns its data.
pub struct Closeness<S> {
    pub layout: Layout,
    pub surface: S,
    pub weight: f64,
    /// Per vertex: closest point, unit normal and, beyond S's boundary, the unit outward
    /// offset in the tangent plane (else zero), at the last refresh.
    foot: Vec<(Vec3, Vec3, Vec3)>,
}

impl<S: Deref<Target = Surface>> Closeness<S> {
    pub fn new(layout: Layout, surface: S, weight: f64) -> Self {
        Closeness {
            layout,
            surface,
            weight,
            foot: vec![(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO); layout.num_vertices],
        }
    }
}

impl<S: Deref<Target = Surface> + Send + Sync> Constraint for Closeness<S> {
    fn name(&self) -> &str {
        "closeness"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        2 * self.layout.num_vertices
    }
    fn arity(&self) -> usize {
        3
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        triple(vars, self.layout.vertex(row / 2));
    }
    fn refresh(&mut self, x: &[f64]) {
        let (layout, surface) = (self.layout, &*self.surface);
        // Vertices `first..` of `feet`.
        let find = |first: usize, feet: &mut [(Vec3, Vec3, Vec3)]| {
            for (k, foot) in feet.iter_mut().enumerate() {
                let q = layout.vertex_at(x, first + k);
                let c = surface.closest_point(q);
                let d = q - c.point;
                let across = d - c.normal * c.normal.dot(d);
                let out = if c.on_boundary && across.norm() > 0.0 {
                    across.normalized()
                } else {
                    Vec3::ZERO
                };
                *foot = (c.point, c.normal, out);
            }
        };
        in_halves(&mut self.foot, PARALLEL_QUERIES_FROM, find);
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (v, &(p, n, out)) in self.foot.iter().enumerate() {
            let d = self.layout.vertex_at(x, v) - p;
            res[2 * v] = n.dot(d);
            res[2 * v + 1] = out.dot(d);
            put(&mut jac[6 * v..], n);
            put(&mut jac[6 * v + 3..], out);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::PolyMesh;

    /// Above S a vertex has only its distance to the tangent plane; beyond S's edge also its
    /// distance across it, to the boundary.
    #[test]
    fn beyond_the_boundary_the_second_row_pulls_back() {
        let surface = Surface::from_mesh(&PolyMesh::unit_square()).unwrap();
        let layout = Layout::new(2, 0);
        let mut c = Closeness::new(layout, &surface, 1.0);
        let points = [Vec3::new(0.5, 0.4, 0.1), Vec3::new(1.2, 0.5, 0.1)];
        let x: Vec<f64> = points.iter().flat_map(|p| p.to_array()).collect();
        c.refresh(&x);
        let mut res = vec![0.0; c.num_rows()];
        let mut jac = vec![0.0; c.num_rows() * c.arity()];
        c.evaluate(&x, &mut res, &mut jac);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        // Above: 0.1 off the plane, nothing across.
        assert!(close(res[0].abs(), 0.1) && res[1] == 0.0, "{res:?}");
        assert!(jac[3..6].iter().all(|&j| j == 0.0), "{jac:?}");
        // Beyond the edge x = 1: the foot (1, 0.5, 0) has the plane's normal, and the offset
        // 0.2 across the edge is the second row, along +x.
        assert!(close(res[2].abs(), 0.1) && close(res[3], 0.2), "{res:?}");
        assert!(close(jac[9], 1.0) && close(jac[10], 0.0) && close(jac[11], 0.0));
    }
}
