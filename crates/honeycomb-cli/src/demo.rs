//! `honeycomb demo`: the first success of a new user, no input file needed.

use crate::optimize::{optimize_and_write, SolveArgs};
use honeycomb::export::write_json;
use honeycomb::generate::{lifted_hex_patch, Shape};
use honeycomb::limits::check_generated_vertices;
use honeycomb::mesh::write_mesh;
use honeycomb::{BaseMesh, Error, Result, Surface};
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// Output directory.
    #[arg(short, long, default_value = "honeycomb-demo")]
    pub output: PathBuf,
    /// Built-in design surface: saddle, dome, cylinder, cone, wave, ring (a bowl round a hole)
    /// or roof (twice as long as wide).
    #[arg(long, default_value = "saddle")]
    pub shape: Shape,
    /// Approximate number of vertices of the hexagonal base mesh.
    #[arg(long, default_value_t = 1500, allow_negative_numbers = true)]
    pub vertices: usize,
    #[command(flatten)]
    pub opts: SolveArgs,
}

pub fn run(args: Args) -> Result<()> {
    if args.opts.surface.is_some() {
        return Err(Error::Parameter(
            "demo builds its own surface; use `honeycomb optimize BASE --surface S` for a file"
                .into(),
        ));
    }
    check_generated_vertices("--vertices", args.vertices)?;
    args.opts.options()?;
    let (base, surface) = lifted_hex_patch(args.shape, args.vertices);
    let options = args.opts.options_for(&BaseMesh::from_mesh(base.clone())?)?;
    // The inputs too, so the result can be reproduced with `honeycomb optimize`.
    let inputs = |dir: &Path| {
        write_mesh(&dir.join("input_base.obj"), &base)?;
        write_mesh(&dir.join("surface.obj"), &surface)?;
        write_json(
            &dir.join("demo.json"),
            &serde_json::json!({ "shape": format!("{:?}", args.shape).to_lowercase(), "vertices": args.vertices }),
        )
    };
    optimize_and_write(
        &BaseMesh::from_mesh(base.clone())?,
        &Surface::new(surface.clone())?,
        &args.opts,
        &options,
        &args.output,
        &[],
        inputs,
    )
    .map(|_| ())
}
