//! The 6-RoSy orientation field: per vertex a unit tangent direction o_i, taken up to turns
//! by multiples of 60 degrees about the normal n_i (the directions of a hexagon's edges).
//! It is smoothed by replacing each o_i with the mean of its neighbours' directions, each
//! neighbour's first turned (in i's tangent plane) to the one of its six representatives
//! closest to the running mean: the mean of directions that only matter modulo 60 degrees.
//!
//! Vertices near a stroke take the stroke's direction. Vertices on S's boundary take the
//! boundary's direction modulo 30 degrees: hex edges along the boundary or across it. Either
//! puts a row of cells along the boundary, and only both together let the lattice fit a
//! rectangle (edges along two sides, across the other two) without turning inside: a field
//! that must turn costs the lattice a dislocation (a pentagon-heptagon pair) every few cells.

use super::hierarchy::Level;
use super::sampling::Sampling;
use super::tangent::{turned, unit_tangent, SplitMix, SIN60};
use crate::error::{Error, Result};
use crate::geometry::Vec3;
use std::collections::HashMap;

/// Gauss-Seidel sweeps per level (more changed little in measurements; fewer on the coarse
/// levels, whose vertices together outnumber the finest level's).
const SWEEPS_FINEST: usize = 10;
const SWEEPS_COARSE: usize = 8;

/// What a vertex's direction must be.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Constraint {
    Free,
    /// Hex edges along this direction (a stroke).
    Along(Vec3),
    /// Hex edges along or across this direction (S's boundary).
    AlongOrAcross(Vec3),
}

/// The representative of the 6-RoSy direction `o` closest to `target`, both seen in the plane
/// of `n` (`target` unit and in that plane). `target` itself when `o` has no direction there.
pub fn closest_sixfold(target: Vec3, n: Vec3, o: Vec3) -> Vec3 {
    let Some(o) = unit_tangent(o, n) else {
        return target;
    };
    // The six turns are +-o, +-o turned by 60 and +-o turned by 120 degrees.
    let candidates = [o, turned(o, n, 0.5, SIN60), turned(o, n, -0.5, SIN60)];
    let mut best = (f64::NEG_INFINITY, o);
    for c in candidates {
        let d = target.dot(c);
        if d.abs() > best.0 {
            best = (d.abs(), if d < 0.0 { -c } else { c });
        }
    }
    best.1
}

/// The direction along or across `t` (modulo 60 degrees) closest to `target`, in the plane
/// of `n`.
pub fn closest_twelvefold(target: Vec3, n: Vec3, t: Vec3) -> Vec3 {
    let along = closest_sixfold(target, n, t);
    let across = closest_sixfold(target, n, n.cross(t));
    if across.dot(target) > along.dot(target) {
        across
    } else {
        along
    }
}

/// The directions the field must take: a stroke's near a stroke (within half a lattice
/// spacing), else, on S's boundary, along or across the boundary.
pub fn constraints(
    sampling: &Sampling,
    strokes: &[Vec<Vec3>],
    follow_boundary: bool,
    spacing: f64,
) -> Result<Vec<Constraint>> {
    let mut fixed: Vec<Constraint> = sampling
        .boundary_tangents
        .iter()
        .map(|t| match t {
            Some(t) if follow_boundary => Constraint::AlongOrAcross(*t),
            _ => Constraint::Free,
        })
        .collect();
    if strokes.iter().all(|s| s.len() < 2) {
        return Ok(fixed);
    }
    let radius = 0.5 * spacing;
    let grid = PointGrid::new(&sampling.points, radius);
    let mut nearest: Vec<f64> = vec![f64::INFINITY; sampling.points.len()];
    let mut followed = false;
    for line in strokes {
        for w in line.windows(2) {
            let (a, b) = (w[0], w[1]);
            let length = (b - a).norm();
            // A zero (or NaN) length has no direction.
            let usable = length > 0.0;
            if !usable {
                continue;
            }
            let direction = (b - a) / length;
            let steps = (length / (0.5 * radius)).ceil().min(1e6) as usize;
            for k in 0..=steps {
                let probe = a + (b - a) * (k as f64 / steps as f64);
                grid.for_each_near(probe, |v| {
                    let p = sampling.points[v];
                    let t = (p - a).dot(direction).clamp(0.0, length);
                    let d = (p - (a + direction * t)).norm();
                    if d <= radius && d < nearest[v] {
                        if let Some(u) = unit_tangent(direction, sampling.normals[v]) {
                            nearest[v] = d;
                            fixed[v] = Constraint::Along(u);
                            followed = true;
                        }
                    }
                });
            }
        }
    }
    if !followed {
        // Strokes that steer nothing are a mistake in the file, not a wish to be ignored.
        return Err(Error::Parameter(format!(
            "--align: no stroke runs along the surface within {} of it (each is too far \
             away, of zero length or along the surface's normal)",
            crate::error::rounded(radius, 6)
        )));
    }
    Ok(fixed)
}

/// Points bucketed in cubes of side `cell`, to find those within `cell` of a probe.
struct PointGrid {
    cell: f64,
    buckets: HashMap<(i64, i64, i64), Vec<u32>>,
}

