//! Minimum edge length (paper section 4, remark; Tang et al. 2014): `|v_a - v_b|^2 = L^2 + d_e^2`
//! with one dummy unknown `d_e` per edge, so that the inequality `|v_a - v_b| >= L` becomes an
//! equation. The dummies are a block of their own after the honeycomb's unknowns.
//!
//! Where an edge is shorter than L no dummy meets the row, and Gauss-Newton on `d^2 = c < 0`
//! never settles: the linear model meets the row by a dummy step `c / 2d` that overshoots
//! through zero, and the next step back overshoots again. (On Yas Island at 4000 cells one
//! edge at 0.8 L kept its dummy swinging between +-2.5 L for 200 iterations, and the row's
//! residual, up to 0.6, stirred every other family.) So at each iteration's start such a
//! dummy is held at zero: its derivative vanishes and the row pushes the edge's ends apart
//! alone. Once the edge is at L or longer the dummy is let go, as a free dummy starts (see
//! `free_dummy`): it meets the row, or nearly, and lets the edge move on (a zero dummy would
//! pin it at exactly L).
//!
//! The seats belong to the unknowns of one solve: a solver whose unknowns are replaced from
//! outside between iterations (an undo) must build this family anew.

use super::layout::{put, triple, Layout};
use crate::geometry::Vec3;
use crate::solve::Constraint;

pub struct MinEdgeLength {
    pub layout: Layout,
    pub edges: Vec<[usize; 2]>,
    /// Per edge, its L, in the solver's (normalized) units.
    pub lengths: Vec<f64>,
    /// Index of the first dummy in the unknown vector.
    pub dummy_start: usize,
    pub weight: f64,
    /// Per edge, what is added to the dummy's unknown: the row sees `x[dummy] + seat`. A
    /// refresh reseats the dummy by changing this (the solver's unknowns are not ours to set).
    seat: Vec<f64>,
    /// Per edge, whether the dummy is held at zero (the edge was shorter than L).
    held: Vec<bool>,
}

impl MinEdgeLength {
    pub fn new(
        layout: Layout,
        edges: Vec<[usize; 2]>,
        length: f64,
        dummy_start: usize,
        weight: f64,
    ) -> MinEdgeLength {
        let lengths = vec![length; edges.len()];
        MinEdgeLength::with_lengths(layout, edges, lengths, dummy_start, weight)
    }

    /// Each edge at least its own length.
    pub fn with_lengths(
        layout: Layout,
        edges: Vec<[usize; 2]>,
        lengths: Vec<f64>,
        dummy_start: usize,
        weight: f64,
    ) -> MinEdgeLength {
        let m = edges.len();
        MinEdgeLength {
            layout,
            edges,
            lengths,
            dummy_start,
            weight,
            seat: vec![0.0; m],
            held: vec![false; m],
        }
    }

    fn dummy(&self, x: &[f64], e: usize) -> f64 {
        x[self.dummy_start + e] + self.seat[e]
    }

    /// Free dummies for `edges` of `vertices` and a minimum `length` (see `free_dummy`; edges
    /// shorter than L have theirs held at zero by the first refresh). Computed before the
    /// family is made: they are the block whose start it is given.
    pub fn initial_dummies(edges: &[[usize; 2]], length: f64, vertices: &[Vec3]) -> Vec<f64> {
        MinEdgeLength::initial_dummies_for(edges, &vec![length; edges.len()], vertices)
    }

    /// As `initial_dummies`, each edge against its own length.
    pub fn initial_dummies_for(
        edges: &[[usize; 2]],
        lengths: &[f64],
        vertices: &[Vec3],
    ) -> Vec<f64> {
        (edges.iter().zip(lengths))
            .map(|(&[a, b], &l)| free_dummy(l, (vertices[a] - vertices[b]).norm_squared()))
            .collect()
    }
}

/// The dummy of a free edge of squared length `l2` against a minimum `length`: the one that
/// meets the row, but never below L/10. The dummy enters squared, so near 0 its derivative
/// vanishes and an edge just longer than L would be held there instead of being free to move.
fn free_dummy(length: f64, l2: f64) -> f64 {
    (l2 - length * length).max(0.0).sqrt().max(0.1 * length)
}

