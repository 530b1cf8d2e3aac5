//! Sparse Cholesky on a fixed pattern: the symbolic analysis (fill-reducing ordering, elimination
//! structure) is done once, every later factorization is numeric only. Large systems are
//! factored in two halves on two threads (`split.rs`).

use super::dissection::split_in_halves;
use super::normal_matrix::NormalMatrix;
use super::ordering::{block_graph, block_order, DISSECTION_MIN_BLOCKS};
use super::split::SplitCholesky;
use crate::error::{Error, Result};
use crate::geometry::Vec3;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltError, LltRegularization};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// The factorization of a system: whole, or (large systems with positions, two threads) in
/// two halves and their separator.
pub enum Cholesky {
    Whole(Box<WholeCholesky>),
    Split(Box<SplitCholesky>),
}

/// From this many blocks on, a system whose blocks have positions is factored in two halves
/// on two threads. At about 1000 blocks (700 vertices) both take the same time; at 2500 the
/// split is 1.4x faster. A process confined to one core splits too (its two threads take
/// turns): the split's roundoff differs from the whole factor's, and on a surface where the
/// sheet's folds are chaotic that decides between results, which must not depend on the
/// machine.
const SPLIT_MIN_BLOCKS: usize = 2000;

impl Cholesky {
    /// Symbolic analysis of unknowns in blocks of `block` consecutive indices (1: each on its
    /// own): the ordering is computed on the block graph, by nested dissection when the
    /// blocks' `positions` are given and the system is large. With positions, from
    /// `SPLIT_MIN_BLOCKS` blocks, the system is split at the first cut.
    pub fn analyse(
        matrix: &NormalMatrix,
        block: usize,
        positions: Option<&[Option<Vec3>]>,
    ) -> Result<Cholesky> {
        let nb = matrix.n / block.max(1);
        match positions {
            Some(p)
                if matrix.n.is_multiple_of(block) && nb >= SPLIT_MIN_BLOCKS && p.len() == nb =>
            {
                let graph = block_graph(matrix, block);
                let [a, b, s] = split_in_halves(&graph, p, DISSECTION_MIN_BLOCKS)?;
                Ok(Cholesky::Split(Box::new(SplitCholesky::analyse(
                    matrix,
                    block,
                    [&a, &b],
                    &s,
                )?)))
            }
            _ => Ok(Cholesky::Whole(Box::new(WholeCholesky::analyse(
                matrix, block, positions,
            )?))),
        }
    }

    /// Non-zeros of the factor.
    pub fn factor_nnz(&self) -> usize {
        match self {
            Cholesky::Whole(c) => c.factor_nnz(),
            Cholesky::Split(c) => c.factor_nnz(),
        }
    }

    /// Threads the last numeric factorization ran on: 2 for a split one, unless no second
    /// thread could be started (its halves then ran one after the other).
    pub fn threads(&self) -> usize {
        match self {
            Cholesky::Whole(_) => 1,
            Cholesky::Split(c) => c.threads(),
        }
    }

    /// Numeric factorization of the matrix's current values.
    pub fn factorize(&mut self, matrix: &NormalMatrix) -> std::result::Result<(), NotPositive> {
        match self {
            Cholesky::Whole(c) => c.factorize(matrix),
            Cholesky::Split(c) => c.factorize(matrix),
        }
    }

    /// Solves `A x = b` in place with the last factorization.
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        match self {
            Cholesky::Whole(c) => c.solve_in_place(b),
            Cholesky::Split(c) => c.solve_in_place(b),
        }
    }
}

/// One sparse factor of the whole system.
pub struct WholeCholesky {
    factor: SparseFactor,
    has_factor: bool,
}

/// A faer sparse Cholesky factor with its buffers: the symbolic analysis once, the numeric
/// factorization as often as asked.
pub(super) struct SparseFactor {
    pub(super) symbolic: SymbolicCholesky<usize>,
    /// The values of L.
    pub(super) values: Vec<f64>,
    scratch: MemBuffer,
    pub(super) solve_scratch: MemBuffer,
}

impl SparseFactor {
    /// The symbolic analysis of an upper-triangular `pattern`.
    pub(super) fn analyse(
        pattern: SymbolicSparseColMatRef<'_, usize>,
        ordering: SymmetricOrdering<'_, usize>,
        params: CholeskySymbolicParams<'_>,
    ) -> Result<SparseFactor> {
        let symbolic = factorize_symbolic_cholesky(pattern, Side::Upper, ordering, params)
            .map_err(|e| Error::Solver(format!("symbolic factorization failed: {e:?}")))?;
        Ok(SparseFactor {
            scratch: MemBuffer::new(
                symbolic.factorize_numeric_llt_scratch::<f64>(parallelism(), Default::default()),
            ),
            solve_scratch: MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq)),
            values: vec![0.0; symbolic.len_val()],
            symbolic,
        })
    }

    /// Numeric factorization of `a` (upper triangle, on the analysed pattern). Err: the
    /// elimination position (from 0) of the first pivot that is not positive.
    pub(super) fn factorize(
        &mut self,
        a: SparseColMatRef<'_, usize, f64>,
    ) -> std::result::Result<(), usize> {
        self.symbolic
            .factorize_numeric_llt(
                &mut self.values,
                a,
                Side::Upper,
                LltRegularization::default(),
                parallelism(),
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .map(|_| ())
            .map_err(|LltError::NonPositivePivot { index }| {
                // faer 0.24 counts a simplicial factor's pivots from 1, a supernodal one's
                // from 0.
                match self.symbolic.raw() {
                    SymbolicCholeskyRaw::Simplicial(_) => index - 1,
                    SymbolicCholeskyRaw::Supernodal(_) => index,
                }
            })
    }
}

