//! Evening the uneven cells of walls across S.
//!
//! Where the fitted sheet curves while S leans from its axes the cells change size
//! (docs/walls.md); letting the axes lean a little more, along the way the sheet curves, evens
//! them. A few steps of the guided projection find that trade: every edge pulled towards the
//! mean length, every wall held where it stands. They are stopped long before the nodes are
//! at 120 degrees again: the sheet of the walls they reached is fitted to unit walls, and
//! the vertices placed on it close to where the steps put them, which is exact by
//! construction and costs a fraction of converging the guided projection.

use super::{across_optimized, again_from, counted, is_clean, uncross, Solved, Step};
use crate::error::{rounded, Error, Result};
use crate::mesh::PolyMesh;
use crate::optimize::{optimize, OptimizeOptions, Optimized};
use crate::reciprocal::{
    trim_drawn_out, walls_across, AcrossOptions, PlacementOptions, Stage, Start, DRAWN_OUT,
};
use crate::structure::{Honeycomb, Measures};
use crate::surface::Surface;
use std::time::Instant;

/// Cells this uneven (edge-length cv) or more are evened: what a designer's mesh of one cell
/// size is asked to keep to.
pub(crate) const UNEVEN_CELLS_CV: f64 = 0.12;
/// Rounds of evening at most, each from the last one's result.
const ROUNDS: usize = 2;
/// Steps of the guided projection per round: enough to find the trade, not to make it exact.
/// A round that is not clean is tried again, once, with fewer: a gentler trade, whose
/// walls are less likely to cross.
const STEPS: usize = 5;
const GENTLE_STEPS: usize = 2;
/// The steps' weights: every edge towards the mean length, every wall normal held where it
/// stands. Their ratio sets the trade between even cells and axes along S's normals.
const EVENNESS: f64 = 0.3;
const HELD_WALLS: f64 = 0.1;
/// And, fading after the first steps, every node axis towards S's normal: of the ways to even
/// the cells the steps then take one that leans the axes less than holding the walls alone.
const AXES_ALONG_NORMALS: f64 = 0.2;
/// The placement's pull to where the steps put the vertices (inside and on the boundary): those
/// positions are the even cells.
const HELD_VERTICES: f64 = 1.0;
/// The sheet's guides (towards the steps' axes and walls) fade this much faster per iteration
/// than in a fit from the base mesh: the sheet starts from the steps' walls, whose fold the
/// guides then only need to hold for the first steps.
const GUIDES_FADE: f64 = 0.5;
/// Boundary cells the placement breaks may be dropped in this many rounds, at most this share
/// of the cells in a round of evening.
const DROP_ROUNDS: usize = 2;
const DROPPED_SHARE: f64 = 0.01;

/// `solved` (a clean honeycomb of walls across S) with its cells evened where their edge cv
/// is [`UNEVEN_CELLS_CV`] or more, in at most [`ROUNDS`] rounds; each round is kept when it is
/// clean and more even (else tried again once with [`GENTLE_STEPS`]). A note says what was
/// traded, or that nothing was.
pub fn evened(
    mut solved: Solved,
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &OptimizeOptions,
    progress: &mut dyn FnMut(Step),
) -> Result<Solved> {
    let before = solved.measures.clone();
    if before.edge_length_cv < UNEVEN_CELLS_CV {
        return Ok(solved);
    }
    let start = Instant::now();
    let mut spent = 0;
    let mut best: Option<Round> = None;
    let (mut rounds, mut steps) = (0, STEPS);
    while rounds < ROUNDS {
        let (h, base, cv) = match &best {
            Some(r) => (&r.result.0.honeycomb, &r.base, r.result.1.edge_length_cv),
            None => (
                &solved.optimized.honeycomb,
                &solved.base,
                before.edge_length_cv,
            ),
        };
        let from = (h, base, steps);
        let next = round(from, surface, model_surface, options, &mut spent, progress)?;
        let better = |r: &Round| {
            let m = &r.result.1;
            is_clean(m, options.min_edge) && m.edge_length_cv < cv
        };
        let Some(mut next) = next.filter(better) else {
            if steps == GENTLE_STEPS {
                break;
            }
            steps = GENTLE_STEPS;
            continue;
        };
        rounds += 1;
        let m = &next.result.1;
        let even = m.edge_length_cv < UNEVEN_CELLS_CV;
        if let Some(last) = &best {
            next.dropped += last.dropped;
            next.trimmed += last.trimmed;
            next.drawn_out += last.drawn_out;
        }
        best = Some(next);
        if even {
            break;
        }
    }
    solved.report.iterations_total += spent;
    let Some(again) = best else {
        solved.notes.push(format!(
            "the cells are uneven (edge cv {}); evening them in {spent} iterations gave no \
             clean honeycomb more even, so these are the cells as fitted",
            rounded(before.edge_length_cv, 3)
        ));
        return Ok(solved);
    };
    let lean = |m: &Measures| rounded(m.axis_normal_deg.mean, 3);
    let mut note = format!(
        "the cells were evened in {spent} iterations: edge cv {} -> {}, the axes {} -> {} \
         degrees from S's normals on average",
        rounded(before.edge_length_cv, 3),
        rounded(again.result.1.edge_length_cv, 3),
        lean(&before),
        lean(&again.result.1)
    );
    if again.dropped > 0 {
        let drawn_out = match again.drawn_out {
            0 => String::new(),
            n => format!(
                ", {n} of them drawn out to an edge of {DRAWN_OUT} mean edge lengths or more"
            ),
        };
        note += &format!(
            "; {} dropped or trimmed{drawn_out} (initial.obj is the mesh without them)",
            counted(again.dropped, "boundary cell").replacen(' ', " more ", 1)
        );
    }
    let seconds = solved.report.seconds + start.elapsed().as_secs_f64();
    solved.replace_by(again.result, note, seconds);
    solved.base = again.base;
    let report = &mut solved.report;
    let add = |count: &mut Option<usize>, more| *count = Some(count.unwrap_or(0) + more);
    add(&mut report.dropped_boundary_cells, again.dropped);
    add(&mut report.trimmed_boundary_cells, again.trimmed);
    Ok(solved)
}

