//! Static condensation: blocks of three unknowns that no entry of the matrix couples to one
//! another are eliminated exactly, each by its own 3 x 3 Cholesky factor, and the sparse
//! factorization sees only the rest (the Schur complement).
//!
//! With `A = [A_ee A_eN; A_Ne A_NN]` for one eliminated block e and its neighbours N,
//! `A_ee = L L^T` and `W = L^-1 A_eN`, the rest's matrix is `A_NN - W^T W`, its right-hand side
//! `b_N - W^T z` with `z = L^-1 b_e`, and afterwards `x_e = L^-T (z - W x_N)`. Blocks whose rows
//! touch one block each (a vertex on its own wall planes, closeness and boundary rows) are
//! such blocks; on a honeycomb they are half of all unknowns, and the factorization of the
//! rest has half the operations of the whole.

use super::cholesky::{Cholesky, NotPositive};
use super::columns::Columns;
use super::lists::Lists;
use super::normal_matrix::NormalMatrix;

const B: usize = 3;

pub struct Condensation {
    /// The rest's matrix: its pattern once, its values at every `condense`.
    pub matrix: NormalMatrix,
    /// Unknown of the rest → unknown of the whole system.
    kept: Vec<usize>,
    /// (whole matrix's slot, rest's slot) of the entries between two kept unknowns.
    copies: Vec<(usize, usize)>,
    blocks: Vec<Eliminated>,
    /// `W` of every eliminated block (3 rows, a column per neighbour), row-major, and `L`
    /// (lower, packed: l00 l10 l11 l20 l21 l22).
    w: Vec<f64>,
    l: Vec<[f64; 6]>,
    /// The rest's right-hand side and `z` per block (solve scratch).
    rest: Vec<f64>,
    z: Vec<[f64; 3]>,
}

/// One eliminated block and where its entries live.
struct Eliminated {
    /// Its first unknown in the whole system.
    first: usize,
    /// Its neighbours among the kept unknowns (indices of the rest).
    neighbours: Vec<usize>,
    /// Slots in the whole matrix of `A_ee` (upper, packed by columns: 00 01 11 02 12 22) and of
    /// `A_eN` (row by row); `None` for an entry outside the pattern, which is zero.
    own: [Option<usize>; 6],
    coupling: Vec<Option<usize>>,
    /// The rest's slot of every neighbour pair (a <= b), column by column.
    pairs: Vec<usize>,
    /// Where its `W` starts in `Condensation::w`.
    w_start: usize,
}

