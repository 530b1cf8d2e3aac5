//! The normal equations `(J^T W J + eps I) dx = -J^T W phi`, assembled straight into a fixed
//! upper-triangular CSC pattern.
//!
//! The pattern and a scatter map (for every row, the value slot of every pair of its variables)
//! are computed once; each iteration only multiplies and adds into the existing value array.
//! With a [`Substitution`] the rows are rewritten over the solver's unknowns once: each row's
//! variables become the union of their terms, and each Jacobian entry is spread over those.

use super::columns::Columns;
use super::constraint::Constraint;
use super::lists::Lists;
use super::substitution::Substitution;

/// One family's rows over the solver's unknowns.
struct MappedRows {
    /// The family's arity (Jacobian entries per row).
    arity: usize,
    /// Row r's unknowns: `vars[var_start[r]..var_start[r + 1]]`.
    var_start: Vec<usize>,
    vars: Vec<usize>,
    /// Jacobian entry (r, a) adds `c * J[r][a]` to the row's unknown at position p, for each
    /// (p, c) in `spread[spread_start[r * arity + a]..spread_start[r * arity + a + 1]]`.
    spread_start: Vec<usize>,
    spread: Vec<(u32, f64)>,
    /// Row r's value slots, one per pair (p <= q) of its unknowns, from `slot_start[r]`.
    slot_start: Vec<usize>,
    slots: Vec<u32>,
}

impl MappedRows {
    fn new(c: &dyn Constraint, subst: Option<&Substitution>) -> MappedRows {
        MappedRows::spread(c.num_rows(), c.arity(), |r, v| c.row_variables(r, v), subst)
    }

    /// The rows `x_i`, one per unknown of x, over y: the sum of their squares is `|S y|^2`,
    /// the measure of a step.
    fn of_substitution(s: &Substitution) -> MappedRows {
        MappedRows::spread(s.x_len(), 1, |r, v| v[0] = r, Some(s))
    }

    /// `rows` rows of `arity` unknowns of x each (`row_variables`), spread over y by `subst`.
    fn spread(
        rows: usize,
        arity: usize,
        row_variables: impl Fn(usize, &mut [usize]),
        subst: Option<&Substitution>,
    ) -> MappedRows {
        let k = arity;
        let mut x_vars = vec![0usize; k];
        let mut var_start = Vec::with_capacity(rows + 1);
        let mut vars = Vec::with_capacity(rows * k);
        let mut spread_start = Vec::with_capacity(rows * k + 1);
        let mut spread = Vec::with_capacity(rows * k);
        var_start.push(0);
        spread_start.push(0);
        for row in 0..rows {
            row_variables(row, &mut x_vars);
            let first = vars.len();
            for &xv in &x_vars {
                let identity = [(xv, 1.0)];
                let terms = subst.map_or(&identity[..], |s| s.terms(xv));
                for &(yv, coef) in terms {
                    let p = match vars[first..].iter().position(|&v| v == yv) {
                        Some(p) => p,
                        None => {
                            vars.push(yv);
                            vars.len() - first - 1
                        }
                    };
                    spread.push((p as u32, coef));
                }
                spread_start.push(spread.len());
            }
            var_start.push(vars.len());
        }
        MappedRows {
            arity: k,
            var_start,
            vars,
            spread_start,
            spread,
            slot_start: Vec::new(),
            slots: Vec::new(),
        }
    }

    /// Adds `w2 J^T J` of these rows to `values` and, given `(rhs, phi)`, `-w2 J^T phi` to
    /// `rhs`; `J` is the rows' Jacobian over x (`jacobian`, row-major) spread over y.
    fn accumulate(
        &self,
        w2: f64,
        jacobian: &[f64],
        values: &mut [f64],
        mut rhs: Option<(&mut [f64], &[f64])>,
        scratch: &mut [f64],
    ) {
        let k = self.arity;
        for (r, jx) in jacobian.chunks_exact(k).enumerate() {
            let vars = self.row(r);
            let j = &mut scratch[..vars.len()];
            j.fill(0.0);
            for (a, &ja) in jx.iter().enumerate() {
                let i = r * k + a;
                for &(p, c) in &self.spread[self.spread_start[i]..self.spread_start[i + 1]] {
                    j[p as usize] += c * ja;
                }
            }
            let slots = &self.slots[self.slot_start[r]..self.slot_start[r + 1]];
            let mut s = 0;
            for a in 0..j.len() {
                let ja = w2 * j[a];
                if let Some((rhs, phi)) = &mut rhs {
                    rhs[vars[a]] -= ja * phi[r];
                }
                for jb in &j[a..] {
                    values[slots[s] as usize] += ja * jb;
                    s += 1;
                }
            }
        }
    }

