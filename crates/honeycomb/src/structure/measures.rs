//! Quality measures of a realized honeycomb (DESIGN.md section 3), computed from the meshes M
//! and M' alone, never from solver variables.

use super::Honeycomb;
use crate::geometry::{segment_distance, Vec3};
use crate::surface::Surface;
use serde::Serialize;
use std::collections::BTreeMap;

#[derive(Clone, Debug, Serialize)]
pub struct Measures {
    /// Deviation of the dihedral angles between consecutive walls at a node from 120 degrees.
    pub omega_max_deg: f64,
    pub omega_avg_deg: f64,
    /// Wall planarity: distance of a wall quad's diagonals over its mean edge length.
    pub delta_max: f64,
    pub delta_avg: f64,
    /// Wall quads that are not convex: crossed (M''s edge runs against M's, because the node
    /// axes at its ends lean together by more than the edge is long over the thickness; a
    /// thinner structure uncrosses it) or folded (the axes lean to opposite sides of the edge).
    /// Such a quad may lie in a plane and still read far from planar in delta.
    pub nonconvex_walls: usize,
    /// Distance of a vertex of M to S over the mean edge length of M.
    pub closeness_max: f64,
    pub closeness_avg: f64,
    pub mean_edge_length: f64,
    /// The shortest edge of M (model units).
    pub min_edge_length: f64,
    pub valence_histogram: BTreeMap<usize, usize>,
    /// How the walls stand on S: the angle (degrees) between each node axis `v' - v` and S's
    /// normal at the vertex's closest point on S, as lines.
    pub axis_normal_deg: Spread,
    /// The same for one common axis, S's area-weighted mean normal, at the same points: what a
    /// plan-view honeycomb with parallel axes scores.
    pub parallel_baseline_deg: Spread,
    /// Standard deviation over mean of the edge lengths of M: cells of one size read 0.
    pub edge_length_cv: f64,
    /// Per node: the largest omega there (degrees).
    #[serde(skip)]
    pub omega_per_node: Vec<f64>,
    /// Per edge: delta of its wall.
    #[serde(skip)]
    pub delta_per_wall: Vec<f64>,
    /// Per edge: whether its wall quad is convex.
    #[serde(skip)]
    pub convex_per_wall: Vec<bool>,
    /// Per node: the angle (degrees) between its axis and S's normal.
    #[serde(skip)]
    pub axis_normal_per_node: Vec<f64>,
    /// Per vertex: its distance to S in mean edge lengths.
    #[serde(skip)]
    pub closeness_per_vertex: Vec<f64>,
}

/// Mean, 95th percentile and largest of a set of values.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Spread {
    pub mean: f64,
    pub p95: f64,
    pub max: f64,
}

