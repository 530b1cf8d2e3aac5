//! `honeycomb bench --roofs [DIR]`: the whole pipeline on every design surface in a folder (and
//! on the built-in ones with `--generated`), one row each: how long, how many iterations, how
//! exact, and how the walls stand on S against parallel axes. With `--variants`, one row per
//! surface and variant instead: what the variant asks (quad planarity, edge parallelity) and
//! what it cost (closeness to S, iterations); with `--suns`, twelve suns in place of two.

use honeycomb::analysis::sun_light;
use honeycomb::generate::{cooling_tower, design_surface, Shape};
use honeycomb::mesh::{read_mesh, validate_base_mesh, PolyMesh};
use honeycomb::structure::QuadPattern;
use honeycomb::{pipeline, Outcome, PipelineOptions, Progress, Surface, Variant, Walls};
use honeycomb::{Error, Result};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Where the real roofs are by default: the team's shared data beside the checkout.
pub const DEFAULT_DIR: &str = "../shared/data";

/// The built-in surfaces `--generated` adds: two developables, a dome, a saddle, a wave, and a
/// developable round a hole; then a cooling tower (a tube, [`Source::Tower`]).
const GENERATED: [Shape; 6] = [
    Shape::Cylinder,
    Shape::Cone,
    Shape::Dome,
    Shape::Saddle,
    Shape::Wave,
    Shape::Ring,
];

/// What `bench --roofs` runs.
pub struct RoofsArgs {
    pub dir: Option<PathBuf>,
    pub cells: Vec<usize>,
    pub generated: bool,
    pub walls: Walls,
    /// Uneven cells evened or not (`pipeline --even-cells`, `--no-even-cells`); `None`: the
    /// pipeline's default.
    pub even_cells: Option<bool>,
    /// One row per variant (see [`VARIANTS`]) instead of the plain pipeline.
    pub variants: bool,
    /// With `variants`: the twelve suns of [`SUNS`] instead of the two of [`VARIANTS`].
    pub suns: bool,
    pub json: bool,
}

/// The variants `--variants` runs on every surface, by the name its rows give: `reshaped 0.3`
/// is the flattest cover whose cells may re-shape up to an edge cv of 0.3
/// (`--quads-reshape 0.3`); the shading rows are for a sun 30 degrees high in the south-west
/// and 60 degrees high in the north-east.
const VARIANTS: [&str; 7] = [
    "zigzag",
    "alternating",
    "flattest",
    "reshaped 0.3",
    "parallel",
    "sun 30/225",
    "sun 60/45",
];

/// `--suns`: suns 30, 45 and 60 degrees high (issue 27 asks 30 to 60) from the four
/// quarters, as elevation and azimuth in degrees.
const SUNS: [(u32, u32); 12] = [
    (30, 0),
    (30, 90),
    (30, 180),
    (30, 270),
    (45, 0),
    (45, 90),
    (45, 180),
    (45, 270),
    (60, 0),
    (60, 90),
    (60, 180),
    (60, 270),
];

/// The variants' row names: [`VARIANTS`], or with `suns` its rows but the suns and then
/// [`SUNS`].
fn variant_names(suns: bool) -> Vec<String> {
    let kept = VARIANTS.iter().filter(|v| !(suns && v.starts_with("sun ")));
    let mut names: Vec<String> = kept.map(|v| v.to_string()).collect();
    if suns {
        names.extend(SUNS.iter().map(|(e, a)| format!("sun {e}/{a}")));
    }
    names
}

fn variant(name: &str) -> Variant {
    let sun = name.strip_prefix("sun ").and_then(|s| s.split_once('/'));
    if let Some((elevation, azimuth)) = sun {
        let degrees = |d: &str| d.parse::<f64>().expect("a sun row names its angles");
        return Variant::Shading {
            light: sun_light(degrees(elevation), degrees(azimuth)),
            sun_path: Vec::new(),
            w_axes: None,
        };
    }
    let reshaped = name.strip_prefix("reshaped ");
    let quads_reshape = reshaped.map(|cv| cv.parse::<f64>().expect("a reshaped row names its cv"));
    match name {
        "parallel" => Variant::Parallel {
            depth: None,
            w_parallel: None,
            w_depth: None,
        },
        pattern => Variant::Quads {
            pattern: match reshaped {
                Some(_) => QuadPattern::Flattest,
                None => (pattern.parse::<QuadPattern>())
                    .expect("the other rows of VARIANTS are quad patterns"),
            },
            quad_direction: None,
            w_cons_faces: None,
            w_fair_zig: None,
            w_fair_str: None,
            quads_reshape,
            quads_whole_pattern: false,
        },
    }
}

