//! The two ways to a honeycomb: from a base mesh, and from a design surface alone.

use super::options::Shading;
use super::{BaseMesh, Options, Outcome, Progress, Step, Variant, Verdict};
use crate::analysis::{shading_against_normals, SHADING_DEPTH};
use crate::error::{rounded, Error, Result};
use crate::init::{Align, CellSize, InitOptions, LatticeFollows, Method};
use crate::mesh::check_base_near_surface;
use crate::optimize::{
    capped, optimize as solve, paired, shading_axes, OptimizeOptions, Optimized, ParallelOptions,
    QuadOptions,
};
use crate::pipeline::{pipeline as run_strategy, solve_base, uncross, Pipelined, Strategy, Walls};
use crate::reciprocal::{AcrossOptions, AxisTargets, Turn, SHADING_TURNS};
use crate::report::Report;
use crate::structure::{
    axes_measures, face_measures, largest_move_along, measure, QuadPattern, FLAT_QUAD,
    FLAT_QUAD_MEAN,
};
use crate::surface::Surface;
use crate::Vec3;
use std::time::Instant;

/// What the pipeline makes its base mesh with, and how it optimizes it.
#[derive(Clone, Debug)]
pub struct PipelineOptions {
    /// The base mesh: its cell size, and the method and flattening the pipeline tries first
    /// when `init_chosen`.
    pub init: InitOptions,
    /// `init.method` and `init.flattener` are the caller's choice; else the pipeline picks
    /// them for the walls asked (and may turn the grid or change method to get a honeycomb).
    pub init_chosen: bool,
    /// `init.align` is the caller's choice; else zigzag quads turn the lattice to follow S's
    /// principal directions where they agree (the straight polylines then carry the flattest
    /// quads), and the boundary everywhere else.
    pub align_chosen: bool,
    /// Walls across S whose cells come out uneven (edge cv 0.12 or more) are evened afterwards,
    /// the axes leaning a little more (see `pipeline::evening`). `None`: evened where walls
    /// stand across S's normals (not for other walls or a shading device); `Some(true)`: asked,
    /// and refused with other walls; `Some(false)`: the cells as fitted.
    pub even_cells: Option<bool>,
    pub options: Options,
}

impl PipelineOptions {
    /// The defaults for about `cells` cells.
    pub fn new(cells: usize) -> PipelineOptions {
        PipelineOptions {
            init: InitOptions::new(CellSize::Cells(cells)),
            init_chosen: false,
            align_chosen: false,
            even_cells: None,
            options: Options::default(),
        }
    }

    /// The pipeline's strategy for these options, checked.
    fn strategy(&self, progress: &Progress) -> Result<Strategy> {
        self.init.validate()?;
        if let Variant::Axes { .. } = &self.options.variant {
            return Err(Error::option(
                "axes",
                "given",
                "prescribes axes per vertex of a base mesh, and the pipeline makes its own \
                 (make it with init, then optimize)",
            ));
        }
        let shading = self.options.shading()?;
        if shading.is_some() && self.options.walls != Walls::Across {
            return Err(Error::option(
                "walls",
                self.options.walls.label(),
                "shading stands its walls across S, turned across the light",
            ));
        }
        let across_normals = self.options.walls == Walls::Across && shading.is_none();
        if self.even_cells == Some(true) && !across_normals {
            return Err(Error::option(
                "even_cells",
                "given",
                "evens the cells of walls across S's normals; with other walls, or a shading \
                 device's, the cells are as the walls make them",
            ));
        }
        let mut optimize = self.options.optimize_options()?;
        // Shading's depth is given to the finished honeycomb (see `shade`).
        if shading.is_some() {
            optimize.thickness = None;
        }
        optimize.solver.cancel = progress.cancel_handle();
        // Quads cap the pipeline's honeycomb afterwards (see `cap_with_quads`), and parallel
        // meshes are paired on its walls (see `pair_on_walls`).
        optimize.quads = None;
        if self.options.paired_parallel()?.is_some() {
            optimize.parallel = None;
        }
        let mut init = self.init.clone();
        // Zigzag quads are flat where their diagonals follow a principal direction, and a
        // flattest cover then picks those diagonals too.
        let along_curvature = matches!(
            self.options.variant,
            Variant::Quads {
                pattern: QuadPattern::Zigzag | QuadPattern::Flattest,
                ..
            }
        );
        if along_curvature && !self.align_chosen && init.method == Method::Flatten {
            init.align = Align::Curvature;
        }
        Ok(Strategy {
            init,
            init_chosen: self.init_chosen,
            walls: self.options.walls,
            optimize,
            // The second try only when the fairness is not the caller's choice.
            second_try: self.options.w_fair.is_none(),
            // Shading sets the axes' targets per try (see `shading_pipeline`).
            across: AcrossOptions::default(),
            guided_fallback: true,
            even_cells: self.even_cells.unwrap_or(true) && across_normals,
        })
    }
}