impl WholeCholesky {
    pub(super) fn analyse(
        matrix: &NormalMatrix,
        block: usize,
        positions: Option<&[Option<Vec3>]>,
    ) -> Result<WholeCholesky> {
        let pattern = pattern_of(matrix);
        let blocked = matrix
            .n
            .is_multiple_of(block)
            .then(|| block_order(matrix, block, positions))
            .transpose()?;
        let ordering = match &blocked {
            Some((fwd, inv)) => SymmetricOrdering::Custom(PermRef::new_checked(fwd, inv, matrix.n)),
            None => SymmetricOrdering::Amd,
        };
        Ok(WholeCholesky {
            factor: SparseFactor::analyse(pattern, ordering, CholeskySymbolicParams::default())?,
            has_factor: false,
        })
    }

    /// Non-zeros of the factor L.
    pub fn factor_nnz(&self) -> usize {
        self.factor.symbolic.len_val()
    }

    /// Numeric factorization of the matrix's current values.
    pub fn factorize(&mut self, matrix: &NormalMatrix) -> std::result::Result<(), NotPositive> {
        self.has_factor = false;
        let a = SparseColMatRef::new(pattern_of(matrix), &matrix.values);
        self.factor.factorize(a).map_err(|position| {
            let symbolic = &self.factor.symbolic;
            NotPositive(symbolic.perm().map_or(position, |p| p.arrays().0[position]))
        })?;
        self.has_factor = true;
        Ok(())
    }

    /// Solves `A x = b` in place with the last factorization.
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        assert!(self.has_factor, "solve before factorize");
        let n = b.len();
        let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
        let f = &mut self.factor;
        LltRef::new(&f.symbolic, &f.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut f.solve_scratch),
        );
    }
}

/// Sequential: on this problem's sizes faer's parallel factorization measured no faster on
/// two cores (bench at 1.5k, 8.5k and 35k vertices); `split.rs` uses the second core.
fn parallelism() -> Par {
    Par::Seq
}

/// A factorization met a pivot that is not positive, at this unknown of the matrix it
/// factored (whose owner knows what that unknown is in the whole system).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NotPositive(pub usize);

impl NotPositive {
    /// The error for the user, the unknown one of `n` in the whole system.
    pub fn error(self, n: usize) -> Error {
        Error::Solver(format!(
            "the linearized system is not positive definite (pivot at unknown {} of {n}); \
             try a larger regularization (--eps)",
            self.0
        ))
    }
}

fn pattern_of(m: &NormalMatrix) -> SymbolicSparseColMatRef<'_, usize> {
    SymbolicSparseColMatRef::new_checked(m.n, m.n, &m.col_ptr, None, &m.row_idx)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// n unknowns, each coupled to the next `band` ones (0.1 / band each), diagonal 1 (`bad`
    /// at unknown `at`).
    fn banded(n: usize, band: usize, at: usize, bad: f64) -> NormalMatrix {
        let columns: Vec<Vec<(usize, f64)>> = (0..n)
            .map(|c| {
                let above = (c.saturating_sub(band)..c).map(|r| (r, 0.1 / band as f64));
                above
                    .chain([(c, if c == at { bad } else { 1.0 })])
                    .collect()
            })
            .collect();
        let columns: Vec<&[(usize, f64)]> = columns.iter().map(|c| &c[..]).collect();
        NormalMatrix::from_upper(n, &columns)
    }

    /// faer counts the pivots of a simplicial factor from 1 and of a supernodal one from 0;
    /// both name the unknown itself.
    #[test]
    fn a_pivot_that_is_not_positive_is_named_by_its_unknown_in_either_kind_of_factor() {
        // Tridiagonal: simplicial; dense: supernodal.
        for (band, supernodal) in [(1, false), (300, true)] {
            let m = banded(300, band, 37, -1.0);
            let mut c = WholeCholesky::analyse(&m, 1, None).unwrap();
            let raw = c.factor.symbolic.raw();
            assert_eq!(
                matches!(raw, SymbolicCholeskyRaw::Supernodal(_)),
                supernodal,
                "band {band}"
            );
            assert_eq!(c.factorize(&m), Err(NotPositive(37)), "band {band}");
            let good = banded(300, band, 37, 1.0);
            assert_eq!(c.factorize(&good), Ok(()), "band {band}");
        }
    }
}
