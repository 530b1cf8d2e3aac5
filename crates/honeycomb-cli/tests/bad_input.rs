//! `honeycomb` on broken meshes and absurd parameters: every case must exit non-zero with one
//! `error:` line naming the problem, never panic, and write nothing.

mod common;

use common::{assert_clean_failure, run, stderr, stdout, TempDir};
use honeycomb::export::write_structure;
use honeycomb::generate::hex_disk;
use honeycomb::geometry::Vec3;
use honeycomb::mesh::{write_mesh, Connectivity, PolyMesh};
use honeycomb::structure::{Honeycomb, StructureJson};
use std::ffi::OsStr;
use std::path::{Path, PathBuf};

const S: f64 = 0.866_025_403_784_438_6; // sqrt(3) / 2

/// OBJ text: one `v` line per vertex (vertex k on line k + 1), then one `f` line per face.
fn obj(vertices: &[[f64; 3]], faces: &[Vec<usize>]) -> String {
    let mut text = String::new();
    for [x, y, z] in vertices {
        text.push_str(&format!("v {x} {y} {z}\n"));
    }
    for face in faces {
        let indices: Vec<String> = face.iter().map(|v| (v + 1).to_string()).collect();
        text.push_str(&format!("f {}\n", indices.join(" ")));
    }
    text
}

/// OFF text: the header's counts line as given, one line per vertex, then the face lines.
fn off(counts: &str, vertices: &[[f64; 3]], face_lines: &str) -> String {
    let mut text = format!("OFF\n{counts}\n");
    for [x, y, z] in vertices {
        text.push_str(&format!("{x} {y} {z}\n"));
    }
    text + face_lines
}

/// Two regular hexagons of edge 1 sharing the edge 1-2, both counter-clockwise: a valid base
/// mesh of 10 vertices and 11 edges.
fn hexagon_pair() -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
    let vertices = [
        (0.0, 1.0),
        (S, 0.5),
        (S, -0.5),
        (0.0, -1.0),
        (-S, -0.5),
        (-S, 0.5),
        (2.0 * S, 1.0),
        (3.0 * S, 0.5),
        (3.0 * S, -0.5),
        (2.0 * S, -1.0),
    ]
    .map(|(x, y)| [x, y, 0.0])
    .to_vec();
    let faces = vec![vec![0, 5, 4, 3, 2, 1], vec![1, 2, 9, 8, 7, 6]];
    (vertices, faces)
}

/// A valid generated base mesh (seven hexagons, 24 vertices) written as OBJ.
fn valid_base(dir: &TempDir) -> PathBuf {
    let path = dir.join("base.obj");
    let mesh: PolyMesh = hex_disk(2.0);
    assert_eq!(mesh.faces.len(), 7);
    write_mesh(&path, &mesh).expect("write the valid base mesh");
    path
}

/// `honeycomb optimize BASE -o DIR/out` must fail cleanly naming every keyword.
/// `honeycomb optimize BASE -q -o OUT`.
fn optimize_quietly(base: &Path, out: &Path) -> std::process::Output {
    run([
        "optimize".as_ref(),
        base.as_os_str(),
        "-q".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ])
}

