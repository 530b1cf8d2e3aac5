//! Fill-reducing ordering on the graph of unknown blocks.
//!
//! Unknowns come in blocks (3 coordinates of a point or a vector) that are coupled to the same
//! neighbours. Ordering the block graph (a third of the size) with AMD and keeping each
//! block's unknowns together gives less fill than AMD on the scalar graph, whose components
//! look different to it (a node row couples only x with x), and it hands the supernodal
//! factorization dense blocks.

use super::normal_matrix::NormalMatrix;
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMatRef;

fn expand(p: &[usize], block: usize) -> Vec<usize> {
    p.iter()
        .flat_map(|&b| (0..block).map(move |c| b * block + c))
        .collect()
}

/// Minimum degree on the block graph, as a scalar permutation (forward, inverse).
pub fn block_amd(m: &NormalMatrix, block: usize) -> Result<(Vec<usize>, Vec<usize>)> {
    let nb = m.n / block;
    // Upper-triangular block pattern, column by column.
    let mut columns: Vec<Vec<usize>> = vec![Vec::new(); nb];
    for j in 0..m.n {
        let bj = j / block;
        for &i in &m.row_idx[m.col_ptr[j]..m.col_ptr[j + 1]] {
            let bi = i / block;
            if bi < bj {
                columns[bj].push(bi);
            }
        }
    }
    let mut col_ptr = vec![0usize];
    let mut row_idx = Vec::new();
    for (bj, col) in columns.iter_mut().enumerate() {
        col.push(bj);
        col.sort_unstable();
        col.dedup();
        row_idx.extend_from_slice(col);
        col_ptr.push(row_idx.len());
    }
    let pattern = SymbolicSparseColMatRef::new_checked(nb, nb, &col_ptr, None, &row_idx);
    let (mut fwd, mut inv) = (vec![0usize; nb], vec![0usize; nb]);
    let mut mem = MemBuffer::new(amd::order_scratch::<usize>(nb, row_idx.len()));
    amd::order(
        &mut fwd,
        &mut inv,
        pattern,
        amd::Control::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| Error::Solver(format!("ordering failed: {e:?}")))?;
    Ok((expand(&fwd, block), expand(&inv, block)))
}
