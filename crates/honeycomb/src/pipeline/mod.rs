//! From a design surface to a honeycomb: which base mesh, which solve, which retries. The one
//! strategy that `honeycomb pipeline` and the editor's surface source share.
//!
//! - [`Walls::Across`] (the default): a flattening that keeps lengths (ARAP) gives cells of one
//!   size on S; the node axes are fitted to S's normals as a folded sheet and the vertices
//!   placed on its walls (`reciprocal`), boundary cells the placement breaks dropped. A surface
//!   that no flattening covers with cells of one size is refused at once, with its curvature.
//!   Where the result is no honeycomb, the guided projection of the same mesh is kept instead.
//! - [`Walls::Uniform`]: S seen along its mean normal, a regular grid laid in plan view and
//!   lifted: a honeycomb with parallel node axes (vertical walls on a roof) from the start.
//! - [`Walls::Direction`]: the same seen along a given direction.

use crate::error::{short_vector, Error, Result};
use crate::geometry::Vec3;
use crate::init::{init, CellSize, Flattener, InitOptions, Initialized, Method};
use crate::mesh::{validate_surface_mesh, PolyMesh};
use crate::optimize::{
    optimize, optimize_made_mesh, Attempt, AxesOptions, Frame, OptimizeOptions, Optimized,
    WallNormals,
};
use crate::reciprocal::{walls_across, Across, AcrossOptions, Stage};
use crate::report::Report;
use crate::solve::IterationInfo;
use crate::structure::{measure, Measures};
use crate::surface::Surface;
use serde::{Serialize, Serializer};
use std::str::FromStr;

/// How the walls stand on S.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Walls {
    /// Node axes as close to S's normals as a honeycomb allows, cells of one size.
    Across,
    /// Every node axis along S's mean normal.
    Uniform,
    /// Every node axis along this direction (unit).
    Direction(Vec3),
}

impl Default for Walls {
    fn default() -> Walls {
        Walls::Across
    }
}

impl FromStr for Walls {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Walls, String> {
        match s {
            "across" => return Ok(Walls::Across),
            "uniform" => return Ok(Walls::Uniform),
            _ => {}
        }
        let numbers: Vec<f64> = s
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|w| !w.is_empty())
            .map(str::parse)
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| format!("`{s}`: expected across, uniform or a direction DX,DY,DZ"))?;
        match numbers[..] {
            [x, y, z] if numbers.iter().all(|v| v.is_finite()) => {
                let d = Vec3::new(x, y, z);
                let n = d.norm();
                if n < 1e-12 || !n.is_finite() {
                    return Err(format!("`{s}`: the direction has no length"));
                }
                Ok(Walls::Direction(d / n))
            }
            _ => Err(format!(
                "`{s}`: expected across, uniform or three finite numbers DX,DY,DZ"
            )),
        }
    }
}

/// `"across"`, `"uniform"`, or the direction as `[x, y, z]`.
impl Serialize for Walls {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Walls::Across => s.serialize_str("across"),
            Walls::Uniform => s.serialize_str("uniform"),
            Walls::Direction(d) => d.to_array().serialize(s),
        }
    }
}

/// Everything the pipeline runs with.
#[derive(Clone, Debug)]
pub struct PipelineOptions {
    /// The base mesh; its method and flattening are the pipeline's to choose unless
    /// `init_chosen`.
    pub init: InitOptions,
    pub init_chosen: bool,
    pub walls: Walls,
    /// The guided projection's options (uniform walls, and the fallback of `across`).
    pub optimize: OptimizeOptions,
    /// A second try without the opposite-wall fairness is allowed (the fairness was not the
    /// caller's choice).
    pub second_try: bool,
    pub across: AcrossOptions,
}

impl PipelineOptions {
    /// The defaults for about `cells` cells.
    pub fn new(cells: usize) -> PipelineOptions {
        PipelineOptions {
            init: InitOptions::new(CellSize::Cells(cells)),
            init_chosen: false,
            walls: Walls::Across,
            optimize: OptimizeOptions::default(),
            second_try: true,
            across: AcrossOptions::default(),
        }
    }
}

