//! Least-squares conformal flattening (LSCM) of a triangulated surface with boundary, and the
//! distortion it leaves (the paper's Figure 6b).
//!
//! The conformal energy of a map u into the plane is its Dirichlet energy minus the area of its
//! image: E_C(u) = 1/2 u^T (L (+) L) u - A(u), with L the cotangent Laplacian and A the signed
//! area enclosed by the image of the boundary, a quadratic form in u as well. E_C >= 0 and is 0
//! exactly for conformal maps; its null space is the similarities, removed by pinning two
//! boundary vertices far apart. What remains is one sparse symmetric positive definite solve.

use crate::error::{Error, Result};
use crate::geometry::Vec3;
use faer::linalg::solvers::SolveCore;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use serde::Serialize;

/// A planar point.
pub type Point2 = [f64; 2];

/// Which flattening.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Flattener {
    /// Least-squares conformal: angles kept, sizes may swell.
    Lscm,
    /// LSCM refined as-rigid-as-possible: lengths kept as well as the surface allows.
    #[default]
    Arap,
    /// Seen along the mean normal: cells of one size in plan view, all node axes parallel
    /// (vertical walls on a roof); for surfaces that do not fold over seen from above.
    Project,
}

impl std::str::FromStr for Flattener {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Flattener, String> {
        match s {
            "lscm" => Ok(Flattener::Lscm),
            "arap" => Ok(Flattener::Arap),
            "project" => Ok(Flattener::Project),
            _ => Err(format!(
                "unknown flattening '{s}': expected arap, lscm or project"
            )),
        }
    }
}

/// The share of S's area a flattening may turn over: a few slivers facing away from a
/// projection's view (noise in the data), or turned over by the ARAP refinement where S
/// crumples at a point more than lengths can follow. The grid folds over less than a cell
/// there, and the cells over them are caught as folds later.
const MAX_FOLDED_AREA: f64 = 1e-3;

/// Local/global steps of the ARAP refinement.
const ARAP_ITERATIONS: usize = 30;

/// How far a flattening is from an isometry, per triangle: the singular values s1 >= s2 of the
/// map's Jacobian (plane -> surface), the plane scaled to the surface's area.
#[derive(Clone, Debug, Serialize)]
pub struct Distortion {
    /// Largest s1 / s2 (1: angles kept).
    pub conformal_max: f64,
    /// Area-weighted mean of s1 / s2.
    pub conformal_avg: f64,
    /// Smallest and largest s1 s2 (area scale; 1: areas kept).
    pub area_scale_min: f64,
    pub area_scale_max: f64,
    /// Area-weighted coefficient of variation of the length scale sqrt(s1 s2): what the cell
    /// sizes on S inherit from a regular grid in the plane.
    pub length_scale_cv: f64,
}

/// A flattening of `vertices`/`triangles` (counter-clockwise seen from the side of the normal)
/// into the plane, scaled to the same total area.
pub struct Flattening {
    pub points: Vec<Point2>,
    /// What was used: LSCM when the ARAP refinement was asked for but failed.
    pub flattener: Flattener,
    /// Triangles the flattening turned over (0 for a good one).
    pub flipped: usize,
    /// The surface's area, which the flat domain has too.
    pub area: f64,
    pub distortion: Distortion,
}

fn cot(a: Vec3, b: Vec3, c: Vec3) -> f64 {
    // The cotangent of the angle at c in triangle abc.
    let (u, v) = (a - c, b - c);
    let s = u.cross(v).norm();
    if s < 1e-300 {
        0.0
    } else {
        u.dot(v) / s
    }
}

