//! How the walls stand on S, end to end: `--walls` on pipeline, optimize and serve, the report's
//! keys, the printed row, `render --color axis`, `bench --roofs` and the demo's spherical image.

mod common;

use common::*;
use std::path::{Path, PathBuf};

/// report.json says how the walls stand, measured from the written meshes; the printed row
/// ends with the axes' mean lean; across leans less than uniform on a dome, and vertical walls
/// (0,0,1) are uniform walls seen from above.
#[test]
fn pipeline_reports_how_the_walls_stand() {
    let tmp = TempDir::new("walls-report");
    let dome = surface_file(&tmp, "dome");
    let mut leans = Vec::new();
    for (name, walls) in [
        ("across", None),
        ("uniform", Some("uniform")),
        ("up", Some("0,0,1")),
    ] {
        let dir = tmp.join(name);
        let extra: Vec<&str> = walls.map(|w| vec!["--walls", w]).unwrap_or_default();
        let out = pipeline(&dome, &dir, &extra);
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        let report = read_json(&dir, "report.json");
        for key in ["mean", "p95", "max"] {
            assert!(
                number(&report["axis_normal_deg"], key).is_finite(),
                "{report}"
            );
        }
        for key in ["mean", "p95"] {
            assert!(
                number(&report["parallel_baseline_deg"], key) > 1.0,
                "{report}"
            );
        }
        assert!(number(&report, "edge_length_cv") < 0.25, "{report}");
        assert!(number(&report, "iterations_total") >= number(&report, "iterations"));
        let axis = number(&report["axis_normal_deg"], "mean");
        // The printed row's last column is the axes' mean lean.
        let text = stdout(&out);
        let lines: Vec<&str> = text.lines().collect();
        let header = lines.iter().position(|l| l.contains("omega_max")).unwrap();
        let row = lines[header + 1];
        let last: f64 = row.split_whitespace().last().unwrap().parse().unwrap();
        assert!((last - axis).abs() < 0.051, "{row} against {axis}");
        leans.push((report["walls"].clone(), axis));
    }
    assert_eq!(leans[0].0, "across");
    assert_eq!(leans[1].0, "uniform");
    assert_eq!(leans[2].0, serde_json::json!([0.0, 0.0, 1.0]));
    assert!(leans[0].1 < 0.65 * leans[1].1, "{leans:?}");
    assert!((leans[1].1 - leans[2].1).abs() < 0.5, "{leans:?}");
}

/// Bad `--walls` values and combinations get one clear error each, before anything is written.
#[test]
fn bad_walls_are_refused() {
    let tmp = TempDir::new("walls-bad");
    let dome = surface_file(&tmp, "dome");
    let dir = tmp.join("out");
    for (walls, keywords) in [
        (
            "sideways",
            vec!["--walls", "sideways", "across, uniform, free"],
        ),
        ("0,0,0", vec!["--walls", "no length"]),
        ("1,2", vec!["--walls", "three numbers"]),
        ("nan,0,1", vec!["--walls"]),
    ] {
        let out = pipeline(&dome, &dir, &["--walls", walls]);
        assert_clean_failure(&out, &keywords, Some(&dir));
    }
    let out = pipeline(&dome, &dir, &["--walls", "uniform", "--parallel"]);
    assert_clean_failure(&out, &["--walls", "--parallel"], Some(&dir));
    let out = run(["serve", "--walls", "uniform", "--port", "0"]);
    assert_clean_failure(&out, &["--walls", "design surface"], None);
}

