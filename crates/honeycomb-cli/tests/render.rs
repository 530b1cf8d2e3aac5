//! `honeycomb render DIR -o FILE.svg`: a picture that is not blank and whose colours follow
//! the measure.

mod common;

use common::{assert_clean_failure, parse_json, run, TempDir};
use std::collections::HashSet;

fn fills(svg: &str) -> Vec<String> {
    svg.lines()
        .filter(|l| l.starts_with("<polygon"))
        .filter_map(|l| l.split("fill=\"").nth(1).map(|r| r[..7].to_string()))
        .collect()
}

#[test]
fn a_rendered_honeycomb_has_its_walls_a_colour_bar_and_varying_colours() {
    let tmp = TempDir::new("render");
    let dir = tmp.join("h");
    assert!(run([
        "demo",
        "--vertices",
        "300",
        "-q",
        "-o",
        dir.to_str().unwrap()
    ])
    .status
    .success());
    let edges = parse_json(
        &std::fs::read_to_string(dir.join("report.json")).unwrap(),
        "report",
    )["edges"]
        .as_u64()
        .unwrap() as usize;
    for (color, view) in [("delta", "iso"), ("omega", "top"), ("delta", "front")] {
        let out = tmp.join(&format!("{color}-{view}.svg"));
        let r = run([
            "render",
            dir.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--color",
            color,
            "--view",
            view,
            "--width",
            "800",
        ]);
        assert!(r.status.success(), "{}", common::stderr(&r));
        let svg = std::fs::read_to_string(&out).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains(r#"width="800""#), "{color} {view}");
        let f = fills(&svg);
        assert_eq!(f.len(), edges, "one polygon per wall");
        // Not blank: the walls are coloured, in several colours (the measure varies).
        let distinct: HashSet<&String> = f.iter().collect();
        assert!(
            distinct.len() >= 5,
            "{color} {view}: only {} colours",
            distinct.len()
        );
        assert!(svg.matches("class=\"colour-bar\"").count() >= 16);
        assert!(svg.contains(if color == "delta" {
            ">delta<"
        } else {
            ">omega<"
        }));
    }
    let bad = run([
        "render",
        dir.to_str().unwrap(),
        "-o",
        tmp.join("x.png").to_str().unwrap(),
    ]);
    assert_clean_failure(&bad, &["x.png", ".svg"], None);
    let bad = run([
        "render",
        dir.to_str().unwrap(),
        "-o",
        tmp.join("x.svg").to_str().unwrap(),
        "--color",
        "taste",
    ]);
    assert_clean_failure(&bad, &["--color taste"], None);
    assert!(!tmp.join("x.svg").exists());
}

#[test]
fn the_spherical_image_tells_zero_area_cells_from_the_others() {
    let tmp = TempDir::new("render-spherical");
    let (good, rough) = (tmp.join("good"), tmp.join("rough"));
    assert!(run([
        "demo",
        "--vertices",
        "300",
        "-q",
        "-o",
        good.to_str().unwrap()
    ])
    .status
    .success());
    // One damped iteration: axes near the dome's normals, every cell a small non-zero area.
    let r = run([
        "demo",
        "--shape",
        "dome",
        "--vertices",
        "300",
        "--iterations",
        "1",
        "--eps",
        "1000",
        "-q",
        "-o",
        rough.to_str().unwrap(),
    ]);
    assert!(!r.status.success());
    for (dir, class) in [(&good, "zero-area"), (&rough, "violation")] {
        let out = dir.join("sphere.svg");
        let r = run([
            "render",
            dir.to_str().unwrap(),
            "--spherical",
            "--tolerance",
            "1e-5",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(r.status.success(), "{}", common::stderr(&r));
        let svg = std::fs::read_to_string(&out).unwrap();
        let cells = svg.matches("<polygon").count();
        assert!(cells > 100, "{cells} cells drawn");
        assert_eq!(
            svg.matches(&format!("class=\"{class}\"")).count(),
            cells,
            "{class}"
        );
        assert!(svg.contains("Proposition 1 violated"));
    }
}
