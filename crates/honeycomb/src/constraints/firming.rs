//! Per-group factors that firm up a family's rows: each doubles at every refresh that finds its
//! group past a bound, up to a cap, and never shrinks. The factors only grow, so they settle
//! once every group is within its bound (or at the cap), and the solve with them; meanwhile
//! the fit turns towards the groups that stay past, as reweighted least squares does for a
//! maximum. [`Firmed`] is a family with its rows so firmed up.

use crate::solve::Constraint;

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

/// A family whose rows come in groups (a vertex's, a quad's) and that can tell which groups are
/// past a bound at an iterate.
pub(crate) trait Groups {
    fn rows_per_group(&self) -> usize;
    fn num_groups(&self) -> usize;
    /// Per group: whether it is past `bound` at `x` (after `refresh` at `x`).
    fn past(&self, x: &[f64], bound: f64) -> Vec<bool>;
}

/// The family `inner` with each group's rows scaled by a [`Firming`] factor that doubles at
/// every refresh that finds the group past `bound`.
pub struct Firmed<C> {
    inner: C,
    bound: f64,
    factor: Firming,
}

impl<C: Groups> Firmed<C> {
    pub fn new(inner: C, bound: f64) -> Self {
        let factor = Firming::new(inner.num_groups(), inner.rows_per_group());
        Firmed {
            inner,
            bound,
            factor,
        }
    }

    #[cfg(test)]
    pub fn factors(&self) -> &[f64] {
        self.factor.factors()
    }
}

impl<C: Constraint + Groups> Constraint for Firmed<C> {
    fn name(&self) -> &str {
        self.inner.name()
    }
    fn weight(&self) -> f64 {
        self.inner.weight()
    }
    fn num_rows(&self) -> usize {
        self.inner.num_rows()
    }
    fn arity(&self) -> usize {
        self.inner.arity()
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        self.inner.row_variables(row, vars)
    }
    fn refresh(&mut self, x: &[f64]) {
        self.inner.refresh(x);
        let past = self.inner.past(x, self.bound);
        self.factor.firm(|group| past[group]);
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        self.inner.evaluate(x, res, jac);
        self.factor.scale(self.inner.arity(), res, jac);
    }
}
