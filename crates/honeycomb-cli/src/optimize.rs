//! `honeycomb optimize BASE [--surface S] ... -o DIR`

use crate::progress::{IterationBar, Output};
use honeycomb::analysis::read_directions;
use honeycomb::error::rounded;
use honeycomb::geometry::{parse_direction, read_axes};
use honeycomb::mesh::{
    check_base_near_surface, nonconvex_faces, read_base, read_surface, LoadedMesh, OutputDir,
    PolyMesh,
};
use honeycomb::report::Report;
use honeycomb::structure::QuadPattern;
use honeycomb::{
    BaseMesh, Error, Options, Outcome, Progress, Result, Surface, Variant, Vec3, WallNormals, Walls,
};
use std::path::{Path, PathBuf};

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
    /// Maximum number of guided-projection iterations (with --quads: of the honeycomb, then of the capping) [default: 10, 20 with --light or --quads, 60 with --quads-reshape].
    #[arg(long, allow_negative_numbers = true)]
    pub iterations: Option<usize>,
    /// Distance between M and M' along the node axes, in model units (default 0.3 mean edge lengths).
    #[arg(long, allow_negative_numbers = true)]
    pub thickness: Option<f64>,
    /// Weight of the 120-degree node condition.
    #[arg(long, default_value_t = Options::default().w_angle, allow_negative_numbers = true)]
    pub w_angle: f64,
    /// Weight of wall consistency (the wall contains its edge).
    #[arg(long, default_value_t = Options::default().w_cons, allow_negative_numbers = true)]
    pub w_cons: f64,
    /// Weight of the unit-normal condition [default: 0.3 with cell points, 10 with normals per
    /// edge].
    #[arg(long, allow_negative_numbers = true)]
    pub w_norm: Option<f64>,
    /// Weight of closeness to the reference surface.
    #[arg(long, default_value_t = Options::default().w_close, allow_negative_numbers = true)]
    pub w_close: f64,
    /// Weight of keeping boundary vertices on the surface's boundary.
    #[arg(long, default_value_t = Options::default().w_boundary, allow_negative_numbers = true)]
    pub w_boundary: f64,
    /// Weight of opposite-wall fairness in hexagons (fades with the regularization) [default:
    /// 3; pipeline tries 0 next if 3 gives no honeycomb].
    #[arg(long, allow_negative_numbers = true)]
    pub w_fair: Option<f64>,
    /// Solve for one point per cell (the default for a plain honeycomb): each wall normal is
    /// the difference of its two cells' points, so the 120-degree condition holds at inner
    /// nodes by construction; a third less fill than one normal per edge and more accuracy per
    /// iteration. Given explicitly, a variant (--parallel, --axes, --light) is an error
    /// instead of a switch to normals per edge (--quads caps a plain honeycomb).
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
    /// strips along the other two by turns, `flattest` splits each cell along whichever
    /// diagonal leaves its quads flattest. The honeycomb (walls as --walls says) is made
    /// first; then its walls are kept and its vertices move, off the surface where the quads
    /// need it (report.json's `capping` says how far).
    #[arg(long, value_name = "zigzag|alternating|flattest")]
    pub quads: Option<QuadPattern>,
    /// With --quads: the straight polylines follow the lattice direction closest to DX,DY,DZ
    /// [default: the direction whose quads start closest to planar].
    #[arg(long, value_parser = parse_direction, allow_hyphen_values = true)]
    pub quad_direction: Option<Vec3>,
    /// Weight of quad planarity (the paper's w_cons^faces; with --quads), against closeness to the surface at 0.3 [default: 1].
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
    /// With --quads: let the cells re-shape, up to this edge-length cv (e.g. 0.3), for flatter
    /// quads. Where the quads miss 0.01 with each vertex kept in its place along the surface,
    /// the vertices slide along it within their walls too, and the slid capping is kept if it
    /// is flatter; report.json's `capping` states the trade [default: the cells keep their
    /// shape].
    #[arg(long, value_name = "CV", allow_negative_numbers = true)]
    pub quads_reshape: Option<f64>,
    /// With --quads zigzag or alternating: split every hexagon as the pattern says. By default,
    /// where the pattern's quads stay short of the floors (worst 0.01, mean 0.004), the cells
    /// whose quads stay least planar take their own flattest diagonal instead, the pattern's
    /// polylines broken there; report.json's `capping` counts them (`cells_off_pattern`).
    #[arg(long)]
    pub quads_whole_pattern: bool,
    /// Guide the node axes towards the surface normals in the first iterations, so that walls
    /// stand across the surface (e.g. 3, with --w-fair 0); fades by 0.3 per iteration.
    #[arg(long, default_value_t = Options::default().w_guide, allow_negative_numbers = true)]
    pub w_guide: f64,
    /// How the walls stand on the surface: `across` (node axes as close to its normals as a
    /// honeycomb allows, cells of one size), `uniform` (every axis along its mean normal), a
    /// direction DX,DY,DZ for every axis (vertical walls on a roof: 0,0,1) or `free` (wherever
    /// the guided projection leaves them, the paper's algorithm) [default: across; not with
    /// --parallel, --axes or --light].
    #[arg(
        long,
        value_name = "across|uniform|DX,DY,DZ|free",
        allow_hyphen_values = true
    )]
    pub walls: Option<String>,
    /// Initial regularization eps (normalized frame); it shrinks as steps succeed.
    #[arg(long, default_value_t = Options::default().eps, allow_negative_numbers = true)]
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

    /// The variants that solve their own way (the guided projection from the base mesh as
    /// given); quads cap the plain honeycomb instead.
    pub fn is_variant(&self) -> bool {
        self.parallel || self.axes.is_some() || self.light.is_some()
    }

    /// `--walls`, checked: `across` unless given; with --parallel across or free only;
    /// refused with the other variants.
    pub fn walls(&self) -> Result<Walls> {
        let Some(text) = &self.walls else {
            return Ok(Walls::Across);
        };
        let walls: Walls = text
            .parse()
            .map_err(|m: String| Error::Parameter(format!("--walls {m}")))?;
        let paired = self.parallel && matches!(walls, Walls::Across | Walls::Free);
        let shading = self.light.is_some() && walls == Walls::Across;
        if self.is_variant() && !paired && !shading {
            return Err(Error::Parameter(
                "--walls shapes the plain honeycomb (and the one --quads caps); --parallel \
                 stands on walls across S (pipeline) or free ones, --light on walls across S \
                 turned across the light, and --axes solves from the base mesh as given"
                    .into(),
            ));
        }
        Ok(walls)
    }

    /// The library's options from the flags, checked; `--axes` is read by [`Self::options_for`]
    /// once the base mesh is known.
    pub fn options(&self) -> Result<Options> {
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
                self.quads_reshape.is_some(),
                "--quads-reshape",
                "--quads",
                quads,
            ),
            (
                self.quads_whole_pattern,
                "--quads-whole-pattern",
                "--quads",
                quads,
            ),
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
                quads,
            ),
        ] {
            if given && !present {
                return Err(Error::Parameter(format!("{flag} needs {needs}")));
            }
        }
        if self.cell_points && self.is_variant() {
            return Err(Error::Parameter(
                "--cell-points: only for the plain honeycomb and the one --quads caps (not \
                 with --parallel, --axes or --light)"
                    .into(),
            ));
        }
        one_variant(&[
            (self.parallel, "--parallel"),
            (self.quads.is_some(), "--quads"),
            (self.axes.is_some(), "--axes"),
            (self.light.is_some(), "--light"),
        ])?;
        let variant = if self.parallel {
            Variant::Parallel {
                depth: self.depth,
                w_parallel: self.w_parallel,
                w_depth: self.w_depth,
            }
        } else if let Some(pattern) = self.quads {
            Variant::Quads {
                pattern,
                quad_direction: self.quad_direction,
                w_cons_faces: self.w_cons_faces,
                w_fair_zig: self.w_fair_zig,
                w_fair_str: self.w_fair_str,
                quads_reshape: self.quads_reshape,
                quads_whole_pattern: self.quads_whole_pattern,
            }
        } else if let Some(light) = self.light {
            Variant::Shading {
                light,
                sun_path: match &self.sun_path {
                    Some(path) => read_directions(path)?,
                    None => Vec::new(),
                },
                w_axes: self.w_axes,
            }
        } else if self.axes.is_some() {
            Variant::Axes {
                axes: Vec::new(),
                w_axes: self.w_axes,
            }
        } else {
            Variant::Plain
        };
        let options = Options {
            walls: self.walls()?,
            variant,
            iterations: self.iterations,
            eps: self.eps,
            thickness: self.thickness,
            min_edge: self.min_edge,
            w_angle: self.w_angle,
            w_cons: self.w_cons,
            w_norm: self.w_norm,
            w_close: self.w_close,
            w_boundary: self.w_boundary,
            w_fair: self.w_fair,
            w_guide: self.w_guide,
            wall_normals: match (self.cell_points, self.per_edge_normals) {
                (true, _) => WallNormals::CellPoints,
                (_, true) => WallNormals::PerEdge,
                _ => WallNormals::Auto,
            },
            ..Options::default()
        };
        options.validate()?;
        Ok(options)
    }

    /// [`Self::options`] with the axes of `--axes` read for `base`.
    pub fn options_for(&self, base: &BaseMesh) -> Result<Options> {
        let mut options = self.options()?;
        if let (Some(path), Variant::Axes { axes, .. }) = (&self.axes, &mut options.variant) {
            *axes = read_axes(path, base.vertices().len())?;
            options.validate().map_err(|e| match e {
                Error::Option {
                    value, expected, ..
                } => Error::Parameter(format!("--axes {}: {value}: {expected}", path.display())),
                e => e,
            })?;
        }
        Ok(options)
    }
}

