//! What `honeycomb demo` and `honeycomb optimize` write and print, checked against measures
//! recomputed here from the written meshes.

mod common;

use common::{
    assert_clean_failure, assert_success, entries, mesh_edges, number, parse_json, read_json,
    read_written_mesh, run, stderr, stdout, TempDir, REPORT_KEYS,
};
use honeycomb::generate::hex_disk;
use honeycomb::mesh::{write_mesh, PolyMesh};
use honeycomb::report::Report;
use honeycomb::Vec3;
use std::collections::BTreeSet;
use std::path::Path;

fn report(dir: &Path) -> serde_json::Value {
    let path = dir.join("report.json");
    let text = std::fs::read_to_string(&path).expect("read report.json");
    parse_json(&text, "report.json")
}

/// The figures every report must have, finite and in range.
fn assert_sane(report: &serde_json::Value, what: &str) {
    for key in REPORT_KEYS {
        let x = number(report, key);
        assert!(x.is_finite() && x >= 0.0, "{what}: {key} = {x}");
    }
    let (v, e, it) = (
        number(report, "vertices"),
        number(report, "edges"),
        number(report, "iterations"),
    );
    // A hex patch with boundary: between |V| and 1.5 |V| edges.
    assert!(v < e && e < 1.5 * v, "{what}: |V| = {v}, |E| = {e}");
    // The node axes' fit and the placement, or the guided projection: at most 40 in all.
    assert!((1.0..=40.0).contains(&it), "{what}: {it} iterations");
    for (max, avg, bound) in [
        ("omega_max_deg", "omega_avg_deg", 0.01),
        ("delta_max", "delta_avg", 1e-6),
        ("closeness_max", "closeness_avg", 0.05),
    ] {
        let (m, a) = (number(report, max), number(report, avg));
        assert!(m < bound, "{what}: {max} = {m}, expected < {bound}");
        assert!(a <= m, "{what}: {avg} = {a} > {max} = {m}");
    }
    let seconds = number(report, "seconds");
    assert!(seconds > 0.0 && seconds < 120.0, "{what}: {seconds} s");
}

/// The `f` lines of an OBJ file, as written.
fn face_lines(path: &Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .expect("read OBJ")
        .lines()
        .filter(|l| l.starts_with("f "))
        .map(str::to_string)
        .collect()
}

fn vertex_line_count(path: &Path) -> usize {
    std::fs::read_to_string(path)
        .expect("read OBJ")
        .lines()
        .filter(|l| l.starts_with("v "))
        .count()
}

/// Shortest distance between the segments p0-p1 and q0-q1 (Ericson, Real-Time Collision
/// Detection, 5.1.9).
fn segment_distance(p0: Vec3, p1: Vec3, q0: Vec3, q1: Vec3) -> f64 {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.dot(d1), d2.dot(d2), d2.dot(r));
    let (s, t) = if a <= 1e-300 && e <= 1e-300 {
        (0.0, 0.0)
    } else if a <= 1e-300 {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e <= 1e-300 {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let mut s = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
            (s, t)
        }
    };
    ((p0 + d1 * s) - (q0 + d2 * t)).norm()
}

/// Distance from `p` to the triangle abc (Ericson 5.1.5).
fn triangle_distance(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.norm();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.norm();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (p - (a + ab * (d1 / (d1 - d3)))).norm();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.norm();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (p - (a + ac * (d2 / (d2 - d6)))).norm();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + (c - b) * w)).norm();
    }
    let denom = 1.0 / (va + vb + vc);
    (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm()
}

/// Distance from `p` to a polygon mesh (faces fanned into triangles): the nearest vertex
/// bounds the search, and only triangles whose box is within that bound are measured.
struct Triangles {
    corners: Vec<[Vec3; 3]>,
    boxes: Vec<(Vec3, Vec3)>,
    vertices: Vec<Vec3>,
}

