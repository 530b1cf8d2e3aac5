//! Orthographic views: a rotation taking model coordinates to screen (x right, y up, z toward
//! the viewer). `auto` picks the view from the shape itself.

use crate::geometry::{smallest_eigenvector, sum_of_outer_products, Vec3};
use std::str::FromStr;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// Along the shape's direction of least bending, from 30 degrees above it: a vault shows
    /// its arch; a saddle is seen a third of the way between its principal directions, so that
    /// its rising and falling edges both show.
    Auto,
    Top,
    Front,
    Side,
    Iso,
}

impl FromStr for View {
    type Err = String;
    fn from_str(s: &str) -> Result<View, String> {
        match s {
            "auto" => Ok(View::Auto),
            "top" => Ok(View::Top),
            "front" => Ok(View::Front),
            "side" => Ok(View::Side),
            "iso" => Ok(View::Iso),
            _ => Err(format!(
                "unknown view '{s}': expected auto, top, front, side or iso"
            )),
        }
    }
}

/// Screen axes in model coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub right: Vec3,
    pub up: Vec3,
    /// From the scene toward the viewer.
    pub toward: Vec3,
}

impl Camera {
    /// A camera looking back along `toward`, with `upward` as close to screen up as it can be.
    fn looking(toward: Vec3, upward: Vec3) -> Camera {
        let toward = toward.normalized();
        let mut right = upward.cross(toward);
        if right.norm() < 1e-9 {
            right = toward.any_orthogonal();
        }
        let right = right.normalized();
        Camera {
            right,
            up: toward.cross(right),
            toward,
        }
    }

    /// (screen x, screen y, depth toward the viewer).
    pub fn project(&self, p: Vec3) -> Vec3 {
        Vec3::new(p.dot(self.right), p.dot(self.up), p.dot(self.toward))
    }
}

impl View {
    /// The camera for a shape with these points (used by `Auto` only).
    pub fn camera(self, points: &[Vec3]) -> Camera {
        let (x, y, z) = (
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        );
        match self {
            View::Top => Camera::looking(z, y),
            View::Front => Camera::looking(-y, z),
            View::Side => Camera::looking(x, z),
            View::Iso => Camera::looking(Vec3::new(1.0, -1.0, 1.0), z),
            View::Auto => auto_camera(points),
        }
    }
}

/// Fits the shape's height over its best plane with a quadric and looks along the quadric's
/// direction of least bending, 30 degrees above the plane, with the plane's normal up.
fn auto_camera(points: &[Vec3]) -> Camera {
    let z = Vec3::new(0.0, 0.0, 1.0);
    if points.len() < 6 {
        return View::Iso.camera(points);
    }
    let centre = points.iter().fold(Vec3::ZERO, |s, &p| s + p) * (1.0 / points.len() as f64);
    let mut normal =
        smallest_eigenvector(sum_of_outer_products(points.iter().map(|&p| p - centre)));
    // A roof is seen from above: the normal points up, or (a wall-like shape) toward -y.
    if normal.dot(z) < 0.0 || (normal.dot(z).abs() < 1e-6 && normal.y > 0.0) {
        normal = -normal;
    }
    let u = normal.any_orthogonal().normalized();
    let v = normal.cross(u);
    // In units of the shape's size, so that the fit's conditioning does not depend on the
    // model's units.
    let size = (points
        .iter()
        .map(|&p| (p - centre).norm_squared())
        .sum::<f64>()
        / points.len() as f64)
        .sqrt()
        .max(1e-300);
    // Height h = a x^2 + b xy + c y^2 + d x + e y + f over the plane, by least squares.
    let mut m = [[0.0; 7]; 6];
    for &p in points {
        let d = (p - centre) * (1.0 / size);
        let (px, py, h) = (d.dot(u), d.dot(v), d.dot(normal));
        let row = [px * px, px * py, py * py, px, py, 1.0];
        for i in 0..6 {
            for j in 0..6 {
                m[i][j] += row[i] * row[j];
            }
            m[i][6] += row[i] * h;
        }
    }
    let Some(q) = solve6(m) else {
        return View::Iso.camera(points);
    };
    // The Hessian [[2a, b], [b, 2c]] and its principal directions (e_least bends least).
    let (a, b, c) = (2.0 * q[0], q[1], 2.0 * q[2]);
    let mean = 0.5 * (a + c);
    let spread = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    let (k1, k2) = (mean + spread, mean - spread);
    let least = if k1.abs() < k2.abs() { k1 } else { k2 };
    // (b, least - a) solves (H - least) e = 0 unless b = 0, where the axes are the eigenvectors.
    let (ex, ey) = if b.abs() > 1e-12 * (a.abs() + c.abs()).max(1e-300) {
        (b, least - a)
    } else if (a - least).abs() <= (c - least).abs() {
        (1.0, 0.0)
    } else {
        (0.0, 1.0)
    };
    let e_least = (u * ex + v * ey).normalized();
    let e_most = normal.cross(e_least);
    // A saddle seen along a principal direction shows one profile only (a vault or a trough),
    // and halfway between them reads as a funnel: a third of the way shows both.
    let saddle = k1 * k2 < 0.0 && k1.abs().min(k2.abs()) > 0.2 * k1.abs().max(k2.abs());
    let mut along = if saddle {
        (e_least * 60f64.to_radians().cos() + e_most * 60f64.to_radians().sin()).normalized()
    } else {
        e_least
    };
    // Of the two ends, the viewer stands on the one toward -y (a front view's side).
    if along.dot(Vec3::new(0.0, -1.0, 0.0)) < 0.0 {
        along = -along;
    }
    let elevation = 30f64.to_radians();
    Camera::looking(along * elevation.cos() + normal * elevation.sin(), normal)
}

