//! Distance between two line segments (used for the planarity of quads: the distance between
//! their diagonals).

use super::Vec3;

/// The shortest distance between segments `p0 p1` and `q0 q1`.
pub fn segment_distance(p0: Vec3, p1: Vec3, q0: Vec3, q1: Vec3) -> f64 {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.dot(d1), d2.dot(d2), d2.dot(r));
    let tiny = 1e-300;
    let (s, t);
    if a <= tiny && e <= tiny {
        return r.norm();
    }
    if a <= tiny {
        s = 0.0;
        t = (f / e).clamp(0.0, 1.0);
    } else {
        let c = d1.dot(r);
        if e <= tiny {
            t = 0.0;
            s = (-c / a).clamp(0.0, 1.0);
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let s0 = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let t0 = (b * s0 + f) / e;
            if t0 < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t0 > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            } else {
                t = t0;
                s = s0;
            }
        }
    }
    ((p0 + d1 * s) - (q0 + d2 * t)).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_skew_and_parallel_segments() {
        let o = Vec3::ZERO;
        let x = Vec3::new(1.0, 0.0, 0.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        let z = Vec3::new(0.0, 0.0, 1.0);
        // Diagonals of a planar unit square cross: distance 0.
        assert!(segment_distance(o, x + y, x, y) < 1e-15);
        // Lifted by 0.25 across: the distance of the skew diagonals.
        assert!((segment_distance(o, x + y, x + z * 0.25, y + z * 0.25) - 0.25).abs() < 1e-15);
        // Parallel segments one apart.
        assert!((segment_distance(o, x, y, x + y) - 1.0).abs() < 1e-15);
        // Disjoint collinear segments: gap between the ends.
        assert!((segment_distance(o, x, x * 3.0, x * 4.0) - 2.0).abs() < 1e-15);
    }
}
