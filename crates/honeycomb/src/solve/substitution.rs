//! Solving in other unknowns: the families see `x = S y`, the solver works on `y`.
//!
//! Each unknown of `x` is a short signed sum of unknowns of `y` (a wall normal as the difference
//! of two cell points, a vertex as itself). The solver evaluates the families at `S y` and
//! assembles the normal equations for `y` with the chain rule `J_y = J_x S`; `S` never changes.

pub struct Substitution {
    y_len: usize,
    /// Terms of x unknown `i`: `terms[start[i]..start[i + 1]]`, each (y unknown, coefficient).
    start: Vec<usize>,
    terms: Vec<(usize, f64)>,
}

impl Substitution {
    /// `per_x[i]`: the terms of x unknown `i`, over `y_len` unknowns of y.
    pub fn new(y_len: usize, per_x: &[Vec<(usize, f64)>]) -> Substitution {
        let mut start = Vec::with_capacity(per_x.len() + 1);
        let mut terms = Vec::new();
        start.push(0);
        for t in per_x {
            debug_assert!(t.iter().all(|&(j, _)| j < y_len));
            terms.extend_from_slice(t);
            start.push(terms.len());
        }
        Substitution {
            y_len,
            start,
            terms,
        }
    }

    pub fn x_len(&self) -> usize {
        self.start.len() - 1
    }

    pub fn y_len(&self) -> usize {
        self.y_len
    }

    pub fn terms(&self, i: usize) -> &[(usize, f64)] {
        &self.terms[self.start[i]..self.start[i + 1]]
    }

    /// `x = S y`.
    pub fn apply(&self, y: &[f64], x: &mut [f64]) {
        for (i, xi) in x.iter_mut().enumerate() {
            *xi = self.terms(i).iter().map(|&(j, c)| c * y[j]).sum();
        }
    }
}