/// One row of the table.
#[derive(Serialize)]
struct Row {
    surface: String,
    cells_asked: usize,
    /// `ok`, `not a honeycomb`, `refused` or `skipped`; `reason` says why for the last two.
    status: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    reason: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    variant: Option<String>,
    #[serde(flatten)]
    figures: Option<Figures>,
    #[serde(flatten)]
    variant_figures: Option<VariantFigures>,
}

/// What a variant asked and what it cost, from the realized meshes.
#[derive(Serialize, Default)]
struct VariantFigures {
    /// Quads: the planarity of the capping quads on the honeycomb before capping, and after.
    #[serde(skip_serializing_if = "Option::is_none")]
    delta_face_max_before: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    delta_face_avg_before: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    delta_face_max: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    delta_face_avg: Option<f64>,
    /// Quads: the capping's own iterations (`iterations_total` counts the honeycomb's too).
    #[serde(skip_serializing_if = "Option::is_none")]
    capping_iterations: Option<usize>,
    /// Parallel meshes: the largest angle between an edge of M and its edge of M'.
    #[serde(skip_serializing_if = "Option::is_none")]
    beta_max_deg: Option<f64>,
    /// Shading: the light share through the same cells along S's normals, and through the
    /// result.
    #[serde(skip_serializing_if = "Option::is_none")]
    light_share_before: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    light_share_after: Option<f64>,
}

#[derive(Serialize)]
struct Figures {
    cells: usize,
    seconds: f64,
    iterations_total: usize,
    omega_max_deg: f64,
    delta_max: f64,
    closeness_max: f64,
    axis_normal_mean_deg: f64,
    axis_normal_p95_deg: f64,
    axis_normal_max_deg: f64,
    parallel_mean_deg: f64,
    parallel_p95_deg: f64,
    edge_length_cv: f64,
    interior_hexagon_share: f64,
    walls: Walls,
}

pub fn run(args: RoofsArgs) -> Result<()> {
    if let Some(&bad) = args.cells.iter().find(|&&c| !(10..=100_000).contains(&c)) {
        return Err(Error::Parameter(format!(
            "--cells {bad}: expected 10 to 100000 cells"
        )));
    }
    let mut surfaces: Vec<(String, Source)> = Vec::new();
    if args.generated {
        for shape in GENERATED {
            let name = format!("{shape:?}").to_lowercase();
            surfaces.push((name, Source::Generated(shape)));
        }
        surfaces.push(("tower".into(), Source::Tower));
    }
    let dir = args
        .dir
        .clone()
        .unwrap_or_else(|| PathBuf::from(DEFAULT_DIR));
    match surface_files(&dir) {
        Ok(files) => {
            if files.is_empty() {
                eprintln!("note: {} has no OBJ, OFF or PLY file", dir.display());
            }
            surfaces.extend(files.into_iter().map(|p| (file_name(&p), Source::File(p))))
        }
        // The default folder may be absent on a fresh machine: say so and go on.
        Err(e) if args.dir.is_none() => eprintln!("skipping {}: {e}", dir.display()),
        Err(e) => return Err(e),
    }
    if args.variants {
        return run_variants(&args, &surfaces);
    }
    if !args.json {
        println!(
            "{:<28} {:>6} {:>6} {:>7} {:>4} {:>9} {:>9} {:>6} {:>6} {:>6} {:>6} {:>6}  status",
            "surface",
            "asked",
            "cells",
            "T (s)",
            "#It",
            "omega_max",
            "delta_max",
            "axis",
            "p95",
            "par",
            "p95",
            "cv"
        );
    }
    for &cells in &args.cells {
        for (name, source) in &surfaces {
            if !args.json {
                // The surface's name first: a row can take seconds.
                print!("{name:<28} {cells:>6} ");
                let _ = std::io::Write::flush(&mut std::io::stdout());
            }
            let row = bench_one(name, source, cells, &args, None);
            print_row(&row, args.json)?;
        }
    }
    Ok(())
}

