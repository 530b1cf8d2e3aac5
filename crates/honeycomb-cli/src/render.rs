//! `honeycomb render DIR -o FILE.svg`: a picture of a structure directory's honeycomb.

use honeycomb::analysis::spherical_image;
use honeycomb::export::read_structure;
use honeycomb::mesh::{read_mesh, write_atomically, Connectivity};
use honeycomb::render::{check_width, spherical_scene, walls_scene, Coloring, Scene, View};
use honeycomb::structure::measure;
use honeycomb::surface::Surface;
use honeycomb::{Error, Result};
use std::path::PathBuf;

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
    /// normal, degrees; needs S too) or area (|spherical area| of its cells, sr).
    #[arg(long, default_value = "delta")]
    pub color: String,
    /// Viewing direction: top, front, side or iso.
    #[arg(long, default_value = "iso")]
    pub view: View,
    /// The design surface S, for --color closeness and axis (default: DIR/surface.obj when present).
    #[arg(long)]
    pub surface: Option<PathBuf>,
    /// Draw the spherical image instead (node axes on the unit sphere, cells by area).
    #[arg(long)]
    pub spherical: bool,
    /// With --spherical: areas within this of 0 (steradians) count as zero.
    #[arg(long, default_value_t = 1e-3)]
    pub tolerance: f64,
    /// Picture width in pixels.
    #[arg(long, default_value_t = 1200)]
    pub width: u32,
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
    let save = |scene: Scene| -> Result<()> {
        let bytes = if ext == "png" {
            scene.to_png()
        } else {
            scene.to_svg().into_bytes()
        };
        write_atomically(&args.output, |w| w.write_all(&bytes))
    };
    check_width(args.width)?;
    let (h, _) = read_structure(&args.dir)?;
    if args.spherical {
        crate::analyse::check_tolerance(args.tolerance)?;
        let image = spherical_image(&h.base.faces, &h.axes, args.tolerance);
        return save(spherical_scene(&h.base.faces, &h.axes, &image, args.width));
    }
    let m = measure(&h, &Surface::from_mesh(&h.base)?);
    let (label, per_wall): (&str, Vec<f64>) = match args.color.as_str() {
        "delta" => ("delta (wall planarity)", m.delta_per_wall.clone()),
        "omega" => (
            "omega (deg)",
            h.edges
                .iter()
                .map(|&[a, b]| m.omega_per_node[a].max(m.omega_per_node[b]))
                .collect(),
        ),
        "closeness" | "axis" => {
            let path = args
                .surface
                .clone()
                .unwrap_or_else(|| args.dir.join("surface.obj"));
            // Only an absent file is "does not exist": a FIFO, a device or a directory is
            // refused by the reader, without being opened.
            if let Ok(false) = path.try_exists() {
                return Err(Error::Parameter(format!(
                    "--color {} needs the design surface: {} does not exist (give --surface S)",
                    args.color,
                    path.display()
                )));
            }
            let surface = Surface::from_mesh(&read_mesh(&path)?.mesh)?;
            let on_surface = measure(&h, &surface);
            let (label, per_node) = if args.color == "axis" {
                ("axis to normal (deg)", on_surface.axis_normal_per_node)
            } else {
                let unit = on_surface.mean_edge_length;
                let d = surface.closest_points(&h.base.vertices);
                (
                    "closeness (edge lengths)",
                    d.iter().map(|c| c.distance / unit).collect(),
                )
            };
            (
                label,
                h.edges
                    .iter()
                    .map(|&[a, b]| per_node[a].max(per_node[b]))
                    .collect(),
            )
        }
        "area" => {
            let image = spherical_image(&h.base.faces, &h.axes, args.tolerance);
            let conn = Connectivity::build(&h.base)?;
            (
                "area (spherical, sr)",
                conn.edge_faces
                    .iter()
                    .map(|fs| {
                        fs.iter()
                            .flatten()
                            .map(|&f| image.per_cell[f].area.abs())
                            .fold(0.0, f64::max)
                    })
                    .collect(),
            )
        }
        other => {
            return Err(Error::Parameter(format!(
                "--color {other}: expected omega, delta, closeness, axis or area"
            )))
        }
    };
    save(walls_scene(
        &h,
        &Coloring {
            label,
            per_wall: &per_wall,
            linear: args.color == "axis",
        },
        args.view,
        args.width,
    ))
}
