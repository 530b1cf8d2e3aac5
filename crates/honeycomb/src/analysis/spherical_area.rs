//! Oriented area of a spherical polygon, counted with its winding number (paper eq. (3)).

use crate::geometry::Vec3;

/// Signed area of the spherical triangle `a b c` (unit vectors), positive when counter-clockwise
/// seen from outside the sphere (Van Oosterom and Strackee): in (-2 pi, 2 pi).
pub fn triangle_area(a: Vec3, b: Vec3, c: Vec3) -> f64 {
    let numerator = a.dot(b.cross(c));
    let denominator = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
    2.0 * numerator.atan2(denominator)
}

/// Oriented area `integral of w(x)` of the closed spherical polygon through `points` (unit
/// vectors), with `w` the winding number. Summed as a fan of signed triangles from the
/// polygon's mean direction; on the sphere the result is defined up to multiples of 4 pi, and
/// this choice gives the small one for a polygon within a hemisphere, as the node axes of one
/// cell are.
pub fn oriented_area(points: &[Vec3]) -> f64 {
    let mut mean = Vec3::ZERO;
    for &p in points {
        mean += p;
    }
    let pole = if mean.norm() > 1e-12 {
        mean.normalized()
    } else {
        points[0].any_orthogonal()
    };
    (0..points.len())
        .map(|k| triangle_area(pole, points[k], points[(k + 1) % points.len()]))
        .sum()
}

/// Sum of the signed turning angles of the closed spherical polygon (counter-clockwise seen
/// from outside positive). With the oriented area it gives the rotation number, eq. (3):
/// `area = 2 pi R - sum of turns`.
pub fn total_turning(points: &[Vec3]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|k| {
            let (a, b, c) = (points[(k + n - 1) % n], points[k], points[(k + 1) % n]);
            // Arriving direction continued past b, and leaving direction, both tangent at b.
            let t1 = (b * a.dot(b) - a).normalized();
            let t2 = (c - b * c.dot(b)).normalized();
            b.dot(t1.cross(t2)).atan2(t1.dot(t2))
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A regular spherical n-gon around the north pole at polar angle `theta`, counter-clockwise.
    fn regular(n: usize, theta: f64) -> Vec<Vec3> {
        (0..n)
            .map(|k| {
                let phi = 2.0 * PI * k as f64 / n as f64;
                Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                )
            })
            .collect()
    }

    /// Interior angle of a spherical polygon at vertex `k` (between the great circles).
    fn interior_angle(p: &[Vec3], k: usize) -> f64 {
        let n = p.len();
        let (a, b, c) = (p[(k + n - 1) % n], p[k], p[(k + 1) % n]);
        let ta = (a - b * a.dot(b)).normalized();
        let tc = (c - b * c.dot(b)).normalized();
        ta.dot(tc).clamp(-1.0, 1.0).acos()
    }

    #[test]
    fn a_pentagon_with_sixty_degree_turns_has_area_pi_over_three() {
        // Find the regular pentagon whose interior angles are 120 degrees (turns of 60), the
        // paper's example after eq. (1): 5 * pi/3 = 2 pi - area, so area = pi/3.
        let (mut lo, mut hi) = (0.01, 1.5);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if interior_angle(&regular(5, mid), 0) < 2.0 * PI / 3.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let pentagon = regular(5, lo);
        assert!((interior_angle(&pentagon, 2) - 2.0 * PI / 3.0).abs() < 1e-9);
        let area = oriented_area(&pentagon);
        assert!((area - PI / 3.0).abs() < 1e-9, "{area}");
        // Five turns of 60 degrees, rotation number 1: pi/3 = 2 pi - 5 pi/3.
        let turning = total_turning(&pentagon);
        assert!((turning - 5.0 * PI / 3.0).abs() < 1e-9, "{turning}");
        // Reversed orientation, negative area.
        let mut reversed = pentagon.clone();
        reversed.reverse();
        assert!((oriented_area(&reversed) + PI / 3.0).abs() < 1e-9);
    }

    #[test]
    fn an_octant_and_a_figure_eight() {
        let (x, y, z) = (
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        );
        assert!((oriented_area(&[x, y, z]) - PI / 2.0).abs() < 1e-12);
        // A figure eight of two equal loops wound oppositely encloses zero oriented area.
        let t = 0.2f64;
        let p = |u: f64, v: f64| Vec3::new(u, v, 1.0).normalized();
        let eight = [p(0.0, 0.0), p(t, t), p(2.0 * t, 0.0), p(t, -t), p(0.0, 0.0)];
        let eight = [
            eight[0],
            eight[1],
            eight[2],
            eight[3],
            p(-t, t),
            p(-2.0 * t, 0.0),
            p(-t, -t),
        ];
        assert!(
            oriented_area(&eight).abs() < 1e-12,
            "{}",
            oriented_area(&eight)
        );
    }
}