impl Condensation {
    /// Eliminates the `candidates` (blocks of three unknowns) that no earlier accepted
    /// candidate is coupled to; `None` if none is accepted.
    pub fn analyse(m: &NormalMatrix, candidates: &[usize]) -> Option<Condensation> {
        let mut candidate = vec![false; m.n.div_ceil(B)];
        for &b in candidates.iter().filter(|&&b| B * b + B <= m.n) {
            candidate[b] = true;
        }
        // Every candidate unknown's neighbours in the whole matrix (both triangles), with the
        // slot of their entry.
        let adjacent = Lists::build(m.n, |visit| {
            for j in 0..m.n {
                for s in m.col_ptr[j]..m.col_ptr[j + 1] {
                    let i = m.row_idx[s];
                    if i != j && candidate[i / B] {
                        visit(i, (j, s));
                    }
                    if i != j && candidate[j / B] {
                        visit(j, (i, s));
                    }
                }
            }
        });
        let mut eliminated = vec![false; m.n.div_ceil(B)];
        for &b in candidates
            .iter()
            .filter(|&&b| candidate.get(b) == Some(&true))
        {
            let coupled = (B * b..B * b + B)
                .flat_map(|i| adjacent.get(i))
                .any(|&(k, _)| k / B != b && eliminated[k / B]);
            eliminated[b] = !coupled;
        }
        let kept: Vec<usize> = (0..m.n).filter(|&i| !eliminated[i / B]).collect();
        if kept.len() == m.n {
            return None;
        }
        let mut index = vec![usize::MAX; m.n];
        for (r, &i) in kept.iter().enumerate() {
            index[i] = r;
        }
        // Each eliminated block: its neighbours (indices of the rest, sorted) and the slots
        // of its entries in the whole matrix, from its unknowns' lists of neighbours.
        let mut blocks = Vec::new();
        let mut w_len = 0;
        for b in (0..m.n / B).filter(|&b| eliminated[b]) {
            let first = B * b;
            let mut neighbours: Vec<usize> = (first..first + B)
                .flat_map(|i| adjacent.get(i).iter().map(|&(k, _)| index[k]))
                .filter(|&r| r != usize::MAX)
                .collect();
            neighbours.sort_unstable();
            neighbours.dedup();
            let n = neighbours.len();
            let mut own = [None; 6];
            let mut coupling = vec![None; B * n];
            for c in 0..B {
                own[packed(c, c)] = m.slot(first + c, first + c);
                for &(k, s) in adjacent.get(first + c) {
                    if k / B == b {
                        own[packed(c.min(k - first), c.max(k - first))] = Some(s);
                    } else if let Ok(p) = neighbours.binary_search(&index[k]) {
                        coupling[c * n + p] = Some(s);
                    }
                }
            }
            blocks.push(Eliminated {
                first,
                neighbours,
                own,
                coupling,
                pairs: vec![0; n * (n + 1) / 2],
                w_start: w_len,
            });
            w_len += B * n;
        }
        // The rest's pattern (upper), column by column (see `Columns`): a kept column's
        // entries between kept unknowns (the numbering keeps their order), copied from the
        // whole matrix, and every pair of neighbours of each block at it.
        let at = Lists::build(kept.len(), |visit| {
            for (k, e) in blocks.iter().enumerate() {
                for (p, &r) in e.neighbours.iter().enumerate() {
                    visit(r, (k, p));
                }
            }
        });
        let mut columns = Columns::new(kept.len());
        let mut copies = Vec::new();
        for (r, &j) in kept.iter().enumerate() {
            for s in m.col_ptr[j]..m.col_ptr[j + 1] {
                let a = index[m.row_idx[s]];
                if a != usize::MAX {
                    copies.push((s, columns.entry(a)));
                }
            }
            for &(k, pb) in at.get(r) {
                let e = &mut blocks[k];
                for pa in 0..=pb {
                    e.pairs[packed(pa, pb)] = columns.entry(e.neighbours[pa]);
                }
            }
            columns.finish_column();
        }
        let pattern = columns.finish();
        for copy in &mut copies {
            copy.1 = pattern.slot(copy.1);
        }
        for e in &mut blocks {
            for s in &mut e.pairs {
                *s = pattern.slot(*s);
            }
        }
        let matrix = NormalMatrix::with_pattern(kept.len(), pattern.col_ptr, pattern.row_idx);
        Some(Condensation {
            rest: vec![0.0; kept.len()],
            kept,
            copies,
            w: vec![0.0; w_len],
            l: vec![[0.0; 6]; blocks.len()],
            z: vec![[0.0; 3]; blocks.len()],
            blocks,
            matrix,
        })
    }

    /// The unknowns of the rest, in the whole system's numbering.
    pub fn kept(&self) -> &[usize] {
        &self.kept
    }

    /// Factors the whole matrix's current values: condenses them into the rest and factors
    /// that in `cholesky`. A pivot that is not positive is named in the whole system.
    pub fn factorize(
        &mut self,
        whole: &NormalMatrix,
        cholesky: &mut Cholesky,
    ) -> Result<(), NotPositive> {
        self.condense(whole)?;
        cholesky
            .factorize(&self.matrix)
            .map_err(|NotPositive(r)| NotPositive(self.kept[r]))
    }

