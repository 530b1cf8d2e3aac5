//! Walls that stay convex while the vertices move on kept walls. The wall of edge `(a, b)` at
//! depth `d` is the quad `[v_a, v_b, v_b + d a_b, v_a + d a_a]`; with its normal `n` and the
//! node axes `a_a`, `a_b` fixed, the turn at each corner, `n . (next - corner) x (previous -
//! corner)`, is linear in `v_a` and `v_b`. A wall is convex while its four turns keep the sign
//! they started with; an edge that runs backwards along its wall flips the first two, one that
//! crosses its wall the last two. One one-sided row per corner: `max(0, margin - s * turn)`,
//! zero while the corner turns the way it did by at least `margin` (`s` the starting sign).

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;

/// How much of a corner's starting turn it keeps at least: a turn that nearly vanishes is a
/// wall about to cross itself.
const KEPT_TURN: f64 = 0.2;

/// One corner's turn: `along_a . v_a + along_b . v_b + offset`.
#[derive(Clone, Copy, Debug)]
struct Turn {
    along_a: Vec3,
    along_b: Vec3,
    offset: f64,
}

impl Turn {
    fn at(&self, va: Vec3, vb: Vec3) -> f64 {
        self.along_a.dot(va) + self.along_b.dot(vb) + self.offset
    }
}

/// A wall convex at the start: its corners' turns, their starting sign and the margins they
/// keep.
#[derive(Clone, Debug)]
struct ConvexWall {
    a: usize,
    b: usize,
    turns: [Turn; 4],
    sign: f64,
    margins: [f64; 4],
}

pub struct WallConvexity {
    pub layout: Layout,
    walls: Vec<ConvexWall>,
    pub weight: f64,
}

/// The four turns of the wall of edge `(a, b)` with unit normal `n` and node axes `axis_a`,
/// `axis_b` (unit), at depth `depth`, as linear functions of `v_a`, `v_b`.
fn turns(n: Vec3, axis_a: Vec3, axis_b: Vec3, depth: f64) -> [Turn; 4] {
    let (da, db) = (axis_a * depth, axis_b * depth);
    // (u x w) . n = u . (w x n) = w . (n x u).
    let w0 = da.cross(n);
    let w1 = n.cross(db);
    let w2 = (-db).cross(n);
    let w3 = n.cross(-da);
    [
        // At v_a: (v_b - v_a) x d a_a.
        Turn {
            along_a: -w0,
            along_b: w0,
            offset: 0.0,
        },
        // At v_b: d a_b x (v_a - v_b).
        Turn {
            along_a: w1,
            along_b: -w1,
            offset: 0.0,
        },
        // At v_b + d a_b: (v_a + d a_a - v_b - d a_b) x (-d a_b).
        Turn {
            along_a: w2,
            along_b: -w2,
            offset: (da - db).dot(w2),
        },
        // At v_a + d a_a: (-d a_a) x (v_b + d a_b - v_a - d a_a).
        Turn {
            along_a: -w3,
            along_b: w3,
            offset: (db - da).dot(w3),
        },
    ]
}

impl WallConvexity {
    /// Every wall of `edges` (with unit `normals`) that is convex at `vertices`, with the node
    /// `axes`, at `depth`.
    pub fn new(
        layout: Layout,
        vertices: &[Vec3],
        edges: &[[usize; 2]],
        normals: &[Vec3],
        axes: &[Vec3],
        depth: f64,
        weight: f64,
    ) -> Self {
        let walls = (edges.iter().zip(normals))
            .filter_map(|(&[a, b], &n)| {
                let turns = turns(n, axes[a], axes[b], depth);
                let start = turns.map(|t| t.at(vertices[a], vertices[b]));
                let sign = start[0].signum();
                (start.iter().all(|&t| t * sign > 0.0)).then(|| ConvexWall {
                    a,
                    b,
                    turns,
                    sign,
                    margins: start.map(|t| KEPT_TURN * t.abs()),
                })
            })
            .collect();
        WallConvexity {
            layout,
            walls,
            weight,
        }
    }
}

