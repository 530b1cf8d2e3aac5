//! `honeycomb edit DIR resize --cell K --by T -o OUT`.

mod common;

use common::{assert_clean_failure, demo, read_json, run, TempDir};

#[test]
fn resize_writes_a_new_honeycomb_and_refuses_nonsense() {
    let tmp = TempDir::new("edit-resize");
    let (src, out) = (tmp.join("src"), tmp.join("out"));
    demo(&src, &[]);
    let ok = run([
        "edit",
        src.to_str().unwrap(),
        "resize",
        "--cell",
        "300",
        "--by",
        "0.2",
        "-q",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(ok.status.success(), "{}", common::stderr(&ok));
    for f in [
        "base.obj",
        "offset.obj",
        "walls.obj",
        "structure.json",
        "report.json",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let report = read_json(&out, "report.json");
    assert_eq!(report["honeycomb"], true, "{report}");
    // Moving walls parallel keeps every angle: omega as exact as the structure it edits.
    let before = read_json(&src, "report.json")["omega_max_deg"]
        .as_f64()
        .unwrap();
    assert!(
        report["omega_max_deg"].as_f64().unwrap() <= before + 1e-9,
        "{report}"
    );
    assert!(report["delta_max"].as_f64().unwrap() < 1e-9, "{report}");
    // Only the six corners of the cell moved off the old structure.
    let moved = std::fs::read_to_string(out.join("base.obj"))
        .unwrap()
        .lines()
        .zip(
            std::fs::read_to_string(src.join("base.obj"))
                .unwrap()
                .lines(),
        )
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(moved, 6);

    let too_far = tmp.join("too-far");
    let bad = run([
        "edit",
        src.to_str().unwrap(),
        "resize",
        "--cell",
        "300",
        "--by",
        "5",
        "-o",
        too_far.to_str().unwrap(),
    ]);
    assert_clean_failure(&bad, &["cell 300", "turns edge"], None);
    assert!(!too_far.exists());
    let bad = run([
        "edit",
        src.to_str().unwrap(),
        "resize",
        "--cell",
        "9999",
        "--by",
        "0.1",
        "-o",
        too_far.to_str().unwrap(),
    ]);
    assert_clean_failure(&bad, &["cell 9999", "does not exist"], None);
    let bad = run([
        "edit",
        src.to_str().unwrap(),
        "resize",
        "--cell",
        "3",
        "--by",
        "0.1",
    ]);
    assert_clean_failure(&bad, &["-o"], None);
}

#[test]
fn subdivide_writes_four_times_the_cells() {
    let tmp = TempDir::new("edit-subdivide");
    let (src, out) = (tmp.join("src"), tmp.join("out"));
    demo(&src, &["--vertices", "600"]);
    let ok = run([
        "edit",
        src.to_str().unwrap(),
        "subdivide",
        "-q",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(ok.status.success(), "{}", common::stderr(&ok));
    let read = |d: &std::path::Path| read_json(d, "report.json");
    let (before, after) = (read(&src), read(&out));
    let ratio = after["faces"].as_f64().unwrap() / before["faces"].as_f64().unwrap();
    assert!(ratio > 3.5 && ratio < 4.0, "{ratio}");
    assert_eq!(after["honeycomb"], true);
    let bad = run([
        "edit",
        src.to_str().unwrap(),
        "subdivide",
        "--shrink",
        "2",
        "-o",
        tmp.join("x").to_str().unwrap(),
    ]);
    assert_clean_failure(&bad, &["shrink 2"], None);
}

#[test]
fn reciprocal_adds_a_triangle_per_node_and_reports_t_junctions() {
    let tmp = TempDir::new("edit-reciprocal");
    let (src, out) = (tmp.join("src"), tmp.join("out"));
    demo(&src, &["--vertices", "300"]);
    let ok = run([
        "edit",
        src.to_str().unwrap(),
        "reciprocal",
        "-q",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(ok.status.success(), "{}", common::stderr(&ok));
    let read = |d: &std::path::Path| read_json(d, "report.json");
    let (before, after) = (read(&src), read(&out));
    let trivalent = before["valence_histogram"]["3"].as_u64().unwrap();
    assert_eq!(
        after["faces"].as_u64().unwrap(),
        before["faces"].as_u64().unwrap() + trivalent
    );
    assert!(
        after["t_junctions"].as_u64().unwrap() >= trivalent,
        "{after}"
    );
    assert_eq!(after["honeycomb"], true, "{after}");
    assert!(after["delta_max"].as_f64().unwrap() < 1e-9);
    let bad = run([
        "edit",
        src.to_str().unwrap(),
        "reciprocal",
        "--by",
        "-1",
        "-o",
        tmp.join("x").to_str().unwrap(),
    ]);
    assert_clean_failure(&bad, &["reciprocal by -1"], None);
}
