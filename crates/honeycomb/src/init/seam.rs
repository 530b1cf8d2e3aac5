//! A hole whose border S turns by a share of a full turn: a lattice laid around it closes only
//! if it turns by a multiple of 60 degrees on the way round.
//!
//! Carried round a hole, a direction on S comes back turned by the curvature the hole holds
//! (Gauss-Bonnet: a full turn less the geodesic curvature of its border). A hexagonal lattice
//! is unchanged by turns of 60 degrees about a cell's center, so a lattice that turns by a
//! multiple of 60 degrees near that curvature fits round the hole with cells of one size,
//! where a flattening of the whole ring into the plane must stretch them (a cone's border is
//! shorter than a planar circle's). The paper's Proposition 1 in another guise: the hole
//! holds the curvature a pentagon (or a heptagon) would.
//!
//! So S is cut along a seam from the hole to the outer border, flattened, and the two sides
//! of the seam are held as images of each other under a turn by that multiple about a point
//! (a cell's center); the lattice then runs on across the seam.
//!
//! A hole holding a full turn is the end of a tube (a tower, a tunnel, a cooling tower's
//! waist): no flattening of the whole lays it in the plane, but cut open it unrolls into a
//! strip whose sides are a shift apart, and a lattice of which that shift is a vector runs
//! round it unturned.

use super::arap::rotate;
use super::flatten::{boundary_half_edges, flatten, flatten_seamed, Flattener, Flattening, Point2};
use crate::geometry::Vec3;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};
use std::f64::consts::PI;

/// S cut open along a seam: the vertices of the seam are doubled, the copies on its left.
#[derive(Clone)]
pub struct Cut {
    pub vertices: Vec<Vec3>,
    pub triangles: Vec<[usize; 3]>,
    /// (right side, left side) of each vertex along the seam, from the hole to the border.
    pub pairs: Vec<(usize, usize)>,
}

/// The border loops of a triangulation (each in the order of its half-edges), or None where a
/// vertex is on the border twice (the surface pinches there).
pub fn border_loops(triangles: &[[usize; 3]]) -> Option<Vec<Vec<usize>>> {
    let mut next = HashMap::new();
    for [a, b] in boundary_half_edges(triangles) {
        if next.insert(a, b).is_some() {
            return None;
        }
    }
    let mut loops = Vec::new();
    let mut seen = std::collections::HashSet::new();
    let mut starts: Vec<usize> = next.keys().copied().collect();
    starts.sort_unstable();
    for start in starts {
        if seen.contains(&start) {
            continue;
        }
        let mut l = Vec::new();
        let mut v = start;
        while seen.insert(v) {
            l.push(v);
            v = *next.get(&v)?;
        }
        if v != start {
            return None;
        }
        loops.push(l);
    }
    Some(loops)
}

fn loop_length(vertices: &[Vec3], l: &[usize]) -> f64 {
    (0..l.len())
        .map(|k| (vertices[l[k]] - vertices[l[(k + 1) % l.len()]]).norm())
        .sum()
}

/// A turned flattening is taken where its lengths vary by at most this share of the whole
/// ring's: a turn that evens them only a little moves the stretch round the hole to the seam's
/// ends rather than removing it.
const WORTH_A_SEAM: f64 = 0.85;

/// A hole whose seam's sides, flattened free and left unturned, lie at least this share of the
/// hole's border length apart wraps S round like a tube (a flat ring's coincide)...
const WRAPS_ROUND: f64 = 0.5;
/// ... where its border is at least this share of the outer one's: a tube's two ends. A small
/// hole down a funnel in a wide roof is wrapped round too, but the lattice must fit the roof.
const TUBE_ENDS: f64 = 0.4;

/// Holes tried at most, the longest first: each costs two flattenings (three round a tube).
const MAX_HOLES_TRIED: usize = 4;

/// The outer border: the longest loop.
fn outer_loop(vertices: &[Vec3], loops: &[Vec<usize>]) -> usize {
    (0..loops.len())
        .max_by(|&a, &b| {
            loop_length(vertices, &loops[a]).total_cmp(&loop_length(vertices, &loops[b]))
        })
        .unwrap_or(0)
}