impl Spread {
    pub fn of(values: &[f64]) -> Spread {
        if values.is_empty() {
            return Spread::default();
        }
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let rank = ((0.95 * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len());
        Spread {
            mean: values.iter().sum::<f64>() / values.len() as f64,
            p95: sorted[rank - 1],
            max: sorted[sorted.len() - 1],
        }
    }
}

/// The coefficient of variation of edge lengths: their standard deviation over their mean.
pub fn edge_length_cv(lengths: &[f64]) -> f64 {
    let count = lengths.len().max(1) as f64;
    let mean = lengths.iter().sum::<f64>() / count;
    let variance = lengths.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / count;
    variance.sqrt() / mean.max(1e-300)
}

/// Per wall (edge `[a, b]`), the larger of its two nodes' values: a wall is as bad as its
/// worse end.
pub fn per_wall_worse_end(edges: &[[usize; 2]], per_node: &[f64]) -> Vec<f64> {
    edges
        .iter()
        .map(|&[a, b]| per_node[a].max(per_node[b]))
        .collect()
}

/// The angle (degrees) between two lines with unit directions `a` and `b`.
pub fn line_angle_deg(a: Vec3, b: Vec3) -> f64 {
    a.dot(b).abs().min(1.0).acos().to_degrees()
}

/// The angles (degrees) between consecutive walls around the axis at node `v`: three for a
/// trivalent node, one (the angle between the two walls) at a valence-2 node.
pub fn node_angles(h: &Honeycomb, v: usize, neighbours: &[usize]) -> Vec<f64> {
    let (p, q) = (h.base.vertices[v], h.offset.vertices[v]);
    let axis = (q - p).normalized();
    let u = axis.any_orthogonal();
    let w = axis.cross(u);
    // Each wall leaves the axis towards its edge's other end.
    let mut dirs: Vec<f64> = neighbours
        .iter()
        .map(|&j| {
            let d = h.base.vertices[j] - p;
            d.dot(w).atan2(d.dot(u))
        })
        .collect();
    let deg = |r: f64| r.to_degrees();
    match dirs.len() {
        2 => {
            let mut a = (dirs[0] - dirs[1]).abs();
            if a > std::f64::consts::PI {
                a = 2.0 * std::f64::consts::PI - a;
            }
            vec![deg(a)]
        }
        _ => {
            dirs.sort_by(f64::total_cmp);
            let k = dirs.len();
            (0..k)
                .map(|i| {
                    let next = if i + 1 < k {
                        dirs[i + 1]
                    } else {
                        dirs[0] + 2.0 * std::f64::consts::PI
                    };
                    deg(next - dirs[i])
                })
                .collect()
        }
    }
}

/// The largest constant thickness at which no wall quad of `h` crosses itself (infinite when
/// no two axes lean together): the M' edge of wall ab is `(v_b - v_a) + t (a_b - a_a)`, which
/// turns against `v_b - v_a` from `t = |v_b - v_a|^2 / -((v_b - v_a) . (a_b - a_a))` on.
pub fn thickest_uncrossed(h: &Honeycomb) -> f64 {
    h.edges
        .iter()
        .map(|&[a, b]| {
            let edge = h.base.vertices[b] - h.base.vertices[a];
            let lean = -edge.dot(h.axes[b] - h.axes[a]);
            if lean > 0.0 {
                edge.norm_squared() / lean
            } else {
                f64::INFINITY
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// Whether a (nearly planar) quad is convex: it turns the same way at all four corners.
pub(crate) fn is_convex(p: [Vec3; 4]) -> bool {
    let corner = |k: usize| (p[(k + 1) % 4] - p[k]).cross(p[(k + 3) % 4] - p[k]);
    let first = corner(0);
    (1..4).all(|k| corner(k).dot(first) > 0.0)
}

/// Planarity of a quad: distance between its diagonals over its mean edge length.
pub fn quad_planarity([p0, p1, p2, p3]: [Vec3; 4]) -> f64 {
    let mean = ((p1 - p0).norm() + (p2 - p1).norm() + (p3 - p2).norm() + (p0 - p3).norm()) / 4.0;
    segment_distance(p0, p2, p1, p3) / mean.max(1e-300)
}

/// The largest move along S from `before` to `after` (the same vertices), in units of `unit`:
/// each move less its part along S's normal where the vertex ended.
pub fn largest_move_along(surface: &Surface, before: &[Vec3], after: &[Vec3], unit: f64) -> f64 {
    (before.iter().zip(after))
        .map(|(&p, &q)| {
            let n = surface.normal_at(q);
            let d = q - p;
            (d - n * d.dot(n)).norm() / unit
        })
        .fold(0.0, f64::max)
}

pub fn measure(h: &Honeycomb, surface: &Surface) -> Measures {
    let nv = h.base.vertices.len();
    let mut neighbours = vec![Vec::new(); nv];
    for &[a, b] in &h.edges {
        neighbours[a].push(b);
        neighbours[b].push(a);
    }
    let mut valence_histogram = BTreeMap::new();
    let (mut omega_sum, mut omega_count) = (0.0, 0usize);
    let omega_per_node: Vec<f64> = (0..nv)
        .map(|v| {
            *valence_histogram.entry(neighbours[v].len()).or_insert(0) += 1;
            if neighbours[v].len() < 2 {
                return 0.0;
            }
            node_angles(h, v, &neighbours[v])
                .into_iter()
                .map(|a| {
                    let dev = (a - 120.0).abs();
                    omega_sum += dev;
                    omega_count += 1;
                    dev
                })
                .fold(0.0, f64::max)
        })
        .collect();
    let (delta_per_wall, convex_per_wall): (Vec<f64>, Vec<bool>) = (0..h.edges.len())
        .map(|e| {
            let wall = h.wall(e);
            (quad_planarity(wall), is_convex(wall))
        })
        .unzip();
    let nonconvex_walls = convex_per_wall.iter().filter(|&&c| !c).count();
    let mean_edge_length = h
        .edges
        .iter()
        .map(|&[a, b]| (h.base.vertices[a] - h.base.vertices[b]).norm())
        .sum::<f64>()
        / h.edges.len().max(1) as f64;
    let min_edge_length = h
        .edges
        .iter()
        .map(|&[a, b]| (h.base.vertices[a] - h.base.vertices[b]).norm())
        .fold(f64::INFINITY, f64::min);
    let feet = surface.closest_points(&h.base.vertices);
    let closeness: Vec<f64> = feet.iter().map(|c| c.distance / mean_edge_length).collect();
    let common = surface.mean_normal();
    let (lean, baseline): (Vec<f64>, Vec<f64>) = (0..nv)
        .map(|v| {
            let axis = (h.offset.vertices[v] - h.base.vertices[v]).normalized();
            let n = feet[v].normal;
            (line_angle_deg(axis, n), line_angle_deg(common, n))
        })
        .unzip();
    let lengths: Vec<f64> = h
        .edges
        .iter()
        .map(|&[a, b]| (h.base.vertices[a] - h.base.vertices[b]).norm())
        .collect();
    let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    let avg = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    Measures {
        omega_max_deg: max(&omega_per_node),
        omega_avg_deg: omega_sum / omega_count.max(1) as f64,
        delta_max: max(&delta_per_wall),
        delta_avg: avg(&delta_per_wall),
        nonconvex_walls,
        closeness_max: max(&closeness),
        closeness_avg: avg(&closeness),
        mean_edge_length,
        min_edge_length,
        valence_histogram,
        axis_normal_deg: Spread::of(&lean),
        parallel_baseline_deg: Spread::of(&baseline),
        edge_length_cv: edge_length_cv(&lengths),
        omega_per_node,
        delta_per_wall,
        convex_per_wall,
        axis_normal_per_node: lean,
        closeness_per_vertex: closeness,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::hex_disk;
    use crate::mesh::validate_base_mesh;

    /// Two neighbouring axes leaning towards each other by more than their edge is long over
    /// the thickness cross that one wall, and only it; leaning to opposite sides folds it.
    #[test]
    fn axes_leaning_together_cross_their_wall() {
        let mesh = hex_disk(4.0);
        let conn = validate_base_mesh(&mesh).unwrap();
        let surface = Surface::from_mesh(&mesh).unwrap();
        let up = Vec3::new(0.0, 0.0, 1.0);
        let upright = Honeycomb::new(mesh.clone(), &conn, vec![up; mesh.vertices.len()], 2.0);
        assert_eq!(measure(&upright, &surface).nonconvex_walls, 0);

        let e = (0..conn.num_edges())
            .find(|&e| !conn.is_boundary_edge(e))
            .unwrap();
        let [a, b] = conn.edges[e];
        let towards = (mesh.vertices[b] - mesh.vertices[a]).normalized();
        let mut axes = vec![up; mesh.vertices.len()];
        axes[a] = (up + towards).normalized();
        axes[b] = (up - towards).normalized();
        // Each tip moves 2 * 0.71 towards the other: more than the unit edge between them.
        let leaning = Honeycomb::new(mesh.clone(), &conn, axes, 2.0);
        assert_eq!(measure(&leaning, &surface).nonconvex_walls, 1);
        let thin = Honeycomb::new(mesh.clone(), &conn, leaning.axes.clone(), 0.3);
        assert_eq!(measure(&thin, &surface).nonconvex_walls, 0);
        // Crossing starts at 1 / (2 * 0.707...): just below it the wall is whole, above not.
        let limit = thickest_uncrossed(&leaning);
        assert!((limit - 0.5f64.sqrt()).abs() < 1e-12, "{limit}");
        for (t, crossed) in [(0.99 * limit, 0), (1.01 * limit, 1)] {
            let h = Honeycomb::new(mesh.clone(), &conn, leaning.axes.clone(), t);
            assert_eq!(
                measure(&h, &surface).nonconvex_walls,
                crossed,
                "thickness {t}"
            );
        }
        assert!(thickest_uncrossed(&upright).is_infinite());
        // Axes leaning to opposite sides of the edge, across the wall: folded at any thickness.
        let across = up.cross(towards);
        let mut axes = vec![up; mesh.vertices.len()];
        axes[a] = (across + up * 0.2).normalized();
        axes[b] = (-across + up * 0.2).normalized();
        for t in [0.05, 0.3] {
            let folded = Honeycomb::new(mesh.clone(), &conn, axes.clone(), t);
            assert!(
                measure(&folded, &surface).nonconvex_walls >= 1,
                "thickness {t}"
            );
        }
    }
}
