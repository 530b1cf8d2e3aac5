//! `honeycomb optimize BASE [--surface S] ... -o DIR`

use crate::progress::{IterationBar, Output};
use honeycomb::analysis::{extruded_along_normals, read_directions, shading_report};
use honeycomb::error::{rounded, short_number};
use honeycomb::geometry::{parse_direction, read_axes};
use honeycomb::mesh::{
    check_base_near_surface, nonconvex_faces, read_mesh, validate_base_mesh, validate_surface_mesh,
    OutputDir, PolyMesh, Verdict,
};
use honeycomb::optimize::{
    optimize, shading_axes, unit_light, AxesOptions, OptimizeOptions, Optimized, ParallelOptions,
    QuadOptions, QuadPattern, WallNormals, Weights,
};
use honeycomb::pipeline::{solve_base, Walls};
use honeycomb::report::Report;
use honeycomb::solve::SolverOptions;
use honeycomb::structure::{measure, thickest_uncrossed};
use honeycomb::surface::Surface;
use honeycomb::{Error, Result, Vec3};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    /// Hexagonal (trivalent) base mesh: OBJ, OFF or PLY.
    pub base: PathBuf,
    #[command(flatten)]
    pub opts: SolveArgs,
    /// Output directory.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// Options shared by every command that optimizes.