/// S flattened with the lattice turning round one of its holes: the cut, its flattening and
/// the seam in the plane.
pub struct Seamed {
    pub cut: Cut,
    pub flat: Flattening,
    pub seam: PlaneSeam,
    /// The lattice's turn round the hole (degrees, a multiple of 60; 0 round a tube).
    pub turn_deg: f64,
}

/// Where S (triangulated as `vertices`, `triangles`) has holes round which a lattice must
/// turn by 60 degrees or more, or which S wraps round like a tube, S cut open from each such
/// hole to its outer border and flattened with the lattice's turn across the seam: the
/// multiple of 60 degrees nearest the turn the seam's sides take when flattened free, and
/// round a tube also none (the sides a shift apart). Those that keep lengths clearly better
/// than `uncut`, the most even first; none where no hole asks for a seam.
pub fn round_holes(vertices: &[Vec3], triangles: &[[usize; 3]], uncut: &Flattening) -> Vec<Seamed> {
    let Some(loops) = border_loops(triangles) else {
        return Vec::new();
    };
    if loops.len() < 2 {
        return Vec::new();
    }
    let outer = outer_loop(vertices, &loops);
    let mut seamed = Vec::new();
    // A hole need not hold the curvature itself: the lattice's turn round it can take up
    // some of a dome's about it too, as a pentagon there would.
    let mut holes: Vec<usize> = (0..loops.len()).filter(|&k| k != outer).collect();
    let length = |k: usize| loop_length(vertices, &loops[k]);
    holes.sort_by(|&a, &b| length(b).total_cmp(&length(a)));
    holes.truncate(MAX_HOLES_TRIED);
    for hole in holes {
        let Some(cut) = cut(vertices, triangles, &loops, hole, outer) else {
            continue;
        };
        let Ok(free) = flatten(&cut.vertices, &cut.triangles, Flattener::Arap) else {
            continue;
        };
        // Left free, the seam's sides turn by about what the hole holds. (Plus zero: no turn
        // is 0, not -0.)
        let sixths = (seam_turn(&free.points, &cut.pairs) / (PI / 3.0)).round() + 0.0;
        let tube = norm(mean_shift(&free.points, &cut.pairs)) >= WRAPS_ROUND * length(hole)
            && length(hole) >= TUBE_ENDS * length(outer);
        // Round a tube whose ends differ, the turn the sides take can lie far between two
        // multiples; none, a shift, is the other one tried.
        let turns = match (sixths == 0.0, tube) {
            (true, false) => vec![],
            (false, true) => vec![sixths, 0.0],
            _ => vec![sixths],
        };
        let seamed_by = |sixths: f64| {
            let angle = sixths * PI / 3.0;
            let turn = [angle.cos(), angle.sin()];
            let flat = flatten_seamed(&cut.vertices, &cut.triangles, &free, &cut.pairs, turn);
            (sixths, turn, flat)
        };
        // A tube's two turns are refined side by side: each refinement's solves run on one
        // thread, and its steps are most of what laying a grid on a tube costs.
        let flats = match turns[..] {
            [a, b] => {
                let (first, second) = crate::parallel::both(|| seamed_by(a), || seamed_by(b));
                vec![first, second]
            }
            _ => turns.into_iter().map(seamed_by).collect(),
        };
        for (sixths, turn, flat) in flats {
            let Some(flat) = flat else {
                continue;
            };
            let seam = PlaneSeam::new(&flat.points, &cut.pairs, turn);
            // A hole holding negative curvature opens the plane by more than a full turn round
            // the seam's center: the flattening then lies over itself there, and a lattice laid
            // on it would be laid twice.
            if let Carry::Turn { center, .. } = seam.carry {
                if swept_angle(&flat.points, &cut, &loops[outer], center) > 2.0 * PI + 0.5 {
                    continue;
                }
            }
            let cv = flat.distortion.length_scale_cv;
            if cv < WORTH_A_SEAM * uncut.distortion.length_scale_cv {
                seamed.push(Seamed {
                    cut: cut.clone(),
                    flat,
                    seam,
                    turn_deg: 60.0 * sixths,
                });
            }
        }
    }
    let cv = |s: &Seamed| s.flat.distortion.length_scale_cv;
    seamed.sort_by(|a, b| cv(a).total_cmp(&cv(b)));
    seamed
}

