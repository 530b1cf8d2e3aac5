//! Each vertex held where it started along S (soft): `t . (v - v0) = 0` for two unit tangents
//! `t` of S at the start `v0`, two rows per vertex. Moves across S are left to closeness.
//! Without it, a condition that any shortened edge eases (a quad's planarity: a quad with a
//! vanishing side is a triangle) collapses edges along their walls, which nothing else resists.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;

pub struct TangentialHold {
    pub layout: Layout,
    /// Per vertex: where it started and two unit tangents of S there.
    pub starts: Vec<(Vec3, [Vec3; 2])>,
    pub weight: f64,
}

impl TangentialHold {
    /// Holds every vertex of `vertices` in the tangent plane orthogonal to `normal(v)`.
    pub fn new(
        layout: Layout,
        vertices: &[Vec3],
        normal: impl Fn(Vec3) -> Vec3,
        weight: f64,
    ) -> Self {
        let starts = vertices
            .iter()
            .map(|&p| {
                let n = normal(p);
                let t = n.any_orthogonal().normalized();
                (p, [t, n.cross(t).normalized()])
            })
            .collect();
        TangentialHold {
            layout,
            starts,
            weight,
        }
    }
}

impl Constraint for TangentialHold {
    fn name(&self) -> &str {
        "tangential_hold"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        2 * self.starts.len()
    }
    fn arity(&self) -> usize {
        3
    }
    fn row_variables(&self, row: usize, vars: &mut [usize]) {
        triple(vars, self.layout.vertex(row / 2));
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (v, (start, tangents)) in self.starts.iter().enumerate() {
            let d = self.layout.vertex_at(x, v) - *start;
            for (k, t) in tangents.iter().enumerate() {
                let row = 2 * v + k;
                res[row] = t.dot(d);
                put(&mut jac[3 * row..3 * row + 3], *t);
            }
        }
    }
}