impl Constraint for MinEdgeLength {
    fn name(&self) -> &str {
        "min_edge_length"
    }
    fn weight(&self) -> f64 {
        self.weight
    }
    fn num_rows(&self) -> usize {
        self.edges.len()
    }
    fn arity(&self) -> usize {
        7
    }
    fn row_variables(&self, e: usize, vars: &mut [usize]) {
        let [a, b] = self.edges[e];
        triple(&mut vars[0..3], self.layout.vertex(a));
        triple(&mut vars[3..6], self.layout.vertex(b));
        vars[6] = self.dummy_start + e;
    }
    fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
        for (e, &[a, b]) in self.edges.iter().enumerate() {
            let d = self.layout.vertex_at(x, a) - self.layout.vertex_at(x, b);
            let dummy = self.dummy(x, e);
            res[e] = d.norm_squared() - self.lengths[e] * self.lengths[e] - dummy * dummy;
            let j = &mut jac[7 * e..7 * e + 7];
            put(&mut j[0..3], d * 2.0);
            put(&mut j[3..6], d * -2.0);
            j[6] = -2.0 * dummy;
        }
    }
    fn refresh(&mut self, x: &[f64]) {
        for (e, &[a, b]) in self.edges.iter().enumerate() {
            let l2 = (self.layout.vertex_at(x, a) - self.layout.vertex_at(x, b)).norm_squared();
            let length = self.lengths[e];
            let seated = if l2 < length * length {
                self.held[e] = true;
                0.0
            } else if self.held[e] {
                self.held[e] = false;
                free_dummy(length, l2)
            } else {
                continue;
            };
            self.seat[e] = seated - x[self.dummy_start + e];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::{GuidedProjection, SolverOptions};

    /// Rows `v_0 - v_1 = 0`: a condition that wants the edge gone.
    struct Together {
        layout: Layout,
    }

    impl Constraint for Together {
        fn name(&self) -> &str {
            "together"
        }
        fn weight(&self) -> f64 {
            1.0
        }
        fn num_rows(&self) -> usize {
            3
        }
        fn arity(&self) -> usize {
            2
        }
        fn row_variables(&self, k: usize, vars: &mut [usize]) {
            vars[0] = self.layout.vertex(0) + k;
            vars[1] = self.layout.vertex(1) + k;
        }
        fn evaluate(&self, x: &[f64], res: &mut [f64], jac: &mut [f64]) {
            let d = self.layout.vertex_at(x, 0) - self.layout.vertex_at(x, 1);
            res.copy_from_slice(&d.to_array());
            for k in 0..3 {
                jac[2 * k] = 1.0;
                jac[2 * k + 1] = -1.0;
            }
        }
    }

    /// Two vertices pulled together against a minimum length L = 1: the least-squares
    /// compromise of `|e|^2 + (|e|^2 - 1)^2` is `|e| = 1 / sqrt 2`, with the dummy at zero. The
    /// solve settles there. With the dummy left free the edge collapsed to nothing: each linear
    /// model met the row by a dummy step instead of by the ends.
    #[test]
    fn against_a_pull_the_solve_settles_with_the_dummy_held() {
        let layout = Layout::new(2, 1);
        let family = MinEdgeLength::new(layout, vec![[0, 1]], 1.0, layout.len(), 1.0);
        let vertices = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0)];
        let mut x = layout.pack(&vertices, &[Vec3::new(0.0, 0.0, 1.0)]);
        x.extend(MinEdgeLength::initial_dummies(
            &family.edges,
            1.0,
            &vertices,
        ));
        let families: Vec<Box<dyn Constraint>> =
            vec![Box::new(Together { layout }), Box::new(family)];
        let mut solver = GuidedProjection::new(x.len(), families).unwrap();
        let opts = SolverOptions {
            max_iterations: 40,
            tolerance: 0.0,
            ..SolverOptions::default()
        };
        let report = solver.solve(&mut x, &opts, &mut |_| {}).unwrap();
        let length = (layout.vertex_at(&x, 0) - layout.vertex_at(&x, 1)).norm();
        assert!(
            (length - 0.5f64.sqrt()).abs() < 1e-9,
            "edge {length}, expected 1/sqrt 2"
        );
        let last = report.history.last().unwrap().step;
        assert!(last < 1e-9, "the last step moved {last}");
    }

    /// An edge shorter than L holds its dummy at zero (the row acts on the ends alone); once
    /// it is longer than L the dummy is let go as a free one: the row met, the edge free.
    #[test]
    fn a_short_edge_holds_its_dummy_and_a_long_one_gets_it_back() {
        let layout = Layout::new(2, 1);
        let mut family = MinEdgeLength::new(layout, vec![[0, 1]], 1.0, layout.len(), 1.0);
        let at = |l: f64, dummy: f64| {
            let mut x = layout.pack(
                &[Vec3::new(0.0, 0.0, 0.0), Vec3::new(l, 0.0, 0.0)],
                &[Vec3::new(0.0, 0.0, 1.0)],
            );
            x.push(dummy);
            x
        };
        let (mut res, mut jac) = ([0.0], [0.0; 7]);
        let short = at(0.8, 0.7);
        family.refresh(&short);
        family.evaluate(&short, &mut res, &mut jac);
        assert!((res[0] - (0.64 - 1.0)).abs() < 1e-15, "residual {}", res[0]);
        assert_eq!(jac[6], 0.0);
        assert!(jac[0] < 0.0, "the row moves the ends: {jac:?}");
        let long = at(1.25, 0.7);
        family.refresh(&long);
        family.evaluate(&long, &mut res, &mut jac);
        assert!(res[0].abs() < 1e-15, "residual {}", res[0]);
        assert!(
            (jac[6] + 2.0 * 0.75).abs() < 1e-15,
            "dummy derivative {}",
            jac[6]
        );
        // Held again, then let go at exactly L: the dummy comes back at L/10, not at zero,
        // where it would pin the edge at L for good.
        family.refresh(&short);
        let at_length = at(1.0, 0.7);
        family.refresh(&at_length);
        family.evaluate(&at_length, &mut res, &mut jac);
        assert!((res[0] + 0.01).abs() < 1e-15, "residual {}", res[0]);
        assert!((jac[6] + 0.2).abs() < 1e-15, "dummy derivative {}", jac[6]);
    }
}
