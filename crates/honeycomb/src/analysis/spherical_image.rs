//! The spherical image of a honeycomb (paper section 2): node axes as points on the unit
//! sphere, cells as spherical polygons. Every cell's oriented area is `2 pi R - sum of turns`,
//! and with walls at 120 degrees both terms are multiples of pi/3: so is the area, and
//! Proposition 1 follows (0, or at least pi/3 in absolute value).

use super::spherical_area::{oriented_area, total_turning};
use crate::geometry::Vec3;
use serde::Serialize;
use std::collections::BTreeMap;
use std::f64::consts::PI;

#[derive(Clone, Debug, Serialize)]
pub struct CellImage {
    pub cell: usize,
    /// Oriented area (steradians), counted with winding number.
    pub area: f64,
    /// The nearest multiple of pi/3, `round(area / (pi/3))`.
    pub multiple: i64,
    /// Sum of the turning angles of the cell's spherical polygon (radians).
    pub turning: f64,
    /// Rotation number `R = (area + turning) / 2 pi`, an integer for a closed polygon.
    pub rotation: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct SphericalImage {
    pub cells: usize,
    /// Cells by the multiple of pi/3 their area is closest to.
    pub histogram: BTreeMap<i64, usize>,
    /// Cells with |area| <= tolerance.
    pub zero_area_cells: usize,
    /// Share of zero-area cells: high for the curve-like images of Property 2.
    pub zero_area_share: f64,
    /// Tolerance (steradians) used for "zero" and for the violations below.
    pub tolerance: f64,
    /// Cells with tolerance < |area| < pi/3 - tolerance (Proposition 1 says there are none).
    pub proposition1_violations: Vec<usize>,
    /// Largest distance of an area from its nearest multiple of pi/3.
    pub max_deviation_from_multiple: f64,
    /// Property 2, measured per cell: the mean of `1 - l2/l1` over cells, with `l1 >= l2` the
    /// principal variances of the cell's axis points in the plane tangent at their mean. Near 1
    /// the cells' images are thin (the zigzag hexagons of a curve-like image, paper Fig. 5),
    /// near 0 round (axes spreading like a doubly curved surface's normals).
    /// `None` when every cell is point-like.
    pub curve_likeness: Option<f64>,
    /// Cells whose axes all coincide (their image is a point), left out of `curve_likeness`.
    pub point_like_cells: usize,
    /// Every cell's area, multiple of pi/3, turning and rotation number.
    pub per_cell: Vec<CellImage>,
}

pub fn spherical_image(faces: &[Vec<usize>], axes: &[Vec3], tolerance: f64) -> SphericalImage {
    let third = PI / 3.0;
    let per_cell: Vec<CellImage> = faces
        .iter()
        .enumerate()
        .map(|(cell, f)| {
            let points: Vec<Vec3> = f.iter().map(|&v| axes[v]).collect();
            let area = oriented_area(&points);
            let turning = total_turning(&points);
            CellImage {
                cell,
                area,
                multiple: (area / third).round() as i64,
                turning,
                rotation: (area + turning) / (2.0 * PI),
            }
        })
        .collect();
    let mut histogram = BTreeMap::new();
    for c in &per_cell {
        *histogram.entry(c.multiple).or_insert(0) += 1;
    }
    let zero_area_cells = per_cell
        .iter()
        .filter(|c| c.area.abs() <= tolerance)
        .count();
    let proposition1_violations = per_cell
        .iter()
        .filter(|c| c.area.abs() > tolerance && c.area.abs() < third - tolerance)
        .map(|c| c.cell)
        .collect();
    let max_deviation_from_multiple = per_cell
        .iter()
        .map(|c| (c.area - c.multiple as f64 * third).abs())
        .fold(0.0, f64::max);
    let shapes: Vec<Option<f64>> = faces
        .iter()
        .map(|f| anisotropy(&f.iter().map(|&v| axes[v]).collect::<Vec<_>>()))
        .collect();
    let thin: Vec<f64> = shapes.iter().flatten().copied().collect();
    SphericalImage {
        curve_likeness: (!thin.is_empty()).then(|| thin.iter().sum::<f64>() / thin.len() as f64),
        point_like_cells: shapes.len() - thin.len(),
        cells: per_cell.len(),
        histogram,
        zero_area_cells,
        zero_area_share: zero_area_cells as f64 / per_cell.len().max(1) as f64,
        tolerance,
        proposition1_violations,
        max_deviation_from_multiple,
        per_cell,
    }
}

/// `1 - l2/l1` of the points' spread in the plane tangent at their mean direction, or `None`
/// when they (nearly) coincide.
fn anisotropy(points: &[Vec3]) -> Option<f64> {
    let mean = points.iter().fold(Vec3::ZERO, |s, &p| s + p);
    if mean.norm() < 1e-12 {
        return None;
    }
    let n = mean.normalized();
    let (u, w) = (n.any_orthogonal(), n.cross(n.any_orthogonal()));
    let uv: Vec<(f64, f64)> = points.iter().map(|p| (p.dot(u), p.dot(w))).collect();
    let k = uv.len() as f64;
    let (mu, mw) = uv
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / k, b + p.1 / k));
    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
    for (x, y) in &uv {
        let (dx, dy) = (x - mu, y - mw);
        a += dx * dx;
        b += dx * dy;
        c += dy * dy;
    }
    let half_trace = 0.5 * (a + c);
    let root = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    let (l1, l2) = (half_trace + root, half_trace - root);
    (l1 > 1e-20).then(|| 1.0 - (l2 / l1).max(0.0))
}
