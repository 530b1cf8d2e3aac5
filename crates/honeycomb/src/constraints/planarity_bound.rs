//! Quad planarity that firms up, quad by quad, where a quad stays less planar than a bound: the
//! rows of [`QuadPlanarity`], each quad's scaled by a factor that doubles at every refresh that
//! finds its planarity (distance between its diagonals over its mean side) above `bound` and
//! never shrinks.
//!
//! A least-squares fit of every quad's planarity leaves the mean low and the worst quads where
//! they are; the floor asked of a cover is on the worst one. Firming up the quads above it
//! turns the fit towards its largest residuals, as reweighted least squares does for a
//! maximum.

use super::firming::{Firmed, Groups};
use super::quad_planarity::QuadPlanarity;
use crate::structure::quad_planarity;

/// Quad planarity at its weight for quads flatter than `bound` (`BoundedPlanarity::new(
/// planarity, bound)`), firming up past it.
pub type BoundedPlanarity = Firmed<QuadPlanarity>;

/// A quad's rows; past the bound where its diagonals are farther apart, over its mean side.
impl Groups for QuadPlanarity {
    fn rows_per_group(&self) -> usize {
        self.sides.len()
    }
    fn num_groups(&self) -> usize {
        self.quads.len()
    }
    fn past(&self, x: &[f64], bound: f64) -> Vec<bool> {
        (self.quads.iter())
            .map(|q| quad_planarity(q.map(|v| self.layout.vertex_at(x, v))) > bound)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::firming::MAX_FACTOR;
    use super::*;
    use crate::constraints::{Layout, QuadNormalBlock};
    use crate::geometry::Vec3;
    use crate::solve::Constraint;

    /// A quad bent past the bound weighs twice as much after each refresh, up to the cap; a
    /// planar one keeps its weight.
    #[test]
    fn a_quad_past_the_bound_firms_up_and_a_planar_one_does_not() {
        let corners = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.1),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
        ];
        let layout = Layout::new(corners.len(), 0);
        let block = QuadNormalBlock {
            start: 3 * corners.len(),
        };
        let planarity = QuadPlanarity {
            layout,
            block,
            quads: vec![[0, 1, 2, 3], [1, 4, 5, 2]],
            sides: vec![0, 1, 2, 3],
            weight: 1.0,
        };
        let mut c = BoundedPlanarity::new(planarity, 0.01);
        let mut x: Vec<f64> = corners.iter().flat_map(|p| p.to_array()).collect();
        x.extend([0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
        let rows = |c: &BoundedPlanarity| {
            let mut res = vec![0.0; 8];
            let mut jac = vec![0.0; 8 * 9];
            c.evaluate(&x, &mut res, &mut jac);
            (res, jac)
        };
        let (plain, plain_jac) = rows(&c);
        for refreshes in 1..=8 {
            c.refresh(&x);
            let (res, jac) = rows(&c);
            let factor = f64::powi(2.0, refreshes).min(MAX_FACTOR);
            // The first quad's third corner is 0.1 up: bent. The second has it too, on its
            // fourth corner, and is as bent; both firm up alike, row and Jacobian.
            for row in 0..8 {
                assert!(
                    (res[row] - factor * plain[row]).abs() < 1e-12,
                    "{refreshes}"
                );
                for a in 0..9 {
                    let (j, p) = (jac[row * 9 + a], plain_jac[row * 9 + a]);
                    assert!((j - factor * p).abs() < 1e-12);
                }
            }
        }
        // Flattened, a fresh family leaves both quads at weight one.
        x[8] = 0.0;
        let mut flat = BoundedPlanarity::new(
            QuadPlanarity {
                layout,
                block,
                quads: vec![[0, 1, 2, 3], [1, 4, 5, 2]],
                sides: vec![0, 1, 2, 3],
                weight: 1.0,
            },
            0.01,
        );
        flat.refresh(&x);
        let factors = flat.factors();
        assert!(factors.iter().all(|&f| f == 1.0), "{factors:?}");
    }
}
