//! `honeycomb edit DIR <operation> -o OUT`: edits that keep a honeycomb a honeycomb.

use crate::progress::Output;
use honeycomb::edit::{reciprocal, reciprocal_range, resize_cell, subdivide};
use honeycomb::error::short_number;
use honeycomb::export::{read_honeycomb, write_structure};
use honeycomb::mesh::{write_output_dir, Verdict};
use honeycomb::report::{EditReport, Report};
use honeycomb::structure::measure;
use honeycomb::surface::Surface;
use honeycomb::{Error, Result};
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// A structure directory written by `optimize`, `demo` or `edit`.
    pub dir: PathBuf,
    #[command(subcommand)]
    pub operation: Operation,
    /// Output structure directory (a new one; DIR is left as it is).
    #[arg(short, long, global = true)]
    pub output: Option<PathBuf>,
    /// Print the report as JSON on stdout.
    #[arg(long, global = true)]
    pub json: bool,
    /// Print nothing on stdout.
    #[arg(short, long, global = true)]
    pub quiet: bool,
}

#[derive(clap::Subcommand)]
pub enum Operation {
    /// Move the walls of one cell inwards (paper Fig. 13); the rest stays exactly as it was.
    Resize {
        /// The cell (face index of base.obj, from 0).
        #[arg(long)]
        cell: usize,
        /// Distance in model units; negative grows the cell.
        #[arg(long, allow_negative_numbers = true)]
        by: f64,
    },
    /// Shrink every cell; the space freed along each interior wall becomes a new cell
    /// (paper Fig. 14): same angles, same spherical image, about 4x the cells.
    Subdivide {
        /// Size of the shrunken cells relative to the old ones (0.5: cells of about one size).
        #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
        shrink: f64,
    },
    /// Move walls out and in by turns (paper Fig. 15): every node becomes a triangular cell,
    /// walls end on walls at T-junctions.
    Reciprocal {
        /// Distance in model units (default 0.1 mean edge lengths, or half the largest distance
        /// the structure takes where that is less).
        #[arg(long, allow_negative_numbers = true)]
        by: Option<f64>,
    },
}

pub fn run(args: Args) -> Result<()> {
    let out = args
        .output
        .clone()
        .ok_or_else(|| Error::Parameter("edit needs -o OUT, a new structure directory".into()))?;
    refuse_input_as_output(&args.dir, &out)?;
    let (h, conn, _) = read_honeycomb(&args.dir)?;
    // Closeness is measured to the structure before the edit.
    let before = Surface::from_mesh(&h.base)?;
    let mut t_junctions = 0;
    let (edited, operation) = match args.operation {
        Operation::Resize { cell, by } => (
            resize_cell(&h, &conn, cell, by)?,
            format!("resize cell {cell} by {}", short_number(by)),
        ),
        Operation::Subdivide { shrink } => {
            let (sub, _) = subdivide(&h, &conn, shrink)?;
            let cells = format!("{} cells -> {}", h.base.faces.len(), sub.base.faces.len());
            (
                sub,
                format!("subdivide with shrink {}: {cells}", short_number(shrink)),
            )
        }
        Operation::Reciprocal { by } => {
            // The default stays inside the range even where one edge is much shorter than
            // the rest.
            let by = match by {
                Some(by) => by,
                None => {
                    (0.1 * h.base.mean_edge_length()).min(0.5 * reciprocal_range(&h, &conn)?.limit)
                }
            };
            let r = reciprocal(&h, &conn, by)?;
            t_junctions = r.t_junctions.len();
            let what = format!(
                "reciprocal by {}: {} triangular cells",
                short_number(by),
                r.honeycomb.base.faces.len() - h.base.faces.len()
            );
            (r.honeycomb, what)
        }
    };
    let measures = measure(&edited, &before);
    let report = EditReport::new(&edited, measures, operation, t_junctions);
    // Every check comes before the first file is written: a failed edit leaves no OUT.
    if !report.honeycomb {
        return Err(Error::Parameter(format!(
            "{} gives no honeycomb: {}; nothing written",
            report.operation,
            Report::tolerance_summary(&report.measures, t_junctions > 0)
        )));
    }
    let json =
        serde_json::to_string_pretty(&report).map_err(|e| Error::Parameter(e.to_string()))?;
    write_output_dir(&out, Verdict::Passed, |dir| {
        write_structure(dir, &edited, &report)
    })?;
    match Output::from_flags(args.quiet, args.json) {
        Output::Json => println!("{json}"),
        Output::Human => {
            println!(
                "{}: omega_max {:.2e} deg, delta_max {:.1e}",
                report.operation, report.measures.omega_max_deg, report.measures.delta_max
            );
            println!("wrote {}", out.display());
        }
        Output::Quiet => {}
    }
    Ok(())
}

/// The edit reads DIR while writing OUT and promises to leave DIR as it is: OUT must be another
/// directory (one that does not exist yet is).
fn refuse_input_as_output(dir: &Path, out: &Path) -> Result<()> {
    if let (Ok(a), Ok(b)) = (dir.canonicalize(), out.canonicalize()) {
        if a == b {
            return Err(Error::Parameter(format!(
                "-o {} is the input directory {}: edit writes a new structure directory and \
                 leaves its input as it is",
                out.display(),
                dir.display()
            )));
        }
    }
    Ok(())
}
