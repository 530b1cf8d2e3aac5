//! As-rigid-as-possible refinement of a flattening (Liu et al. 2008, local/global): each
//! triangle's best rotation onto its current image (local), then the positions that best fit
//! all the rotated triangles (global, one cotangent-Laplacian solve whose factorization is done
//! once). Where a conformal map lets cell sizes swell (annuli, strongly curved pieces), this
//! trades a little angle distortion for nearly kept lengths: what a hex grid of equal cells
//! needs.

use super::flatten::Point2;
use crate::geometry::Vec3;
use faer::linalg::solvers::SolveCore;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

/// The steps stop early once no point moves by more than this many mean edge lengths of S's
/// triangles in one step: the flattening is then at rest to round-off (a developable S is
/// after the first step), and the steps left would change nothing a lattice could see.
const AT_REST: f64 = 1e-8;

/// The mean edge length of the triangles in their own planes.
fn mean_edge(locals: &[[Point2; 3]]) -> f64 {
    let sum: f64 = locals
        .iter()
        .flat_map(|p| (0..3).map(move |k| (p[(k + 1) % 3], p[k])))
        .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
        .sum();
    sum / (3 * locals.len()).max(1) as f64
}

/// Moves `points` to `next` and says whether none moved by more than `rest`.
fn moved_to(points: &mut [Point2], next: impl Iterator<Item = (usize, Point2)>, rest: f64) -> bool {
    let mut at_rest = true;
    for (v, p) in next {
        let q = &mut points[v];
        at_rest &= (p[0] - q[0]).abs() <= rest && (p[1] - q[1]).abs() <= rest;
        *q = p;
    }
    at_rest
}

/// Each triangle in its own plane: corner coordinates in an orthonormal frame of the triangle.
fn local_triangle(vertices: &[Vec3], t: &[usize; 3]) -> [Point2; 3] {
    let [a, b, c] = t.map(|v| vertices[v]);
    let e1 = b - a;
    let x = e1.normalized();
    let n = e1.cross(c - a);
    let y = n.cross(e1).normalized();
    [
        [0.0, 0.0],
        [e1.norm(), 0.0],
        [(c - a).dot(x), (c - a).dot(y)],
    ]
}

/// Each triangle in its own plane, and the half-cotangent weight of its edge (k+1, k+2): the
/// angle at k faces it.
fn locals_and_weights(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
) -> (Vec<[Point2; 3]>, Vec<[f64; 3]>) {
    let locals: Vec<[Point2; 3]> = triangles
        .iter()
        .map(|t| local_triangle(vertices, t))
        .collect();
    let weights = locals
        .iter()
        .map(|p| [0, 1, 2].map(|k| 0.5 * cot_at(*p, k).clamp(0.0, 100.0)))
        .collect();
    (locals, weights)
}

fn cot_at(p: [Point2; 3], k: usize) -> f64 {
    // Cotangent of the angle at corner k.
    let (o, a, b) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
    let (u, v) = ([a[0] - o[0], a[1] - o[1]], [b[0] - o[0], b[1] - o[1]]);
    let cross = (u[0] * v[1] - u[1] * v[0]).abs();
    if cross < 1e-300 {
        0.0
    } else {
        (u[0] * v[0] + u[1] * v[1]) / cross
    }
}

/// Refines `points` in place by at most `iterations` local/global steps (fewer where they come
/// to rest, [`AT_REST`]); vertex 0 stays where it is. Returns the steps taken, or `None` (and
/// leaves `points` alone) when the Laplacian cannot be factorized.
pub fn refine(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    points: &mut [Point2],
    iterations: usize,
) -> Option<usize> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let (locals, weights) = locals_and_weights(vertices, triangles);
    // Laplacian over vertices 1..n (vertex 0 pinned), lower triangle.
    let index = |v: usize| v.checked_sub(1);
    let mut triplets = Vec::new();
    for (t, w) in triangles.iter().zip(&weights) {
        for k in 0..3 {
            let (i, j, c) = (t[(k + 1) % 3], t[(k + 2) % 3], w[k]);
            for a in [i, j].into_iter().filter_map(index) {
                triplets.push(Triplet::new(a, a, c));
            }
            if let (Some(a), Some(b)) = (index(i), index(j)) {
                triplets.push(Triplet::new(a.max(b), a.min(b), -c));
            }
        }
    }
    let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(n - 1, n - 1, &triplets).ok()?;
    let llt = matrix.sp_cholesky(Side::Lower).ok()?;
    let pinned = points[0];
    let rest = AT_REST * mean_edge(&locals);
    let mut rhs = Mat::<f64>::zeros(n - 1, 2);
    let mut steps = 0;
    while steps < iterations {
        steps += 1;
        rhs.fill(0.0);
        for ((t, local), w) in triangles.iter().zip(&locals).zip(&weights) {
            let rotation = best_rotation(t.map(|v| points[v]), *local, *w);
            for k in 0..3 {
                let (i, j, c) = (t[(k + 1) % 3], t[(k + 2) % 3], w[k]);
                let d = rotated_edge(rotation, local, k);
                // Both ends of the edge pull towards the rotated edge.
                for (v, sign) in [(i, 1.0), (j, -1.0)] {
                    if let Some(a) = index(v) {
                        rhs[(a, 0)] += sign * c * d[0];
                        rhs[(a, 1)] += sign * c * d[1];
                    }
                }
                // A pinned neighbour moves its term to the right-hand side.
                for (v, other) in [(i, j), (j, i)] {
                    if let (Some(a), None) = (index(v), index(other)) {
                        rhs[(a, 0)] += c * pinned[0];
                        rhs[(a, 1)] += c * pinned[1];
                    }
                }
            }
        }
        llt.solve_in_place_with_conj(faer::Conj::No, rhs.as_mut());
        let next = (1..n).map(|v| (v, [rhs[(v - 1, 0)], rhs[(v - 1, 1)]]));
        if moved_to(points, next, rest) {
            break;
        }
    }
    Some(steps)
}

