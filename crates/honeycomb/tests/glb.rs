//! `structure.glb`: its named nodes and wall positions read back with the `gltf` crate, the
//! Khronos validator's verdict on a honeycomb across a saddle, and (where installed) Blender's
//! importer.

use honeycomb::export::{glb_bytes, Frame, Model, Units};
use honeycomb::generate::{design_surface, Shape};
use honeycomb::mesh::PolyMesh;
use honeycomb::structure::Honeycomb;
use honeycomb::{pipeline, PipelineOptions, Progress, Surface};
use std::collections::HashMap;
use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

/// A honeycomb across a saddle and the saddle's mesh, made once for every test here.
fn saddle() -> &'static (Honeycomb, PolyMesh) {
    static MADE: OnceLock<(Honeycomb, PolyMesh)> = OnceLock::new();
    MADE.get_or_init(|| {
        let surface = design_surface(Shape::Saddle);
        let s = Surface::new(surface.clone()).unwrap();
        let made = pipeline(&s, &PipelineOptions::new(150), &mut Progress::silent())
            .unwrap_or_else(|e| panic!("saddle: {e}"));
        assert!(made.is_honeycomb(), "saddle: {:?}", made.report.notes);
        (made.honeycomb, surface)
    })
}

fn saddle_glb(units: Units) -> (Model, Vec<u8>) {
    let (h, s) = saddle();
    let model = Model::new(h.clone(), Some(s.clone()), units).unwrap();
    let bytes = glb_bytes(&model).unwrap();
    (model, bytes)
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A file in a fresh temporary directory, removed on drop.
struct TempFile(PathBuf);

impl TempFile {
    fn new(name: &str, bytes: &[u8]) -> TempFile {
        let dir = std::env::temp_dir().join(format!("honeycomb-glb-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        TempFile(path)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
        if let Some(dir) = self.0.parent() {
            let _ = std::fs::remove_dir(dir);
        }
    }
}

fn extras(e: &Option<Box<serde_json::value::RawValue>>) -> serde_json::Value {
    serde_json::from_str(e.as_ref().expect("extras").get()).unwrap()
}

type Rgb = [f32; 3];

/// The vertex positions of the mesh on `node`, with its triangles' indices and the vertex
/// colours, if any.
fn mesh_data(gltf: &gltf::Gltf, node: &gltf::Node) -> (Vec<[f32; 3]>, Vec<u32>, Option<Vec<Rgb>>) {
    let blob = gltf.blob.as_deref().expect("a BIN chunk");
    let mesh = node
        .mesh()
        .unwrap_or_else(|| panic!("{:?}: no mesh", node.name()));
    let primitive = mesh.primitives().next().unwrap();
    let reader = primitive.reader(|_| Some(blob));
    (
        reader.read_positions().unwrap().collect(),
        reader.read_indices().unwrap().into_u32().collect(),
        reader.read_colors(0).map(|c| c.into_rgb_f32().collect()),
    )
}

fn mesh_positions(gltf: &gltf::Gltf, node: &gltf::Node) -> Vec<[f32; 3]> {
    mesh_data(gltf, node).0
}

#[test]
fn the_named_nodes_hold_every_wall_and_cell_in_metres_with_y_up() {
    let (model, metres) = saddle_glb(Units::M);
    let (_, millimetres) = saddle_glb(Units::Mm);
    let h = &model.honeycomb;
    let gltf = gltf::Gltf::from_slice(&metres).unwrap();
    let scene = gltf.default_scene().expect("a default scene");
    let top: Vec<&str> = scene.nodes().map(|n| n.name().unwrap()).collect();
    assert_eq!(
        top,
        ["surface", "base", "offset", "walls", "node_axes", "cells"]
    );
    let by_name: HashMap<&str, gltf::Node> = gltf.nodes().map(|n| (n.name().unwrap(), n)).collect();

    let walls: Vec<String> = by_name["walls"]
        .children()
        .map(|n| n.name().unwrap().to_string())
        .collect();
    let expected: Vec<String> = (0..h.edges.len()).map(|e| format!("W{e}")).collect();
    assert_eq!(walls, expected);
    let cells: Vec<String> = by_name["cells"]
        .children()
        .map(|n| n.name().unwrap().to_string())
        .collect();
    let expected: Vec<String> = (0..h.base.faces.len()).map(|f| format!("C{f}")).collect();
    assert_eq!(cells, expected);
    assert_eq!(
        gltf.meshes().filter(|m| m.name() == Some("W0")).count(),
        1,
        "each wall's mesh is named like its node"
    );

    // One wall, numerically: v_a v_b v'_b v'_a in metres with Y up.
    let e = h.edges.len() / 2;
    let name = format!("W{e}");
    let wall = &by_name[name.as_str()];
    let extra = extras(wall.extras());
    assert_eq!(extra["edge"], e);
    assert_eq!(extra["nodes"], serde_json::json!(h.edges[e]));
    let frame = Frame::gltf(Units::M);
    let (got, triangles, colours) = mesh_data(&gltf, wall);
    assert_eq!(triangles, [0, 1, 2, 0, 2, 3]);
    let colours = colours.expect("COLOR_0 on a wall");
    assert!(
        colours.len() == 4 && colours.iter().all(|&c| c == colours[0]),
        "{colours:?}"
    );
    let want = h.wall(e).map(|p| frame.point(p));
    assert_eq!(got.len(), 4);
    for (g, w) in got.iter().zip(&want) {
        for k in 0..3 {
            assert!(
                (g[k] as f64 - w[k]).abs() <= 1e-6 * (1.0 + w[k].abs()),
                "{name}: {got:?} vs {want:?}"
            );
        }
    }
    // Y up: the model's Z is glTF's Y.
    assert!((got[0][1] as f64 - h.wall(e)[0].z).abs() < 1e-5);

    // The same model in millimetres is a thousandth of the size.
    let small = gltf::Gltf::from_slice(&millimetres).unwrap();
    let node = small
        .nodes()
        .find(|n| n.name() == Some(name.as_str()))
        .unwrap();
    for (g, w) in mesh_positions(&small, &node).iter().zip(&want) {
        for k in 0..3 {
            assert!(
                (g[k] as f64 - 0.001 * w[k]).abs() <= 1e-9 * (1.0 + w[k].abs()),
                "{name} in mm"
            );
        }
    }
    let asset = extras(&small.document.as_json().asset.extras);
    assert_eq!(
        asset,
        serde_json::json!({"units": "m", "source_units": "mm"})
    );
}

#[test]
fn without_a_surface_there_is_no_surface_node() {
    let (h, _) = saddle();
    let model = Model::new(h.clone(), None, Units::M).unwrap();
    let gltf = gltf::Gltf::from_slice(&glb_bytes(&model).unwrap()).unwrap();
    let top: Vec<&str> = gltf
        .default_scene()
        .unwrap()
        .nodes()
        .map(|n| n.name().unwrap())
        .collect();
    assert_eq!(top, ["base", "offset", "walls", "node_axes", "cells"]);
}

/// What the validator test needs and lacks, if anything.
fn validator_missing() -> Option<String> {
    if Command::new("node").arg("--version").output().is_err() {
        return Some("no node".into());
    }
    if !repo().join("web/node_modules/gltf-validator").exists() {
        return Some("no web/node_modules/gltf-validator (npm ci --prefix web)".into());
    }
    None
}

#[test]
fn the_khronos_validator_finds_no_error_or_warning() {
    if let Some(why) = validator_missing() {
        if std::env::var("HONEYCOMB_E2E").as_deref() == Ok("1") {
            panic!("HONEYCOMB_E2E=1 but the glTF validator cannot run: {why}");
        }
        println!("skipped: {why}");
        return;
    }
    let (_, bytes) = saddle_glb(Units::Mm);
    let file = TempFile::new("structure.glb", &bytes);
    let out = Command::new("node")
        .arg(repo().join("web/e2e/validate-glb.mjs"))
        .arg(&file.0)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "validator: {stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    println!("{report}");
    assert_eq!(report["numErrors"], 0, "{report:#}");
    assert_eq!(report["numWarnings"], 0, "{report:#}");
}

/// Imports the file named after `--` and prints each object with its parent; prints
/// `UNUSABLE` instead when Blender's Python lacks numpy, which its glTF importer needs (Debian's
/// Blender without python3-numpy): that says nothing about the file. Flat shading: the walls are
/// planar, and the importer's default (guessing smooth faces from normals) fails with Debian's
/// Blender 3.4 and numpy 1.24 on any file.
const BLENDER_SCRIPT: &str = r#"
import sys, bpy
try:
    import numpy
except ImportError as e:
    print('UNUSABLE', e)
else:
    bpy.ops.import_scene.gltf(filepath=sys.argv[sys.argv.index('--') + 1], import_shading='FLAT')
    for o in bpy.data.objects:
        print('OBJECT', o.name, o.parent.name if o.parent else '-')
"#;

#[test]
fn blender_imports_the_named_objects() {
    if Command::new("blender").arg("--version").output().is_err() {
        println!("skipped: blender not installed");
        return;
    }
    let (_, bytes) = saddle_glb(Units::M);
    let file = TempFile::new("blender.glb", &bytes);
    let out = Command::new("blender")
        .args(["--background", "--factory-startup", "--python-expr"])
        .arg(BLENDER_SCRIPT)
        .arg("--")
        .arg(&file.0)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    if let Some(why) = stdout.lines().find_map(|l| l.strip_prefix("UNUSABLE ")) {
        println!("skipped: blender cannot import glTF here: {why}");
        return;
    }
    for line in [
        "OBJECT base -",
        "OBJECT walls -",
        "OBJECT W0 walls",
        "OBJECT W1 walls",
        "OBJECT C0 cells",
    ] {
        assert!(
            stdout.lines().any(|l| l.trim() == line),
            "no {line:?} in Blender's output:\n{stdout}{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
