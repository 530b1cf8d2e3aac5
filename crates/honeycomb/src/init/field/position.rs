//! The position field: per vertex a point p_i of its tangent plane, the origin of a local
//! triangular lattice of spacing s whose axes are o_i turned by 90 degrees (and by 60 and 120
//! more): its points are the hex cells' centres, and hex edges, perpendicular to the lattice
//! edges, run along o_i. Smoothing moves each vertex's lattice towards its neighbours': a
//! neighbour's lattice is first translated by the lattice vector that brings its point closest
//! to i's, near the point both tangent planes share, then the lattices are averaged and i's
//! origin is rounded to the lattice point nearest x_i.

use super::hierarchy::Level;
use super::tangent::{SplitMix, SIN60};
use crate::geometry::Vec3;

/// Gauss-Seidel sweeps per level (more changed little in measurements; fewer on the coarse
/// levels, whose vertices together outnumber the finest level's).
const SWEEPS_FINEST: usize = 10;
const SWEEPS_COARSE: usize = 8;

/// The lattice vector (u, v) nearest to the planar point (x, y), both in units of the spacing
/// with the first axis along x, and its distance from it.
pub fn nearest_step(x: f64, y: f64) -> ([i64; 2], f64) {
    let [u, v] = nearest_coordinates(x, y);
    if !u.is_finite() || !v.is_finite() {
        return ([0, 0], f64::INFINITY);
    }
    let (px, py) = (u + 0.5 * v, SIN60 * v);
    (
        [u as i64, v as i64],
        ((x - px).powi(2) + (y - py).powi(2)).sqrt(),
    )
}

/// [`nearest_step`]'s lattice vector as floats.
#[inline]
fn nearest_coordinates(x: f64, y: f64) -> [f64; 2] {
    let v = y / SIN60;
    let u = x - 0.5 * v;
    let (u0, v0) = (floor(u), floor(v));
    // The point lies in the lattice parallelogram at (u0, v0); its nearest lattice point is
    // one of that parallelogram's corners.
    let mut best = ([u0, v0], f64::INFINITY);
    for (du, dv) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
        let (uu, vv) = (u0 + du, v0 + dv);
        let (px, py) = (uu + 0.5 * vv, SIN60 * vv);
        let d2 = (x - px) * (x - px) + (y - py) * (y - py);
        if d2 < best.1 {
            best = ([uu, vv], d2);
        }
    }
    best.0
}

/// `x.floor()` without the library call the baseline x86-64 target makes of it (a tenth of
/// the solve's time); saturates beyond 2^63 and maps NaN to 0, which rounding then ignores.
#[inline]
fn floor(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t > x {
        t - 1.0
    } else {
        t
    }
}

/// The point of both tangent planes (through `a` with normal `na`, through `b` with normal
/// `nb`) closest to the middle of a and b; the middle itself when the planes are near
/// parallel.
pub fn middle_point(a: Vec3, na: Vec3, b: Vec3, nb: Vec3) -> Vec3 {
    let m = (a + b) * 0.5;
    let c = na.dot(nb);
    let det = 1.0 - c * c;
    if det < 1e-4 {
        return m;
    }
    let (ra, rb) = (na.dot(a - m), nb.dot(b - m));
    let la = (ra - c * rb) / det;
    let lb = (rb - c * ra) / det;
    m + na * la + nb * lb
}

/// The lattice axis of each vertex on each level: its orientation turned by 90 degrees.
pub fn axes(level: &Level, orientation: &[Vec3]) -> Vec<Vec3> {
    (0..level.len())
        .map(|i| level.normals[i].cross(orientation[i]))
        .collect()
}

/// The position field on the finest level, solved coarse to fine on the hierarchy with the
/// orientation field `fields` (one per level).
pub fn solve(levels: &[Level], fields: &[Vec<Vec3>], spacing: f64, seed: u64) -> Vec<Vec3> {
    let top = levels.len() - 1;
    let mut rng = SplitMix::new(seed.rotate_left(17) ^ 0x51_7CC1_B727_220A);
    let mut origins: Vec<Vec3> = {
        let level = &levels[top];
        let frames = Frames::new(level, &fields[top], spacing);
        (0..level.len())
            .map(|i| {
                let (a, b) = (frames.axis[i], frames.across[i]);
                level.points[i] + (a * rng.unit() + b * rng.unit()) * spacing
            })
            .collect()
    };
    for l in (0..levels.len()).rev() {
        let level = &levels[l];
        let frames = Frames::new(level, &fields[l], spacing);
        if l < top {
            origins = (0..level.len())
                .map(|i| {
                    let (x, n) = (level.points[i], level.normals[i]);
                    let p = origins[level.parent[i] as usize];
                    frames.round(i, p - n * n.dot(p - x), x)
                })
                .collect();
        }
        let sweeps = if l == 0 { SWEEPS_FINEST } else { SWEEPS_COARSE };
        for _ in 0..sweeps {
            sweep(level, &frames, &mut origins);
        }
    }
    origins
}