impl PointGrid {
    fn new(points: &[Vec3], cell: f64) -> PointGrid {
        let mut grid = PointGrid {
            cell,
            buckets: HashMap::new(),
        };
        for (i, &p) in points.iter().enumerate() {
            let key = grid.key(p);
            grid.buckets.entry(key).or_default().push(i as u32);
        }
        grid
    }

    fn key(&self, p: Vec3) -> (i64, i64, i64) {
        let k = |x: f64| (x / self.cell).floor() as i64;
        (k(p.x), k(p.y), k(p.z))
    }

    fn for_each_near(&self, p: Vec3, mut f: impl FnMut(usize)) {
        let (x, y, z) = self.key(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(bucket) = self.buckets.get(&(x + dx, y + dy, z + dz)) {
                        bucket.iter().for_each(|&v| f(v as usize));
                    }
                }
            }
        }
    }
}

/// The field on every level (finest first): solved coarse to fine, then the finest result
/// carried back up, so that each level holds the final field for the position solve.
pub fn solve(levels: &[Level], finest_constraints: &[Constraint], seed: u64) -> Vec<Vec<Vec3>> {
    let mut fixed = vec![finest_constraints.to_vec()];
    for l in 1..levels.len() {
        let restricted = restrict_constraints(&levels[l - 1], &levels[l], &fixed[l - 1]);
        fixed.push(restricted);
    }
    let top = levels.len() - 1;
    // The start: a random direction per vertex of the coarsest level (seeded). One direction
    // for all, laid into each tangent plane, measured no better on the test surfaces.
    let mut rng = SplitMix::new(seed);
    let mut field: Vec<Vec3> = (0..levels[top].len())
        .map(|i| {
            let n = levels[top].normals[i];
            obey(fixed[top][i], n, rng.tangent(n))
        })
        .collect();
    let mut fields = vec![Vec::new(); levels.len()];
    for l in (0..levels.len()).rev() {
        if l < top {
            field = prolongate(&levels[l], &fields[l + 1], &fixed[l]);
        }
        let sweeps = if l == 0 { SWEEPS_FINEST } else { SWEEPS_COARSE };
        for _ in 0..sweeps {
            sweep(&levels[l], &mut field, &fixed[l]);
        }
        fields[l] = std::mem::take(&mut field);
    }
    for l in 1..levels.len() {
        fields[l] = restrict_field(&levels[l - 1], &levels[l], &fields[l - 1], &fields[l]);
    }
    fields
}

/// The direction closest to `wish` that the constraint allows.
fn obey(constraint: Constraint, n: Vec3, wish: Vec3) -> Vec3 {
    match constraint {
        Constraint::Free => wish,
        Constraint::Along(t) => unit_tangent(t, n).unwrap_or(wish),
        Constraint::AlongOrAcross(t) => match unit_tangent(wish, n) {
            Some(w) => closest_twelvefold(w, n, t),
            None => unit_tangent(t, n).unwrap_or(wish),
        },
    }
}

/// One Gauss-Seidel sweep of the 6-fold mean.
fn sweep(level: &Level, field: &mut [Vec3], fixed: &[Constraint]) {
    for i in 0..level.len() {
        if let Constraint::Along(_) = fixed[i] {
            continue;
        }
        let n = level.normals[i];
        let mut mean = field[i];
        let mut weight = 0.0;
        for &j in level.neighbours(i) {
            // The six turns of o_j in j's own plane, compared in space: near enough to the
            // turns seen in i's plane for neighbours, and cheaper.
            let (oj, nj) = (field[j as usize], level.normals[j as usize]);
            let mut best = (mean.dot(oj), oj);
            for c in [turned(oj, nj, 0.5, SIN60), turned(oj, nj, -0.5, SIN60)] {
                let d = mean.dot(c);
                if d.abs() > best.0.abs() {
                    best = (d, c);
                }
            }
            let matched = if best.0 < 0.0 { -best.1 } else { best.1 };
            mean = unit_tangent(mean * weight + matched, n).unwrap_or(mean);
            weight += 1.0;
        }
        field[i] = obey(fixed[i], n, mean);
    }
}

/// A coarse vertex is held along a stroke if a child is (their 6-fold mean direction), else
/// along or across the boundary if a child is (their 12-fold mean).
fn restrict_constraints(fine: &Level, coarse: &Level, fixed: &[Constraint]) -> Vec<Constraint> {
    let mut along: Vec<Option<Vec3>> = vec![None; coarse.len()];
    let mut boundary: Vec<Option<Vec3>> = vec![None; coarse.len()];
    for (i, constraint) in fixed.iter().enumerate() {
        let c = fine.parent[i] as usize;
        let n = coarse.normals[c];
        match *constraint {
            Constraint::Free => {}
            Constraint::Along(t) => accumulate(&mut along[c], n, t, closest_sixfold),
            Constraint::AlongOrAcross(t) => accumulate(&mut boundary[c], n, t, closest_twelvefold),
        }
    }
    (0..coarse.len())
        .map(|c| {
            let n = coarse.normals[c];
            let mean = |s: Option<Vec3>| s.and_then(|s| unit_tangent(s, n));
            match (mean(along[c]), mean(boundary[c])) {
                (Some(t), _) => Constraint::Along(t),
                (None, Some(t)) => Constraint::AlongOrAcross(t),
                _ => Constraint::Free,
            }
        })
        .collect()
}

