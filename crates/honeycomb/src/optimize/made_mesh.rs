//! How a base mesh that the program made itself is optimized (`pipeline`, the editor's surface
//! source): its boundary cells may be dropped, and the fairness may be dropped too.

use super::{optimize_dropping_broken_cells, OptimizeOptions, Settled};
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::report::Report;
use crate::solve::IterationInfo;

/// Which try a solve belongs to, and its number within the try (from 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Attempt {
    pub second_try: bool,
    pub solve: usize,
}

/// What [`optimize_made_mesh`] gives: the kept try, whether it is the second, and the options
/// it ran with.
pub struct MadeMeshResult {
    pub settled: Settled,
    pub second_try: bool,
    pub options: OptimizeOptions,
}

/// Optimizes a base mesh that `init` made on `surface`, dropping boundary cells the solve
/// breaks. When that gives no honeycomb and `second_try` allows it, once more with
/// [`OptimizeOptions::second_try`] (no fairness, a minimum edge length, more iterations); the
/// second result is kept when it is a honeycomb or closer to one (smaller omega_max).
pub fn optimize_made_mesh(
    base: &PolyMesh,
    surface: &PolyMesh,
    options: &OptimizeOptions,
    second_try: bool,
    progress: &mut dyn FnMut(Attempt, &IterationInfo),
) -> Result<MadeMeshResult> {
    let first = optimize_dropping_broken_cells(base, surface, options, &mut |solve, info| {
        progress(
            Attempt {
                second_try: false,
                solve,
            },
            info,
        )
    })?;
    if !second_try || Report::within_tolerances(&first.measures) {
        return Ok(MadeMeshResult {
            settled: first,
            second_try: false,
            options: options.clone(),
        });
    }
    let again = options.second_try(base);
    let second = optimize_dropping_broken_cells(base, surface, &again, &mut |solve, info| {
        progress(
            Attempt {
                second_try: true,
                solve,
            },
            info,
        )
    })?;
    let better = Report::within_tolerances(&second.measures)
        || second.measures.omega_max_deg < first.measures.omega_max_deg;
    Ok(if better {
        MadeMeshResult {
            settled: second,
            second_try: true,
            options: again,
        }
    } else {
        MadeMeshResult {
            settled: first,
            second_try: false,
            options: options.clone(),
        }
    })
}
