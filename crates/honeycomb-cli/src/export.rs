//! `honeycomb export DIR --format ... -o OUT`: the files a fabricator cuts from and that
//! Rhino, Blender and three.js open.

use crate::progress::Output;
use honeycomb::export::{export, parse_sheet, ExportOptions, Format, Model, Units, Up};
use honeycomb::{Error, Result};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// A structure directory written by `pipeline`, `optimize`, `demo` or `edit`.
    pub dir: PathBuf,
    /// What to write: glb (structure.glb), obj (structure.obj + .mtl), dxf (panels.dxf), svg
    /// (panels.svg), csv (walls.csv, nodes.csv, bom.csv), all, or several joined by commas.
    #[arg(long, default_value = "all")]
    pub format: String,
    /// The length one model unit stands for: mm, cm, m, in or ft (glTF is written in metres;
    /// DXF states it; the bill counts wall lengths that differ by 1 mm).
    #[arg(long, default_value = "m")]
    pub units: String,
    /// Up axis of structure.obj and nodes.csv: z (as the model is) or y (turned for tools that
    /// assume Y up). structure.glb is always Y up, as glTF requires.
    #[arg(long, default_value = "z")]
    pub up: String,
    /// Plate thickness (model units): each panel's ends are cut for the 120-degree node, and
    /// panels lie 2 x T apart on the sheets.
    #[arg(long, allow_negative_numbers = true)]
    pub material_thickness: Option<f64>,
    /// Sheet size WxH (model units; default 2.5 m x 1.25 m).
    #[arg(long)]
    pub sheet: Option<String>,
    /// Height of the labels on the panels (model units; default a fifth of the median wall
    /// height).
    #[arg(long, allow_negative_numbers = true)]
    pub label_height: Option<f64>,
    /// The design surface S, for the walls' angle to the cladding (default: DIR/surface.obj
    /// when present, else M itself).
    #[arg(long)]
    pub surface: Option<PathBuf>,
    /// Output folder (replaced whole).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Print what was written as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    /// Print nothing on stdout.
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(args: Args) -> Result<()> {
    // Every option is checked before the structure is read.
    let options = ExportOptions {
        formats: Format::parse_list(&args.format)?,
        units: Units::parse(&args.units)?,
        up: Up::parse(&args.up)?,
        material_thickness: args.material_thickness,
        sheet: args.sheet.as_deref().map(parse_sheet).transpose()?,
        label_height: args.label_height,
    };
    let model = Model::read(&args.dir, args.surface.as_deref(), options.units)?;
    let structure = args.dir.join("structure.json");
    let mut inputs = vec![structure.as_path()];
    if let Some(s) = &args.surface {
        inputs.push(s);
    }
    let exported = export(&model, &options, &args.output, &inputs)?;
    match Output::from_flags(args.quiet, args.json) {
        Output::Json => println!(
            "{}",
            serde_json::to_string_pretty(&exported).map_err(|e| Error::Parameter(e.to_string()))?
        ),
        Output::Human => {
            let b = &exported.bom;
            println!(
                "{} walls, {} nodes (one node type), {} cells; wall area {:.4} {u}^2, edge length {:.4} {u}, {} distinct wall lengths at 1 mm",
                b.walls, b.nodes, b.cells, b.total_wall_area, b.total_edge_length, b.distinct_wall_lengths,
                u = b.units
            );
            if exported.sheets > 0 {
                println!(
                    "{} panels on {} sheets of {} x {} {}",
                    b.walls, exported.sheets, exported.sheet[0], exported.sheet[1], b.units
                );
            }
            if let (Some(s), Some(bevel)) = (exported.end_setback, exported.end_bevel_deg) {
                println!(
                    "end cuts: faces set back {s:.4} {} from the node axis (square), or bevelled {bevel} deg from square to the axis",
                    b.units
                );
            }
            println!(
                "wrote {} to {}",
                exported.files.join(", "),
                exported.dir.display()
            );
        }
        Output::Quiet => {}
    }
    Ok(())
}