    fn row(&self, r: usize) -> &[usize] {
        &self.vars[self.var_start[r]..self.var_start[r + 1]]
    }

    fn rows(&self) -> usize {
        self.var_start.len() - 1
    }
}

pub struct NormalMatrix {
    pub n: usize,
    /// Upper triangle, column-compressed: rows of column j are `row_idx[col_ptr[j]..col_ptr[j+1]]`.
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    pub values: Vec<f64>,
    diagonal: Vec<usize>,
    families: Vec<MappedRows>,
    /// With a substitution: the rows `x_i` over y and their unit Jacobian, so that the
    /// regularization measures a step by how far it moves x (`eps |S dy|^2`), not y.
    metric: Option<(MappedRows, Vec<f64>)>,
    /// The longest row (scratch for the chain rule).
    scratch: Vec<f64>,
}

impl NormalMatrix {
    /// The pattern over `n` unknowns; with `subst`, `n` unknowns of y and families over `S y`.
    pub fn new(
        n: usize,
        families: &[Box<dyn Constraint + '_>],
        subst: Option<&Substitution>,
    ) -> NormalMatrix {
        // The families' rows, then (with a substitution) the step measure's.
        let mut mapped: Vec<MappedRows> = families
            .iter()
            .map(|c| MappedRows::new(c.as_ref(), subst))
            .chain(subst.map(MappedRows::of_substitution))
            .collect();
        let (col_ptr, row_idx) = pattern(n, &mut mapped);
        let diagonal = (1..=n).map(|j| col_ptr[j] - 1).collect();
        let longest = mapped
            .iter()
            .flat_map(|m| (0..m.rows()).map(|r| m.row(r).len()))
            .max()
            .unwrap_or(0);
        let metric = subst.and_then(|s| Some((mapped.pop()?, vec![1.0; s.x_len()])));
        let nnz = row_idx.len();
        NormalMatrix {
            n,
            col_ptr,
            row_idx,
            values: vec![0.0; nnz],
            diagonal,
            families: mapped,
            metric,
            scratch: vec![0.0; longest],
        }
    }

    /// A matrix of no families on an upper-triangular pattern (column-compressed, sorted rows,
    /// the diagonal last in every column), its values zero: filled by its owner.
    pub(super) fn with_pattern(n: usize, col_ptr: Vec<usize>, row_idx: Vec<usize>) -> NormalMatrix {
        NormalMatrix {
            n,
            diagonal: (0..n).map(|j| col_ptr[j + 1] - 1).collect(),
            values: vec![0.0; row_idx.len()],
            col_ptr,
            row_idx,
            families: Vec::new(),
            metric: None,
            scratch: Vec::new(),
        }
    }

    /// The value slot of entry (r, c) or (c, r), if it is in the pattern.
    pub(super) fn slot(&self, r: usize, c: usize) -> Option<usize> {
        find_slot(&self.col_ptr, &self.row_idx, r, c)
    }

    /// A matrix given by its upper triangle (column-compressed, sorted rows, the diagonal
    /// present), for testing the factorizations on small systems.
    #[cfg(test)]
    pub(super) fn from_upper(n: usize, columns: &[&[(usize, f64)]]) -> NormalMatrix {
        let mut col_ptr = vec![0];
        let (mut row_idx, mut values) = (Vec::new(), Vec::new());
        for column in columns {
            row_idx.extend(column.iter().map(|e| e.0));
            values.extend(column.iter().map(|e| e.1));
            col_ptr.push(row_idx.len());
        }
        let mut m = NormalMatrix::with_pattern(n, col_ptr, row_idx);
        m.values = values;
        m
    }

    /// The largest entry of `A x - b` (A symmetric, from its upper triangle), for checking
    /// solves in tests.
    #[cfg(test)]
    pub(super) fn residual(&self, x: &[f64], b: &[f64]) -> f64 {
        let mut y = vec![0.0; self.n];
        for j in 0..self.n {
            for k in self.col_ptr[j]..self.col_ptr[j + 1] {
                let i = self.row_idx[k];
                y[i] += self.values[k] * x[j];
                if i != j {
                    y[j] += self.values[k] * x[i];
                }
            }
        }
        y.iter()
            .zip(b)
            .fold(0.0f64, |m, (y, b)| m.max((y - b).abs()))
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Zeroes the matrix and the right-hand side.
    pub fn clear(&mut self, rhs: &mut [f64]) {
        self.values.fill(0.0);
        rhs.fill(0.0);
    }

    /// Adds family `f`'s weighted rows: `w^2 J^T J` to the matrix, `-w^2 J^T phi` to `rhs`
    /// (`J` over the solver's unknowns: the family's Jacobian spread by the substitution).
    pub fn add_family(
        &mut self,
        f: usize,
        weight: f64,
        residuals: &[f64],
        jacobian: &[f64],
        rhs: &mut [f64],
    ) {
        self.families[f].accumulate(
            weight * weight,
            jacobian,
            &mut self.values,
            Some((rhs, residuals)),
            &mut self.scratch,
        );
    }

    /// `eps I`, or with a substitution `eps (S^T S + 1e-6 I)` (the small identity holds the
    /// directions S does not see, such as moving all cell points together).
    pub fn add_diagonal(&mut self, eps: f64) {
        let identity = match &self.metric {
            Some((rows, unit)) => {
                rows.accumulate(eps, unit, &mut self.values, None, &mut self.scratch);
                1e-6 * eps
            }
            None => eps,
        };
        for &d in &self.diagonal {
            self.values[d] += identity;
        }
    }
}

/// The upper-triangular pattern, column-compressed with sorted rows (the diagonal last), of
/// the diagonal and every pair of unknowns that share a row; fills in every row's value slots.
///
/// Column by column (see `Columns`): the rows that hold the column's unknown are visited, so
/// no pair is searched for.
fn pattern(n: usize, mapped: &mut [MappedRows]) -> (Vec<usize>, Vec<usize>) {
    // Every row of every family, and where each unknown occurs: (row, position in it).
    let rows: Vec<(u32, u32)> = (0..mapped.len())
        .flat_map(|f| (0..mapped[f].rows()).map(move |r| (f as u32, r as u32)))
        .collect();
    assert!(rows.len() < u32::MAX as usize, "too many rows");
    let occurrences = Lists::build(n, |visit| {
        for (g, &(f, r)) in rows.iter().enumerate() {
            for (p, &v) in mapped[f as usize].row(r as usize).iter().enumerate() {
                visit(v, (g as u32, p as u32));
            }
        }
    });
    for m in mapped.iter_mut() {
        let mut slot_start = Vec::with_capacity(m.rows() + 1);
        slot_start.push(0);
        for r in 0..m.rows() {
            let k = m.row(r).len();
            slot_start.push(slot_start[r] + k * (k + 1) / 2);
        }
        m.slots = vec![0; slot_start[m.rows()]];
        m.slot_start = slot_start;
    }
    let mut columns = Columns::new(n);
    for b in 0..n {
        for &(g, pb) in occurrences.get(b) {
            let (f, r) = rows[g as usize];
            let m = &mut mapped[f as usize];
            let (r, pb) = (r as usize, pb as usize);
            let vars = &m.vars[m.var_start[r]..m.var_start[r + 1]];
            let first = m.slot_start[r];
            for (pa, &a) in vars.iter().enumerate().filter(|&(_, &a)| a <= b) {
                m.slots[first + pair_index(pa.min(pb), pa.max(pb), vars.len())] =
                    columns.entry(a) as u32;
            }
        }
        columns.entry(b);
        assert!(
            columns.nnz() < u32::MAX as usize,
            "normal matrix too large for 32-bit slots"
        );
        columns.finish_column();
    }
    let pattern = columns.finish();
    for m in mapped.iter_mut() {
        for s in &mut m.slots {
            *s = pattern.slot(*s as usize) as u32;
        }
    }
    (pattern.col_ptr, pattern.row_idx)
}

/// The place of pair (p, q), p <= q, among the pairs of a row of `k` unknowns listed as
/// (0, 0), (0, 1), .., (0, k - 1), (1, 1), ..
fn pair_index(p: usize, q: usize, k: usize) -> usize {
    p * k - p * (p + 1) / 2 + q
}

/// The slot of entry (r, c) or (c, r) in an upper-triangular pattern with sorted columns.
fn find_slot(col_ptr: &[usize], row_idx: &[usize], r: usize, c: usize) -> Option<usize> {
    let (r, c) = (r.min(c), r.max(c));
    let range = col_ptr[c]..col_ptr[c + 1];
    let pos = row_idx[range.clone()].binary_search(&r).ok()?;
    Some(range.start + pos)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows `x_a * x_b - 1` over pairs of four unknowns.
    struct Products;

    impl Constraint for Products {
        fn name(&self) -> &str {
            "products"
        }
        fn weight(&self) -> f64 {
            1.5
        }
        fn num_rows(&self) -> usize {
            3
        }
        fn arity(&self) -> usize {
            2
        }
        fn row_variables(&self, row: usize, vars: &mut [usize]) {
            vars.copy_from_slice(&[[0, 1], [1, 2], [2, 3]][row]);
        }
        fn evaluate(&self, x: &[f64], residuals: &mut [f64], jacobian: &mut [f64]) {
            for row in 0..3 {
                let (a, b) = (row, row + 1);
                residuals[row] = x[a] * x[b] - 1.0;
                jacobian[2 * row] = x[b];
                jacobian[2 * row + 1] = x[a];
            }
        }
    }

    /// Assembled over y with `x = S y`, the matrix is `w^2 S^T J^T J S + eps S^T S (+ 1e-6 eps
    /// I)` and the right-hand side `-w^2 S^T J^T phi`: compared with dense products.
    #[test]
    fn a_substitution_assembles_the_chain_rule() {
        // x0 = y0, x1 = y1 - y2, x2 = y2 + 2 y0, x3 = y3.
        let per_x = vec![
            vec![(0, 1.0)],
            vec![(1, 1.0), (2, -1.0)],
            vec![(2, 1.0), (0, 2.0)],
            vec![(3, 1.0)],
        ];
        let s = Substitution::new(4, &per_x);
        let y = [0.3, 1.2, -0.4, 0.9];
        let mut x = [0.0; 4];
        s.apply(&y, &mut x);
        assert_eq!(x, [0.3, 1.6, -0.4 + 0.6, 0.9]);
        let families: Vec<Box<dyn Constraint>> = vec![Box::new(Products)];
        let mut m = NormalMatrix::new(4, &families, Some(&s));
        let (mut phi, mut jac) = ([0.0; 3], [0.0; 6]);
        Products.evaluate(&x, &mut phi, &mut jac);
        let mut rhs = [0.0; 4];
        m.clear(&mut rhs);
        m.add_family(0, 1.5, &phi, &jac, &mut rhs);
        let eps = 0.01;
        m.add_diagonal(eps);
        // Dense reference.
        let mut jx = [[0.0; 4]; 3];
        for row in 0..3 {
            jx[row][row] = jac[2 * row];
            jx[row][row + 1] = jac[2 * row + 1];
        }
        let mut sm = [[0.0; 4]; 4];
        for (i, t) in per_x.iter().enumerate() {
            for &(j, c) in t {
                sm[i][j] = c;
            }
        }
        let jy: Vec<[f64; 4]> = jx
            .iter()
            .map(|r| std::array::from_fn(|j| (0..4).map(|i| r[i] * sm[i][j]).sum()))
            .collect();
        for a in 0..4 {
            let expected_rhs: f64 = (0..3).map(|r| -2.25 * jy[r][a] * phi[r]).sum();
            assert!((rhs[a] - expected_rhs).abs() < 1e-12, "rhs {a}");
            for b in a..4 {
                let jtj: f64 = (0..3).map(|r| 2.25 * jy[r][a] * jy[r][b]).sum();
                let sts: f64 = (0..4).map(|i| sm[i][a] * sm[i][b]).sum();
                let expected = jtj + eps * sts + if a == b { 1e-6 * eps } else { 0.0 };
                let range = m.col_ptr[b]..m.col_ptr[b + 1];
                let got = m.row_idx[range.clone()]
                    .iter()
                    .position(|&r| r == a)
                    .map_or(0.0, |p| m.values[range.start + p]);
                assert!(
                    (got - expected).abs() < 1e-12,
                    "entry ({a}, {b}): {got} vs {expected}"
                );
            }
        }
    }

    /// Rows over listed unknowns (any order), each residual 0 and every Jacobian entry 1.
    struct Listed(Vec<Vec<usize>>);

    impl Constraint for Listed {
        fn name(&self) -> &str {
            "listed"
        }
        fn weight(&self) -> f64 {
            1.0
        }
        fn num_rows(&self) -> usize {
            self.0.len()
        }
        fn arity(&self) -> usize {
            self.0[0].len()
        }
        fn row_variables(&self, row: usize, vars: &mut [usize]) {
            vars.copy_from_slice(&self.0[row]);
        }
        fn evaluate(&self, _x: &[f64], residuals: &mut [f64], jacobian: &mut [f64]) {
            residuals.fill(0.0);
            jacobian.fill(1.0);
        }
    }

    /// The pattern holds exactly the diagonal and the pairs that share a row, each column
    /// sorted with the diagonal last, and every row adds into the slots of its own pairs: with
    /// unit Jacobians entry (a, b) counts the rows that hold both.
    #[test]
    fn the_pattern_has_every_shared_pair_once_and_rows_find_their_slots() {
        let n = 9;
        let lists = [
            vec![vec![4, 1, 7], vec![0, 8, 2], vec![7, 4, 3], vec![2, 0, 8]],
            vec![vec![5, 1], vec![1, 5], vec![6, 0]],
        ];
        let families: Vec<Box<dyn Constraint>> = lists
            .iter()
            .map(|rows| Box::new(Listed(rows.clone())) as Box<dyn Constraint>)
            .collect();
        // count[b][a]: the rows holding both a and b (a <= b).
        let mut count = vec![vec![0.0; n]; n];
        for row in lists.iter().flatten() {
            for (p, &a) in row.iter().enumerate() {
                for &b in &row[p..] {
                    count[a.max(b)][a.min(b)] += 1.0;
                }
            }
        }
        let mut m = NormalMatrix::new(n, &families, None);
        let mut rhs = vec![0.0; n];
        m.clear(&mut rhs);
        for (f, c) in families.iter().enumerate() {
            let mut phi = vec![0.0; c.num_rows()];
            let mut jac = vec![0.0; c.num_rows() * c.arity()];
            c.evaluate(&[], &mut phi, &mut jac);
            m.add_family(f, 1.0, &phi, &jac, &mut rhs);
        }
        for (b, counts) in count.iter().enumerate() {
            let column = &m.row_idx[m.col_ptr[b]..m.col_ptr[b + 1]];
            let expected: Vec<usize> = (0..b).filter(|&a| counts[a] > 0.0).chain([b]).collect();
            assert_eq!(
                column,
                &expected[..],
                "column {b}: sorted, the diagonal last"
            );
            for (k, &a) in column.iter().enumerate() {
                let value = m.values[m.col_ptr[b] + k];
                assert_eq!(value, counts[a], "entry ({a}, {b})");
            }
        }
    }
}