    /// The rest's matrix for the whole matrix's current values.
    fn condense(&mut self, whole: &NormalMatrix) -> Result<(), NotPositive> {
        let values = &mut self.matrix.values;
        values.fill(0.0);
        for &(from, to) in &self.copies {
            values[to] = whole.values[from];
        }
        for (k, e) in self.blocks.iter().enumerate() {
            let value = |s: Option<usize>| s.map_or(0.0, |s| whole.values[s]);
            let a = e.own.map(value);
            let l = cholesky3(&a).map_err(|c| NotPositive(e.first + c))?;
            self.l[k] = l;
            let n = e.neighbours.len();
            let w = &mut self.w[e.w_start..e.w_start + B * n];
            for p in 0..n {
                let column = [0, 1, 2].map(|c| value(e.coupling[c * n + p]));
                let solved = forward(&l, column);
                for c in 0..B {
                    w[c * n + p] = solved[c];
                }
            }
            let mut s = 0;
            for b in 0..n {
                for a in 0..=b {
                    let dot = w[a] * w[b] + w[n + a] * w[n + b] + w[2 * n + a] * w[2 * n + b];
                    values[e.pairs[s]] -= dot;
                    s += 1;
                }
            }
        }
        Ok(())
    }

    /// Solves `A x = b` in place (b and x over the whole system) with the rest factored in
    /// `cholesky`.
    pub fn solve_in_place(&mut self, cholesky: &mut Cholesky, b: &mut [f64]) {
        for (r, &i) in self.kept.iter().enumerate() {
            self.rest[r] = b[i];
        }
        for (k, e) in self.blocks.iter().enumerate() {
            let z = forward(&self.l[k], [0, 1, 2].map(|c| b[e.first + c]));
            self.z[k] = z;
            let n = e.neighbours.len();
            let w = &self.w[e.w_start..e.w_start + B * n];
            for (p, &r) in e.neighbours.iter().enumerate() {
                self.rest[r] -= w[p] * z[0] + w[n + p] * z[1] + w[2 * n + p] * z[2];
            }
        }
        cholesky.solve_in_place(&mut self.rest);
        for (r, &i) in self.kept.iter().enumerate() {
            b[i] = self.rest[r];
        }
        for (k, e) in self.blocks.iter().enumerate() {
            let n = e.neighbours.len();
            let w = &self.w[e.w_start..e.w_start + B * n];
            let mut t = self.z[k];
            for (p, &r) in e.neighbours.iter().enumerate() {
                let x = self.rest[r];
                for (c, tc) in t.iter_mut().enumerate() {
                    *tc -= w[c * n + p] * x;
                }
            }
            let x = backward(&self.l[k], t);
            b[e.first..e.first + B].copy_from_slice(&x);
        }
    }
}

/// The place of entry (r, c), r <= c, of a symmetric matrix's upper triangle packed column by
/// column: (0, 0), (0, 1), (1, 1), (0, 2), ..
fn packed(r: usize, c: usize) -> usize {
    c * (c + 1) / 2 + r
}

/// Cholesky factor of a symmetric 3 x 3 matrix given by its upper triangle (00 01 11 02 12 22),
/// packed lower (l00 l10 l11 l20 l21 l22). Err: the first pivot that is not positive.
fn cholesky3(a: &[f64; 6]) -> Result<[f64; 6], usize> {
    let [a00, a01, a11, a02, a12, a22] = *a;
    let positive = |d: f64, c: usize| if d > 0.0 { Ok(d.sqrt()) } else { Err(c) };
    let l00 = positive(a00, 0)?;
    let l10 = a01 / l00;
    let l20 = a02 / l00;
    let l11 = positive(a11 - l10 * l10, 1)?;
    let l21 = (a12 - l20 * l10) / l11;
    let l22 = positive(a22 - l20 * l20 - l21 * l21, 2)?;
    Ok([l00, l10, l11, l20, l21, l22])
}

/// `L^-1 b`.
fn forward(l: &[f64; 6], b: [f64; 3]) -> [f64; 3] {
    let x0 = b[0] / l[0];
    let x1 = (b[1] - l[1] * x0) / l[2];
    let x2 = (b[2] - l[3] * x0 - l[4] * x1) / l[5];
    [x0, x1, x2]
}