/// Directed boundary half-edges (a -> b with the triangle on the left), in triangle order.
pub(crate) fn boundary_half_edges(triangles: &[[usize; 3]]) -> Vec<[usize; 2]> {
    let mut directed: Vec<([usize; 2], usize)> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| [t[k], t[(k + 1) % 3]]))
        .enumerate()
        .map(|(i, e)| (e, i))
        .collect();
    let mut keys: Vec<[usize; 2]> = directed.iter().map(|(e, _)| *e).collect();
    keys.sort_unstable();
    directed.retain(|([a, b], _)| keys.binary_search(&[*b, *a]).is_err());
    directed.sort_unstable_by_key(|(_, i)| *i);
    directed.into_iter().map(|(e, _)| e).collect()
}

pub fn flatten(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    flattener: Flattener,
) -> Result<Flattening> {
    flatten_viewed(vertices, triangles, flattener, None)
}

/// [`flatten`], with `Flattener::Project` seen along `view` (unit) when given.
pub fn flatten_viewed(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    flattener: Flattener,
    view: Option<Vec3>,
) -> Result<Flattening> {
    let boundary = boundary_half_edges(triangles);
    if boundary.is_empty() {
        return Err(Error::Mesh(
            "the surface is closed (no boundary): it cannot be flattened".into(),
        ));
    }
    let area3: f64 = triangles.iter().map(|t| triangle_area(vertices, t)).sum();
    let mut points = match flattener {
        Flattener::Project => project(vertices, triangles, view),
        Flattener::Lscm | Flattener::Arap => lscm(vertices, triangles, &boundary)?,
    };
    if flattener == Flattener::Project {
        // A few slivers facing away (noise in the data) are let through: the cells over them
        // are caught as folds later. More than that is a surface that overhangs.
        let away_area = turned_over_area(vertices, triangles, &points);
        if away_area > MAX_FOLDED_AREA * area3 {
            if let Some(d) = view {
                return Err(Error::Mesh(format!(
                    "{} triangles ({:.1}% of the area) face away from the direction {}: seen \
                     along it the surface folds over itself, so walls along it would lie in \
                     the surface",
                    flipped(&points, triangles),
                    100.0 * away_area / area3,
                    crate::error::short_vector(d)
                )));
            }
            return Err(Error::Mesh(format!(
                "{} triangles ({:.1}% of the area) face away from every view direction: seen \
                 from anywhere the surface folds over itself, so it cannot be projected \
                 (--flatten arap can)",
                flipped(&points, triangles),
                100.0 * away_area / area3
            )));
        }
    }
    let mut used = flattener;
    if flattener == Flattener::Arap {
        used = Flattener::Lscm;
        // Kept as LSCM left it when the Laplacian cannot be factorized or the refinement
        // turns over more than slivers (strongly curved pieces: the rotations cannot agree).
        // A sliver is no reason to keep LSCM, whose cells grow and shrink with the conformal
        // factor over the whole of S.
        let mut refined = points.clone();
        if super::arap::refine(vertices, triangles, &mut refined, ARAP_ITERATIONS).is_some()
            && turns_over_slivers_only(vertices, triangles, &refined, &points, area3)
        {
            points = refined;
            used = Flattener::Arap;
        }
    }
    scaled_to_area(vertices, triangles, points, area3, used).ok_or_else(|| {
        Error::Mesh(
            "the flattening folded over (negative area): the surface is too far from a disk".into(),
        )
    })
}

/// Whether the refined flattening `refined` turns over at most slivers more of S (of area
/// `area3`) than `before` did.
fn turns_over_slivers_only(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    refined: &[Point2],
    before: &[Point2],
    area3: f64,
) -> bool {
    turned_over_area(vertices, triangles, refined)
        <= turned_over_area(vertices, triangles, before) + MAX_FOLDED_AREA * area3
}