/// Optimizes `base` into a honeycomb on the design surface `surface` (or on itself:
/// [`Surface::of_base`]), with the walls and the variant `options` ask for.
///
/// ```
/// use honeycomb::generate::{lifted_hex_patch, Shape};
/// use honeycomb::{optimize, BaseMesh, Options, Progress, Surface};
/// // About 150 vertices lifted onto a dome, and the dome.
/// let (base, surface) = lifted_hex_patch(Shape::Dome, 150);
/// let (base, surface) = (BaseMesh::from_mesh(base)?, Surface::new(surface)?);
/// let outcome = optimize(&base, &surface, &Options::default(), &mut Progress::silent())?;
/// assert!(outcome.is_honeycomb());
/// assert!(outcome.measures.omega_max_deg < 0.01);
/// # Ok::<(), honeycomb::Error>(())
/// ```
pub fn optimize(
    base: &BaseMesh,
    surface: &Surface,
    options: &Options,
    progress: &mut Progress,
) -> Result<Outcome> {
    let start = Instant::now();
    if !surface.is_base() {
        check_base_near_surface(base.mesh(), surface.source_mesh())?;
    }
    let mut solver_options = options.optimize_options_for(base.mesh(), surface)?;
    solver_options.solver.cancel = progress.cancel_handle();
    // Quads cap the honeycomb the walls asked give (see `cap_with_quads`).
    let quads = solver_options.quads.take();
    let shading = options.shading()?;
    if let Some(shading) = &shading {
        // Walls across S turned across the light, the guided projection with the axes
        // prescribed across it where those are no clean honeycomb; its depth is given
        // afterwards (see `shade`).
        solver_options.thickness = None;
        let tries = SHADING_TURNS.map(ShadingTry::Turned);
        let tries = [&tries[..], &[ShadingTry::Prescribed]].concat();
        // A turned try whose walls were not clean already ended in the guided projection.
        let mut guided_ran = false;
        return shading_tries(&tries, progress, |shading_try, progress| {
            if shading_try == ShadingTry::Prescribed && guided_ran {
                return Ok(Tried::Skipped);
            }
            let (walls, targets) = match shading_try {
                ShadingTry::Turned(turn) => (options.walls, shading.targets(turn, surface)),
                // `solver_options` prescribe the axes across the light.
                ShadingTry::Prescribed => (Walls::Free, shading.targets(SHADING_TURNS[0], surface)),
                ShadingTry::Unturned => unreachable!("a designer's mesh prescribes the axes"),
            };
            let solved = solve_base(
                base.mesh(),
                surface,
                walls,
                targets,
                &solver_options,
                &mut |step| progress.step(step),
            )?;
            guided_ran |= solved.report.walls == Walls::Free;
            let (optimized, report) = match &quads {
                Some(q) => cap_with_quads(
                    solved.optimized,
                    solved.report,
                    surface,
                    q,
                    &solver_options,
                    progress,
                )?,
                None => (solved.optimized, solved.report),
            };
            let (optimized, report) = shade(optimized, report, surface, shading, targets);
            Ok(Tried::Made(Box::new(outcome(
                optimized,
                report,
                solved.base,
                None,
            ))))
        });
    }
    let (optimized, report) = if solver_options.is_variant() {
        let optimized = solve(
            base.mesh(),
            surface.design_mesh(),
            &solver_options,
            &mut |info| progress.step(Step::Iteration(VARIANT_SOLVE, 1, info)),
        )?;
        let measures = measure(&optimized.honeycomb, surface);
        let report = Report::new(&optimized, &measures, 0.0);
        (optimized, report)
    } else {
        let solved = solve_base(
            base.mesh(),
            surface,
            options.walls,
            AxisTargets::Normals,
            &solver_options,
            &mut |step| progress.step(step),
        )?;
        (solved.optimized, solved.report)
    };
    let (optimized, mut report) = match &quads {
        Some(q) => cap_with_quads(optimized, report, surface, q, &solver_options, progress)?,
        None => (optimized, report),
    };
    report.seconds = start.elapsed().as_secs_f64();
    Ok(outcome(optimized, report, base.mesh().clone(), None))
}

