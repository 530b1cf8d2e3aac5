//! `honeycomb init SURFACE ... -o BASE.obj` and `honeycomb pipeline SURFACE ... -o DIR`.

use crate::optimize::{finish, load_surface, print_notes, SolveArgs};
use crate::progress::{IterationBar, Output, Spinner};
use honeycomb::export::stage_json;
use honeycomb::init::{
    init, Align, BoundaryMode, CellSize, Flattener, InitOptions, InitReport, Initialized, Method,
};
use honeycomb::limits::check_solve_cells;
use honeycomb::mesh::{write_mesh, OutputDir, Outputs, PolyMesh};
use honeycomb::{pipeline, Error, PipelineOptions, Progress, Result, Step, Surface};
use std::path::{Path, PathBuf};

/// How the hex mesh is made (shared by `init` and `pipeline`).
#[derive(clap::Args, Clone)]
#[command(group(clap::ArgGroup::new("size").required(true).args(["cells", "edge_length"])))]
pub struct InitArgs {
    /// About this many cells over the surface's area.
    #[arg(long, allow_negative_numbers = true)]
    pub cells: Option<usize>,
    /// Cell edge length in model units.
    #[arg(long, allow_negative_numbers = true)]
    pub edge_length: Option<f64>,
    /// `flatten`: a flattening and a regular hex grid (disk-like, gently curved surfaces, holes
    /// allowed). `field`: field-aligned remeshing (any surface, strongly curved ones too; the
    /// hex edges follow a smooth 6-fold direction field; boundary cells trimmed).
    #[arg(long, default_value = "flatten")]
    pub method: Method,
    /// `boundary`: hex edges follow the surface's boundary; `curvature`: one edge direction
    /// follows its principal curvature directions where they agree over most of it (else the
    /// boundary), so that zigzag quads along it are flattest; `none`; or an OBJ file of
    /// polylines (`l` records) the hex edges should follow [default: boundary; pipeline
    /// --quads zigzag or flattest: curvature].
    #[arg(long)]
    pub align: Option<String>,
    /// `trim`: drop cells the boundary cuts; `keep`: close them against the boundary.
    #[arg(long, default_value = "trim")]
    pub boundary: BoundaryMode,
    /// With flatten: `arap` keeps lengths (cells of one size on S), `lscm` keeps angles only,
    /// `project` lays the grid in plan view along the mean normal (all node axes parallel)
    /// [default: arap; pipeline: arap for walls across or free, project for uniform walls].
    #[arg(long)]
    pub flatten: Option<Flattener>,
    /// Shifts the grid by a pseudo-random offset (flatten; where the grid turns round a hole,
    /// turns it about the hole's center instead) or seeds the fields (field); the same seed
    /// gives the same mesh [pipeline with field: the next seed too, where this one's mesh gives
    /// no honeycomb].
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

impl InitArgs {
    /// The checked options (the strokes file read once); the flattening is `--flatten` or ARAP.
    fn options(&self) -> Result<InitOptions> {
        let size = match (self.cells, self.edge_length) {
            (Some(n), _) => CellSize::Cells(n),
            (None, Some(l)) => CellSize::EdgeLength(l),
            (None, None) => unreachable!("clap requires one of --cells and --edge-length"),
        };
        if self.flatten.is_some() && self.method == Method::Field {
            return Err(Error::Parameter(
                "--flatten picks how --method flatten flattens; --method field does not flatten"
                    .into(),
            ));
        }
        let mut options = InitOptions {
            method: self.method,
            boundary: self.boundary,
            flattener: self.flatten.unwrap_or_default(),
            seed: self.seed,
            ..InitOptions::new(size)
        };
        if let Some(align) = &self.align {
            options.align = Align::parse(align)?;
        }
        options.validate()?;
        Ok(options)
    }
}

/// Runs init on `surface` with a spinner.
fn make(surface: &PolyMesh, options: &InitOptions, output: Output) -> Result<Initialized> {
    let spinner = Spinner::new(output, "making the hex mesh");
    let result = init(surface, options);
    spinner.finish();
    result
}

#[derive(clap::Args)]
pub struct Args {
    /// Design surface S: a triangle, quad or polygon mesh (OBJ, OFF, PLY).
    pub surface: PathBuf,
    #[command(flatten)]
    pub init: InitArgs,
    /// The hex base mesh to write (OBJ, OFF or PLY by extension).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the report (cells by sides, edge-length spread, distortion) as JSON here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    #[arg(short, long)]
    pub quiet: bool,
    /// Print the report as JSON on stdout.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: Args) -> Result<()> {
    let output = Output::from_flags(args.quiet, args.json);
    let options = args.init.options()?;
    let surface = load_surface(&args.surface, output)?;
    let made = make(&surface, &options, output).map_err(|e| e.about_file(&args.surface))?;
    // Both or neither: a mesh without the report asked for looks like a finished run.
    let mut outputs = Outputs::new();
    outputs.mesh(&args.output, &made.base)?;
    if let Some(path) = &args.report {
        stage_json(&mut outputs, path, &made.report)?;
    }
    outputs.commit()?;
    print_init_report(&made.report, output, &args.output)
}

fn print_init_report(r: &InitReport, output: Output, written: &Path) -> Result<()> {
    match output {
        Output::Json => println!(
            "{}",
            serde_json::to_string_pretty(r).map_err(|e| Error::Parameter(e.to_string()))?
        ),
        Output::Human => {
            let how = match &r.flat {
                Some(f) => format!(
                    "flattening: angle distortion {:.3} avg, length scale cv {:.3}",
                    f.flattening.conformal_avg, f.flattening.length_scale_cv
                ),
                None => "field-aligned".to_string(),
            };
            println!(
                "{} cells ({} interior, {:.1}% hexagons), {} vertices; edge length {} (cv \
                 {:.3}); {how}; {:.2} s",
                r.cells,
                r.interior_cells,
                100.0 * r.interior_hexagon_share,
                r.vertices,
                honeycomb::error::rounded(r.edge_length_mean, 4),
                r.edge_length_cv,
                r.seconds
            );
            println!("wrote {}", written.display());
        }
        Output::Quiet => {}
    }
    Ok(())
}

#[derive(clap::Args)]
pub struct PipelineArgs {
    /// Design surface S: a triangle, quad or polygon mesh (OBJ, OFF, PLY).
    pub surface: PathBuf,
    #[command(flatten)]
    pub init: InitArgs,
    #[command(flatten)]
    pub opts: SolveArgs,
    /// Where walls across S leave cells of uneven size (edge-length cv 0.12 or more), even them
    /// out afterwards (the default with walls across S): a few steps pulling every edge towards
    /// the mean length while every wall is held where it stands, then the axes fitted and the
    /// vertices placed again. The axes lean a little more; kept only when clean and more even
    /// (a note says what was traded). Refused with other walls or a shading device
    #[arg(long, conflicts_with = "no_even_cells")]
    pub even_cells: bool,
    /// Keep the cells as the walls across S were fitted, uneven or not
    #[arg(long)]
    pub no_even_cells: bool,
    /// Output directory: the structure files, plus initial.obj, init.json and surface.obj.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// `--even-cells` / `--no-even-cells` as the library takes them: `None` when neither is given.
pub fn even_cells(even: bool, no_even: bool) -> Option<bool> {
    (even || no_even).then_some(even)
}

pub fn run_pipeline(args: PipelineArgs) -> Result<()> {
    if args.opts.surface.is_some() {
        return Err(Error::Parameter(
            "pipeline takes the surface as its argument; --surface is for `optimize`".into(),
        ));
    }
    if args.opts.axes.is_some() {
        return Err(Error::Parameter(
            "--axes lists one axis per vertex of a given base mesh, and pipeline makes its own: \
             run `init`, then `optimize --axes`"
                .into(),
        ));
    }
    let init = args.init.options()?;
    let options = PipelineOptions {
        init,
        init_chosen: args.init.flatten.is_some() || args.init.method == Method::Field,
        align_chosen: args.init.align.is_some(),
        even_cells: even_cells(args.even_cells, args.no_even_cells),
        options: args.opts.options()?,
    };
    let output = args.opts.output();
    let surface = load_surface(&args.surface, output)?;
    // The pipeline checks it too; here it is refused before -o's parents are made.
    check_solve_cells(&options.init, &surface).map_err(|e| e.about_file(&args.surface))?;
    let surface = Surface::new(surface).map_err(|e| e.about_file(&args.surface))?;
    let strokes = Path::new(args.init.align.as_deref().unwrap_or(""));
    let mut inputs = vec![args.surface.as_path()];
    if strokes.is_file() {
        inputs.push(strokes);
    }
    let out = OutputDir::begin(&args.output, &inputs)?;
    let mut bar = IterationBar::new(output, options.options.max_iterations());
    let spinner = std::cell::RefCell::new(None::<Spinner>);
    let result = pipeline(
        &surface,
        &options,
        &mut Progress::new(|step| match step {
            Step::Init => *spinner.borrow_mut() = Some(Spinner::new(output, "making the hex mesh")),
            step => {
                if let Some(s) = spinner.borrow_mut().take() {
                    s.finish();
                }
                bar.step(step)
            }
        }),
    );
    if let Some(s) = spinner.borrow_mut().take() {
        s.finish();
    }
    bar.finish();
    let mut outcome = result.map_err(|e| e.about_file(&args.surface))?;
    outcome.report.notes.extend(out.note(outcome.placement()));
    let dir = &out.finish(outcome.placement(), |dir| {
        write_mesh(&dir.join("surface.obj"), surface.source_mesh())?;
        outcome.write(dir)
    })?;
    if output == Output::Human {
        if let Some(init) = &outcome.initialized {
            print_init_report(init, output, &dir.join("initial.obj"))?;
        }
    }
    print_notes(&outcome.report.notes, output);
    finish(&outcome, dir, output, args.opts.cell_points, 0)
}
