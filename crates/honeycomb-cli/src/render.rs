//! `honeycomb render DIR -o FILE.svg`: a picture of a structure directory's honeycomb.

use honeycomb::analysis::spherical_image;
use honeycomb::export::read_structure;
use honeycomb::mesh::{read_mesh, write_atomically};
use honeycomb::render::{
    check_width, quads_scene, shading_scene, spherical_scene, walls_scene, Coloring, DesignLight,
    View, WallMeasure,
};
use honeycomb::structure::measure as measure_structure;
use honeycomb::surface::Surface;
use honeycomb::{Error, Result, Vec3};
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// A structure directory written by `optimize`, `demo` or `edit`.
    pub dir: PathBuf,
    /// Output picture: .svg, or .png (no text labels in PNG).
    #[arg(short, long)]
    pub output: PathBuf,
    /// What the wall colours show: omega (the worst node angle at either end, degrees), delta
    /// (the wall's planarity), closeness (distance of its ends from S, in mean edge lengths;
    /// needs --surface or DIR/surface.obj), axis (the larger angle of its two node axes to S's
    /// normal, degrees; needs S too), area (|spherical area| of its cells, sr) or length (its
    /// edge over the mean edge length: how even the cells are).
    #[arg(long, default_value = "delta")]
    pub color: String,
    /// Viewing direction: auto (along the shape's direction of least bending, from 30 degrees
    /// above), top, front, side or iso.
    #[arg(long, default_value = "auto")]
    pub view: View,
    /// The design surface S, for --color closeness and axis (default: DIR/surface.obj when present).
    #[arg(long)]
    pub surface: Option<PathBuf>,
    /// Draw the spherical image instead (node axes on the unit sphere, cells by area).
    #[arg(long, conflicts_with = "quads")]
    pub spherical: bool,
    /// Draw the quads that cap the honeycomb instead (DIR/quads.obj, written with --quads),
    /// each by its planarity delta_face, red above 0.01.
    #[arg(long, conflicts_with = "color")]
    pub quads: bool,
    /// Draw a shading device's cells instead (made with --light), each by the light it lets
    /// through against the same cell along S's normals (DIR/report.json's light and depth;
    /// needs S too), red above the 0.5 asked.
    #[arg(long, conflicts_with_all = ["color", "quads", "spherical"])]
    pub shading: bool,
    /// With --spherical: areas within this of 0 (steradians) count as zero.
    #[arg(long, default_value_t = 1e-3)]
    pub tolerance: f64,
    /// Picture width in pixels.
    #[arg(long, default_value_t = 1200)]
    pub width: u32,
    /// Print nothing on stdout.
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(args: Args) -> Result<()> {
    let ext = args
        .output
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if ext != "svg" && ext != "png" {
        return Err(Error::Parameter(format!(
            "-o {}: the picture must be .svg or .png",
            args.output.display()
        )));
    }
    check_width(args.width)?;
    let measure: WallMeasure = args.color.parse().map_err(Error::Parameter)?;
    let (h, conn) = read_structure(&args.dir)?;
    let name = args.dir.file_name().map_or_else(
        || args.dir.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let (scene, what) = if args.shading {
        let light = design_light(&args.dir)?;
        let surface = Surface::from_mesh(&read_mesh(&surface_path(&args, "--shading")?)?.mesh)?;
        let camera = args.view.camera(&h.base.vertices);
        let title = format!("{name}: light let through");
        shading_scene(&h, &conn, &surface, light, title, camera, args.width)
    } else if args.quads {
        let path = args.dir.join("quads.obj");
        if let Ok(false) = path.try_exists() {
            return Err(Error::Parameter(format!(
                "--quads draws the quads that cap the honeycomb, and {} does not exist: make \
                 the honeycomb with --quads zigzag, alternating or flattest",
                path.display()
            )));
        }
        let cover = read_mesh(&path)?.mesh;
        let camera = args.view.camera(&h.base.vertices);
        quads_scene(&cover, format!("{name}: quads"), camera, args.width)
    } else if args.spherical {
        crate::analyse::check_tolerance(args.tolerance)?;
        let image = spherical_image(&h.base.faces, &h.axes, args.tolerance);
        let what = format!(
            "{} cells: {} of zero area, {} violating Proposition 1",
            image.cells,
            image.zero_area_cells,
            image.proposition1_violations.len()
        );
        let title = format!("{name}: spherical image");
        (
            spherical_scene(&h.base.faces, &h.axes, &image, args.width, &title),
            what,
        )
    } else {
        // Closeness and axis are measured against S; the others need only M.
        let surface = if measure.needs_surface() {
            let path = surface_path(&args, &format!("--color {}", args.color))?;
            Surface::from_mesh(&read_mesh(&path)?.mesh)?
        } else {
            Surface::from_mesh(&h.base)?
        };
        let m = measure_structure(&h, &surface);
        let per_wall = measure.per_wall(&h, &m, &conn, args.tolerance);
        let coloring = Coloring {
            title: format!("{name}: {}", measure.name()),
            measure: measure.name(),
            meaning: measure.meaning(),
            unit: measure.unit(),
            items: "walls",
            values: &per_wall,
            tolerance: measure.tolerance(),
        };
        let camera = args.view.camera(&h.base.vertices);
        (
            walls_scene(&h, &coloring, camera, args.width),
            coloring.verdict(),
        )
    };
    let bytes = if ext == "png" {
        scene.to_png()?
    } else {
        scene.to_svg().into_bytes()
    };
    write_atomically(&args.output, |w| w.write_all(&bytes))?;
    if !args.quiet {
        println!(
            "wrote {} ({} x {} px): {what}",
            args.output.display(),
            scene.width,
            scene.height
        );
    }
    Ok(())
}

/// The design surface's file (`--surface`, else DIR/surface.obj), which `what` needs.
fn surface_path(args: &Args, what: &str) -> Result<PathBuf> {
    let path = args
        .surface
        .clone()
        .unwrap_or_else(|| args.dir.join("surface.obj"));
    // Only an absent file is "does not exist": a FIFO, a device or a directory is refused by
    // the reader, without being opened.
    if let Ok(false) = path.try_exists() {
        return Err(Error::Parameter(format!(
            "{what} needs the design surface: {} does not exist (give --surface S)",
            path.display()
        )));
    }
    Ok(path)
}

/// The light a shading device in `dir` was made for, from its report.json.
fn design_light(dir: &Path) -> Result<DesignLight> {
    let path = dir.join("report.json");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| Error::Parameter(format!("--shading reads {}: {e}", path.display())))?;
    let report: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| Error::Parameter(format!("{}: not JSON: {e}", path.display())))?;
    let shading = &report["shading"];
    let direction: Option<Vec<f64>> = shading["light"]["direction"]
        .as_array()
        .and_then(|d| d.iter().map(|c| c.as_f64()).collect());
    match (direction.as_deref(), shading["depth"].as_f64()) {
        (Some(&[x, y, z]), Some(depth)) if depth > 0.0 && depth.is_finite() => Ok(DesignLight {
            direction: Vec3::new(x, y, z),
            depth,
        }),
        _ => Err(Error::Parameter(format!(
            "--shading draws a shading device, and {} has no light and depth (its \"shading\"): \
             make the honeycomb with --light DX,DY,DZ",
            path.display()
        ))),
    }
}