#[derive(clap::Args, Clone)]
pub struct SolveArgs {
    /// Reference surface S (triangle/quad/polygon mesh); default: the base mesh itself.
    #[arg(long)]
    pub surface: Option<PathBuf>,
    /// Maximum number of guided-projection iterations [default: 10, 20 with --light].
    #[arg(long, allow_negative_numbers = true)]
    pub iterations: Option<usize>,
    /// Distance between M and M' along the node axes, in model units (default 0.3 mean edge lengths).
    #[arg(long, allow_negative_numbers = true)]
    pub thickness: Option<f64>,
    /// Weight of the 120-degree node condition.
    #[arg(long, default_value_t = Weights::default().angle, allow_negative_numbers = true)]
    pub w_angle: f64,
    /// Weight of wall consistency (the wall contains its edge).
    #[arg(long, default_value_t = Weights::default().consistency, allow_negative_numbers = true)]
    pub w_cons: f64,
    /// Weight of the unit-normal condition [default: 0.3 with cell points, 10 with normals per
    /// edge].
    #[arg(long, allow_negative_numbers = true)]
    pub w_norm: Option<f64>,
    /// Weight of closeness to the reference surface.
    #[arg(long, default_value_t = Weights::default().closeness, allow_negative_numbers = true)]
    pub w_close: f64,
    /// Weight of keeping boundary vertices on the surface's boundary.
    #[arg(long, default_value_t = Weights::default().boundary, allow_negative_numbers = true)]
    pub w_boundary: f64,
    /// Weight of opposite-wall fairness in hexagons (fades with the regularization) [default:
    /// 3; pipeline tries 0 next if 3 gives no honeycomb].
    #[arg(long, allow_negative_numbers = true)]
    pub w_fair: Option<f64>,
    /// Solve for one point per cell (the default for a plain honeycomb): each wall normal is
    /// the difference of its two cells' points, so the 120-degree condition holds at inner
    /// nodes by construction; a third less fill than one normal per edge and more accuracy per
    /// iteration. Given explicitly, a variant (--parallel, --quads, --axes, --light) is an
    /// error instead of a switch to normals per edge.
    #[arg(long)]
    pub cell_points: bool,
    /// Solve for one unit normal per edge (the paper's formulation; what the variants use).
    #[arg(long, conflicts_with = "cell_points")]
    pub per_edge_normals: bool,
    /// Keep every edge at least this long (model units), by dummy unknowns [default with
    /// --light: 0.3 mean edge lengths].
    #[arg(long, allow_negative_numbers = true)]
    pub min_edge: Option<f64>,
    /// Parallel meshes (Fig. 9): solve for M' too, its vertices on the node axes and its edges
    /// parallel to those of M (M' starts at --thickness along the surface normals).
    #[arg(long)]
    pub parallel: bool,
    /// With --parallel: a soft constant depth |v_i - v'_i| = C (model units).
    #[arg(long, allow_negative_numbers = true)]
    pub depth: Option<f64>,
    /// Weight of edge parallelity (with --parallel) [default: 1].
    #[arg(long, allow_negative_numbers = true)]
    pub w_parallel: Option<f64>,
    /// Weight of the constant depth (with --depth) [default: 0.1].
    #[arg(long, allow_negative_numbers = true)]
    pub w_depth: Option<f64>,
    /// Prescribed node axes (Fig. 10): a text file with one direction "x y z" per base-mesh
    /// vertex, in vertex order ("0 0 0" leaves a vertex free).
    #[arg(long, conflicts_with = "light")]
    pub axes: Option<PathBuf>,
    /// Weight of the prescribed axes [default: 0.1, 0.03 with --light].
    #[arg(long, allow_negative_numbers = true)]
    pub w_axes: Option<f64>,
    /// Shading (Fig. 18): the direction DX,DY,DZ the light travels in; the node axes are
    /// prescribed across it (the surface normal with its component along the light removed),
    /// and report.json compares the light share through the cells before and after.
    #[arg(long, value_parser = parse_direction, allow_hyphen_values = true)]
    pub light: Option<Vec3>,
    /// With --light: more light directions (e.g. a day's sun path), one "x y z" per line; each
    /// gets its light share before and after in report.json.
    #[arg(long)]
    pub sun_path: Option<PathBuf>,
    /// Cap every hexagon with two planar quads (Figs. 1, 11, 17), written to quads.obj:
    /// `zigzag` splits all cells along one lattice direction, `alternating` splits neighbouring
    /// strips along the other two by turns.
    #[arg(long, value_name = "zigzag|alternating")]
    pub quads: Option<QuadPattern>,
    /// With --quads: the straight polylines follow the lattice direction closest to DX,DY,DZ
    /// [default: the direction whose quads start closest to planar].
    #[arg(long, value_parser = parse_direction, allow_hyphen_values = true)]
    pub quad_direction: Option<Vec3>,
    /// Weight of quad planarity (the paper's w_cons^faces; with --quads) [default: 0.1].
    #[arg(long, allow_negative_numbers = true)]
    pub w_cons_faces: Option<f64>,
    /// Weight of zigzag-polyline fairness (the paper's w_fair^zig; with --quads) [default:
    /// 0.01].
    #[arg(long, allow_negative_numbers = true)]
    pub w_fair_zig: Option<f64>,
    /// Weight of straight-polyline fairness (the paper's w_fair^str; with --quads) [default:
    /// 0.01].
    #[arg(long, allow_negative_numbers = true)]
    pub w_fair_str: Option<f64>,
    /// Guide the node axes towards the surface normals in the first iterations, so that walls
    /// stand across the surface (e.g. 3, with --w-fair 0); fades by 0.3 per iteration.
    #[arg(long, default_value_t = Weights::default().guide, allow_negative_numbers = true)]
    pub w_guide: f64,
    /// How the walls stand on the surface: `across` (node axes as close to its normals as a
    /// honeycomb allows, cells of one size), `uniform` (every axis along its mean normal), a
    /// direction DX,DY,DZ for every axis (vertical walls on a roof: 0,0,1) or `free` (wherever
    /// the guided projection leaves them, the paper's algorithm) [default: across; not with
    /// --parallel, --quads, --axes or --light].
    #[arg(
        long,
        value_name = "across|uniform|DX,DY,DZ|free",
        allow_hyphen_values = true
    )]
    pub walls: Option<String>,
    /// Initial regularization eps (normalized frame); it shrinks as steps succeed.
    #[arg(long, default_value_t = SolverOptions::default().eps, allow_negative_numbers = true)]
    pub eps: f64,
    /// No progress output.
    #[arg(short, long)]
    pub quiet: bool,
    /// Print the report as JSON on stdout instead of a table row.
    #[arg(long)]
    pub json: bool,
}

impl SolveArgs {
    pub fn output(&self) -> Output {
        Output::from_flags(self.quiet, self.json)
    }

    /// The variants solve their own way (the guided projection from the base mesh as given).
    pub fn is_variant(&self) -> bool {
        self.parallel || self.quads.is_some() || self.axes.is_some() || self.light.is_some()
    }