/// The angle the outer border of the cut S sweeps round `center` in the flattening `points`
/// (counter-clockwise positive): a full turn less the lattice's turn round the hole.
fn swept_angle(points: &[Point2], cut: &Cut, outer: &[usize], center: Point2) -> f64 {
    let original = |v: usize| cut.pairs.iter().find(|p| p.1 == v).map_or(v, |p| p.0);
    let on_outer: std::collections::HashSet<usize> = outer.iter().copied().collect();
    boundary_half_edges(&cut.triangles)
        .into_iter()
        .filter(|&[a, b]| on_outer.contains(&original(a)) && on_outer.contains(&original(b)))
        .map(|[a, b]| {
            let (u, v) = (sub(points[a], center), sub(points[b], center));
            (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1])
        })
        .sum()
}

/// The shortest path over S's edges from hole loop `hole` to the outer border loop `outer`,
/// through no other border vertex.
fn seam_path(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    hole: &[usize],
    outer: &[usize],
    on_border: &[bool],
) -> Option<Vec<usize>> {
    let n = vertices.len();
    let mut neighbours = vec![Vec::new(); n];
    for t in triangles {
        for k in 0..3 {
            neighbours[t[k]].push(t[(k + 1) % 3]);
            neighbours[t[(k + 1) % 3]].push(t[k]);
        }
    }
    let mut is_outer = vec![false; n];
    for &v in outer {
        is_outer[v] = true;
    }
    let mut distance = vec![f64::INFINITY; n];
    let mut from = vec![usize::MAX; n];
    let mut queue = BinaryHeap::new();
    for &v in hole {
        distance[v] = 0.0;
        queue.push(Reverse((0u64, v)));
    }
    while let Some(Reverse((d, v))) = queue.pop() {
        let d = f64::from_bits(d);
        if d > distance[v] {
            continue;
        }
        if is_outer[v] {
            let mut path = vec![v];
            let mut u = v;
            while from[u] != usize::MAX {
                u = from[u];
                path.push(u);
            }
            path.reverse();
            return Some(path);
        }
        // From the hole's border only inwards; inner vertices step anywhere but another hole.
        for &w in &neighbours[v] {
            if on_border[w] && !is_outer[w] {
                continue;
            }
            let dw = d + (vertices[w] - vertices[v]).norm();
            if dw < distance[w] {
                distance[w] = dw;
                from[w] = v;
                // Non-negative floats order as their bits.
                queue.push(Reverse((dw.to_bits(), w)));
            }
        }
    }
    None
}

/// S cut along the shortest seam from hole loop `hole` to loop `outer`.
pub fn cut(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    loops: &[Vec<usize>],
    hole: usize,
    outer: usize,
) -> Option<Cut> {
    let mut on_border = vec![false; vertices.len()];
    for &v in loops.iter().flatten() {
        on_border[v] = true;
    }
    let path = seam_path(vertices, triangles, &loops[hole], &loops[outer], &on_border)?;
    if path.len() < 2 {
        return None;
    }
    // Around each vertex, the triangle after edge (v, x) counter-clockwise: (v, x, y).
    let mut around: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            around.insert((tri[k], tri[(k + 1) % 3]), (t, tri[(k + 2) % 3]));
        }
    }
    let mut out_vertices = vertices.to_vec();
    let mut out_triangles = triangles.to_vec();
    let mut pairs = Vec::with_capacity(path.len());
    let last = path.len() - 1;
    for (i, &v) in path.iter().enumerate() {
        // The triangles left of the seam at v: counter-clockwise from the edge to the next
        // vertex back round to the edge from the previous one (or to the border).
        let start = if i < last {
            path[i + 1]
        } else {
            // At the outer border, from its edge out of v.
            let out = around
                .keys()
                .find(|&&(a, b)| a == v && !around.contains_key(&(b, a)))?;
            out.1
        };
        let stop = (i > 0).then(|| path[i - 1]);
        let copy = out_vertices.len();
        out_vertices.push(vertices[v]);
        pairs.push((v, copy));
        let mut x = start;
        let mut ended = false;
        for _ in 0..=triangles.len() {
            if Some(x) == stop {
                ended = true;
                break;
            }
            let Some(&(t, y)) = around.get(&(v, x)) else {
                // The border: only the seam's first vertex, on the hole, ends there.
                ended = i == 0;
                break;
            };
            for corner in out_triangles[t].iter_mut() {
                if *corner == v {
                    *corner = copy;
                }
            }
            x = y;
        }
        if !ended {
            return None;
        }
    }
    Some(Cut {
        vertices: out_vertices,
        triangles: out_triangles,
        pairs,
    })
}

