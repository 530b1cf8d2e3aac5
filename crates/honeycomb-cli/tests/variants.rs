//! End to end: the paper's variants as options of `optimize`/`demo`, judged from the files they
//! write, and their nonsense values rejected.

mod common;

use common::{
    assert_clean_failure, demo, mesh_edges, number, quad_delta, read_json, read_written_mesh, run,
    run_demo, stderr, stdout, TempDir,
};
use honeycomb::geometry::Vec3;

#[test]
fn parallel_meshes_have_parallel_edges_and_the_asked_depth() {
    let tmp = TempDir::new("parallel");
    let dir = tmp.join("out");
    demo(&dir, &["--vertices", "600", "--parallel", "--depth", "0.5"]);
    let report = read_json(&dir, "report.json");
    let (base, offset) = (
        read_written_mesh(&dir.join("base.obj")),
        read_written_mesh(&dir.join("offset.obj")),
    );
    assert_eq!(base.faces, offset.faces);
    // Recomputed from the files: corresponding edges are parallel, depths are 0.5.
    let mut beta_max = 0.0f64;
    for [a, b] in mesh_edges(&base) {
        let e = (base.vertices[b] - base.vertices[a]).normalized();
        let f = (offset.vertices[b] - offset.vertices[a]).normalized();
        beta_max = beta_max.max(e.cross(f).norm().asin().to_degrees());
        assert!(e.dot(f) > 0.0, "edge {a}-{b} reversed in M'");
    }
    assert!(beta_max < 0.1, "beta {beta_max}");
    assert!((number(&report, "beta_max_deg") - beta_max).abs() < 1e-6);
    for (v, w) in base.vertices.iter().zip(&offset.vertices) {
        assert!(
            ((*w - *v).norm() - 0.5).abs() < 1e-3,
            "{}",
            (*w - *v).norm()
        );
    }
    assert!(number(&report, "depth_min") > 0.499 && number(&report, "depth_max") < 0.501);
    assert!(number(&report, "omega_max_deg") < 0.05);
    assert!(number(&report, "delta_max") < 1e-5);
}

#[test]
fn quads_are_written_planar_on_the_optimized_vertices() {
    let tmp = TempDir::new("quads");
    let dir = tmp.join("out");
    demo(&dir, &["--vertices", "600", "--quads", "zigzag"]);
    let report = read_json(&dir, "report.json");
    let (base, quads) = (
        read_written_mesh(&dir.join("base.obj")),
        read_written_mesh(&dir.join("quads.obj")),
    );
    assert_eq!(base.vertices, quads.vertices);
    let hexagons = base.faces.iter().filter(|f| f.len() == 6).count();
    let split: Vec<&Vec<usize>> = quads.faces.iter().take(2 * hexagons).collect();
    assert!(split.iter().all(|f| f.len() == 4));
    assert_eq!(
        quads.faces.len(),
        2 * hexagons + base.faces.len() - hexagons
    );
    assert_eq!(number(&report, "quads") as usize, 2 * hexagons);
    assert_eq!(report["quad_pattern"], "zigzag");
    let deltas: Vec<f64> = split
        .iter()
        .map(|f| quad_delta([0, 1, 2, 3].map(|k| quads.vertices[f[k]])))
        .collect();
    let max = deltas.iter().copied().fold(0.0, f64::max);
    let avg = deltas.iter().sum::<f64>() / deltas.len() as f64;
    assert!((number(&report, "delta_face_max") - max).abs() < 1e-9);
    assert!((number(&report, "delta_face_avg") - avg).abs() < 1e-9);
    assert!(max < 0.02, "delta_face_max {max}");
    assert!(number(&report, "omega_max_deg") < 0.1);
}