/// `points` scaled to S's area `area3`, with the distortion they leave; None where their
/// image has no positive area (the flattening folded over).
fn scaled_to_area(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    mut points: Vec<Point2>,
    area3: f64,
    flattener: Flattener,
) -> Option<Flattening> {
    let area2: f64 = triangles.iter().map(|t| signed_area(&points, t)).sum();
    if area2.is_nan() || area2 <= 0.0 {
        return None;
    }
    let s = (area3 / area2).sqrt();
    for p in &mut points {
        *p = [p[0] * s, p[1] * s];
    }
    Some(Flattening {
        flipped: flipped(&points, triangles),
        distortion: distortion(vertices, triangles, &points),
        area: area3,
        points,
        flattener,
    })
}

/// `free`, a flattening of S cut open along a seam (`pairs`, see [`super::seam`]), refined
/// as-rigid-as-possible with the seam's left side held as the right side turned by `turn`
/// (cos, sin); None where that refinement fails or turns over more than slivers.
pub fn flatten_seamed(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    free: &Flattening,
    pairs: &[(usize, usize)],
    turn: [f64; 2],
) -> Option<Flattening> {
    let mut points = free.points.clone();
    super::arap::refine_seamed(
        vertices,
        triangles,
        &mut points,
        ARAP_ITERATIONS,
        pairs,
        turn,
    )?;
    if !turns_over_slivers_only(vertices, triangles, &points, &free.points, free.area) {
        return None;
    }
    scaled_to_area(vertices, triangles, points, free.area, Flattener::Arap)
}

/// Least-squares conformal map, two far boundary vertices pinned.
fn lscm(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    boundary: &[[usize; 2]],
) -> Result<Vec<Point2>> {
    let n = vertices.len();
    // Pin the two boundary vertices farthest apart (from the first, then from that one).
    let farthest = |from: usize| {
        boundary
            .iter()
            .map(|e| e[0])
            .max_by(|&a, &b| {
                let (da, db) = (
                    (vertices[a] - vertices[from]).norm(),
                    (vertices[b] - vertices[from]).norm(),
                );
                da.total_cmp(&db)
            })
            .unwrap_or(from)
    };
    let p0 = farthest(boundary[0][0]);
    let p1 = farthest(p0);
    let span = (vertices[p1] - vertices[p0]).norm();
    if p0 == p1 || span <= 0.0 {
        return Err(Error::Mesh("the surface has no extent to flatten".into()));
    }

    // Unknown index of coordinate c (0: x, 1: y) of vertex v, or the pinned value.
    let mut free = vec![usize::MAX; n];
    let mut m = 0;
    for (v, f) in free.iter_mut().enumerate() {
        if v != p0 && v != p1 {
            *f = m;
            m += 1;
        }
    }
    let pinned = |v: usize, c: usize| -> f64 {
        match (v == p1, c) {
            (true, 0) => span,
            _ => 0.0,
        }
    };
    let index = |v: usize, c: usize| (free[v] != usize::MAX).then(|| free[v] + c * m);

    // The quadratic form Q of E_C = 1/2 u^T Q u as (row, col, value) over all 2n coordinates.
    let mut entries: Vec<(usize, usize, usize, usize, f64)> = Vec::new(); // (v, c, w, d, value)
    for t in triangles {
        for k in 0..3 {
            let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let w = 0.5 * cot(vertices[a], vertices[b], vertices[c]);
            for d in 0..2 {
                entries.push((a, d, a, d, w));
                entries.push((b, d, b, d, w));
                entries.push((a, d, b, d, -w));
                entries.push((b, d, a, d, -w));
            }
        }
    }
    // -A(u) with A = 1/2 sum over boundary a -> b of (x_a y_b - x_b y_a) = 1/2 u^T M u.
    for &[a, b] in boundary {
        entries.push((a, 0, b, 1, -0.5));
        entries.push((b, 1, a, 0, -0.5));
        entries.push((b, 0, a, 1, 0.5));
        entries.push((a, 1, b, 0, 0.5));
    }
    let mut triplets = Vec::with_capacity(entries.len());
    let mut rhs = Mat::<f64>::zeros(2 * m, 1);
    for &(v, c, w, d, value) in &entries {
        match (index(v, c), index(w, d)) {
            // The lower triangle only: the Cholesky reads that side.
            (Some(i), Some(j)) if i >= j => triplets.push(Triplet::new(i, j, value)),
            (Some(i), None) => rhs[(i, 0)] -= value * pinned(w, d),
            _ => {}
        }
    }
    let q = SparseColMat::<usize, f64>::try_new_from_triplets(2 * m, 2 * m, &triplets)
        .map_err(|e| Error::Solver(format!("flattening: {e:?}")))?;
    let llt = q.sp_cholesky(Side::Lower).map_err(|e| {
        Error::Mesh(format!(
            "the surface cannot be flattened ({e:?}): is it connected, with no degenerate \
             triangles?"
        ))
    })?;
    llt.solve_in_place_with_conj(faer::Conj::No, rhs.as_mut());
    let points: Vec<Point2> = (0..n)
        .map(|v| match free[v] {
            usize::MAX => [pinned(v, 0), pinned(v, 1)],
            i => [rhs[(i, 0)], rhs[(i + m, 0)]],
        })
        .collect();
    if let Some(v) = points
        .iter()
        .position(|p| !p[0].is_finite() || !p[1].is_finite())
    {
        return Err(Error::Mesh(format!(
            "the flattening is not finite at vertex {v}: degenerate triangles around it?"
        )));
    }
    Ok(points)
}