/// What a variant's solve is called in [`Step::Iteration`].
const VARIANT_SOLVE: &str = "guided projection";
/// What the capping solve is called in [`Step::Iteration`].
const CAPPING_SOLVE: &str = "planar quads";

/// The honeycomb `optimized` (reported in `report`) capped by planar quads on `surface` (see
/// [`cap_with_cover`]). A flattest cover whose worst quad stays above [`FLAT_QUAD`] is set
/// against the zigzag cover of the same honeycomb, and the flatter kept: each cell's own
/// flattest diagonal is chosen before the capping, which sees the whole cover; where S folds
/// along straight creases (a folded plate), the zigzag's straight polylines follow them and cap
/// flatter.
fn cap_with_quads(
    optimized: Optimized,
    report: Report,
    surface: &Surface,
    quads: &QuadOptions,
    options: &OptimizeOptions,
    progress: &mut Progress,
) -> Result<(Optimized, Report)> {
    let spare =
        (quads.pattern == QuadPattern::Flattest).then(|| (optimized.clone(), report.clone()));
    let flattest = cap_with_cover(optimized, report, surface, quads, options, progress)?;
    let Some((optimized, report)) = spare.filter(|_| worst_quad(&flattest.1) > FLAT_QUAD) else {
        return Ok(flattest);
    };
    // The zigzag whole: cells off it would take their own diagonals, as the flattest cover's.
    let zigzag = QuadOptions {
        pattern: QuadPattern::Zigzag,
        whole_pattern: true,
        ..quads.clone()
    };
    let mut pattern = cap_with_cover(optimized, report, surface, &zigzag, options, progress)?;
    let (a, b) = (worst_quad(&flattest.1), worst_quad(&pattern.1));
    let spent = flattest.1.iterations_total + capping_iterations(&pattern.1);
    let mut kept = if pattern.1.honeycomb && b < a {
        pattern.1.notes.retain(|n| !n.contains("--quads flattest"));
        pattern.1.notes.push(format!(
            "flattest quads: the zigzag cover, whose worst quad is flatter than with each cell's \
             own diagonal ({} against {})",
            rounded(b, 4),
            rounded(a, 4)
        ));
        pattern
    } else {
        let mut flattest = flattest;
        flattest.1.notes.push(format!(
            "flattest quads: each cell's own diagonal (its worst quad {}, with the zigzag cover {})",
            rounded(a, 4),
            rounded(b, 4)
        ));
        flattest
    };
    kept.1.iterations_total = spent;
    Ok(kept)
}