/// `pipeline --quads zigzag` on the built-in wave (its surface as `demo` writes it), where the
/// zigzag whole stays short of the quad floors: report.json's `capping` counts the cells taken
/// off the pattern and gives the pattern whole's quads; `--quads-whole-pattern` takes none
/// off and the written quads stay short.
#[test]
fn a_pattern_broken_for_flat_quads_is_reported() {
    let tmp = TempDir::new("pattern_broken");
    demo(&tmp.join("wave"), &["--shape", "wave"]);
    let surface = tmp.join("wave").join("surface.obj");
    let capped = |extra: &[&str]| {
        let dir = tmp.join(&format!("capped{}", extra.len()));
        let mut args = vec!["pipeline", surface.to_str().unwrap(), "--cells", "750"];
        args.extend(["--quads", "zigzag", "-q", "-o", dir.to_str().unwrap()]);
        args.extend(extra.iter().copied());
        let out = run(&args);
        assert!(out.status.success(), "{}", stderr(&out));
        read_json(&dir, "report.json")
    };
    let floors = |r: &serde_json::Value| {
        number(r, "delta_face_max") <= 0.01 && number(r, "delta_face_avg") <= 0.004
    };
    let broken = capped(&[]);
    let capping = &broken["capping"];
    let off = number(capping, "cells_off_pattern");
    assert!(
        off >= 1.0 && 5.0 * off <= number(&broken, "quads") / 2.0,
        "{capping}"
    );
    assert!(floors(&broken), "{broken}");
    assert!(
        number(&capping["whole_pattern"], "delta_face_max") > 0.01,
        "{capping}"
    );
    let whole = capped(&["--quads-whole-pattern"]);
    assert_eq!(number(&whole["capping"], "cells_off_pattern"), 0.0);
    assert!(whole["capping"].get("whole_pattern").is_none(), "{whole}");
    assert!(!floors(&whole), "{whole}");
}

