//! Sparse Cholesky in two halves factored at the same time.
//!
//! The block graph is cut once (nested dissection's first cut): halves A and B share no
//! coupling, and the separator S holds every block coupled to both. Each half is factored with
//! S numbered last, with the whole of `A_SS` in its corner:
//!
//! ```text
//! [A_AA A_AS]   [L_AA      ] [L_AA      ]^T
//! [A_SA A_SS] = [L_SA  L_S^A] [L_SA  L_S^A]
//! ```
//!
//! so `L_S^A L_S^A^T = A_SS - A_SA A_AA^-1 A_AS`, positive definite since the whole matrix is.
//! The Schur complement of both halves is then `L_S^A L_S^A^T + L_S^B L_S^B^T - A_SS`, a dense
//! matrix of the separator's size, factored last. The two sparse factorizations are the work,
//! and they run on two threads; a single factor cannot be split like this by faer, whose
//! parallel factorization measured no faster here.

use super::cholesky::{NotPositive, SparseFactor};
use super::normal_matrix::NormalMatrix;
use super::ordering::expand;
use crate::error::Result;
use crate::parallel::{both, both_telling};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::linalg::cholesky::llt::factor::{LltError, LltRegularization};
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, Mat, MatMut, MatRef, Par};

/// One half with the separator: its own pattern in elimination order (the half's unknowns,
/// then the separator's), where each entry's value comes from in the whole matrix, and its
/// factor.
struct Half {
    /// Local unknown k is the whole system's unknown `global[k]`.
    global: Vec<usize>,
    /// Unknowns before the separator's.
    interior: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Entry k's value is the whole matrix's value `source[k]`.
    source: Vec<usize>,
    values: Vec<f64>,
    factor: SparseFactor,
    /// The separator's corner of L (dense, lower) is the bottom right of the last supernode,
    /// unless the separator spans several (then this copy holds it).
    corner_copy: Option<Mat<f64>>,
    /// The corner times its transpose (lower triangle).
    corner_square: Mat<f64>,
    /// A right-hand side in local order.
    work: Vec<f64>,
    /// The half's term of the separator's right-hand side.
    to_separator: Vec<f64>,
}

pub struct SplitCholesky {
    n: usize,
    halves: [Half; 2],
    /// The separator's unknowns (the whole system's indices).
    separator: Vec<usize>,
    /// `A_SS`'s entries: (row, column) in the separator, row >= column, and the value's index.
    separator_entries: Vec<(usize, usize, usize)>,
    /// The Schur complement, then its Cholesky factor (lower).
    schur: Mat<f64>,
    schur_scratch: MemBuffer,
    factor_nnz: usize,
    has_factor: bool,
    /// Threads the last factorization ran on: 2, or 1 where no second thread could be started.
    threads: usize,
}

impl SplitCholesky {
    /// `halves` and `separator` are blocks of `block` unknowns, each in elimination order; no
    /// block of one half may be coupled to a block of the other.
    pub fn analyse(
        matrix: &NormalMatrix,
        block: usize,
        halves: [&[usize]; 2],
        separator: &[usize],
    ) -> Result<SplitCholesky> {
        let scalars = |blocks: &[usize]| expand(blocks, block);
        let separator = scalars(separator);
        let m = separator.len();
        let half = |blocks: &[usize]| {
            let mut global = scalars(blocks);
            let interior = global.len();
            global.extend_from_slice(&separator);
            Half::analyse(matrix, global, interior)
        };
        let (a, b) = both(|| half(halves[0]), || half(halves[1]));
        let (a, b) = (a?, b?);
        let mut local = vec![usize::MAX; matrix.n];
        for (k, &g) in separator.iter().enumerate() {
            local[g] = k;
        }
        let mut separator_entries = Vec::new();
        for (j, &gj) in separator.iter().enumerate() {
            for k in matrix.col_ptr[gj]..matrix.col_ptr[gj + 1] {
                let i = local[matrix.row_idx[k]];
                if i != usize::MAX {
                    separator_entries.push((i.max(j), i.min(j), k));
                }
            }
        }
        let factor_nnz =
            a.factor.symbolic.len_val() + b.factor.symbolic.len_val() + m * (m + 1) / 2;
        Ok(SplitCholesky {
            n: matrix.n,
            halves: [a, b],
            separator,
            separator_entries,
            schur: Mat::zeros(m, m),
            schur_scratch: MemBuffer::new(llt::factor::cholesky_in_place_scratch::<f64>(
                m,
                Par::Seq,
                Default::default(),
            )),
            factor_nnz,
            has_factor: false,
            threads: 2,
        })
    }