/// The honeycomb `optimized` (reported in `report`) capped by planar quads on `surface`: its
/// walls kept, its vertices moved (see `optimize::capped`), its report turned into the capped
/// one's with the trade stated.
fn cap_with_cover(
    optimized: Optimized,
    mut report: Report,
    surface: &Surface,
    quads: &QuadOptions,
    options: &OptimizeOptions,
    progress: &mut Progress,
) -> Result<(Optimized, Report)> {
    let uncapped = optimized.honeycomb.base.vertices.clone();
    let mut capped = capped(
        optimized,
        surface.source_mesh(),
        quads,
        &options.solver,
        &mut |info| progress.step(Step::Iteration(CAPPING_SOLVE, 1, info)),
    )?;
    let mut measures = measure(&capped.honeycomb, surface);
    // Edges the capping shortened where axes lean together may cross their walls.
    let thinner = uncross(
        &mut capped.honeycomb,
        &capped.connectivity,
        &mut measures,
        surface,
        options.thickness,
    );
    let cover = (capped.quad_cover.as_ref()).expect("a capped honeycomb has its cover");
    let unit = capped.honeycomb.base.mean_edge_length();
    let after = &capped.honeycomb.base.vertices;
    let along_s = largest_move_along(surface, &uncapped, after, unit);
    let cv_before = report.measures.edge_length_cv;
    let before = face_measures(&uncapped, &cover.quads);
    let moves = (along_s, cv_before, quads.reshape);
    report.capped(&capped, &measures, &before, moves);
    report.notes.extend(thinner);
    // The capping works in a frame of its own: the way back leaves roundoff.
    let unmoved = (after.iter().zip(&uncapped)).all(|(p, q)| (*p - *q).norm() <= 1e-9 * unit);
    if unmoved {
        report.notes.push(
            "no capping step within its iterations kept every vertex within 0.1 mean edge \
             lengths of S and the cells as even without crossing a wall or turning an edge \
             back; the quads cap the honeycomb as it was"
                .into(),
        );
    } else if let Some(q) = &report.quads {
        let capping = q.capping.as_ref().expect("a capped report has its capping");
        let m = &report.measures;
        let trade = capping.trade(&q.faces, m.closeness_max, m.edge_length_cv);
        report.notes.push(trade);
    }
    report.notes.extend(cells_off_pattern(&report));
    report.notes.extend(flatter_pattern(&report));
    report.notes.extend(reshaped_cells(&report));
    Ok((capped, report))
}

/// Where cells were taken off the pattern, how many, and what the pattern whole gave.
fn cells_off_pattern(report: &Report) -> Option<String> {
    let q = report.quads.as_ref()?;
    let capping = q.capping.as_ref()?;
    let whole = capping.whole_pattern.as_ref()?;
    Some(format!(
        "{} quads: {} of {} hexagons split along their own flattest diagonal, where the \
         pattern's quads stayed least planar (the pattern whole: the worst quad {} and the \
         mean {} from planar); --quads-whole-pattern keeps every cell on it",
        q.quad_pattern.label(),
        capping.cells_off_pattern,
        q.faces.quads / 2,
        rounded(whole.delta_face_max, 4),
        rounded(whole.delta_face_avg, 4),
    ))
}

/// Where a cover whose cells kept their shape stays less flat than a glazed one asks, a note
/// pointing to the cells re-shaped.
fn reshaped_cells(report: &Report) -> Option<String> {
    let q = report.quads.as_ref()?;
    let held = q.capping.as_ref().is_some_and(|c| c.reshape.is_none());
    let f = &q.faces;
    let short = !f.meet_floors();
    (held && short).then(|| {
        format!(
            "each vertex kept its place along S, and so each cell its shape: --quads-reshape \
             CV lets the vertices slide along S within their walls for flatter quads, the cells \
             re-shaped up to that edge-length cv (now {})",
            rounded(report.measures.edge_length_cv, 3)
        )
    })
}

/// Where a patterned cover stays less flat than a glazed one asks, a note pointing to the cover
/// whose cells pick their own diagonals.
fn flatter_pattern(report: &Report) -> Option<String> {
    let q = report.quads.as_ref()?;
    let f = &q.faces;
    let short = !f.meet_floors();
    (short && q.quad_pattern != QuadPattern::Flattest).then(|| {
        format!(
            "the {} cover's quads are {} (worst) and {} (mean) from planar, above the \
             {FLAT_QUAD} and {FLAT_QUAD_MEAN} a glazed cover asks: --quads flattest, whose cells \
             each take their flattest diagonal, is flatter where S's principal directions turn",
            q.quad_pattern.label(),
            rounded(f.delta_face_max, 4),
            rounded(f.delta_face_avg, 4)
        )
    })
}

