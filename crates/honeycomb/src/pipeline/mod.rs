//! From a design surface to a honeycomb: which base mesh, which solve, which retries. The one
//! strategy that `honeycomb pipeline`, `optimize`, `demo` and the editor's surface source share.
//!
//! - [`Walls::Across`] (the default): a flattening that keeps lengths (ARAP) gives cells of one
//!   size on S; the node axes are fitted to S's normals as a folded sheet and the vertices
//!   placed on its walls (`reciprocal`), boundary cells the placement breaks dropped and those
//!   standing out beyond S's border trimmed. A surface that curves more than a lattice of the
//!   cells asked absorbs is refused at once. Where the result is not clean (after a repair, the
//!   lattice turned by 30 degrees and the first lattice again with the sheet's walls facing
//!   out), the guided projection of the same mesh is kept instead, unless it is no honeycomb
//!   while the walls across S are one.
//! - [`Walls::Uniform`]: S seen along its mean normal, a regular grid laid in plan view and
//!   lifted: a honeycomb with parallel node axes (vertical walls on a roof) from the start.
//!   Where S folds over in that view, no parallel axes stand on it: walls across S instead.
//! - [`Walls::Direction`]: the same seen along a given direction.
//! - [`Walls::Free`]: the guided projection of the ARAP mesh from walls orthogonal to S, the
//!   axes wherever it leaves them (the paper's algorithm).

mod evening;
mod walls;

pub use walls::Walls;

use evening::evened;
pub(crate) use evening::UNEVEN_CELLS_CV;

use crate::error::{rounded, short_vector, Error, Result};
use crate::init::{flatten_viewed, init, Align, Flattener, InitOptions, Initialized, Method};
use crate::mesh::{validate_surface_mesh, PolyMesh};
use crate::optimize::{
    optimize, optimize_made_mesh, Attempt, AxesOptions, Frame, OptimizeOptions, Optimized,
    WallNormals, DEFAULT_THICKNESS,
};
use crate::reciprocal::{
    walls_across, Across, AcrossOptions, AxisTargets, Stage, PROVISIONAL_OMEGA_DEG,
};
use crate::report::Report;
use crate::solve::IterationInfo;
use crate::structure::{measure, Measures};
use crate::surface::Surface;
use std::time::Instant;

/// Everything the pipeline runs with, in the solver's terms ([`crate::PipelineOptions`] is
/// the front door's).
#[derive(Clone, Debug)]
pub struct Strategy {
    /// The base mesh; its method and flattening are the pipeline's to choose unless
    /// `init_chosen`.
    pub init: InitOptions,
    pub init_chosen: bool,
    pub walls: Walls,
    /// The guided projection's options (every walls but across, and the fallback of across).
    pub optimize: OptimizeOptions,
    /// A second try without the opposite-wall fairness is allowed (the fairness was not the
    /// caller's choice).
    pub second_try: bool,
    pub across: AcrossOptions,
    /// Where walls across S give no clean honeycomb on the last base mesh, the guided
    /// projection of that mesh (else the unclean walls across if they are a honeycomb, or
    /// an error saying why there is none).
    pub guided_fallback: bool,
    /// Uneven cells of clean walls across S are evened ([`evened`]); never for a shading
    /// device, whose axes are fitted across the light (`PipelineOptions` refuses both).
    pub even_cells: bool,
}

/// What the pipeline made.
pub struct Pipelined {
    /// The hexagonal mesh `init` made (its report, which `init.json` holds).
    pub initialized: Initialized,
    /// The mesh the kept result started from: `initialized.base` without dropped cells.
    pub base: PolyMesh,
    pub optimized: Optimized,
    /// `report.json` (its `seconds` from the pipeline's start; its notes say what the pipeline
    /// changed on the way, one sentence each).
    pub report: Report,
}

/// Where the pipeline is, for a progress display.
#[derive(Clone, Copy, Debug)]
pub enum Step<'a> {
    /// Making the hexagonal mesh.
    Init,
    /// An iteration of a solve: which solve (a short phrase), its number from 1, and the
    /// iteration.
    Iteration(&'a str, usize, &'a IterationInfo),
}

/// A base mesh whose cells on S differ in edge length by more than this (coefficient of
/// variation) means a surface no lattice of one cell size covers: refused.
pub const MAX_BASE_EDGE_CV: f64 = 0.25;

/// A honeycomb of walls across S is kept when every vertex is this close to S (mean edge
/// lengths), besides the honeycomb tolerances and no wall quad crossed (see `is_clean`).
const ACROSS_CLOSENESS: f64 = crate::reciprocal::ON_S;

/// Seeds the pipeline tries with the field method: the next one's singular points and
/// dislocations fall elsewhere.
const FIELD_SEEDS: u64 = 2;
/// Where walls across S on the flattened grid give no clean honeycomb, the grid is laid once
/// more turned by this much (radians): half the lattice's symmetry, the cells' walls then
/// where the first grid's edges ran.
const SECOND_TURN: f64 = std::f64::consts::FRAC_PI_6;

/// The weight of the walls facing out (`AxisFieldOptions::facing`) in the last try of walls
/// across on a flattened grid. Where S curves too sharply for the sheet, its fit turns some
/// node triangles over (the orthogonality guides hold either side); which folds it takes
/// depends on the start and the guides, so a fit that tells the sides apart is another
/// chance, not a better default: it slows the fit on gently curved surfaces.
const FACING_RETRY: f64 = 1.0;

/// Rounds of dropping boundary cells from a designer's mesh whose walls a light turned.
const DESIGNER_DROP_ROUNDS: usize = 5;