/// Adds `v` to a running sum of directions, matched to it by `closest`.
fn accumulate(sum: &mut Option<Vec3>, n: Vec3, v: Vec3, closest: fn(Vec3, Vec3, Vec3) -> Vec3) {
    *sum = Some(match *sum {
        None => v,
        Some(s) => match unit_tangent(s, n) {
            Some(target) => s + closest(target, n, v),
            None => v,
        },
    });
}

/// Each coarse vertex's 6-fold mean of its children's directions.
fn restrict_field(fine: &Level, coarse: &Level, values: &[Vec3], old: &[Vec3]) -> Vec<Vec3> {
    let mut sums: Vec<Option<Vec3>> = vec![None; coarse.len()];
    for (i, &v) in values.iter().enumerate() {
        let c = fine.parent[i] as usize;
        accumulate(&mut sums[c], coarse.normals[c], v, closest_sixfold);
    }
    sums.into_iter()
        .enumerate()
        .map(|(c, s)| {
            s.and_then(|s| unit_tangent(s, coarse.normals[c]))
                .unwrap_or(old[c])
        })
        .collect()
}

/// Each fine vertex starts from its parent's direction, laid into its own tangent plane.
fn prolongate(fine: &Level, coarse_field: &[Vec3], fixed: &[Constraint]) -> Vec<Vec3> {
    (0..fine.len())
        .map(|i| {
            let n = fine.normals[i];
            let o = coarse_field[fine.parent[i] as usize];
            let wish = unit_tangent(o, n).unwrap_or_else(|| n.any_orthogonal());
            obey(fixed[i], n, wish)
        })
        .collect()
}

/// The smallest turn (radians, in [0, 30 degrees]) between two 6-RoSy directions in the
/// plane of `n`.
#[cfg(test)]
fn sixfold_angle(a: Vec3, b: Vec3, n: Vec3) -> f64 {
    let Some(a) = unit_tangent(a, n) else {
        return 0.0;
    };
    let c = closest_sixfold(a, n, b);
    super::tangent::tangential(c, n)
        .dot(a)
        .clamp(-1.0, 1.0)
        .acos()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::field::hierarchy;

    fn z() -> Vec3 {
        Vec3::new(0.0, 0.0, 1.0)
    }

    fn at(degrees: f64) -> Vec3 {
        let (s, c) = degrees.to_radians().sin_cos();
        Vec3::new(c, s, 0.0)
    }

    #[test]
    fn the_closest_of_six_turns_is_found() {
        // 70 degrees is 10 degrees from 60: its representative near 5 degrees is at 10.
        let c = closest_sixfold(at(5.0), z(), at(70.0));
        assert!((c - at(10.0)).norm() < 1e-12, "{c:?}");
        // 175 degrees is -5 modulo 60.
        let c = closest_sixfold(at(0.0), z(), at(175.0));
        assert!((c - at(-5.0)).norm() < 1e-12, "{c:?}");
        // A direction out of the plane is projected first.
        let c = closest_sixfold(at(0.0), z(), Vec3::new(1.0, 0.0, 5.0));
        assert!((c - at(0.0)).norm() < 1e-12, "{c:?}");
        assert!((sixfold_angle(at(3.0), at(-115.0), z()).to_degrees() - 2.0).abs() < 1e-9);
        assert!((sixfold_angle(at(0.0), at(30.0), z()).to_degrees() - 30.0).abs() < 1e-9);
    }

    #[test]
    fn a_square_field_held_on_its_border_turns_to_it() {
        // A flat grid, its border held at 12 degrees (in different 6-fold representatives):
        // everything follows.
        let n = 24;
        let levels = hierarchy::build(hierarchy::flat_grid(n));
        let count = levels[0].len();
        let fixed: Vec<Constraint> = (0..count)
            .map(|v| {
                let (i, j) = (v % (n + 1), v / (n + 1));
                match i == 0 || j == 0 || i == n || j == n {
                    true => Constraint::Along(at(12.0 + 60.0 * (v % 3) as f64)),
                    false => Constraint::Free,
                }
            })
            .collect();
        let fields = solve(&levels, &fixed, 3);
        let deviations: Vec<f64> = fields[0]
            .iter()
            .map(|&o| sixfold_angle(at(12.0), o, z()).to_degrees())
            .collect();
        let mean = deviations.iter().sum::<f64>() / deviations.len() as f64;
        let worst = deviations.iter().copied().fold(0.0, f64::max);
        println!("deviation: mean {mean} degrees, worst {worst}");
        assert!(
            mean < 3.0 && worst < 20.0,
            "mean {mean}, worst {worst} degrees"
        );
        assert_eq!(fields.len(), levels.len());
        assert!(fields.iter().zip(&levels).all(|(f, l)| f.len() == l.len()));
    }
}