/// The honeycomb `optimized` (reported in `report`) as a shading device: its walls as deep as
/// `shading` asks (less where a wall would cross itself), and the light they let through
/// against the same cells along S's normals in its report.
fn shade(
    mut optimized: Optimized,
    mut report: Report,
    surface: &Surface,
    shading: &Shading,
    targets: AxisTargets,
) -> (Optimized, Report) {
    let h = &optimized.honeycomb;
    let depth = shading
        .depth
        .unwrap_or(SHADING_DEPTH * h.base.mean_edge_length());
    let deep = h.deepened(&optimized.connectivity, depth, h.thickness.min(depth));
    let conn = &optimized.connectivity;
    let light = shading_against_normals(
        &deep,
        conn,
        surface,
        depth,
        shading.light,
        &shading.sun_path,
    );
    // What the kept axes were asked to follow: the sheet's targets, or, from the guided
    // projection, the axes it was given (S's normals turned wholly across the light).
    let fitted = || {
        (deep.base.vertices.iter())
            .map(|&v| targets.at(surface.normal_at(v)))
            .collect()
    };
    let axes: Vec<Vec3> = match report.walls {
        Walls::Free => {
            shading_axes(surface, &deep.base.vertices, shading.light).unwrap_or_else(|_| fitted())
        }
        _ => fitted(),
    };
    report.deepened(&deep, &measure(&deep, surface), light);
    report.axes = Some(axes_measures(&deep, &axes));
    optimized.honeycomb = deep;
    (optimized, report)
}

/// What the pairing solve is called in [`Step::Iteration`].
const PAIRING_SOLVE: &str = "parallel meshes";

/// The honeycomb `optimized` (reported in `report`) as parallel meshes M, M' on its walls
/// (see `optimize::paired`), its report turned into theirs.
fn pair_on_walls(
    optimized: Optimized,
    mut report: Report,
    surface: &Surface,
    parallel: &ParallelOptions,
    options: &OptimizeOptions,
    progress: &mut Progress,
) -> Result<(Optimized, Report)> {
    let paired = paired(optimized, parallel, &options.solver, &mut |info| {
        progress.step(Step::Iteration(PAIRING_SOLVE, 1, info))
    })?;
    let measures = measure(&paired.honeycomb, surface);
    report.paired(&paired, &measures);
    Ok((paired, report))
}

/// Makes a honeycomb on the design surface `surface` from nothing else: a hexagonal base
/// mesh of about `init`'s cells, walls as asked, and the retries that it takes.
///
/// ```
/// use honeycomb::generate::{design_surface, Shape};
/// use honeycomb::{pipeline, PipelineOptions, Progress, Surface};
/// let surface = Surface::new(design_surface(Shape::Saddle))?;
/// let outcome = pipeline(&surface, &PipelineOptions::new(120), &mut Progress::silent())?;
/// assert!(outcome.is_honeycomb());
/// // Walls across S: the node axes lean from S's normals less than parallel ones would.
/// let m = &outcome.measures;
/// assert!(m.axis_normal_deg.mean < m.parallel_baseline_deg.mean);
/// # Ok::<(), honeycomb::Error>(())
/// ```
pub fn pipeline(
    surface: &Surface,
    options: &PipelineOptions,
    progress: &mut Progress,
) -> Result<Outcome> {
    let strategy = options.strategy(progress)?;
    // Before any work: a cell count that no solve takes is refused at once.
    crate::limits::check_solve_cells(&options.init, surface.source_mesh())?;
    if let Some(s) = &options.options.shading()? {
        return shading_pipeline(surface, strategy, s, progress);
    }
    let start = Instant::now();
    let mut made = run_strategy(surface, &strategy, &mut |step| progress.step(step))?;
    if let Some(q) = &options.options.quads()? {
        made = capped_made(made, surface, q, &strategy.optimize, progress)?;
        let follows = made
            .initialized
            .report
            .flat
            .as_ref()
            .map(|f| f.lattice_follows);
        if follows == Some(LatticeFollows::Curvature)
            && !options.align_chosen
            && worst_quad(&made.report) > FLAT_QUAD
        {
            made = flatter_grid(made, surface, &strategy, q, progress)?;
        }
    }
    let (mut optimized, mut report) = (made.optimized, made.report);
    if let Some(p) = &options.options.paired_parallel()? {
        (optimized, report) =
            pair_on_walls(optimized, report, surface, p, &strategy.optimize, progress)?;
    }
    report.seconds = start.elapsed().as_secs_f64();
    let mut out = outcome(optimized, report, made.base, None);
    out.initialized = Some(made.initialized.report);
    Ok(out)
}

