//! `honeycomb render DIR -o FILE.svg`: a picture that is not blank and whose colours follow
//! the measure.

mod common;

use common::{assert_clean_failure, demo, read_json, run, TempDir};
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
    demo(&dir, &["--vertices", "300"]);
    let edges = read_json(&dir, "report.json")["edges"].as_u64().unwrap() as usize;
    for (color, view) in [
        ("delta", "iso"),
        ("omega", "top"),
        ("delta", "front"),
        ("closeness", "side"),
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
        assert!(svg.contains(&format!(">{color}<")), "{color}");
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
        assert!(svg.contains("Proposition 1 violated"));
    }
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

/// Width, height and RGB pixels of a PNG made of stored (uncompressed) deflate blocks, as
/// `render` writes them.
fn decode_stored_png(bytes: &[u8]) -> (u32, u32, Vec<[u8; 3]>) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let (mut pos, mut idat, mut size) = (8, Vec::new(), (0, 0));
    while pos < bytes.len() {
        let len = u32::from_be_bytes(bytes[pos..pos + 4].try_into().unwrap()) as usize;
        let kind = &bytes[pos + 4..pos + 8];
        let data = &bytes[pos + 8..pos + 8 + len];
        if kind == b"IHDR" {
            size = (
                u32::from_be_bytes(data[0..4].try_into().unwrap()),
                u32::from_be_bytes(data[4..8].try_into().unwrap()),
            );
            assert_eq!(&data[8..10], &[8, 2], "8-bit RGB");
        } else if kind == b"IDAT" {
            idat.extend_from_slice(data);
        }
        pos += 12 + len;
    }
    let (mut raw, mut at) = (Vec::new(), 2);
    loop {
        let last = idat[at] & 1 == 1;
        let len = u16::from_le_bytes([idat[at + 1], idat[at + 2]]) as usize;
        raw.extend_from_slice(&idat[at + 5..at + 5 + len]);
        at += 5 + len;
        if last {
            break;
        }
    }
    let (w, h) = size;
    assert_eq!(raw.len(), (h * (1 + 3 * w)) as usize);
    let pixels = raw
        .chunks((1 + 3 * w) as usize)
        .flat_map(|row| {
            row[1..]
                .chunks(3)
                .map(|p| [p[0], p[1], p[2]])
                .collect::<Vec<_>>()
        })
        .collect();
    (w, h, pixels)
}

#[test]
fn png_pictures_have_the_asked_size_and_colour() {
    let tmp = TempDir::new("render-png");
    let dir = tmp.join("h");
    demo(&dir, &["--vertices", "300"]);
    for extra in [&["--color", "delta"][..], &["--spherical"][..]] {
        let out = tmp.join("p.png");
        let mut args = vec![
            "render",
            dir.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--width",
            "640",
        ];
        args.extend_from_slice(extra);
        let r = run(&args);
        assert!(r.status.success(), "{}", common::stderr(&r));
        let (w, h, pixels) = decode_stored_png(&std::fs::read(&out).unwrap());
        assert_eq!(w, 640);
        assert!(h >= 260, "{h}");
        let white = pixels.iter().filter(|p| **p == [255, 255, 255]).count();
        let colours: HashSet<[u8; 3]> = pixels.iter().copied().collect();
        println!(
            "{extra:?}: {w}x{h}, {} colours, {:.0}% white",
            colours.len(),
            100.0 * white as f64 / pixels.len() as f64
        );
        if extra[0] == "--spherical" {
            // A curve-like image: the zero-area cells' outlines trace the curve.
            let outline = pixels.iter().filter(|p| **p == [122, 166, 194]).count();
            assert!(outline > 50, "only {outline} outline pixels");
        } else {
            assert!(white < pixels.len() * 97 / 100, "nearly blank");
            assert!(colours.len() >= 20, "only {} colours", colours.len());
        }
    }
}
