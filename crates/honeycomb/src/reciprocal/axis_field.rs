//! The node axes designed first: a sheet of unit triangles (every wall a unit difference of
//! cell points) whose normals fit target axes, solved on the sheet's points alone.
//!
//! Each node's triangle is a rigid copy of one unit triangle, turned by a rotation of its own
//! (`RigidTriangles`); the solve asks neighbouring triangles to agree on their shared points.
//! Solved with unit distances between the points instead, a step that bends the sheet far
//! stretches it to second order, and the iteration crawls; a rotation turns a triangle far
//! without stretching it. The rotations are eliminated before each factorization (no row
//! joins two of them), so the factor is over the points only.

use super::ghosts::Ghosts;
use super::Sheet;
use crate::constraints::{OrthogonalDifference, RigidTriangles, SharedRotations};
use crate::error::Result;
use crate::geometry::rotation::{frame, multiply, Matrix3};
use crate::geometry::Vec3;
use crate::solve::{
    Cancel, Constraint, GuidedProjection, IterationInfo, Role, SolveReport, SolveState,
    SolverOptions,
};

/// How the sheet is fitted.
#[derive(Clone, Debug)]
pub struct AxisFieldOptions {
    pub iterations: usize,
    /// Weight of the rigid triangles (the honeycomb's condition).
    pub rigid: f64,
    /// Weight of the axes along their targets, at the start; it fades.
    pub axes: f64,
    /// Weight of the walls across the base mesh's edges, at the start; it fades.
    pub across: f64,
    /// Weight of each wall normal facing the way it faces in the base mesh (across its edge
    /// within S), at the start; it fades.
    pub facing: f64,
    /// The factor the fitting weights fade by per iteration.
    pub fade: f64,
    /// Iterations the fitting weights have faded by already: the fit of the rest of a sheet
    /// whose broken cells were dropped before its fit was done goes on with them as faded.
    pub faded: usize,
    pub eps: f64,
    /// The factor a step may multiply the energy by before it is halved: close to 1, since
    /// the sheet's rows bend it far and a step the linearization overrates only wanders.
    pub energy_growth: f64,
    /// The sheet is done when every squared wall length is this close to 1.
    pub tolerance: f64,
    pub cancel: Cancel,
}

impl Default for AxisFieldOptions {
    fn default() -> Self {
        AxisFieldOptions {
            iterations: 60,
            rigid: 10.0,
            axes: 1.0,
            across: 1.0,
            facing: 0.0,
            fade: 0.5,
            faded: 0,
            eps: 1e-3,
            energy_growth: 1.1,
            tolerance: 1e-8,
            cancel: Cancel::default(),
        }
    }
}

/// Once the guides have faded to this share of their start they no longer steer the fit: the
/// ghosts are then set by their own walls between the steps ([`Ghosts`]), while some wall is
/// still this far from unit length (in `|p_a - p_b|^2 - 1`).
const GHOSTS_SETTLE_BELOW: f64 = 1.0 / 256.0;
const GHOSTS_SETTLE_ABOVE_GAP: f64 = 1e-2;
/// Once every wall is this close to unit length the guides are let go: the sheet's fold is
/// set, and the last steps only make its walls unit.
const GUIDES_RELEASED_BELOW: f64 = 1e-3;
/// A fit still short of unit walls this many steps after its guides were let go is crawling
/// along the soft folds of a nearly flat sheet, where halving a step that raised the energy
/// only holds the regularization up; from then on a step is taken whole unless it multiplies
/// the energy by more than this, as in the guided projection.
const CRAWLING_AFTER: usize = 4;
const CRAWLING_ENERGY_GROWTH: f64 = 100.0;

/// How far `points` of `sheet` are from unit walls: the largest `| |p_a - p_b|^2 - 1 |`.
pub fn unit_gap(sheet: &Sheet, points: &[Vec3]) -> f64 {
    let y: Vec<f64> = points.iter().flat_map(|p| p.to_array()).collect();
    max_gap(&y, &sheet.unit_pairs())
}

/// The largest `| |p_a - p_b|^2 - 1 |` over `pairs` of the points in `y`.
fn max_gap(y: &[f64], pairs: &[[usize; 2]]) -> f64 {
    pairs.iter().fold(0.0f64, |m, &[a, b]| {
        let d = Vec3::from_slice(&y[3 * a..]) - Vec3::from_slice(&y[3 * b..]);
        m.max((d.norm_squared() - 1.0).abs())
    })
}

/// The corners of the reference triangle: unit sides, in z = 0, counterclockwise.
fn reference_corner(k: usize) -> Vec3 {
    let a = std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::FRAC_PI_3 * k as f64;
    Vec3::new(a.cos(), a.sin(), 0.0) / 3f64.sqrt()
}

/// The sides of the reference triangle, from its corner k to corner k + 1.
pub(super) fn reference_sides() -> [Vec3; 3] {
    std::array::from_fn(|k| reference_corner(k + 1) - reference_corner(k))
}