/// Each vertex's lattice axes in its tangent plane, and the spacing.
struct Frames {
    axis: Vec<Vec3>,
    /// The axis turned by 90 degrees about the normal.
    across: Vec<Vec3>,
    spacing: f64,
    inverse: f64,
}

impl Frames {
    fn new(level: &Level, orientation: &[Vec3], spacing: f64) -> Frames {
        let axis = axes(level, orientation);
        let across = (0..level.len())
            .map(|i| level.normals[i].cross(axis[i]))
            .collect();
        Frames {
            axis,
            across,
            spacing,
            inverse: 1.0 / spacing,
        }
    }

    /// The point nearest to `q` of vertex i's lattice moved to `origin`.
    #[inline]
    fn round(&self, i: usize, origin: Vec3, q: Vec3) -> Vec3 {
        let (a, b) = (self.axis[i], self.across[i]);
        let d = q - origin;
        let [u, v] = nearest_coordinates(d.dot(a) * self.inverse, d.dot(b) * self.inverse);
        origin + a * ((u + 0.5 * v) * self.spacing) + b * (SIN60 * v * self.spacing)
    }
}

/// One Gauss-Seidel sweep of lattice averaging.
fn sweep(level: &Level, frames: &Frames, origins: &mut [Vec3]) {
    for i in 0..level.len() {
        let (x, n) = (level.points[i], level.normals[i]);
        let mut mean = origins[i];
        let mut weight = 0.0;
        for &j in level.neighbours(i) {
            let j = j as usize;
            let shared = middle_point(x, n, level.points[j], level.normals[j]);
            let mine = frames.round(i, mean, shared);
            let theirs = frames.round(j, origins[j], mine);
            mean = (mine * weight + theirs) / (weight + 1.0);
            mean = mean - n * n.dot(mean - x);
            weight += 1.0;
        }
        origins[i] = frames.round(i, mean, x);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::field::tangent::SQRT3;

    #[test]
    fn nearest_lattice_points_and_steps() {
        assert_eq!(nearest_step(0.1, -0.2).0, [0, 0]);
        assert_eq!(nearest_step(0.9, 0.1).0, [1, 0]);
        // The second axis is at 60 degrees: (0.5, sqrt 3 / 2) is one step along it.
        assert_eq!(nearest_step(0.45, 0.8).0, [0, 1]);
        // (-0.5, sqrt 3 / 2) is one step along the second axis, one back along the first.
        assert_eq!(nearest_step(-0.55, 0.9).0, [-1, 1]);
        let (step, residual) = nearest_step(2.0 + 0.1, 0.0);
        assert_eq!(step, [2, 0]);
        assert!((residual - 0.1).abs() < 1e-12);
        // The farthest a point can be from the lattice is the circumradius 1 / sqrt 3.
        for k in 0..1000 {
            let (x, y) = (
                (k as f64 * 0.618).fract() * 5.0,
                (k as f64 * 0.377).fract() * 5.0,
            );
            assert!(nearest_step(x, y).1 <= 1.0 / SQRT3 + 1e-12);
        }
        assert_eq!(nearest_step(f64::NAN, 0.0).0, [0, 0]);
        for x in [-2.5, -2.0, -0.3, 0.0, 0.7, 3.0, 1e9 + 0.5] {
            assert_eq!(floor(x), x.floor());
        }
    }

    #[test]
    fn the_nearest_point_is_a_lattice_point_in_the_plane() {
        let normal = Vec3::new(0.0, 0.6, 0.8);
        let axis = Vec3::new(1.0, 0.0, 0.0);
        let frames = Frames {
            axis: vec![axis],
            across: vec![normal.cross(axis)],
            spacing: 0.7,
            inverse: 1.0 / 0.7,
        };
        let origin = Vec3::new(0.3, 0.2, -0.1);
        let q = Vec3::new(5.1, -2.3, 7.0);
        let p = frames.round(0, origin, q);
        assert!(normal.dot(p - origin).abs() < 1e-12);
        let d = p - origin;
        let across = normal.cross(axis);
        let ([u, v], r) = nearest_step(d.dot(axis) / 0.7, d.dot(across) / 0.7);
        assert!(r < 1e-9, "{u} {v} {r}");
        // No other lattice point is nearer to q's projection.
        let qp = q - normal * normal.dot(q - origin);
        for du in -2..=2 {
            for dv in -2..=2 {
                let other =
                    p + (axis * (du as f64 + 0.5 * dv as f64) + across * (SIN60 * dv as f64)) * 0.7;
                assert!((other - qp).norm() >= (p - qp).norm() - 1e-12);
            }
        }
    }

    #[test]
    fn the_middle_point_lies_on_both_planes() {
        let (a, na) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0));
        let (b, nb) = (
            Vec3::new(1.0, 0.0, 0.2),
            Vec3::new(-0.3, 0.0, 1.0).normalized(),
        );
        let m = middle_point(a, na, b, nb);
        assert!(na.dot(m - a).abs() < 1e-12);
        assert!(nb.dot(m - b).abs() < 1e-12);
        // Parallel planes: the midpoint.
        let m = middle_point(a, na, b, na);
        assert!((m - (a + b) * 0.5).norm() < 1e-12);
    }
}