    /// Non-zeros of both halves' factors (each with the separator's block, stored square as
    /// faer stores supernodes' diagonal blocks) and of the separator's dense factor.
    pub fn factor_nnz(&self) -> usize {
        self.factor_nnz
    }

    /// Threads the last factorization ran on (2 before the first).
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// Numeric factorization: both halves at once, then the separator's Schur complement.
    pub fn factorize(&mut self, matrix: &NormalMatrix) -> std::result::Result<(), NotPositive> {
        self.has_factor = false;
        let [a, b] = &mut self.halves;
        let (ra, rb, apart) = both_telling(|| a.factorize(matrix), || b.factorize(matrix));
        self.threads = if apart { 2 } else { 1 };
        ra?;
        rb?;
        let m = self.separator.len();
        if m == 0 {
            self.has_factor = true;
            return Ok(());
        }
        let [a, b] = &self.halves;
        let mut schur = self.schur.as_mut();
        for j in 0..m {
            for i in j..m {
                schur[(i, j)] = a.corner_square[(i, j)] + b.corner_square[(i, j)];
            }
        }
        for &(i, j, k) in &self.separator_entries {
            schur[(i, j)] -= matrix.values[k];
        }
        llt::factor::cholesky_in_place(
            schur,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.schur_scratch),
            Default::default(),
        )
        .map_err(|e| {
            let LltError::NonPositivePivot { index } = e;
            NotPositive(self.separator[index.min(m - 1)])
        })?;
        self.has_factor = true;
        Ok(())
    }

    /// Solves `A x = b` in place with the last factorization.
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        assert!(self.has_factor, "solve before factorize");
        assert_eq!(b.len(), self.n, "right-hand side of another size");
        let m = self.separator.len();
        // Forward, both halves at once: each gives its part of the separator's right-hand side.
        let [a, c] = &mut self.halves;
        let given: &[f64] = b;
        both(|| a.forward(given), || c.forward(given));
        let mut rhs: Vec<f64> = self.separator.iter().map(|&g| b[g]).collect();
        for half in &self.halves {
            for (r, t) in rhs.iter_mut().zip(&half.to_separator) {
                *r += t;
            }
        }
        if m > 0 {
            llt::solve::solve_in_place_with_conj(
                self.schur.as_ref(),
                Conj::No,
                MatMut::from_column_major_slice_mut(&mut rhs, m, 1),
                Par::Seq,
                MemStack::new(&mut []),
            );
        }
        let [a, c] = &mut self.halves;
        both(|| a.backward(&rhs), || c.backward(&rhs));
        for half in &self.halves {
            for (&g, &x) in half.global.iter().zip(&half.work[..half.interior]) {
                b[g] = x;
            }
        }
        for (&g, &x) in self.separator.iter().zip(&rhs) {
            b[g] = x;
        }
    }
}

/// The factor as supernodes (the halves are analysed with the supernodal form forced).
fn supernodal<'a>(
    symbolic: &'a SymbolicCholesky<usize>,
    factor: &'a [f64],
) -> SupernodalLltRef<'a, usize, f64> {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => SupernodalLltRef::new(s, factor),
        SymbolicCholeskyRaw::Simplicial(_) => unreachable!("analysed as supernodal"),
    }
}

/// The separator's corner of a half's factor L: a view into the last supernode, or `copy`.
fn corner<'a>(
    symbolic: &'a SymbolicCholesky<usize>,
    factor: &'a [f64],
    interior: usize,
    copy: &'a Option<Mat<f64>>,
) -> MatRef<'a, f64> {
    if let Some(copy) = copy {
        return copy.as_ref();
    }
    let factor = supernodal(symbolic, factor);
    let last = factor.supernode(factor.symbolic().n_supernodes() - 1);
    let (offset, m) = (interior - last.start(), symbolic.nrows() - interior);
    last.val().submatrix(offset, offset, m, m)
}