/// optimize stands a designer's base mesh's walls as asked, keeping every cell.
#[test]
fn optimize_takes_walls_too() {
    let tmp = TempDir::new("walls-optimize");
    let src = tmp.join("src");
    demo(&src, &["--vertices", "400", "--shape", "dome"]);
    let (base, surface) = (src.join("input_base.obj"), src.join("surface.obj"));
    let cells = read_written_mesh(&base).faces.len();
    for walls in ["across", "free", "uniform", "0.1,0,1"] {
        let dir = tmp.join(walls);
        let out = run([
            "optimize",
            base.to_str().unwrap(),
            "--surface",
            surface.to_str().unwrap(),
            "--walls",
            walls,
            "-q",
            "-o",
            dir.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{walls}: {}", stderr(&out));
        let report = read_json(&dir, "report.json");
        assert_eq!(number(&report, "faces") as usize, cells, "{walls}");
        assert!(number(&report, "omega_max_deg") < 0.01, "{walls}: {report}");
    }
}

/// `render --color axis` colours each wall by its nodes' lean from S's normal, and needs S.
#[test]
fn render_colours_walls_by_their_lean() {
    let tmp = TempDir::new("walls-render");
    let dir = tmp.join("demo");
    demo(&dir, &["--vertices", "300"]);
    let svg = tmp.join("axis.svg");
    let out = run([
        "render",
        dir.to_str().unwrap(),
        "--color",
        "axis",
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.contains(">axis (deg)<") && text.contains("walls: mean "),
        "legend missing"
    );
    std::fs::remove_file(dir.join("surface.obj")).unwrap();
    let out = run([
        "render",
        dir.to_str().unwrap(),
        "--color",
        "axis",
        "-o",
        tmp.join("again.svg").to_str().unwrap(),
    ]);
    assert_clean_failure(&out, &["--color axis", "surface"], None);
}

/// The demo's walls stand across its saddle: its node axes are spread over a strip of the
/// sphere (Property 2), not gathered in one point as parallel axes would be.
#[test]
fn the_demo_stands_its_walls_across_the_saddle() {
    let tmp = TempDir::new("walls-demo");
    let dir = tmp.join("demo");
    demo(&dir, &[]);
    let report = read_json(&dir, "report.json");
    assert_eq!(report["walls"], "across");
    let (axis, parallel) = (
        number(&report["axis_normal_deg"], "mean"),
        number(&report["parallel_baseline_deg"], "mean"),
    );
    assert!(axis < 0.7 * parallel, "{axis} against {parallel}");
    let structure = read_json(&dir, "structure.json");
    let axes: Vec<[f64; 3]> = serde_json::from_value(structure["node_axes"].clone()).unwrap();
    let (along, across) = principal_spreads_deg(&axes);
    assert!(along > 10.0, "{along} {across}");
    assert!(across < 0.6 * along, "{along} {across}");
}

/// The spreads (degrees) of unit vectors about their mean, along the direction they spread
/// most and across it.
fn principal_spreads_deg(axes: &[[f64; 3]]) -> (f64, f64) {
    let n = axes.len() as f64;
    let mean: Vec<f64> = (0..3)
        .map(|k| axes.iter().map(|a| a[k]).sum::<f64>() / n)
        .collect();
    let norm = mean.iter().map(|m| m * m).sum::<f64>().sqrt();
    let m: Vec<f64> = mean.iter().map(|x| x / norm).collect();
    // A frame of the tangent plane at the mean.
    let helper = if m[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let d: f64 = (0..3).map(|k| helper[k] * m[k]).sum();
    let t1: Vec<f64> = (0..3).map(|k| helper[k] - d * m[k]).collect();
    let l = t1.iter().map(|x| x * x).sum::<f64>().sqrt();
    let t1: Vec<f64> = t1.iter().map(|x| x / l).collect();
    let t2 = [
        m[1] * t1[2] - m[2] * t1[1],
        m[2] * t1[0] - m[0] * t1[2],
        m[0] * t1[1] - m[1] * t1[0],
    ];
    let (mut xx, mut yy, mut xy) = (0.0, 0.0, 0.0);
    for a in axes {
        let (x, y): (f64, f64) = (
            (0..3).map(|k| a[k] * t1[k]).sum(),
            (0..3).map(|k| a[k] * t2[k]).sum(),
        );
        xx += x * x / n;
        yy += y * y / n;
        xy += x * y / n;
    }
    let half = 0.5 * (xx + yy);
    let root = (0.25 * (xx - yy) * (xx - yy) + xy * xy).sqrt();
    let deg = |v: f64| v.max(0.0).sqrt().asin().to_degrees();
    (deg(half + root), deg(half - root))
}

/// The rows of `bench --roofs DIR --cells 200 --json EXTRA`.
fn bench_rows(roofs: &Path, extra: &[&str]) -> Vec<serde_json::Value> {
    let mut args = vec![
        "bench",
        "--roofs",
        roofs.to_str().unwrap(),
        "--cells",
        "200",
        "--json",
    ];
    args.extend_from_slice(extra);
    let out = run(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    stdout(&out)
        .lines()
        .map(|l| parse_json(l, "a bench row"))
        .collect()
}

/// A folder `roofs` in `tmp` holding the dome as `dome.obj`.
fn roofs_with_dome(tmp: &TempDir) -> PathBuf {
    let roofs = tmp.join("roofs");
    std::fs::create_dir_all(&roofs).unwrap();
    std::fs::copy(surface_file(tmp, "dome"), roofs.join("dome.obj")).unwrap();
    roofs
}

/// The `variant` of each bench row, in order.
fn variant_names(rows: &[serde_json::Value]) -> Vec<&str> {
    rows.iter().filter_map(|r| r["variant"].as_str()).collect()
}

/// `bench --roofs DIR` has a row per surface in DIR (a base mesh skipped with its reason) and
/// one JSON object per row with `--json`; without the default folder it says so and goes on.
#[test]
fn bench_roofs_has_a_row_per_surface() {
    let tmp = TempDir::new("walls-bench");
    let roofs = roofs_with_dome(&tmp);
    let src = tmp.join("src");
    demo(&src, &["--vertices", "200"]);
    std::fs::copy(src.join("input_base.obj"), roofs.join("hexes.obj")).unwrap();
    let rows = bench_rows(&roofs, &[]);
    assert_eq!(rows.len(), 2, "{rows:?}");
    let dome_row = rows.iter().find(|r| r["surface"] == "dome.obj").unwrap();
    assert_eq!(dome_row["status"], "ok", "{dome_row}");
    for key in [
        "cells",
        "seconds",
        "iterations_total",
        "omega_max_deg",
        "delta_max",
        "axis_normal_mean_deg",
        "axis_normal_p95_deg",
        "parallel_mean_deg",
        "parallel_p95_deg",
        "edge_length_cv",
    ] {
        assert!(number(dome_row, key).is_finite(), "{key}: {dome_row}");
    }
    let hexes = rows.iter().find(|r| r["surface"] == "hexes.obj").unwrap();
    assert_eq!(hexes["status"], "skipped", "{hexes}");
    // The dome's cells are even already: evening (the default) leaves its row as it was, but
    // for the few steps that place the vertices on the walls its provisional fit goes on to.
    let fitted = bench_rows(&roofs, &["--no-even-cells"]);
    let fitted = fitted.iter().find(|r| r["surface"] == "dome.obj").unwrap();
    assert!(number(dome_row, "edge_length_cv") < 0.12, "{dome_row}");
    assert_eq!(fitted["cells"], dome_row["cells"]);
    let spent = number(dome_row, "iterations_total") - number(fitted, "iterations_total");
    assert!((1.0..=4.0).contains(&spent), "{spent}");
    for (key, within) in [("edge_length_cv", 0.005), ("axis_normal_mean_deg", 0.1)] {
        let (a, b) = (number(fitted, key), number(dome_row, key));
        assert!((a - b).abs() <= within, "{key}: {a} -> {b}");
    }
    let table = run([
        "bench",
        "--roofs",
        roofs.to_str().unwrap(),
        "--cells",
        "200",
    ]);
    assert!(table.status.success());
    assert!(stdout(&table).lines().next().unwrap().contains("axis"));
}

/// `bench --roofs DIR --variants` has a row per surface and variant; a quad row gives the
/// planarity before and after capping and the capping's own iterations, within the total.
#[test]
fn bench_roofs_variants_has_a_row_per_variant() {
    let tmp = TempDir::new("walls-bench-variants");
    let roofs = roofs_with_dome(&tmp);
    let rows = bench_rows(&roofs, &["--variants"]);
    let variants = variant_names(&rows);
    assert_eq!(
        variants,
        [
            "zigzag",
            "alternating",
            "flattest",
            "reshaped 0.3",
            "parallel",
            "sun 30/225",
            "sun 60/45"
        ]
    );
    for row in rows.iter().take(4) {
        assert_eq!(row["status"], "ok", "{row}");
        let capping = number(row, "capping_iterations");
        assert!(
            capping >= 1.0 && capping < number(row, "iterations_total"),
            "{row}"
        );
        assert!(number(row, "delta_face_max") <= number(row, "delta_face_max_before"));
    }
}

/// `bench --roofs DIR --variants --suns` has twelve sun rows (30, 45 and 60 degrees high from
/// the four quarters) in place of the two, each with its light shares, and the table counts
/// the suns met per surface; `--suns` alone is refused.
#[test]
fn bench_roofs_suns_has_twelve_sun_rows() {
    let tmp = TempDir::new("walls-bench-suns");
    let roofs = roofs_with_dome(&tmp);
    let rows = bench_rows(&roofs, &["--variants", "--suns"]);
    let variants = variant_names(&rows);
    let mut expected = vec![
        "zigzag",
        "alternating",
        "flattest",
        "reshaped 0.3",
        "parallel",
    ];
    let suns: Vec<String> = [30, 45, 60]
        .iter()
        .flat_map(|e| [0, 90, 180, 270].map(|a| format!("sun {e}/{a}")))
        .collect();
    expected.extend(suns.iter().map(String::as_str));
    assert_eq!(variants, expected);
    let mut met = 0;
    for row in &rows[5..] {
        let (before, after) = (
            number(row, "light_share_before"),
            number(row, "light_share_after"),
        );
        assert!(
            (0.0..=1.0).contains(&before) && (0.0..=1.0).contains(&after),
            "{row}"
        );
        let halved = after <= 0.5 * before || after < 0.005;
        assert_eq!(row["status"] == "ok", halved, "{row}");
        met += usize::from(row["status"] == "ok");
    }
    let table = run([
        "bench",
        "--roofs",
        roofs.to_str().unwrap(),
        "--cells",
        "200",
        "--variants",
        "--suns",
    ]);
    assert!(table.status.success(), "{}", stderr(&table));
    let count = stdout(&table)
        .lines()
        .find(|l| l.contains("suns met"))
        .map(|l| l.split_whitespace().last().unwrap().to_string());
    assert_eq!(count, Some(format!("{met}/12")));
    let alone = run(["bench", "--roofs", roofs.to_str().unwrap(), "--suns"]);
    assert_eq!(alone.status.code(), Some(2), "{}", stderr(&alone));
    assert!(stderr(&alone).contains("--variants"), "{}", stderr(&alone));
}

/// `pipeline --parallel` writes M and M' on walls across S with their edges parallel, as the
/// written meshes show; `--walls free` is the paper's simultaneous solve instead.
#[test]
fn pipeline_pairs_parallel_meshes_on_walls_across() {
    let tmp = TempDir::new("walls-parallel");
    let dome = surface_file(&tmp, "dome");
    let dir = tmp.join("paired");
    let out = pipeline(&dome, &dir, &["--parallel"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = read_json(&dir, "report.json");
    assert_eq!(report["walls"], "across");
    let m = read_written_mesh(&dir.join("base.obj"));
    let offset = read_written_mesh(&dir.join("offset.obj"));
    let mut beta_max = 0.0f64;
    for face in &m.faces {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            let (e, twin) = (
                m.vertices[b] - m.vertices[a],
                offset.vertices[b] - offset.vertices[a],
            );
            beta_max = beta_max.max(e.cross(twin).norm().atan2(e.dot(twin)).to_degrees());
        }
    }
    assert!(beta_max <= 0.5, "beta_max {beta_max}");
    assert!(
        (number(&report, "beta_max_deg") - beta_max).abs() < 1e-6,
        "{report}"
    );
    assert!(
        number(&report["axis_normal_deg"], "mean")
            < number(&report["parallel_baseline_deg"], "mean")
    );
    let free = tmp.join("free");
    let out = pipeline(&dome, &free, &["--parallel", "--walls", "free"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(read_json(&free, "report.json")["walls"], "free");
}

/// `pipeline --light` from a surface alone: walls across S turned across the light, as deep
/// as 1.5 mean edge lengths, every wall planar (measured on the written walls.obj), half the
/// light or less let through; other walls are refused by name.
#[test]
fn pipeline_shades_with_walls_turned_across_the_light() {
    let tmp = TempDir::new("walls-light");
    let dome = surface_file(&tmp, "dome");
    let dir = tmp.join("shaded");
    let out = pipeline(&dome, &dir, &["--light", "0.5,0.3,-0.8"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(String::from_utf8_lossy(&out.stdout).contains("light share"));
    let report = read_json(&dir, "report.json");
    assert_eq!(report["walls"], "across");
    let shading = &report["shading"];
    assert_eq!(shading["met"], true);
    let light = &shading["light"];
    assert!(
        number(light, "after") <= 0.5 * number(light, "before"),
        "{light}"
    );
    let walls = read_written_mesh(&dir.join("walls.obj"));
    let base = read_written_mesh(&dir.join("base.obj"));
    let unit = base.mean_edge_length();
    let mut deepest = 0.0f64;
    for wall in &walls.faces {
        let p: Vec<_> = wall.iter().map(|&v| walls.vertices[v]).collect();
        let normal = (p[2] - p[0]).cross(p[3] - p[1]).normalized();
        let off = (p[1] - p[0])
            .dot(normal)
            .abs()
            .max((p[3] - p[0]).dot(normal).abs());
        assert!(off < 1e-6 * unit, "wall off its plane by {off}");
        deepest = deepest.max((p[3] - p[0]).norm());
    }
    assert!((deepest / unit - 1.5).abs() < 0.05, "{deepest} / {unit}");
    let refused = pipeline(
        &dome,
        &tmp.join("free"),
        &["--light", "0,0,-1", "--walls", "free"],
    );
    assert!(!refused.status.success());
    assert!(stderr(&refused).contains("--walls"), "{}", stderr(&refused));
}