    /// `--walls`, checked: `across` unless given; refused with a variant.
    pub fn walls(&self) -> Result<Walls> {
        let Some(text) = &self.walls else {
            return Ok(Walls::Across);
        };
        if self.is_variant() {
            return Err(Error::Parameter(
                "--walls shapes the plain honeycomb; --parallel, --quads, --axes and --light \
                 solve from the base mesh as given"
                    .into(),
            ));
        }
        text.parse()
            .map_err(|m: String| Error::Parameter(format!("--walls {m}")))
    }

    /// The options that do not depend on the input meshes, checked.
    pub fn options(&self) -> Result<OptimizeOptions> {
        let iterations = self
            .iterations
            .unwrap_or(if self.light.is_some() { 20 } else { 10 });
        if iterations == 0 || iterations > 10_000 {
            return Err(Error::Parameter(format!(
                "--iterations {iterations}: expected 1 to 10000"
            )));
        }
        // Checked here rather than by clap, whose message spans several lines.
        let quads = self.quads.is_some();
        for (given, flag, needs, present) in [
            (self.depth.is_some(), "--depth", "--parallel", self.parallel),
            (
                self.w_parallel.is_some(),
                "--w-parallel",
                "--parallel",
                self.parallel,
            ),
            (
                self.w_depth.is_some(),
                "--w-depth",
                "--depth",
                self.depth.is_some(),
            ),
            (
                self.w_axes.is_some(),
                "--w-axes",
                "--axes or --light",
                self.axes.is_some() || self.light.is_some(),
            ),
            (
                self.w_cons_faces.is_some(),
                "--w-cons-faces",
                "--quads",
                quads,
            ),
            (self.w_fair_zig.is_some(), "--w-fair-zig", "--quads", quads),
            (self.w_fair_str.is_some(), "--w-fair-str", "--quads", quads),
            (
                self.sun_path.is_some(),
                "--sun-path",
                "--light",
                self.light.is_some(),
            ),
            (
                self.quad_direction.is_some(),
                "--quad-direction",
                "--quads",
                self.quads.is_some(),
            ),
        ] {
            if given && !present {
                return Err(Error::Parameter(format!("{flag} needs {needs}")));
            }
        }
        if let Some(light) = self.light {
            unit_light(light).map_err(|_| {
                Error::Parameter(format!(
                    "--light {}: expected a non-zero direction",
                    honeycomb::error::short_vector(light)
                ))
            })?;
        }
        if let Some(t) = self.thickness {
            if !t.is_finite() || t <= 0.0 {
                return Err(Error::Parameter(format!(
                    "--thickness {}: expected a positive length in model units",
                    short_number(t)
                )));
            }
        }
        if let Some(l) = self.min_edge {
            if !l.is_finite() || l <= 0.0 {
                return Err(Error::Parameter(format!(
                    "--min-edge {}: expected a positive length in model units",
                    short_number(l)
                )));
            }
        }
        let variant = self.is_variant();
        self.walls()?;
        if self.cell_points && variant {
            return Err(Error::Parameter(
                "--cell-points: only for the plain honeycomb (not with --parallel, --quads, \
                 --axes or --light)"
                    .into(),
            ));
        }
        // Below 1e-12 the regularization is lost in roundoff against unit weights.
        if !self.eps.is_finite() || !(1e-12..=1e3).contains(&self.eps) {
            return Err(Error::Parameter(format!(
                "--eps {}: expected a number from 1e-12 to 1e3, typically 1e-3",
                short_number(self.eps)
            )));
        }
        let weights = Weights {
            angle: self.w_angle,
            consistency: self.w_cons,
            normalization: self.w_norm,
            closeness: self.w_close,
            boundary: self.w_boundary,
            fairness: self.w_fair.unwrap_or(Weights::default().fairness),
            guide: self.w_guide,
        };
        // Named by flag: the user typed flags, not the library's weight names.
        weights.validate_as([
            "--w-angle",
            "--w-cons",
            "--w-norm",
            "--w-close",
            "--w-boundary",
            "--w-fair",
            "--w-guide",
        ])?;
        let quads = match self.quads {
            Some(pattern) => {
                let defaults = QuadOptions::default();
                let quads = QuadOptions {
                    pattern,
                    direction: self.quad_direction,
                    w_cons_faces: self.w_cons_faces.unwrap_or(defaults.w_cons_faces),
                    w_fair_zigzag: self.w_fair_zig.unwrap_or(defaults.w_fair_zigzag),
                    w_fair_straight: self.w_fair_str.unwrap_or(defaults.w_fair_straight),
                };
                quads.validate().map_err(|e| match e {
                    Error::Parameter(m) => Error::Parameter(format!("--quads: {m}")),
                    e => e,
                })?;
                Some(quads)
            }
            None => None,
        };
        let parallel = self.parallel.then_some(ParallelOptions {
            depth: self.depth,
            weight: self.w_parallel.unwrap_or(ParallelOptions::default().weight),
            depth_weight: self
                .w_depth
                .unwrap_or(ParallelOptions::default().depth_weight),
        });
        if let Some(p) = &parallel {
            p.validate_as(["--depth", "--w-parallel", "--w-depth"])?;
        }
        Ok(OptimizeOptions {
            weights,
            quads,
            solver: SolverOptions {
                max_iterations: iterations,
                eps: self.eps,
                ..SolverOptions::default()
            },
            thickness: self.thickness,
            min_edge: self.min_edge,
            parallel,
            wall_normals: match (self.cell_points, self.per_edge_normals) {
                (true, _) => WallNormals::CellPoints,
                (_, true) => WallNormals::PerEdge,
                _ => WallNormals::Auto,
            },
            ..OptimizeOptions::default()
        })
    }