/// `--variants`: the pipeline with each variant on every surface.
fn run_variants(args: &RoofsArgs, surfaces: &[(String, Source)]) -> Result<()> {
    if !args.json {
        println!(
            "{:<28} {:<12} {:>6} {:>6} {:>7} {:>4} {:>4} {:>9} {:>9} {:>15} {:>15} {:>7} {:>13} \
             {:>6} {:>6}  status",
            "surface",
            "variant",
            "asked",
            "cells",
            "T (s)",
            "#It",
            "cap",
            "omega_max",
            "delta_max",
            "df max bef/aft",
            "df avg bef/aft",
            "beta",
            "light bef/aft",
            "close",
            "cv"
        );
    }
    let names = variant_names(args.suns);
    for &cells in &args.cells {
        for (name, source) in surfaces {
            let (mut suns, mut met) = (0, 0);
            for variant in &names {
                if !args.json {
                    print!("{name:<28} {variant:<12} {cells:>6} ");
                    let _ = std::io::Write::flush(&mut std::io::stdout());
                }
                let row = bench_one(name, source, cells, args, Some(variant));
                print_variant_row(&row, args.json)?;
                if variant.starts_with("sun ") && row.figures.is_some() {
                    suns += 1;
                    met += usize::from(row.status == "ok");
                }
            }
            if args.suns && !args.json && suns > 0 {
                println!("{name:<28} suns met     {cells:>6} {met}/{suns}");
            }
        }
    }
    Ok(())
}

fn print_variant_row(row: &Row, json: bool) -> Result<()> {
    let (Some(f), Some(v)) = (&row.figures, &row.variant_figures) else {
        return print_row(row, json);
    };
    if json {
        return print_row(row, json);
    }
    let pair = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => format!("{a:.4}/{b:.4}"),
        _ => "-".into(),
    };
    println!(
        "{:>6} {:>7.2} {:>4} {:>4} {:>9.1e} {:>9.1e} {:>15} {:>15} {:>7} {:>13} {:>6.3} {:>6.3}  {}",
        f.cells,
        f.seconds,
        f.iterations_total,
        v.capping_iterations.map_or("-".into(), |n| n.to_string()),
        f.omega_max_deg,
        f.delta_max,
        pair(v.delta_face_max_before, v.delta_face_max),
        pair(v.delta_face_avg_before, v.delta_face_avg),
        v.beta_max_deg.map_or("-".into(), |b| format!("{b:.1e}")),
        pair(v.light_share_before, v.light_share_after),
        f.closeness_max,
        f.edge_length_cv,
        row.status
    );
    Ok(())
}

enum Source {
    File(PathBuf),
    Generated(Shape),
    /// The built-in cooling tower (a tube).
    Tower,
}

/// The mesh files in `dir` (OBJ, OFF, PLY), by name.
fn surface_files(dir: &Path) -> Result<Vec<PathBuf>> {
    if !dir.is_dir() {
        return Err(Error::Parameter(format!(
            "--roofs {}: no such folder (expected a folder of design surfaces: OBJ, OFF, PLY)",
            dir.display()
        )));
    }
    let entries = std::fs::read_dir(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.is_file()
                && p.extension()
                    .and_then(|e| e.to_str())
                    .is_some_and(|e| ["obj", "off", "ply"].contains(&e.to_lowercase().as_str()))
        })
        .collect();
    files.sort();
    Ok(files)
}

fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into(),
    )
}

/// The pipeline on one surface, timed from reading it to the measured result.
fn bench_one(
    name: &str,
    source: &Source,
    cells: usize,
    args: &RoofsArgs,
    variant_name: Option<&str>,
) -> Row {
    let row = |status, reason: Option<String>, figures| Row {
        surface: name.to_string(),
        cells_asked: cells,
        status,
        reason,
        variant: variant_name.map(String::from),
        figures,
        variant_figures: None,
    };
    let start = Instant::now();
    let surface: PolyMesh = match source {
        Source::Generated(shape) => design_surface(*shape),
        Source::Tower => cooling_tower(10.0, 120),
        Source::File(path) => match read_mesh(path) {
            Ok(loaded) => loaded.mesh,
            Err(e) => return row("refused", Some(e.to_string()), None),
        },
    };
    // A trivalent hex mesh is a base mesh for `optimize`, not a design surface.
    if validate_base_mesh(&surface).is_ok() {
        let reason = "a hex base mesh (every vertex of valence 2 or 3): for optimize".into();
        return row("skipped", Some(reason), None);
    }
    let mut options = PipelineOptions::new(cells);
    options.options.walls = args.walls;
    options.even_cells = args.even_cells;
    if let Some(name) = variant_name {
        options.options.variant = variant(name);
    }
    let made = match Surface::new(surface)
        .and_then(|surface| pipeline(&surface, &options, &mut Progress::silent()))
    {
        Ok(made) => made,
        Err(e) => return row("refused", Some(e.to_string()), None),
    };
    let seconds = start.elapsed().as_secs_f64();
    let status = if !made.report.honeycomb {
        "not a honeycomb"
    } else if made.verdict.unmet.is_some() {
        "short of half the light"
    } else {
        "ok"
    };
    let mut row = row(status, None, Some(figures(&made, seconds)));
    if variant_name.is_some() {
        row.variant_figures = Some(variant_figures(&made));
    }
    row
}

