//! A wall unrolled into its plane. Each wall quad `v_a v_b v'_b v'_a` is planar, so laying it
//! flat keeps its lengths and angles; its two ends run along the node axes at a and b.

use crate::geometry::Vec3;
use crate::structure::Honeycomb;

/// A point in a panel's plane (model units).
pub type Point = [f64; 2];

/// How a panel's ends are cut for plates of thickness T. At every node the three walls' mid-planes
/// meet in the node axis at 120 degrees (to the structure's omega), so one cut serves every end
/// (at a boundary node with two walls, the open side keeps a notch): each face of the plate
/// stops `setback` short of the axis (square cut: the three plates touch along their edges
/// around a triangular void), or the end is bevelled `bevel_deg` from square on both faces to a
/// ridge on the axis (the plates close the node).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EndCut {
    pub thickness: f64,
    /// T / (2 tan 60 deg): where a face meets the bisecting plane with a neighbour.
    pub setback: f64,
    /// Half the 60-degree angle between a plate and the plane that bisects it and a neighbour.
    pub bevel_deg: f64,
}

impl EndCut {
    pub fn new(thickness: f64) -> EndCut {
        EndCut {
            thickness,
            setback: thickness / (2.0 * 3f64.sqrt()),
            bevel_deg: 30.0,
        }
    }
}

/// One wall laid flat: the corners `v_a, v_b, v'_b, v'_a` in the wall's plane, with `v_a` at the
/// origin, the edge of M along +x and M' above it (+y).
#[derive(Clone, Debug)]
pub struct Panel {
    /// The wall's edge of M (its index in structure.json).
    pub edge: usize,
    /// The nodes at its ends, a and b.
    pub nodes: [usize; 2],
    /// The wall on its mid-plane: its ends are the node axes.
    pub outline: [Point; 4],
    /// The outline cut from the sheet: the ends set back from the axes by the end cut (the
    /// outline itself without one).
    pub cut: [Point; 4],
}

impl Panel {
    /// Smallest and largest coordinates of the outline.
    pub fn bounds(&self) -> (Point, Point) {
        bounds(&self.outline)
    }
}

pub fn bounds(points: &[Point]) -> (Point, Point) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// Every wall of `h` laid flat, with `cut` (if any) applied at both ends. A node with one wall
/// only (valence 1) has no neighbour to meet, so that end stays on the axis.
pub fn unroll(h: &Honeycomb, cut: Option<EndCut>) -> Vec<Panel> {
    let mut valence = vec![0usize; h.base.vertices.len()];
    for &[a, b] in &h.edges {
        valence[a] += 1;
        valence[b] += 1;
    }
    (0..h.edges.len())
        .map(|e| {
            let [a, b] = h.edges[e];
            let outline = flatten(h.wall(e), h.wall_normal(e));
            let setback = |v: usize| match cut {
                Some(c) if valence[v] >= 2 => c.setback,
                _ => 0.0,
            };
            Panel {
                edge: e,
                nodes: [a, b],
                outline,
                cut: set_back_ends(outline, setback(a), setback(b)),
            }
        })
        .collect()
}

/// The corners of a planar quad `[p0, p1, p2, p3]` in its plane (normal `n`): p0 at the origin,
/// p1 on +x, and p3 on the +y side.
fn flatten(p: [Vec3; 4], n: Vec3) -> [Point; 4] {
    let x = (p[1] - p[0]).normalized();
    let mut y = n.cross(x).normalized();
    if (p[3] - p[0]).dot(y) < 0.0 {
        y = -y;
    }
    p.map(|q| {
        let d = q - p[0];
        [d.dot(x), d.dot(y)]
    })
}

/// The quad `[p0, p1, p2, p3]` with its end p3-p0 moved `sa` into the quad and its end p1-p2
/// moved `sb` into it, each parallel to itself; the other two sides are kept as lines.
fn set_back_ends(q: [Point; 4], sa: f64, sb: f64) -> [Point; 4] {
    // End a runs p0 -> p3, end b runs p1 -> p2; each moves along its inward normal.
    let (a0, a1) = shift(q[0], q[3], q[1], sa);
    let (b0, b1) = shift(q[1], q[2], q[0], sb);
    [
        intersect(q[0], q[1], a0, a1),
        intersect(q[0], q[1], b0, b1),
        intersect(q[3], q[2], b0, b1),
        intersect(q[3], q[2], a0, a1),
    ]
}

