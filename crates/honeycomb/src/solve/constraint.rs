//! The contract between a constraint family and the solver.
//!
//! A family is a block of scalar residual rows `phi_r(x) = 0`. Every row of a family touches the
//! same number of variables (its arity), and which variables it touches never changes during a
//! solve: that is what lets the solver fix the sparsity pattern and the symbolic Cholesky
//! factorization once. The solver knows nothing else about a family.

/// How the solver treats a family's weight over the iterations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// A condition the result must satisfy (possibly soft, at a lower weight).
    Condition,
    /// A fairness term: part of the regularization, so its weight fades with it.
    Fairness,
    /// A guide for the first iterations: its weight fades by a fixed factor per iteration.
    Guide,
}

/// A guide's weight is multiplied by this after every iteration, unless it says otherwise.
pub const GUIDE_FADE: f64 = 0.3;

pub trait Constraint: Send + Sync {
    /// Short name for reports, e.g. "node_120".
    fn name(&self) -> &str;
    fn weight(&self) -> f64;
    fn role(&self) -> Role {
        Role::Condition
    }
    /// With `Role::Guide`: the factor its weight is multiplied by after every iteration.
    fn guide_fade(&self) -> f64 {
        GUIDE_FADE
    }
    fn num_rows(&self) -> usize;
    /// Number of variables each row touches.
    fn arity(&self) -> usize;
    /// Writes the `arity()` variable indices of `row` into `vars` (distinct within a row).
    fn row_variables(&self, row: usize, vars: &mut [usize]);
    /// Residuals `phi(x)` (length `num_rows`) and Jacobian entries (length
    /// `num_rows * arity`, row-major, in `row_variables` order).
    fn evaluate(&self, x: &[f64], residuals: &mut [f64], jacobian: &mut [f64]);
    /// Called at the start of every iteration: recompute linearization data that depends on the
    /// iterate (closest points, tangent planes).
    fn refresh(&mut self, _x: &[f64]) {}
}

#[cfg(test)]
/// Checks a family's Jacobian against central finite differences at `x`; returns the largest
/// absolute deviation, relative to max(1, |entry|).
pub fn jacobian_fd_error(c: &dyn Constraint, x: &[f64], h: f64) -> f64 {
    let (rows, k) = (c.num_rows(), c.arity());
    let mut res = vec![0.0; rows];
    let mut jac = vec![0.0; rows * k];
    c.evaluate(x, &mut res, &mut jac);
    let mut vars = vec![0; k];
    let (mut rp, mut rm) = (vec![0.0; rows], vec![0.0; rows]);
    let mut scratch = vec![0.0; rows * k];
    let mut xp = x.to_vec();
    let mut worst = 0.0f64;
    for row in 0..rows {
        c.row_variables(row, &mut vars);
        for (a, &var) in vars.iter().enumerate() {
            xp[var] = x[var] + h;
            c.evaluate(&xp, &mut rp, &mut scratch);
            xp[var] = x[var] - h;
            c.evaluate(&xp, &mut rm, &mut scratch);
            xp[var] = x[var];
            let fd = (rp[row] - rm[row]) / (2.0 * h);
            let exact = jac[row * k + a];
            worst = worst.max((fd - exact).abs() / exact.abs().max(1.0));
        }
    }
    worst
}
