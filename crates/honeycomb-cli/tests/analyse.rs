//! `honeycomb analyse DIR`: the spherical image of a written structure.

mod common;

use common::{assert_clean_failure, demo, read_json, run, shared_data, stdout, TempDir};

fn analysis(dir: &std::path::Path) -> serde_json::Value {
    read_json(dir, "analysis.json")
}

#[test]
fn an_optimized_honeycomb_satisfies_proposition_1_and_an_unoptimized_mesh_does_not() {
    let tmp = TempDir::new("analyse-demo");
    let good = tmp.join("good");
    demo(&good, &["--shape", "dome"]);
    let out = run(["analyse", good.to_str().unwrap()]);
    assert!(out.status.success(), "{}", common::stderr(&out));
    assert!(
        stdout(&out).contains("violating Proposition 1"),
        "{}",
        stdout(&out)
    );
    let a = analysis(&good);
    let cells = a["cells"].as_u64().unwrap();
    assert!(cells > 700, "{a}");
    assert_eq!(
        a["proposition1_violations"].as_array().unwrap().len(),
        0,
        "{a}"
    );
    let counted: u64 = a["histogram"]
        .as_object()
        .unwrap()
        .values()
        .map(|n| n.as_u64().unwrap())
        .sum();
    assert_eq!(counted, cells);
    assert!(
        a["max_deviation_from_multiple"].as_f64().unwrap() < 1e-6,
        "{a}"
    );
    // The image itself: one vertex per node axis on the unit sphere, one face per cell.
    let obj = std::fs::read_to_string(good.join("spherical_image.obj")).unwrap();
    assert_eq!(
        obj.lines().filter(|l| l.starts_with("f ")).count() as u64,
        cells
    );
    for line in obj.lines().filter(|l| l.starts_with("v ")) {
        let r: f64 = line[2..]
            .split_whitespace()
            .map(|x| x.parse::<f64>().unwrap().powi(2))
            .sum::<f64>()
            .sqrt();
        assert!((r - 1.0).abs() < 1e-9, "{line}");
    }

    // One damped iteration leaves the walls near the dome's normals: every cell's image then
    // encloses a little Gaussian curvature, which no honeycomb cell can (0 < area < pi/3).
    let rough = tmp.join("rough");
    let out = run([
        "demo",
        "--shape",
        "dome",
        "--walls",
        "free",
        "--iterations",
        "1",
        "--eps",
        "1000",
        "-q",
        "-o",
        rough.to_str().unwrap(),
    ]);
    assert!(
        !out.status.success(),
        "one damped iteration should not give a honeycomb"
    );
    // A result that fails its verdict is written beside DIR, for inspection.
    let rough = tmp.join("rough.failed");
    let out = run([
        "analyse",
        rough.to_str().unwrap(),
        "--tolerance",
        "1e-5",
        "-q",
    ]);
    assert!(out.status.success());
    let a = analysis(&rough);
    assert!(
        a["proposition1_violations"].as_array().unwrap().len() as u64 > cells / 2,
        "{a}"
    );
    // Axes near a dome's normals: every cell's image is a small round patch, not curve-like.
    assert!(a["curve_likeness"].as_f64().unwrap() < 0.3, "{a}");
}

#[test]
fn optimized_saddle_and_dome_have_no_proposition_1_violation() {
    let tmp = TempDir::new("analyse-shapes");
    for shape in ["saddle", "dome"] {
        let dir = tmp.join(shape);
        demo(&dir, &["--shape", shape]);
        let out = run(["analyse", dir.to_str().unwrap()]);
        assert!(out.status.success());
        // The report says what the image is like: here every cell's axes coincide (the demo's
        // honeycombs are vertical extrusions), which the summary states.
        assert!(stdout(&out).contains("image"), "{}", stdout(&out));
        let a = analysis(&dir);
        assert_eq!(
            a["proposition1_violations"].as_array().unwrap().len(),
            0,
            "{shape}"
        );
        assert!(a.get("curve_likeness").is_some(), "{shape}");
    }
}

#[test]
fn missing_or_broken_structure_fails_cleanly() {
    let tmp = TempDir::new("analyse-bad");
    let out = run(["analyse", tmp.join("nothing").to_str().unwrap()]);
    assert_clean_failure(&out, &["structure.json"], None);
    let dir = tmp.join("broken");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("structure.json"), "{\"vertices\": [[0, 0").unwrap();
    let out = run(["analyse", dir.to_str().unwrap()]);
    assert_clean_failure(&out, &["structure.json", "not a structure.json"], None);
    assert!(!dir.join("analysis.json").exists());
    let out = run(["analyse", dir.to_str().unwrap(), "--tolerance", "-1"]);
    assert_clean_failure(&out, &["--tolerance"], None);
}

#[test]
fn hexagonalminimal_has_a_zero_area_image() {
    let Some(data) = shared_data() else {
        println!("skipping: ../shared/data not found");
        return;
    };
    let tmp = TempDir::new("analyse-hexmin");
    let dir = tmp.join("out");
    let input = data.join("hexagonalminimal_plusgauss.off");
    let out = run([
        "optimize",
        input.to_str().unwrap(),
        "--eps",
        "1",
        "-q",
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", common::stderr(&out));
    let out = run(["analyse", dir.to_str().unwrap(), "-q"]);
    assert!(out.status.success());
    let a = analysis(&dir);
    println!("{a}");
    // As in the paper's Figure 4: hexagons whose axes are close together have zero area.
    assert_eq!(
        a["proposition1_violations"].as_array().unwrap().len(),
        0,
        "{a}"
    );
    assert!(a["zero_area_share"].as_f64().unwrap() > 0.9, "{a}");
    // Property 2: the image is curve-like (the cells' images are thin zigzags).
    assert!(a["curve_likeness"].as_f64().unwrap() > 0.7, "{a}");
}
