//! The library's front door as a program uses it: checked inputs, plain options, a judged and
//! measured outcome, progress and cancellation.

use honeycomb::generate::{design_surface, lifted_hex_patch, Shape};
use honeycomb::structure::measure;
use honeycomb::{
    optimize, pipeline, BaseMesh, Cancel, Error, Options, PipelineOptions, Progress, Step, Surface,
    Variant, Vec3, Walls,
};

fn dome(vertices: usize) -> (BaseMesh, Surface) {
    let (base, surface) = lifted_hex_patch(Shape::Dome, vertices);
    (
        BaseMesh::from_mesh(base).unwrap(),
        Surface::new(surface).unwrap(),
    )
}

#[test]
fn options_are_plain_data_and_bad_fields_are_named() {
    let options = Options {
        walls: Walls::Direction(Vec3::new(0.0, 0.0, 1.0)),
        iterations: Some(25),
        w_fair: Some(0.0),
        ..Options::default()
    };
    let text = serde_json::to_string(&options).unwrap();
    assert_eq!(serde_json::from_str::<Options>(&text).unwrap(), options);
    let quads: Options =
        serde_json::from_str(r#"{"variant": {"kind": "quads", "pattern": "alternating"}}"#)
            .unwrap();
    assert!(matches!(quads.variant, Variant::Quads { .. }));
    assert!(serde_json::from_str::<Options>(r#"{"iteration": 3}"#).is_err());
    let bad = [
        (
            Options {
                iterations: Some(0),
                ..Options::default()
            },
            "iterations",
            "0",
        ),
        (
            Options {
                w_fair: Some(-1.0),
                ..Options::default()
            },
            "w_fair",
            "-1",
        ),
        (
            Options {
                thickness: Some(f64::NAN),
                ..Options::default()
            },
            "thickness",
            "NaN",
        ),
        (
            Options {
                eps: 0.0,
                ..Options::default()
            },
            "eps",
            "0",
        ),
        (
            Options {
                walls: Walls::Uniform,
                variant: Variant::Parallel {
                    depth: None,
                    w_parallel: None,
                    w_depth: None,
                },
                ..Options::default()
            },
            "walls",
            "uniform",
        ),
        (
            Options {
                variant: Variant::Shading {
                    light: Vec3::ZERO,
                    sun_path: Vec::new(),
                    w_axes: None,
                },
                ..Options::default()
            },
            "light",
            "0,0,0",
        ),
    ];
    for (options, field, value) in bad {
        match options.validate() {
            Err(Error::Option {
                field: f, value: v, ..
            }) => assert_eq!((f, v.as_str()), (field, value)),
            other => panic!("{field}: {other:?}"),
        }
    }
}

#[test]
fn a_base_mesh_is_checked_once_when_made() {
    // Four cells around a vertex: valence 4.
    let v = |x: f64, y: f64| Vec3::new(x, y, 0.0);
    let vertices = vec![
        v(0.0, 0.0),
        v(1.0, 0.0),
        v(1.0, 1.0),
        v(0.0, 1.0),
        v(-1.0, 1.0),
        v(-1.0, 0.0),
        v(-1.0, -1.0),
        v(0.0, -1.0),
        v(1.0, -1.0),
    ];
    let cells = vec![
        vec![0, 1, 2, 3],
        vec![0, 3, 4, 5],
        vec![0, 5, 6, 7],
        vec![0, 7, 8, 1],
    ];
    let e = BaseMesh::new(vertices, cells).unwrap_err().to_string();
    assert!(e.contains("vertex 0") && e.contains("4"), "{e}");
    let missing = BaseMesh::read("no/such/base.obj").unwrap_err().to_string();
    assert!(missing.contains("no/such/base.obj"), "{missing}");
}

#[test]
fn an_optimized_outcome_is_measured_from_its_meshes_and_saved_whole() {
    let (base, surface) = dome(300);
    let mut steps = 0;
    let outcome = optimize(
        &base,
        &surface,
        &Options::default(),
        &mut Progress::new(|step| {
            if let Step::Iteration(..) = step {
                steps += 1;
            }
        }),
    )
    .unwrap();
    assert!(outcome.is_honeycomb(), "{:?}", outcome.verdict);
    assert_eq!(outcome.verdict.why, None);
    assert!(
        steps > 0 && steps == outcome.report.iterations_total,
        "{steps} {}",
        outcome.report.iterations_total
    );
    // The measures are those of the realized meshes.
    let again = measure(&outcome.honeycomb, &surface);
    assert_eq!(again.omega_max_deg, outcome.measures.omega_max_deg);
    assert_eq!(again.delta_max, outcome.measures.delta_max);
    assert!(outcome.measures.omega_max_deg < 0.01 && outcome.measures.delta_max < 1e-6);
    assert_eq!(outcome.honeycomb.base.faces, base.cells());
    // Walls across the dome lean less than parallel ones.
    let m = &outcome.measures;
    assert!(m.axis_normal_deg.mean < 0.7 * m.parallel_baseline_deg.mean);

    let dir = std::env::temp_dir().join(format!("front-door-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let written = outcome.save(&dir).unwrap();
    assert_eq!(written, dir);
    for file in [
        "base.obj",
        "offset.obj",
        "walls.obj",
        "structure.json",
        "report.json",
    ] {
        assert!(dir.join(file).is_file(), "{file}");
    }
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["honeycomb"], true);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_cancelled_solve_stops_before_its_next_iteration() {
    let (base, surface) = dome(600);
    let options = Options {
        walls: Walls::Free,
        iterations: Some(50),
        tolerance: 0.0,
        ..Options::default()
    };
    // Cancelled before it starts: no iteration at all.
    let mut iterations = 0;
    let mut progress = Progress::new(|step| {
        if let Step::Iteration(..) = step {
            iterations += 1;
        }
    });
    progress.cancel_handle().cancel();
    let e = optimize(&base, &surface, &options, &mut progress).err();
    assert!(matches!(e, Some(Error::Cancelled)), "{e:?}");
    drop(progress);
    assert_eq!(iterations, 0);

    // From inside the callback, after two of the fifty iterations; the pipeline likewise.
    for solve in ["optimize", "pipeline"] {
        let stop = Cancel::new();
        let inside = stop.clone();
        let mut iterations = 0;
        let mut progress = Progress::new(|step| {
            if let Step::Iteration(..) = step {
                iterations += 1;
                if iterations == 2 {
                    inside.cancel();
                }
            }
        })
        .with_cancel(stop);
        let e = match solve {
            "optimize" => optimize(&base, &surface, &options, &mut progress).err(),
            _ => pipeline(&surface, &PipelineOptions::new(300), &mut progress).err(),
        };
        assert!(matches!(e, Some(Error::Cancelled)), "{solve}: {e:?}");
        drop(progress);
        assert_eq!(iterations, 2, "{solve}");
    }
}

#[test]
fn the_pipeline_makes_and_judges_a_honeycomb_from_a_surface_alone() {
    let surface = Surface::new(design_surface(Shape::Wave)).unwrap();
    let outcome = pipeline(
        &surface,
        &PipelineOptions::new(200),
        &mut Progress::silent(),
    )
    .unwrap();
    assert!(outcome.is_honeycomb());
    let init = outcome
        .initialized
        .as_ref()
        .expect("the pipeline's base mesh");
    assert!(
        (init.cells as f64 / 200.0 - 1.0).abs() < 0.15,
        "{}",
        init.cells
    );
    assert_eq!(outcome.report.walls, Walls::Across);
    let bad = PipelineOptions {
        options: Options {
            variant: Variant::Axes {
                axes: Vec::new(),
                w_axes: None,
            },
            ..Options::default()
        },
        ..PipelineOptions::new(200)
    };
    let e = pipeline(&surface, &bad, &mut Progress::silent()).err();
    assert!(
        matches!(e, Some(Error::Option { field: "axes", .. })),
        "{e:?}"
    );
}

#[test]
fn a_variant_runs_through_the_same_door() {
    let (base, surface) = dome(300);
    let options = Options {
        variant: Variant::Parallel {
            depth: None,
            w_parallel: None,
            w_depth: None,
        },
        ..Options::default()
    };
    let outcome = optimize(&base, &surface, &options, &mut Progress::silent()).unwrap();
    assert!(outcome.is_honeycomb());
    let parallel = outcome.report.parallel.as_ref().expect("parallel measures");
    assert!(parallel.beta_max_deg < 1e-3, "{}", parallel.beta_max_deg);
}
