//! The ghosts of a sheet set by their own walls between the fit's steps.
//!
//! A ghost (a lattice cell the boundary cut away) hangs on the boundary cells and its
//! neighbouring ghosts by two to five walls, real and virtual, and nothing else holds it once
//! the fit's guides have faded. The fit's steps then swing the ghosts about those hinges
//! further than the linearization holds, each step is halved for the sake of a few of them,
//! and the whole sheet crawls. Set by a small solve of its own (its neighbours held), a ghost
//! goes where its walls are closest to unit length at once, its triangles turned after it,
//! and the next step starts there.

use super::axis_field::fitted_rotation;
use super::Sheet;
use crate::constraints::SharedRotations;
use crate::geometry::{solve_symmetric, sum_of_outer_products, Vec3};

/// Newton steps per ghost and sweep: its walls are few, so the steps converge fast
/// where its neighbours leave it a place at all.
const STEPS: usize = 3;
/// Halvings of a step that does not bring the ghost's walls closer to unit length.
const HALVINGS: usize = 5;
/// The damping of a ghost's step, relative to its normal matrix's trace: for a ghost whose
/// walls all lie in one plane (a flat stretch of sheet), which cannot move it out of that
/// plane to first order.
const DAMPING: f64 = 1e-9;

/// For each ghost of a sheet, the points at unit distance from it and the node triangles it
/// belongs to.
pub struct Ghosts {
    first: usize,
    neighbours: Vec<Vec<usize>>,
    triangles_of: Vec<Vec<usize>>,
    /// Every triangle with a ghost among its corners.
    triangles: Vec<usize>,
}

impl Ghosts {
    pub fn new(sheet: &Sheet) -> Ghosts {
        let first = sheet.cells;
        let mut neighbours = vec![Vec::new(); sheet.ghosts];
        for [a, b] in sheet.unit_pairs() {
            for (p, q) in [(a, b), (b, a)] {
                if p >= first {
                    neighbours[p - first].push(q);
                }
            }
        }
        let mut triangles_of = vec![Vec::new(); sheet.ghosts];
        for (t, corners) in sheet.triangles.iter().enumerate() {
            for &p in corners.iter().filter(|&&p| p >= first) {
                triangles_of[p - first].push(t);
            }
        }
        let mut triangles: Vec<usize> = triangles_of.iter().flatten().copied().collect();
        triangles.sort_unstable();
        triangles.dedup();
        Ghosts {
            first,
            neighbours,
            triangles_of,
            triangles,
        }
    }

    /// One sweep over the ghosts: each moved, every other point held, down the sum of its
    /// walls' squared gaps `(|p - q|^2 - 1)^2` (so that sum over the sheet never rises), but
    /// never across a hinge: no triangle of it is turned over. Then each triangle with a ghost
    /// starts again from the frame of its points, as the fit's first step does (`rotations`,
    /// per triangle of `corners`, of the reference triangle whose first side is `first_side`).
    pub fn settle(
        &self,
        points: &mut [Vec3],
        corners: &[[usize; 3]],
        first_side: Vec3,
        rotations: &SharedRotations,
    ) {
        for (k, around) in self.neighbours.iter().enumerate() {
            let g = self.first + k;
            let normal = |x: Vec3, points: &[Vec3], t: usize| {
                let p = corners[t].map(|c| if c == g { x } else { points[c] });
                (p[1] - p[0]).cross(p[2] - p[0])
            };
            let facing: Vec<(usize, Vec3)> = (self.triangles_of[k].iter())
                .map(|&t| (t, normal(points[g], points, t)))
                .collect();
            let turned_over = |x: Vec3, points: &[Vec3]| {
                (facing.iter()).any(|&(t, n)| normal(x, points, t).dot(n) <= 0.0)
            };
            points[g] = settled(points[g], around, points, turned_over);
        }
        for &t in &self.triangles {
            rotations.set(
                t,
                fitted_rotation(corners[t].map(|p| points[p]), first_side),
            );
        }
    }
}