/// Copies the separator's corner of L out of the supernodes that hold it.
fn copy_corner(
    symbolic: &SymbolicCholesky<usize>,
    factor: &[f64],
    interior: usize,
    copy: &mut Mat<f64>,
) {
    copy.fill(0.0);
    let factor = supernodal(symbolic, factor);
    for s in 0..factor.symbolic().n_supernodes() {
        let node = factor.supernode(s);
        let (first, values) = (node.start(), node.val());
        let width = values.ncols();
        if first + width <= interior {
            continue;
        }
        let rows: Vec<usize> = (first..first + width)
            .chain(node.pattern().iter().copied())
            .collect();
        for c in first.max(interior) - first..width {
            for (r, &row) in rows.iter().enumerate().skip(c) {
                copy[(row - interior, first + c - interior)] = values[(r, c)];
            }
        }
    }
}

impl Half {
    fn analyse(matrix: &NormalMatrix, global: Vec<usize>, interior: usize) -> Result<Half> {
        let n = global.len();
        let mut local = vec![usize::MAX; matrix.n];
        for (k, &g) in global.iter().enumerate() {
            local[g] = k;
        }
        // The whole matrix's upper entries between two of this half's unknowns, as upper
        // entries in local numbering.
        let mut columns: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
        for (j, &gj) in global.iter().enumerate() {
            for k in matrix.col_ptr[gj]..matrix.col_ptr[gj + 1] {
                let i = local[matrix.row_idx[k]];
                if i != usize::MAX {
                    columns[i.max(j)].push((i.min(j), k));
                } else {
                    // Only the separator may be coupled to the other half.
                    debug_assert!(j >= interior, "the halves are coupled at unknown {gj}");
                }
            }
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let (mut row_idx, mut source) = (Vec::new(), Vec::new());
        col_ptr.push(0);
        for column in &mut columns {
            column.sort_unstable();
            row_idx.extend(column.iter().map(|e| e.0));
            source.extend(column.iter().map(|e| e.1));
            col_ptr.push(row_idx.len());
        }
        let pattern = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let factor = SparseFactor::analyse(pattern, SymmetricOrdering::Identity, params)?;
        let m = n - interior;
        let in_last_supernode = match factor.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => s
                .supernode_begin()
                .last()
                .is_some_and(|&first| first <= interior),
            SymbolicCholeskyRaw::Simplicial(_) => false,
        };
        let corner_copy = (!in_last_supernode).then(|| Mat::zeros(m, m));
        Ok(Half {
            interior,
            values: vec![0.0; source.len()],
            factor,
            global,
            col_ptr,
            row_idx,
            source,
            corner_copy,
            corner_square: Mat::zeros(m, m),
            work: vec![0.0; n],
            to_separator: vec![0.0; m],
        })
    }