#[test]
fn prescribed_axes_are_followed() {
    let tmp = TempDir::new("axes");
    let dir = tmp.join("first");
    demo(&dir, &["--vertices", "300"]);
    let base = read_written_mesh(&dir.join("base.obj"));
    // Every axis tilted 10 degrees from the vertical, the same way.
    let target = Vec3::new(10f64.to_radians().sin(), 0.0, 10f64.to_radians().cos());
    let line = format!("{} {} {}\n", target.x, target.y, target.z);
    let axes = tmp.write("axes.txt", &line.repeat(base.vertices.len()));
    let out = tmp.join("out");
    let output = run([
        "optimize",
        dir.join("base.obj").to_str().unwrap(),
        "--surface",
        dir.join("surface.obj").to_str().unwrap(),
        "--axes",
        axes.to_str().unwrap(),
        "--w-axes",
        "1",
        "-q",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", common::stderr(&output));
    let report = read_json(&out, "report.json");
    let (m, m2) = (
        read_written_mesh(&out.join("base.obj")),
        read_written_mesh(&out.join("offset.obj")),
    );
    let mut worst = 0.0f64;
    for (v, w) in m.vertices.iter().zip(&m2.vertices) {
        let axis = (*w - *v).normalized();
        // atan2, not acos: the angles are small.
        let angle = axis.cross(target).norm().atan2(axis.dot(target).abs());
        worst = worst.max(angle.to_degrees());
    }
    assert!(worst < 0.5, "axes off their target by {worst} degrees");
    let reported = number(&report, "axes_angle_max_deg");
    assert!((reported - worst).abs() < 1e-4, "{reported} vs {worst}");
    assert_eq!(
        number(&report, "axes_prescribed") as usize,
        m.vertices.len()
    );
}

/// `demo --light` on a base mesh: walls across S turned across the light and the sun path,
/// their share of the light and the path's mean halved against the same cells along S's
/// normals (report.json, which the written meshes bear out in the library's tests), one
/// entry per direction of the path; walls too shallow to halve it are an error naming the
/// light and the share reached, with the outputs kept aside in DIR.failed.
#[test]
fn shading_reports_the_light_before_and_after_per_direction() {
    let tmp = TempDir::new("light");
    let sun = tmp.write("sun.txt", "# morning, noon\n0.5 0 -0.8\n\n0 0.1 -1\n");
    let dir = tmp.join("out");
    let light = ["--vertices", "600", "--light", "0.8,0,-0.57"];
    let path = ["--sun-path", sun.to_str().unwrap()];
    demo(&dir, &[&light[..], &path[..]].concat());
    let report = read_json(&dir, "report.json");
    let shading = &report["shading"];
    let (before, after) = (
        number(&shading["light"], "before"),
        number(&shading["light"], "after"),
    );
    assert!(after <= 0.5 * before, "light share {before} -> {after}");
    let mean = &shading["sun_path_mean"];
    assert!(
        number(mean, "after") <= 0.5 * number(mean, "before"),
        "{mean}"
    );
    assert_eq!(shading["sun_path"].as_array().unwrap().len(), 2);
    assert_eq!(shading["met"], true);
    // On this mesh the shortest turns across the light block too little over the sun path;
    // the turns leaning one way across it block enough, walls across S as exact as ever,
    // their axes turned well away from S's normals.
    assert_eq!(report["honeycomb"], true);
    assert_eq!(report["walls"], "across");
    assert!(number(&report, "omega_max_deg") < 0.01);
    assert!(number(&report, "delta_max") < 1e-6);
    let notes = report["notes"].to_string();
    assert!(
        notes.contains(
            "this is the axes turned across the light at most 45 degrees, leaning one way"
        ),
        "{notes}"
    );
    let lean = number(&report["axis_normal_deg"], "mean");
    assert!(lean > 25.0, "the axes {lean} degrees from S's normals");

    let thin = tmp.join("thin");
    let output = run_demo(&thin, &[&light[..], &["--thickness", "0.05"]].concat());
    assert_eq!(output.status.code(), Some(1));
    let err = stderr(&output);
    assert!(
        err.contains("light 0.8144,0,-0.5803") && err.contains("let through"),
        "{err}"
    );
    assert!(!thin.exists() && tmp.join("thin.failed").join("report.json").is_file());
}

#[test]
fn minimum_edge_length_holds() {
    let tmp = TempDir::new("min_edge");
    let dir = tmp.join("out");
    demo(&dir, &["--vertices", "300", "--min-edge", "0.9"]);
    let base = read_written_mesh(&dir.join("base.obj"));
    for [a, b] in mesh_edges(&base) {
        let length = (base.vertices[b] - base.vertices[a]).norm();
        assert!(length >= 0.9 * (1.0 - 1e-6), "edge {a}-{b}: {length}");
    }
}

/// `demo --vertices 60 EXTRA... -o DIR/out` must fail cleanly naming every keyword, before
/// writing anything.
fn demo_fails(name: &str, extra: &[&str], keywords: &[&str]) {
    let tmp = TempDir::new(&format!("reject_{name}"));
    let out = tmp.join("out");
    let mut args = vec!["demo", "--vertices", "60"];
    args.extend_from_slice(extra);
    args.extend(["-o", out.to_str().unwrap()]);
    let output = run(&args);
    assert_clean_failure(&output, keywords, Some(&out));
    assert_eq!(stdout(&output), "");
}

#[test]
fn nonsense_variant_values_are_rejected() {
    demo_fails(
        "zero_light",
        &["--light", "0,0,0"],
        &["--light", "non-zero"],
    );
    demo_fails(
        "word_light",
        &["--light", "up"],
        &["--light", "three numbers"],
    );
    demo_fails("nan_light", &["--light", "1,nan,0"], &["--light", "finite"]);
    demo_fails(
        "negative_depth",
        &["--parallel", "--depth", "-1"],
        &["--depth -1", "positive"],
    );
    demo_fails("depth_alone", &["--depth", "1"], &["--depth", "--parallel"]);
    demo_fails(
        "parallel_weight",
        &["--parallel", "--w-parallel", "-1"],
        &["parallel", "-1"],
    );
    demo_fails(
        "min_edge",
        &["--min-edge", "0"],
        &["--min-edge 0", "positive"],
    );
    demo_fails(
        "quads",
        &["--quads", "spiral"],
        &["spiral", "zigzag, alternating or flattest"],
    );
    demo_fails(
        "quad_direction",
        &["--quads", "zigzag", "--quad-direction", "0,0,0"],
        &["--quad-direction", "0,0,0", "non-zero"],
    );
    demo_fails(
        "quad_weight",
        &["--quads", "zigzag", "--w-cons-faces", "0"],
        &["--w-cons-faces 0", "weight above 0"],
    );
    demo_fails(
        "quads_reshape",
        &["--quads", "zigzag", "--quads-reshape", "-1"],
        &["--quads-reshape -1", "edge-length cv above 0"],
    );
    demo_fails(
        "quads_reshape_nan",
        &["--quads", "flattest", "--quads-reshape", "NaN"],
        &["--quads-reshape NaN", "edge-length cv above 0"],
    );
    demo_fails(
        "sun_alone",
        &["--sun-path", "sun.txt"],
        &["--sun-path", "--light"],
    );
    demo_fails(
        "axes_and_light",
        &["--axes", "a.txt", "--light", "0,0,-1"],
        &["--axes", "--light"],
    );
}

#[test]
fn bad_axes_and_sun_path_files_are_named() {
    let tmp = TempDir::new("bad_files");
    let dir = tmp.join("first");
    demo(&dir, &["--vertices", "60"]);
    let base = dir.join("base.obj");
    let surface = dir.join("surface.obj");
    let optimize_fails = |extra: &[&str], keywords: &[&str]| {
        let out = tmp.join("out");
        let mut args = vec![
            "optimize",
            base.to_str().unwrap(),
            "--surface",
            surface.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        args.extend(["-o", out.to_str().unwrap()]);
        let output = run(&args);
        assert_clean_failure(&output, keywords, Some(&out));
    };
    let too_few = tmp.write("few.txt", "0 0 1\n0 0 1\n");
    optimize_fails(&["--axes", too_few.to_str().unwrap()], &["few.txt", "2"]);
    let nv = read_written_mesh(&base).vertices.len();
    let mut text = "0 0 1\n".repeat(nv - 1);
    text.push_str("0 nan 1\n");
    let nan = tmp.write("nan.txt", &text);
    optimize_fails(
        &["--axes", nan.to_str().unwrap()],
        &["nan.txt", &format!(":{nv}:"), "nan"],
    );
    let missing = tmp.join("missing.txt");
    optimize_fails(
        &["--light", "0,0,-1", "--sun-path", missing.to_str().unwrap()],
        &["missing.txt"],
    );
    let bad = tmp.write("sun.txt", "0 0 -1\n0 0\n");
    optimize_fails(
        &["--light", "0,0,-1", "--sun-path", bad.to_str().unwrap()],
        &["sun.txt", ":2:"],
    );
    let zero = tmp.write("zero.txt", "0 0 0\n");
    optimize_fails(
        &["--light", "0,0,-1", "--sun-path", zero.to_str().unwrap()],
        &["zero.txt", ":1:"],
    );
}

/// The variant weights are options without a clap default (giving one for a variant not asked
/// for is refused), so their defaults are written in the help text by hand: they must be the
/// library's.
#[test]
fn the_help_states_the_library_defaults_of_the_variant_weights() {
    use honeycomb::structure::QuadPattern;
    use honeycomb::{Variant, Vec3};
    let output = run(["optimize", "--help"]);
    let help = stdout(&output)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let weights = |v: Variant| v.weights();
    let parallel = weights(Variant::Parallel {
        depth: None,
        w_parallel: None,
        w_depth: None,
    });
    let quads = weights(Variant::Quads {
        pattern: QuadPattern::Zigzag,
        quad_direction: None,
        w_cons_faces: None,
        w_fair_zig: None,
        w_fair_str: None,
        quads_reshape: None,
        quads_whole_pattern: false,
    });
    let axes = weights(Variant::Axes {
        axes: Vec::new(),
        w_axes: None,
    })[0]
        .1;
    let shading = weights(Variant::Shading {
        light: Vec3::new(0.0, 0.0, -1.0),
        sun_path: Vec::new(),
        w_axes: None,
    })[0]
        .1;
    let flag = |field: &str| format!("--{}", field.replace('_', "-"));
    let mut expected: Vec<(String, String)> = parallel
        .iter()
        .chain(&quads)
        .map(|&(field, w)| (flag(field), format!("[default: {w}]")))
        .collect();
    expected.push((
        "--w-axes".into(),
        format!("[default: {axes}, {shading} with --light]"),
    ));
    for (flag, default) in expected {
        let at = help
            .find(&format!("{flag} <"))
            .unwrap_or_else(|| panic!("{flag} is not in the help:\n{help}"));
        let entry = &help[at..];
        let end = entry.find(']').map_or(entry.len(), |e| e + 1);
        assert!(
            entry[..end].ends_with(&default),
            "{flag}: the help says {:?}, the library's default is {default}",
            &entry[..end]
        );
    }
}