fn variant_figures(made: &Outcome) -> VariantFigures {
    let shading = made.report.shading.as_ref();
    let mut v = VariantFigures {
        beta_max_deg: made.report.parallel.as_ref().map(|p| p.beta_max_deg),
        light_share_before: shading.map(|s| s.light.before),
        light_share_after: shading.map(|s| s.light.after),
        ..VariantFigures::default()
    };
    if let Some(q) = &made.report.quads {
        v.delta_face_max = Some(q.faces.delta_face_max);
        v.delta_face_avg = Some(q.faces.delta_face_avg);
        if let Some(c) = &q.capping {
            v.delta_face_max_before = Some(c.delta_face_max_before);
            v.delta_face_avg_before = Some(c.delta_face_avg_before);
            v.capping_iterations = Some(c.iterations);
        }
    }
    v
}

fn figures(made: &Outcome, seconds: f64) -> Figures {
    let m = &made.measures;
    Figures {
        cells: made.report.faces,
        seconds,
        iterations_total: made.report.iterations_total,
        omega_max_deg: m.omega_max_deg,
        delta_max: m.delta_max,
        closeness_max: m.closeness_max,
        axis_normal_mean_deg: m.axis_normal_deg.mean,
        axis_normal_p95_deg: m.axis_normal_deg.p95,
        axis_normal_max_deg: m.axis_normal_deg.max,
        parallel_mean_deg: m.parallel_baseline_deg.mean,
        parallel_p95_deg: m.parallel_baseline_deg.p95,
        edge_length_cv: m.edge_length_cv,
        interior_hexagon_share: interior_hexagon_share(&made.honeycomb.base),
        walls: made.report.walls,
    }
}

/// The share of hexagons among the cells that touch no boundary, of the result.
fn interior_hexagon_share(mesh: &PolyMesh) -> f64 {
    let Ok(conn) = honeycomb::mesh::Connectivity::build(mesh) else {
        return f64::NAN;
    };
    let interior: Vec<usize> = (0..mesh.faces.len())
        .filter(|&f| mesh.faces[f].iter().all(|&v| !conn.is_boundary_vertex[v]))
        .collect();
    let hexagons = interior
        .iter()
        .filter(|&&f| mesh.faces[f].len() == 6)
        .count();
    hexagons as f64 / interior.len().max(1) as f64
}

fn print_row(row: &Row, json: bool) -> Result<()> {
    if json {
        let text = serde_json::to_string(row).map_err(|e| Error::Parameter(e.to_string()))?;
        println!("{text}");
        return Ok(());
    }
    let Some(f) = &row.figures else {
        println!(
            "{:>6}  {}: {}",
            "-",
            row.status,
            row.reason.as_deref().unwrap_or("")
        );
        return Ok(());
    };
    println!(
        "{:>6} {:>7.2} {:>4} {:>9.1e} {:>9.1e} {:>6.2} {:>6.2} {:>6.2} {:>6.2} {:>6.3}  {}",
        f.cells,
        f.seconds,
        f.iterations_total,
        f.omega_max_deg,
        f.delta_max,
        f.axis_normal_mean_deg,
        f.axis_normal_p95_deg,
        f.parallel_mean_deg,
        f.parallel_p95_deg,
        f.edge_length_cv,
        if f.walls == Walls::Across {
            row.status.to_string()
        } else {
            format!("{} (walls {})", row.status, f.walls.label())
        }
    );
    Ok(())
}
