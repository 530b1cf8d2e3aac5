//! Eigenvectors of symmetric 3x3 matrices by cyclic Jacobi rotations: tiny, exact to rounding,
//! and indifferent to repeated eigenvalues.

use super::Vec3;

/// The unit eigenvector of the smallest eigenvalue of the symmetric matrix `m`.
pub fn smallest_eigenvector(m: [[f64; 3]; 3]) -> Vec3 {
    let mut a = m;
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let scale = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-300 || off <= 1e-17 * scale {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            // Rotation zeroing a[p][q] (Golub & Van Loan, symmetric Schur decomposition).
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for row in &mut a {
                let (akp, akq) = (row[p], row[q]);
                row[p] = c * akp - s * akq;
                row[q] = s * akp + c * akq;
            }
            let (row_p, row_q) = (a[p], a[q]);
            for k in 0..3 {
                a[p][k] = c * row_p[k] - s * row_q[k];
                a[q][k] = s * row_p[k] + c * row_q[k];
            }
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    let k = (0..3)
        .min_by(|&i, &j| a[i][i].total_cmp(&a[j][j]))
        .unwrap_or(0);
    Vec3::new(v[0][k], v[1][k], v[2][k]).normalized()
}

/// The solution of `m x = b` for a symmetric `m`, or `None` where `m` is singular to
/// rounding. The rows of the inverse of a symmetric matrix are the cross products of its rows.
pub fn solve_symmetric(m: [[f64; 3]; 3], b: Vec3) -> Option<Vec3> {
    let [r0, r1, r2] = m.map(|r| Vec3::new(r[0], r[1], r[2]));
    let (c0, c1, c2) = (r1.cross(r2), r2.cross(r0), r0.cross(r1));
    let det = r0.dot(c0);
    let scale = r0.norm() * r1.norm() * r2.norm();
    // A NaN determinant is singular too.
    if det.is_nan() || det.abs() <= 1e-12 * scale {
        return None;
    }
    Some(Vec3::new(c0.dot(b), c1.dot(b), c2.dot(b)) / det)
}

/// `sum_k u_k u_k^T`.
pub fn sum_of_outer_products(vectors: impl IntoIterator<Item = Vec3>) -> [[f64; 3]; 3] {
    let mut m = [[0.0; 3]; 3];
    for u in vectors {
        let a = u.to_array();
        for (i, row) in m.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x += a[i] * a[j];
            }
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smallest_eigenvector_is_the_common_normal_of_three_coplanar_directions() {
        let axis = Vec3::new(0.3, -0.5, 0.8).normalized();
        let u = axis.any_orthogonal();
        let w = axis.cross(u);
        let dirs = (0..3).map(|k| {
            let t = 2.0 * std::f64::consts::PI * k as f64 / 3.0 + 0.2;
            u * t.cos() + w * t.sin()
        });
        let e = smallest_eigenvector(sum_of_outer_products(dirs));
        assert!((e.dot(axis).abs() - 1.0).abs() < 1e-14, "{e:?} vs {axis:?}");
    }

    /// `solve_symmetric` inverts a symmetric matrix and tells a singular one.
    #[test]
    fn a_symmetric_system_is_solved() {
        let m = [[4.0, 1.0, -2.0], [1.0, 3.0, 0.5], [-2.0, 0.5, 5.0]];
        let x = Vec3::new(0.7, -1.3, 2.1);
        let b = Vec3::new(
            m[0][0] * x.x + m[0][1] * x.y + m[0][2] * x.z,
            m[1][0] * x.x + m[1][1] * x.y + m[1][2] * x.z,
            m[2][0] * x.x + m[2][1] * x.y + m[2][2] * x.z,
        );
        let got = solve_symmetric(m, b).unwrap();
        assert!((got - x).norm() < 1e-13, "{got:?}");
        let flat = sum_of_outer_products([Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)]);
        assert!(solve_symmetric(flat, b).is_none());
    }

    #[test]
    fn diagonal_and_repeated_eigenvalues() {
        let e = smallest_eigenvector([[3.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 2.0]]);
        assert!((e.y.abs() - 1.0).abs() < 1e-15);
        let e = smallest_eigenvector([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]]);
        assert!((e.z.abs() - 1.0).abs() < 1e-15);
    }
}