/// What the pipeline made.
pub struct Pipelined {
    /// The hexagonal mesh `init` made (its report, which `init.json` holds).
    pub initialized: Initialized,
    /// The mesh the kept result started from: `initialized.base` without dropped cells.
    pub base: PolyMesh,
    pub optimized: Optimized,
    pub measures: Measures,
    /// `report.json` (without its timing, which the caller knows).
    pub report: Report,
    /// What the pipeline changed on the way, one sentence each, for the front to show.
    pub notes: Vec<String>,
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

/// A honeycomb of walls across S kept without the guided projection's second opinion: every
/// vertex this close to S (mean edge lengths), no wall quad crossed.
const ACROSS_CLOSENESS: f64 = 0.05;

/// Runs the pipeline on `surface`.
pub fn pipeline(
    surface: &PolyMesh,
    options: &PipelineOptions,
    progress: &mut dyn FnMut(Step),
) -> Result<Pipelined> {
    validate_surface_mesh(surface)?;
    let model_surface = Surface::from_mesh(surface)?;
    let mut notes = Vec::new();
    // Variants solve the plan-view mesh by the guided projection, as uniform walls do.
    let across = options.walls == Walls::Across && !options.optimize.is_variant();
    let initialized = match options.walls {
        Walls::Across if across => {
            progress(Step::Init);
            let init_options = InitOptions {
                flattener: if options.init_chosen {
                    options.init.flattener
                } else {
                    Flattener::Arap
                },
                ..options.init.clone()
            };
            let made = init(surface, &init_options)?;
            check_cell_sizes(&made, &model_surface)?;
            made
        }
        _ => plan_view(surface, options, &mut notes, progress)?,
    };
    options.optimize.validate(&initialized.base)?;
    if across {
        let start = std::time::Instant::now();
        let across = across_or_none(
            &initialized.base,
            surface,
            &model_surface,
            &options.optimize,
            &options.across,
            progress,
        )?;
        match across {
            Ok(solved) => return Ok(solved.made_from(initialized, notes)),
            Err((why, iterations)) => {
                notes.push(why);
                let mut solved = guided(&initialized, surface, options, progress)?;
                solved.report.iterations_total += iterations;
                solved.report.seconds = start.elapsed().as_secs_f64();
                return Ok(solved.made_from(initialized, notes));
            }
        }
    }
    let solved = guided(&initialized, surface, options, progress)?;
    Ok(solved.made_from(initialized, notes))
}

/// A honeycomb on a base mesh, with its report.
pub struct Solved {
    /// The mesh the result started from (the base mesh without dropped cells).
    pub base: PolyMesh,
    pub optimized: Optimized,
    pub measures: Measures,
    pub report: Report,
}

impl Solved {
    fn made_from(self, initialized: Initialized, notes: Vec<String>) -> Pipelined {
        Pipelined {
            initialized,
            base: self.base,
            optimized: self.optimized,
            measures: self.measures,
            report: self.report,
            notes,
        }
    }
}

/// Solves a given base mesh on `surface` (`None`: the base mesh itself) with its walls as
/// asked: across S by the fitted sheet (the guided projection where that gives no honeycomb,
/// which a note says), or uniform or along a direction by the guided projection with those
/// axes prescribed. `optimize` and `demo` solve this way; variants (parallel meshes, quads,
/// prescribed axes) go to [`crate::optimize::optimize`] directly.
pub fn solve_base(
    base: &PolyMesh,
    surface: Option<&PolyMesh>,
    walls: Walls,
    options: &OptimizeOptions,
    progress: &mut dyn FnMut(Step),
) -> Result<(Solved, Vec<String>)> {
    let surface_mesh = surface.unwrap_or(base);
    let model_surface = Surface::from_mesh(surface_mesh)?;
    let start = std::time::Instant::now();
    let mut notes = Vec::new();
    let mut spent = 0;
    if walls == Walls::Across {
        // A designer's cells are the design: none are dropped.
        let across_options = AcrossOptions {
            max_drops: 0,
            ..AcrossOptions::default()
        };
        match across_or_none(
            base,
            surface_mesh,
            &model_surface,
            options,
            &across_options,
            progress,
        )? {
            Ok(solved) => return Ok((solved, notes)),
            Err((why, iterations)) => {
                notes.push(why);
                spent = iterations;
            }
        }
    }
    let mut prescribed = options.clone();
    let direction = match walls {
        Walls::Uniform => Some(model_surface.mean_normal()),
        Walls::Direction(d) => Some(d),
        Walls::Across => None,
    };
    if let Some(d) = direction {
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
    let measures = measure(&optimized.honeycomb, &model_surface);
    let mut report = Report::new(&optimized, &measures, start.elapsed().as_secs_f64());
    report.walls = walls;
    report.iterations_total = spent + iterations;
    Ok((
        Solved {
            base: base.clone(),
            optimized,
            measures,
            report,
        },
        notes,
    ))
}

/// Walls across S on `base`: the solved honeycomb, or why it is none and the iterations spent.
#[allow(clippy::type_complexity)]
fn across_or_none(
    base: &PolyMesh,
    surface: &PolyMesh,
    model_surface: &Surface,
    options: &OptimizeOptions,
    across_options: &AcrossOptions,
    progress: &mut dyn FnMut(Step),
) -> Result<std::result::Result<Solved, (String, usize)>> {
    let start = std::time::Instant::now();
    let across_options = AcrossOptions {
        thickness: options.thickness,
        ..across_options.clone()
    };
    let mut spent = 0;
    let across = walls_across(
        base,
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
    let across = match across {
        Ok(across) => across,
        // A sheet whose triangles the fit left degenerate gives no lines to place vertices on.
        Err(Error::Solver(m)) => {
            return Ok(Err((
                format!(
                    "the node axes fitted to S's normals gave no honeycomb here ({m}); this is \
                     the guided projection of the same mesh"
                ),
                spent,
            )))
        }
        Err(e) => return Err(e),
    };
    let m = &across.measures;
    if Report::within_tolerances(m) && m.nonconvex_walls == 0 && m.closeness_max <= ACROSS_CLOSENESS
    {
        return Ok(Ok(across_solved(
            across,
            options,
            start.elapsed().as_secs_f64(),
        )));
    }
    Ok(Err((
        format!(
            "the node axes fitted to S's normals gave no honeycomb here (omega_max {} deg, {} \
             crossed walls, closeness {}); this is the guided projection of the same mesh",
            crate::error::rounded(m.omega_max_deg, 3),
            m.nonconvex_walls,
            crate::error::rounded(m.closeness_max, 3)
        ),
        across.solve.iterations,
    )))
}

/// The plan-view base mesh of uniform walls: S seen along its mean normal or the direction
/// given. Uniform walls on a surface that folds over seen along its mean normal take the ARAP
/// grid instead (a note says so); a direction given is kept, or refused.
fn plan_view(
    surface: &PolyMesh,
    options: &PipelineOptions,
    notes: &mut Vec<String>,
    progress: &mut dyn FnMut(Step),
) -> Result<Initialized> {
    let view = match options.walls {
        Walls::Direction(d) => Some(d),
        _ => None,
    };
    if options.init_chosen
        && (options.init.method == Method::Field || options.init.flattener != Flattener::Project)
    {
        if view.is_some() {
            return Err(Error::Parameter(
                "--walls DX,DY,DZ lays the grid in plan view along the direction: it takes no \
                 --method or --flatten"
                    .into(),
            ));
        }
        progress(Step::Init);
        return init(surface, &options.init);
    }
    let projected = InitOptions {
        flattener: Flattener::Project,
        method: Method::Flatten,
        view,
        ..options.init.clone()
    };
    progress(Step::Init);
    match init(surface, &projected) {
        Ok(made) => Ok(made),
        Err(e) if view.is_none() => {
            notes.push(format!(
                "--flatten project: {e}; this is the ARAP grid, whose axes are not parallel"
            ));
            progress(Step::Init);
            init(
                surface,
                &InitOptions {
                    flattener: Flattener::Arap,
                    ..options.init.clone()
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

/// A surface whose hex mesh has cells of very different sizes is refused, with how much it
/// curves at the scale of a cell.
fn check_cell_sizes(made: &Initialized, surface: &Surface) -> Result<()> {
    let r = &made.report;
    if r.edge_length_cv <= MAX_BASE_EDGE_CV {
        return Ok(());
    }
    let units = surface.curvature_units(2.0 * r.edge_length_mean);
    Err(Error::Mesh(format!(
        "too curved for a honeycomb of cells of one size: at the scale of a cell (edge {:.4}) S \
         curves by {:.0} units of 60 degrees like a dome and {:.0} like a saddle, and a \
         hexagonal lattice of even spacing absorbs one unit only with a pentagon or a heptagon; \
         flattened, its cells differ in edge length by a cv of {:.2} (a honeycomb wants at \
         most 0.12). Split S into nearly developable pieces (a roof, a vault), or use --method \
         field for a mesh with pentagons and heptagons and --walls uniform",
        r.edge_length_mean, units.positive, units.negative, r.edge_length_cv
    )))
}

/// Walls across S as a solved honeycomb with its report.
pub fn across_solved(across: Across, options: &OptimizeOptions, seconds: f64) -> Solved {
    let frame = Frame::of(&across.base);
    let h = across.honeycomb;
    let normals = (0..h.edges.len()).map(|e| h.wall_normal(e)).collect();
    let optimized = Optimized {
        honeycomb: h,
        connectivity: across.connectivity,
        normals,
        solve: across.solve,
        frame,
        prescribed_axes: None,
        parallel: false,
        quads: None,
        quad_cover: None,
        weights: options.weights.resolved(WallNormals::CellPoints),
        wall_normals: WallNormals::CellPoints,
    };
    let mut report = Report::new(&optimized, &across.measures, seconds);
    report.walls = Walls::Across;
    report.iterations_total = optimized.solve.iterations;
    report.dropped_boundary_cells = Some(across.dropped_cells);
    report.axis_field_iterations = Some(across.field_iterations);
    Solved {
        base: across.base,
        optimized,
        measures: across.measures,
        report,
    }
}

/// The guided projection of the made mesh, with its retries (dropped boundary cells, a second
/// try without fairness, normals per edge).
fn guided(
    initialized: &Initialized,
    surface: &PolyMesh,
    options: &PipelineOptions,
    progress: &mut dyn FnMut(Step),
) -> Result<Solved> {
    let start = std::time::Instant::now();
    // Every iteration of every try counts.
    let mut iterations = 0usize;
    let made = optimize_made_mesh(
        &initialized.base,
        surface,
        &options.optimize,
        options.second_try,
        &mut |attempt: Attempt, info| {
            iterations += 1;
            let name = if attempt.second_try {
                "second try"
            } else {
                "guided projection"
            };
            progress(Step::Iteration(name, attempt.solve, info))
        },
    )?;
    let s = made.settled;
    let mut report = Report::new(&s.optimized, &s.measures, start.elapsed().as_secs_f64());
    report.walls = options.walls;
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
    })
}