/// Orthogonal projection onto the plane across a view direction: `view` when given, else the
/// surface's mean normal (area-weighted) when every triangle faces it, else the direction
/// that the worst triangle faces best. A grid laid there and lifted back is a honeycomb with
/// parallel node axes from the start.
fn project(vertices: &[Vec3], triangles: &[[usize; 3]], view: Option<Vec3>) -> Vec<Point2> {
    let normals: Vec<Vec3> = triangles
        .iter()
        .map(|t| (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]))
        .collect();
    let mean = normals.iter().fold(Vec3::ZERO, |s, &n| s + n).normalized();
    let units: Vec<Vec3> = normals
        .iter()
        .filter(|n| n.norm() > 0.0)
        .map(|n| n.normalized())
        .collect();
    let worst = |d: Vec3| units.iter().fold(f64::INFINITY, |m, n| m.min(n.dot(d)));
    let view = match view {
        // An axis is a line: seen from whichever side S faces.
        Some(d) if d.dot(mean) < 0.0 => -d,
        Some(d) => d,
        None if worst(mean) > 0.0 => mean,
        None => best_view(&worst, mean),
    };
    let u = view.any_orthogonal().normalized();
    let v = view.cross(u);
    vertices.iter().map(|&p| [p.dot(u), p.dot(v)]).collect()
}

/// The direction maximizing `worst`: a spread of directions over the sphere, then rounds of
/// smaller and smaller steps around the best so far (deterministic).
fn best_view(worst: &dyn Fn(Vec3) -> f64, start: Vec3) -> Vec3 {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let spread = (0..400).map(|k| {
        let z = 1.0 - 2.0 * (k as f64 + 0.5) / 400.0;
        let r = (1.0 - z * z).sqrt();
        let a = golden * k as f64;
        Vec3::new(r * a.cos(), r * a.sin(), z)
    });
    let (mut best, mut value) = (start, worst(start));
    for d in spread {
        let w = worst(d);
        if w > value {
            (best, value) = (d, w);
        }
    }
    let mut step = 0.1;
    for _ in 0..6 {
        let u = best.any_orthogonal().normalized();
        let v = best.cross(u);
        for k in 0..24 {
            let a = std::f64::consts::TAU * k as f64 / 24.0;
            let d = (best + (u * a.cos() + v * a.sin()) * step).normalized();
            let w = worst(d);
            if w > value {
                (best, value) = (d, w);
            }
        }
        step *= 0.5;
    }
    best
}