/// The rotation (cos, sin) that best turns the local triangle onto its image (weighted
/// Procrustes in the plane: the angle of the summed cross and dot products).
fn best_rotation(image: [Point2; 3], local: [Point2; 3], w: [f64; 3]) -> [f64; 2] {
    let (mut dot, mut cross) = (0.0, 0.0);
    for (k, wk) in w.iter().enumerate() {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let u = [image[i][0] - image[j][0], image[i][1] - image[j][1]];
        let x = [local[i][0] - local[j][0], local[i][1] - local[j][1]];
        dot += wk * (u[0] * x[0] + u[1] * x[1]);
        cross += wk * (x[0] * u[1] - x[1] * u[0]);
    }
    let r = (dot * dot + cross * cross).sqrt();
    if r > 0.0 {
        [dot / r, cross / r]
    } else {
        [1.0, 0.0]
    }
}

/// Edge (k+1, k+2) of the triangle in its own plane `local`, turned by `r`: where the global
/// step pulls that edge.
fn rotated_edge(r: [f64; 2], local: &[Point2; 3], k: usize) -> Point2 {
    let (li, lj) = (local[(k + 1) % 3], local[(k + 2) % 3]);
    rotate(r, [li[0] - lj[0], li[1] - lj[1]])
}

/// `v` turned by the rotation `r` (cos, sin).
pub(super) fn rotate(r: [f64; 2], v: Point2) -> Point2 {
    [r[0] * v[0] - r[1] * v[1], r[1] * v[0] + r[0] * v[1]]
}

/// A 2x2 matrix, rows first.
type Block = [[f64; 2]; 2];

const IDENTITY: Block = [[1.0, 0.0], [0.0, 1.0]];

fn block_of(r: [f64; 2]) -> Block {
    [[r[0], -r[1]], [r[1], r[0]]]
}

/// a^T b.
fn transpose_times(a: Block, b: Block) -> Block {
    [0, 1].map(|r| [0, 1].map(|s| a[0][r] * b[0][s] + a[1][r] * b[1][s]))
}

fn apply(m: Block, v: Point2) -> Point2 {
    [
        m[0][0] * v[0] + m[0][1] * v[1],
        m[1][0] * v[0] + m[1][1] * v[1],
    ]
}

