//! `honeycomb bench`: the optimizer on generated hex meshes of growing size, in the columns of
//! the paper's Figure 16 plus time per iteration, the share of numeric factorization and the
//! process's peak memory.

use honeycomb::generate::{lifted_hex_patch, Shape};
use honeycomb::limits::{check_generated_vertices, MAX_VERTEX_ITERATIONS};
use honeycomb::report::Report;
use honeycomb::{
    optimize, BaseMesh, Error, Options, Progress, Result, Surface, WallNormals, Walls,
};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    /// Approximate vertex counts, comma separated (run in this order; keep them ascending so
    /// that the process's peak memory is the peak of each size).
    #[arg(
        long,
        value_delimiter = ',',
        default_values_t = [1500, 8500, 35000, 140000],
        allow_negative_numbers = true
    )]
    pub sizes: Vec<usize>,
    /// Iterations per run (all are done: the convergence test is off).
    #[arg(long, default_value_t = 5, allow_negative_numbers = true)]
    pub iterations: usize,
    /// Built-in surface: saddle, dome, cylinder, cone, wave, ring or roof.
    #[arg(long, default_value = "dome")]
    pub shape: Shape,
    /// Print one JSON object per size instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Wall normals as differences of cell points (the default: the node condition exact, a
    /// smaller factor; normalization weight 0.3).
    #[arg(long)]
    pub cell_points: bool,
    /// One unknown normal per edge (the paper's formulation) instead of cell points.
    #[arg(long, conflicts_with = "cell_points")]
    pub per_edge: bool,
    /// Instead of the sizes: one row per variant of the paper's section 4 (parallel meshes,
    /// quads, shading, prescribed axes, minimum edge length) on its test subject. With
    /// --roofs: one row per surface and variant of the pipeline (quads zigzag, alternating and
    /// flattest, flattest with --quads-reshape 0.3, parallel meshes, two suns): iterations,
    /// seconds, omega, delta, delta_face before and after capping, beta or the light share,
    /// closeness, edge cv.
    #[arg(long)]
    pub variants: bool,
    /// Instead of the sizes: `init` (flatten with ARAP, and field) on a 40k-triangle roof, for 2000 and
    /// 100000 cells.
    #[arg(long, conflicts_with = "variants")]
    pub init: bool,
    /// Instead of the sizes: the editor's latency (`honeycomb serve`), from an axis drag sent
    /// over a WebSocket to the updated geometry received, on 1.5k- and 8.5k-vertex domes.
    #[arg(long, conflicts_with_all = ["variants", "init"])]
    pub serve: bool,
    /// Instead of the sizes: the whole `pipeline` on every design surface (OBJ, OFF, PLY) in
    /// DIR (default ../shared/data, skipped with a reason when absent), one row each: cells,
    /// seconds, iterations, omega_max, delta_max, the axes' angle to S's normals (mean, p95)
    /// against parallel axes', edge-length cv.
    #[arg(long, value_name = "DIR", num_args = 0..=1, conflicts_with_all = ["init", "serve"])]
    pub roofs: Option<Option<PathBuf>>,
    /// With --roofs: cells asked for, comma separated.
    #[arg(long, value_delimiter = ',', default_values_t = [1500], requires = "roofs")]
    pub cells: Vec<usize>,
    /// With --roofs: the built-in cylinder, cone, dome, saddle, wave, ring and a cooling tower
    /// too.
    #[arg(long, requires = "roofs")]
    pub generated: bool,
    /// With --roofs: how the walls stand (as `pipeline --walls`).
    #[arg(
        long,
        default_value = "across",
        requires = "roofs",
        allow_hyphen_values = true
    )]
    pub walls: String,
    /// With --roofs: uneven cells evened, as `pipeline --even-cells` (the default with walls
    /// across S).
    #[arg(long, requires = "roofs", conflicts_with = "no_even_cells")]
    pub even_cells: bool,
    /// With --roofs: the cells as the walls across S were fitted (as `pipeline
    /// --no-even-cells`).
    #[arg(long, requires = "roofs")]
    pub no_even_cells: bool,
    /// With --roofs --variants: twelve suns (30, 45 and 60 degrees high from azimuths 0, 90,
    /// 180 and 270) instead of two, and a line per surface counting those that met half the
    /// light
    #[arg(long, requires_all = ["roofs", "variants"])]
    pub suns: bool,
}

