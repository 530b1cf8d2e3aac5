//! Tangent-plane arithmetic shared by the fields: projecting into a vertex's tangent plane,
//! turning about its normal, and the seeded random numbers the fields start from.

use crate::geometry::Vec3;

pub const SQRT3: f64 = 1.732_050_807_568_877_2;
pub const SIN60: f64 = 0.5 * SQRT3;

/// The part of `v` in the plane with unit normal `n`.
pub fn tangential(v: Vec3, n: Vec3) -> Vec3 {
    v - n * n.dot(v)
}

/// `v` (in the plane of unit normal `n`) turned by the angle with this cosine and sine,
/// counter-clockwise seen from the normal's side.
pub fn turned(v: Vec3, n: Vec3, cos: f64, sin: f64) -> Vec3 {
    v * cos + n.cross(v) * sin
}

/// The unit direction of `v` in the plane of `n`, if `v` has one there.
pub fn unit_tangent(v: Vec3, n: Vec3) -> Option<Vec3> {
    let t = tangential(v, n);
    let length = t.norm();
    (length > 1e-12 * v.norm().max(1e-300) && length.is_finite()).then(|| t / length)
}

/// A unit normal that is never zero: `n` when it is a direction, else +z.
pub fn usable_normal(n: Vec3) -> Vec3 {
    let u = n.normalized();
    if u.norm_squared() > 0.5 && u.is_finite() {
        u
    } else {
        Vec3::new(0.0, 0.0, 1.0)
    }
}

/// splitmix64: a tiny, well-mixed generator, so that one seed always gives one mesh.
pub struct SplitMix(u64);

impl SplitMix {
    pub fn new(seed: u64) -> SplitMix {
        SplitMix(seed ^ 0x6A09_E667_F3BC_C909)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut x = self.0;
        x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        x ^ (x >> 31)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A uniformly random unit direction in the plane of `n`.
    pub fn tangent(&mut self, n: Vec3) -> Vec3 {
        let e1 = n.any_orthogonal();
        let e2 = n.cross(e1);
        let (sin, cos) = (std::f64::consts::TAU * self.unit()).sin_cos();
        e1 * cos + e2 * sin
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turning_by_sixty_degrees_six_times_comes_back() {
        let n = Vec3::new(1.0, 2.0, 2.0).normalized();
        let v = n.any_orthogonal();
        let mut w = v;
        for _ in 0..6 {
            w = turned(w, n, 0.5, SIN60);
            assert!((w.dot(n)).abs() < 1e-12);
        }
        assert!((w - v).norm() < 1e-12);
        let w = turned(v, n, 0.5, SIN60);
        assert!((v.dot(w) - 0.5).abs() < 1e-12);
        // Counter-clockwise seen from the normal: v x w points along n.
        assert!(v.cross(w).dot(n) > 0.0);
    }

    #[test]
    fn the_same_seed_gives_the_same_numbers() {
        let (mut a, mut b, mut c) = (SplitMix::new(7), SplitMix::new(7), SplitMix::new(8));
        let xs: Vec<f64> = (0..5).map(|_| a.unit()).collect();
        let ys: Vec<f64> = (0..5).map(|_| b.unit()).collect();
        let zs: Vec<f64> = (0..5).map(|_| c.unit()).collect();
        assert_eq!(xs, ys);
        assert_ne!(xs, zs);
        assert!(xs.iter().all(|x| (0.0..1.0).contains(x)));
    }
}