/// The line through `p`, `q` moved by `s` towards the side of `inside`.
fn shift(p: Point, q: Point, inside: Point, s: f64) -> (Point, Point) {
    let d = [q[0] - p[0], q[1] - p[1]];
    let len = d[0].hypot(d[1]);
    let mut n = [-d[1] / len, d[0] / len];
    if (inside[0] - p[0]) * n[0] + (inside[1] - p[1]) * n[1] < 0.0 {
        n = [-n[0], -n[1]];
    }
    let m = |r: Point| [r[0] + s * n[0], r[1] + s * n[1]];
    (m(p), m(q))
}

/// Where the line through `p`, `q` meets the line through `r`, `s`.
fn intersect(p: Point, q: Point, r: Point, s: Point) -> Point {
    let d1 = [q[0] - p[0], q[1] - p[1]];
    let d2 = [s[0] - r[0], s[1] - r[1]];
    let det = d1[0] * d2[1] - d1[1] * d2[0];
    let t = ((r[0] - p[0]) * d2[1] - (r[1] - p[1]) * d2[0]) / det;
    [p[0] + t * d1[0], p[1] + t * d1[1]]
}

/// Length of a side of a flat outline.
pub fn side(a: Point, b: Point) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::upright_hex_disk;

    /// The angle (degrees) at corner `p` between the sides to `q` and `r`.
    fn corner_deg(p: Point, q: Point, r: Point) -> f64 {
        let u = [q[0] - p[0], q[1] - p[1]];
        let v = [r[0] - p[0], r[1] - p[1]];
        (u[0] * v[1] - u[1] * v[0])
            .abs()
            .atan2(u[0] * v[0] + u[1] * v[1])
            .to_degrees()
    }

    fn angle3(p: Vec3, q: Vec3, r: Vec3) -> f64 {
        let (u, v) = (q - p, r - p);
        u.cross(v).norm().atan2(u.dot(v)).to_degrees()
    }

    #[test]
    fn a_leaning_wall_unrolls_with_its_lengths_and_angles() {
        // A flat disk whose axes lean: walls are planar trapezoids, not rectangles.
        let (mut h, conn) = upright_hex_disk(2.0, 0.4);
        let tilt = Vec3::new(0.3, -0.2, 1.0).normalized();
        h = Honeycomb::new(h.base.clone(), &conn, vec![tilt; h.axes.len()], 0.4);
        for panel in unroll(&h, None) {
            let p = h.wall(panel.edge);
            let q = panel.outline;
            for k in 0..4 {
                let (i, j) = (k, (k + 1) % 4);
                assert!((side(q[i], q[j]) - (p[j] - p[i]).norm()).abs() < 1e-12);
                let (prev, next) = ((k + 3) % 4, (k + 1) % 4);
                let flat = corner_deg(q[k], q[prev], q[next]);
                assert!((flat - angle3(p[k], p[prev], p[next])).abs() < 1e-9);
            }
            assert_eq!(q[0], [0.0, 0.0]);
            assert!(q[1][1].abs() < 1e-15 && q[1][0] > 0.0 && q[3][1] > 0.0);
        }
    }

    #[test]
    fn end_cuts_set_each_end_back_square_to_its_axis() {
        let (h, _) = upright_hex_disk(2.0, 0.4);
        let cut = EndCut::new(0.05);
        assert!((cut.setback - 0.05 / (2.0 * 3f64.sqrt())).abs() < 1e-15);
        for panel in unroll(&h, Some(cut)) {
            let (o, c) = (panel.outline, panel.cut);
            // Vertical walls are rectangles: each end comes in by the setback (or not at all
            // at a node with one wall).
            let shortened = side(o[0], o[1]) - side(c[0], c[1]);
            let expected: f64 = panel
                .nodes
                .iter()
                .map(|&v| {
                    let walls = h.edges.iter().filter(|e| e.contains(&v)).count();
                    if walls >= 2 {
                        cut.setback
                    } else {
                        0.0
                    }
                })
                .sum();
            assert!(
                (shortened - expected).abs() < 1e-12,
                "{shortened} {expected}"
            );
            assert!((side(c[1], c[2]) - side(o[1], o[2])).abs() < 1e-12);
        }
    }
}