/// `made` capped by planar quads (see [`cap_with_quads`]).
fn capped_made(
    made: Pipelined,
    surface: &Surface,
    quads: &QuadOptions,
    options: &OptimizeOptions,
    progress: &mut Progress,
) -> Result<Pipelined> {
    let (optimized, report) = cap_with_quads(
        made.optimized,
        made.report,
        surface,
        quads,
        options,
        progress,
    )?;
    Ok(Pipelined {
        optimized,
        report,
        ..made
    })
}

/// The iterations of a capped honeycomb's capping solve.
fn capping_iterations(report: &Report) -> usize {
    (report.quads.as_ref())
        .and_then(|q| q.capping.as_ref())
        .map_or(0, |c| c.iterations)
}

/// The largest planarity defect of a capped honeycomb's quads.
fn worst_quad(report: &Report) -> f64 {
    (report.quads.as_ref()).map_or(f64::MAX, |c| c.faces.delta_face_max)
}

/// A zigzag or flattest cover on the grid along S's principal directions (`along`, capped)
/// made on the boundary's grid too; the one whose worst quad is flatter is kept, a note saying
/// which. The grid along the principal directions makes the twist least on average, not at
/// every cell.
fn flatter_grid(
    along: Pipelined,
    surface: &Surface,
    strategy: &Strategy,
    quads: &QuadOptions,
    progress: &mut Progress,
) -> Result<Pipelined> {
    let mut other = strategy.clone();
    other.init.align = Align::Boundary;
    let across = run_strategy(surface, &other, &mut |step| progress.step(step))?;
    let across = capped_made(across, surface, quads, &strategy.optimize, progress)?;
    let (a, b) = (worst_quad(&along.report), worst_quad(&across.report));
    let spent = along.report.iterations_total + across.report.iterations_total;
    let (mut kept, note) = if across.report.honeycomb && b < a {
        let note = format!(
            "the grid along the boundary, whose worst quad is flatter than on the grid along \
             S's principal directions ({} against {})",
            rounded(b, 4),
            rounded(a, 4)
        );
        (across, note)
    } else {
        let note = format!(
            "the grid along S's principal directions (its worst quad {}, on the boundary's \
             grid {})",
            rounded(a, 4),
            rounded(b, 4)
        );
        (along, note)
    };
    kept.report.iterations_total = spent;
    kept.report
        .notes
        .push(format!("{} quads: this is {note}", quads.pattern.label()));
    Ok(kept)
}

/// The pipeline's shading device (see [`shading_tries`]), each try from a base mesh of its own.
/// A turn whose walls across S are not clean keeps them as they came if they are a honeycomb
/// (else it fails, saying why). The guided projection from walls orthogonal to S does not
/// turn them across the light, so it blocks about as much as the cells along S's normals: it
/// runs last, and only where no turn gave a honeycomb, so that there is one to show.
fn shading_pipeline(
    surface: &Surface,
    strategy: Strategy,
    shading: &Shading,
    progress: &mut Progress,
) -> Result<Outcome> {
    let tries = SHADING_TURNS.map(ShadingTry::Turned);
    let tries = [&tries[..], &[ShadingTry::Unturned]].concat();
    shading_tries(&tries, progress, |shading_try, progress| {
        let (walls, targets) = match shading_try {
            ShadingTry::Turned(turn) => (strategy.walls, shading.targets(turn, surface)),
            ShadingTry::Unturned => (Walls::Free, shading.targets(SHADING_TURNS[0], surface)),
            ShadingTry::Prescribed => unreachable!("the pipeline prescribes no axes"),
        };
        let tried = Strategy {
            walls,
            guided_fallback: false,
            across: AcrossOptions {
                targets,
                ..strategy.across.clone()
            },
            ..strategy.clone()
        };
        let mut iterations = 0;
        let made = run_strategy(surface, &tried, &mut |step| {
            iterations += matches!(step, Step::Iteration(..)) as usize;
            progress.step(step)
        });
        let made = match made {
            Ok(made) => made,
            Err(Error::Solver(why)) => return Ok(Tried::Failed(why, iterations)),
            Err(e) => return Err(e),
        };
        let (optimized, report) = shade(made.optimized, made.report, surface, shading, targets);
        Ok(Tried::Made(Box::new(outcome(
            optimized,
            report,
            made.base,
            Some(made.initialized.report),
        ))))
    })
}

