//! `honeycomb render DIR -o FILE.svg`: a picture that is not blank and whose colours follow
//! the measure.

mod common;

use common::{assert_clean_failure, demo, quad_delta, read_json, read_written_mesh, run, TempDir};
use honeycomb::error::rounded;
use std::collections::HashSet;

fn fills(svg: &str) -> Vec<String> {
    svg.lines()
        .filter(|l| l.starts_with("<polygon"))
        .filter_map(|l| l.split("fill=\"").nth(1).map(|r| r[..7].to_string()))
        .collect()
}

/// The calm ramp's ends and the red of walls over the tolerance.
const PALE: &str = "#e2e8ee";
const RED: &str = "#d62728";

/// Whether a fill lies on the calm ramp (between pale and the steady blue, channel by channel).
fn calm(fill: &str) -> bool {
    let channel = |k: usize| u8::from_str_radix(&fill[1 + 2 * k..3 + 2 * k], 16).unwrap();
    let (r, g, b) = (channel(0), channel(1), channel(2));
    (49..=226).contains(&r) && (104..=232).contains(&g) && (166..=238).contains(&b) && b >= r
}

#[test]
fn a_rendered_honeycomb_has_its_walls_a_title_a_verdict_and_a_legend() {
    let tmp = TempDir::new("render");
    let dir = tmp.join("h");
    demo(&dir, &["--vertices", "300"]);
    let edges = read_json(&dir, "report.json")["edges"].as_u64().unwrap() as usize;
    for (color, view) in [
        ("delta", "auto"),
        ("omega", "top"),
        ("delta", "front"),
        ("closeness", "side"),
        ("axis", "iso"),
    ] {
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
        assert!(
            common::stdout(&r).starts_with(&format!("wrote {}", out.display())),
            "{}",
            common::stdout(&r)
        );
        let svg = std::fs::read_to_string(&out).unwrap();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains(r#"width="800""#), "{color} {view}");
        let f = fills(&svg);
        assert_eq!(
            svg.matches("class=\"wall\"").count(),
            edges,
            "one polygon per wall"
        );
        assert!(svg.matches("class=\"colour-bar\"").count() >= 16);
        // The title, the measure's heading and the triad and scale bar.
        assert!(svg.contains(&format!(">h: {color}<")), "{color}");
        for text in [">X<", ">Y<", ">Z<", " model units<"] {
            assert!(svg.contains(text), "{color}: {text}");
        }
        if color == "axis" {
            // A design measure: the full colour map over round ticks, mean and largest told.
            assert!(svg.contains(">axis (deg)<") && svg.contains("walls: mean "));
            let distinct: HashSet<&String> = f.iter().collect();
            assert!(distinct.len() >= 5, "only {} colours", distinct.len());
            assert!(svg.contains(">0<") && svg.contains(">10<"), "ticks");
        } else {
            // An exact honeycomb is judged against the tolerance and looks calm: every wall
            // on the pale end of one ramp, none red.
            assert!(
                svg.contains(&format!(">all {edges} walls within ")),
                "{color}: no verdict"
            );
            assert!(f.iter().all(|c| calm(c)), "{color}: {f:?}");
            assert!(svg.contains("over tolerance"));
            if color != "closeness" {
                assert!(
                    f.iter().filter(|c| c.as_str() == PALE).count() > edges / 2,
                    "{color}"
                );
            }
        }
    }
    let bad = run([
        "render",
        dir.to_str().unwrap(),
        "-o",
        tmp.join("x.gif").to_str().unwrap(),
    ]);
    assert_clean_failure(&bad, &["x.gif", ".svg or .png"], None);
    let bad = run([
        "render",
        dir.to_str().unwrap(),
        "-o",
        tmp.join("x.svg").to_str().unwrap(),
        "--color",
        "taste",
    ]);
    assert_clean_failure(&bad, &["--color taste"], None);
    // Closeness needs the design surface; this directory has none once surface.obj is gone.
    std::fs::remove_file(dir.join("surface.obj")).unwrap();
    let bad = run([
        "render",
        dir.to_str().unwrap(),
        "-o",
        tmp.join("x.svg").to_str().unwrap(),
        "--color",
        "closeness",
    ]);
    assert_clean_failure(&bad, &["closeness", "--surface"], None);
    assert!(!tmp.join("x.svg").exists());
}

#[test]
fn the_spherical_image_tells_zero_area_cells_from_the_others() {
    let tmp = TempDir::new("render-spherical");
    let (good, rough) = (tmp.join("good"), tmp.join("rough"));
    demo(&good, &["--vertices", "300"]);
    // One damped iteration: axes near the dome's normals, every cell a small non-zero area.
    let r = run([
        "demo",
        "--shape",
        "dome",
        "--vertices",
        "300",
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
    assert!(!r.status.success());
    // A result that fails its verdict is written beside DIR, for inspection.
    let rough = tmp.join("rough.failed");
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
        assert!(
            svg.contains("violations (0 &lt; |area| &lt; pi/3)"),
            "legend"
        );
        assert!(svg.contains("equal-area projection"));
    }
    // A honeycomb that fails its tolerance says so, and paints its bad walls red.
    let out = rough.join("omega.svg");
    let r = run([
        "render",
        rough.to_str().unwrap(),
        "--color",
        "omega",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", common::stderr(&r));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains(" walls over 0.1 deg (worst "), "verdict");
    assert!(fills(&svg).iter().any(|c| c == RED), "no red wall");
    // Parallel axes: the image is one point, and the picture says so.
    let parallel = tmp.join("parallel");
    demo(&parallel, &["--vertices", "300", "--walls", "0,0,1"]);
    let out = parallel.join("sphere.svg");
    let r = run([
        "render",
        parallel.to_str().unwrap(),
        "--spherical",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", common::stderr(&r));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(
        svg.contains("node axes parallel: the image is one point"),
        "{svg}"
    );
    // Walls coloured by the spherical area of their cells vary where the areas do.
    let out = rough.join("area.svg");
    let r = run([
        "render",
        rough.to_str().unwrap(),
        "--color",
        "area",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", common::stderr(&r));
    let svg = std::fs::read_to_string(&out).unwrap();
    let distinct: HashSet<String> = fills(&svg).into_iter().collect();
    assert!(distinct.len() >= 5, "only {} colours", distinct.len());
}

/// Width, height and RGB pixels of a PNG.
fn decode_png(bytes: &[u8]) -> (u32, u32, Vec<[u8; 3]>) {
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let pixels = buf[..info.buffer_size()]
        .chunks(channels)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    (info.width, info.height, pixels)
}

#[test]
fn png_pictures_have_the_asked_size_colour_and_text() {
    let tmp = TempDir::new("render-png");
    let dir = tmp.join("h");
    demo(&dir, &["--vertices", "300"]);
    for extra in [&["--color", "axis"][..], &["--spherical"][..]] {
        let out = tmp.join("p.png");
        let mut args = vec![
            "render",
            dir.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--width",
            "640",
            "-q",
        ];
        args.extend_from_slice(extra);
        let r = run(&args);
        assert!(r.status.success(), "{}", common::stderr(&r));
        assert!(common::stdout(&r).is_empty(), "--quiet");
        let bytes = std::fs::read(&out).unwrap();
        let (w, h, pixels) = decode_png(&bytes);
        assert_eq!(w, 640);
        assert!(h >= 300, "{h}");
        // Compressed: far smaller than its raw pixels.
        assert!(bytes.len() < pixels.len(), "{} bytes", bytes.len());
        let white = pixels.iter().filter(|p| **p == [255, 255, 255]).count();
        let colours: HashSet<[u8; 3]> = pixels.iter().copied().collect();
        println!(
            "{extra:?}: {w}x{h}, {} bytes, {} colours, {:.0}% white",
            bytes.len(),
            colours.len(),
            100.0 * white as f64 / pixels.len() as f64
        );
        // The title is drawn: dark ink where it stands (top left), none in the empty corner
        // to its right above the drawing.
        let ink = |x0: u32, x1: u32, y0: u32, y1: u32| {
            (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| {
                    let p = pixels[(y * w + x) as usize];
                    p.iter().all(|&c| c < 110)
                })
                .count()
        };
        assert!(ink(20, 200, 10, 32) > 80, "no title ink");
        assert!(ink(20, 300, 36, 52) > 40, "no second line");
        if extra[0] == "--spherical" {
            let outline = pixels
                .iter()
                .filter(|p| p[2] > p[0] + 40 && p[2] > 150)
                .count();
            assert!(outline > 50, "only {outline} outline pixels");
        } else {
            assert!(white < pixels.len() * 97 / 100, "nearly blank");
            assert!(colours.len() >= 20, "only {} colours", colours.len());
        }
    }
}

/// `render --quads` draws the quads of quads.obj, one polygon each, red where a quad is less
/// flat than 0.01 and calm elsewhere; the verdict counts those over 0.01 as the written quads
/// measure. Without quads.obj it says how to make them.
#[test]
fn the_quads_picture_shows_which_quads_are_not_flat_enough() {
    let tmp = TempDir::new("render-quads");
    let dir = tmp.join("q");
    demo(&dir, &["--vertices", "600", "--quads", "flattest"]);
    let cover = read_written_mesh(&dir.join("quads.obj"));
    let deltas: Vec<f64> = (cover.faces.iter())
        .filter(|f| f.len() == 4)
        .map(|f| quad_delta([0, 1, 2, 3].map(|k| cover.vertices[f[k]])))
        .collect();
    let over = deltas.iter().filter(|&&d| d > 0.01).count();
    // A few quads bent beyond the floor show red.
    let mut bent = cover.clone();
    for v in bent.faces[0].clone() {
        bent.vertices[v].z += 0.3 * ((v % 3) as f64 - 1.0);
    }
    for (name, mesh) in [("flat", &cover), ("bent", &bent)] {
        let d = tmp.join(name);
        std::fs::create_dir_all(&d).unwrap();
        for f in ["structure.json", "base.obj", "offset.obj"] {
            std::fs::copy(dir.join(f), d.join(f)).unwrap();
        }
        let mut file = std::fs::File::create(d.join("quads.obj")).unwrap();
        honeycomb::mesh::io::write_obj(&mut file, mesh).unwrap();
    }
    let out = tmp.join("quads.svg");
    let render = |dir: &std::path::Path| render_drawing(dir, "--quads", &out);
    let picture = |dir: &std::path::Path| {
        let r = render(dir);
        assert!(r.status.success(), "{}", common::stderr(&r));
        std::fs::read_to_string(&out).unwrap()
    };
    let svg = picture(&tmp.join("flat"));
    let quads = svg.lines().filter(|l| l.contains("class=\"quad\"")).count();
    assert_eq!(quads, deltas.len());
    let verdict = if over == 0 {
        format!("all {} quads within 0.01", deltas.len())
    } else {
        format!("{over} of {} quads over 0.01", deltas.len())
    };
    assert!(svg.contains(&verdict), "{verdict}");
    assert!(svg.contains("delta_face"), "legend");
    assert_eq!(fills(&svg).iter().filter(|c| *c == RED).count(), over);
    let svg = picture(&tmp.join("bent"));
    assert!(fills(&svg).iter().filter(|c| *c == RED).count() > over);
    // A honeycomb without quads: one clear error naming the missing file and the option.
    let plain = tmp.join("plain");
    demo(&plain, &["--vertices", "300"]);
    assert_clean_failure(&render(&plain), &["quads.obj", "--quads zigzag"], None);
}

/// `render DIR --shading` draws a shading device's cells, each by the light it lets through
/// against the same cell along S's normals (the report's light and depth), red above the 0.5
/// asked: one polygon per cell, the red ones those whose share, measured here from the written
/// meshes, is over half their reference's.
#[test]
fn the_shading_picture_shows_where_the_light_leaks() {
    use honeycomb::analysis::{extruded_along_normals, light_share, DEFAULT_LIGHT_SAMPLES};
    let tmp = TempDir::new("render-shading");
    let dir = tmp.join("s");
    demo(&dir, &["--vertices", "600", "--light", "0.6,0.6,-0.5"]);
    let report = read_json(&dir, "report.json");
    let shading = &report["shading"];
    let light: Vec<f64> = (shading["light"]["direction"].as_array().unwrap().iter())
        .map(|c| c.as_f64().unwrap())
        .collect();
    let light = honeycomb::Vec3::new(light[0], light[1], light[2]);
    let depth = shading["depth"].as_f64().unwrap();
    let (h, conn) = honeycomb::export::read_structure(&dir).unwrap();
    let surface = honeycomb::Surface::read(dir.join("surface.obj")).unwrap();
    let reference = extruded_along_normals(&h.base, &conn, &surface, depth);
    let after = light_share(&h, light, DEFAULT_LIGHT_SAMPLES).per_cell;
    let before = light_share(&reference, light, DEFAULT_LIGHT_SAMPLES).per_cell;
    // A reference that lets through under 5% of a cell counts as 5%.
    let over = (after.iter().zip(&before))
        .filter(|(a, b)| **a > 0.5 * b.max(0.05))
        .count();
    let out = tmp.join("shading.svg");
    let render = |dir: &std::path::Path| render_drawing(dir, "--shading", &out);
    let r = render(&dir);
    assert!(r.status.success(), "{}", common::stderr(&r));
    let svg = std::fs::read_to_string(&out).unwrap();
    let cells = svg.lines().filter(|l| l.contains("class=\"cell\"")).count();
    assert_eq!(cells, h.base.faces.len());
    assert!(svg.contains("light ratio"), "legend");
    assert_eq!(fills(&svg).iter().filter(|c| *c == RED).count(), over);
    let verdict = if over == 0 {
        format!("all {cells} cells within 0.5")
    } else {
        format!("{over} of {cells} cells over 0.5")
    };
    assert!(svg.contains(&verdict), "{verdict}");
    // The whole device's shares, as the report has them.
    let stdout = String::from_utf8_lossy(&r.stdout).to_string();
    let share = |key: &str| shading["light"][key].as_f64().unwrap();
    assert!(
        stdout.contains(&format!("let through {}", rounded(share("after"), 3))),
        "{stdout}"
    );
    // A honeycomb made without a light: one clear error naming the report and the option.
    let plain = tmp.join("plain");
    demo(&plain, &["--vertices", "300"]);
    assert_clean_failure(&render(&plain), &["report.json", "--light"], None);
}

/// `honeycomb render DIR DRAWING -o OUT` (DRAWING: `--quads`, `--shading`, ...).
fn render_drawing(
    dir: &std::path::Path,
    drawing: &str,
    out: &std::path::Path,
) -> std::process::Output {
    run([
        "render",
        dir.to_str().unwrap(),
        drawing,
        "-o",
        out.to_str().unwrap(),
    ])
}