    /// Factors the half and squares its separator corner.
    fn factorize(&mut self, matrix: &NormalMatrix) -> std::result::Result<(), NotPositive> {
        // Nothing to factor (faer would not even make it supernodal).
        if self.global.is_empty() {
            return Ok(());
        }
        for (v, &k) in self.values.iter_mut().zip(&self.source) {
            *v = matrix.values[k];
        }
        let n = self.global.len();
        let pattern =
            SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx);
        let a = SparseColMatRef::new(pattern, &self.values);
        self.factor
            .factorize(a)
            .map_err(|index| NotPositive(self.global[index.min(n - 1)]))?;
        if let Some(copy) = &mut self.corner_copy {
            copy_corner(
                &self.factor.symbolic,
                &self.factor.values,
                self.interior,
                copy,
            );
        }
        let corner = corner(
            &self.factor.symbolic,
            &self.factor.values,
            self.interior,
            &self.corner_copy,
        );
        // Only the lower triangle of the square is read.
        triangular::matmul(
            self.corner_square.as_mut(),
            BlockStructure::TriangularLower,
            Accum::Replace,
            corner,
            BlockStructure::TriangularLower,
            corner.transpose(),
            BlockStructure::TriangularUpper,
            1.0,
            Par::Seq,
        );
        Ok(())
    }

    /// Forward substitution of the half's part of `b` (the separator's part taken as 0):
    /// keeps `y = L_AA^-1 b_A` in `work` and `-L_SA y` in `to_separator`.
    fn forward(&mut self, b: &[f64]) {
        if self.global.is_empty() {
            return;
        }
        let start = self.interior;
        for (w, &g) in self.work.iter_mut().zip(&self.global[..start]) {
            *w = b[g];
        }
        self.work[start..].fill(0.0);
        let n = self.work.len();
        let factor = supernodal(&self.factor.symbolic, &self.factor.values);
        factor.l_solve_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut self.work, n, 1),
            Par::Seq,
            MemStack::new(&mut self.factor.solve_scratch),
        );
        // The bottom is -L_S^-1 L_SA y; L_S times it is -L_SA y.
        self.to_separator.fill(0.0);
        let corner = corner(
            &self.factor.symbolic,
            &self.factor.values,
            start,
            &self.corner_copy,
        );
        for (j, &u) in self.work[start..].iter().enumerate() {
            let column = corner.col(j);
            for i in j..n - start {
                self.to_separator[i] += column[i] * u;
            }
        }
    }

    /// Backward substitution with the separator's solution `xs`: leaves the half's unknowns
    /// `L_AA^-T (y - L_SA^T xs)` at the start of `work`.
    fn backward(&mut self, xs: &[f64]) {
        if self.global.is_empty() {
            return;
        }
        let start = self.interior;
        let m = xs.len();
        let corner = corner(
            &self.factor.symbolic,
            &self.factor.values,
            start,
            &self.corner_copy,
        );
        for i in 0..m {
            self.work[start + i] = (i..m).map(|j| corner[(j, i)] * xs[j]).sum();
        }
        let n = self.work.len();
        let factor = supernodal(&self.factor.symbolic, &self.factor.values);
        factor.l_transpose_solve_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut self.work, n, 1),
            Par::Seq,
            MemStack::new(&mut self.factor.solve_scratch),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::super::cholesky::WholeCholesky;
    use super::super::dissection::split_in_halves;
    use super::super::ordering::{block_graph, DISSECTION_MIN_BLOCKS};
    use super::*;
    use crate::generate::{lifted_hex_patch, Shape};
    use crate::mesh::Connectivity;
    use crate::optimize::{block_positions, families, WallRows, Weights};
    use crate::surface::Surface;

    /// A honeycomb system's pattern (2.5k blocks) with positions, its values a symmetric
    /// matrix made positive definite by its diagonal.
    fn honeycomb_system() -> (NormalMatrix, Vec<Option<crate::geometry::Vec3>>) {
        let (base, surface) = lifted_hex_patch(Shape::Saddle, 1500);
        let conn = Connectivity::build(&base).unwrap();
        let surface = Surface::from_mesh(&surface).unwrap();
        let fams = families(
            &base,
            &conn,
            &surface,
            &Weights::default(),
            WallRows::Consistency,
        );
        let n = 3 * (base.vertices.len() + conn.num_edges());
        let mut matrix = NormalMatrix::new(n, &fams, None);
        let mut row_sums = vec![0.0; n];
        let mut seed = 7u64;
        for j in 0..n {
            for k in matrix.col_ptr[j]..matrix.col_ptr[j + 1] {
                let i = matrix.row_idx[k];
                if i != j {
                    seed = seed
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    let v = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                    matrix.values[k] = v;
                    row_sums[i] += v.abs();
                    row_sums[j] += v.abs();
                }
            }
        }
        for (j, sum) in row_sums.iter().enumerate() {
            let k = matrix.col_ptr[j + 1] - 1;
            assert_eq!(matrix.row_idx[k], j, "the diagonal closes each column");
            matrix.values[k] = sum + 1e-3;
        }
        (matrix, block_positions(&base, &conn, n))
    }

    #[test]
    fn two_halves_solve_what_the_whole_factor_solves() {
        let (matrix, positions) = honeycomb_system();
        let graph = block_graph(&matrix, 3);
        let [a, b, s] = split_in_halves(&graph, &positions, DISSECTION_MIN_BLOCKS).unwrap();
        assert!(!s.is_empty() && a.len() > 10 * s.len() && b.len() > 10 * s.len());
        for &x in &a {
            assert!(graph.adjacency[x].iter().all(|y| !b.contains(y)));
        }
        let mut whole = WholeCholesky::analyse(&matrix, 3, Some(&positions)).unwrap();
        whole.factorize(&matrix).unwrap();
        let rhs: Vec<f64> = (0..matrix.n)
            .map(|i| ((i * 37) % 101) as f64 - 50.0)
            .collect();
        let mut xw = rhs.clone();
        whole.solve_in_place(&mut xw);
        let scale = rhs.iter().fold(0.0f64, |m, b| m.max(b.abs()));
        // The corner read in the last supernode (as here), and copied out (the way for a
        // separator that spans several supernodes; `separator_over_several_supernodes` has one).
        for copied in [false, true] {
            let mut split = SplitCholesky::analyse(&matrix, 3, [&a, &b], &s).unwrap();
            assert!(split.halves.iter().all(|h| h.corner_copy.is_none()));
            if copied {
                let m = split.separator.len();
                split.halves[1].corner_copy = Some(Mat::zeros(m, m));
            }
            split.factorize(&matrix).unwrap();
            let mut xs = rhs.clone();
            split.solve_in_place(&mut xs);
            let residual = matrix.residual(&xs, &rhs);
            assert!(
                residual < 1e-10 * scale,
                "residual {residual} (copied: {copied})"
            );
            let apart = xs
                .iter()
                .zip(&xw)
                .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
            assert!(
                apart < 1e-10 * scale,
                "the two solutions differ by {apart} (copied: {copied})"
            );
        }
    }

    #[test]
    fn a_matrix_that_is_not_positive_definite_is_an_error_naming_the_pivot() {
        let (mut matrix, positions) = honeycomb_system();
        let graph = block_graph(&matrix, 3);
        let [a, b, s] = split_in_halves(&graph, &positions, DISSECTION_MIN_BLOCKS).unwrap();
        let mut split = SplitCholesky::analyse(&matrix, 3, [&a, &b], &s).unwrap();
        // One unknown of the separator, one inside a half.
        for unknown in [3 * s[0] + 1, 3 * a[a.len() / 2]] {
            let k = matrix.col_ptr[unknown + 1] - 1;
            let kept = matrix.values[k];
            matrix.values[k] = -1.0;
            assert_eq!(split.factorize(&matrix), Err(NotPositive(unknown)));
            matrix.values[k] = kept;
        }
        split.factorize(&matrix).unwrap();
    }

    /// Halves with no unknowns of their own, no separator, and a separator whose corner spans
    /// two supernodes (its two unknowns are coupled through nothing): each solves the system.
    #[test]
    fn empty_halves_and_a_separator_over_several_supernodes() {
        // 4 x 4: unknown 0 coupled to 1 and 3; 1, 2 and 3 not to each other.
        let matrix = NormalMatrix::from_upper(
            4,
            &[
                &[(0, 4.0)],
                &[(0, 1.0), (1, 3.0)],
                &[(2, 2.0)],
                &[(0, -1.0), (3, 5.0)],
            ],
        );
        let rhs = [1.0, -2.0, 3.0, 0.5];
        let cases: [([&[usize]; 2], &[usize]); 5] = [
            ([&[0], &[]], &[1, 2, 3]),
            ([&[0, 1], &[2]], &[3]),
            ([&[0, 1, 2, 3], &[]], &[]),
            ([&[], &[]], &[0, 1, 2, 3]),
            ([&[], &[0, 1, 3]], &[2]),
        ];
        for (halves, separator) in cases {
            let mut split = SplitCholesky::analyse(&matrix, 1, halves, separator).unwrap();
            split.factorize(&matrix).unwrap();
            let mut x = rhs;
            split.solve_in_place(&mut x);
            let residual = matrix.residual(&x, &rhs);
            assert!(
                residual < 1e-14,
                "{halves:?} {separator:?}: residual {residual}"
            );
        }
        // The first case's corner is copied out of two supernodes.
        let split = SplitCholesky::analyse(&matrix, 1, [&[0], &[]], &[1, 2, 3]).unwrap();
        assert!(split.halves[0].corner_copy.is_some());
    }
}
