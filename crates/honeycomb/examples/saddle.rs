//! The library from a program: a honeycomb with walls across a saddle, its measures, and the
//! files a fabricator cuts. `cargo run --release --example saddle` writes `saddle-honeycomb/`
//! and `saddle-export/`.

use honeycomb::export::{export, ExportOptions, Model};
use honeycomb::generate::{design_surface, Shape};
use honeycomb::{pipeline, PipelineOptions, Progress, Surface};
use std::path::Path;

fn main() -> honeycomb::Result<()> {
    let surface = Surface::new(design_surface(Shape::Saddle))?;
    let made = pipeline(
        &surface,
        &PipelineOptions::new(750),
        &mut Progress::silent(),
    )?;
    let m = &made.measures;
    println!(
        "honeycomb {}: omega_max {:.1e} deg, axis to normal {:.1} deg",
        made.is_honeycomb(),
        m.omega_max_deg,
        m.axis_normal_deg.mean
    );
    made.save("saddle-honeycomb")?;
    let model = Model::new(
        made.honeycomb,
        Some(surface.source_mesh().clone()),
        Default::default(),
    )?;
    let written = export(
        &model,
        &ExportOptions::default(),
        Path::new("saddle-export"),
        &[],
    )?;
    println!("{}", written.files.join(", "));
    Ok(())
}