/// `L^-T b`.
fn backward(l: &[f64; 6], b: [f64; 3]) -> [f64; 3] {
    let x2 = b[2] / l[5];
    let x1 = (b[1] - l[4] * x2) / l[2];
    let x0 = (b[0] - l[1] * x1 - l[3] * x2) / l[0];
    [x0, x1, x2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A symmetric, diagonally dominant matrix of 12 unknowns with off-diagonal `entries`
    /// (row < column, value).
    fn matrix(entries: &[(usize, usize, f64)]) -> NormalMatrix {
        let n = 12;
        let mut columns: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        let mut diagonal = vec![1.0; n];
        for &(r, c, v) in entries {
            columns[c].push((r, v));
            diagonal[r] += v.abs();
            diagonal[c] += v.abs();
        }
        for (c, column) in columns.iter_mut().enumerate() {
            column.sort_by_key(|e| e.0);
            column.push((c, diagonal[c]));
        }
        let columns: Vec<&[(usize, f64)]> = columns.iter().map(|c| &c[..]).collect();
        NormalMatrix::from_upper(n, &columns)
    }

    /// Blocks 0 (unknowns 0-2) and 1 (3-5) touch the unknowns 9-11 but not each other; block
    /// 2 (6-8) is coupled to block 0. Block 1 has a zero inside ((3, 5) is not in the pattern).
    fn example() -> NormalMatrix {
        matrix(&[
            (0, 1, 0.3),
            (0, 2, -0.2),
            (1, 2, 0.5),
            (3, 4, 0.4),
            (4, 5, -0.1),
            (6, 7, 0.2),
            (0, 9, 0.7),
            (1, 10, -0.6),
            (2, 9, 0.1),
            (3, 10, 0.9),
            (5, 11, -0.8),
            (2, 6, 0.5),
            (8, 11, 0.3),
            (9, 10, 0.2),
        ])
    }

    #[test]
    fn the_condensed_solve_solves_the_whole_system() {
        let m = example();
        let mut c = Condensation::analyse(&m, &[0, 1, 2]).expect("blocks to eliminate");
        // Block 2 is coupled to block 0, eliminated before it, so it stays.
        assert_eq!(c.kept(), &[6, 7, 8, 9, 10, 11]);
        let mut cholesky = Cholesky::analyse(&c.matrix, 1, None).unwrap();
        c.factorize(&m, &mut cholesky).unwrap();
        let b: Vec<f64> = (0..12).map(|i| (i as f64 * 0.7).sin()).collect();
        let mut x = b.clone();
        c.solve_in_place(&mut cholesky, &mut x);
        let residual = m.residual(&x, &b);
        assert!(residual < 1e-14, "residual {residual}");
        // Nothing to eliminate: no condensation.
        assert!(Condensation::analyse(&m, &[]).is_none());
        assert!(Condensation::analyse(&m, &[7]).is_none());
    }

    #[test]
    fn a_block_that_is_not_positive_definite_is_an_error_naming_its_unknown() {
        let mut m = example();
        let slot = m.slot(4, 4).unwrap();
        m.values[slot] = -1.0;
        let mut c = Condensation::analyse(&m, &[0, 1]).unwrap();
        let mut cholesky = Cholesky::analyse(&c.matrix, 1, None).unwrap();
        assert_eq!(c.factorize(&m, &mut cholesky), Err(NotPositive(4)));
        assert_eq!(
            NotPositive(4).error(12).to_string(),
            "solver: the linearized system is not positive definite (pivot at unknown 4 of \
             12); try a larger regularization (--eps)"
        );
    }

    /// A pivot of the rest is named by its unknown in the whole system, not in the rest.
    #[test]
    fn a_rest_that_is_not_positive_definite_is_an_error_naming_the_whole_systems_unknown() {
        let mut m = example();
        let slot = m.slot(10, 10).unwrap();
        m.values[slot] = -1.0;
        let mut c = Condensation::analyse(&m, &[0, 1, 2]).unwrap();
        assert_eq!(c.kept()[4], 10);
        let mut cholesky = Cholesky::analyse(&c.matrix, 1, None).unwrap();
        assert_eq!(c.factorize(&m, &mut cholesky), Err(NotPositive(10)));
    }
}