fn optimize_fails(dir: &TempDir, base: &Path, keywords: &[&str]) -> String {
    let out = dir.join("out");
    let output = run([
        "optimize".as_ref(),
        base.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    // Whatever the problem, the message says which file has it.
    let name = base.file_name().unwrap().to_string_lossy().into_owned();
    let keywords: Vec<&str> = keywords.iter().copied().chain([name.as_str()]).collect();
    let line = assert_clean_failure(&output, &keywords, Some(&out));
    assert!(!out.exists(), "{} was created", out.display());
    line
}

/// `honeycomb optimize VALID_BASE EXTRA... -o DIR/out` must fail cleanly naming every keyword.
fn optimize_with_fails(dir: &TempDir, extra: &[&str], keywords: &[&str]) -> String {
    let base = valid_base(dir);
    let out = dir.join("out");
    let mut args: Vec<std::ffi::OsString> = vec!["optimize".into(), base.into()];
    args.extend(extra.iter().map(Into::into));
    args.extend(["-o".into(), out.clone().into()]);
    let output = run(&args);
    let line = assert_clean_failure(&output, keywords, Some(&out));
    assert!(!out.exists(), "{} was created", out.display());
    assert_eq!(stdout(&output), "", "nothing on stdout");
    line
}

#[test]
fn valid_base_mesh_is_accepted() {
    // The control for every case below: the same files without the defect are optimized.
    let dir = TempDir::new("valid_base_mesh_is_accepted");
    let (vertices, faces) = hexagon_pair();
    for (name, base) in [
        ("pair.obj", dir.write("pair.obj", &obj(&vertices, &faces))),
        ("disk.obj", valid_base(&dir)),
    ] {
        let out = dir.join(&format!("out-{name}"));
        let output = run([
            "optimize".as_ref(),
            base.as_os_str(),
            "--quiet".as_ref(),
            "-o".as_ref(),
            out.as_os_str(),
        ]);
        common::assert_success(&output, name);
        assert!(out.join("report.json").is_file(), "{name}");
    }
}

#[test]
fn empty_file() {
    let dir = TempDir::new("empty_file");
    for name in ["empty.obj", "empty.off"] {
        let base = dir.write(name, "");
        optimize_fails(&dir, &base, &[name, "empty file"]);
    }
    // No line applies to a whole-file problem: no ":0:" in the message.
    let base = dir.write("empty.obj", "");
    let line = optimize_fails(&dir, &base, &["empty file"]);
    assert!(!line.contains(":0:"), "{line}");
    let base = dir.write("blank.obj", "\n  \n# only a comment\n");
    optimize_fails(
        &dir,
        &base,
        &["blank.obj", "no vertex (`v`) or face (`f`) records"],
    );
    // Binary data with an .obj name.
    let path = dir.join("binary.obj");
    std::fs::write(
        &path,
        [0x7f, b'E', b'L', b'F', 2, 1, 0, 0, 0xff, 0xfe, 0x80],
    )
    .unwrap();
    optimize_fails(&dir, &path, &["not a text OBJ file"]);
}

#[test]
fn truncated_off() {
    let dir = TempDir::new("truncated_off");
    let base = dir.write("truncated.off", "OFF\n10 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n");
    optimize_fails(
        &dir,
        &base,
        &["truncated.off", "truncated", "10 vertices", "only 4"],
    );
}

#[test]
fn nan_coordinate() {
    let dir = TempDir::new("nan_coordinate");
    let (mut vertices, faces) = hexagon_pair();
    vertices[2][0] = f64::NAN; // vertex 2, on line 3
    let base = dir.write("nan.obj", &obj(&vertices, &faces));
    assert!(std::fs::read_to_string(&base).unwrap().contains("v NaN"));
    let at_line_3 = format!("{}:3:", base.display());
    optimize_fails(&dir, &base, &[&at_line_3, "vertex 2", "non-finite", "NaN"]);
}

#[test]
fn out_of_range_face_index() {
    let dir = TempDir::new("out_of_range_face_index");
    let (vertices, mut faces) = hexagon_pair();
    faces[1][3] = 10; // written as 11 in the 1-based file; face 1 is on line 12
    let base = dir.write("range.obj", &obj(&vertices, &faces));
    let at_line_12 = format!("{}:12:", base.display());
    optimize_fails(
        &dir,
        &base,
        &[
            &at_line_12,
            "face 1",
            "vertex index 11",
            "out of range",
            "10 vertices",
        ],
    );

    // The same in a 0-based OFF file (index 0 is used, so it is not taken for 1-based).
    let text = off("10 2 0", &vertices, "6 0 5 4 3 2 1\n6 1 2 9 10 7 6\n");
    let base = dir.write("range.off", &text);
    optimize_fails(
        &dir,
        &base,
        &["range.off:14:", "face 1", "vertex index 10", "out of range"],
    );
}

#[test]
fn non_manifold_edge() {
    let dir = TempDir::new("non_manifold_edge");
    let (mut vertices, mut faces) = hexagon_pair();
    // A third hexagon on the edge 1-2, standing upright in the plane x = S.
    let h = 3f64.sqrt() / 2.0;
    vertices.extend([
        [S, -1.0, h],
        [S, -0.5, 2.0 * h],
        [S, 0.5, 2.0 * h],
        [S, 1.0, h],
    ]);
    faces.push(vec![1, 2, 10, 11, 12, 13]);
    let base = dir.write("fin.obj", &obj(&vertices, &faces));
    let line = optimize_fails(&dir, &base, &["non-manifold edge", "more than two faces"]);
    assert!(line.contains("1-2") || line.contains("2-1"), "{line}");
}

/// A base mesh whose faces have corners of their own (an unwelded export) is joined, with a
/// warning: taken as it was, each cell stood alone and `optimize` made a honeycomb of
/// separate cells.
#[test]
fn unwelded_base_mesh_is_joined() {
    let dir = TempDir::new("unwelded_base_mesh");
    let (vertices, faces) = hexagon_pair();
    let mut own = Vec::new();
    let mut cells = Vec::new();
    for face in &faces {
        cells.push((own.len()..own.len() + face.len()).collect());
        own.extend(face.iter().map(|&v| vertices[v]));
    }
    let welded = dir.write("welded.obj", &obj(&vertices, &faces));
    let unwelded = dir.write("unwelded.obj", &obj(&own, &cells));
    let optimized = |base: &Path, name: &str| {
        let out = dir.join(name);
        let output = optimize_quietly(base, &out);
        assert!(output.status.success(), "{}", stderr(&output));
        let report = std::fs::read_to_string(out.join("report.json")).unwrap();
        (stderr(&output), report)
    };
    let (warnings, joined) = optimized(&unwelded, "joined");
    assert!(
        warnings.contains("2 vertices repeat the position of another"),
        "{warnings}"
    );
    let (_, reference) = optimized(&welded, "reference");
    let key = |report: &str, name: &str| {
        let v: serde_json::Value = serde_json::from_str(report).unwrap();
        v[name].clone()
    };
    for name in ["vertices", "edges", "faces", "omega_max_deg"] {
        assert_eq!(key(&joined, name), key(&reference, name), "{name}");
    }
}

#[test]
fn inconsistent_orientation() {
    // Not on the list, but the neighbour of the case above: two faces, one flipped.
    let dir = TempDir::new("inconsistent_orientation");
    let (vertices, mut faces) = hexagon_pair();
    faces[1].reverse();
    let base = dir.write("flipped.obj", &obj(&vertices, &faces));
    optimize_fails(
        &dir,
        &base,
        &["same direction", "not consistently oriented"],
    );
}

#[test]
fn non_manifold_vertex() {
    let dir = TempDir::new("non_manifold_vertex");
    // Two hexagons, centred at (0, 0) and (0, 2), touching only at vertex 1 = (0, 1).
    let corners = |cy: f64| -> Vec<[f64; 3]> {
        (0..6)
            .map(|k| {
                let t = std::f64::consts::FRAC_PI_6 + std::f64::consts::FRAC_PI_3 * k as f64;
                [t.cos(), cy + t.sin(), 0.0]
            })
            .collect()
    };
    let mut vertices = corners(0.0); // 0..6; vertex 1 is the top corner (0, 1)
    let upper = corners(2.0); // its corner 4 is (0, 1) again
    vertices.extend(
        upper
            .iter()
            .enumerate()
            .filter(|&(k, _)| k != 4)
            .map(|(_, p)| *p),
    );
    // Upper corners 0, 1, 2, 3, 5 became vertices 6, 7, 8, 9, 10.
    let faces = vec![vec![0, 1, 2, 3, 4, 5], vec![6, 7, 8, 9, 1, 10]];
    let base = dir.write("bowtie.obj", &obj(&vertices, &faces));
    optimize_fails(&dir, &base, &["non-manifold vertex 1"]);
}

#[test]
fn valence_four_vertex() {
    let dir = TempDir::new("valence_four_vertex");
    // Four quads on a 3 x 3 vertex grid: the centre vertex 4 has valence 4.
    let vertices: Vec<[f64; 3]> = (0..9)
        .map(|k| [(k % 3) as f64, (k / 3) as f64, 0.0])
        .collect();
    let faces = vec![
        vec![0, 1, 4, 3],
        vec![1, 2, 5, 4],
        vec![3, 4, 7, 6],
        vec![4, 5, 8, 7],
    ];
    let base = dir.write("quads.obj", &obj(&vertices, &faces));
    optimize_fails(
        &dir,
        &base,
        &[
            "valence > 3",
            "trivalent",
            "vertex 4 (valence 4) at (1, 1, 0)",
        ],
    );

    // A bigger grid: vertex 12 is the centre of a 5 x 5 grid, among 9 interior vertices.
    let vertices: Vec<[f64; 3]> = (0..25)
        .map(|k| [(k % 5) as f64, (k / 5) as f64, 0.0])
        .collect();
    let faces: Vec<Vec<usize>> = (0..16)
        .map(|q| {
            let v = q % 4 + 5 * (q / 4);
            vec![v, v + 1, v + 6, v + 5]
        })
        .collect();
    let base = dir.write("grid.obj", &obj(&vertices, &faces));
    optimize_fails(
        &dir,
        &base,
        &[
            "9 vertices have valence > 3",
            "vertex 12 (valence 4)",
            "and 4 more",
        ],
    );
}

#[test]
fn isolated_vertex() {
    let dir = TempDir::new("isolated_vertex");
    let (mut vertices, faces) = hexagon_pair();
    vertices.push([5.0, 5.0, 5.0]);
    let base = dir.write("isolated.obj", &obj(&vertices, &faces));
    optimize_fails(&dir, &base, &["isolated vertex", "vertex 10 at (5, 5, 5)"]);
}

#[test]
fn zero_length_edge() {
    let dir = TempDir::new("zero_length_edge");
    let (mut vertices, faces) = hexagon_pair();
    vertices[8] = vertices[7];
    let base = dir.write("zero.obj", &obj(&vertices, &faces));
    optimize_fails(&dir, &base, &["zero-length edge 7-8", "coincide"]);
}

#[test]
fn unknown_format() {
    let dir = TempDir::new("unknown_format");
    let base = dir.write("points.xyz", "0 0 0\n1 0 0\n0 1 0\n");
    optimize_fails(
        &dir,
        &base,
        &["unknown mesh format", ".xyz", ".obj, .off or .ply"],
    );
    let base = dir.write("noextension", "v 0 0 0\n");
    optimize_fails(&dir, &base, &["unknown mesh format", "no file extension"]);
}

#[test]
fn missing_file() {
    let dir = TempDir::new("missing_file");
    let base = dir.join("does-not-exist.obj");
    let path = base.display().to_string();
    optimize_fails(&dir, &base, &[&path, "No such file"]);
}

#[test]
fn bad_surface_file() {
    // The --surface file goes through the same checks, and is named in the message.
    let dir = TempDir::new("bad_surface_file");
    let surface = dir.write("surface.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    let surface_arg = surface.display().to_string();
    optimize_with_fails(
        &dir,
        &["--surface", &surface_arg],
        &["surface.obj:4:", "vertex index 4", "out of range"],
    );
}

#[test]
fn zero_iterations() {
    let dir = TempDir::new("zero_iterations");
    optimize_with_fails(&dir, &["--iterations", "0"], &["--iterations 0"]);
    // Negative: rejected by the argument parser, which names the option.
    optimize_with_fails(&dir, &["--iterations", "-1"], &["'-1'", "--iterations"]);
}

#[test]
fn negative_thickness() {
    let dir = TempDir::new("negative_thickness");
    optimize_with_fails(
        &dir,
        &["--thickness", "-1"],
        &["--thickness -1", "positive"],
    );
    optimize_with_fails(&dir, &["--thickness=-1"], &["--thickness -1", "positive"]);
    optimize_with_fails(&dir, &["--thickness", "0"], &["--thickness 0", "positive"]);
}

#[test]
fn nan_thickness() {
    let dir = TempDir::new("nan_thickness");
    optimize_with_fails(&dir, &["--thickness", "nan"], &["--thickness NaN"]);
    optimize_with_fails(&dir, &["--thickness", "inf"], &["--thickness inf"]);
    optimize_with_fails(&dir, &["--thickness", "thick"], &["'thick'", "--thickness"]);
}

#[test]
fn negative_weight() {
    let dir = TempDir::new("negative_weight");
    optimize_with_fails(&dir, &["--w-angle", "-3"], &["--w-angle -3", "weight"]);
    optimize_with_fails(&dir, &["--w-fair", "-0.5"], &["--w-fair -0.5", "weight"]);
    // The honeycomb conditions need a positive weight; the others may be 0.
    optimize_with_fails(&dir, &["--w-norm", "0"], &["--w-norm 0", "weight"]);
    optimize_with_fails(&dir, &["--w-cons", "nan"], &["--w-cons NaN", "weight"]);
    optimize_with_fails(
        &dir,
        &["--w-close", "1e9"],
        &["--w-close 1000000000", "1e6"],
    );
}

#[test]
fn zero_eps() {
    let dir = TempDir::new("zero_eps");
    optimize_with_fails(&dir, &["--eps", "0"], &["--eps 0", "from 1e-12"]);
    optimize_with_fails(&dir, &["--eps", "-1"], &["--eps -1", "from 1e-12"]);
    // Subnormal: the system would be singular in roundoff.
    optimize_with_fails(&dir, &["--eps", "1e-320"], &["--eps 1e-320", "from 1e-12"]);
}

#[test]
fn a_cell_without_area() {
    let dir = TempDir::new("a_cell_without_area");
    let (mut vertices, faces) = hexagon_pair();
    // The second cell's corners spread along a line: distinct vertices, no area.
    for (k, v) in [1, 2, 9, 8, 7, 6].into_iter().enumerate() {
        vertices[v] = [k as f64, 0.0, 0.0];
    }
    let base = dir.write("flat_cell.obj", &obj(&vertices, &faces));
    optimize_fails(
        &dir,
        &base,
        &["face 1 (vertices 1, 2, 9, 8, 7, 6) has no area"],
    );
}

#[test]
fn a_coordinate_beyond_computing_range() {
    let dir = TempDir::new("a_coordinate_beyond_computing_range");
    let (mut vertices, faces) = hexagon_pair();
    vertices[3][2] = 1e308;
    let base = dir.write("far.obj", &obj(&vertices, &faces));
    optimize_fails(&dir, &base, &["vertex 3 at (0, -1, 1e308)", "beyond 1e12"]);
}

#[test]
fn lengths_far_beyond_the_cells() {
    // The disk's mean edge length is 1: these ask for a structure a million cells deep.
    let dir = TempDir::new("lengths_far_beyond_the_cells");
    // Named by the flag the user typed, not the library's name for it.
    optimize_with_fails(
        &dir,
        &["--thickness", "1e308"],
        &["--thickness 1e308", "mean edge length"],
    );
    optimize_with_fails(
        &dir,
        &["--min-edge", "1e308"],
        &["--min-edge 1e308", "mean edge length"],
    );
    optimize_with_fails(
        &dir,
        &["--parallel", "--depth", "1e6"],
        &["--depth 1000000", "mean edge length"],
    );
    optimize_with_fails(
        &dir,
        &["--parallel", "--w-parallel", "0"],
        &["--w-parallel 0", "above 0"],
    );
}

#[test]
fn a_weight_for_a_variant_not_asked_for() {
    // Silently ignored, they would look like they had been used.
    let dir = TempDir::new("a_weight_for_a_variant_not_asked_for");
    for (flag, needs) in [
        ("--w-parallel", "--parallel"),
        ("--w-depth", "--depth"),
        ("--w-axes", "--axes or --light"),
        ("--w-cons-faces", "--quads"),
        ("--w-fair-zig", "--quads"),
        ("--w-fair-str", "--quads"),
        ("--quads-reshape", "--quads"),
    ] {
        let need = format!("{flag} needs {needs}");
        optimize_with_fails(&dir, &[flag, "0.5"], &[&need]);
    }
    optimize_with_fails(
        &dir,
        &["--quads-whole-pattern"],
        &["--quads-whole-pattern needs --quads"],
    );
}

#[test]
fn demo_with_three_vertices() {
    let dir = TempDir::new("demo_with_three_vertices");
    let out = dir.join("out");
    let output = run([
        "demo".as_ref(),
        "--vertices".as_ref(),
        "3".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert_clean_failure(&output, &["--vertices 3", "50"], Some(&out));
    assert!(!out.exists());
    assert_eq!(stdout(&output), "");
}

#[test]
fn bench_with_ten_vertices() {
    let output = run(["bench", "--sizes", "10"]);
    assert_clean_failure(&output, &["--sizes 10", "50"], None);
    // Rejected before the table header is printed.
    assert_eq!(stdout(&output), "");
    let output = run(["bench", "--sizes", "1500,10", "--iterations", "1"]);
    assert_clean_failure(&output, &["--sizes 10"], None);
    assert_eq!(
        stdout(&output),
        "",
        "a later bad size is rejected before any run"
    );
}

#[test]
fn cell_points_with_a_variant() {
    let dir = TempDir::new("cell_points_with_a_variant");
    optimize_with_fails(
        &dir,
        &["--cell-points", "--light", "1,0,-1"],
        &["--cell-points", "plain honeycomb"],
    );
    optimize_with_fails(
        &dir,
        &["--cell-points", "--parallel"],
        &["--cell-points", "--parallel"],
    );
    optimize_with_fails(
        &dir,
        &["--parallel", "--quads", "zigzag"],
        &["--parallel and --quads", "one variant at a time"],
    );
}

/// `DIR/name`: a structure directory of seven flat hexagons of edge 1 with vertical walls (an
/// exact honeycomb), its structure.json then changed by `change`.
fn structure_dir(dir: &TempDir, name: &str, change: &dyn Fn(&mut StructureJson)) -> PathBuf {
    let path = dir.join(name);
    let base = hex_disk(2.0);
    let conn = Connectivity::build(&base).unwrap();
    let axes = vec![Vec3::new(0.0, 0.0, 1.0); base.vertices.len()];
    let h = Honeycomb::new(base, &conn, axes, 0.3);
    write_structure(&path, &h, &serde_json::json!({})).unwrap();
    let mut json = h.to_json();
    change(&mut json);
    let text = serde_json::to_string(&json).unwrap();
    std::fs::write(path.join("structure.json"), text).unwrap();
    path
}

/// `honeycomb edit STRUCTURE OPERATION... -o OUT`.
fn edit(structure: &Path, operation: &[&str], out: &Path) -> std::process::Output {
    let mut args: Vec<std::ffi::OsString> = vec!["edit".into(), structure.into()];
    args.extend(operation.iter().map(Into::into));
    args.extend(["-o".into(), out.into()]);
    run(&args)
}

#[test]
fn structure_with_coincident_vertices() {
    let dir = TempDir::new("structure_with_coincident_vertices");
    let all_same = structure_dir(&dir, "all-same", &|s| {
        s.vertices.iter_mut().for_each(|p| *p = [1.0, 1.0, 1.0])
    });
    let duplicate = structure_dir(&dir, "duplicate", &|s| {
        let [a, b] = s.edges[0];
        s.vertices[b] = s.vertices[a];
    });
    for structure in [&all_same, &duplicate] {
        let written_before = common::entries(structure);
        let out = dir.join("out");
        let picture = dir.join("picture.svg");
        let keywords = ["structure.json", "zero-length edge"];
        assert_clean_failure(
            &run(["analyse".as_ref(), structure.as_os_str()]),
            &keywords,
            None,
        );
        let render = run([
            "render".as_ref(),
            structure.as_os_str(),
            "-o".as_ref(),
            picture.as_os_str(),
        ]);
        assert_clean_failure(&render, &keywords, None);
        // The default distance is no parameter of the user's to blame.
        let line = assert_clean_failure(
            &edit(structure, &["reciprocal"], &out),
            &keywords,
            Some(&out),
        );
        assert!(!line.contains("reciprocal by"), "{line}");
        assert!(!out.exists() && !picture.exists());
        assert_eq!(common::entries(structure), written_before, "analyse wrote");
    }
}

#[test]
fn edit_into_its_own_directory() {
    let dir = TempDir::new("edit_into_its_own_directory");
    let structure = structure_dir(&dir, "structure", &|_| {});
    let before = std::fs::read(structure.join("structure.json")).unwrap();
    let resize = ["resize", "--cell", "0", "--by", "0.1", "-q"];
    // The same directory spelled another way.
    let again = structure.join("..").join("structure");
    for out in [&structure, &again] {
        let output = edit(&structure, &resize, out);
        assert_clean_failure(&output, &["-o", "is the input directory"], None);
        assert_eq!(
            std::fs::read(structure.join("structure.json")).unwrap(),
            before
        );
    }
    // A new directory is fine.
    let output = edit(&structure, &resize, &dir.join("out"));
    common::assert_success(&output, "resize into a new directory");
}

#[test]
fn edit_amounts_beyond_the_structure() {
    let dir = TempDir::new("edit_amounts_beyond_the_structure");
    let structure = structure_dir(&dir, "structure", &|_| {});
    let out = dir.join("out");
    for (operation, keywords) in [
        (
            &["resize", "--cell", "3", "--by", "-1e308"][..],
            &["cell 3 by -1e308", "turns edge", "between -0.866 and 0.866"][..],
        ),
        (
            &["resize", "--cell", "3", "--by", "0.9"],
            &["cell 3 by 0.9", "turns edge"],
        ),
        (
            &["subdivide", "--shrink", "1e-320"],
            &["shrink 1e-320", "between 1e-6 and 1 - 1e-6"],
        ),
    ] {
        let output = edit(&structure, operation, &out);
        assert_clean_failure(&output, keywords, Some(&out));
        assert!(!out.exists(), "{operation:?} created {}", out.display());
    }
}

#[test]
fn edit_of_a_structure_that_is_no_honeycomb() {
    let dir = TempDir::new("edit_of_a_structure_that_is_no_honeycomb");
    // One node of M' pushed sideways: its three walls twist out of plane.
    let twisted = structure_dir(&dir, "twisted", &|s| s.offset_vertices[5][0] += 0.3);
    let out = dir.join("out");
    for operation in [
        &["resize", "--cell", "3", "--by", "0.1"][..],
        &["subdivide"],
        &["reciprocal"],
    ] {
        let output = edit(&twisted, operation, &out);
        assert_clean_failure(
            &output,
            &["structure.json", "not a honeycomb", "delta_max"],
            Some(&out),
        );
        assert!(!out.exists(), "{operation:?} created {}", out.display());
    }
}

#[test]
fn reciprocal_distances_beyond_the_structure() {
    let dir = TempDir::new("reciprocal_distances_beyond_the_structure");
    let structure = structure_dir(&dir, "structure", &|_| {});
    let out = dir.join("out");
    // Regular hexagons of edge 1: the node triangles meet at 1 / (2 sqrt(3)).
    for by in ["1e308", "100", "0.29", "1e-300"] {
        let output = edit(&structure, &["reciprocal", "--by", by], &out);
        let keywords = [format!("reciprocal by {by}:"), "to below 0.2887".into()];
        let keywords: Vec<&str> = keywords.iter().map(String::as_str).collect();
        assert_clean_failure(&output, &keywords, Some(&out));
        assert!(!out.exists(), "--by {by} created {}", out.display());
    }
}

#[test]
fn reciprocal_default_on_a_structure_with_a_short_edge() {
    let dir = TempDir::new("reciprocal_default_on_a_structure_with_a_short_edge");
    let structure = structure_dir(&dir, "structure", &|_| {});
    // The middle cell's sides shrink to 1 - 2 * 0.8 / sqrt(3) = 0.076: 0.1 mean edge lengths
    // is beyond the reciprocal's range there.
    let shrunk = dir.join("shrunk");
    let output = edit(
        &structure,
        &["resize", "--cell", "3", "--by", "0.8", "-q"],
        &shrunk,
    );
    common::assert_success(&output, "resize");
    let (h, conn) = honeycomb::export::read_structure(&shrunk).unwrap();
    let limit = honeycomb::edit::reciprocal_range(&h, &conn).unwrap().limit;
    assert!(limit < 0.1 * h.base.mean_edge_length(), "{limit}");
    let out = dir.join("out");
    let output = edit(&shrunk, &["reciprocal", "-q"], &out);
    common::assert_success(&output, "reciprocal with the default distance");
    let report = common::read_json(&out, "report.json");
    let operation = report["operation"].as_str().unwrap();
    let by: f64 = operation["reciprocal by ".len()..]
        .split(':')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        (by - 0.5 * limit).abs() < 1e-9 * limit,
        "{operation}, limit {limit}"
    );
}

#[test]
fn every_line_ending_and_a_byte_order_mark_read_alike() {
    let dir = TempDir::new("every_line_ending_and_a_byte_order_mark_read_alike");
    let valid = std::fs::read_to_string(valid_base(&dir)).unwrap();
    let ply = dir.join("base.ply");
    write_mesh(&ply, &hex_disk(2.0)).unwrap();
    let ply = std::fs::read_to_string(&ply).unwrap();
    // An OBJ with CR-only endings was one line: "empty mesh".
    for (name, text) in [
        ("cr.obj", valid.replace('\n', "\r")),
        ("crlf.obj", valid.replace('\n', "\r\n")),
        ("bom.obj", format!("\u{feff}{valid}")),
        ("bom.ply", format!("\u{feff}{ply}")),
        ("cr.ply", ply.replace('\n', "\r")),
    ] {
        let base = dir.write(name, &text);
        let out = dir.join(&format!("out-{name}"));
        let output = optimize_quietly(&base, &out);
        common::assert_success(&output, name);
        let report = common::read_json(&out, "report.json");
        assert_eq!(report["vertices"], 24, "{name}: {report}");
    }
}

#[test]
fn an_off_vertex_count_too_large_names_the_first_face_line() {
    let dir = TempDir::new("an_off_vertex_count_too_large");
    let (vertices, _) = hexagon_pair();
    // 12 vertices announced, 10 given: the two face lines are read as vertices 10 and 11.
    let text = off("12 2 0", &vertices, "6 0 5 4 3 2 1\n6 1 2 9 8 7 6\n");
    let base = dir.write("count.off", &text);
    optimize_fails(
        &dir,
        &base,
        &[
            "the header says 2 faces, but only 0 were found",
            "line 13, read as vertex 10, reads like a face",
            "is the vertex count 10",
        ],
    );
}

#[test]
fn a_mesh_below_the_smallest_scale() {
    let dir = TempDir::new("a_mesh_below_the_smallest_scale");
    let (vertices, faces) = hexagon_pair();
    // It was "corners lie on one line" at 1e-100, and "zero-length edge" with 300-digit
    // coordinates at 1e-300.
    for (scale, spans) in [(1e-100, "3.4641e-100"), (1e-300, "3.4641e-300")] {
        let small: Vec<[f64; 3]> = vertices.iter().map(|p| p.map(|c| c * scale)).collect();
        let base = dir.write("small.obj", &obj(&small, &faces));
        let shown = format!("the mesh spans only {spans} model units");
        let line = optimize_fails(&dir, &base, &[&shown, "at least 1e-6", "rescale"]);
        assert!(line.len() < 300, "{line}");
    }
}

#[test]
fn numbers_in_messages_have_at_most_six_digits() {
    let dir = TempDir::new("numbers_in_messages_have_at_most_six_digits");
    optimize_with_fails(
        &dir,
        &["--w-close", "1e308"],
        &["--w-close 1e308: expected a weight"],
    );
    optimize_with_fails(
        &dir,
        &["--w-guide=-0.1234567891"],
        &["--w-guide -0.123457:"],
    );
    let structure = structure_dir(&dir, "structure", &|_| {});
    let output = run([
        "analyse".as_ref(),
        structure.as_os_str(),
        "--tolerance".as_ref(),
        "1e308".as_ref(),
    ]);
    assert_clean_failure(&output, &["--tolerance 1e308: expected"], None);
}

#[test]
fn a_light_of_tiny_components_is_a_direction() {
    // It was called "not non-zero": its squared length underflows.
    let dir = TempDir::new("a_light_of_tiny_components_is_a_direction");
    let base = valid_base(&dir);
    let out = dir.join("out");
    let output = run([
        "optimize".as_ref(),
        base.as_os_str(),
        "--light".as_ref(),
        "1e-200,1e-200,-1e-200".as_ref(),
        "--iterations".as_ref(),
        "2".as_ref(),
        "-q".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert!(!stderr(&output).contains("--light"), "{}", stderr(&output));
    // Honeycomb or not after two iterations, the run was made with that light.
    let report = common::read_json(&common::written(&output, &out), "report.json");
    assert!(report["shading"].is_object(), "{report}");
    let zero = TempDir::new("a_light_of_no_direction");
    optimize_with_fails(
        &zero,
        &["--light", "0,0,0"],
        &["--light", "0,0,0", "non-zero"],
    );
}

#[test]
fn a_surface_far_from_the_base_mesh() {
    // It solved, failed, and suggested more --iterations.
    let dir = TempDir::new("a_surface_far_from_the_base_mesh");
    let (vertices, faces) = hexagon_pair();
    let far: Vec<[f64; 3]> = vertices.iter().map(|&[x, y, z]| [x, y, z + 1e6]).collect();
    let surface = dir.write("far.obj", &obj(&far, &faces));
    optimize_with_fails(
        &dir,
        &["--surface", surface.to_str().unwrap()],
        &[
            "far.obj",
            "the base mesh lies 1000000 model units",
            "from the surface",
        ],
    );
}

/// The demo's saddle surface written into `dir`.
fn saddle_surface(dir: &TempDir) -> PathBuf {
    let path = dir.join("saddle.obj");
    let (_, surface) =
        honeycomb::generate::lifted_hex_patch(honeycomb::generate::Shape::Saddle, 200);
    write_mesh(&path, &surface).expect("write the surface");
    path
}

/// `honeycomb init SURFACE --edge-length EDGE --method METHOD -q -o DIR/base.obj`.
fn init_at(dir: &TempDir, surface: &Path, edge: &str, method: &str) -> std::process::Output {
    let base = dir.join("base.obj");
    let _ = std::fs::remove_file(&base);
    common::run_bounded(
        [
            "init".as_ref(),
            surface.as_os_str(),
            "--edge-length".as_ref(),
            edge.as_ref(),
            "--method".as_ref(),
            method.as_ref(),
            "-q".as_ref(),
            "-o".as_ref(),
            base.as_os_str(),
        ],
        60,
    )
}

/// The top of the range of edge lengths an `init` error line offers (`... to X model units`).
fn offered_top(line: &str) -> String {
    let (head, _) = line
        .split_once(" model units")
        .unwrap_or_else(|| panic!("no range in {line}"));
    let (_, top) = head
        .rsplit_once(" to ")
        .unwrap_or_else(|| panic!("no range in {line}"));
    top.to_string()
}

#[test]
fn the_edge_lengths_offered_are_the_ones_accepted() {
    // The top of the range a refusal offers must itself be accepted, the next step up not.
    let dir = TempDir::new("the_edge_lengths_offered_are_the_ones_accepted");
    let surface = saddle_surface(&dir);
    for method in ["flatten", "field"] {
        let by = format!("(the longest that lays cells by the {method} method)");
        let line = assert_clean_failure(
            &init_at(&dir, &surface, "1000", method),
            &[
                "--edge-length 1000:",
                "choose smaller cells, 0.0104407 to ",
                &by,
            ],
            None,
        );
        let top = offered_top(&line);
        let value: f64 = top.parse().unwrap_or_else(|_| panic!("{top} in {line}"));
        assert!(value > 1.0 && value < 32.0, "{line}");
        // The same range whichever way the edge length is out of it.
        let line = assert_clean_failure(
            &init_at(&dir, &surface, "1e-300", method),
            &["--edge-length 1e-300:", "choose larger cells"],
            None,
        );
        assert_eq!(offered_top(&line), top, "{line}");
        // Its top end lays a mesh.
        let output = init_at(&dir, &surface, &top, method);
        common::assert_success(
            &output,
            &format!("init --edge-length {top} --method {method}"),
        );
        assert!(dir.join("base.obj").is_file());
        // The next value of as many digits above it is refused, naming the option.
        let unit = 10f64.powi(value.log10().floor() as i32 - 3);
        let above = honeycomb::error::rounded(value + unit, 4);
        let shown = format!("--edge-length {above}:");
        let line = assert_clean_failure(
            &init_at(&dir, &surface, &above, method),
            &[
                &shown,
                "no cell of that size fits",
                "choose smaller cells",
                &by,
            ],
            None,
        );
        assert_eq!(offered_top(&line), top, "{line}");
    }
}

#[test]
fn numbers_in_messages_are_readable_at_every_scale() {
    // Tiny lengths and huge counts must read as numbers, never as 0.0000 or inf.
    let dir = TempDir::new("numbers_in_messages_are_readable_at_every_scale");
    let (vertices, faces) = hexagon_pair();
    let small: Vec<[f64; 3]> = vertices.iter().map(|p| p.map(|c| c * 1e-5)).collect();
    let base = dir.write("small.obj", &obj(&small, &faces));
    let out = dir.join("out");
    for (extra, shown) in [
        (
            &["--thickness", "1"][..],
            "--thickness 1: more than 1000 times",
        ),
        (&["--min-edge", "1"], "--min-edge 1: more than 10 times"),
        (
            &["--parallel", "--depth", "1"],
            "--depth 1: more than 1000 times",
        ),
    ] {
        let mut args: Vec<std::ffi::OsString> = vec!["optimize".into(), base.clone().into()];
        args.extend(extra.iter().map(Into::into));
        args.extend(["-o".into(), out.clone().into()]);
        let line = assert_clean_failure(
            &run(&args),
            &[shown, "the base mesh's mean edge length 1e-5;"],
            Some(&out),
        );
        assert!(!line.contains("0.0000"), "{line}");
    }
    let surface = saddle_surface(&dir);
    for method in ["flatten", "field"] {
        let line = assert_clean_failure(
            &init_at(&dir, &surface, "1e-300", method),
            &[
                "--edge-length 1e-300: more cells than can be counted",
                "on a surface of area 566.426",
                "expected at most 2000000",
            ],
            None,
        );
        assert!(!line.contains("inf"), "{line}");
    }
    // A size inside the range the lattice misses: its edge length and area in a few digits.
    let line = assert_clean_failure(
        &init_at(&dir, &surface, "8", "field"),
        &["no whole cell of edge length 8 fits on the surface (area 566.426, about 3.4 cells)"],
        None,
    );
    assert!(!line.contains("8.0000"), "{line}");
}

#[test]
fn a_demo_of_the_largest_size_offered_is_not_refused_for_its_size() {
    // The top of the range offered must not be refused for the mesh it makes.
    let dir = TempDir::new("a_demo_of_the_largest_size_offered");
    let out = dir.join("out");
    let demo = |extra: &[&str]| {
        let mut args: Vec<std::ffi::OsString> = vec!["demo".into()];
        args.extend(extra.iter().map(Into::into));
        args.extend(["-o".into(), out.clone().into()]);
        common::run_bounded(&args, 60)
    };
    for shape in ["saddle", "roof"] {
        let line = assert_clean_failure(
            &demo(&["--shape", shape, "--vertices", "300000"]),
            &[
                "--vertices 300000: expected 50 to 295000 vertices",
                "a solve takes at most 300000",
            ],
            Some(&out),
        );
        assert!(!line.contains("base mesh has"), "{line}");
        // At the top of the range the mesh is within a solve: only the iterations asked for
        // (a week's work at that size) are refused.
        let line = assert_clean_failure(
            &demo(&[
                "--shape",
                shape,
                "--vertices",
                "295000",
                "--iterations",
                "10000",
            ]),
            &["--iterations 10000: on", "vertices expected at most"],
            Some(&out),
        );
        assert!(!line.contains("base mesh has"), "{line}");
        assert!(!out.exists());
    }
}

#[test]
fn lengths_the_pipeline_is_given_are_named_by_their_flags() {
    let dir = TempDir::new("lengths_the_pipeline_is_given_are_named_by_their_flags");
    let surface = saddle_surface(&dir);
    let out = dir.join("out");
    for (extra, shown) in [
        (
            &["--min-edge", "1e308"][..],
            "--min-edge 1e308: more than 10 times",
        ),
        (
            &["--thickness", "1e30"],
            "--thickness 1e30: more than 1000 times",
        ),
    ] {
        let mut args: Vec<std::ffi::OsString> = vec![
            "pipeline".into(),
            surface.clone().into(),
            "--cells".into(),
            "100".into(),
        ];
        args.extend(extra.iter().map(Into::into));
        args.extend(["-o".into(), out.clone().into()]);
        let line = assert_clean_failure(&common::run_bounded(&args, 120), &[shown], Some(&out));
        assert!(!line.contains("minimum edge length"), "{line}");
        assert!(!out.exists());
    }
}

#[test]
fn even_cells_are_asked_of_walls_across_only() {
    let dir = TempDir::new("even_cells_are_asked_of_walls_across_only");
    let surface = saddle_surface(&dir);
    let out = dir.join("out");
    for extra in [&["--walls", "uniform"][..], &["--light", "0,0.3,-1"]] {
        let mut args: Vec<std::ffi::OsString> = vec![
            "pipeline".into(),
            surface.clone().into(),
            "--cells".into(),
            "100".into(),
            "--even-cells".into(),
        ];
        args.extend(extra.iter().map(Into::into));
        args.extend(["-o".into(), out.clone().into()]);
        let shown = ["--even-cells given", "walls across S's normals"];
        assert_clean_failure(&common::run_bounded(&args, 120), &shown, Some(&out));
        assert!(!out.exists());
    }
}

#[test]
fn vector_files_with_a_byte_order_mark_are_read_as_the_meshes_are() {
    // "`\u{feff}0` is not a number": the mark was kept in the first line of --axes and
    // --sun-path files, which the mesh readers drop.
    let dir = TempDir::new("vector_files_with_a_byte_order_mark");
    let base = valid_base(&dir);
    let axes = dir.write("axes.txt", &format!("\u{feff}{}", "0 0 1\r".repeat(24)));
    let sun = dir.write("sun.txt", "\u{feff}0.3 0.1 1\r\n0 0.5 1\r\n");
    for (name, extra) in [
        ("axes", vec!["--axes", axes.to_str().unwrap()]),
        (
            "sun",
            vec!["--light", "0,0.2,1", "--sun-path", sun.to_str().unwrap()],
        ),
    ] {
        let out = dir.join(&format!("out-{name}"));
        let mut args: Vec<std::ffi::OsString> = vec!["optimize".into(), base.clone().into()];
        args.extend(extra.iter().map(Into::into));
        args.extend(["--iterations", "2", "-q", "-o"].map(Into::into));
        args.push(out.clone().into());
        let output = run(&args);
        let err = stderr(&output);
        let file = format!("{name}.txt");
        assert!(
            !err.contains(&file) && !err.contains("not a number"),
            "{err}"
        );
        // Honeycomb or not after two iterations, the run was made with the file.
        let report = common::read_json(&common::written(&output, &out), "report.json");
        assert_eq!(report["vertices"], 24, "{name}: {report}");
    }
}

#[cfg(unix)]
#[test]
fn a_fifo_as_the_render_surface_is_not_a_regular_file() {
    let dir = TempDir::new("a_fifo_as_the_render_surface");
    let fifo = dir.join("surface.obj");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        println!("skipping: mkfifo is not available");
        return;
    }
    let structure = structure_dir(&dir, "structure", &|_| {});
    let picture = dir.join("picture.svg");
    for color in ["closeness", "axis"] {
        // Not "does not exist"; opening it would wait for a writer that never comes.
        let output = common::run_bounded(
            [
                "render".as_ref(),
                structure.as_os_str(),
                "--color".as_ref(),
                color.as_ref(),
                "--surface".as_ref(),
                fifo.as_os_str(),
                "-o".as_ref(),
                picture.as_os_str(),
            ],
            30,
        );
        let line = assert_clean_failure(
            &output,
            &["surface.obj", "not a regular file (a FIFO"],
            None,
        );
        assert!(!line.contains("does not exist"), "{line}");
        assert!(!picture.exists());
    }
    // An absent file still is one that does not exist.
    let absent = dir.join("absent.obj");
    let output = run([
        "render".as_ref(),
        structure.as_os_str(),
        "--color".as_ref(),
        "closeness".as_ref(),
        "--surface".as_ref(),
        absent.as_os_str(),
        "-o".as_ref(),
        picture.as_os_str(),
    ]);
    assert_clean_failure(&output, &["absent.obj does not exist"], None);
}

#[test]
fn serve_refuses_a_thickness_it_would_not_use() {
    // `serve DIR --thickness nan` must not start the editor as if none had been given.
    let dir = TempDir::new("serve_refuses_a_thickness_it_would_not_use");
    let structure = structure_dir(&dir, "structure", &|_| {});
    let saves = dir.join("saves");
    let serve = |extra: &[&std::ffi::OsStr]| {
        let mut args: Vec<std::ffi::OsString> = vec![
            "serve".into(),
            "--port".into(),
            "0".into(),
            "--saves".into(),
            saves.clone().into(),
        ];
        args.extend(extra.iter().map(|a| a.to_os_string()));
        // Accepted, the server would run until killed: the test then fails as a hang.
        common::run_bounded(&args, 60)
    };
    let structure = structure.as_os_str();
    for (value, shown) in [("nan", "NaN"), ("inf", "inf"), ("-1", "-1"), ("0", "0")] {
        let keyword = format!("--thickness {shown}: expected a positive length");
        for input in [&[structure][..], &[]] {
            let mut extra = input.to_vec();
            extra.extend([OsStr::new("--thickness"), OsStr::new(value)]);
            assert_clean_failure(&serve(&extra), &[&keyword], Some(&saves));
        }
    }
    // A structure directory is edited at its own thickness: another one is not used.
    assert_clean_failure(
        &serve(&[structure, "--thickness".as_ref(), "0.5".as_ref()]),
        &["--thickness 0.5", "structure directory"],
        Some(&saves),
    );
    assert!(!saves.exists());
}