/// Runs the pipeline on `surface`.
pub fn pipeline(
    model_surface: &Surface,
    options: &Strategy,
    progress: &mut dyn FnMut(Step),
) -> Result<Pipelined> {
    let start = Instant::now();
    let surface = model_surface.source_mesh();
    validate_surface_mesh(surface)?;
    let mut notes = Vec::new();
    // Variants solve a plan-view mesh by the guided projection; their axes are their own.
    let walls = match options.walls {
        Walls::Across if options.optimize.is_variant() => Walls::Free,
        w => w,
    };
    let walls = match walls {
        Walls::Uniform if !options.init_chosen => match seen_in_plan(surface) {
            Ok(()) => walls,
            Err(e) => {
                notes.push(format!(
                    "seen along its mean normal: {}; no parallel axes stand on it, and these \
                     are walls across S (the default)",
                    message(&e)
                ));
                Walls::Across
            }
        },
        w => w,
    };
    let mut attempts = attempts(&options.init, walls);
    let mut spent = 0;
    // Whether walls across S mirrored a node on every mesh tried so far.
    let mut mirrored_every = true;
    for k in 0..attempts.len() {
        let (init_options, what, facing) = attempts[k].clone();
        let init_options = &init_options;
        let mut tried = options.clone();
        if let Some(weight) = facing {
            tried.across.field.facing = weight;
        }
        let options = &tried;
        let last = k + 1 == attempts.len();
        progress(Step::Init);
        let (made, made_notes) =
            match base_mesh(surface, model_surface, init_options, options, walls) {
                Ok(made) => made,
                // S too curved for the cells asked is so whichever way the grid is laid.
                Err(e) if !last && !matches!(e, Error::Unsuited(_)) => {
                    mirrored_every = false;
                    notes.push(format!(
                        "{what}: {}; trying {}",
                        message(&e),
                        attempts[k + 1].1
                    ));
                    continue;
                }
                Err(e) => return Err(e),
            };
        notes.extend(made_notes);
        if !last && made.report.method == Method::Field && init_options.method == Method::Flatten {
            // No flattening suited S: the next try is the field's next seed, not a turned grid.
            let seed = init_options.seed.wrapping_add(1);
            let next = InitOptions {
                method: Method::Field,
                seed,
                ..init_options.clone()
            };
            attempts[k + 1] = (next, format!("--method field --seed {seed}"), None);
            // The tries after it are of the flattened grid, which did not suit S.
            attempts.truncate(k + 2);
        }
        // Uniform walls on a grid that is not the plan view (S folds over seen from it) are the
        // guided projection's.
        let planar = made.report.flat.as_ref().map(|f| f.flattener) == Some(Flattener::Project);
        let walls = match walls {
            Walls::Uniform if !planar => Walls::Free,
            w => w,
        };
        let otherwise = match (last, mirrored_every) {
            (false, _) => Otherwise::Why,
            (true, false) => Otherwise::Guided,
            (true, true) => Otherwise::GuidedUnlessMirrored(k + 1),
        };
        let solved = solve_made(
            &made,
            surface,
            model_surface,
            options,
            walls,
            otherwise,
            progress,
        )?;
        let solved = match solved {
            Err(not_clean) if last => {
                return Err(Error::Solver(format!("{what}: {}", not_clean.why)))
            }
            solved => solved,
        };
        let (made, solved) = match solved {
            Ok(solved) if solved.report.honeycomb => {
                let (made, solved, note) = more_even_unturned(
                    made,
                    solved,
                    (surface, model_surface),
                    init_options,
                    options,
                    walls,
                    progress,
                );
                notes.extend(note);
                (made, Ok(solved))
            }
            solved => (made, solved),
        };
        match solved {
            Ok(mut solved) if solved.report.honeycomb || last => {
                if k > 0 {
                    notes.push(format!("this is {what}"));
                }
                notes.append(&mut solved.notes);
                solved.report.iterations_total += spent;
                solved.report.seconds = start.elapsed().as_secs_f64();
                solved.report.notes = notes.clone();
                return Ok(Pipelined {
                    initialized: made,
                    base: solved.base,
                    optimized: solved.optimized,
                    report: solved.report,
                });
            }
            Ok(solved) => {
                spent += solved.report.iterations_total;
                mirrored_every = false;
                notes.push(format!(
                    "{what}: its mesh gave no honeycomb ({}); trying {}",
                    flaws(&solved.measures, None),
                    attempts[k + 1].1
                ));
            }
            Err(not_clean) => {
                spent += not_clean.iterations;
                mirrored_every &= not_clean.mirrored;
                let why = &not_clean.why;
                notes.push(format!("{what}: {why}; trying {}", attempts[k + 1].1));
            }
        }
    }
    unreachable!("the last attempt returns")
}

/// Walls across S on a grid turned round a hole (`made`) whose cells stayed uneven: the same
/// grid laid on S flattened whole instead, kept where it is a honeycomb with more even cells
/// (the turn evens the flattening, not always the walls), with a note saying so; the
/// iterations of both count.
fn more_even_unturned(
    made: Initialized,
    solved: Solved,
    (surface, model_surface): (&PolyMesh, &Surface),
    init_options: &InitOptions,
    options: &Strategy,
    walls: Walls,
    progress: &mut dyn FnMut(Step),
) -> (Initialized, Solved, Option<String>) {
    let turned = made.report.flat.as_ref().and_then(|f| f.hole_turn_deg);
    let uneven = solved.measures.edge_length_cv >= UNEVEN_CELLS_CV;
    let (Some(turn), true, Walls::Across) = (turned, uneven, walls) else {
        return (made, solved, None);
    };
    let whole = InitOptions {
        round_holes: false,
        ..init_options.clone()
    };
    let Ok((again_made, _)) = base_mesh(surface, model_surface, &whole, options, walls) else {
        return (made, solved, None);
    };
    let again = solve_made(
        &again_made,
        surface,
        model_surface,
        options,
        walls,
        Otherwise::Why,
        progress,
    );
    let spent = match &again {
        Ok(Ok(again)) => again.report.iterations_total,
        Ok(Err(not_clean)) => not_clean.iterations,
        Err(_) => 0,
    };
    match again {
        Ok(Ok(mut again))
            if again.report.honeycomb
                && again.measures.edge_length_cv < solved.measures.edge_length_cv =>
        {
            again.report.iterations_total += solved.report.iterations_total;
            let laid = if turn == 0.0 {
                "run round a tube".to_string()
            } else {
                format!("turned by {turn} degrees round a hole")
            };
            let note = format!(
                "the grid {laid} left the cells uneven (edge cv {}); laid on S flattened whole \
                 they are more even ({})",
                rounded(solved.measures.edge_length_cv, 3),
                rounded(again.measures.edge_length_cv, 3)
            );
            (again_made, again, Some(note))
        }
        _ => {
            let mut solved = solved;
            solved.report.iterations_total += spent;
            (made, solved, None)
        }
    }
}

