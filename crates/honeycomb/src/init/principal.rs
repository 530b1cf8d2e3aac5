//! The direction in which S twists least, for a lattice whose straight polylines should carry
//! planar quads.
//!
//! A hexagon split by its long diagonal gives two trapezoids. With its corners on S, such a
//! trapezoid is planar to second order exactly when S's twist `II(t, t_perp)` vanishes along the
//! diagonal's direction `t`, that is when the diagonal follows a principal direction of S (the
//! affine dependency of a symmetric trapezoid's corners weighs them 1, -2, 2, -1, which cancels
//! every term of the second fundamental form but the twist). The long diagonals run along a
//! lattice edge direction, so a lattice turned to follow S's principal directions caps best.

use super::Point2;
use crate::geometry::Vec3;
use crate::surface::normals;

/// Below this agreement of S's principal directions (1: the same everywhere, weighted by
/// anisotropy; 0: spread evenly) no one direction follows them: a lattice turned to follow
/// them would do no better than one turned at random.
const MIN_AGREEMENT: f64 = 0.5;

/// The direction (radians, modulo 90 degrees, in the plane of `points`) that makes the
/// area-weighted mean square twist of S least: the 4-fold mean of the principal directions,
/// each triangle weighted by the square of its curvature anisotropy. `None` where S does not
/// prefer one: a plane, a sphere, or principal directions that turn over S.
///
/// `vertices`, `triangles`: S; `points`: where each vertex went in the flattening.
pub fn least_twist_direction(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    points: &[Point2],
) -> Option<f64> {
    let normals = normals::vertex_normals(
        vertices,
        triangles,
        &normals::face_normals(vertices, triangles),
    );
    // The sum of area * twist(theta)^2 is a constant + c cos(4 theta) + s sin(4 theta).
    let (mut c, mut s, mut anisotropy, mut curving) = (0.0, 0.0, 0.0, 0.0);
    for &[i, j, k] in triangles {
        let Some(form) = second_fundamental_form(
            [vertices[i], vertices[j], vertices[k]],
            [normals[i], normals[j], normals[k]],
            [points[i], points[j], points[k]],
        ) else {
            continue;
        };
        let area = 0.5
            * (vertices[j] - vertices[i])
                .cross(vertices[k] - vertices[i])
                .norm();
        // The twist along theta: half_difference sin(2 theta) + off cos(2 theta).
        let (half_difference, off) = (0.5 * (form[1][1] - form[0][0]), form[0][1]);
        c += area * 0.5 * (off * off - half_difference * half_difference);
        s += area * half_difference * off;
        anisotropy += area * (half_difference * half_difference + off * off);
        curving += area * (form[0][0].powi(2) + 2.0 * off * off + form[1][1].powi(2));
    }
    // `curving` is dimensionless (an area times a squared curvature): roundoff on a plane.
    let umbilic = curving < 1e-12 || anisotropy < 1e-2 * curving;
    let agreement = 2.0 * (c * c + s * s).sqrt() / anisotropy;
    (!umbilic && agreement >= MIN_AGREEMENT).then(|| (-s).atan2(-c) / 4.0)
}

/// A triangle's second fundamental form in the coordinates of its flattened image
/// (symmetric), from how the normal turns along its edges: `dN = -II` read through the affine
/// map from the plane to the triangle. `None` for a degenerate image.
fn second_fundamental_form(p: [Vec3; 3], n: [Vec3; 3], u: [Point2; 3]) -> Option<[[f64; 2]; 2]> {
    let du = [
        [u[1][0] - u[0][0], u[1][1] - u[0][1]],
        [u[2][0] - u[0][0], u[2][1] - u[0][1]],
    ];
    let det = du[0][0] * du[1][1] - du[1][0] * du[0][1];
    if !det.is_finite() || det.abs() < 1e-300 {
        return None;
    }
    // Columns of d/du (x and y) of a quantity with differences dq[0], dq[1] along the edges.
    let gradient = |dq: [Vec3; 2]| {
        let x = (dq[0] * du[1][1] - dq[1] * du[0][1]) / det;
        let y = (dq[1] * du[0][0] - dq[0] * du[1][0]) / det;
        [x, y]
    };
    let tangent = gradient([p[1] - p[0], p[2] - p[0]]);
    let turn = gradient([n[1] - n[0], n[2] - n[0]]);
    let entry = |a: usize, b: usize| -tangent[a].dot(turn[b]);
    let off = 0.5 * (entry(0, 1) + entry(1, 0));
    let form = [[entry(0, 0), off], [off, entry(1, 1)]];
    form.iter().flatten().all(|x| x.is_finite()).then_some(form)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A height field over [-1/2, 1/2]^2, flattened by dropping z.
    fn grid(height: impl Fn(f64, f64) -> f64) -> (Vec<Vec3>, Vec<[usize; 3]>, Vec<Point2>) {
        let (vertices, triangles) =
            super::super::flatten::lifted_grid(24, |x, y| height(x - 0.5, y - 0.5));
        let points = vertices.iter().map(|v| [v.x - 0.5, v.y - 0.5]).collect();
        (vertices, triangles, points)
    }

    /// The angle between two directions modulo 90 degrees, in degrees.
    fn off_mod_90(a: f64, b: f64) -> f64 {
        let d = (a - b).to_degrees().rem_euclid(90.0);
        d.min(90.0 - d)
    }

    #[test]
    fn the_least_twist_follows_the_principal_directions() {
        // z = (x^2 - y^2) / 2 turned by 25 degrees: principal directions at 25 and 115.
        let t = 25f64.to_radians();
        let (vertices, triangles, points) = grid(|x, y| {
            let (a, b) = (x * t.cos() + y * t.sin(), -x * t.sin() + y * t.cos());
            0.5 * (a * a - b * b)
        });
        let theta = least_twist_direction(&vertices, &triangles, &points).unwrap();
        assert!(off_mod_90(theta, t) < 1.0, "{}", theta.to_degrees());
        // A cylinder's rulings (along y) and its bending direction (x).
        let (vertices, triangles, points) = grid(|x, _| 0.4 * x * x);
        let theta = least_twist_direction(&vertices, &triangles, &points).unwrap();
        assert!(off_mod_90(theta, 0.0) < 1.0, "{}", theta.to_degrees());
    }

    #[test]
    fn principal_directions_that_turn_over_s_give_none() {
        // Saddles turned by 0 and 45 degrees side by side, each with half of S.
        let (vertices, triangles, points) = grid(|x, y| {
            if x < 0.0 {
                0.5 * (x * x - y * y)
            } else {
                x * y
            }
        });
        assert_eq!(least_twist_direction(&vertices, &triangles, &points), None);
    }

    #[test]
    fn a_plane_and_a_sphere_prefer_no_direction() {
        let (vertices, triangles, points) = grid(|x, y| 0.3 * x - 0.1 * y);
        assert_eq!(least_twist_direction(&vertices, &triangles, &points), None);
        let (vertices, triangles, points) = grid(|x, y| (25.0 - x * x - y * y).sqrt());
        assert_eq!(least_twist_direction(&vertices, &triangles, &points), None);
    }
}