    /// Completes `options` with what depends on the inputs: prescribed axes (read from --axes or
    /// built from --light on S) and the minimum edge length that shading needs.
    fn add_axes(
        &self,
        options: &mut OptimizeOptions,
        base: &PolyMesh,
        surface: Option<&PolyMesh>,
    ) -> Result<()> {
        let targets = match (&self.axes, self.light) {
            (Some(path), _) => read_axes(path, base.vertices.len())?,
            (None, Some(light)) => {
                let s = Surface::from_mesh(surface.unwrap_or(base))?;
                // Walls tilted far from the normals collapse boundary edges without it.
                options
                    .min_edge
                    .get_or_insert(0.3 * base.mean_edge_length());
                shading_axes(&s, &base.vertices, light)?
            }
            (None, None) => return Ok(()),
        };
        let default = if self.light.is_some() {
            AxesOptions::SHADING_WEIGHT
        } else {
            AxesOptions::DEFAULT_WEIGHT
        };
        let axes = AxesOptions {
            targets,
            weight: self.w_axes.unwrap_or(default),
        };
        axes.validate(base.vertices.len())
            .map_err(|e| match (&self.axes, e) {
                (Some(path), Error::Parameter(m)) => {
                    Error::Parameter(format!("--axes {}: {m}", path.display()))
                }
                (_, e) => e,
            })?;
        options.axes = Some(axes);
        Ok(())
    }
}

/// The flags of the thickness, the minimum edge length and the depth, as the library's
/// checks of them name them ([`OptimizeOptions::validate_as`]).
pub const LENGTH_FLAGS: [&str; 3] = ["--thickness", "--min-edge", "--depth"];

/// Reads a mesh, passing the reader's warnings to stderr.
pub fn load(path: &Path, output: Output) -> Result<PolyMesh> {
    let loaded = read_mesh(path)?;
    if output != Output::Json || !loaded.warnings.is_empty() {
        for w in &loaded.warnings {
            eprintln!("warning: {w}");
        }
    }
    Ok(loaded.mesh)
}

/// What a solve of one base mesh runs with: its options, every one checked (against the mesh
/// too), and the sun path (`--sun-path`, empty without it).
pub struct Prepared {
    options: OptimizeOptions,
    sun_path: Vec<Vec3>,
}

/// The solve of `base` prepared from the arguments: done once, before anything is written.
pub fn solve_options(
    args: &SolveArgs,
    base: &PolyMesh,
    surface: Option<&PolyMesh>,
) -> Result<Prepared> {
    let mut options = args.options()?;
    args.add_axes(&mut options, base, surface)?;
    options.validate_as(base, LENGTH_FLAGS)?;
    let sun_path = match &args.sun_path {
        Some(path) => read_directions(path)?,
        None => Vec::new(),
    };
    Ok(Prepared { options, sun_path })
}