/// What a round of evening made: the honeycomb, measured (and its note if its walls were made
/// thinner), the base mesh it stands on, and the boundary cells it dropped (the trimmed
/// ones among them) and trimmed.
struct Round {
    result: (Optimized, Measures, Option<String>),
    base: PolyMesh,
    dropped: usize,
    trimmed: usize,
    /// The trimmed cells that were drawn out ([`trim_drawn_out`]).
    drawn_out: usize,
}

/// One round from `h` on `base` (the base mesh without the cells dropped so far): `steps` of
/// the guided projection, then the sheet of where they got to fitted and the vertices placed
/// again. `None` where a solve breaks down or the steps leave no valid base mesh (the cells
/// then stay as they were).
fn round(
    (h, base, steps): (&Honeycomb, &PolyMesh, usize),
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &OptimizeOptions,
    spent: &mut usize,
    progress: &mut dyn FnMut(Step),
) -> Result<Option<Round>> {
    let mut stepping = again_from(h, options, steps);
    stepping.weights.evenness = EVENNESS;
    stepping.weights.held_walls = HELD_WALLS;
    stepping.weights.guide = AXES_ALONG_NORMALS;
    let stepped = optimize(&h.base, Some(surface), &stepping, &mut |info| {
        *spent += 1;
        progress(Step::Iteration("evening the cells", 1, info))
    });
    let stepped = match stepped {
        Ok(stepped) => stepped,
        Err(Error::Cancelled) => return Err(Error::Cancelled),
        Err(_) => return Ok(None),
    };
    let mut across_options = AcrossOptions {
        thickness: options.thickness,
        placement: PlacementOptions {
            anchor: HELD_VERTICES,
            boundary_anchor: HELD_VERTICES,
            ..PlacementOptions::default()
        },
        max_drops: DROP_ROUNDS,
        max_dropped_share: DROPPED_SHARE,
        ..AcrossOptions::default()
    };
    across_options.field.fade *= GUIDES_FADE;
    across_options.field.cancel = options.solver.cancel.clone();
    across_options.placement.cancel = options.solver.cancel.clone();
    let stepped_h = &stepped.honeycomb;
    let start = Start {
        vertices: &stepped_h.base.vertices,
        wall_normals: &stepped.normals,
        axes: &stepped_h.axes,
    };
    let across = walls_across(
        base,
        Some(start),
        surface,
        model_surface,
        &across_options,
        &mut |stage, info| {
            *spent += 1;
            let name = match stage {
                Stage::AxisField => "evening the cells: fitting the node axes",
                Stage::Placement => "evening the cells: placing the vertices",
            };
            progress(Step::Iteration(name, 1, info))
        },
    );
    let across = match across {
        Ok(across) => across,
        Err(Error::Cancelled) => return Err(Error::Cancelled),
        Err(_) => return Ok(None),
    };
    let trimmed_before = across.trimmed_cells;
    let across = trim_drawn_out(across, UNEVEN_CELLS_CV, DROPPED_SHARE, model_surface);
    let drawn_out = across.trimmed_cells - trimmed_before;
    let mut measures = across.measures;
    let mut optimized = across_optimized(
        across.honeycomb,
        across.connectivity,
        across.solve,
        &across.base,
        options,
    );
    let (h, conn) = (&mut optimized.honeycomb, &optimized.connectivity);
    let thinner = uncross(h, conn, &mut measures, model_surface, options.thickness);
    Ok(Some(Round {
        result: (optimized, measures, thinner),
        base: across.base,
        dropped: across.dropped_cells,
        trimmed: across.trimmed_cells,
        drawn_out,
    }))
}