/// The base meshes the pipeline tries in turn, each with how a note names it and the weight
/// of the walls facing out in the sheet's fit (`AxisFieldOptions::facing`; `None`: as the
/// options have it): the field method's seed and the next; walls across on a flattened grid,
/// the grid, the grid turned by [`SECOND_TURN`], and the grid again with the walls facing out
/// ([`FACING_RETRY`]); else the one asked for.
fn attempts(init: &InitOptions, walls: Walls) -> Vec<(InitOptions, String, Option<f64>)> {
    match (init.method, walls) {
        (Method::Field, _) => (0..FIELD_SEEDS)
            .map(|k| {
                let seed = init.seed.wrapping_add(k);
                let options = InitOptions {
                    seed,
                    ..init.clone()
                };
                (options, format!("--seed {seed}"), None)
            })
            .collect(),
        (Method::Flatten, Walls::Across) => {
            let turned = InitOptions {
                turn: init.turn + SECOND_TURN,
                ..init.clone()
            };
            vec![
                (init.clone(), "the flattened grid".into(), None),
                (
                    turned,
                    "the flattened grid turned by 30 degrees".into(),
                    None,
                ),
                (
                    init.clone(),
                    "the flattened grid with the sheet's walls facing out".into(),
                    Some(FACING_RETRY),
                ),
            ]
        }
        _ => vec![(init.clone(), "the grid".into(), None)],
    }
}

/// `n` things, in words: "1 boundary cell", "3 boundary cells".
fn counted(n: usize, thing: &str) -> String {
    format!("{n} {thing}{}", if n == 1 { "" } else { "s" })
}

/// The verb for `n` things: "1 cell was", "3 cells were".
fn were(n: usize) -> &'static str {
    if n == 1 {
        "was"
    } else {
        "were"
    }
}

/// An error's message without its kind (for a note).
fn message(e: &Error) -> String {
    match e {
        Error::Mesh(m) | Error::Parameter(m) | Error::Solver(m) | Error::Unsuited(m) => m.clone(),
        e => e.to_string(),
    }
}

/// Whether `surface` seen along its mean normal (or the view nearby that sees most of it) lies
/// in plan without folding over, as uniform walls need: otherwise why not.
fn seen_in_plan(surface: &PolyMesh) -> Result<()> {
    let (vertices, triangles) = surface.star_triangulated();
    flatten_viewed(&vertices, &triangles, Flattener::Project, None).map(|_| ())
}

/// The base mesh for `walls`, with the notes of what it took.
fn base_mesh(
    surface: &PolyMesh,
    model_surface: &Surface,
    init_options: &InitOptions,
    options: &Strategy,
    walls: Walls,
) -> Result<(Initialized, Vec<String>)> {
    let mut notes = Vec::new();
    let made = match walls {
        Walls::Uniform | Walls::Direction(_) => plan_view(
            surface,
            init_options,
            options.init_chosen,
            walls,
            &mut notes,
        )?,
        Walls::Across | Walls::Free
            if options.init_chosen || init_options.method == Method::Field =>
        {
            let made = init(surface, init_options)?;
            if walls == Walls::Across {
                check_cell_sizes(&made, model_surface)?;
            }
            made
        }
        Walls::Across | Walls::Free => {
            let arap = InitOptions {
                flattener: Flattener::Arap,
                method: Method::Flatten,
                ..init_options.clone()
            };
            match init(surface, &arap) {
                Ok(made) if made.report.edge_length_cv <= MAX_BASE_EDGE_CV => made,
                flat => {
                    // No flattening lays cells of one size here: S wraps around a hole (a
                    // band), or curves more than a lattice of this size absorbs.
                    let why = match &flat {
                        Ok(made) => format!(
                            "the flattened grid's cells differ in edge length by a cv of {}",
                            rounded(made.report.edge_length_cv, 3)
                        ),
                        Err(e) => message(e),
                    };
                    check_curvature(surface, model_surface, init_options, &why)?;
                    notes.push(format!(
                        "{why}; this is the field-aligned mesh (--method field)"
                    ));
                    // The field has no principal directions to follow: the boundary then.
                    let align = match &init_options.align {
                        Align::Curvature => Align::Boundary,
                        align => align.clone(),
                    };
                    init(
                        surface,
                        &InitOptions {
                            method: Method::Field,
                            align,
                            ..init_options.clone()
                        },
                    )?
                }
            }
        }
    };
    Ok((made, notes))
}

/// A honeycomb on a base mesh, with its report and what it took.
pub struct Solved {
    /// The mesh the result started from (the base mesh without dropped cells).
    pub base: PolyMesh,
    pub optimized: Optimized,
    pub measures: Measures,
    pub report: Report,
    pub notes: Vec<String>,
    /// Walls across S fitted provisionally (`AcrossOptions::provisional_if_uneven`), for the
    /// evening to start from: no result yet.
    pub provisional: bool,
}

/// What follows where walls across S give no clean honeycomb on a mesh the pipeline made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Otherwise {
    /// Why (another mesh is tried next).
    Why,
    /// The guided projection (the strategy's fallback, on the last mesh).
    Guided,
    /// The guided projection, unless this mesh too mirrors a node, as the ones before it did
    /// (this many meshes in all): where no fitted sheet keeps every node facing up, the
    /// guided projection from walls orthogonal to S has made no honeycomb either, and it
    /// takes the longest (docs/walls.md, "Checks and retries").
    GuidedUnlessMirrored(usize),
}