/// One way to a shading device.
#[derive(Clone, Copy, Debug, PartialEq)]
enum ShadingTry {
    /// Walls across S, their axes turned across the light as this says.
    Turned(Turn),
    /// The guided projection with the axes prescribed across the light.
    Prescribed,
    /// The guided projection from walls orthogonal to S, not turned across the light: the
    /// last resort, made only where no other try made a honeycomb.
    Unturned,
}

impl std::fmt::Display for ShadingTry {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            ShadingTry::Turned(turn) => write!(
                f,
                "the axes turned across the light at most {} degrees{}",
                degrees(turn.max_tilt),
                if turn.steady { ", leaning one way" } else { "" }
            ),
            ShadingTry::Prescribed => {
                write!(
                    f,
                    "the guided projection with the axes prescribed across the light"
                )
            }
            ShadingTry::Unturned => write!(
                f,
                "the guided projection from walls orthogonal to S, not turned across the light"
            ),
        }
    }
}

/// What a try at a shading device gave.
enum Tried {
    Made(Box<Outcome>),
    /// Nothing: the try would repeat an earlier one.
    Skipped,
    /// No honeycomb, for this reason, after these iterations.
    Failed(String, usize),
}

/// A shading device: each of `tries` in turn (`shaded` makes one), until one is a honeycomb
/// that blocks enough; else the one that blocks most. Notes say what the other tries fell
/// short of.
fn shading_tries(
    tries: &[ShadingTry],
    progress: &mut Progress,
    mut shaded: impl FnMut(ShadingTry, &mut Progress) -> Result<Tried>,
) -> Result<Outcome> {
    let start = Instant::now();
    // Not a honeycomb last, then by the share let through against the reference's.
    let rank = |o: &Outcome| {
        let s = o.report.shading.as_ref().expect("shaded");
        (
            !o.verdict.honeycomb,
            s.light.after / s.light.before.max(f64::MIN_POSITIVE),
        )
    };
    let mut best: Option<(Outcome, ShadingTry)> = None;
    // What each try fell short of.
    let (mut short, mut spent) = (Vec::new(), 0);
    for &this in tries {
        // The last resort only where no other try made a honeycomb.
        if this == ShadingTry::Unturned && best.is_some() {
            continue;
        }
        let out = match shaded(this, progress)? {
            Tried::Made(out) => *out,
            Tried::Skipped => continue,
            Tried::Failed(why, iterations) => {
                spent += iterations;
                short.push((this, why));
                continue;
            }
        };
        spent += out.report.iterations_total;
        let met = out.verdict.honeycomb && out.verdict.unmet.is_none();
        if let Some(unmet) = &out.verdict.unmet {
            short.push((this, unmet.clone()));
        } else if let Some(why) = &out.verdict.why {
            short.push((this, why.clone()));
        }
        if best
            .as_ref()
            .is_none_or(|(b, _)| met || rank(&out) < rank(b))
        {
            best = Some((out, this));
        }
        if met {
            break;
        }
    }
    let Some((mut out, kept)) = best else {
        let whys: Vec<String> = short.iter().map(|(t, why)| format!("{t}: {why}")).collect();
        return Err(Error::Solver(format!(
            "no try gave a shading device ({})",
            whys.join("; ")
        )));
    };
    for (other, unmet) in short.iter().filter(|(other, _)| *other != kept) {
        out.report.notes.push(format!("{other}: {unmet}"));
    }
    if !short.is_empty() {
        out.report.notes.push(format!("this is {kept}"));
    }
    out.report.iterations_total = spent;
    out.report.seconds = start.elapsed().as_secs_f64();
    Ok(out)
}