pub fn run(args: Args) -> Result<()> {
    if args.variants && args.roofs.is_none() {
        return crate::bench_variants::run(args.json);
    }
    if args.init {
        return run_init(args.json);
    }
    if args.serve {
        return crate::serve::bench(args.json);
    }
    if let Some(dir) = args.roofs {
        let walls = args
            .walls
            .parse()
            .map_err(|m: String| Error::Parameter(format!("--walls {m}")))?;
        return crate::bench_roofs::run(crate::bench_roofs::RoofsArgs {
            dir,
            cells: args.cells,
            generated: args.generated,
            walls,
            even_cells: crate::init::even_cells(args.even_cells, args.no_even_cells),
            variants: args.variants,
            suns: args.suns,
            json: args.json,
        });
    }
    if args.iterations == 0 || args.iterations > 1000 {
        return Err(Error::Parameter(format!(
            "--iterations {}: expected 1 to 1000",
            args.iterations
        )));
    }
    for &size in &args.sizes {
        check_generated_vertices("--sizes", size)?;
    }
    let largest = args.sizes.iter().copied().max().unwrap_or(0);
    if largest * args.iterations > MAX_VERTEX_ITERATIONS {
        return Err(Error::Parameter(format!(
            "--iterations {} with --sizes {largest}: expected at most {} iterations at that size",
            args.iterations,
            MAX_VERTEX_ITERATIONS / largest
        )));
    }
    if !args.json {
        println!(
            "{}  {:>8} {:>8} {:>8} {:>8} {:>8} {:>7}",
            Report::FIGURE16_HEADER,
            "ms/it",
            "factor%",
            "symb(s)",
            "nnz(L)M",
            "peakMiB",
            "threads"
        );
    }
    for &size in &args.sizes {
        let (base, surface) = lifted_hex_patch(args.shape, size);
        let (base, surface) = (BaseMesh::from_mesh(base)?, Surface::new(surface)?);
        let options = Options {
            // The guided projection alone, as the paper's Figure 16 times it.
            walls: Walls::Free,
            wall_normals: if args.per_edge {
                WallNormals::PerEdge
            } else {
                WallNormals::CellPoints
            },
            ..all_iterations(args.iterations)
        };
        let start = Instant::now();
        let outcome = optimize(&base, &surface, &options, &mut Progress::silent())?;
        let seconds = start.elapsed().as_secs_f64();
        let report = &outcome.report;
        let s = report;
        let iter_seconds = s.seconds_assembly + s.seconds_factorization + s.seconds_other;
        let per_iteration_ms = 1e3 * iter_seconds / s.iterations.max(1) as f64;
        let factor_share = 100.0 * s.seconds_factorization / iter_seconds.max(1e-12);
        let peak_mib = peak_memory_kib().map_or(f64::NAN, |k| k as f64 / 1024.0);
        if args.json {
            println!(
                "{}",
                serde_json::json!({
                    "vertices": report.vertices, "edges": report.edges,
                    "iterations": report.iterations, "omega_max_deg": report.measures.omega_max_deg,
                    "omega_avg_deg": report.measures.omega_avg_deg, "delta_max": report.measures.delta_max,
                    "delta_avg": report.measures.delta_avg, "closeness_max": report.measures.closeness_max,
                    "seconds": seconds, "ms_per_iteration": per_iteration_ms,
                    "factorization_share": factor_share / 100.0,
                    "seconds_symbolic": s.seconds_symbolic, "factor_nnz": s.factor_nnz,
                    "factor_threads": s.factor_threads,
                    "factorizations": s.factorizations, "peak_mib": peak_mib,
                })
            );
        } else {
            println!(
                "{}  {:>8.1} {:>7.0}% {:>8.3} {:>8.2} {:>8.0} {:>7}",
                report.figure16_row(),
                per_iteration_ms,
                factor_share,
                s.seconds_symbolic,
                s.factor_nnz as f64 / 1e6,
                peak_mib,
                s.factor_threads
            );
        }
    }
    Ok(())
}

/// Options that run every iteration (the convergence test off), so rows compare.
pub fn all_iterations(iterations: usize) -> Options {
    Options {
        iterations: Some(iterations),
        tolerance: 0.0,
        ..Options::default()
    }
}

/// `init` on a roof triangulated into about 40k triangles (the yardstick: Instant Meshes
/// makes 2000 cells from such a surface in about 0.85 s).
fn run_init(json: bool) -> Result<()> {
    use honeycomb::generate::HeightField;
    use honeycomb::init::{init, CellSize, InitOptions, Method};
    let surface = HeightField {
        shape: Shape::Roof,
        d: 50.0,
    }
    .triangulate(141);
    if !json {
        println!(
            "{:>8} {:>10} {:>8} {:>8} {:>8} {:>10} {:>8} {:>8}",
            "method", "triangles", "cells", "vertices", "hex%", "edge cv", "T (s)", "peakMiB"
        );
    }
    // Peak memory is the process's so far: each row's own peak only where it exceeds the
    // rows before it.
    let runs = [Method::Flatten, Method::Field]
        .into_iter()
        .flat_map(|m| [2000, 100_000].map(|cells| (m, cells)));
    for (method, cells) in runs {
        let options = InitOptions {
            method,
            ..InitOptions::new(CellSize::Cells(cells))
        };
        let start = Instant::now();
        let made = init(&surface, &options)?;
        let seconds = start.elapsed().as_secs_f64();
        let r = &made.report;
        let peak_mib = peak_memory_kib().map_or(f64::NAN, |k| k as f64 / 1024.0);
        if json {
            println!(
                "{}",
                serde_json::json!({
                    "method": method, "triangles": surface.faces.len(), "cells_asked": cells,
                    "cells": r.cells,
                    "vertices": r.vertices, "interior_hexagon_share": r.interior_hexagon_share,
                    "edge_length_cv": r.edge_length_cv, "seconds": seconds, "peak_mib": peak_mib,
                })
            );
        } else {
            println!(
                "{:>8} {:>10} {:>8} {:>8} {:>7.1}% {:>10.4} {:>8.3} {:>8.0}",
                format!("{method:?}").to_lowercase(),
                surface.faces.len(),
                r.cells,
                r.vertices,
                100.0 * r.interior_hexagon_share,
                r.edge_length_cv,
                seconds,
                peak_mib
            );
        }
    }
    Ok(())
}

/// The process's peak resident memory (Linux `VmHWM`), in KiB.
fn peak_memory_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}