/// Solves a mesh the pipeline made (its boundary cells may be dropped): walls across S, else
/// (as `otherwise` says) the guided projection or, where that is no honeycomb, the unclean
/// walls across that are one; or why walls across gave no clean honeycomb and the iterations
/// that took.
fn solve_made(
    made: &Initialized,
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &Strategy,
    walls: Walls,
    otherwise: Otherwise,
    progress: &mut dyn FnMut(Step),
) -> Result<std::result::Result<Solved, NotClean>> {
    options.optimize.validate(&made.base)?;
    if walls == Walls::Across {
        let mut across_options = options.across.clone();
        if options.even_cells {
            across_options.provisional_if_uneven = Some(UNEVEN_CELLS_CV);
        }
        let across = |across_options: &AcrossOptions, progress: &mut dyn FnMut(Step)| {
            across_or_none(
                &made.base,
                surface,
                model_surface,
                &options.optimize,
                across_options,
                progress,
            )
        };
        let not_clean = match across(&across_options, progress)? {
            Ok(solved) if !options.even_cells => return Ok(Ok(solved)),
            Ok(solved) => {
                let fitted_notes = solved.notes.len();
                let evened = evened(solved, surface, model_surface, &options.optimize, progress)?;
                if !evened.provisional {
                    return Ok(Ok(evened));
                }
                // The evening kept nothing of a provisional fit: the walls fitted to unit
                // length after all, with what the evening tried said and counted.
                let tried = evened.report.iterations_total;
                across_options.provisional_if_uneven = None;
                match across(&across_options, progress)? {
                    Ok(mut solved) => {
                        solved.report.iterations_total += tried;
                        solved
                            .notes
                            .extend(evened.notes.into_iter().skip(fitted_notes));
                        return Ok(Ok(solved));
                    }
                    Err(not_clean) => NotClean {
                        iterations: not_clean.iterations + tried,
                        ..not_clean
                    },
                }
            }
            Err(not_clean) => not_clean,
        };
        if otherwise == Otherwise::Why {
            return Ok(Err(not_clean));
        }
        if !options.guided_fallback {
            return Ok(not_clean.into_walls_as_they_came());
        }
        if let (true, Otherwise::GuidedUnlessMirrored(meshes)) = (not_clean.mirrored, otherwise) {
            return Ok(Err(not_clean.mirrored_on_every_mesh(meshes)));
        }
        let solved = guided(
            &made.base,
            surface,
            model_surface,
            options,
            Walls::Free,
            progress,
        )?;
        return Ok(Ok(not_clean.or_better(solved)));
    }
    Ok(Ok(guided(
        &made.base,
        surface,
        model_surface,
        options,
        walls,
        progress,
    )?))
}

/// Solves a designer's base mesh on `surface` (which may be the base mesh itself,
/// [`Surface::of_base`]) with its walls as asked: across S by the fitted sheet (the guided projection where that gives no honeycomb,
/// which a note says), free by the guided projection, or uniform or along a direction by the
/// guided projection with those axes prescribed. No cell is dropped: a designer's cells are
/// the design. Variants (parallel meshes, quads, prescribed axes) go to
/// [`crate::optimize::optimize`] directly.
pub fn solve_base(
    base: &PolyMesh,
    model_surface: &Surface,
    walls: Walls,
    targets: AxisTargets,
    options: &OptimizeOptions,
    progress: &mut dyn FnMut(Step),
) -> Result<Solved> {
    let start = Instant::now();
    let surface_mesh = model_surface.source_mesh();
    let surface = model_surface.design_mesh();
    let mut not_clean = None;
    if walls == Walls::Across {
        // A designer's mesh keeps its cells; turned across a light, the axes cross the walls
        // of a few boundary cells, which are dropped rather than the device given up.
        let defaults = AcrossOptions::default();
        let keep_cells = AcrossOptions {
            max_drops: if targets == AxisTargets::Normals {
                0
            } else {
                DESIGNER_DROP_ROUNDS
            },
            max_dropped_share: crate::optimize::MAX_DROPPED_SHARE,
            max_trimmed_share: 0.0,
            targets,
            ..defaults
        };
        match across_or_none(
            base,
            surface_mesh,
            model_surface,
            options,
            &keep_cells,
            progress,
        )? {
            Ok(mut solved) => {
                solved.report.seconds = start.elapsed().as_secs_f64();
                solved.report.notes = solved.notes.clone();
                return Ok(solved);
            }
            Err(e) => not_clean = Some(e),
        }
    }
    let mut prescribed = options.clone();
    let direction = match walls {
        Walls::Uniform => Some(model_surface.mean_normal()),
        Walls::Direction(d) => Some(d),
        Walls::Across | Walls::Free => None,
    };
    if let Some(d) = direction {
        if d.norm() == 0.0 {
            return Err(Error::Mesh(
                "--walls uniform: S has no mean normal (its areas cancel: a closed surface); \
                 give a direction DX,DY,DZ"
                    .into(),
            ));
        }
        prescribed.axes = Some(AxesOptions {
            targets: vec![d; base.vertices.len()],
            weight: AxesOptions::DEFAULT_WEIGHT,
        });
    }
    let mut iterations = 0;
    let optimized = optimize(base, surface, &prescribed, &mut |info| {
        iterations += 1;
        progress(Step::Iteration("guided projection", 1, info))
    })?;
    let measures = measure(&optimized.honeycomb, model_surface);
    let guided_iterations = iterations;
    let (optimized, measures, made_exact) = exact(
        optimized,
        measures,
        walls,
        surface_mesh,
        model_surface,
        &prescribed,
        &mut |info| {
            iterations += 1;
            progress(Step::Iteration("making it exact", 1, info))
        },
    )?;
    let mut notes = Vec::new();
    if made_exact {
        notes.push(made_exact_note(iterations - guided_iterations));
    }
    let mut report = Report::new(&optimized, &measures, start.elapsed().as_secs_f64());
    report.walls = if walls == Walls::Across {
        Walls::Free
    } else {
        walls
    };
    report.iterations_total = iterations;
    let solved = Solved {
        base: base.clone(),
        optimized,
        measures,
        report,
        notes,
        provisional: false,
    };
    let mut solved = match not_clean {
        Some(not_clean) => not_clean.or_better(solved),
        None => solved,
    };
    solved.report.seconds = start.elapsed().as_secs_f64();
    solved.report.notes = solved.notes.clone();
    Ok(solved)
}

