//! `honeycomb export DIR --format ... -o OUT`: files a fabricator cuts and exchange formats,
//! checked against the structure's own meshes.

mod common;

use common::{assert_clean_failure, demo, read_json, read_written_mesh, run, stdout, TempDir};
use honeycomb::Vec3;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

fn export(src: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["export", src.to_str().unwrap()];
    args.extend_from_slice(extra);
    args.extend(["-o", out.to_str().unwrap()]);
    run(&args)
}

fn csv_rows(path: &Path) -> Vec<BTreeMap<String, String>> {
    let mut reader = csv::Reader::from_path(path).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            header
                .iter()
                .cloned()
                .zip(r.iter().map(String::from))
                .collect()
        })
        .collect()
}

fn num(row: &BTreeMap<String, String>, key: &str) -> f64 {
    row[key]
        .parse()
        .unwrap_or_else(|_| panic!("{key}: {:?}", row[key]))
}

/// A honeycomb on the demo's saddle: walls that lean, cells of several sizes.
fn saddle(tmp: &TempDir) -> std::path::PathBuf {
    let src = tmp.join("src");
    demo(&src, &["--vertices", "300"]);
    src
}

#[test]
fn csv_figures_agree_with_the_meshes() {
    let tmp = TempDir::new("export-csv");
    let src = saddle(&tmp);
    let out = tmp.join("out");
    let ok = export(&src, &out, &["--format", "csv", "-q"]);
    assert!(ok.status.success(), "{}", common::stderr(&ok));
    let base = read_written_mesh(&src.join("base.obj"));
    let offset = read_written_mesh(&src.join("offset.obj"));
    let edges = common::mesh_edges(&base);
    let walls = csv_rows(&out.join("walls.csv"));
    assert_eq!(walls.len(), edges.len());
    let close = |a: f64, b: f64, what: &str| assert!((a - b).abs() < 1e-9, "{what}: {a} vs {b}");
    let (mut area, mut standing) = (0.0, 0.0);
    for row in &walls {
        let (i, j) = (num(row, "i") as usize, num(row, "j") as usize);
        assert!(
            edges.binary_search(&[i.min(j), i.max(j)]).is_ok(),
            "edge {i}-{j}"
        );
        let (m, o) = (&base.vertices, &offset.vertices);
        close(num(row, "length"), (m[j] - m[i]).norm(), "length");
        close(
            num(row, "length_offset"),
            (o[j] - o[i]).norm(),
            "length_offset",
        );
        close(num(row, "height_i"), (o[i] - m[i]).norm(), "height_i");
        close(num(row, "height_j"), (o[j] - m[j]).norm(), "height_j");
        let wall_area = 0.5 * (o[j] - m[i]).cross(o[i] - m[j]).norm();
        close(num(row, "area"), wall_area, "area");
        area += wall_area;
        let (u, v) = (m[j] - m[i], o[i] - m[i]);
        let angle = u.cross(v).norm().atan2(u.dot(v)).to_degrees();
        close(num(row, "end_angle_i_deg"), angle, "end angle");
        let stand = num(row, "surface_angle_deg");
        assert!((0.0..=90.0).contains(&stand), "{row:?}");
        standing += stand;
        assert!(!row["cell_left"].is_empty() || !row["cell_right"].is_empty());
    }
    // Walls across S stand near square on the cladding.
    let mean = standing / walls.len() as f64;
    assert!(mean > 75.0, "walls stand at {mean} deg to S on average");
    let nodes = csv_rows(&out.join("nodes.csv"));
    assert_eq!(nodes.len(), base.vertices.len());
    for row in &nodes {
        let v = num(row, "node") as usize;
        let p = Vec3::new(num(row, "x"), num(row, "y"), num(row, "z"));
        close((p - base.vertices[v]).norm(), 0.0, "position");
        let axis = Vec3::new(num(row, "axis_x"), num(row, "axis_y"), num(row, "axis_z"));
        let realized = offset.vertices[v] - base.vertices[v];
        close(axis.cross(realized.normalized()).norm(), 0.0, "axis");
        close(num(row, "axis_length"), realized.norm(), "axis length");
        // The three walls leave the axis 120 degrees apart: the one node design.
        let dirs: Vec<Vec3> = (1..=num(row, "valence") as usize)
            .map(|k| {
                let c = |s: &str| num(row, &format!("wall_{k}_{s}"));
                Vec3::new(c("x"), c("y"), c("z"))
            })
            .collect();
        for a in 0..dirs.len() {
            for b in a + 1..dirs.len() {
                let deg = dirs[a].dot(dirs[b]).clamp(-1.0, 1.0).acos().to_degrees();
                assert!((deg - 120.0).abs() < 1e-3, "node {v}: {deg}");
            }
        }
        assert!(num(row, "omega_deg") < 1e-3);
    }
    let bom: BTreeMap<String, String> = csv_rows(&out.join("bom.csv"))
        .into_iter()
        .map(|r| (r["item"].clone(), r["value"].clone()))
        .collect();
    assert_eq!(bom["walls"], edges.len().to_string());
    assert_eq!(bom["nodes"], base.vertices.len().to_string());
    assert_eq!(bom["cells"], base.faces.len().to_string());
    assert_eq!(bom["node_types"], "1");
    close(bom["total_wall_area"].parse().unwrap(), area, "total area");
    let lengths: BTreeSet<i64> = walls
        .iter()
        .map(|r| (num(r, "length") / 0.001).round() as i64)
        .collect();
    assert_eq!(bom["distinct_wall_lengths"], lengths.len().to_string());
    // Only the asked format (and export.json) is written.
    assert_eq!(
        common::entries(&out),
        ["bom.csv", "export.json", "nodes.csv", "walls.csv"]
    );
}

