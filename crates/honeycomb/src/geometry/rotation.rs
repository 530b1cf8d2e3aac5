//! Rotations as 3 x 3 matrices (row-major) and their exponential map from rotation vectors.

use super::Vec3;

pub type Matrix3 = [[f64; 3]; 3];

pub const IDENTITY: Matrix3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

pub fn apply(m: &Matrix3, v: Vec3) -> Vec3 {
    Vec3::new(
        m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
        m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
        m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z,
    )
}

pub fn multiply(a: &Matrix3, b: &Matrix3) -> Matrix3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

/// The matrix of `v x .`: `cross(v, w) = skew(v) w`.
pub fn skew(v: Vec3) -> Matrix3 {
    [[0.0, -v.z, v.y], [v.z, 0.0, -v.x], [-v.y, v.x, 0.0]]
}

/// The rotation by the angle `|w|` about `w` (Rodrigues).
pub fn exp(w: Vec3) -> Matrix3 {
    let theta = w.norm();
    let k = skew(w);
    let k2 = multiply(&k, &k);
    // sin(t)/t and (1 - cos(t))/t^2, by their series near zero.
    let (a, b) = if theta < 1e-6 {
        (1.0 - theta * theta / 6.0, 0.5 - theta * theta / 24.0)
    } else {
        (theta.sin() / theta, (1.0 - theta.cos()) / (theta * theta))
    };
    std::array::from_fn(|i| std::array::from_fn(|j| IDENTITY[i][j] + a * k[i][j] + b * k2[i][j]))
}

/// The right Jacobian of the exponential map, `J_r(w) = I - (1 - cos t)/t^2 skew(w) +
/// (t - sin t)/t^3 skew(w)^2` with `t = |w|`.
pub fn right_jacobian(w: Vec3) -> Matrix3 {
    let theta = w.norm();
    let k = skew(w);
    let k2 = multiply(&k, &k);
    let (b, c) = if theta < 1e-4 {
        (
            0.5 - theta * theta / 24.0,
            1.0 / 6.0 - theta * theta / 120.0,
        )
    } else {
        let t2 = theta * theta;
        (
            (1.0 - theta.cos()) / t2,
            (theta - theta.sin()) / (t2 * theta),
        )
    };
    std::array::from_fn(|i| std::array::from_fn(|j| IDENTITY[i][j] - b * k[i][j] + c * k2[i][j]))
}

/// The derivative of `exp(w) v` with respect to `w`, given `r = exp(w)` and `jr =
/// right_jacobian(w)` (a caller applying one rotation to several vectors computes them once):
/// `-r skew(v) jr`.
pub fn apply_derivative(r: &Matrix3, jr: &Matrix3, v: Vec3) -> Matrix3 {
    let m = multiply(&multiply(r, &skew(v)), jr);
    std::array::from_fn(|i| std::array::from_fn(|j| -m[i][j]))
}

/// The rotation whose columns are the orthonormal frame `(t, n x t, n)` for a unit `n` and a
/// unit `t` orthogonal to it.
pub fn frame(t: Vec3, n: Vec3) -> Matrix3 {
    let s = n.cross(t);
    [[t.x, s.x, n.x], [t.y, s.y, n.y], [t.z, s.z, n.z]]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// exp turns about its vector by its length, and the derivative of exp(w) v matches central
    /// differences, near zero and far from it.
    #[test]
    fn the_exponential_and_its_derivative() {
        let q = exp(Vec3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2));
        let turned = apply(&q, Vec3::new(1.0, 0.0, 0.0));
        assert!(
            (turned - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-12,
            "{turned:?}"
        );
        let v = Vec3::new(0.3, -0.7, 0.5);
        for w in [
            Vec3::new(1e-9, 0.0, 0.0),
            Vec3::new(0.4, -1.1, 0.8),
            Vec3::new(2e-5, 1e-5, -3e-5),
        ] {
            let d = apply_derivative(&exp(w), &right_jacobian(w), v);
            let h = 1e-6;
            for j in 0..3 {
                let mut e = [0.0; 3];
                e[j] = h;
                let step = Vec3::new(e[0], e[1], e[2]);
                let fd = (apply(&exp(w + step), v) - apply(&exp(w - step), v)) * (0.5 / h);
                let col = Vec3::new(d[0][j], d[1][j], d[2][j]);
                assert!(
                    (fd - col).norm() < 1e-8,
                    "w {w:?} column {j}: {fd:?} vs {col:?}"
                );
            }
        }
    }
}
