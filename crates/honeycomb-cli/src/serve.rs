//! `honeycomb serve`: the interactive editor in the browser (a thin front over honeycomb-serve).

use crate::progress::{Output, Spinner};
use honeycomb::analysis::read_directions;
use honeycomb::error::rounded;
use honeycomb::generate::Shape;
use honeycomb::geometry::parse_direction;
use honeycomb::structure::QuadPattern;
use honeycomb::{Error, Options, Result, Variant, Vec3, Walls};
use honeycomb_serve::{start, ServeOptions, Source};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// A structure directory (from optimize, demo, pipeline or a save) or a design surface
    /// (.obj, .off, .ply; a hex base mesh is made on it first). Without it: the demo dome.
    pub input: Option<PathBuf>,
    /// Port on 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = 8080)]
    pub port: u16,
    /// Listen on all interfaces instead of 127.0.0.1 only (the editor has no login).
    #[arg(long)]
    pub public: bool,
    /// Folder for the page's saves (one structure directory per name).
    #[arg(long, default_value = "honeycomb-saves")]
    pub saves: PathBuf,
    /// Cells of the base mesh made on a design surface.
    #[arg(long, default_value_t = 750)]
    pub cells: usize,
    /// With a design surface: how the walls stand on it, as `pipeline --walls` (across,
    /// uniform, free or a direction DX,DY,DZ) [default: across].
    #[arg(
        long,
        value_name = "across|uniform|DX,DY,DZ|free",
        allow_hyphen_values = true
    )]
    pub walls: Option<String>,
    /// With a design surface: uneven cells of walls across it evened, as `pipeline
    /// --even-cells` (the default with walls across S).
    #[arg(long, conflicts_with = "no_even_cells")]
    pub even_cells: bool,
    /// With a design surface: the cells as the walls across it were fitted, as `pipeline
    /// --no-even-cells`.
    #[arg(long)]
    pub no_even_cells: bool,
    /// With a design surface: cap every hexagon with two planar quads, as `pipeline --quads`;
    /// the page shows their planarity after every edit.
    #[arg(long, value_name = "zigzag|alternating|flattest")]
    pub quads: Option<QuadPattern>,
    /// With --quads: let the cells re-shape up to this edge-length cv for flatter quads, as
    /// `pipeline --quads-reshape`.
    #[arg(
        long,
        value_name = "CV",
        requires = "quads",
        allow_negative_numbers = true
    )]
    pub quads_reshape: Option<f64>,
    /// With --quads: every hexagon split as the pattern says, as `pipeline
    /// --quads-whole-pattern`.
    #[arg(long, requires = "quads")]
    pub quads_whole_pattern: bool,
    /// With a design surface: parallel meshes M, M' on the honeycomb's walls, as `pipeline
    /// --parallel`; the page shows how parallel they stay after every edit.
    #[arg(long)]
    pub parallel: bool,
    /// With a design surface: a shading device against light travelling along DX,DY,DZ, as
    /// `pipeline --light`; the page shows the light share after every edit.
    #[arg(long, value_parser = parse_direction, allow_hyphen_values = true)]
    pub light: Option<Vec3>,
    /// With --light: more light directions (a day's sun path), one "x y z" per line.
    #[arg(long, requires = "light")]
    pub sun_path: Option<PathBuf>,
    /// Built-in surface of the demo (no input): saddle, dome, cylinder, cone, wave, ring or roof.
    #[arg(long, default_value = "dome")]
    pub shape: Shape,
    /// Vertices of the demo's base mesh (no input).
    #[arg(long, default_value_t = 1500)]
    pub vertices: usize,
    /// Distance of M' from M in model units (default 0.3 mean edge lengths).
    #[arg(long, allow_negative_numbers = true)]
    pub thickness: Option<f64>,
    /// Print only errors (and the address on stdout).
    #[arg(short, long)]
    pub quiet: bool,
    /// Print the address as one JSON object on stdout: {"url": ..., "source": ...}.
    #[arg(long, conflicts_with = "quiet")]
    pub json: bool,
}