/// The turn (radians, in (-pi, pi]) that best carries the seam's right side onto its left in
/// the flattening `points`: the length-weighted mean over its edges.
pub fn seam_turn(points: &[Point2], pairs: &[(usize, usize)]) -> f64 {
    let (mut dot, mut cross) = (0.0, 0.0);
    for w in pairs.windows(2) {
        let (a0, b0, a1, b1) = (w[0].0, w[0].1, w[1].0, w[1].1);
        let u = sub(points[a1], points[a0]);
        let v = sub(points[b1], points[b0]);
        dot += u[0] * v[0] + u[1] * v[1];
        cross += u[0] * v[1] - u[1] * v[0];
    }
    cross.atan2(dot)
}

/// The mean step from the seam's right side to its left in the flattening `points`.
fn mean_shift(points: &[Point2], pairs: &[(usize, usize)]) -> Point2 {
    let n = pairs.len().max(1) as f64;
    pairs.iter().fold([0.0, 0.0], |s, &(r, l)| {
        let d = sub(points[l], points[r]);
        [s[0] + d[0] / n, s[1] + d[1] / n]
    })
}

fn sub(a: Point2, b: Point2) -> Point2 {
    [a[0] - b[0], a[1] - b[1]]
}

fn norm(a: Point2) -> f64 {
    a[0].hypot(a[1])
}

/// How a seam's right side is carried onto its left in the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Carry {
    /// A turn, (cos, sin), about `center`: the lattice turns round the hole about a cell's
    /// center there.
    Turn { turn: [f64; 2], center: Point2 },
    /// A shift: S wraps round the hole like a tube, and the lattice, of which the shift is a
    /// vector, runs round it unturned.
    Shift(Point2),
}

/// The two sides of a seam in the plane, images of each other.
#[derive(Clone, Debug)]
pub struct PlaneSeam {
    pub carry: Carry,
    pub right: Vec<Point2>,
    pub left: Vec<Point2>,
}

impl PlaneSeam {
    /// The seam of `pairs` in the flattening `points`, turned by `turn`: about the fixed point
    /// of the turn that best carries the right side onto the left, or, unturned, by the mean
    /// shift between the sides.
    pub fn new(points: &[Point2], pairs: &[(usize, usize)], turn: [f64; 2]) -> PlaneSeam {
        let right: Vec<Point2> = pairs.iter().map(|p| points[p.0]).collect();
        let left: Vec<Point2> = pairs.iter().map(|p| points[p.1]).collect();
        // left = R right + t, t the mean of left - R right; the center solves (I - R) c = t.
        let n = pairs.len() as f64;
        let mut t = [0.0, 0.0];
        for (r, l) in right.iter().zip(&left) {
            let turned = rotate(turn, *r);
            t[0] += (l[0] - turned[0]) / n;
            t[1] += (l[1] - turned[1]) / n;
        }
        let (a, b) = (1.0 - turn[0], turn[1]);
        // (I - R) = [[a, b], [-b, a]], inverse [[a, -b], [b, a]] / (a^2 + b^2).
        let det = a * a + b * b;
        let carry = if det < 1e-12 {
            Carry::Shift(t)
        } else {
            let center = [(a * t[0] - b * t[1]) / det, (b * t[0] + a * t[1]) / det];
            Carry::Turn { turn, center }
        };
        PlaneSeam { carry, right, left }
    }

    /// `p` carried across the seam: forwards takes the right side onto the left.
    pub fn carried(&self, p: Point2, forwards: bool) -> Point2 {
        let sign = if forwards { 1.0 } else { -1.0 };
        match self.carry {
            Carry::Turn { turn, center } => {
                let q = rotate([turn[0], sign * turn[1]], sub(p, center));
                [q[0] + center[0], q[1] + center[1]]
            }
            Carry::Shift(t) => [p[0] + sign * t[0], p[1] + sign * t[1]],
        }
    }