/// The rotation that turns the reference triangle, whose first side is `first_side`, towards
/// triangle `p`: its first side along `p`'s, its normal along `p`'s.
pub(super) fn fitted_rotation(p: [Vec3; 3], first_side: Vec3) -> Matrix3 {
    let n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
    let t = (p[1] - p[0]).normalized();
    let r = frame(first_side.normalized(), Vec3::new(0.0, 0.0, 1.0));
    let back: Matrix3 = std::array::from_fn(|i| std::array::from_fn(|j| r[j][i]));
    multiply(&frame(t, n), &back)
}

/// A fit of `sheet` to one target axis per vertex, keeping each wall across its edge of the
/// base mesh and, optionally, its normal facing out (see [`AxisFit::new`]). It may stop
/// short of unit walls and later go on from where it stopped, as if it had not: its guides
/// as faded, its regularization and rotations as they were.
pub struct AxisFit<'a> {
    sheet: &'a Sheet,
    pairs: Vec<[usize; 2]>,
    /// The points, then one turn per triangle (zero between steps).
    y: Vec<f64>,
    solver: GuidedProjection<'a>,
    solver_options: SolverOptions,
    state: SolveState,
    bases: SharedRotations,
    ghosts: Ghosts,
    /// The factor the guides fade by per iteration, and the iterations they faded by before.
    fade: f64,
    faded: usize,
    /// Steps that ended with every wall within the gap at which the guides are let go.
    released_steps: usize,
    /// The walls are within the tolerance of the last `run`.
    met: bool,
}

