//! `honeycomb analyse DIR`: the spherical image of a structure directory's honeycomb.

use crate::progress::Output;
use honeycomb::analysis::spherical_image;
use honeycomb::export::{read_structure, write_json};
use honeycomb::mesh::{write_mesh, PolyMesh};
use honeycomb::{Error, Result};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// A structure directory written by `optimize` or `demo`.
    pub dir: PathBuf,
    /// Areas (steradians) within this of 0 count as zero, and Proposition 1 is checked to it.
    #[arg(long, default_value_t = 1e-3, allow_negative_numbers = true)]
    pub tolerance: f64,
    /// Print the analysis as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    /// Print nothing on stdout.
    #[arg(short, long)]
    pub quiet: bool,
}

/// The area tolerance of `analyse` and `render --spherical`.
pub fn check_tolerance(tolerance: f64) -> Result<()> {
    if !tolerance.is_finite() || tolerance <= 0.0 || tolerance >= 0.5 {
        return Err(Error::Parameter(format!(
            "--tolerance {}: expected a positive area below 0.5 steradians",
            honeycomb::error::rounded(tolerance, 6)
        )));
    }
    Ok(())
}

pub fn run(args: Args) -> Result<()> {
    check_tolerance(args.tolerance)?;
    let output = Output::from_flags(args.quiet, args.json);
    let (h, _) = read_structure(&args.dir)?;
    let image = spherical_image(&h.base.faces, &h.axes, args.tolerance);
    write_json(&args.dir.join("analysis.json"), &image)?;
    // The image itself, to look at: node axes as points of the unit sphere, cells as faces.
    write_mesh(
        &args.dir.join("spherical_image.obj"),
        &PolyMesh::new(h.axes.clone(), h.base.faces.clone()),
    )?;
    match output {
        Output::Json => println!(
            "{}",
            serde_json::to_string_pretty(&image).map_err(|e| Error::Parameter(e.to_string()))?
        ),
        Output::Human => {
            println!(
                "{} cells: {} of zero area ({:.0}%), {} violating Proposition 1 (tolerance {:.0e} sr)",
                image.cells,
                image.zero_area_cells,
                100.0 * image.zero_area_share,
                image.proposition1_violations.len(),
                image.tolerance
            );
            println!("area / (pi/3): cells");
            for (k, n) in &image.histogram {
                println!("{k:>13}: {n}");
            }
            println!(
                "largest distance of an area from a multiple of pi/3: {:.1e} sr",
                image.max_deviation_from_multiple
            );
            match image.curve_likeness {
                Some(c) => println!(
                    "curve-likeness of the cells' images (Property 2; 1 thin, 0 round): {c:.2} \
                     ({} point-like cells left out)",
                    image.point_like_cells
                ),
                None => println!("every cell's image is a point: all node axes of a cell coincide"),
            }
            println!(
                "wrote analysis.json and spherical_image.obj in {}",
                args.dir.display()
            );
        }
        Output::Quiet => {}
    }
    Ok(())
}