impl Solved {
    /// These walls across S replaced by `again` (the honeycomb solved again from them, its
    /// measures and a thinning note), `note` saying why: the report is the new honeycomb's,
    /// with the fit's bookkeeping (walls, iterations in all, cells dropped and trimmed)
    /// kept.
    fn replace_by(
        &mut self,
        (optimized, measures, thinner): (Optimized, Measures, Option<String>),
        note: String,
        seconds: f64,
    ) {
        let fitted = &self.report;
        let mut report = Report::new(&optimized, &measures, seconds);
        report.walls = fitted.walls;
        report.iterations_total = fitted.iterations_total;
        report.dropped_boundary_cells = fitted.dropped_boundary_cells;
        report.trimmed_boundary_cells = fitted.trimmed_boundary_cells;
        report.axis_field_iterations = fitted.axis_field_iterations;
        self.report = report;
        self.notes.push(note);
        self.notes.extend(thinner);
        self.optimized = optimized;
        self.measures = measures;
        self.provisional = false;
    }
}

/// Walls across S that are no clean honeycomb: why, the iterations that took, and the result
/// itself when it still meets the honeycomb tolerances (kept if nothing better comes).
struct NotClean {
    why: String,
    iterations: usize,
    honeycomb: Option<Box<Solved>>,
    /// A node was mirrored (turned over), which no repair turns back.
    mirrored: bool,
}

impl NotClean {
    /// These walls across as they came where they are a honeycomb (a note says what they
    /// fall short of), else why there is none and the iterations it took.
    fn into_walls_as_they_came(self) -> std::result::Result<Solved, NotClean> {
        match self.honeycomb {
            Some(mut across) => {
                across
                    .notes
                    .push(format!("{}; these are the walls as they came", self.why));
                Ok(*across)
            }
            None => Err(self),
        }
    }

    /// Why there is no honeycomb where walls across S mirrored a node on each of `meshes`
    /// meshes, and the guided projection is therefore not tried.
    fn mirrored_on_every_mesh(self, meshes: usize) -> NotClean {
        NotClean {
            why: format!(
                "{}; walls across S turned a node over on each of the {meshes} meshes tried, \
                 and the guided projection from walls orthogonal to S, which has made no \
                 honeycomb wherever that happened, is not run (`--walls free` runs it; \
                 `--walls uniform` stands every node axis along S's mean normal)",
                self.why
            ),
            ..self
        }
    }

    /// The better of `solved` (the guided projection) and these walls across: the guided
    /// projection unless it is no honeycomb and these are (a note says so).
    fn or_better(self, mut solved: Solved) -> Solved {
        match self.honeycomb {
            Some(mut across) if !solved.report.honeycomb => {
                across.report.iterations_total += solved.report.iterations_total;
                across.notes.push(format!(
                    "{}; the guided projection gave no honeycomb either ({}), so these are the \
                     walls across S as they came",
                    self.why,
                    flaws(&solved.measures, None)
                ));
                *across
            }
            _ => {
                solved.report.iterations_total += self.iterations;
                solved.notes.insert(
                    0,
                    format!("{}; this is the guided projection (--walls free)", self.why),
                );
                solved
            }
        }
    }
}

/// Walls across S on `base`: the clean honeycomb, or why there is none.
fn across_or_none(
    base: &PolyMesh,
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &OptimizeOptions,
    across_options: &AcrossOptions,
    progress: &mut dyn FnMut(Step),
) -> Result<std::result::Result<Solved, NotClean>> {
    let start = Instant::now();
    let mut across_options = AcrossOptions {
        thickness: options.thickness,
        ..across_options.clone()
    };
    across_options.field.cancel = options.solver.cancel.clone();
    across_options.placement.cancel = options.solver.cancel.clone();
    let mut spent = 0;
    let across = walls_across(
        base,
        None,
        surface,
        model_surface,
        &across_options,
        &mut |stage, info| {
            spent += 1;
            let name = match stage {
                Stage::AxisField => "fitting the node axes",
                Stage::Placement => "placing the vertices",
            };
            progress(Step::Iteration(name, 1, info))
        },
    );
    let mut across = match across {
        Ok(across) => across,
        // A sheet the fit left folded flat gives nodes no line to place their vertex on.
        Err(Error::Solver(_)) => {
            return Ok(Err(NotClean {
                why: "the node axes fitted to S's normals folded too sharply to place the \
                      vertices on their walls"
                    .into(),
                iterations: spent,
                honeycomb: None,
                mirrored: false,
            }));
        }
        Err(e) => return Err(e),
    };
    let (h, m) = (&mut across.honeycomb, &mut across.measures);
    let thinner = uncross(h, &across.connectivity, m, model_surface, options.thickness);
    let mut notes: Vec<String> = thinner.into_iter().collect();
    let nodes_deg = match across.provisional {
        true => PROVISIONAL_OMEGA_DEG,
        false => CLEAN_OMEGA_DEG,
    };
    let clean = is_clean_to(&across.measures, options.min_edge, nodes_deg);
    if across.provisional && !clean {
        // Flawed besides its nodes' last digits: walls across fitted to unit length from the
        // start, to be checked and repaired as any other.
        let exact = AcrossOptions {
            provisional_if_uneven: None,
            ..across_options
        };
        let again = across_or_none(base, surface, model_surface, options, &exact, progress)?;
        return Ok(match again {
            Ok(mut solved) => {
                solved.report.iterations_total += spent;
                Ok(solved)
            }
            Err(not_clean) => Err(NotClean {
                iterations: not_clean.iterations + spent,
                ..not_clean
            }),
        });
    }
    if clean {
        let mut solved = across_solved(across, options, start.elapsed().as_secs_f64());
        solved.notes.append(&mut notes);
        return Ok(Ok(solved));
    }
    let why = format!(
        "walls across S: {}",
        flaws(&across.measures, options.min_edge)
    );
    let mut repair_iterations = 0;
    // A few steps from where the vertices stand move them a little: they do not turn a
    // mirrored node back over, whose walls would have to pass through each other.
    let mirrored = across.measures.omega_max_deg >= MIRRORED_NODE_DEG;
    let repaired = if mirrored {
        None
    } else {
        repair(&across, surface, model_surface, options, &mut |info| {
            repair_iterations += 1;
            progress(Step::Iteration("repairing", 1, info))
        })?
    };
    spent += repair_iterations;
    let seconds = start.elapsed().as_secs_f64();
    let mut solved = across_solved(across, options, seconds);
    solved.report.iterations_total = spent;
    match repaired {
        Some(again) => {
            let note = format!(
                "{why}; {repair_iterations} iterations of the guided projection from there \
                 (without fairness, with a minimum edge length) repaired them"
            );
            solved.replace_by(again, note, seconds);
            Ok(Ok(solved))
        }
        None => {
            solved.notes.append(&mut notes);
            let honeycomb = solved.report.honeycomb.then(|| Box::new(solved));
            Ok(Err(NotClean {
                why: if mirrored {
                    format!("{why}, which a repair does not turn back")
                } else {
                    format!("{why}, and a repair did not mend them")
                },
                iterations: spent,
                honeycomb,
                mirrored,
            }))
        }
    }
}