/// `x` moved by a few Newton steps down `sum_q (|x - q|^2 - 1)^2` over `around`, never to
/// where `turned_over`.
fn settled(
    mut x: Vec3,
    around: &[usize],
    points: &[Vec3],
    turned_over: impl Fn(Vec3, &[Vec3]) -> bool,
) -> Vec3 {
    let gaps = |x: Vec3| -> f64 {
        (around.iter())
            .map(|&q| ((x - points[q]).norm_squared() - 1.0).powi(2))
            .sum()
    };
    for _ in 0..STEPS {
        // Newton's step on half the sum: the gaps' Jacobian rows are 2 (x - q), and each
        // stretched wall adds its curvature 2 (|x - q|^2 - 1) I; a compressed wall's would make
        // the matrix indefinite, and is left out.
        let mut normal = sum_of_outer_products(around.iter().map(|&q| (x - points[q]) * 2.0));
        let stretched: f64 = (around.iter())
            .map(|&q| 2.0 * ((x - points[q]).norm_squared() - 1.0).max(0.0))
            .sum();
        let trace = normal[0][0] + normal[1][1] + normal[2][2];
        for (i, row) in normal.iter_mut().enumerate() {
            row[i] += stretched + DAMPING * trace;
        }
        let rhs = (around.iter()).fold(Vec3::ZERO, |s, &q| {
            let d = x - points[q];
            s - d * (2.0 * (d.norm_squared() - 1.0))
        });
        let Some(mut step) = solve_symmetric(normal, rhs) else {
            break;
        };
        let now = gaps(x);
        let mut halvings = 0;
        while gaps(x + step) >= now || turned_over(x + step, points) {
            if halvings == HALVINGS {
                return x;
            }
            step = step * 0.5;
            halvings += 1;
        }
        x += step;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::hex_disk;
    use crate::geometry::rotation::{apply, exp, multiply};
    use crate::mesh::validate_base_mesh;
    use crate::reciprocal::axis_field::reference_sides;

    fn flat_sheet() -> (Sheet, Vec<Vec3>) {
        let mesh = hex_disk(4.0);
        let conn = validate_base_mesh(&mesh).unwrap();
        let sheet = Sheet::new(&mesh, &conn).unwrap();
        let up = Vec3::new(0.0, 0.0, 1.0);
        let lattice = sheet.initial_points(&mesh, &conn, |_| up);
        (sheet, lattice)
    }

    fn fitted_rotations(sheet: &Sheet, p: &[Vec3], sides: [Vec3; 3]) -> SharedRotations {
        SharedRotations::new(
            (sheet.triangles.iter())
                .map(|c| fitted_rotation(c.map(|k| p[k]), sides[0]))
                .collect(),
        )
    }

    fn gaps(sheet: &Sheet, p: &[Vec3]) -> Vec<f64> {
        (sheet.unit_pairs().iter())
            .map(|&[a, b]| (p[a] - p[b]).norm_squared() - 1.0)
            .collect()
    }

    /// On a flat sheet of unit walls whose ghosts were pushed off within its plane and whose
    /// ghost triangles were turned, each ghost returns to its lattice point and each triangle
    /// to its rotation, and the cells stay where they are.
    #[test]
    fn ghosts_pushed_off_return_to_the_lattice() {
        let (sheet, lattice) = flat_sheet();
        let sides = reference_sides();
        let rotations = fitted_rotations(&sheet, &lattice, sides);
        let ghosts = Ghosts::new(&sheet);
        assert!(sheet.ghosts > 10 && ghosts.triangles.len() > sheet.ghosts);
        assert!(gaps(&sheet, &lattice).iter().all(|g| g.abs() < 1e-12));
        let mut points = lattice.clone();
        for (k, p) in points.iter_mut().enumerate().skip(sheet.cells) {
            let s = k as f64;
            *p += Vec3::new(0.15 * s.sin(), 0.15 * (1.7 * s).cos(), 0.0);
        }
        for &t in &ghosts.triangles {
            rotations.set(
                t,
                multiply(&exp(Vec3::new(0.3, -0.2, 0.1)), &rotations.get(t)),
            );
        }
        // Neighbouring ghosts pull on each other through their virtual walls, so the sweeps
        // converge linearly.
        for _ in 0..60 {
            ghosts.settle(&mut points, &sheet.triangles, sides[0], &rotations);
        }
        assert_eq!(points[..sheet.cells], lattice[..sheet.cells]);
        let off = (points.iter().zip(&lattice))
            .map(|(p, q)| (*p - *q).norm())
            .fold(0.0, f64::max);
        assert!(
            off < 1e-8,
            "a ghost settled {off} away from its lattice point"
        );
        for (t, c) in sheet.triangles.iter().enumerate() {
            let r = rotations.get(t);
            for s in 0..3 {
                let side = points[c[(s + 1) % 3]] - points[c[s]];
                assert!((side - apply(&r, sides[s])).norm() < 1e-8, "triangle {t}");
            }
        }
    }

    /// A sweep never raises the sum of the walls' squared gaps, even where no place for a
    /// ghost makes its walls unit (the cells pulled out of the lattice and out of its plane).
    #[test]
    fn a_sweep_never_raises_the_gaps() {
        let (sheet, lattice) = flat_sheet();
        let sides = reference_sides();
        let start: Vec<Vec3> = (lattice.iter())
            .map(|&p| Vec3::new(1.3 * p.x, p.y, 0.2 * p.x * p.y))
            .collect();
        let rotations = fitted_rotations(&sheet, &start, sides);
        let ghosts = Ghosts::new(&sheet);
        let squared = |p: &[Vec3]| -> f64 { gaps(&sheet, p).iter().map(|g| g * g).sum() };
        let mut points = start.clone();
        let mut before = squared(&points);
        for _ in 0..4 {
            ghosts.settle(&mut points, &sheet.triangles, sides[0], &rotations);
            let after = squared(&points);
            assert!(after <= before, "{before} -> {after}");
            before = after;
        }
        assert!(before < 0.9 * squared(&start));
        assert_eq!(points[..sheet.cells], start[..sheet.cells]);
    }

    /// A ghost whose walls would all be unit only across the hinge of its triangle is not
    /// moved across: it would turn the triangle over.
    #[test]
    fn a_ghost_is_not_moved_across_its_hinge() {
        let points = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.5, 1.732, 0.0),
        ];
        let start = Vec3::new(0.5, -0.1, 0.0);
        let normal = |x: Vec3| (points[1] - points[0]).cross(x - points[0]);
        let facing = normal(start);
        let gaps = |x: Vec3| -> f64 {
            (points.iter())
                .map(|&q| ((x - q).norm_squared() - 1.0).powi(2))
                .sum()
        };
        let free = settled(start, &[0, 1, 2], &points, |_, _| false);
        assert!(free.y > 0.5 && gaps(free) < 0.1 * gaps(start), "{free:?}");
        let held = settled(start, &[0, 1, 2], &points, |x, _| {
            normal(x).dot(facing) <= 0.0
        });
        assert!(normal(held).dot(facing) > 0.0, "{held:?}");
        assert!(gaps(held) < gaps(start));
    }
}