/// The closed CUT polylines of a DXF sheet row and the LABEL texts.
struct DxfContents {
    cuts: Vec<Vec<[f64; 2]>>,
    labels: Vec<(String, [f64; 2])>,
    layers: BTreeSet<String>,
}

fn read_dxf(path: &Path) -> DxfContents {
    let drawing = dxf::Drawing::load_file(path).unwrap();
    let mut contents = DxfContents {
        cuts: Vec::new(),
        labels: Vec::new(),
        layers: drawing.layers().map(|l| l.name.clone()).collect(),
    };
    for e in drawing.entities() {
        match (&e.specific, e.common.layer.as_str()) {
            (dxf::entities::EntityType::LwPolyline(p), "CUT") => {
                assert!(p.is_closed());
                contents
                    .cuts
                    .push(p.vertices.iter().map(|v| [v.x, v.y]).collect());
            }
            (dxf::entities::EntityType::Text(t), "LABEL") => contents
                .labels
                .push((t.value.clone(), [t.location.x, t.location.y])),
            _ => {}
        }
    }
    contents
}

fn inside(p: [f64; 2], poly: &[[f64; 2]]) -> bool {
    let mut odd = false;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
        {
            odd = !odd;
        }
    }
    odd
}

#[test]
fn panels_read_back_with_every_label_and_the_walls_true_shape() {
    let tmp = TempDir::new("export-panels");
    let src = saddle(&tmp);
    let out = tmp.join("out");
    let ok = export(
        &src,
        &out,
        &["--format", "dxf,svg", "--sheet", "3x1.5", "--json"],
    );
    assert!(ok.status.success(), "{}", common::stderr(&ok));
    let report = common::parse_json(&stdout(&ok), "export --json");
    let sheets = report["sheets"].as_u64().unwrap() as usize;
    assert!(sheets >= 1);
    let base = read_written_mesh(&src.join("base.obj"));
    let offset = read_written_mesh(&src.join("offset.obj"));
    let edges = common::mesh_edges(&base);
    let contents = read_dxf(&out.join("panels.dxf"));
    for layer in ["CUT", "LABEL", "BEVEL", "SHEET"] {
        assert!(contents.layers.contains(layer), "{layer}");
    }
    assert_eq!(contents.cuts.len(), edges.len());
    let structure = read_json(&src, "structure.json");
    let wall_edges: Vec<[usize; 2]> = serde_json::from_value(structure["edges"].clone()).unwrap();
    for (e, &[a, b]) in wall_edges.iter().enumerate() {
        let name = format!("W{e}");
        let (_, at) = contents
            .labels
            .iter()
            .find(|(t, _)| *t == name)
            .unwrap_or_else(|| panic!("no label {name}"));
        // The panel around the label is the wall: the same four sides as the 3D quad.
        let outline = contents
            .cuts
            .iter()
            .find(|c| inside(*at, c))
            .unwrap_or_else(|| panic!("{name} lies on no panel"));
        let (m, o) = (&base.vertices, &offset.vertices);
        let mut sides3: Vec<f64> = [(m[a], m[b]), (m[b], o[b]), (o[b], o[a]), (o[a], m[a])]
            .iter()
            .map(|(p, q)| (*q - *p).norm())
            .collect();
        let mut sides2: Vec<f64> = (0..4)
            .map(|k| {
                let (p, q) = (outline[k], outline[(k + 1) % 4]);
                (q[0] - p[0]).hypot(q[1] - p[1])
            })
            .collect();
        sides3.sort_by(f64::total_cmp);
        sides2.sort_by(f64::total_cmp);
        for (s2, s3) in sides2.iter().zip(&sides3) {
            assert!((s2 - s3).abs() < 1e-9, "{name}: {sides2:?} vs {sides3:?}");
        }
        // And the same corner angles.
        let quad = [m[a], m[b], o[b], o[a]];
        let mut corners3: Vec<f64> = (0..4)
            .map(|k| {
                let (u, v) = (quad[(k + 1) % 4] - quad[k], quad[(k + 3) % 4] - quad[k]);
                u.cross(v).norm().atan2(u.dot(v)).to_degrees()
            })
            .collect();
        let mut corners2: Vec<f64> = (0..4)
            .map(|k| {
                let (p, q, r) = (outline[k], outline[(k + 1) % 4], outline[(k + 3) % 4]);
                let (u, v) = ([q[0] - p[0], q[1] - p[1]], [r[0] - p[0], r[1] - p[1]]);
                (u[0] * v[1] - u[1] * v[0])
                    .abs()
                    .atan2(u[0] * v[0] + u[1] * v[1])
                    .to_degrees()
            })
            .collect();
        corners3.sort_by(f64::total_cmp);
        corners2.sort_by(f64::total_cmp);
        for (c2, c3) in corners2.iter().zip(&corners3) {
            assert!(
                (c2 - c3).abs() < 1e-9,
                "{name}: {corners2:?} vs {corners3:?}"
            );
        }
        for node in [a, b] {
            let label = format!("N{node}");
            assert!(
                contents
                    .labels
                    .iter()
                    .any(|(t, p)| *t == label && inside(*p, outline)),
                "{name}: no {label} on its panel"
            );
        }
    }
    // No two panels overlap: no corner of one lies inside another.
    for (i, a) in contents.cuts.iter().enumerate() {
        for (j, b) in contents.cuts.iter().enumerate() {
            if i != j {
                assert!(
                    !a.iter().any(|&p| inside(p, b)),
                    "panels {i} and {j} overlap"
                );
            }
        }
    }
    let svg = std::fs::read_to_string(out.join("panels.svg")).unwrap();
    assert_eq!(svg.matches("<inkscape:page ").count(), sheets);
    assert_eq!(svg.matches("<polygon ").count(), edges.len() + sheets);
    assert!(svg.contains(">W0</text>") && svg.contains(&format!(">W{}</text>", edges.len() - 1)));
}

