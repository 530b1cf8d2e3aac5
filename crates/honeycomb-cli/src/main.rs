//! `honeycomb`: the command-line front of the honeycomb library.

mod analyse;
mod bench;
mod bench_roofs;
mod bench_variants;
mod demo;
mod edit;
mod export;
mod init;
mod optimize;
mod progress;
mod render;
mod serve;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "honeycomb",
    version,
    about = "Freeform honeycomb structures: hexagonal support structures whose walls meet at 120 degrees"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Make a hexagonal base mesh on a design surface.
    Init(init::Args),
    /// Init then optimize: from a design surface to a structure directory in one command.
    Pipeline(init::PipelineArgs),
    /// Optimize a hexagonal base mesh into a honeycomb and write a structure directory.
    Optimize(optimize::Args),
    /// Build a hex mesh on a built-in surface, optimize it and write a structure directory.
    Demo(demo::Args),
    /// Edit a structure directory by wall translations (resize a cell).
    Edit(edit::Args),
    /// Files for fabrication and exchange: glTF, OBJ, flat wall panels (DXF, SVG), CSV tables.
    Export(export::Args),
    /// Draw a structure directory's honeycomb as an SVG picture, colour-coded.
    Render(render::Args),
    /// Spherical image of a structure directory: cell areas, Proposition 1 check.
    Analyse(analyse::Args),
    /// The interactive editor in the browser: drag vertices and node axes, watch it re-solve.
    Serve(serve::Args),
    /// Time the optimizer on generated hex meshes of growing size (Figure 16 columns).
    Bench(bench::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Init(args) => init::run(args),
        Command::Pipeline(args) => init::run_pipeline(args),
        Command::Optimize(args) => optimize::run(args),
        Command::Demo(args) => demo::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Analyse(args) => analyse::run(args),
        Command::Edit(args) => edit::run(args),
        Command::Export(args) => export::run(args),
        Command::Render(args) => render::run(args),
        Command::Serve(args) => serve::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", named_by_flag(e));
            ExitCode::FAILURE
        }
    }
}

/// The library names an option by its field (`w_fair`); a user typed its flag (`--w-fair`).
fn named_by_flag(e: honeycomb::Error) -> honeycomb::Error {
    match e {
        honeycomb::Error::Option {
            field,
            value,
            expected,
        } => {
            let flag = match (field, value.as_str()) {
                ("wall_normals", "cell_points") => "--cell-points".to_string(),
                _ => format!("--{}", field.replace('_', "-")),
            };
            honeycomb::Error::Parameter(format!("{flag} {value}: {expected}"))
        }
        e => e,
    }
}