impl Triangles {
    fn new(mesh: &PolyMesh) -> Triangles {
        let p = &mesh.vertices;
        let corners: Vec<[Vec3; 3]> = mesh
            .faces
            .iter()
            .flat_map(|f| (1..f.len() - 1).map(move |k| [p[f[0]], p[f[k]], p[f[k + 1]]]))
            .collect();
        let boxes = corners
            .iter()
            .map(|[a, b, c]| (a.min(*b).min(*c), a.max(*b).max(*c)))
            .collect();
        Triangles {
            corners,
            boxes,
            vertices: mesh.vertices.clone(),
        }
    }

    fn distance(&self, p: Vec3) -> f64 {
        let mut best = self
            .vertices
            .iter()
            .map(|&v| (v - p).norm())
            .fold(f64::INFINITY, f64::min);
        for (t, (lo, hi)) in self.corners.iter().zip(&self.boxes) {
            let outside = (lo.max(p) - p) + (p - hi.min(p));
            if outside.norm() < best {
                best = best.min(triangle_distance(p, t[0], t[1], t[2]));
            }
        }
        best
    }
}

/// The measures of DESIGN.md section 3, recomputed from base.obj, offset.obj and the surface.
struct Recomputed {
    omega_max_deg: f64,
    delta_max: f64,
    closeness_max: f64,
    thickness_spread: (f64, f64),
}

fn recompute(base: &PolyMesh, offset: &PolyMesh, surface: &PolyMesh) -> Recomputed {
    let (m, o) = (&base.vertices, &offset.vertices);
    let edges = mesh_edges(base);
    let mean_edge = edges
        .iter()
        .map(|&[a, b]| (m[a] - m[b]).norm())
        .sum::<f64>()
        / edges.len() as f64;

    // Planarity of the wall quad m_a m_b o_b o_a: distance of its diagonals over its mean side.
    let delta_max = edges
        .iter()
        .map(|&[a, b]| {
            let side = ((m[b] - m[a]).norm()
                + (o[b] - m[b]).norm()
                + (o[a] - o[b]).norm()
                + (m[a] - o[a]).norm())
                / 4.0;
            segment_distance(m[a], o[b], m[b], o[a]) / side
        })
        .fold(0.0, f64::max);

    // Angles between consecutive walls around the node axis m_v -> o_v: every wall contains
    // the axis, so the angle is the one between the edges projected across the axis.
    let mut neighbours = vec![Vec::new(); m.len()];
    for &[a, b] in &edges {
        neighbours[a].push(b);
        neighbours[b].push(a);
    }
    let mut omega_max_deg: f64 = 0.0;
    for (v, around) in neighbours.iter().enumerate() {
        let axis = (o[v] - m[v]).normalized();
        let flat: Vec<Vec3> = around
            .iter()
            .map(|&j| {
                let d = m[j] - m[v];
                (d - axis * d.dot(axis)).normalized()
            })
            .collect();
        let angle = |x: Vec3, y: Vec3| x.dot(y).clamp(-1.0, 1.0).acos().to_degrees();
        let deviation = match flat.len() {
            2 => (angle(flat[0], flat[1]) - 120.0).abs(),
            3 => {
                // Three walls at 120 degrees: each pair at 120, and the three directions
                // around the axis (not all on one side), so their sum vanishes.
                let pairs = [(0, 1), (1, 2), (2, 0)];
                pairs
                    .iter()
                    .map(|&(i, k)| (angle(flat[i], flat[k]) - 120.0).abs())
                    .fold(0.0, f64::max)
            }
            n => panic!("vertex {v} has valence {n}"),
        };
        omega_max_deg = omega_max_deg.max(deviation);
    }

    let surface = Triangles::new(surface);
    let closeness_max = m
        .iter()
        .map(|&p| surface.distance(p) / mean_edge)
        .fold(0.0, f64::max);

    let lengths: Vec<f64> = m.iter().zip(o).map(|(&p, &q)| (q - p).norm()).collect();
    let thickness_spread = (
        lengths.iter().copied().fold(f64::INFINITY, f64::min),
        lengths.iter().copied().fold(0.0, f64::max),
    );
    Recomputed {
        omega_max_deg,
        delta_max,
        closeness_max,
        thickness_spread,
    }
}