#[test]
fn end_cuts_set_panels_back_and_are_stated() {
    let tmp = TempDir::new("export-cuts");
    let src = saddle(&tmp);
    let out = tmp.join("out");
    let t = 0.02;
    let ok = export(
        &src,
        &out,
        &["--format", "dxf,csv", "--material-thickness", "0.02", "-q"],
    );
    assert!(ok.status.success(), "{}", common::stderr(&ok));
    let report = read_json(&out, "export.json");
    let setback = report["end_setback"].as_f64().unwrap();
    assert!((setback - t / (2.0 * 3f64.sqrt())).abs() < 1e-15);
    assert_eq!(report["end_bevel_deg"].as_f64(), Some(30.0));
    assert_eq!(report["gap"].as_f64(), Some(2.0 * t));
    let walls = csv_rows(&out.join("walls.csv"));
    let contents = read_dxf(&out.join("panels.dxf"));
    // Each cut panel is the wall less a strip of `setback` at each end, measured square to
    // the end's node axis: its area shrinks by about setback x (height_i + height_j).
    let total_cut: f64 = contents
        .cuts
        .iter()
        .map(|c| {
            (0..c.len())
                .map(|k| {
                    let (p, q) = (c[k], c[(k + 1) % c.len()]);
                    p[0] * q[1] - q[0] * p[1]
                })
                .sum::<f64>()
                .abs()
                / 2.0
        })
        .sum();
    let total: f64 = walls.iter().map(|r| num(r, "area")).sum();
    let strips: f64 = walls
        .iter()
        .map(|r| setback * (num(r, "height_i") + num(r, "height_j")))
        .sum();
    // Boundary nodes with one wall keep their end; the strips are parallelograms.
    assert!(
        total - total_cut > 0.8 * strips && total - total_cut < 1.2 * strips,
        "{total} - {total_cut} vs {strips}"
    );
    let bom: BTreeMap<String, String> = csv_rows(&out.join("bom.csv"))
        .into_iter()
        .map(|r| (r["item"].clone(), r["value"].clone()))
        .collect();
    assert_eq!(bom["end_bevel_deg"], "30");
    assert_eq!(bom["material_thickness"], "0.02");
}