fn triangle_area(vertices: &[Vec3], t: &[usize; 3]) -> f64 {
    0.5 * (vertices[t[1]] - vertices[t[0]])
        .cross(vertices[t[2]] - vertices[t[0]])
        .norm()
}

/// How many triangles face the other way in the plane.
fn flipped(points: &[Point2], triangles: &[[usize; 3]]) -> usize {
    triangles
        .iter()
        .filter(|t| signed_area(points, t) <= 0.0)
        .count()
}

/// S's area over the triangles that `points` turn over.
fn turned_over_area(vertices: &[Vec3], triangles: &[[usize; 3]], points: &[Point2]) -> f64 {
    triangles
        .iter()
        .filter(|t| signed_area(points, t) <= 0.0)
        .map(|t| triangle_area(vertices, t))
        .sum()
}

pub fn signed_area(points: &[Point2], t: &[usize; 3]) -> f64 {
    let [a, b, c] = t.map(|v| points[v]);
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
}

/// Singular values of the linear map taking the planar triangle onto the spatial one.
fn singular_values(vertices: &[Vec3], points: &[Point2], t: &[usize; 3]) -> Option<(f64, f64)> {
    let [p0, p1, p2] = t.map(|v| points[v]);
    let [q0, q1, q2] = t.map(|v| vertices[v]);
    let (u1, u2) = (
        [p1[0] - p0[0], p1[1] - p0[1]],
        [p2[0] - p0[0], p2[1] - p0[1]],
    );
    let det = u1[0] * u2[1] - u2[0] * u1[1];
    if det.abs() < 1e-300 {
        return None;
    }
    // J [u1 u2] = [e1 e2]  =>  J = [e1 e2] [u1 u2]^-1 (3x2).
    let (e1, e2) = (q1 - q0, q2 - q0);
    let inv = [[u2[1] / det, -u2[0] / det], [-u1[1] / det, u1[0] / det]];
    let jx = e1 * inv[0][0] + e2 * inv[1][0];
    let jy = e1 * inv[0][1] + e2 * inv[1][1];
    // Eigenvalues of J^T J.
    let (a, b, c) = (jx.dot(jx), jx.dot(jy), jy.dot(jy));
    let mean = 0.5 * (a + c);
    let root = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    Some(((mean + root).sqrt(), (mean - root).max(0.0).sqrt()))
}

fn distortion(vertices: &[Vec3], triangles: &[[usize; 3]], points: &[Point2]) -> Distortion {
    let mut d = Distortion {
        conformal_max: 1.0,
        conformal_avg: 0.0,
        area_scale_min: f64::INFINITY,
        area_scale_max: 0.0,
        length_scale_cv: 0.0,
    };
    let (mut weight, mut sum_l, mut sum_l2) = (0.0, 0.0, 0.0);
    for t in triangles {
        let Some((s1, s2)) = singular_values(vertices, points, t) else {
            continue;
        };
        let w = triangle_area(vertices, t);
        let conformal = if s2 > 0.0 { s1 / s2 } else { f64::INFINITY };
        d.conformal_max = d.conformal_max.max(conformal);
        d.conformal_avg += w * conformal;
        d.area_scale_min = d.area_scale_min.min(s1 * s2);
        d.area_scale_max = d.area_scale_max.max(s1 * s2);
        let l = (s1 * s2).sqrt();
        weight += w;
        sum_l += w * l;
        sum_l2 += w * l * l;
    }
    if weight > 0.0 {
        d.conformal_avg /= weight;
        let mean = sum_l / weight;
        d.length_scale_cv = (sum_l2 / weight - mean * mean).max(0.0).sqrt() / mean;
    }
    d
}