#[test]
fn demo_writes_a_consistent_structure_and_optimize_reproduces_it() {
    let dir = TempDir::new("demo_writes_a_consistent_structure");
    let out = dir.join("demo");
    let output = run([
        "demo".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
        "--quiet".as_ref(),
    ]);
    assert_success(&output, "demo");
    assert_eq!(stdout(&output), "", "--quiet prints nothing on stdout");
    assert_eq!(stderr(&output), "", "--quiet prints nothing on stderr");

    let names = entries(&out);
    for name in [
        "base.obj",
        "offset.obj",
        "walls.obj",
        "structure.json",
        "report.json",
        "input_base.obj",
        "surface.obj",
    ] {
        assert!(names.iter().any(|n| n == name), "{name} missing: {names:?}");
    }
    assert!(
        names
            .iter()
            .all(|n| !n.starts_with('.') && !n.contains(".tmp")),
        "temporary files left: {names:?}"
    );

    let report = report(&out);
    assert_sane(&report, "demo report.json");
    let nv = number(&report, "vertices") as usize;
    let ne = number(&report, "edges") as usize;
    assert!(
        (1300..1800).contains(&nv),
        "{nv} vertices for --vertices 1500"
    );

    // M and M' share vertex order and faces; one wall quad per edge over M then M'.
    let (base_path, offset_path, walls_path) = (
        out.join("base.obj"),
        out.join("offset.obj"),
        out.join("walls.obj"),
    );
    assert_eq!(vertex_line_count(&base_path), nv);
    assert_eq!(vertex_line_count(&offset_path), nv);
    let faces = face_lines(&base_path);
    assert!(!faces.is_empty());
    assert_eq!(
        faces,
        face_lines(&offset_path),
        "base and offset faces differ"
    );
    let walls = read_written_mesh(&walls_path);
    assert_eq!(walls.faces.len(), ne, "one wall per edge");
    assert_eq!(walls.vertices.len(), 2 * nv);
    assert!(walls.faces.iter().all(|f| f.len() == 4), "walls are quads");

    let base = read_written_mesh(&base_path);
    let offset = read_written_mesh(&offset_path);
    assert_eq!(base.faces, offset.faces);
    assert_eq!(
        mesh_edges(&base).len(),
        ne,
        "report.edges is the edge count of base.obj"
    );
    // walls.obj: the quads a b b' a' over the vertices of M followed by those of M'.
    let wall_edges: BTreeSet<[usize; 2]> = walls
        .faces
        .iter()
        .map(|f| {
            let (a, b) = (f[0], f[1]);
            assert!(a < nv && b < nv, "{f:?}");
            assert_eq!(f[2..], [b + nv, a + nv], "{f:?}");
            [a.min(b), a.max(b)]
        })
        .collect();
    assert_eq!(
        wall_edges.into_iter().collect::<Vec<_>>(),
        mesh_edges(&base)
    );
    assert_eq!(walls.vertices[..nv], base.vertices[..]);
    assert_eq!(walls.vertices[nv..], offset.vertices[..]);

    // The measures, recomputed here from the files.
    let surface = read_written_mesh(&out.join("surface.obj"));
    let r = recompute(&base, &offset, &surface);
    println!(
        "demo: |V| {nv} |E| {ne} omega_max {:.2e} deg delta_max {:.2e} closeness_max {:.2e} \
         thickness {:.6}..{:.6}",
        r.omega_max_deg, r.delta_max, r.closeness_max, r.thickness_spread.0, r.thickness_spread.1
    );
    assert!(r.delta_max < 1e-6, "recomputed delta_max {}", r.delta_max);
    assert!(
        r.omega_max_deg < 0.01,
        "recomputed omega_max {}",
        r.omega_max_deg
    );
    assert!(
        r.closeness_max < 0.05,
        "recomputed closeness_max {}",
        r.closeness_max
    );
    for (key, ours, tolerance) in [
        ("omega_max_deg", r.omega_max_deg, 1e-6),
        ("delta_max", r.delta_max, 1e-9),
        ("closeness_max", r.closeness_max, 1e-6),
    ] {
        let theirs = number(&report, key);
        assert!(
            (ours - theirs).abs() <= tolerance,
            "{key}: report {theirs:e}, recomputed {ours:e}"
        );
    }
    let thickness = report["thickness"].as_f64().expect("report.thickness");
    let (lo, hi) = r.thickness_spread;
    assert!(
        (lo - thickness).abs() < 1e-9 * thickness && (hi - thickness).abs() < 1e-9 * thickness,
        "|M' - M| spans {lo}..{hi}, report thickness {thickness}"
    );

    // The inputs reproduce the result through `optimize`, whose --json is the report.
    let again = dir.join("again");
    let output = run([
        "optimize".as_ref(),
        out.join("input_base.obj").as_os_str(),
        "--surface".as_ref(),
        out.join("surface.obj").as_os_str(),
        "-o".as_ref(),
        again.as_os_str(),
        "--json".as_ref(),
    ]);
    assert_success(&output, "optimize --json");
    let printed = parse_json(&stdout(&output), "optimize --json stdout");
    assert_sane(&printed, "optimize --json");
    let written = self::report(&again);
    for key in REPORT_KEYS {
        assert!(printed.get(key).is_some(), "--json lacks {key}");
        if key != "seconds" {
            assert_eq!(printed[key], written[key], "{key}: stdout vs report.json");
        }
    }
    assert_eq!(printed["vertices"], report["vertices"]);
    assert_eq!(printed["edges"], report["edges"]);
    assert_eq!(
        face_lines(&again.join("base.obj")),
        faces,
        "the same base mesh"
    );
}