#[test]
fn obj_has_a_named_object_per_part_and_wall() {
    let tmp = TempDir::new("export-obj");
    let src = saddle(&tmp);
    let (z, y) = (tmp.join("z"), tmp.join("y"));
    assert!(
        export(&src, &z, &["--format", "obj", "-q", "--units", "mm"])
            .status
            .success()
    );
    assert!(export(&src, &y, &["--format", "obj", "-q", "--up", "y"])
        .status
        .success());
    let text = std::fs::read_to_string(z.join("structure.obj")).unwrap();
    assert!(text.contains("# units: mm") && text.contains("Z up"));
    assert!(text.contains("mtllib structure.mtl"));
    for part in [
        "o surface",
        "o base",
        "o offset",
        "o node_axes",
        "o W0\ng walls",
    ] {
        assert!(text.contains(part), "{part}");
    }
    let walls = text.matches("\ng walls\n").count();
    let edges = read_json(&src, "structure.json")["edges"]
        .as_array()
        .unwrap()
        .len();
    assert_eq!(walls, edges);
    let mtl = std::fs::read_to_string(z.join("structure.mtl")).unwrap();
    for m in text.lines().filter_map(|l| l.strip_prefix("usemtl ")) {
        assert!(mtl.contains(&format!("newmtl {m}\n")), "{m}");
    }
    // Y up is the same model turned: the first vertex (x, y, z) reads (x, z, -y).
    let first = |text: &str| -> Vec<f64> {
        let line = text.lines().find(|l| l.starts_with("v ")).unwrap();
        line[2..].split(' ').map(|x| x.parse().unwrap()).collect()
    };
    let yt = std::fs::read_to_string(y.join("structure.obj")).unwrap();
    let (a, b) = (first(&text), first(&yt));
    assert_eq!([b[0], b[1], b[2]], [a[0], a[2], -a[1]]);
}

