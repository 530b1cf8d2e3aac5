//! How a base mesh that the program made itself is optimized (`pipeline`, the editor's surface
//! source): its boundary cells may be dropped, and the fairness may be dropped too.

use super::{optimize_dropping_broken_cells, OptimizeOptions, Settled, WallNormals};
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::report::Report;
use crate::solve::IterationInfo;

/// Which try a solve belongs to, and its number within the try (from 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Attempt {
    pub second_try: bool,
    /// The tries again with normals per edge, after cell points gave no honeycomb.
    pub per_edge: bool,
    pub solve: usize,
}

/// What [`optimize_made_mesh`] gives: the kept try and which it is (the weights and wall
/// normals it ran with are in `settled.optimized`).
pub struct MadeMeshResult {
    pub settled: Settled,
    pub second_try: bool,
    /// Normals per edge, after cell points (chosen by `Auto`) gave no honeycomb.
    pub per_edge_fallback: bool,
}

impl MadeMeshResult {
    fn is_honeycomb(&self) -> bool {
        Report::within_tolerances(&self.settled.measures)
    }

    /// A honeycomb, else the smaller omega_max.
    fn better(self, other: MadeMeshResult) -> MadeMeshResult {
        let (a, b) = (&self.settled.measures, &other.settled.measures);
        if other.is_honeycomb() && !self.is_honeycomb()
            || !self.is_honeycomb() && b.omega_max_deg < a.omega_max_deg
        {
            other
        } else {
            self
        }
    }
}

/// Optimizes a base mesh that `init` made on `surface`, dropping boundary cells the solve
/// breaks. When that gives no honeycomb and `second_try` allows it, once more with
/// [`OptimizeOptions::second_try`] (no fairness, a minimum edge length, more iterations). When
/// the wall normals were left to `Auto` and chose cell points, and neither try is a honeycomb,
/// both again with normals per edge: the soft normalization of cell points lets a wall turn
/// over now and then (a field mesh on a saddle kept mirrored nodes that per edge did not).
/// The first honeycomb is kept, else the result with the smallest omega_max.
pub fn optimize_made_mesh(
    base: &PolyMesh,
    surface: &PolyMesh,
    options: &OptimizeOptions,
    second_try: bool,
    progress: &mut dyn FnMut(Attempt, &IterationInfo),
) -> Result<MadeMeshResult> {
    let resolved = options.resolved();
    let fallback = options.wall_normals == WallNormals::Auto
        && resolved.wall_normals == WallNormals::CellPoints;
    let first = tries(base, surface, &resolved, second_try, false, progress)?;
    if !fallback || first.is_honeycomb() {
        return Ok(first);
    }
    let per_edge = OptimizeOptions {
        wall_normals: WallNormals::PerEdge,
        ..options.clone()
    }
    .resolved();
    let again = tries(base, surface, &per_edge, second_try, true, progress)?;
    Ok(first.better(again))
}

/// The first try and, unless it is a honeycomb or `second_try` forbids, the second.
fn tries(
    base: &PolyMesh,
    surface: &PolyMesh,
    options: &OptimizeOptions,
    second_try: bool,
    per_edge: bool,
    progress: &mut dyn FnMut(Attempt, &IterationInfo),
) -> Result<MadeMeshResult> {
    let mut attempt = |second_try: bool, options: &OptimizeOptions| {
        let settled =
            optimize_dropping_broken_cells(base, surface, options, &mut |solve, info| {
                let attempt = Attempt {
                    second_try,
                    per_edge,
                    solve,
                };
                progress(attempt, info)
            })?;
        Ok::<_, crate::error::Error>(MadeMeshResult {
            settled,
            second_try,
            per_edge_fallback: per_edge,
        })
    };
    let first = attempt(false, options)?;
    if !second_try || first.is_honeycomb() {
        return Ok(first);
    }
    let second = attempt(true, &options.second_try(base))?;
    Ok(first.better(second))
}