/// A small demo (fast) with the given extra arguments.
fn small_demo(out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args: Vec<std::ffi::OsString> = vec![
        "demo".into(),
        "--vertices".into(),
        "200".into(),
        "-o".into(),
        out.into(),
    ];
    args.extend(extra.iter().map(Into::into));
    run(&args)
}

#[test]
fn default_output_is_the_figure16_row_and_quiet_is_silent() {
    let dir = TempDir::new("default_output_is_the_figure16_row");
    let out = dir.join("loud");
    let output = small_demo(&out, &[]);
    assert_success(&output, "demo");
    let text = stdout(&output);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines.len() >= 2, "{text}");
    assert_eq!(lines[0], Report::FIGURE16_HEADER);
    let header: Vec<&str> = lines[0].split_whitespace().collect();
    let row: Vec<&str> = lines[1].split_whitespace().collect();
    // Twelve columns; the header "T (s)" is two words.
    assert_eq!(header.len(), 13, "{text}");
    assert_eq!(row.len(), 12, "{text}");
    assert_eq!(header[12], "axis");
    assert_eq!(header[..2], ["|V|", "|E|"]);
    let report = report(&out);
    assert_eq!(row[0], report["vertices"].to_string(), "{text}");
    assert_eq!(row[1], report["edges"].to_string(), "{text}");
    for cell in &row {
        let x: f64 = cell
            .parse()
            .unwrap_or_else(|_| panic!("{cell:?} in {text}"));
        assert!(x.is_finite(), "{text}");
    }
    assert!(text.contains(&format!("wrote {}", out.display())), "{text}");

    let quiet = dir.join("quiet");
    let output = small_demo(&quiet, &["--quiet"]);
    assert_success(&output, "demo --quiet");
    assert_eq!(stdout(&output), "");
    assert!(quiet.join("report.json").is_file());

    // The same for optimize, on the demo's own inputs.
    let again = dir.join("again");
    let output = run([
        "optimize".as_ref(),
        quiet.join("input_base.obj").as_os_str(),
        "--surface".as_ref(),
        quiet.join("surface.obj").as_os_str(),
        "-q".as_ref(),
        "-o".as_ref(),
        again.as_os_str(),
    ]);
    assert_success(&output, "optimize -q");
    assert_eq!(stdout(&output), "");
    assert_eq!(stderr(&output), "");
    assert!(again.join("report.json").is_file());
}