    /// Where the step from `from` to `to` comes out having crossed the seam: `to` carried to
    /// the other side, or None where the step crosses neither side.
    pub fn across(&self, from: Point2, to: Point2) -> Option<Point2> {
        if crosses(&self.right, from, to) {
            Some(self.carried(to, true))
        } else if crosses(&self.left, from, to) {
            Some(self.carried(to, false))
        } else {
            None
        }
    }
}

/// Whether segment p-q crosses the polyline.
fn crosses(polyline: &[Point2], p: Point2, q: Point2) -> bool {
    let side = |a: Point2, b: Point2, c: Point2| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    polyline.windows(2).any(|w| {
        let (a, b) = (w[0], w[1]);
        let (d1, d2) = (side(a, b, p), side(a, b, q));
        let (d3, d4) = (side(p, q, a), side(p, q, b));
        d1 * d2 < 0.0 && d3 * d4 < 0.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{design_surface, Shape};

    fn ring() -> (Vec<Vec3>, Vec<[usize; 3]>) {
        design_surface(Shape::Ring).star_triangulated()
    }

    /// A ring cut from its hole to its outer border is a disk: one border loop, each vertex
    /// of the seam doubled in place, no triangle holding both copies.
    #[test]
    fn a_ring_is_cut_open_into_a_disk() {
        let (vertices, triangles) = ring();
        let loops = border_loops(&triangles).expect("a ring's borders do not pinch");
        assert_eq!(loops.len(), 2);
        let outer = outer_loop(&vertices, &loops);
        let cut = cut(&vertices, &triangles, &loops, 1 - outer, outer).expect("a seam");
        assert_eq!(border_loops(&cut.triangles).unwrap().len(), 1);
        assert_eq!(cut.vertices.len(), vertices.len() + cut.pairs.len());
        assert_eq!(cut.triangles.len(), triangles.len());
        assert!(cut.pairs.len() >= 2);
        for &(right, left) in &cut.pairs {
            assert_eq!(cut.vertices[right], cut.vertices[left]);
            assert!(!cut
                .triangles
                .iter()
                .any(|t| t.contains(&right) && t.contains(&left)));
            // Both sides keep triangles.
            assert!(cut.triangles.iter().any(|t| t.contains(&right)));
            assert!(cut.triangles.iter().any(|t| t.contains(&left)));
        }
    }

    /// The bowl's hole holds a sixth of a turn: the lattice turns by 60 degrees round it, the
    /// turned flattening keeps lengths all but exactly (the bowl is developable) where the ring
    /// flattened whole stretches them, and its outer border sweeps the other five sixths round
    /// the turn's center.
    #[test]
    fn a_bowl_flattens_without_stretch_once_its_lattice_turns_a_sixth() {
        let (vertices, triangles) = ring();
        let whole = flatten(&vertices, &triangles, Flattener::Arap).unwrap();
        let seamed = round_holes(&vertices, &triangles, &whole)
            .into_iter()
            .next()
            .expect("the hole asks a turn");
        assert_eq!(seamed.turn_deg, 60.0);
        let (cv, cv_whole) = (
            seamed.flat.distortion.length_scale_cv,
            whole.distortion.length_scale_cv,
        );
        assert!(cv < 0.005 && cv_whole > 3.0 * cv, "{cv} against {cv_whole}");
        assert_eq!(seamed.flat.flipped, 0);
        let loops = border_loops(&triangles).unwrap();
        let outer = &loops[outer_loop(&vertices, &loops)];
        let Carry::Turn { center, .. } = seamed.seam.carry else {
            panic!("a turn, not a shift");
        };
        let swept = swept_angle(&seamed.flat.points, &seamed.cut, outer, center);
        assert!(
            (swept.to_degrees() - 300.0).abs() < 1e-6,
            "{}",
            swept.to_degrees()
        );
        // Its two sides are images of each other under the turn.
        for (r, l) in seamed.seam.right.iter().zip(&seamed.seam.left) {
            let t = seamed.seam.carried(*r, true);
            assert!((t[0] - l[0]).hypot(t[1] - l[1]) < 1e-6 * whole.area.sqrt());
        }
    }

    /// A tube holds a full turn round each end: cut open from end to end it unrolls into a
    /// strip without stretch, its sides a shift of one circumference apart, and the lattice
    /// runs round it unturned.
    #[test]
    fn a_tube_unrolls_into_a_strip_its_sides_a_shift_apart() {
        let (radius, height) = (4.0, 10.0);
        let (vertices, triangles) = crate::generate::tube(radius, height, 90).star_triangulated();
        let whole = flatten(&vertices, &triangles, Flattener::Arap).unwrap();
        let seamed = round_holes(&vertices, &triangles, &whole);
        let first = seamed.first().expect("a tube asks for a seam");
        assert_eq!(first.turn_deg, 0.0);
        let Carry::Shift(shift) = first.seam.carry else {
            panic!("a shift, not a turn");
        };
        // The circumference of the polygon the tube's rows are.
        let around = 90.0 * 2.0 * radius * (PI / 90.0).sin();
        assert!((norm(shift) - around).abs() < 1e-3 * around, "{shift:?}");
        assert!(first.flat.distortion.length_scale_cv < 1e-3);
        for (r, l) in first.seam.right.iter().zip(&first.seam.left) {
            let s = first.seam.carried(*r, true);
            assert!((s[0] - l[0]).hypot(s[1] - l[1]) < 1e-6 * around);
        }
    }

    /// A cooling tower's ends differ: the turn its seam's sides take flattened free (a sixth)
    /// and none (a shift) are both tried, the more even first; each is the flattening its turn
    /// gives refined alone, its sides images of each other.
    #[test]
    fn a_tower_tries_a_turn_and_a_shift() {
        let (vertices, triangles) = crate::generate::cooling_tower(10.0, 48).star_triangulated();
        let whole = flatten(&vertices, &triangles, Flattener::Arap).unwrap();
        let seamed = round_holes(&vertices, &triangles, &whole);
        let turns: Vec<f64> = seamed.iter().map(|s| s.turn_deg.abs()).collect();
        assert_eq!(turns, [60.0, 0.0]);
        let cv = |s: &Seamed| s.flat.distortion.length_scale_cv;
        assert!(cv(&seamed[0]) < cv(&seamed[1]));
        for s in &seamed {
            let (cut, angle) = (&s.cut, s.turn_deg.to_radians());
            let free = flatten(&cut.vertices, &cut.triangles, Flattener::Arap).unwrap();
            let turn = [angle.cos(), angle.sin()];
            let alone = flatten_seamed(&cut.vertices, &cut.triangles, &free, &cut.pairs, turn);
            assert_eq!(alone.unwrap().points, s.flat.points, "turn {}", s.turn_deg);
            let size = whole.area.sqrt();
            for (r, l) in s.seam.right.iter().zip(&s.seam.left) {
                let t = s.seam.carried(*r, true);
                assert!(
                    (t[0] - l[0]).hypot(t[1] - l[1]) < 1e-6 * size,
                    "turn {}",
                    s.turn_deg
                );
            }
        }
    }

    /// A plane with a hole holds no curvature round it: it is flattened whole.
    #[test]
    fn a_flat_ring_is_not_cut() {
        let (mut vertices, triangles) = ring();
        for v in &mut vertices {
            v.z = 0.0;
        }
        let whole = flatten(&vertices, &triangles, Flattener::Arap).unwrap();
        assert!(round_holes(&vertices, &triangles, &whole).is_empty());
    }

    /// A step across a side of the seam comes out turned onto the other side; a step that
    /// crosses neither stays where it was.
    #[test]
    fn a_step_across_the_seam_comes_out_on_its_other_side() {
        let seam = PlaneSeam {
            carry: Carry::Turn {
                turn: [0.5, 0.75f64.sqrt()],
                center: [0.0, 0.0],
            },
            right: vec![[1.0, 0.0], [3.0, 0.0]],
            left: vec![[0.5, 0.75f64.sqrt()], [1.5, 3.0 * 0.75f64.sqrt()]],
        };
        let beyond_right = seam.across([2.0, 0.1], [2.0, -0.1]).unwrap();
        let expected = seam.carried([2.0, -0.1], true);
        assert_eq!(beyond_right, expected);
        let back = seam.carried(expected, false);
        assert!((back[0] - 2.0).abs() < 1e-12 && (back[1] + 0.1).abs() < 1e-12);
        assert!(seam.across([2.0, 0.5], [2.0, 0.3]).is_none());
    }
}
