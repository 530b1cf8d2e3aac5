//! Writing a honeycomb structure directory: `base.obj`, `offset.obj`, `walls.obj`,
//! `structure.json`, `report.json` (and `quads.obj` for a quad-capped honeycomb). Every file is written to a temporary name and renamed, so a
//! reader never sees a half-written file.

use crate::error::{rounded, Error, Result};
use crate::geometry::Vec3;
use crate::mesh::io::read_file;
use crate::mesh::{validate_base_mesh, Outputs};
use crate::mesh::{Connectivity, PolyMesh};
use crate::optimize::MAX_LENGTH;
use crate::structure::{Honeycomb, StructureJson};
use std::path::Path;

mod frame;
mod glb;
mod model;

pub use frame::{Frame, Units, Up};
pub use glb::glb_bytes;
pub use model::{read_honeycomb, Model};

pub fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    let mut outputs = Outputs::new();
    stage_json(&mut outputs, path, value)?;
    outputs.commit()
}

/// Writes `value` as pretty JSON into a set of outputs.
pub fn stage_json(outputs: &mut Outputs, path: &Path, value: &impl serde::Serialize) -> Result<()> {
    outputs.file(path, |w| {
        serde_json::to_writer_pretty(&mut *w, value).map_err(std::io::Error::other)?;
        writeln!(w)
    })
}

pub fn write_structure(
    dir: &Path,
    honeycomb: &Honeycomb,
    report: &impl serde::Serialize,
) -> Result<()> {
    write_structure_with(dir, honeycomb, &[], report)
}

/// `write_structure` with more meshes (file name, mesh) written before `report.json`, which
/// comes last so that a report always describes complete files.
pub fn write_structure_with(
    dir: &Path,
    honeycomb: &Honeycomb,
    extra: &[(&str, &PolyMesh)],
    report: &impl serde::Serialize,
) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut outputs = Outputs::new();
    outputs.mesh(&dir.join("base.obj"), &honeycomb.base)?;
    outputs.mesh(&dir.join("offset.obj"), &honeycomb.offset)?;
    outputs.mesh(&dir.join("walls.obj"), &honeycomb.walls())?;
    stage_json(
        &mut outputs,
        &dir.join("structure.json"),
        &honeycomb.to_json(),
    )?;
    for (name, mesh) in extra {
        outputs.mesh(&dir.join(name), mesh)?;
    }
    stage_json(&mut outputs, &dir.join("report.json"), report)?;
    outputs.commit()
}