/// The one variant flag given of `flags` (each with whether it was given), if any; more than
/// one is an error naming them.
pub fn one_variant<'a>(flags: &[(bool, &'a str)]) -> Result<Option<&'a str>> {
    let given: Vec<&str> = (flags.iter())
        .filter_map(|&(given, flag)| given.then_some(flag))
        .collect();
    if given.len() > 1 {
        return Err(Error::Parameter(format!(
            "{}: one variant at a time",
            given.join(" and ")
        )));
    }
    Ok(given.first().copied())
}

/// Reads a base mesh (vertices at one position joined), passing the reader's warnings to
/// stderr.
pub fn load_base(path: &Path, output: Output) -> Result<PolyMesh> {
    warned(read_base(path)?, output)
}

/// Reads a design surface (repaired), passing the reader's warnings to stderr.
pub fn load_surface(path: &Path, output: Output) -> Result<PolyMesh> {
    warned(read_surface(path)?, output)
}

fn warned(loaded: LoadedMesh, output: Output) -> Result<PolyMesh> {
    if output != Output::Json || !loaded.warnings.is_empty() {
        for w in &loaded.warnings {
            eprintln!("warning: {w}");
        }
    }
    Ok(loaded.mesh)
}

/// Optimizes a designer's base mesh (`optimize`, `demo`), writes the structure directory (with
/// what `inputs` writes into it; it may hold none of `input_files`) and prints the result.
pub fn optimize_and_write(
    base: &BaseMesh,
    surface: &Surface,
    args: &SolveArgs,
    options: &Options,
    dir: &Path,
    input_files: &[&Path],
    inputs: impl FnOnce(&Path) -> Result<()>,
) -> Result<Report> {
    // Before the solve, so that an unusable -o fails at once, not after a long run.
    let out = OutputDir::begin(dir, input_files)?;
    let output = args.output();
    let nonconvex = nonconvex_faces(base.mesh());
    if !nonconvex.is_empty() {
        eprintln!(
            "warning: {} of {} cells of the base mesh are not convex (first: cell {}); \
             the optimization may fold or collapse them",
            nonconvex.len(),
            base.cells().len(),
            nonconvex[0]
        );
    }
    let mut bar = IterationBar::new(output, options.max_iterations());
    let result = honeycomb::optimize(
        base,
        surface,
        options,
        &mut Progress::new(|step| bar.step(step)),
    );
    bar.finish();
    let mut outcome = result?;
    outcome.report.notes.extend(out.note(outcome.placement()));
    let dir = out.finish(outcome.placement(), |dir| {
        outcome.write(dir)?;
        inputs(dir)
    })?;
    print_notes(&outcome.report.notes, output);
    finish(&outcome, &dir, output, args.cell_points, nonconvex.len())?;
    Ok(outcome.report)
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
    outcome: &Outcome,
    dir: &Path,
    output: Output,
    cell_points_asked: bool,
    nonconvex_cells: usize,
) -> Result<()> {
    let report = &outcome.report;
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
    if let (Some(s), Output::Human) = (&report.shading, output) {
        println!(
            "light share {} -> {} (the same cells along S's normals -> these walls, {} deep){}",
            rounded(s.light.before, 3),
            rounded(s.light.after, 3),
            rounded(s.depth, 4),
            s.sun_path_mean.as_ref().map_or(String::new(), |m| format!(
                "; over the sun path {} -> {}",
                rounded(m.before, 3),
                rounded(m.after, 3)
            ))
        );
    }
    let Some(why) = &outcome.verdict.why else {
        return match &outcome.verdict.unmet {
            Some(unmet) => Err(Error::Solver(format!(
                "the shading falls short: {unmet}; the outputs in {} are for inspection",
                dir.display()
            ))),
            None => Ok(()),
        };
    };
    // A shading device that no try made a honeycomb of: the light and the share of the
    // closest, then why it is none.
    let device = report.shading.as_ref().map_or(String::new(), |s| {
        format!(
            "no try made a shading device for light {}: the best try lets through {} of the \
             direct light, against {} for the same cells along S's normals, and ",
            honeycomb::error::short_vector(honeycomb::Vec3::from_slice(&s.light.direction)),
            rounded(s.light.after, 3),
            rounded(s.light.before, 3)
        )
    });
    // Chosen, not asked for, and not already followed by a solve per edge (pipeline): the
    // other formulation takes another path.
    let per_edge = if report.wall_normals == WallNormals::CellPoints
        && report.per_edge_fallback.is_none()
        && !cell_points_asked
    {
        ", and so may --per-edge-normals"
    } else {
        ""
    };
    // A pipeline's guided projection that ran its second try (hundreds of iterations, without
    // the fairness) has had what more iterations would give.
    let advice = match report.second_try {
        Some(true) => String::new(),
        _ => format!(". More --iterations or a larger --eps may help{per_edge}"),
    };
    Err(Error::Solver(format!(
        "{device}the result is {why}; the outputs in {} are for inspection{advice}{}{}",
        dir.display(),
        if nonconvex_cells == 0 {
            String::new()
        } else {
            format!("; {nonconvex_cells} cells of the base mesh are not convex")
        },
        match outcome.verdict.uncrossed_below {
            Some(limit) => format!(
                "; --thickness below {} uncrosses the wall quads whose axes lean together",
                rounded(limit, 4)
            ),
            None => String::new(),
        }
    )))
}

pub fn run(args: Args) -> Result<()> {
    // Parameters first: a typo should not wait for a large mesh to load.
    args.opts.options()?;
    let output = args.opts.output();
    let base = BaseMesh::from_mesh(load_base(&args.base, output)?)
        .map_err(|e| e.about_file(&args.base))?;
    let surface = match &args.opts.surface {
        Some(path) => {
            let surface =
                Surface::new(load_surface(path, output)?).map_err(|e| e.about_file(path))?;
            // A bounding-box check (optimize makes it too): here the message can name the file.
            check_base_near_surface(base.mesh(), surface.source_mesh())
                .map_err(|e| e.about_file(path))?;
            surface
        }
        None => Surface::of_base(&base)?,
    };
    let options = args.opts.options_for(&base)?;
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
        &surface,
        &args.opts,
        &options,
        &args.output,
        &input_files,
        |_| Ok(()),
    )
    .map(|_| ())
}
