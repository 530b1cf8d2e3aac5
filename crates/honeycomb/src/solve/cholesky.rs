//! Sparse Cholesky on a fixed pattern: the symbolic analysis (fill-reducing ordering, elimination
//! structure) is done once, every later factorization is numeric only.

use super::normal_matrix::NormalMatrix;
use super::ordering::block_order;
use crate::error::{Error, Result};
use crate::geometry::Vec3;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltError, LltRegularization};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

pub struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    factor: Vec<f64>,
    factor_scratch: MemBuffer,
    solve_scratch: MemBuffer,
    has_factor: bool,
}

impl Cholesky {
    /// Symbolic analysis; with `block > 1` (unknowns in blocks of that many consecutive
    /// indices) the ordering is computed on the block graph, by nested dissection when the
    /// blocks' `positions` are given and the system is large.
    pub fn analyse(
        matrix: &NormalMatrix,
        block: usize,
        positions: Option<&[Option<Vec3>]>,
    ) -> Result<Cholesky> {
        let pattern = pattern_of(matrix);
        let blocked = (block > 1 && matrix.n.is_multiple_of(block))
            .then(|| block_order(matrix, block, positions))
            .transpose()?;
        let ordering = match &blocked {
            Some((fwd, inv)) => SymmetricOrdering::Custom(PermRef::new_checked(fwd, inv, matrix.n)),
            None => SymmetricOrdering::Amd,
        };
        let symbolic = factorize_symbolic_cholesky(
            pattern,
            Side::Upper,
            ordering,
            CholeskySymbolicParams::default(),
        )
        .map_err(|e| Error::Solver(format!("symbolic factorization failed: {e:?}")))?;
        let factor_scratch = MemBuffer::new(
            symbolic.factorize_numeric_llt_scratch::<f64>(parallelism(), Default::default()),
        );
        let solve_scratch = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        let factor = vec![0.0; symbolic.len_val()];
        Ok(Cholesky {
            symbolic,
            factor,
            factor_scratch,
            solve_scratch,
            has_factor: false,
        })
    }

    /// Non-zeros of the factor L.
    pub fn factor_nnz(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Numeric factorization of the matrix's current values.
    pub fn factorize(&mut self, matrix: &NormalMatrix) -> Result<()> {
        let a = SparseColMatRef::new(pattern_of(matrix), &matrix.values);
        self.has_factor = false;
        self.symbolic
            .factorize_numeric_llt(
                &mut self.factor,
                a,
                Side::Upper,
                LltRegularization::default(),
                parallelism(),
                MemStack::new(&mut self.factor_scratch),
                Default::default(),
            )
            .map_err(|e| {
                let LltError::NonPositivePivot { index } = e;
                Error::Solver(format!(
                    "the linearized system is not positive definite (pivot {index} of {}); \
                     try a larger regularization (--eps)",
                    matrix.n
                ))
            })?;
        self.has_factor = true;
        Ok(())
    }

    /// Solves `A x = b` in place with the last factorization.
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        assert!(self.has_factor, "solve before factorize");
        let n = b.len();
        let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
        LltRef::new(&self.symbolic, &self.factor).solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut self.solve_scratch),
        );
    }
}

/// Sequential: on this problem's sizes faer's parallel factorization measured no faster on
/// two cores (bench at 1.5k, 8.5k and 35k vertices).
fn parallelism() -> Par {
    Par::Seq
}

fn pattern_of(m: &NormalMatrix) -> SymbolicSparseColMatRef<'_, usize> {
    SymbolicSparseColMatRef::new_checked(m.n, m.n, &m.col_ptr, None, &m.row_idx)
}