/// Optimizes a designer's base mesh (`optimize`, `demo`), writes the structure directory (with
/// what `inputs` writes into it; it may hold none of `input_files`) and prints the result.
pub fn optimize_and_write(
    base: &PolyMesh,
    surface: Option<&PolyMesh>,
    args: &SolveArgs,
    prepared: Prepared,
    dir: &Path,
    input_files: &[&Path],
    inputs: impl FnOnce(&Path) -> Result<()>,
) -> Result<Report> {
    // Before the solve, so that an unusable -o fails at once, not after a long run.
    let out = OutputDir::begin(dir, input_files)?;
    solve_and_write(base, surface, args, out, prepared, inputs)
}

/// `optimize_and_write` once the options are checked and the output directory begun.
fn solve_and_write(
    base: &PolyMesh,
    surface: Option<&PolyMesh>,
    args: &SolveArgs,
    out: OutputDir,
    prepared: Prepared,
    inputs: impl FnOnce(&Path) -> Result<()>,
) -> Result<Report> {
    let output = args.output();
    let nonconvex = nonconvex_faces(base);
    if !nonconvex.is_empty() {
        eprintln!(
            "warning: {} of {} cells of the base mesh are not convex (first: cell {}); \
             the optimization may fold or collapse them",
            nonconvex.len(),
            base.faces.len(),
            nonconvex[0]
        );
    }
    let Prepared { options, sun_path } = prepared;
    let mut bar = IterationBar::new(output, options.solver.max_iterations);
    let start = Instant::now();
    let model_surface = Surface::from_mesh(surface.unwrap_or(base))?;
    let (optimized, mut report, mut notes) = if args.is_variant() {
        let result = optimize(base, surface, &options, &mut |info| bar.update(info));
        bar.finish();
        let optimized = result?;
        let measures = measure(&optimized.honeycomb, &model_surface);
        let report = Report::new(&optimized, &measures, start.elapsed().as_secs_f64());
        (optimized, report, Vec::new())
    } else {
        let result = solve_base(base, surface, args.walls()?, &options, &mut |step| {
            bar.step(step)
        });
        bar.finish();
        let solved = result?;
        (solved.optimized, solved.report, solved.notes)
    };
    report.seconds = start.elapsed().as_secs_f64();
    if let Some(light) = args.light {
        let before = extruded_along_normals(
            base,
            &optimized.connectivity,
            &model_surface,
            optimized.honeycomb.thickness,
        );
        report.shading = Some(shading_report(
            &before,
            &optimized.honeycomb,
            light,
            &sun_path,
        ));
    }
    notes.extend(out.note(verdict(&report)));
    report.notes = notes.clone();
    let quads: Vec<(&str, &PolyMesh)> = optimized.quads.iter().map(|q| ("quads.obj", q)).collect();
    let dir = out.finish(verdict(&report), |dir| {
        honeycomb::export::write_structure_with(dir, &optimized.honeycomb, &quads, &report)?;
        inputs(dir)
    })?;
    print_notes(&notes, output);
    finish(
        &report,
        &optimized,
        &dir,
        output,
        args.cell_points,
        nonconvex.len(),
    )?;
    Ok(report)
}

/// A honeycomb's outputs take DIR's place; any other go to DIR.failed for inspection.
pub fn verdict(report: &Report) -> Verdict {
    if report.honeycomb {
        Verdict::Passed
    } else {
        Verdict::Failed
    }
}

/// Notes of what a run changed on the way, on stderr (report.json has them too).
pub fn print_notes(notes: &[String], output: Output) {
    if output != Output::Quiet {
        for note in notes {
            eprintln!("note: {note}");
        }
    }
}