pub fn run(args: Args) -> Result<()> {
    if !(50..=200_000).contains(&args.vertices) {
        return Err(Error::Parameter(format!(
            "--vertices {}: expected 50 to 200000 (an editor is for live work)",
            args.vertices
        )));
    }
    // Saves come later, on a click: a path they can never go to is refused now.
    if args.saves.exists() && !args.saves.is_dir() {
        return Err(Error::Parameter(format!(
            "--saves {}: exists and is not a directory",
            args.saves.display()
        )));
    }
    let walls = match &args.walls {
        None => Walls::Across,
        Some(text) => text
            .parse()
            .map_err(|m: String| Error::Parameter(format!("--walls {m}")))?,
    };
    let surface_input = args.input.as_ref().is_some_and(|p| p.is_file());
    if let Some(t) = args.thickness {
        honeycomb::error::check_positive_length("thickness", t)?;
        if args.input.as_ref().is_some_and(|p| p.is_dir()) {
            return Err(Error::Parameter(format!(
                "--thickness {}: a structure directory is edited at the thickness it was made \
                 with (its structure.json); --thickness is for a design surface or the demo",
                rounded(t, 6)
            )));
        }
    }
    if args.walls.is_some() && !surface_input {
        return Err(Error::Parameter(
            "--walls shapes the honeycomb made on a design surface: give one (serve SURFACE.obj --walls ...); a structure directory and the demo have their walls"
                .into(),
        ));
    }
    let even_cells = crate::init::even_cells(args.even_cells, args.no_even_cells);
    if let (Some(even), false) = (even_cells, surface_input) {
        let flag = if even {
            "--even-cells"
        } else {
            "--no-even-cells"
        };
        return Err(Error::Parameter(format!(
            "{flag} is about the cells the pipeline makes on a design surface: give one (serve SURFACE.obj {flag}); a structure directory and the demo have their cells"
        )));
    }
    let variant = variant(&args, surface_input)?;
    let options = Options {
        walls,
        variant,
        ..Options::default()
    };
    options.validate()?;
    let source = match &args.input {
        None => Source::Demo {
            shape: args.shape,
            vertices: args.vertices,
        },
        Some(path) if !path.exists() => {
            return Err(Error::Parameter(format!(
                "{}: no such file or directory",
                path.display()
            )))
        }
        Some(path) => Source::from_path(path, args.cells, options).with_even_cells(even_cells),
    };
    let options = ServeOptions {
        host: if args.public {
            [0, 0, 0, 0].into()
        } else {
            [127, 0, 0, 1].into()
        },
        port: args.port,
        save_root: args.saves.clone(),
        thickness: args.thickness,
        ..ServeOptions::default()
    };
    let output = Output::from_flags(args.quiet, args.json);
    // Making the base mesh and the first solve can take seconds on a large surface.
    let spinner = Spinner::new(output, "making the honeycomb to edit");
    let server = start(&source, options);
    spinner.finish();
    let server = match &args.input {
        Some(path) => server.map_err(|e| e.about_file(path))?,
        None => server?,
    };
    crate::optimize::print_notes(&server.notes, output);
    // The address on stdout, alone on its line: scripts and the tests read it from there.
    if output == Output::Json {
        println!(
            "{}",
            serde_json::json!({ "url": server.url(), "source": source.label() })
        );
    } else {
        println!("{}", server.url());
    }
    if output == Output::Human {
        eprintln!(
            "honeycomb editor at {} (saves go to {}); Ctrl-C stops it",
            server.url(),
            args.saves.display()
        );
    }
    server.wait();
    Ok(())
}

/// `bench --serve`: drag-to-update latency through a real WebSocket, at 1.5k and 8k vertices.
pub fn bench(json: bool) -> Result<()> {
    if !json {
        println!(
            "{:>8} {:>6} {:>12} {:>10} {:>10} {:>8} {:>9} {:>9} {:>11}",
            "|V|",
            "drags",
            "first med",
            "first p90",
            "done med",
            "steps",
            "step med",
            "slide med",
            "omega_max"
        );
    }
    for vertices in [1500, 8500] {
        let source = Source::Demo {
            shape: Shape::Dome,
            vertices,
        };
        let l = honeycomb_serve::latency::measure(&source, 30)?;
        if json {
            println!(
                "{}",
                serde_json::to_string(&l).map_err(|e| Error::Parameter(e.to_string()))?
            );
        } else {
            println!(
                "{:>8} {:>6} {:>9.1} ms {:>7.1} ms {:>7.1} ms {:>8.1} {:>6.1} ms {:>6.1} ms {:>11.2e}",
                l.vertices,
                l.drags,
                l.first_update_median_ms,
                l.first_update_p90_ms,
                l.done_median_ms,
                l.steps_per_drag,
                l.step_median_ms,
                l.slide_median_ms,
                l.omega_max_deg
            );
        }
    }
    Ok(())
}

/// The variant asked for the honeycomb made on a design surface (one at a time).
fn variant(args: &Args, surface_input: bool) -> Result<Variant> {
    let given = crate::optimize::one_variant(&[
        (args.quads.is_some(), "--quads"),
        (args.parallel, "--parallel"),
        (args.light.is_some(), "--light"),
    ])?;
    if let (Some(flag), false) = (given, surface_input) {
        return Err(Error::Parameter(format!(
            "{flag} shapes the honeycomb made on a design surface: give one (serve \
             SURFACE.obj {flag} ...); a structure directory and the demo are edited as they are"
        )));
    }
    Ok(if let Some(pattern) = args.quads {
        Variant::Quads {
            pattern,
            quad_direction: None,
            w_cons_faces: None,
            w_fair_zig: None,
            w_fair_str: None,
            quads_reshape: args.quads_reshape,
            quads_whole_pattern: args.quads_whole_pattern,
        }
    } else if args.parallel {
        Variant::Parallel {
            depth: None,
            w_parallel: None,
            w_depth: None,
        }
    } else if let Some(light) = args.light {
        Variant::Shading {
            light,
            sun_path: match &args.sun_path {
                Some(path) => read_directions(path)?,
                None => Vec::new(),
            },
            w_axes: None,
        }
    } else {
        Variant::Plain
    })
}