/// Reads `DIR/structure.json` back into a honeycomb, checking that it is one of ours.
pub fn read_structure(dir: &Path) -> Result<(Honeycomb, Connectivity)> {
    let path = dir.join("structure.json");
    let bad = |line: usize, message: String| Error::Parse {
        path: path.clone(),
        line,
        message,
    };
    let bytes = read_file(&path)?;
    let text = std::str::from_utf8(&bytes).map_err(|_| bad(0, "not UTF-8 text".into()))?;
    let s: StructureJson = serde_json::from_str(text)
        .map_err(|e| bad(e.line(), format!("not a structure.json: {e}")))?;
    let nv = s.vertices.len();
    if s.node_axes.len() != nv || s.offset_vertices.len() != nv {
        return Err(bad(
            0,
            format!(
                "{nv} vertices but {} node axes and {} offset vertices",
                s.node_axes.len(),
                s.offset_vertices.len()
            ),
        ));
    }
    if let Some(v) = s.node_axes.iter().position(|a| {
        !a.iter().all(|x| x.is_finite()) || (Vec3::from_slice(a).norm() - 1.0).abs() > 1e-6
    }) {
        return Err(bad(0, format!("node axis {v} is not a unit vector")));
    }
    if !s.thickness.is_finite() || s.thickness <= 0.0 {
        return Err(bad(
            0,
            format!(
                "thickness {} is not a positive length",
                rounded(s.thickness, 6)
            ),
        ));
    }
    let vertices: Vec<Vec3> = s.vertices.iter().map(|p| Vec3::from_slice(p)).collect();
    let base = PolyMesh::new(vertices, s.faces.clone());
    // The same checks as optimize's input: coincident or far-flung vertices leave the walls
    // undefined, and every measure and edit of them would be noise.
    let conn = validate_base_mesh(&base).map_err(|e| match e {
        Error::Mesh(message) => Error::Mesh(format!("{}: {message}", path.display())),
        other => other,
    })?;
    if conn.edges != s.edges {
        return Err(bad(0, "the edges do not match the faces".into()));
    }
    let offset: Vec<Vec3> = s
        .offset_vertices
        .iter()
        .map(|p| Vec3::from_slice(p))
        .collect();
    if let Some(v) = offset.iter().position(|p| !p.is_finite()) {
        return Err(bad(0, format!("offset vertex {v} is not finite")));
    }
    // At most as deep as optimize builds: beyond that every wall's measures are noise (and
    // their squares overflow).
    let edge = base.mean_edge_length();
    let deepest = MAX_LENGTH * edge;
    if s.thickness > deepest {
        return Err(bad(
            0,
            format!(
                "thickness {}: more than {MAX_LENGTH} mean edge lengths ({})",
                rounded(s.thickness, 6),
                rounded(edge, 6)
            ),
        ));
    }
    let too_deep = |(&o, &p): (&Vec3, &Vec3)| (o - p).norm() > deepest;
    if let Some(v) = offset.iter().zip(&base.vertices).position(too_deep) {
        return Err(bad(
            0,
            format!(
                "offset vertex {v} lies more than {MAX_LENGTH} mean edge lengths ({}) from \
                 its vertex",
                rounded(edge, 6)
            ),
        ));
    }
    // M' as written (its depth may vary, as for parallel meshes), with the written axes.
    let honeycomb = Honeycomb {
        offset: PolyMesh::new(offset, base.faces.clone()),
        base,
        edges: conn.edges.clone(),
        axes: s.node_axes.iter().map(|a| Vec3::from_slice(a)).collect(),
        thickness: s.thickness,
    };
    Ok((honeycomb, conn))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::upright_hex_disk;

    /// A structure directory holding `json` as its structure.json, removed on drop.
    struct StructureDir(std::path::PathBuf);

    impl StructureDir {
        fn new(name: &str, json: &StructureJson) -> StructureDir {
            let dir = std::env::temp_dir()
                .join(format!("honeycomb-export-{name}-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            write_json(&dir.join("structure.json"), json).unwrap();
            StructureDir(dir)
        }
    }

    impl Drop for StructureDir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// Seven flat hexagons with vertical walls.
    fn flat_structure() -> StructureJson {
        upright_hex_disk(2.0, 0.3).0.to_json()
    }

    fn read_error(name: &str, json: &StructureJson) -> String {
        let dir = StructureDir::new(name, json);
        match read_structure(&dir.0) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("{name}: read as a valid structure"),
        }
    }

    #[test]
    fn a_valid_structure_reads_back() {
        let json = flat_structure();
        let dir = StructureDir::new("valid", &json);
        let (h, conn) = read_structure(&dir.0).unwrap();
        assert_eq!(h.base.faces, json.faces);
        assert_eq!(conn.edges, json.edges);
    }

    #[test]
    fn coincident_vertices_are_refused_naming_the_file() {
        let mut json = flat_structure();
        json.vertices.iter_mut().for_each(|p| *p = [1.0, 1.0, 1.0]);
        let message = read_error("all-same", &json);
        assert!(
            message.contains("structure.json: zero-length edge"),
            "{message}"
        );

        let mut json = flat_structure();
        let [a, b] = json.edges[0];
        json.vertices[b] = json.vertices[a];
        let message = read_error("duplicate", &json);
        assert!(
            message.contains(&format!("structure.json: zero-length edge {a}-{b}")),
            "{message}"
        );
    }

    #[test]
    fn a_wall_deeper_than_optimize_builds_is_refused() {
        // The editor's states and saves of such a structure held inf and null.
        let mut json = flat_structure();
        json.offset_vertices[3][2] = 1e160;
        let message = read_error("deep-offset", &json);
        assert!(
            message.contains("offset vertex 3 lies more than 1000 mean edge lengths"),
            "{message}"
        );
        let mut json = flat_structure();
        json.thickness = 1e6;
        let message = read_error("deep-thickness", &json);
        assert!(
            message.contains("thickness 1000000: more than 1000"),
            "{message}"
        );
    }
}