#[test]
fn output_under_a_regular_file_fails_cleanly() {
    let dir = TempDir::new("output_under_a_regular_file");
    let base = dir.join("base.obj");
    write_mesh(&base, &hex_disk(2.0)).expect("write base");
    let blocker = dir.write("blocker", "keep me\n");

    // -o inside a regular file.
    let out = blocker.join("out");
    let output = run([
        "optimize".as_ref(),
        base.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert_clean_failure(&output, &["blocker/out"], None);
    assert_eq!(stdout(&output), "");

    // -o naming the regular file itself, for optimize and demo.
    let output = run([
        "optimize".as_ref(),
        base.as_os_str(),
        "-o".as_ref(),
        blocker.as_os_str(),
    ]);
    assert_clean_failure(&output, &["blocker", "not a directory"], None);
    let output = small_demo(&blocker, &["--quiet"]);
    assert_clean_failure(&output, &["blocker", "not a directory"], None);

    assert_eq!(std::fs::read_to_string(&blocker).unwrap(), "keep me\n");
    assert_eq!(
        entries(&dir.path),
        ["base.obj", "blocker"],
        "nothing else written"
    );
}

#[test]
fn the_recomputing_helpers_measure_what_they_claim() {
    let v = |x: f64, y: f64, z: f64| Vec3::new(x, y, z);
    // Crossing diagonals of a planar square, skew ones of a lifted corner, and disjoint ends.
    assert!(segment_distance(v(0., 0., 0.), v(1., 1., 0.), v(1., 0., 0.), v(0., 1., 0.)) < 1e-15);
    let d = segment_distance(v(0., 0., 0.), v(1., 1., 0.), v(1., 0., 0.), v(0., 1., 0.2));
    // |r . (d1 x d2)| / |d1 x d2| with d1 x d2 = (0.2, -0.2, 2).
    assert!((d - 0.2 / 4.08f64.sqrt()).abs() < 1e-12, "{d}");
    let d = segment_distance(v(0., 0., 0.), v(1., 0., 0.), v(3., 0., 0.), v(3., 2., 0.));
    assert!((d - 2.0).abs() < 1e-12, "{d}");
    // Above the inside, beyond an edge and beyond a corner of a triangle.
    let (a, b, c) = (v(0., 0., 0.), v(2., 0., 0.), v(0., 2., 0.));
    assert!((triangle_distance(v(0.5, 0.5, 3.), a, b, c) - 3.0).abs() < 1e-12);
    assert!((triangle_distance(v(1., -1., 0.), a, b, c) - 1.0).abs() < 1e-12);
    let d = triangle_distance(v(3., 3., 0.), a, b, c);
    assert!((d - 2f64.sqrt() * 2.0).abs() < 1e-12, "{d}");
    assert!((triangle_distance(v(-1., -1., 1.), a, b, c) - 3f64.sqrt()).abs() < 1e-12);
    // The measures of a perfect honeycomb (a planar hex patch, straight up), then spoiled.
    let base = hex_disk(2.0);
    let mut offset = base.clone();
    for p in &mut offset.vertices {
        p.z = 0.5;
    }
    let r = recompute(&base, &offset, &base);
    assert!(r.omega_max_deg < 1e-9, "{}", r.omega_max_deg);
    assert!(r.delta_max < 1e-12, "{}", r.delta_max);
    assert!(r.closeness_max < 1e-12, "{}", r.closeness_max);
    offset.vertices[2].x += 0.1;
    let r = recompute(&base, &offset, &base);
    assert!(r.delta_max > 1e-3, "{}", r.delta_max);
    let mut bent = base.clone();
    bent.vertices[2].x += 0.1;
    bent.vertices[2].z += 0.2;
    let r = recompute(&bent, &offset, &base);
    assert!(r.omega_max_deg > 1.0, "{}", r.omega_max_deg);
    assert!(r.closeness_max > 0.1, "{}", r.closeness_max);
}

/// `--cell-points`: the same outputs, a honeycomb, and the weight it used in report.json.
/// Cell points by default, each formulation with its own normalization weight (an explicit
/// one wins); a solve that falls short names the other formulation, unless cell points were
/// asked for.
#[test]
fn demo_solves_for_cell_points_by_default() {
    let dir = TempDir::new("demo_with_cell_points");
    // The guided projection's formulation: free walls.
    let run = |name: &str, extra: &[&str]| {
        let out = dir.join(name);
        let args: Vec<&str> = ["--walls", "free"].iter().chain(extra).copied().collect();
        (small_demo(&out, &args), out)
    };
    let (output, out) = run("default", &["--shape", "dome", "--iterations", "6"]);
    assert_success(&output, "demo");
    let r = report(&out);
    assert_sane(&r, "demo");
    assert!(number(&r, "omega_max_deg") < 1e-6, "{r}");
    assert_eq!(r["wall_normals"], "cell_points", "{r}");
    assert_eq!(r["weights"]["normalization"].as_f64(), Some(0.3), "{r}");
    let (output, out) = run("edges", &["--per-edge-normals"]);
    assert_success(&output, "demo --per-edge-normals");
    let r = report(&out);
    assert_eq!(r["wall_normals"], "per_edge", "{r}");
    assert_eq!(r["weights"]["normalization"].as_f64(), Some(10.0), "{r}");
    let (output, out) = run("weight", &["--cell-points", "--w-norm", "1"]);
    assert_success(&output, "demo --cell-points --w-norm 1");
    assert_eq!(report(&out)["weights"]["normalization"].as_f64(), Some(1.0));
    let (output, _) = run("short", &["--iterations", "1"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("--per-edge-normals"),
        "{}",
        stderr(&output)
    );
    let (output, _) = run("short_asked", &["--iterations", "1", "--cell-points"]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        !stderr(&output).contains("--per-edge-normals"),
        "{}",
        stderr(&output)
    );
}

/// `honeycomb ARGS...` with `-q`, as `OsString`s.
fn quiet_run(args: &[&std::ffi::OsStr]) -> std::process::Output {
    let mut all: Vec<&std::ffi::OsStr> = args.to_vec();
    all.push("-q".as_ref());
    run(&all)
}

/// The bytes of every file in `dir`, by name.
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    entries(dir)
        .into_iter()
        .map(|name| {
            let bytes = std::fs::read(dir.join(&name)).unwrap();
            (name, bytes)
        })
        .collect()
}

#[test]
fn a_run_replaces_its_output_directory_whole() {
    let dir = TempDir::new("a_run_replaces_its_output_directory_whole");
    let out = dir.join("out");
    assert_success(&small_demo(&out, &["-q"]), "demo");
    assert_success(
        &run(["analyse".as_ref(), out.as_os_str(), "-q".as_ref()]),
        "analyse",
    );
    assert!(out.join("analysis.json").is_file());
    let base = dir.join("base.obj");
    let surface = dir.join("surface.obj");
    std::fs::copy(out.join("input_base.obj"), &base).unwrap();
    std::fs::copy(out.join("surface.obj"), &surface).unwrap();

    // optimize into the demo's directory: none of the demo's or analyse's files survive, so
    // `render --color closeness` cannot measure against a surface of another run.
    let o = "-o".as_ref();
    let output = quiet_run(&["optimize".as_ref(), base.as_os_str(), o, out.as_os_str()]);
    assert_success(&output, "optimize into the demo's directory");
    let structure = [
        "base.obj",
        "offset.obj",
        "report.json",
        "structure.json",
        "walls.obj",
    ];
    assert_eq!(entries(&out), structure);
    let picture = dir.join("closeness.svg");
    let render = run([
        "render".as_ref(),
        out.as_os_str(),
        "--color".as_ref(),
        "closeness".as_ref(),
        o,
        picture.as_os_str(),
    ]);
    assert_clean_failure(&render, &["needs the design surface", "surface.obj"], None);

    // pipeline into it: its own files, and nothing else.
    let output = quiet_run(&[
        "pipeline".as_ref(),
        surface.as_os_str(),
        "--cells".as_ref(),
        "40".as_ref(),
        o,
        out.as_os_str(),
    ]);
    assert_success(&output, "pipeline into the same directory");
    let mut expected = structure.to_vec();
    expected.extend(["init.json", "initial.obj", "surface.obj"]);
    expected.sort();
    assert_eq!(entries(&out), expected);
    // Nothing left beside it: no staging folder, no earlier directory.
    assert_eq!(entries(&dir.path), ["base.obj", "out", "surface.obj"]);
}

#[test]
fn a_failed_run_leaves_a_good_directory_and_writes_beside_it() {
    let dir = TempDir::new("a_failed_run_leaves_a_good_directory");
    let out = dir.join("out");
    assert_success(&small_demo(&out, &["-q"]), "demo");
    let base = dir.join("base.obj");
    std::fs::copy(out.join("input_base.obj"), &base).unwrap();
    let surface = dir.join("surface.obj");
    std::fs::copy(out.join("surface.obj"), &surface).unwrap();
    let good = contents(&out);

    // One iteration of parallel meshes gives no honeycomb.
    let failing = |out: &Path| {
        quiet_run(&[
            "optimize".as_ref(),
            base.as_os_str(),
            "--surface".as_ref(),
            surface.as_os_str(),
            "--parallel".as_ref(),
            "--iterations".as_ref(),
            "1".as_ref(),
            "-o".as_ref(),
            out.as_os_str(),
        ])
    };
    let failed = dir.join("out.failed");
    let line = assert_clean_failure(&failing(&out), &["not a honeycomb"], None);
    let named = format!("the outputs in {} are for inspection", failed.display());
    assert!(line.contains(&named), "{line}");
    // One iteration is far from what a solve may take: more are worth asking for.
    assert!(line.contains("More --iterations"), "{line}");
    assert_eq!(contents(&out), good, "the good directory changed");
    let report = read_json(&failed, "report.json");
    assert_eq!(report["honeycomb"], false, "{report}");
    assert!(failed.join("structure.json").is_file());

    // A passing run takes the good one's place and clears the stale inspection outputs.
    let output = quiet_run(&[
        "optimize".as_ref(),
        base.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert_success(&output, "optimize after a failure");
    assert_eq!(entries(&dir.path), ["base.obj", "out", "surface.obj"]);
    assert_eq!(read_json(&out, "report.json")["honeycomb"], true);

    // Without an earlier directory a failure writes DIR.failed only.
    let fresh = dir.join("fresh");
    assert_clean_failure(&failing(&fresh), &["fresh.failed"], None);
    assert!(!fresh.exists() && dir.join("fresh.failed/report.json").is_file());
}

#[test]
fn an_output_directory_of_other_files_is_not_replaced() {
    let dir = TempDir::new("an_output_directory_of_other_files");
    let base = dir.join("base.obj");
    write_mesh(&base, &hex_disk(2.0)).expect("write base");
    let mine = dir.join("mine");
    std::fs::create_dir(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "keep me\n").unwrap();
    let output = run([
        "optimize".as_ref(),
        base.as_os_str(),
        "-o".as_ref(),
        mine.as_os_str(),
    ]);
    assert_clean_failure(
        &output,
        &["mine", "other files (such as notes.txt)", "new or empty"],
        None,
    );
    assert_eq!(entries(&mine), ["notes.txt"]);
    assert_eq!(entries(&dir.path), ["base.obj", "mine"]);
}

/// An input inside -o would be lost when the run's folder takes DIR's place: the surface and
/// the strokes file of `pipeline` alike.
#[test]
fn pipeline_refuses_an_output_folder_holding_its_inputs() {
    let dir = TempDir::new("pipeline_refuses_an_output_folder_holding_its_inputs");
    let out = dir.join("out");
    assert_success(&small_demo(&out, &["-q"]), "demo");
    let surface = out.join("surface.obj");
    let strokes = out.join("strokes.obj");
    std::fs::write(&strokes, "v -1 0 0\nv 1 0 0\nl 1 2\n").unwrap();
    let outside = dir.join("surface.obj");
    std::fs::copy(&surface, &outside).unwrap();
    for (input, align) in [
        (&surface, "boundary"),
        (&outside, strokes.to_str().unwrap()),
    ] {
        let output = run([
            "pipeline".as_ref(),
            input.as_os_str(),
            "--cells".as_ref(),
            "40".as_ref(),
            "--align".as_ref(),
            align.as_ref(),
            "-q".as_ref(),
            "-o".as_ref(),
            out.as_os_str(),
        ]);
        assert_clean_failure(&output, &["holds the input"], None);
    }
    assert!(strokes.is_file() && surface.is_file());
}