/// Solves a 6x6 system given as rows `[m | rhs]` by Gaussian elimination with partial
/// pivoting; `None` when it is singular (points on a line or a conic).
fn solve6(mut m: [[f64; 7]; 6]) -> Option<[f64; 6]> {
    let scale = m
        .iter()
        .flat_map(|r| r[..6].iter())
        .fold(0.0f64, |s, x| s.max(x.abs()));
    for col in 0..6 {
        let pivot = (col..6).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        if m[pivot][col].abs() <= 1e-12 * scale {
            return None;
        }
        m.swap(col, pivot);
        let pivot_row = m[col];
        for row in m.iter_mut().skip(col + 1) {
            let f = row[col] / pivot_row[col];
            for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
        }
    }
    let mut x = [0.0; 6];
    for row in (0..6).rev() {
        let s: f64 = (row + 1..6).map(|k| m[row][k] * x[k]).sum();
        x[row] = (m[row][6] - s) / m[row][row];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(height: impl Fn(f64, f64) -> f64) -> Vec<Vec3> {
        let mut points = Vec::new();
        for i in -10..=10 {
            for j in -10..=10 {
                let (x, y) = (i as f64 / 10.0, j as f64 / 10.0);
                points.push(Vec3::new(x, y, height(x, y)));
            }
        }
        points
    }

    #[test]
    fn a_vault_is_seen_along_its_axis_and_a_saddle_along_a_principal_direction() {
        // A barrel along y: the view looks along y, so the arch shows.
        let vault = View::Auto.camera(&grid(|x, _| -0.4 * x * x));
        assert!(vault.toward.y.abs() > 0.8, "{vault:?}");
        assert!(vault.up.z > 0.8 && vault.right.x.abs() > 0.99);
        // A saddle z = x^2 - y^2 turned 20 degrees: a third of the way between its principal
        // directions, not along one (a vault) or halfway (a funnel).
        let turn = 20f64.to_radians();
        let saddle = View::Auto.camera(&grid(|x, y| {
            let (a, b) = (
                x * turn.cos() + y * turn.sin(),
                -x * turn.sin() + y * turn.cos(),
            );
            0.3 * (a * a - b * b)
        }));
        let azimuth = saddle
            .toward
            .y
            .atan2(saddle.toward.x)
            .to_degrees()
            .rem_euclid(90.0);
        let off = (azimuth - 20.0).rem_euclid(90.0);
        assert!(
            (off - 30.0).abs() < 1.0 || (off - 60.0).abs() < 1.0,
            "{azimuth} {saddle:?}"
        );
        assert!(
            (saddle.toward.z - 0.5).abs() < 1e-6,
            "30 degrees above: {saddle:?}"
        );
    }

    #[test]
    fn the_auto_view_does_not_depend_on_the_units() {
        let saddle = |k: f64| {
            grid(|x, y| 0.3 * (x * x - y * y))
                .iter()
                .map(|&p| p * k)
                .collect::<Vec<_>>()
        };
        let metres = View::Auto.camera(&saddle(1.0));
        for k in [1e-3, 1e3, 1e6] {
            let c = View::Auto.camera(&saddle(k));
            assert!((c.toward - metres.toward).norm() < 1e-9, "{k}: {c:?}");
        }
        assert!((metres.toward - View::Iso.camera(&[]).toward).norm() > 0.1);
    }

    #[test]
    fn named_views_are_rotations() {
        for view in [View::Top, View::Front, View::Side, View::Iso, View::Auto] {
            let c = view.camera(&grid(|x, y| x * y));
            assert!((c.right.cross(c.up) - c.toward).norm() < 1e-12, "{view:?}");
        }
    }
}