/// Radians in degrees, to a tenth.
fn degrees(angle: f64) -> f64 {
    (angle.to_degrees() * 10.0).round() / 10.0
}

/// An outcome judged from its report (whose measures are of the realized meshes).
fn outcome(
    optimized: Optimized,
    report: Report,
    base: crate::mesh::PolyMesh,
    initialized: Option<crate::init::InitReport>,
) -> Outcome {
    let verdict = Verdict::of(&optimized.honeycomb, &report);
    Outcome {
        measures: report.measures.clone(),
        honeycomb: optimized.honeycomb,
        quads: optimized.quads,
        verdict,
        report,
        base,
        initialized,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tries that give no honeycomb end in one error that names each and why.
    #[test]
    fn shading_tries_that_all_fail_are_named() {
        let tries = SHADING_TURNS.map(ShadingTry::Turned);
        let err = shading_tries(&tries, &mut Progress::silent(), |t, _| {
            Ok(match t {
                ShadingTry::Turned(turn) if turn.max_tilt < 0.6 => Tried::Skipped,
                _ => Tried::Failed("a node mirrored".into(), 10),
            })
        })
        .err()
        .expect("no try made anything")
        .to_string();
        assert!(err.contains("at most 45 degrees: a node mirrored"), "{err}");
        for tilt in ["45", "60", "75", "37.5", "52.5"] {
            let named = format!("at most {tilt} degrees, leaning one way: a node mirrored");
            assert!(err.contains(&named), "{err}");
        }
        assert!(!err.contains("30 degrees"), "{err}");
    }

    /// The guided projection from walls orthogonal to S runs only where no turn made a
    /// honeycomb, and the iterations of failed tries are counted.
    #[test]
    fn the_unturned_walls_are_the_last_resort() {
        let tries = [
            ShadingTry::Turned(SHADING_TURNS[0]),
            ShadingTry::Turned(SHADING_TURNS[1]),
            ShadingTry::Unturned,
        ];
        let mut asked = Vec::new();
        let err = shading_tries(&tries, &mut Progress::silent(), |t, _| {
            asked.push(t);
            Ok(Tried::Failed(format!("no honeycomb ({t})"), 7))
        })
        .err()
        .expect("no try made anything")
        .to_string();
        assert_eq!(
            asked, tries,
            "every try is made where none gives a honeycomb"
        );
        assert!(
            err.contains("not turned across the light: no honeycomb"),
            "{err}"
        );

        let (base, surface) = crate::generate::lifted_hex_patch(crate::generate::Shape::Dome, 150);
        let surface = Surface::new(surface).unwrap();
        let shading = Shading {
            light: Vec3::new(0.0, 0.0, -1.0),
            sun_path: Vec::new(),
            depth: None,
        };
        let (mut asked, mut made) = (Vec::new(), 0);
        let out = shading_tries(&tries, &mut Progress::silent(), |t, _| {
            asked.push(t);
            if t != ShadingTry::Turned(SHADING_TURNS[1]) {
                return Ok(Tried::Failed("a node mirrored".into(), 7));
            }
            let solved = solve_base(
                &base,
                &surface,
                Walls::Across,
                shading.targets(SHADING_TURNS[1], &surface),
                &OptimizeOptions::default(),
                &mut |_| {},
            )?;
            made = solved.report.iterations_total;
            let targets = shading.targets(SHADING_TURNS[1], &surface);
            let (optimized, report) =
                shade(solved.optimized, solved.report, &surface, &shading, targets);
            Ok(Tried::Made(Box::new(outcome(
                optimized,
                report,
                base.clone(),
                None,
            ))))
        })
        .expect("a try made a honeycomb");
        assert_eq!(asked, tries[..2], "the last resort is not made");
        assert!(made > 0);
        assert_eq!(out.report.iterations_total, made + 7);
    }
}