/// What keeps walls across S from being a clean honeycomb, in words.
fn flaws(m: &Measures, min_edge: Option<f64>) -> String {
    let mut flaws = Vec::new();
    if m.omega_max_deg > CLEAN_OMEGA_DEG {
        flaws.push(format!(
            "a node {} degrees off 120",
            rounded(m.omega_max_deg, 3)
        ));
    }
    if m.delta_max > CLEAN_DELTA {
        flaws.push(format!("a wall {} off planar", rounded(m.delta_max, 3)));
    }
    if m.nonconvex_walls > 0 {
        flaws.push(counted(m.nonconvex_walls, "crossed wall"));
    }
    if m.closeness_max > ACROSS_CLOSENESS {
        flaws.push(format!(
            "a vertex {} edge lengths off S",
            rounded(m.closeness_max, 3)
        ));
    }
    if min_edge.is_some_and(|l| m.min_edge_length < l) {
        flaws.push(format!(
            "an edge {} model units long (shorter than --min-edge)",
            rounded(m.min_edge_length, 4)
        ));
    }
    flaws.join(", ")
}

/// A honeycomb across S is kept when its nodes and walls are exact (omega and delta well
/// within the honeycomb tolerances), no wall quad crossed, every vertex on S and every edge at
/// least `min_edge` long (model units).
fn is_clean(m: &Measures, min_edge: Option<f64>) -> bool {
    is_clean_to(m, min_edge, CLEAN_OMEGA_DEG)
}

/// `is_clean` with the nodes within `omega_deg` of 120 degrees.
fn is_clean_to(m: &Measures, min_edge: Option<f64>, omega_deg: f64) -> bool {
    m.omega_max_deg <= omega_deg
        && m.delta_max <= CLEAN_DELTA
        && m.nonconvex_walls == 0
        && m.closeness_max <= ACROSS_CLOSENESS
        && min_edge.is_none_or(|l| m.min_edge_length >= l * (1.0 - 1e-9))
}

/// The least thickness (mean edge lengths) the default is made to keep every wall quad from
/// crossing itself.
const MIN_THICKNESS: f64 = 0.1;

/// A honeycomb at the default thickness (`asked` is `None`) whose wall quads cross (M''s edge
/// running against M's, where two neighbouring axes lean together) made thinner, down to
/// [`MIN_THICKNESS`] mean edge lengths, so that none does; a note says so. A thickness the
/// user asked for is kept.
pub(crate) fn uncross(
    h: &mut crate::structure::Honeycomb,
    conn: &crate::mesh::Connectivity,
    measures: &mut Measures,
    surface: &Surface,
    asked: Option<f64>,
) -> Option<String> {
    if asked.is_some() {
        return None;
    }
    let unit = h.base.mean_edge_length();
    let (default, least) = (DEFAULT_THICKNESS * unit, MIN_THICKNESS * unit);
    let thickest = crate::structure::thickest_uncrossed(h);
    if measures.nonconvex_walls == 0 || thickest >= default || 0.9 * thickest < least {
        return None;
    }
    let thickness = 0.9 * thickest;
    *h = crate::structure::Honeycomb::new(h.base.clone(), conn, h.axes.clone(), thickness);
    *measures = measure(h, surface);
    Some(format!(
        "the walls are {} mean edge lengths deep instead of {DEFAULT_THICKNESS}, so that none \
         crosses itself where neighbouring node axes lean together (--thickness sets it)",
        rounded(thickness / unit, 3)
    ))
}

/// What `is_clean` asks of a node's angles (degrees) and a wall's planarity.
const CLEAN_OMEGA_DEG: f64 = 0.01;
const CLEAN_DELTA: f64 = 1e-6;

/// A node this far off 120 degrees is mirrored (a trivalent one measures 120): no repair is
/// tried.
const MIRRORED_NODE_DEG: f64 = 90.0;

/// Iterations of the repair at most.
const REPAIR_ITERATIONS: usize = 20;
/// The repair's shortest edge, in mean edge lengths.
const REPAIR_MIN_EDGE: f64 = 0.3;