/// [`refine`] for a surface cut open along a seam whose two sides stay images of each other:
/// each `(right, left)` pair of `pairs` keeps `left = R right + t`, R the turn `turn` (cos, sin)
/// and t free. Returns the steps taken, or `None` when the system cannot be factorized or the
/// points end not finite.
pub fn refine_seamed(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    points: &mut [Point2],
    iterations: usize,
    pairs: &[(usize, usize)],
    turn: [f64; 2],
) -> Option<usize> {
    let n = points.len();
    let mut partner = vec![usize::MAX; n];
    for &(right, left) in pairs {
        partner[left] = right;
    }
    let pin = (0..n).find(|&v| partner[v] == usize::MAX && !pairs.iter().any(|p| p.0 == v))?;
    // Two unknowns per vertex that is neither pinned nor a left copy, then two for t.
    let mut unknown = vec![usize::MAX; n];
    let mut m = 0;
    for v in 0..n {
        if v != pin && partner[v] == usize::MAX {
            unknown[v] = m;
            m += 2;
        }
    }
    let t_unknown = m;
    m += 2;
    let rotation = block_of(turn);
    let pinned = points[pin];
    // A vertex as a sum of blocks times unknown pairs, plus a constant.
    let expression = |v: usize| -> (Vec<(Block, usize)>, Point2) {
        let (right, map) = match partner[v] {
            usize::MAX => (v, IDENTITY),
            r => (r, rotation),
        };
        let mut terms = Vec::with_capacity(2);
        let constant = if right == pin {
            apply(map, pinned)
        } else {
            terms.push((map, unknown[right]));
            [0.0, 0.0]
        };
        if partner[v] != usize::MAX {
            terms.push((IDENTITY, t_unknown));
        }
        (terms, constant)
    };
    let (locals, weights) = locals_and_weights(vertices, triangles);
    // Each edge of each triangle: u_i - u_j as terms and a constant.
    let mut edges = Vec::with_capacity(3 * triangles.len());
    let mut triplets = Vec::new();
    for (t, w) in triangles.iter().zip(&weights) {
        for k in 0..3 {
            let (i, j, c) = (t[(k + 1) % 3], t[(k + 2) % 3], w[k]);
            let (mut terms, ci) = expression(i);
            let (others, cj) = expression(j);
            terms.extend(
                others
                    .into_iter()
                    .map(|(b, u)| (b.map(|row| row.map(|x| -x)), u)),
            );
            // c (Bk^T Bl) at block (k, l), the lower triangle only.
            for &(bk, uk) in &terms {
                for &(bl, ul) in &terms {
                    for (r, row) in transpose_times(bk, bl).iter().enumerate() {
                        for (s, g) in row.iter().enumerate() {
                            if uk + r >= ul + s && *g != 0.0 {
                                triplets.push(Triplet::new(uk + r, ul + s, c * g));
                            }
                        }
                    }
                }
            }
            edges.push((terms, [ci[0] - cj[0], ci[1] - cj[1]]));
        }
    }
    let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(m, m, &triplets).ok()?;
    let llt = matrix.sp_cholesky(Side::Lower).ok()?;
    let rest = AT_REST * mean_edge(&locals);
    let mut rhs = Mat::<f64>::zeros(m, 1);
    let mut steps = 0;
    while steps < iterations {
        steps += 1;
        rhs.fill(0.0);
        let mut edge = edges.iter();
        for ((t, local), w) in triangles.iter().zip(&locals).zip(&weights) {
            let r = best_rotation(t.map(|v| points[v]), *local, *w);
            for (k, c) in w.iter().enumerate() {
                let d = rotated_edge(r, local, k);
                let (terms, constant) = edge.next().expect("one per edge");
                let target = [c * (d[0] - constant[0]), c * (d[1] - constant[1])];
                for &(b, u) in terms {
                    rhs[(u, 0)] += b[0][0] * target[0] + b[1][0] * target[1];
                    rhs[(u + 1, 0)] += b[0][1] * target[0] + b[1][1] * target[1];
                }
            }
        }
        llt.solve_in_place_with_conj(faer::Conj::No, rhs.as_mut());
        let t = [rhs[(t_unknown, 0)], rhs[(t_unknown + 1, 0)]];
        let next = (0..n)
            .filter(|&v| unknown[v] != usize::MAX)
            .map(|v| (v, [rhs[(unknown[v], 0)], rhs[(unknown[v] + 1, 0)]]));
        let right_at_rest = moved_to(points, next, rest);
        let next = pairs.iter().map(|&(right, left)| {
            let turned = apply(rotation, points[right]);
            (left, [turned[0] + t[0], turned[1] + t[1]])
        });
        let next: Vec<(usize, Point2)> = next.collect();
        if moved_to(points, next.into_iter(), rest) && right_at_rest {
            break;
        }
    }
    points
        .iter()
        .all(|p| p[0].is_finite() && p[1].is_finite())
        .then_some(steps)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An 8 x 8 grid of unit squares, each split into two triangles, lifted by `height`.
    fn grid(height: impl Fn(f64, f64) -> f64) -> (Vec<Vec3>, Vec<[usize; 3]>) {
        let n = 9;
        let vertices = (0..n * n)
            .map(|k| {
                let (x, y) = ((k % n) as f64, (k / n) as f64);
                Vec3::new(x, y, height(x, y))
            })
            .collect();
        let triangles = (0..n - 1)
            .flat_map(|j| (0..n - 1).map(move |i| j * n + i))
            .flat_map(|a| [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]])
            .collect();
        (vertices, triangles)
    }

    /// A plane laid out stretched comes to rest at its own shape in two steps (the first
    /// finds it, the second moves nothing) and stops there; a curved cap, which no
    /// flattening keeps rigid, settles only slowly and takes many more.
    #[test]
    fn the_steps_stop_once_the_flattening_is_at_rest() {
        let (flat, triangles) = grid(|_, _| 0.0);
        let stretched = |v: &[Vec3]| -> Vec<Point2> {
            v.iter()
                .map(|p| [1.1 * (p.x - v[0].x), 1.1 * (p.y - v[0].y)])
                .collect()
        };
        let mut points = stretched(&flat);
        assert_eq!(refine(&flat, &triangles, &mut points, 30), Some(2));
        for (p, v) in points.iter().zip(&flat) {
            assert!(
                (p[0] - v.x).abs() < 1e-9 && (p[1] - v.y).abs() < 1e-9,
                "{p:?}"
            );
        }
        let (cap, triangles) = grid(|x, y| 0.05 * ((x - 4.0).powi(2) + (y - 4.0).powi(2)));
        let mut points = stretched(&cap);
        let steps = refine(&cap, &triangles, &mut points, 30).unwrap();
        assert!(steps > 10, "{steps}");
    }
}
