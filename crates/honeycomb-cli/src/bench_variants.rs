//! `honeycomb bench --variants`: one row per variant of the paper's section 4 on the generated
//! subject of its test, beside the time of the paper's Figure 16 row where it has one.

use crate::bench::all_iterations;
use honeycomb::generate::{lifted_hex_patch, roof, Shape, ROOF_AMPLITUDE};
use honeycomb::mesh::PolyMesh;
use honeycomb::report::Report;
use honeycomb::structure::QuadPattern;
use honeycomb::{optimize, BaseMesh, Options, Progress, Result, Surface, Variant, Vec3};
use std::time::Instant;

/// One benchmark case: its subject, its options and what to say about its result.
struct Case {
    name: &'static str,
    /// The paper's time for the same variant (Figure 16), in seconds.
    paper_seconds: Option<f64>,
    subject: (PolyMesh, PolyMesh),
    options: Options,
}

fn cases() -> Vec<Case> {
    let dome = |n| lifted_hex_patch(Shape::Dome, n);
    // The honeycomb, then its capping (see `optimize::capped`), 10 iterations each.
    let quads = |pattern, amplitude| Case {
        name: match pattern {
            QuadPattern::Zigzag => "zigzag quads",
            QuadPattern::Alternating => "alternating quads",
            QuadPattern::Flattest => "flattest quads",
        },
        paper_seconds: (pattern == QuadPattern::Zigzag).then_some(3.0),
        subject: roof(3500, amplitude),
        options: Options {
            variant: Variant::Quads {
                pattern,
                quad_direction: None,
                w_cons_faces: None,
                w_fair_zig: None,
                w_fair_str: None,
                quads_reshape: None,
                quads_whole_pattern: false,
            },
            ..all_iterations(10)
        },
    };
    // Shading as in tests/variants.rs: a sun 35 degrees high, cells 1.2 edge lengths deep.
    let light = Vec3::new(35f64.to_radians().cos(), 0.0, -35f64.to_radians().sin());
    let shading = |name, subject: (PolyMesh, PolyMesh)| {
        let edge = subject.0.mean_edge_length();
        Case {
            name,
            paper_seconds: Some(2.0),
            subject,
            options: Options {
                thickness: Some(1.2 * edge),
                min_edge: Some(0.3 * edge),
                variant: Variant::Shading {
                    light,
                    sun_path: Vec::new(),
                    w_axes: None,
                },
                ..all_iterations(20)
            },
        }
    };
    let tilted = dome(1500);
    let tilt = Vec3::new(10f64.to_radians().sin(), 0.0, 10f64.to_radians().cos());
    let min_edge = dome(1500);
    // As in tests/optimize.rs: 5% above the shortest edge the dome starts with.
    let shortest = 1.05 * min_edge.0.shortest_edge_length();
    vec![
        Case {
            name: "parallel",
            paper_seconds: Some(4.0),
            subject: dome(6144),
            options: Options {
                variant: Variant::Parallel {
                    depth: None,
                    w_parallel: None,
                    w_depth: None,
                },
                ..all_iterations(5)
            },
        },
        quads(QuadPattern::Zigzag, ROOF_AMPLITUDE),
        quads(QuadPattern::Alternating, 0.12),
        shading("shading (dome)", dome(3300)),
        shading("shading (roof)", roof(3300, ROOF_AMPLITUDE)),
        Case {
            name: "prescribed axes",
            paper_seconds: None,
            options: Options {
                variant: Variant::Axes {
                    axes: vec![tilt; tilted.0.vertices.len()],
                    w_axes: None,
                },
                ..all_iterations(5)
            },
            subject: tilted,
        },
        Case {
            name: "minimum edge",
            paper_seconds: None,
            subject: min_edge,
            options: Options {
                // The guided projection alone, as the other rows.
                walls: honeycomb::Walls::Free,
                wall_normals: honeycomb::WallNormals::CellPoints,
                min_edge: Some(shortest),
                ..all_iterations(15)
            },
        },
    ]
}

/// The variant's own measure, from the realized geometry, as a short text.
fn variant_measure(case: &Case, report: &Report) -> String {
    if let Some(p) = &report.parallel {
        return format!("beta_max {:.1e} deg", p.beta_max_deg);
    }
    if let Some(q) = &report.quads {
        let before = (q.capping.as_ref())
            .map(|c| {
                format!(
                    " (from {:.1e}/{:.1e})",
                    c.delta_face_max_before, c.delta_face_avg_before
                )
            })
            .unwrap_or_default();
        return format!(
            "delta_face {:.1e}/{:.1e}{before}",
            q.faces.delta_face_max, q.faces.delta_face_avg
        );
    }
    if let (Some(shading), Some(a)) = (&report.shading, &report.axes) {
        // The light share through cells extruded along the normals, then through the result.
        return format!(
            "light {:.2}->{:.2}, axes {:.1} deg avg",
            shading.light.before, shading.light.after, a.axes_angle_avg_deg,
        );
    }
    if let Some(a) = &report.axes {
        return format!("axes off {:.1e} deg max", a.axes_angle_max_deg);
    }
    match case.options.min_edge {
        Some(l) => format!("min edge / L {:.7}", report.measures.min_edge_length / l),
        None => String::new(),
    }
}

pub fn run(json: bool) -> Result<()> {
    if !json {
        println!(
            "{:<18} {:>6} {:>4} {:>10} {:>10}  {:<44} {:>7} {:>7}",
            "variant", "|V|", "#It", "omega_max", "delta_max", "measure", "T (s)", "paper"
        );
    }
    for case in cases() {
        let (base, surface) = &case.subject;
        let (base, surface) = (
            BaseMesh::from_mesh(base.clone())?,
            Surface::new(surface.clone())?,
        );
        let start = Instant::now();
        let outcome = optimize(&base, &surface, &case.options, &mut Progress::silent())?;
        let seconds = start.elapsed().as_secs_f64();
        let (report, measures) = (&outcome.report, &outcome.measures);
        let text = variant_measure(&case, report);
        if json {
            println!(
                "{}",
                serde_json::json!({
                    "variant": case.name, "vertices": report.vertices,
                    "iterations": report.iterations, "omega_max_deg": measures.omega_max_deg,
                    "delta_max": measures.delta_max, "measure": text, "seconds": seconds,
                    "paper_seconds": case.paper_seconds,
                })
            );
        } else {
            println!(
                "{:<18} {:>6} {:>4} {:>10.2e} {:>10.2e}  {:<44} {:>7.3} {:>7}",
                case.name,
                report.vertices,
                report.iterations,
                measures.omega_max_deg,
                measures.delta_max,
                text,
                seconds,
                case.paper_seconds.map_or("-".into(), |s| format!("{s}"))
            );
        }
    }
    Ok(())
}
