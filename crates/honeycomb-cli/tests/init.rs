//! End to end: `honeycomb init` and `honeycomb pipeline` on surface files.

mod common;

use common::{
    assert_clean_failure, bowl_file, number, paraboloid_file, pipeline, read_json,
    read_written_mesh, run, stderr, surface_file, TempDir,
};
use honeycomb::mesh::validate_base_mesh;
use std::path::Path;

#[test]
fn init_writes_a_valid_base_mesh_and_its_report() {
    let tmp = TempDir::new("init");
    let surface = surface_file(&tmp, "cylinder");
    let base = tmp.join("base.obj");
    let report = tmp.join("init.json");
    let out = run([
        "init",
        surface.to_str().unwrap(),
        "--cells",
        "250",
        "-o",
        base.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "-q",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let mesh = read_written_mesh(&base);
    validate_base_mesh(&mesh).unwrap();
    let r = read_json(report.parent().unwrap(), "init.json");
    assert_eq!(number(&r, "vertices") as usize, mesh.vertices.len());
    assert_eq!(number(&r, "cells") as usize, mesh.faces.len());
    assert!(number(&r, "interior_hexagon_share") >= 0.95);
    assert!(number(&r, "edge_length_cv") <= 0.12);
    assert!(number(&r, "distance_to_surface_max") < 1e-9);
    assert!(r["cells_by_sides"]["6"].as_u64().unwrap() > 150);
    assert!(r["flattening"]["conformal_avg"].as_f64().unwrap() < 1.1);
    // --json: the same report on stdout, nothing else; -q: nothing at all.
    let out = run([
        "init",
        surface.to_str().unwrap(),
        "--cells",
        "250",
        "-o",
        base.to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let printed = common::parse_json(&common::stdout(&out), "init --json");
    assert_eq!(printed["cells"], r["cells"]);
    let out = run([
        "init",
        surface.to_str().unwrap(),
        "--cells",
        "250",
        "-o",
        base.to_str().unwrap(),
        "-q",
    ]);
    assert!(out.status.success() && out.stdout.is_empty() && out.stderr.is_empty());
    // The base mesh is ready for optimize.
    let dir = tmp.join("structure");
    let out = run([
        "optimize",
        base.to_str().unwrap(),
        "--surface",
        surface.to_str().unwrap(),
        "-q",
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(number(&read_json(&dir, "report.json"), "omega_max_deg") < 0.01);
}

#[test]
fn pipeline_goes_from_a_surface_to_a_honeycomb() {
    let tmp = TempDir::new("pipeline");
    let surface = surface_file(&tmp, "roof");
    let dir = tmp.join("out");
    pipeline_of(300, &surface, &dir, &["--json"]);
    for file in [
        "initial.obj",
        "init.json",
        "surface.obj",
        "base.obj",
        "offset.obj",
        "walls.obj",
        "report.json",
    ] {
        assert!(dir.join(file).is_file(), "{file} missing");
    }
    let report = read_json(&dir, "report.json");
    assert!(number(&report, "omega_max_deg") < 0.01, "{report}");
    let initial = read_written_mesh(&dir.join("initial.obj"));
    let base = read_written_mesh(&dir.join("base.obj"));
    assert_eq!(initial.faces, base.faces);
}

/// `pipeline SURFACE --cells CELLS FLAGS -o DIR`, which must succeed.
fn pipeline_of(cells: usize, surface: &Path, dir: &Path, flags: &[&str]) -> std::process::Output {
    let cells = cells.to_string();
    let mut args = vec!["pipeline", surface.to_str().unwrap(), "--cells", &cells];
    args.extend_from_slice(flags);
    args.extend(["-o", dir.to_str().unwrap()]);
    let out = run(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    out
}

/// A surface exported with corners of its own per face (an unwelded mesh, as from STL) and some
/// faces wound the other way is read as the welded, oriented one, with a warning for each
/// repair; before, it came apart into one piece per face.
#[test]
fn pipeline_repairs_an_unwelded_surface_wound_both_ways() {
    let tmp = TempDir::new("unwelded");
    let welded = read_written_mesh(&surface_file(&tmp, "wave"));
    let mut text = String::new();
    for f in &welded.faces {
        for &v in f {
            let p = welded.vertices[v];
            text += &format!("v {} {} {}\n", p.x, p.y, p.z);
        }
    }
    let mut next = 1;
    for (i, f) in welded.faces.iter().enumerate() {
        let mut corners: Vec<String> = (next..next + f.len()).map(|k| k.to_string()).collect();
        // Every third face wound the other way: the minority, turned back.
        if i % 3 == 1 {
            corners.reverse();
        }
        text += &format!("f {}\n", corners.join(" "));
        next += f.len();
    }
    let turned = (welded.faces.len() + 1) / 3;
    let surface = tmp.join("unwelded.obj");
    std::fs::write(&surface, text).unwrap();
    let dir = tmp.join("out");
    let out = pipeline_of(300, &surface, &dir, &["-q"]);
    let repeated = next - 1 - welded.vertices.len();
    for warning in [
        format!("{repeated} vertices repeat the position of another"),
        format!("{turned} faces were wound against their neighbours"),
    ] {
        assert!(stderr(&out).contains(&warning), "{}", stderr(&out));
    }
    let report = read_json(&dir, "report.json");
    assert!(number(&report, "omega_max_deg") < 0.01, "{report}");
    let s = read_written_mesh(&dir.join("surface.obj"));
    assert_eq!(s.vertices.len(), welded.vertices.len());
}

/// The same surface gives the same honeycomb, to the last digit, on one core as on two: the
/// factorization's roundoff must not depend on the machine (on a surface where the sheet's
/// folds are chaotic it decides between results). Skipped where `taskset` cannot confine the
/// run to one core.
#[test]
fn a_honeycomb_does_not_depend_on_the_cores_it_was_made_on() {
    let tmp = TempDir::new("pipeline-cores");
    let surface = surface_file(&tmp, "roof");
    let args = |dir: &Path| {
        let surface = surface.to_str().unwrap().to_string();
        let dir = dir.to_str().unwrap().to_string();
        ["pipeline", &surface, "--cells", "1000", "-q", "-o", &dir].map(String::from)
    };
    let one = tmp.join("one-core");
    let confined = std::process::Command::new("taskset")
        .args(["-c", "0", env!("CARGO_BIN_EXE_honeycomb")])
        .args(args(&one))
        .output();
    match confined {
        Ok(out) if out.status.success() => {}
        Ok(out)
            if !one.exists()
                && out.status.code() == Some(1)
                && stderr(&out).contains("taskset") =>
        {
            println!("skipping: taskset cannot confine the run: {}", stderr(&out));
            return;
        }
        Ok(out) => panic!("{}", stderr(&out)),
        Err(e) => {
            println!("skipping: no taskset ({e})");
            return;
        }
    }
    let all = tmp.join("all-cores");
    let out = run(args(&all));
    assert!(out.status.success(), "{}", stderr(&out));
    let report = read_json(&all, "report.json");
    assert_eq!(number(&report, "factor_threads"), 2.0, "{report}");
    for file in ["base.obj", "offset.obj"] {
        let read = |dir: &Path| std::fs::read(dir.join(file)).unwrap();
        assert!(
            read(&one) == read(&all),
            "{file} differs between one core and all"
        );
    }
}

/// Zigzag quads turn the grid to follow S's principal directions unless --align says otherwise
/// (init.json says what the grid follows); the plain honeycomb follows the boundary.
#[test]
fn pipeline_turns_the_grid_of_zigzag_quads_along_the_principal_directions() {
    let tmp = TempDir::new("pipeline_align");
    let saddle = surface_file(&tmp, "saddle");
    for (name, extra, follows) in [
        ("zigzag", &["--quads", "zigzag"][..], "curvature"),
        (
            "zigzag_boundary",
            &["--quads", "zigzag", "--align", "boundary"][..],
            "boundary",
        ),
        ("plain", &[][..], "boundary"),
    ] {
        let dir = tmp.join(name);
        let out = pipeline(&saddle, &dir, extra);
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        assert_eq!(
            read_json(&dir, "init.json")["lattice_follows"],
            follows,
            "{name}"
        );
    }
}

/// init.json says by how much the lattice turns round a hole: 60 degrees round the bowl of the
/// built-in ring, none round a tube (its lattice runs round it unturned), null on a surface
/// with no hole (a saddle) and where the grid is the plan view (`--walls uniform`).
#[test]
fn init_json_says_how_the_lattice_turns_round_a_hole() {
    let tmp = TempDir::new("hole_turn");
    let ring = surface_file(&tmp, "ring");
    let saddle = surface_file(&tmp, "saddle");
    let tube = tmp.join("tube.obj");
    honeycomb::mesh::write_mesh(&tube, &honeycomb::generate::tube(4.0, 6.0, 90)).unwrap();
    for (name, surface, extra, turn) in [
        ("ring", &ring, &[][..], serde_json::json!(60.0)),
        ("tube", &tube, &[][..], serde_json::json!(0.0)),
        ("saddle", &saddle, &[][..], serde_json::Value::Null),
        (
            "uniform",
            &ring,
            &["--walls", "uniform"][..],
            serde_json::Value::Null,
        ),
    ] {
        let dir = tmp.join(name);
        let out = pipeline(surface, &dir, extra);
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        assert_eq!(
            read_json(&dir, "init.json")["hole_turn_deg"],
            turn,
            "{name}"
        );
    }
}

/// Without --flatten, pipeline picks the grid for the walls asked: ARAP for walls across S (the
/// default), the plan view for uniform walls (the dome: a honeycomb with parallel axes from the
/// start), which falls back to ARAP where S folds over seen from above (a vault closing past
/// the vertical), saying so.
#[test]
fn pipeline_picks_the_flattening() {
    let tmp = TempDir::new("pipeline_auto");
    let dome = surface_file(&tmp, "dome");
    let pipeline = |name: &str, surface: &Path, extra: &[&str]| {
        let dir = tmp.join(name);
        let mut args = vec!["pipeline", surface.to_str().unwrap(), "-o"];
        args.push(dir.to_str().unwrap());
        args.extend(extra);
        (run(args), dir)
    };
    let (out, dir) = pipeline("across", &dome, &["--cells", "300"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(read_json(&dir, "init.json")["flattener"], "arap");
    let report = read_json(&dir, "report.json");
    assert_eq!(report["walls"], "across", "{report}");
    assert!(number(&report, "omega_max_deg") < 0.01, "{report}");
    let (out, dir) = pipeline("uniform", &dome, &["--cells", "300", "--walls", "uniform"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(read_json(&dir, "init.json")["flattener"], "project");
    let report = read_json(&dir, "report.json");
    assert_eq!(report["walls"], "uniform", "{report}");
    assert!(number(&report, "omega_max_deg") < 0.01, "{report}");
    // Every axis along S's mean normal: the axes' angles to S's normals are the baseline's.
    let (axis, baseline) = (&report["axis_normal_deg"], &report["parallel_baseline_deg"]);
    assert!(
        (number(axis, "mean") - number(baseline, "mean")).abs() < 0.01,
        "{report}"
    );
    // A vault over 216 degrees of arc, 2 wide.
    let mut obj = String::new();
    let (n, m) = (36, 6);
    for j in 0..=n {
        let a = std::f64::consts::PI * (-0.1 + 1.2 * j as f64 / n as f64);
        for i in 0..=m {
            obj += &format!("v {} {} {}\n", 3.0 * a.cos(), i as f64, 3.0 * a.sin());
        }
    }
    for j in 0..n {
        for i in 0..m {
            let v = |i: usize, j: usize| j * (m + 1) + i + 1;
            obj += &format!(
                "f {} {} {} {}\n",
                v(i, j),
                v(i, j + 1),
                v(i + 1, j + 1),
                v(i + 1, j)
            );
        }
    }
    let vault = tmp.write("vault.obj", &obj);
    let extra = ["--cells", "150", "--w-fair", "0", "--walls", "uniform"];
    let (out, dir) = pipeline("vault", &vault, &extra);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("note: seen along its mean normal"),
        "{}",
        stderr(&out)
    );
    assert_eq!(read_json(&dir, "init.json")["flattener"], "arap");
    assert!(number(&read_json(&dir, "report.json"), "omega_max_deg") < 0.01);
}

/// `init SURFACE EXTRA... -o DIR/base.obj` must fail cleanly, naming every keyword.
fn init_fails(tmp: &TempDir, surface: &Path, extra: &[&str], keywords: &[&str]) {
    let out_dir = tmp.join("out");
    std::fs::create_dir_all(&out_dir).unwrap();
    let base = out_dir.join("base.obj");
    let mut args = vec!["init", surface.to_str().unwrap()];
    args.extend_from_slice(extra);
    args.extend(["-o", base.to_str().unwrap()]);
    assert_clean_failure(&run(&args), keywords, Some(&out_dir));
}

#[test]
fn bad_surfaces_and_options_are_named() {
    let tmp = TempDir::new("init_bad");
    let surface = surface_file(&tmp, "dome");
    let cells = ["--cells", "100"];
    init_fails(&tmp, &surface, &[], &["required"]);
    init_fails(
        &tmp,
        &surface,
        &["--cells", "10", "--edge-length", "1"],
        &["--cells", "--edge-length"],
    );
    init_fails(&tmp, &surface, &["--cells", "0"], &["--cells 0"]);
    init_fails(
        &tmp,
        &surface,
        &["--edge-length", "-2"],
        &["--edge-length -2", "positive"],
    );
    init_fails(
        &tmp,
        &surface,
        &["--edge-length", "1e6"],
        &["no cell", "smaller cells", "surface.obj"],
    );
    init_fails(
        &tmp,
        &surface,
        &["--cells", "100", "--method", "field", "--boundary", "keep"],
        &["--boundary keep", "--method field"],
    );
    init_fails(
        &tmp,
        &surface,
        &["--cells", "100", "--method", "field", "--flatten", "arap"],
        &["--flatten", "--method field"],
    );
    init_fails(
        &tmp,
        &surface,
        &["--cells", "100", "--method", "magic"],
        &["magic", "flatten or field"],
    );
    init_fails(
        &tmp,
        &surface,
        &["--cells", "100", "--boundary", "cut"],
        &["cut", "trim or keep"],
    );
    init_fails(
        &tmp,
        &surface,
        &[
            "--cells",
            "100",
            "--method",
            "field",
            "--align",
            "curvature",
        ],
        &["--align curvature", "--method flatten"],
    );
    let missing = tmp.join("strokes.obj");
    init_fails(
        &tmp,
        &surface,
        &["--cells", "100", "--align", missing.to_str().unwrap()],
        &["--align", "strokes.obj"],
    );
    let no_lines = tmp.write("points.obj", "v 0 0 0\nv 1 0 0\n");
    init_fails(
        &tmp,
        &surface,
        &["--cells", "100", "--align", no_lines.to_str().unwrap()],
        &["points.obj", "no polyline"],
    );
    // Surfaces: closed, empty, missing.
    let cube = tmp.write(
        "cube.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n\
         f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n",
    );
    init_fails(&tmp, &cube, &cells, &["cube.obj", "closed"]);
    let empty = tmp.write("empty.obj", "");
    init_fails(&tmp, &empty, &cells, &["empty.obj"]);
    init_fails(&tmp, &tmp.join("nothing.obj"), &cells, &["nothing.obj"]);
    // Strokes that steer nothing: far off the surface, or of zero length (both methods).
    for (name, text) in [
        ("far.obj", "v 0 0 1000\nv 1 0 1000\nl 1 2\n"),
        ("point.obj", "v 0 0 0\nv 0 0 0\nl 1 2\n"),
    ] {
        let strokes = tmp.write(name, text);
        for method in ["field", "flatten"] {
            init_fails(
                &tmp,
                &surface,
                &[
                    "--cells",
                    "100",
                    "--method",
                    method,
                    "--align",
                    strokes.to_str().unwrap(),
                ],
                &["--align", "stroke"],
            );
        }
    }
    // A report that cannot be written takes the mesh with it: both or neither.
    let nowhere = tmp.join("nowhere/init.json");
    init_fails(
        &tmp,
        &surface,
        &["--cells", "100", "--report", nowhere.to_str().unwrap()],
        &["nowhere/init.json"],
    );
    // An output format nobody reads.
    let out = run([
        "init",
        surface.to_str().unwrap(),
        "--cells",
        "100",
        "-o",
        tmp.join("base.xyz").to_str().unwrap(),
    ]);
    assert_clean_failure(&out, &["base.xyz"], None);
    assert!(!tmp.join("base.xyz").exists());
}

/// A height field over a disk whose rim waves in and out (`lobes` times, by `wave` of the
/// radius 1), as quads on a 90 x 90 grid: a surface whose trimmed boundary cells shear.
fn wavy_disk(height: fn(f64, f64) -> f64, lobes: f64, wave: f64) -> String {
    let n = 90;
    let at = |i: usize| -1.3 + 2.6 * i as f64 / n as f64;
    let mut index = vec![0usize; (n + 1) * (n + 1)];
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (x, y) = ((at(i) + at(i + 1)) / 2.0, (at(j) + at(j + 1)) / 2.0);
            let rim = 1.0 + wave * (lobes * y.atan2(x)).sin();
            if x.hypot(y) <= rim {
                let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
                faces.push(corners.map(|(i, j)| i * (n + 1) + j));
            }
        }
    }
    let mut obj = String::new();
    let mut used = 0;
    for face in &faces {
        for &v in face {
            if index[v] == 0 {
                used += 1;
                index[v] = used;
                let (x, y) = (at(v / (n + 1)), at(v % (n + 1)));
                obj += &format!("v {x} {y} {}\n", height(x, y));
            }
        }
    }
    for face in &faces {
        let [a, b, c, d] = face.map(|v| index[v]);
        obj += &format!("f {a} {b} {c} {d}\n");
    }
    obj
}

/// The guided projection (`--walls free`) of a plan-view grid on a monkey saddle with a wavy
/// rim: with normals per edge the solve breaks a few boundary cells (and `optimize` on the same
/// grid stops with omega far above the tolerance); pipeline drops them and gets a honeycomb.
/// (With cell points, the default, it is a honeycomb at once: checked first.)
#[test]
fn pipeline_drops_broken_boundary_cells_and_tries_again() {
    let tmp = TempDir::new("pipeline_broken");
    let monkey = tmp.write(
        "monkey.obj",
        &wavy_disk(|x, y| 0.8 * (x * x * x - 3.0 * x * y * y), 4.0, 0.3),
    );
    let grid = tmp.join("grid.obj");
    let out = run([
        "init",
        monkey.to_str().unwrap(),
        "--edge-length",
        "0.0928",
        "--flatten",
        "project",
        "-q",
        "-o",
        grid.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let optimize = |dir: &Path, normals: &str| {
        let mut args = vec!["optimize", grid.to_str().unwrap(), "--surface"];
        args.extend([monkey.to_str().unwrap(), "--walls", "free", "-q", "-o"]);
        args.push(dir.to_str().unwrap());
        args.extend((!normals.is_empty()).then_some(normals));
        run(args)
    };
    let cells = tmp.join("cells");
    let out = optimize(&cells, "");
    assert!(out.status.success(), "{}", stderr(&out));
    let report = read_json(&cells, "report.json");
    assert_eq!(report["wall_normals"], "cell_points", "{report}");
    assert!(number(&report, "omega_max_deg") < 0.01, "{report}");
    let plain = tmp.join("plain");
    let out = optimize(&plain, "--per-edge-normals");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    // No honeycomb: the outputs for inspection go beside the directory asked for.
    let failed = tmp.join("plain.failed");
    assert!(number(&read_json(&failed, "report.json"), "omega_max_deg") > 1.0);

    let dir = tmp.join("monkey");
    let out = run([
        "pipeline",
        monkey.to_str().unwrap(),
        "--edge-length",
        "0.0928",
        "--flatten",
        "project",
        "--walls",
        "free",
        "--per-edge-normals",
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("boundary cells"), "{}", stderr(&out));
    let report = read_json(&dir, "report.json");
    assert!(number(&report, "omega_max_deg") < 0.01, "{report}");
    assert!(number(&report, "dropped_boundary_cells") >= 1.0, "{report}");
    assert!(number(&report, "solves") >= 2.0, "{report}");
    // initial.obj is the mesh the kept solve started from: same cells as base.obj, fewer
    // than the grid.
    let initial = read_written_mesh(&dir.join("initial.obj"));
    let base = read_written_mesh(&dir.join("base.obj"));
    assert_eq!(initial.faces, base.faces);
    let cells = read_written_mesh(&grid).faces.len();
    let dropped = number(&report, "dropped_boundary_cells") as usize;
    assert_eq!(base.faces.len() + dropped, cells);
}

/// `--method field`: the field-aligned mesh on a saddle, reported as such, becomes a honeycomb
/// with walls across S through pipeline.
#[test]
fn pipeline_with_the_field_method() {
    let tmp = TempDir::new("pipeline_field");
    let saddle = tmp.write("saddle.obj", &wavy_disk(|x, y| x * x - y * y, 1.0, 0.0));
    let dir = tmp.join("out");
    let out = run([
        "pipeline",
        saddle.to_str().unwrap(),
        "--cells",
        "300",
        "--method",
        "field",
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let init = read_json(&dir, "init.json");
    assert_eq!(init["method"], "field", "{init}");
    assert!(init.get("flattener").is_none(), "{init}");
    assert!(number(&init, "interior_hexagon_share") >= 0.95, "{init}");
    assert!(number(&init, "edge_length_cv") <= 0.12, "{init}");
    let report = read_json(&dir, "report.json");
    assert!(number(&report, "omega_max_deg") < 0.01, "{report}");
    assert_eq!(number(&report, "nonconvex_walls"), 0.0, "{report}");
    assert_eq!(report["walls"], "across", "{report}");
    assert!(number(&report, "iterations_total") <= 40.0, "{report}");
}

/// Options that the made mesh shows to be unusable stop the pipeline before it writes anything.
#[test]
fn pipeline_checks_its_options_before_writing() {
    let tmp = TempDir::new("pipeline_options");
    let surface = surface_file(&tmp, "dome");
    let axes = tmp.write("axes.txt", "0 0 1\n");
    for (extra, keywords) in [
        (
            vec!["--thickness", "1e308"],
            vec!["--thickness 1e308", "mean edge length"],
        ),
        (
            vec!["--parallel", "--w-parallel", "0"],
            vec!["--w-parallel 0"],
        ),
        (
            vec!["--axes", axes.to_str().unwrap()],
            vec!["--axes", "init", "optimize --axes"],
        ),
    ] {
        let dir = tmp.join("out");
        let mut args = vec!["pipeline", surface.to_str().unwrap(), "--cells", "100"];
        args.extend(extra);
        args.extend(["-o", dir.to_str().unwrap()]);
        assert_clean_failure(&run(&args), &keywords, Some(&dir));
    }
}

/// `pipeline` on a steep bowl, `z = 1.7 r^2` over the unit square, where walls across S leave
/// uneven cells (`--no-even-cells`): by default (and with `--even-cells`) report.json's edge
/// cv, measured on the written meshes, meets what a base mesh is asked, and a note says what
/// was traded.
#[test]
fn pipeline_evens_uneven_cells() {
    let tmp = TempDir::new("even_cells");
    let surface = bowl_file(&tmp);
    let cv = |flag: &str| {
        let dir = tmp.join(flag.trim_start_matches('-'));
        pipeline_of(750, &surface, &dir, &[flag]);
        let report = read_json(&dir, "report.json");
        assert!(number(&report, "omega_max_deg") < 0.01, "{report}");
        (number(&report, "edge_length_cv"), report)
    };
    let (fitted, _) = cv("--no-even-cells");
    let (evened, report) = cv("-q");
    assert!(fitted > 0.12 && evened <= 0.1, "{fitted} -> {evened}");
    assert!(
        report["notes"]
            .to_string()
            .contains("the cells were evened"),
        "{report}"
    );
    let (asked, _) = cv("--even-cells");
    assert_eq!(asked, evened);
}

/// On a deep bowl, `z = 4 r^2` over the unit square, walls across S turn a node over on
/// every mesh `pipeline` lays: it ends in one error saying so and naming `--walls free`,
/// without writing anything. Asked for, `--walls free` runs the guided projection with its
/// retries and is no honeycomb either: its error counts the iterations of every try and
/// points to the outputs for inspection, not to more iterations, which its second try has
/// had.
#[test]
fn pipeline_says_when_its_retries_are_spent() {
    let tmp = TempDir::new("deep_bowl");
    let surface = paraboloid_file(&tmp, 4.0, "deep_bowl.obj");
    let dir = tmp.join("across");
    let said = ["turned a node over on each of the 2 meshes", "--walls free"];
    assert_clean_failure(&pipeline(&surface, &dir, &["-q"]), &said, Some(&dir));
    let free = tmp.join("free");
    let out = pipeline(&surface, &free, &["--walls", "free", "-q"]);
    let said = [
        "not a honeycomb",
        "in all, every try counted",
        "for inspection",
    ];
    let line = assert_clean_failure(&out, &said, None);
    assert!(!line.contains("--iterations"), "{line}");
    let report = read_json(&tmp.join("free.failed"), "report.json");
    assert_eq!(report["second_try"], true, "{report}");
}

/// A capping given one iteration on a steep bowl ends with its vertices still off S (the
/// loosest try moves them first): the quads cap the honeycomb as it was, and a note says so
/// (the capping's frame, and its way back, must not hide that the vertices stayed).
#[test]
fn a_capping_out_of_iterations_says_the_honeycomb_is_as_it_was() {
    let tmp = TempDir::new("capping-as-it-was");
    let surface = bowl_file(&tmp);
    let dir = tmp.join("out");
    let flags = ["--quads", "zigzag", "--iterations", "1", "-q"];
    pipeline_of(300, &surface, &dir, &flags);
    let report = read_json(&dir, "report.json");
    let before = number(&report["capping"], "delta_face_max_before");
    let after = number(&report, "delta_face_max");
    assert!(
        (after - before).abs() <= 1e-9 * before,
        "{before} -> {after}"
    );
    assert!(
        report["notes"]
            .to_string()
            .contains("the quads cap the honeycomb as it was"),
        "{report}"
    );
}
