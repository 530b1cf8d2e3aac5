//! Points from their differences: the least-squares inverse of taking differences along the
//! edges of a graph (one sparse Cholesky of its Laplacian, three right-hand sides).

use crate::error::{Error, Result};
use crate::geometry::Vec3;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

/// The `n` points `p` minimizing `sum |p_l - p_r - d|^2` over `differences` `(l, r, d)`, with
/// a tiny pull to the origin that fixes the free translation of each connected piece.
pub fn integrated(n: usize, differences: &[(usize, usize, Vec3)]) -> Result<Vec<Vec3>> {
    let mut triplets: Vec<Triplet<usize, usize, f64>> =
        (0..n).map(|f| Triplet::new(f, f, 1e-9)).collect();
    let mut rhs = Mat::<f64>::zeros(n, 3);
    for &(l, r, d) in differences {
        for (a, b, v) in [(l, l, 1.0), (r, r, 1.0), (l, r, -1.0), (r, l, -1.0)] {
            triplets.push(Triplet::new(a, b, v));
        }
        let d = d.to_array();
        for k in 0..3 {
            rhs[(l, k)] += d[k];
            rhs[(r, k)] -= d[k];
        }
    }
    let fail = |what: &str| Error::Solver(format!("points from their differences: {what}"));
    let laplacian = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| fail(&format!("{e:?}")))?;
    let llt = laplacian
        .sp_cholesky(Side::Lower)
        .map_err(|e| fail(&format!("{e:?}")))?;
    let solution = faer::linalg::solvers::Solve::solve(&llt, &rhs);
    Ok((0..n)
        .map(|f| Vec3::new(solution[(f, 0)], solution[(f, 1)], solution[(f, 2)]))
        .collect())
}