impl Constraint for WallConvexity {
    fn name(&self) -> &str {
        "wall_convexity"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        4 * self.walls.len()
    }
    fn arity(&self) -> usize {
        6
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        let w = &self.walls[row / 4];
        triple(&mut vars[0..3], self.layout.vertex(w.a));
        triple(&mut vars[3..6], self.layout.vertex(w.b));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (k, w) in self.walls.iter().enumerate() {
            let (va, vb) = (self.layout.vertex_at(x, w.a), self.layout.vertex_at(x, w.b));
            for (c, turn) in w.turns.iter().enumerate() {
                let row = 4 * k + c;
                let short = w.margins[c] - w.sign * turn.at(va, vb);
                let j = &mut jac[6 * row..6 * row + 6];
                if short > 0.0 {
                    res[row] = short;
                    put(&mut j[0..3], turn.along_a * -w.sign);
                    put(&mut j[3..6], turn.along_b * -w.sign);
                } else {
                    res[row] = 0.0;
                    j.fill(0.0);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::structure::is_convex;

    /// The turns are the corners' cross products: their signs agree with `is_convex` as an
    /// edge shortens, reverses along its wall, or crosses its wall.
    #[test]
    fn the_turns_are_the_corners_cross_products() {
        let (axis_a, axis_b) = (
            Vec3::new(0.2, 0.0, 1.0).normalized(),
            Vec3::new(-0.3, 0.0, 1.0).normalized(),
        );
        let n = Vec3::new(0.0, 1.0, 0.0);
        let depth = 2.0;
        let t = turns(n, axis_a, axis_b, depth);
        let va = Vec3::new(0.0, 0.0, 0.0);
        for bx in [1.0, 0.5, 0.1, -0.2, -1.0] {
            let vb = Vec3::new(bx, 0.0, 0.3);
            let p = [va, vb, vb + axis_b * depth, va + axis_a * depth];
            for (c, turn) in t.iter().enumerate() {
                let corner = (p[(c + 1) % 4] - p[c]).cross(p[(c + 3) % 4] - p[c]).dot(n);
                assert!((turn.at(va, vb) - corner).abs() < 1e-12, "{bx} {c}");
            }
            let same_sign =
                t.iter().all(|x| x.at(va, vb) > 0.0) || t.iter().all(|x| x.at(va, vb) < 0.0);
            assert_eq!(same_sign, is_convex(p), "{bx}");
        }
    }

    /// Rows vanish while every corner keeps its margin, and grow as one gives it up.
    #[test]
    fn a_wall_that_starts_to_cross_is_pushed_back() {
        let axes = [
            Vec3::new(0.2, 0.0, 1.0).normalized(),
            Vec3::new(-0.3, 0.0, 1.0).normalized(),
        ];
        let start = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.3)];
        let layout = Layout::new(2, 0);
        let c = WallConvexity::new(
            layout,
            &start,
            &[[0, 1]],
            &[Vec3::new(0.0, 1.0, 0.0)],
            &axes,
            1.0,
            1.0,
        );
        assert_eq!(c.num_rows(), 4);
        let rows = |b: Vec3| {
            let x: Vec<f64> = [start[0], b].iter().flat_map(|p| p.to_array()).collect();
            let mut res = vec![0.0; 4];
            let mut jac = vec![0.0; 24];
            c.evaluate(&x, &mut res, &mut jac);
            res
        };
        assert!(rows(start[1]).iter().all(|&r| r == 0.0));
        let reversed = rows(Vec3::new(-0.2, 0.0, 0.3));
        assert!(reversed[0] > 0.0 && reversed[1] > 0.0, "{reversed:?}");
        // Off the wall's plane and past the margins, the rows' Jacobian is the turns'.
        let x: Vec<f64> = [Vec3::new(0.05, 0.1, -0.02), Vec3::new(-0.2, 0.3, 0.3)]
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let err = crate::solve::jacobian_fd_error(&c, &x, 1e-6);
        assert!(err < 1e-7, "{err}");
    }
}