#[test]
fn export_refuses_what_it_cannot_make() {
    let tmp = TempDir::new("export-bad");
    let src = saddle(&tmp);
    let out = tmp.join("out");
    let fails = |extra: &[&str], keywords: &[&str]| {
        let o = export(&src, &out, extra);
        assert_clean_failure(&o, keywords, Some(&out));
    };
    fails(&["--format", "step"], &["--format step", "unknown format"]);
    fails(&["--units", "furlong"], &["--units furlong"]);
    fails(&["--up", "x"], &["--up x"]);
    fails(&["--sheet", "0x1"], &["--sheet 0x1", "positive"]);
    fails(&["--sheet", "big"], &["--sheet big"]);
    fails(
        &["--material-thickness", "NaN"],
        &["--material-thickness", "positive"],
    );
    fails(
        &["--material-thickness", "-1"],
        &["--material-thickness", "positive"],
    );
    fails(
        &["--material-thickness", "50"],
        &["--material-thickness 50", "leave nothing"],
    );
    fails(&["--label-height", "0"], &["--label-height", "positive"]);
    // Numbers too large for the geometry are refused, not written as NaN or infinity.
    fails(
        &["--material-thickness", "1e300", "--sheet", "1e308x1e308"],
        &["--material-thickness 1e300", "leave nothing"],
    );
    fails(
        &["--sheet", "1e308x1e308"],
        &["--sheet 1e308x1e308", "more than 10000 times"],
    );
    // A sheet too small only for the gap a thick plate asks says so.
    fails(
        &["--material-thickness", "0.5", "--format", "svg"],
        &["does not fit", "2 x --material-thickness", "thinner plate"],
    );
    fails(
        &["--sheet", "0.2x0.2", "--format", "dxf"],
        &["--sheet 0.2x0.2", "does not fit"],
    );
    // OUT must not be the input directory: it is replaced whole.
    let o = export(&src, &src, &["-q"]);
    assert_clean_failure(&o, &["holds the input"], None);
    assert!(src.join("structure.json").is_file());
    // A directory that is not a honeycomb is not cut.
    let bent = tmp.join("bent");
    std::fs::create_dir_all(&bent).unwrap();
    let mut json = read_json(&src, "structure.json");
    json["offset_vertices"][0][2] =
        serde_json::json!(json["offset_vertices"][0][2].as_f64().unwrap() + 0.2);
    std::fs::write(bent.join("structure.json"), json.to_string()).unwrap();
    let o = export(&bent, &out, &["-q"]);
    assert_clean_failure(&o, &["structure.json", "not a honeycomb"], Some(&out));
    let o = export(&tmp.join("nowhere"), &out, &["-q"]);
    assert_clean_failure(&o, &["nowhere"], Some(&out));
}

#[test]
fn a_second_export_replaces_the_first_whole() {
    let tmp = TempDir::new("export-again");
    let src = saddle(&tmp);
    let out = tmp.join("out");
    assert!(export(&src, &out, &["--format", "dxf,csv", "-q"])
        .status
        .success());
    assert!(out.join("panels.dxf").is_file());
    assert!(export(&src, &out, &["--format", "svg", "-q"])
        .status
        .success());
    assert_eq!(common::entries(&out), ["export.json", "panels.svg"]);
}

#[test]
fn all_formats_by_default() {
    let tmp = TempDir::new("export-all");
    let src = saddle(&tmp);
    let out = tmp.join("out");
    let ok = export(&src, &out, &[]);
    assert!(ok.status.success(), "{}", common::stderr(&ok));
    assert!(
        stdout(&ok).contains("wrote structure.glb"),
        "{}",
        stdout(&ok)
    );
    assert_eq!(
        common::entries(&out),
        [
            "bom.csv",
            "export.json",
            "nodes.csv",
            "panels.dxf",
            "panels.svg",
            "structure.glb",
            "structure.mtl",
            "structure.obj",
            "walls.csv"
        ]
    );
    let glb = std::fs::read(out.join("structure.glb")).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    let length = u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize;
    assert_eq!(length, glb.len());
    let text = String::from_utf8_lossy(&glb);
    for name in [
        "\"walls\"",
        "\"W0\"",
        "\"C0\"",
        "\"node_axes\"",
        "\"surface\"",
    ] {
        assert!(text.contains(name), "{name}");
    }
}
