//! Quad planarity that firms up, quad by quad, where a quad stays less planar than a bound: the
//! rows of [`QuadPlanarity`], each quad's scaled by a factor that doubles at every refresh that
//! finds its planarity (distance between its diagonals over its mean side) above `bound` and
//! never shrinks.
//!
//! A least-squares fit of every quad's planarity leaves the mean low and the worst quads where
//! they are; the floor asked of a cover is on the worst one. Firming up the quads above it
//! turns the fit towards its largest residuals, as reweighted least squares does for a
//! maximum.

use super::firming::Firming;
use super::quad_planarity::QuadPlanarity;
use crate::solve::Constraint;
use crate::structure::quad_planarity;

pub struct BoundedPlanarity {
    planarity: QuadPlanarity,
    /// Planarity past which a quad's factor doubles.
    pub bound: f64,
    /// Per quad: the factor its rows are scaled by.
    factor: Firming,
}

impl BoundedPlanarity {
    pub fn new(planarity: QuadPlanarity, bound: f64) -> Self {
        let factor = Firming::new(planarity.quads.len(), planarity.sides.len());
        BoundedPlanarity {
            planarity,
            bound,
            factor,
        }
    }
}

impl Constraint for BoundedPlanarity {
    fn name(&self) -> &str {
        self.planarity.name()
    }
    fn weight(&self) -> f64 {
        self.planarity.weight
    }
    fn num_rows(&self) -> usize {
        self.planarity.num_rows()
    }
    fn arity(&self) -> usize {
        self.planarity.arity()
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        self.planarity.row_variables(row, vars)
    }
    fn refresh(&mut self, x: &[f64]) {
        let (layout, quads, bound) = (self.planarity.layout, &self.planarity.quads, self.bound);
        self.factor
            .firm(|q| quad_planarity(quads[q].map(|v| layout.vertex_at(x, v))) > bound);
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        self.planarity.evaluate(x, res, jac);
        self.factor.scale(self.planarity.arity(), res, jac);
    }
}

#[cfg(test)]
mod tests {
    use super::super::firming::MAX_FACTOR;
    use super::*;
    use crate::constraints::{Layout, QuadNormalBlock};
    use crate::geometry::Vec3;

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
        let factors = flat.factor.factors();
        assert!(factors.iter().all(|&f| f == 1.0), "{factors:?}");
    }
}