/// A triangulated grid of `n` x `n` squares over [0, 1]^2 lifted by `height`,
/// counter-clockwise from +z: the init tests' surface.
#[cfg(test)]
pub(crate) fn lifted_grid(
    n: usize,
    height: impl Fn(f64, f64) -> f64,
) -> (Vec<Vec3>, Vec<[usize; 3]>) {
    let mut vertices = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            vertices.push(Vec3::new(x, y, height(x, y)));
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (vertices, triangles)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_flat_square_is_flattened_onto_itself() {
        let (vertices, triangles) = lifted_grid(10, |_, _| 0.0);
        let f = flatten(&vertices, &triangles, Flattener::Lscm).unwrap();
        // Up to a similarity: all distances kept.
        for (a, b) in [(0, 120), (5, 77), (13, 64)] {
            let d3 = (vertices[a] - vertices[b]).norm();
            let (p, q) = (f.points[a], f.points[b]);
            let d2 = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
            assert!((d2 - d3).abs() < 1e-9, "{a}-{b}: {d2} vs {d3}");
        }
        assert!(f.distortion.conformal_max < 1.0 + 1e-9);
        assert!(f.distortion.length_scale_cv < 1e-6, "{:?}", f.distortion);
        assert!(triangles.iter().all(|t| signed_area(&f.points, t) > 0.0));
    }

    #[test]
    fn a_developable_sheet_is_flattened_without_distortion() {
        // A cylinder piece: isometric to the plane, so LSCM finds (nearly) the isometry.
        let (vertices, triangles) = lifted_grid(30, |x, _| (1.0 - (x - 0.5).powi(2)).sqrt());
        let f = flatten(&vertices, &triangles, Flattener::Lscm).unwrap();
        assert!(f.distortion.length_scale_cv < 0.01, "{:?}", f.distortion);
        assert!(f.distortion.conformal_avg < 1.01, "{:?}", f.distortion);
    }

    #[test]
    fn a_dome_keeps_angles_and_reports_its_area_distortion() {
        let (vertices, triangles) = lifted_grid(30, |x, y| {
            (4.0 - (x - 0.5).powi(2) - (y - 0.5).powi(2)).sqrt()
        });
        let f = flatten(&vertices, &triangles, Flattener::Lscm).unwrap();
        assert!(f.distortion.conformal_avg < 1.02, "{:?}", f.distortion);
        assert!(f.distortion.area_scale_max > f.distortion.area_scale_min);
        assert!(triangles.iter().all(|t| signed_area(&f.points, t) > 0.0));
    }

    /// A flat plate crumpled at one point (a small monkey saddle: more than 360 degrees of
    /// angle there). No map keeps the lengths around it, so the ARAP refinement turns a few
    /// slivers over; LSCM keeps angles by shrinking the cells all over the plate instead.
    #[test]
    fn a_plate_crumpled_at_a_point_keeps_its_lengths() {
        let (vertices, triangles) = lifted_grid(100, |x, y| {
            let (u, v, s) = (x - 0.5, y - 0.5, 0.025f64);
            0.075 * (u.powi(3) - 3.0 * u * v * v) / s.powi(3) * (-(u * u + v * v) / (s * s)).exp()
        });
        let lscm = flatten(&vertices, &triangles, Flattener::Lscm).unwrap();
        let arap = flatten(&vertices, &triangles, Flattener::Arap).unwrap();
        assert_eq!(arap.flattener, Flattener::Arap);
        assert!(arap.flipped > 0, "the refinement turned nothing over");
        let area = arap.area;
        let over = turned_over_area(&vertices, &triangles, &arap.points);
        assert!(
            over <= MAX_FOLDED_AREA * area,
            "{over} of {area} turned over"
        );
        assert!(
            arap.distortion.length_scale_cv < 0.3 * lscm.distortion.length_scale_cv,
            "ARAP {:?}, LSCM {:?}",
            arap.distortion,
            lscm.distortion
        );
    }

    #[test]
    fn a_closed_surface_is_refused() {
        // A tetrahedron, outward oriented.
        let vertices = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        let triangles = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        let e = flatten(&vertices, &triangles, Flattener::Lscm)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("closed"), "{e}");
    }
}