/// Prints a written result (its Figure 16 row and how the walls stand, or the JSON report) and
/// fails if it is no honeycomb.
pub fn finish(
    report: &Report,
    optimized: &Optimized,
    dir: &Path,
    output: Output,
    cell_points_asked: bool,
    nonconvex_cells: usize,
) -> Result<()> {
    match output {
        Output::Json => println!(
            "{}",
            serde_json::to_string_pretty(report).map_err(|e| Error::Parameter(e.to_string()))?
        ),
        Output::Human => {
            println!("{}", Report::FIGURE16_HEADER);
            println!("{}", report.figure16_row());
            let m = &report.measures;
            println!(
                "walls {}: axis to normal {:.2} deg mean, {:.2} p95 (parallel axes {:.2}, {:.2}); \
                 edge cv {:.3}; {} iterations in all",
                report.walls.label(),
                m.axis_normal_deg.mean,
                m.axis_normal_deg.p95,
                m.parallel_baseline_deg.mean,
                m.parallel_baseline_deg.p95,
                m.edge_length_cv,
                report.iterations_total
            );
            if !report.converged && !report.honeycomb {
                eprintln!(
                    "note: not converged to tolerance in {} iterations (largest residual {:.1e}); \
                     more --iterations may help",
                    report.iterations,
                    report
                        .residuals
                        .iter()
                        .map(|r| r.max_abs)
                        .fold(0.0, f64::max)
                );
            }
            println!("wrote {}", dir.display());
        }
        Output::Quiet => {}
    }
    if !report.honeycomb {
        return Err(Error::Solver(format!(
            "the result is not a honeycomb after {} iterations: omega_max {:.3} deg, \
             delta_max {:.1e} (tolerance {} deg, {:.0e}); the outputs in {} are for inspection. \
             More --iterations or a larger --eps may help{}{}{}",
            report.iterations,
            report.measures.omega_max_deg,
            report.measures.delta_max,
            Report::OMEGA_TOLERANCE_DEG,
            Report::DELTA_TOLERANCE,
            dir.display(),
            // Chosen, not asked for, and not already followed by a solve per edge (pipeline):
            // the other formulation takes another path.
            if report.wall_normals == WallNormals::CellPoints
                && report.per_edge_fallback.is_none()
                && !cell_points_asked
            {
                ", and so may --per-edge-normals"
            } else {
                ""
            },
            if nonconvex_cells == 0 {
                String::new()
            } else {
                format!("; {nonconvex_cells} cells of the base mesh are not convex")
            },
            match report.measures.nonconvex_walls {
                0 => String::new(),
                n => {
                    let limit = thickest_uncrossed(&optimized.honeycomb);
                    format!(
                        "; {n} wall quads are not convex at thickness {} (the node axes at \
                         their ends lean together or apart across the wall){}",
                        rounded(report.thickness, 4),
                        if limit < report.thickness {
                            format!(
                                ": --thickness below {} uncrosses those leaning together",
                                rounded(limit, 4)
                            )
                        } else {
                            String::new()
                        }
                    )
                }
            }
        )));
    }
    Ok(())
}

pub fn run(args: Args) -> Result<()> {
    // Parameters first: a typo should not wait for a large mesh to load.
    args.opts.options()?;
    let output = args.opts.output();
    let base = load(&args.base, output)?;
    // Validated here too (optimize does it again), so that the message names the file.
    validate_base_mesh(&base).map_err(|e| name_file(&args.base, e))?;
    let surface = match &args.opts.surface {
        Some(path) => {
            let surface = load(path, output)?;
            validate_surface_mesh(&surface).map_err(|e| name_file(path, e))?;
            check_base_near_surface(&base, &surface).map_err(|e| name_file(path, e))?;
            Some(surface)
        }
        None => None,
    };
    let prepared = solve_options(&args.opts, &base, surface.as_ref())?;
    let opts = &args.opts;
    let given = [
        Some(&args.base),
        opts.surface.as_ref(),
        opts.axes.as_ref(),
        opts.sun_path.as_ref(),
    ];
    let input_files: Vec<&Path> = given.into_iter().flatten().map(|p| p.as_path()).collect();
    optimize_and_write(
        &base,
        surface.as_ref(),
        &args.opts,
        prepared,
        &args.output,
        &input_files,
        |_| Ok(()),
    )
    .map(|_| ())
}

/// Prefixes an error about a mesh with the file it is about.
pub fn name_file(path: &Path, e: Error) -> Error {
    match e {
        Error::Mesh(m) => Error::Mesh(format!("{}: {m}", path.display())),
        Error::Unsuited(m) => Error::Unsuited(format!("{}: {m}", path.display())),
        e => e,
    }
}