impl<'a> AxisFit<'a> {
    /// The fit of `sheet` from `points`, before its first step, to one target axis per vertex
    /// (`targets`, unit), keeping each wall across its edge, whose direction in the base mesh
    /// is `edges[e]` (unit, or zero for none), and its normal facing `facing[e]` (unit: the
    /// edge's normal within S, or zero for none).
    pub fn new(
        sheet: &'a Sheet,
        points: &[Vec3],
        targets: &[Vec3],
        edges: &[Vec3],
        facing: &[Vec3],
        options: &AxisFieldOptions,
    ) -> Result<AxisFit<'a>> {
        let (np, nt) = (points.len(), sheet.triangles.len());
        let sides = reference_sides();
        let bases = SharedRotations::new(
            sheet
                .triangles
                .iter()
                .map(|t| fitted_rotation(t.map(|p| points[p]), sides[0]))
                .collect(),
        );
        // A node's axis along its target: both sides of its triangle from its first point
        // orthogonal to it.
        let axis_rows = sheet
            .triangles
            .iter()
            .zip(targets)
            .flat_map(|(&[a, b, c], &t)| [([b, a], t), ([c, a], t)])
            .collect();
        // One row per wall with a direction given (zero: none).
        let side_rows = |directions: &[Vec3]| {
            (sheet.sides.iter().zip(directions))
                .filter(|(_, d)| d.norm() > 0.0)
                .map(|(&s, &d)| (s, d))
                .collect()
        };
        let faded = options.fade.powi(options.faded as i32);
        let guide = |name, rows, weight: f64| OrthogonalDifference {
            name,
            rows,
            value: 0.0,
            weight: weight * faded,
            role: Role::Guide,
            fade: options.fade,
        };
        let mut families: Vec<Box<dyn Constraint>> = vec![
            Box::new(RigidTriangles {
                triangles: sheet.triangles.clone(),
                rotations: np,
                bases: bases.clone(),
                sides,
                weight: options.rigid,
            }),
            Box::new(guide("axes_along_targets", axis_rows, options.axes)),
        ];
        if options.across > 0.0 {
            families.push(Box::new(guide(
                "walls_across_edges",
                side_rows(edges),
                options.across,
            )));
        }
        if options.facing > 0.0 {
            // The orthogonality rows hold a triangle turned over as well as one facing up; these
            // tell the two apart while the sheet takes its folds.
            families.push(Box::new(OrthogonalDifference {
                value: 1.0,
                ..guide("walls_facing_out", side_rows(facing), options.facing)
            }));
        }
        let mut positions: Vec<Option<Vec3>> = points.iter().map(|&p| Some(p)).collect();
        positions.extend(
            sheet
                .triangles
                .iter()
                .map(|t| Some((points[t[0]] + points[t[1]] + points[t[2]]) / 3.0)),
        );
        let rotation_blocks: Vec<usize> = (np..np + nt).collect();
        let solver = GuidedProjection::eliminating(
            3 * (np + nt),
            families,
            Some(&positions),
            &rotation_blocks,
        )?;
        let solver_options = SolverOptions {
            max_iterations: options.iterations,
            eps: options.eps,
            // Done by the walls' lengths, below: the rows of the fit never vanish.
            tolerance: 0.0,
            energy_growth: options.energy_growth,
            cancel: options.cancel.clone(),
            ..SolverOptions::default()
        };
        let mut y: Vec<f64> = points.iter().flat_map(|p| p.to_array()).collect();
        y.resize(3 * (np + nt), 0.0);
        Ok(AxisFit {
            sheet,
            pairs: sheet.unit_pairs(),
            y,
            solver,
            solver_options,
            state: SolveState::new(options.eps),
            bases,
            ghosts: Ghosts::new(sheet),
            fade: options.fade,
            faded: options.faded,
            released_steps: 0,
            met: false,
        })
    }

    /// Steps until every wall is within `tolerance` of unit length (in `|p_a - p_b|^2 - 1`),
    /// or the fit's iterations are spent; whether it got there.
    pub fn run(
        &mut self,
        tolerance: f64,
        progress: &mut dyn FnMut(&IterationInfo),
    ) -> Result<bool> {
        let (sheet, np) = (self.sheet, self.sheet.points());
        let nt = sheet.triangles.len();
        let sides = reference_sides();
        let mut gap = max_gap(&self.y, &self.pairs);
        while gap >= tolerance && self.state.iterations() < self.solver_options.max_iterations {
            let (y, state) = (&mut self.y, &mut self.state);
            match self.solver.iterate(y, state, &self.solver_options)? {
                Some(info) => progress(&info),
                None => break,
            }
            // The step's turns into the base rotations: the next linearization is at zero
            // turn.
            let turns: Vec<Vec3> = (0..nt)
                .map(|t| Vec3::from_slice(&y[3 * (np + t)..]))
                .collect();
            self.bases.rebase(&turns);
            y[3 * np..].fill(0.0);
            // The ghosts crawl where the steps' linearization fails, far from unit walls; near
            // them the steps converge fast on their own, and settled ghosts only pull against
            // what is left of the guides.
            let steps = self.faded + state.iterations();
            let faded = self.fade.powi(steps as i32) <= GHOSTS_SETTLE_BELOW;
            gap = max_gap(y, &self.pairs);
            if faded && gap >= GHOSTS_SETTLE_ABOVE_GAP {
                let mut p: Vec<Vec3> = y[..3 * np].chunks(3).map(Vec3::from_slice).collect();
                self.ghosts
                    .settle(&mut p, &sheet.triangles, sides[0], &self.bases);
                for (k, q) in p.iter().enumerate().skip(sheet.cells) {
                    y[3 * k..3 * k + 3].copy_from_slice(&q.to_array());
                }
                gap = max_gap(y, &self.pairs);
            }
            if gap < GUIDES_RELEASED_BELOW {
                state.release_guides();
                self.released_steps += 1;
                if self.released_steps == CRAWLING_AFTER {
                    self.solver_options.energy_growth = CRAWLING_ENERGY_GROWTH;
                }
            }
        }
        self.met = gap < tolerance;
        Ok(self.met)
    }

    /// The sheet's points as they stand.
    pub fn points(&self) -> Vec<Vec3> {
        let np = self.sheet.points();
        self.y[..3 * np].chunks(3).map(Vec3::from_slice).collect()
    }

    /// The report of every step taken; converged where the last `run` got there.
    pub fn finish(mut self) -> SolveReport {
        let mut solve = self
            .solver
            .report(&self.y, self.state, &self.solver_options);
        solve.converged = self.met;
        solve
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::hex_disk;
    use crate::mesh::validate_base_mesh;

    /// A fit stopped short of unit walls and taken on from there ends where one that never
    /// stopped ends, in as many steps; a sheet of unit walls takes none.
    #[test]
    fn a_fit_goes_on_from_where_it_stopped() {
        let mesh = hex_disk(4.0);
        let conn = validate_base_mesh(&mesh).unwrap();
        let sheet = Sheet::new(&mesh, &conn).unwrap();
        // A saddle's normals: the sheet must fold to follow them.
        let normal = |p: Vec3| Vec3::new(-p.x, p.y, 2.0).normalized();
        let targets: Vec<Vec3> = mesh.vertices.iter().map(|&p| normal(p)).collect();
        let points = sheet.initial_points(&mesh, &conn, normal);
        let none = vec![Vec3::ZERO; conn.num_edges()];
        let options = AxisFieldOptions::default();
        let to_unit = options.tolerance;
        let new = |points: &[Vec3]| {
            AxisFit::new(&sheet, points, &targets, &none, &none, &options).unwrap()
        };

        let mut straight = new(&points);
        assert!(straight.run(to_unit, &mut |_| {}).unwrap());
        let straight_points = straight.points();
        let straight = straight.finish();

        let mut stopping = new(&points);
        assert!(stopping.run(1e-2, &mut |_| {}).unwrap());
        let short = unit_gap(&sheet, &stopping.points());
        assert!((to_unit..1e-2).contains(&short), "stopped at {short}");
        assert!(stopping.run(to_unit, &mut |_| {}).unwrap());
        let stopped_points = stopping.points();
        let stopped = stopping.finish();

        assert!(straight.iterations > 3 && straight.converged);
        assert_eq!(stopped.iterations, straight.iterations);
        assert!(stopped.converged);
        for (a, b) in stopped_points.iter().zip(&straight_points) {
            assert!((*a - *b).norm() < 1e-12, "{a:?} against {b:?}");
        }
        assert!(unit_gap(&sheet, &stopped_points) < to_unit);

        let mut fitted = new(&stopped_points);
        assert!(fitted.run(to_unit, &mut |_| {}).unwrap());
        let none_taken = fitted.finish();
        assert_eq!((none_taken.iterations, none_taken.factorizations), (0, 0));
    }
}
