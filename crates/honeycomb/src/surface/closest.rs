//! Exact closest points on the two primitives of the reference surface: triangles and segments.

use crate::geometry::Vec3;

/// Below this squared sine of the angle at `a`, a triangle is treated as flat (a union of
/// edges): the region formulas would divide by a vanishing area. The shape error of doing so
/// is at most the triangle's height, 1e-10 of its edge length.
const FLAT_SIN2: f64 = 1e-20;

/// The point of segment `ab` closest to `p`, with its parameter `t` (`a + t (b - a)`).
/// A zero-length segment answers `a`.
pub fn closest_point_on_segment(p: Vec3, a: Vec3, b: Vec3) -> (Vec3, f64) {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 <= 0.0 {
        return (a, 0.0);
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    // Return the endpoints exactly rather than `a + 1.0 * ab`, which may be off by rounding.
    let q = if t >= 1.0 { b } else { a + ab * t };
    (q, t)
}

/// The point of triangle `abc` closest to `p`, with its barycentric weights `[wa, wb, wc]`
/// (non-negative, summing to 1).
///
/// Follows the Voronoi-region classification of Ericson (Real-Time Collision Detection,
/// 5.1.5): vertex regions, then edge regions, then the interior. Zero-area and near-zero-area
/// triangles are answered as the union of their edges, so no division by zero can occur.
pub fn closest_point_on_triangle(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> (Vec3, [f64; 3]) {
    let ab = b - a;
    let ac = c - a;
    let n2 = ab.cross(ac).norm_squared();
    if n2 <= FLAT_SIN2 * ab.norm_squared() * ac.norm_squared() {
        return closest_on_edges(p, [a, b, c]);
    }

    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, [1.0, 0.0, 0.0]);
    }

    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, [0.0, 1.0, 0.0]);
    }

    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = ratio(d1, d1 - d3);
        return (a + ab * v, [1.0 - v, v, 0.0]);
    }

    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, [0.0, 0.0, 1.0]);
    }

    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = ratio(d2, d2 - d6);
        return (a + ac * w, [1.0 - w, 0.0, w]);
    }

    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        let w = ratio(d4 - d3, (d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, [0.0, 1.0 - w, w]);
    }

    // Interior. In exact arithmetic va, vb, vc > 0 here; clamping keeps the answer on the
    // triangle when rounding disagrees for very thin triangles.
    let (va, vb, vc) = (va.max(0.0), vb.max(0.0), vc.max(0.0));
    let sum = va + vb + vc;
    if sum <= 0.0 {
        return closest_on_edges(p, [a, b, c]);
    }
    let (v, w) = (vb / sum, vc / sum);
    (a + ab * v + ac * w, [1.0 - v - w, v, w])
}

/// `num / den` for `0 <= num <= den`, clamped to [0, 1]; 0 when `den` vanishes.
fn ratio(num: f64, den: f64) -> f64 {
    if den > 0.0 {
        (num / den).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Closest point over the three edges: exact for a flat triangle, whose point set is the
/// union of its edges.
fn closest_on_edges(p: Vec3, v: [Vec3; 3]) -> (Vec3, [f64; 3]) {
    let mut best = (v[0], [1.0, 0.0, 0.0]);
    let mut best_d2 = (p - v[0]).norm_squared();
    for i in 0..3 {
        let j = (i + 1) % 3;
        let (q, t) = closest_point_on_segment(p, v[i], v[j]);
        let d2 = (p - q).norm_squared();
        if d2 < best_d2 {
            let mut w = [0.0; 3];
            w[i] = 1.0 - t;
            w[j] = t;
            best = (q, w);
            best_d2 = d2;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random numbers in [-1, 1) (SplitMix64).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
        fn vec(&mut self) -> Vec3 {
            Vec3::new(self.next(), self.next(), self.next())
        }
    }

    /// An independent reference: project onto the plane; if the projection lies inside
    /// (barycentric weights from sub-triangle areas), that is the answer, else the best edge.
    fn reference(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> f64 {
        let n = (b - a).cross(c - a);
        let q = p - n * ((p - a).dot(n) / n.norm_squared());
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| (v - u).cross(q - u).dot(n) >= 0.0);
        if inside {
            return (p - q).norm();
        }
        [(a, b), (b, c), (c, a)]
            .iter()
            .map(|&(u, v)| (p - closest_point_on_segment(p, u, v).0).norm())
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn triangle_matches_projection_reference() {
        let mut rng = Rng(7);
        for _ in 0..20_000 {
            let (a, b, c) = (rng.vec(), rng.vec(), rng.vec());
            let p = rng.vec() * 2.0;
            let (q, w) = closest_point_on_triangle(p, a, b, c);
            assert!(((p - q).norm() - reference(p, a, b, c)).abs() < 1e-12);
            assert!(w.iter().all(|&x| (0.0..=1.0).contains(&x)));
            assert!((w[0] + w[1] + w[2] - 1.0).abs() < 1e-12);
            assert!((a * w[0] + b * w[1] + c * w[2] - q).norm() < 1e-12);
        }
    }

    #[test]
    fn degenerate_triangles_are_finite() {
        let mut rng = Rng(11);
        for _ in 0..1000 {
            let (a, b, p) = (rng.vec(), rng.vec(), rng.vec());
            let cases = [
                (a, a, a),             // a point
                (a, a, b),             // two coincident corners
                (a, b, (a + b) * 0.5), // collinear
                (a, b, a * 2.0 - b),   // collinear, c outside ab
            ];
            for (x, y, z) in cases {
                let (q, w) = closest_point_on_triangle(p, x, y, z);
                assert!(q.is_finite() && w.iter().all(|v| v.is_finite()));
                // The flat triangle is its longest edge: compare with the segment answer.
                let best = [(x, y), (y, z), (z, x)]
                    .iter()
                    .map(|&(u, v)| (p - closest_point_on_segment(p, u, v).0).norm())
                    .fold(f64::INFINITY, f64::min);
                assert!(((p - q).norm() - best).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn segment_endpoints_and_interior() {
        let (a, b) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0));
        assert_eq!(
            closest_point_on_segment(Vec3::new(-1.0, 1.0, 0.0), a, b),
            (a, 0.0)
        );
        assert_eq!(
            closest_point_on_segment(Vec3::new(3.0, 1.0, 0.0), a, b),
            (b, 1.0)
        );
        let (q, t) = closest_point_on_segment(Vec3::new(0.5, 1.0, 2.0), a, b);
        assert_eq!((q, t), (Vec3::new(0.5, 0.0, 0.0), 0.25));
        assert_eq!(closest_point_on_segment(b, a, a), (a, 0.0));
    }
}