/// Walls across S that are no clean honeycomb (a node turned over, a wall crossed, a vertex
/// off S, an edge shorter than `--min-edge`) solved again by the guided projection from where
/// they stand ([`resolved`]). `None` when that is no clean honeycomb either.
fn repair(
    across: &Across,
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &OptimizeOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Option<(Optimized, Measures, Option<String>)>> {
    let solved = resolved(&across.honeycomb, surface, model_surface, options, progress)?;
    Ok(solved.filter(|(_, measures, _)| is_clean(measures, options.min_edge)))
}

/// The honeycomb `h` solved again by at most [`REPAIR_ITERATIONS`] of the guided projection
/// from where it stands (see [`again_from`]). `None` when the solve breaks down.
fn resolved(
    h: &crate::structure::Honeycomb,
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &OptimizeOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Option<(Optimized, Measures, Option<String>)>> {
    let again = again_from(h, options, REPAIR_ITERATIONS);
    solved_again(h, surface, model_surface, &again, progress)
}

/// Options that solve the honeycomb `h` again by at most `iterations` of the guided projection
/// from where it stands: its vertices and walls, without the opposite-wall fairness (which
/// would flatten its axes) and without prescribed axes, every edge kept from collapsing (or
/// as long as asked).
fn again_from(
    h: &crate::structure::Honeycomb,
    options: &OptimizeOptions,
    iterations: usize,
) -> OptimizeOptions {
    let mut again = options.clone();
    again.initial_normals = Some((0..h.edges.len()).map(|e| h.wall_normal(e)).collect());
    again.weights.fairness = 0.0;
    // From the walls as they stand: prescribed axes (the fallback's, for shading) would pull
    // them elsewhere, and cell points take none.
    again.axes = None;
    again.wall_normals = WallNormals::CellPoints;
    again.min_edge = options
        .min_edge
        .or(Some(REPAIR_MIN_EDGE * h.base.mean_edge_length()));
    again.solver.max_iterations = iterations;
    again
}

/// `h` solved with the options `again` (see [`again_from`]), measured, and made thinner
/// where its walls cross unless their thickness was asked. `None` when the solve breaks down.
fn solved_again(
    h: &crate::structure::Honeycomb,
    surface: &PolyMesh,
    model_surface: &Surface,
    again: &OptimizeOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<Option<(Optimized, Measures, Option<String>)>> {
    let mut optimized = match optimize(&h.base, Some(surface), again, progress) {
        Ok(optimized) => optimized,
        Err(Error::Solver(_)) => return Ok(None),
        Err(e) => return Err(e),
    };
    let mut measures = measure(&optimized.honeycomb, model_surface);
    let (h, conn) = (&mut optimized.honeycomb, &optimized.connectivity);
    let thinner = uncross(h, conn, &mut measures, model_surface, again.thickness);
    Ok(Some((optimized, measures, thinner)))
}

/// The guided projection with prescribed axes (shading's) made exact: the soft axes hold
/// the node and wall conditions off by about their weight, so a result short of the
/// variants' tolerances is solved again without them ([`resolved`]), the axes moving a
/// little. Only for axes prescribed across a light (walls across S or free), not a
/// direction the walls were asked to stand in (`walls`). The result as it was unless that is
/// exact, uncrossed where it was, and on S; `true` when it was made exact.
fn exact(
    optimized: Optimized,
    measures: Measures,
    walls: Walls,
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &OptimizeOptions,
    progress: &mut dyn FnMut(&IterationInfo),
) -> Result<(Optimized, Measures, bool)> {
    let shading = matches!(walls, Walls::Across | Walls::Free) && options.axes.is_some();
    if !shading || is_exact(&measures) {
        return Ok((optimized, measures, false));
    }
    let again = resolved(
        &optimized.honeycomb,
        surface,
        model_surface,
        options,
        progress,
    )?;
    Ok(match again {
        Some((o, m, _))
            if is_exact(&m)
                && m.nonconvex_walls <= measures.nonconvex_walls
                && m.closeness_max <= ACROSS_CLOSENESS.max(measures.closeness_max) =>
        {
            (o, m, true)
        }
        _ => (optimized, measures, false),
    })
}

/// What [`exact`] did, in a note.
fn made_exact_note(iterations: usize) -> String {
    format!(
        "the prescribed axes held the nodes and walls off exact; {iterations} iterations \
         without them made it exact"
    )
}

/// Within what the paper's variants ask of a honeycomb: omega below 0.05 degrees, delta
/// below 1e-5.
fn is_exact(m: &Measures) -> bool {
    m.omega_max_deg < 0.05 && m.delta_max < 1e-5
}

/// The plan-view base mesh of uniform walls: S seen along its mean normal or the direction
/// given. Uniform walls on a surface that folds over seen along its mean normal are walls
/// across S (see [`pipeline`]) unless the caller chose the grid; then they take the ARAP grid
/// (a note says so). A direction given is kept, or refused.
fn plan_view(
    surface: &PolyMesh,
    init_options: &InitOptions,
    init_chosen: bool,
    walls: Walls,
    notes: &mut Vec<String>,
) -> Result<Initialized> {
    let view = match walls {
        Walls::Direction(d) => Some(d),
        _ => None,
    };
    if init_chosen
        && (init_options.method == Method::Field || init_options.flattener != Flattener::Project)
    {
        if view.is_some() {
            return Err(Error::Parameter(
                "--walls DX,DY,DZ lays the grid in plan view along the direction: it takes no \
                 --method or --flatten"
                    .into(),
            ));
        }
        return init(surface, init_options);
    }
    let projected = InitOptions {
        flattener: Flattener::Project,
        method: Method::Flatten,
        view,
        ..init_options.clone()
    };
    match init(surface, &projected) {
        Ok(made) => Ok(made),
        Err(e) if view.is_none() => {
            notes.push(format!(
                "seen along its mean normal: {}; this is the ARAP grid and the guided \
                 projection (--walls free), whose axes are not parallel",
                message(&e)
            ));
            init(
                surface,
                &InitOptions {
                    flattener: Flattener::Arap,
                    ..init_options.clone()
                },
            )
        }
        Err(Error::Mesh(m)) => Err(Error::Mesh(format!(
            "--walls {}: {m}",
            short_vector(view.unwrap_or_default())
        ))),
        Err(e) => Err(e),
    }
}

/// A lattice of even spacing absorbs S's curvature one unit of 60 degrees per pentagon or
/// heptagon: beyond this many units per cell a mostly hexagonal honeycomb of cells of one size
/// is out of reach.
pub const MAX_CURVATURE_PER_CELL: f64 = 0.02;

/// Refuses a surface that curves more at the scale of the cells asked for than a hexagonal
/// lattice absorbs, saying how much and what would work; `why` is what the flattening showed.
fn check_curvature(
    surface: &PolyMesh,
    model_surface: &Surface,
    init_options: &InitOptions,
    why: &str,
) -> Result<()> {
    let area = surface.area();
    let edge = init_options.size.edge_on(area);
    let cells = area / crate::init::hexagon_area(edge);
    curved_at_most(model_surface, edge, cells, why)
}

/// A mesh made as the caller chose whose cells differ much in size is refused when S curves
/// more than a lattice absorbs (see [`check_curvature`]).
fn check_cell_sizes(made: &Initialized, surface: &Surface) -> Result<()> {
    let r = &made.report;
    if r.edge_length_cv <= MAX_BASE_EDGE_CV {
        return Ok(());
    }
    let why = format!(
        "the base mesh's cells differ in edge length by a cv of {}",
        rounded(r.edge_length_cv, 3)
    );
    curved_at_most(surface, r.edge_length_mean, r.cells as f64, &why)
}

/// Refuses S when it curves by more units of 60 degrees at the scale of cells of `edge` than
/// [`MAX_CURVATURE_PER_CELL`] of `cells`.
fn curved_at_most(surface: &Surface, edge: f64, cells: f64, why: &str) -> Result<()> {
    let units = surface.curvature_units(2.0 * edge);
    if units.positive + units.negative <= MAX_CURVATURE_PER_CELL * cells {
        return Ok(());
    }
    Err(Error::Unsuited(format!(
        "too curved for a honeycomb of cells of one size: at the scale of a cell (edge {}) S \
         curves by {:.0} units of 60 degrees like a dome and {:.0} like a saddle, and a \
         hexagonal lattice of even spacing absorbs one unit only with a pentagon or a heptagon \
         (about {:.0} cells here: at most {}% of them); {why}. What would work: S split into \
         pieces that each curve less (nearly developable ones, such as a roof or a vault), or \
         a surface smoother at this cell size",
        rounded(edge, 4),
        units.positive,
        units.negative,
        cells,
        (100.0 * MAX_CURVATURE_PER_CELL).round()
    )))
}

/// Walls across S as a solved honeycomb with its report.
fn across_solved(across: Across, options: &OptimizeOptions, seconds: f64) -> Solved {
    let optimized = across_optimized(
        across.honeycomb,
        across.connectivity,
        across.solve,
        &across.base,
        options,
    );
    let mut report = Report::new(&optimized, &across.measures, seconds);
    // The conditions hold by construction once the sheet has unit walls.
    report.converged = across.field_converged;
    report.walls = Walls::Across;
    report.iterations_total = optimized.solve.iterations;
    report.dropped_boundary_cells = Some(across.dropped_cells);
    report.trimmed_boundary_cells = Some(across.trimmed_cells);
    report.axis_field_iterations = Some(across.field_iterations);
    let mut notes = Vec::new();
    let broken = across.dropped_cells - across.trimmed_cells;
    if broken > 0 {
        notes.push(format!(
            "{} whose walls the fitted axes crossed or turned over (or that their loss cut \
             off) {} dropped; initial.obj is the mesh without them",
            counted(broken, "boundary cell"),
            were(broken)
        ));
    }
    if across.trimmed_cells > 0 {
        notes.push(format!(
            "{} that stood out beyond S's border (or that their loss cut off) {} trimmed; \
             initial.obj is the mesh without them",
            counted(across.trimmed_cells, "boundary cell"),
            were(across.trimmed_cells)
        ));
    }
    Solved {
        base: across.base,
        optimized,
        measures: across.measures,
        report,
        notes,
        provisional: across.provisional,
    }
}

/// A honeycomb of the sheet in the guided projection's terms (its wall normals those of its
/// walls; `base` the mesh it started from, for the frame).
fn across_optimized(
    honeycomb: crate::structure::Honeycomb,
    connectivity: crate::mesh::Connectivity,
    solve: crate::solve::SolveReport,
    base: &PolyMesh,
    options: &OptimizeOptions,
) -> Optimized {
    let normals = (0..honeycomb.edges.len())
        .map(|e| honeycomb.wall_normal(e))
        .collect();
    Optimized {
        honeycomb,
        connectivity,
        normals,
        solve,
        frame: Frame::of(base),
        prescribed_axes: None,
        parallel: false,
        quads: None,
        quad_cover: None,
        quads_whole_pattern: None,
        weights: options.weights.resolved(WallNormals::CellPoints),
        wall_normals: WallNormals::CellPoints,
    }
}

/// The guided projection of a made mesh, with its retries (dropped boundary cells, a second
/// try without fairness, normals per edge), made thinner where wall quads cross at the default
/// thickness.
fn guided(
    base: &PolyMesh,
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &Strategy,
    walls: Walls,
    progress: &mut dyn FnMut(Step),
) -> Result<Solved> {
    let start = Instant::now();
    // Every iteration of every try counts.
    let mut iterations = 0usize;
    let made = optimize_made_mesh(
        base,
        surface,
        &options.optimize,
        options.second_try,
        &mut |attempt: Attempt, info| {
            iterations += 1;
            let name = match (attempt.second_try, attempt.per_edge) {
                (false, false) => "guided projection",
                (true, false) => "second try",
                (false, true) => "guided projection, normals per edge",
                (true, true) => "second try, normals per edge",
            };
            progress(Step::Iteration(name, attempt.solve, info))
        },
    )?;
    let mut s = made.settled;
    let mut notes = Vec::new();
    let before = iterations;
    let made_exact;
    (s.optimized, s.measures, made_exact) = exact(
        s.optimized,
        s.measures,
        walls,
        surface,
        model_surface,
        &options.optimize,
        &mut |info| {
            iterations += 1;
            progress(Step::Iteration("making it exact", 1, info))
        },
    )?;
    if made_exact {
        notes.push(made_exact_note(iterations - before));
    }
    let (h, conn) = (&mut s.optimized.honeycomb, &s.optimized.connectivity);
    let asked = options.optimize.thickness;
    notes.extend(uncross(h, conn, &mut s.measures, model_surface, asked));
    if made.per_edge_fallback {
        notes.push(
            "the solve for one point per cell gave no honeycomb; this is the solve for one \
             normal per wall"
                .into(),
        );
    }
    if made.second_try {
        notes.push(format!(
            "the first try gave no honeycomb; this is the second try, without the fairness that \
             holds opposite walls parallel and with every edge at least {} mean edge lengths",
            crate::optimize::SECOND_TRY_MIN_EDGE
        ));
    }
    if s.dropped_cells > 0 {
        notes.push(format!(
            "{} that the solve broke (collapsed cap, mirrored node or crossed wall, or that \
             their loss cut off) {} dropped; initial.obj is the mesh without them",
            counted(s.dropped_cells, "boundary cell"),
            were(s.dropped_cells)
        ));
    }
    let mut report = Report::new(&s.optimized, &s.measures, start.elapsed().as_secs_f64());
    report.walls = walls;
    report.iterations_total = iterations;
    report.dropped_boundary_cells = Some(s.dropped_cells);
    report.solves = Some(s.solves);
    report.second_try = Some(made.second_try);
    report.per_edge_fallback = Some(made.per_edge_fallback);
    Ok(Solved {
        base: s.base,
        optimized: s.optimized,
        measures: s.measures,
        report,
        notes,
        provisional: false,
    })
}
