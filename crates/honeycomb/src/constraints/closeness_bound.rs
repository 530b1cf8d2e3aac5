//! Closeness to S that is loose where a vertex is near S and firms up, vertex by vertex, where
//! one strays past a bound: the rows of [`Closeness`], each vertex's pair scaled by a factor that
//! doubles at every refresh that finds the vertex farther than `bound` and never shrinks.
//!
//! A solve that may take vertices off S up to a bound (capping by quads) then spends that bound
//! where it helps, instead of holding every vertex as firmly as the one that strays most. The
//! factors only grow, so they settle once every vertex is within the bound (or at the cap), and
//! the solve with them.

use super::closeness::Closeness;
use super::firming::{Firmed, Groups};
use crate::solve::Constraint;
use crate::surface::Surface;
use std::ops::Deref;

/// Closeness at its weight for vertices within `bound` of S (`BoundedCloseness::new(closeness,
/// bound)`), firming up past it.
pub type BoundedCloseness<S> = Firmed<Closeness<S>>;

/// A vertex's two rows; past the bound where their distance is.
impl<S: Deref<Target = Surface> + Send + Sync> Groups for Closeness<S> {
    fn rows_per_group(&self) -> usize {
        2
    }
    fn num_groups(&self) -> usize {
        self.layout.num_vertices
    }
    fn past(&self, x: &[f64], bound: f64) -> Vec<bool> {
        let rows = self.num_rows();
        let mut res = vec![0.0; rows];
        let mut jac = vec![0.0; rows * self.arity()];
        self.evaluate(x, &mut res, &mut jac);
        (0..self.num_groups())
            .map(|v| res[2 * v].hypot(res[2 * v + 1]) > bound)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::firming::MAX_FACTOR;
    use super::*;
    use crate::constraints::Layout;
    use crate::geometry::Vec3;
    use crate::mesh::PolyMesh;

    /// The scale of each vertex's distance row after `refreshes` refreshes at `points`.
    fn scales(points: &[Vec3], bound: f64, refreshes: usize) -> Vec<f64> {
        let surface = Surface::from_mesh(&PolyMesh::unit_square()).unwrap();
        let layout = Layout::new(points.len(), 0);
        let mut c = BoundedCloseness::new(Closeness::new(layout, &surface, 1.0), bound);
        let x: Vec<f64> = points.iter().flat_map(|p| p.to_array()).collect();
        for _ in 0..refreshes {
            c.refresh(&x);
        }
        let mut res = vec![0.0; c.num_rows()];
        let mut jac = vec![0.0; c.num_rows() * c.arity()];
        c.evaluate(&x, &mut res, &mut jac);
        (0..points.len())
            .map(|v| {
                let scale = (res[2 * v] / points[v].z).abs();
                // The Jacobian row is scaled alike: the plane's normal, times the scale.
                assert!((jac[6 * v + 2].abs() - scale).abs() < 1e-12, "{jac:?}");
                scale
            })
            .collect()
    }

    /// A vertex past the bound weighs twice as much after each refresh, up to the cap; one
    /// within it keeps plain closeness.
    #[test]
    fn a_vertex_past_the_bound_firms_up_and_one_within_does_not() {
        let points = [Vec3::new(0.5, 0.5, 0.1), Vec3::new(0.3, 0.6, 0.01)];
        let scale = |refreshes| scales(&points, 0.05, refreshes);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        let (one, three, many) = (scale(1), scale(3), scale(20));
        assert!(close(one[0], 2.0) && close(one[1], 1.0), "{one:?}");
        assert!(close(three[0], 8.0) && close(three[1], 1.0), "{three:?}");
        assert!(
            close(many[0], MAX_FACTOR) && close(many[1], 1.0),
            "{many:?}"
        );
    }
}
