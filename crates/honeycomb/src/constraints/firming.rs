//! Per-group factors that firm up a family's rows: each doubles at every refresh that finds its
//! group past a bound, up to a cap, and never shrinks. The factors only grow, so they settle
//! once every group is within its bound (or at the cap), and the solve with them; meanwhile
//! the fit turns towards the groups that stay past, as reweighted least squares does for a
//! maximum.

/// A group's factor grows to at most this: its rows then weigh as much as firm ones.
pub(crate) const MAX_FACTOR: f64 = 64.0;

pub(crate) struct Firming {
    rows_per_group: usize,
    /// Per group: the factor its rows are scaled by.
    factor: Vec<f64>,
}

impl Firming {
    pub fn new(groups: usize, rows_per_group: usize) -> Self {
        Firming {
            rows_per_group,
            factor: vec![1.0; groups],
        }
    }

    /// Doubles the factor of every group `past` says is past its bound.
    pub fn firm(&mut self, past: impl Fn(usize) -> bool) {
        for (group, f) in self.factor.iter_mut().enumerate() {
            if past(group) {
                *f = (*f * 2.0).min(MAX_FACTOR);
            }
        }
    }

    /// Scales each row of `res` and of `jac` (`arity` entries per row) by its group's factor.
    pub fn scale(&self, arity: usize, res: &mut [f64], jac: &mut [f64]) {
        for (row, r) in res.iter_mut().enumerate() {
            let f = self.factor[row / self.rows_per_group];
            *r *= f;
            jac[row * arity..(row + 1) * arity]
                .iter_mut()
                .for_each(|j| *j *= f);
        }
    }

    #[cfg(test)]
    pub fn factors(&self) -> &[f64] {
        &self.factor
    }
}
