//! Mesh files: OBJ, OFF and PLY readers, and writers that replace their target atomically.
//!
//! Readers never panic on malformed input: every problem becomes an [`Error::Parse`] naming the
//! file, the line (0 when none applies, e.g. in binary data) and what was expected. Vertex and
//! face numbers in messages are 0-based, as everywhere in the library; OBJ index values are
//! quoted as written in the file.

mod atomic;
mod input;
mod obj;
mod off;
mod ply;

pub use atomic::{
    replace_folder, write_atomically, write_output_dir, OutputDir, Outputs, Previous, Verdict,
};
pub use input::{read_file, strip_bom_bytes, text_lines, TextLines, MAX_INPUT_BYTES};

pub use obj::{parse_obj, write_obj};
pub use off::{parse_off, write_off};
pub use ply::{parse_ply, write_ply};

use crate::error::{short_point, Error, Result};
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use std::io::Write;
use std::path::Path;

/// A mesh read from a file, with the non-fatal oddities found while reading it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadedMesh {
    pub mesh: PolyMesh,
    pub warnings: Vec<String>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Format {
    Obj,
    Off,
    Ply,
}

impl Format {
    /// The format named by the file extension (case-insensitive), or a message saying why not.
    fn of(path: &Path) -> std::result::Result<Format, String> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("obj") => Ok(Format::Obj),
            Some("off") => Ok(Format::Off),
            Some("ply") => Ok(Format::Ply),
            Some(other) => Err(format!(
                "unknown mesh format '.{other}': expected .obj, .off or .ply"
            )),
            None => Err(
                "unknown mesh format (no file extension): expected .obj, .off or .ply".to_string(),
            ),
        }
    }
}

/// Reads an OBJ, OFF or PLY file, chosen by its extension.
pub fn read_mesh(path: &Path) -> Result<LoadedMesh> {
    let format = Format::of(path).map_err(|message| parse_error(path, 0, message))?;
    let bytes = read_file(path)?;
    match format {
        Format::Obj => parse_obj(&String::from_utf8_lossy(&bytes), path),
        Format::Off => parse_off(&String::from_utf8_lossy(&bytes), path),
        Format::Ply => parse_ply(&bytes, path),
    }
}

/// Reads a design surface as [`read_mesh`] does, repaired
/// ([`crate::mesh::repair_surface_mesh`]) with a warning for each repair.
pub fn read_surface(path: &Path) -> Result<LoadedMesh> {
    read_repaired(path, crate::mesh::repair_surface_mesh)
}

/// Reads a base mesh as [`read_mesh`] does, repaired ([`crate::mesh::repair_base_mesh`]) with
/// a warning for each repair.
pub fn read_base(path: &Path) -> Result<LoadedMesh> {
    read_repaired(path, crate::mesh::repair_base_mesh)
}

fn read_repaired(path: &Path, repair: fn(&mut PolyMesh) -> Vec<String>) -> Result<LoadedMesh> {
    let mut loaded = read_mesh(path)?;
    for repaired in repair(&mut loaded.mesh) {
        loaded
            .warnings
            .push(format!("{}: {repaired}", path.display()));
    }
    Ok(loaded)
}

/// Writes `mesh` as OBJ, OFF or ASCII PLY, chosen by the extension of `path`.
pub fn write_mesh(path: &Path, mesh: &PolyMesh) -> Result<()> {
    let mut outputs = Outputs::new();
    outputs.mesh(path, mesh)?;
    outputs.commit()
}

/// `mesh` in the format `path` names, for writing to `path`.
fn mesh_writer<'a>(
    path: &Path,
    mesh: &'a PolyMesh,
) -> Result<impl FnOnce(&mut dyn Write) -> std::io::Result<()> + 'a> {
    let format = Format::of(path).map_err(|message| {
        Error::Parameter(format!("cannot write {}: {message}", path.display()))
    })?;
    Ok(move |w: &mut dyn Write| match format {
        Format::Obj => write_obj(w, mesh),
        Format::Off => write_off(w, mesh),
        Format::Ply => write_ply(w, mesh),
    })
}

/// The body shared by OFF and ASCII PLY: one `x y z` line per vertex, then one
/// `k i_1 ... i_k` line per face.
fn write_counted_body(w: &mut dyn Write, mesh: &PolyMesh) -> std::io::Result<()> {
    for v in &mesh.vertices {
        writeln!(w, "{} {} {}", v.x, v.y, v.z)?;
    }
    for f in &mesh.faces {
        write!(w, "{}", f.len())?;
        for &i in f {
            write!(w, " {i}")?;
        }
        writeln!(w)?;
    }
    Ok(())
}

fn parse_error(path: &Path, line: usize, message: impl Into<String>) -> Error {
    Error::Parse {
        path: path.to_path_buf(),
        line,
        message: message.into(),
    }
}

/// How many items to preallocate for `count` items announced by a header, when each item takes
/// at least `min_item_bytes` of the `available` bytes: a bogus count cannot exhaust memory.
fn capacity(count: usize, available: usize, min_item_bytes: usize) -> usize {
    count.min(available / min_item_bytes.max(1))
}

/// The text before the first `c` (all of it when there is none).
fn before(text: &str, c: char) -> &str {
    text.find(c).map_or(text, |i| &text[..i])
}

/// Reads the x, y, z of vertex `index` from `tokens`; values after them (an OBJ `w`, colours,
/// normals) are left unread.
fn parse_position<'a>(
    tokens: &mut impl Iterator<Item = &'a str>,
    index: usize,
    path: &Path,
    line: usize,
) -> Result<Vec3> {
    let mut c = [0.0; 3];
    for (k, slot) in c.iter_mut().enumerate() {
        let token = tokens.next().ok_or_else(|| {
            parse_error(
                path,
                line,
                format!("vertex {index} has {k} coordinates; expected 3"),
            )
        })?;
        *slot = token.parse().map_err(|_| {
            parse_error(
                path,
                line,
                format!("vertex {index}: '{token}' is not a number"),
            )
        })?;
    }
    let p = Vec3::new(c[0], c[1], c[2]);
    check_finite(p, index, path, line)?;
    Ok(p)
}

fn check_finite(p: Vec3, index: usize, path: &Path, line: usize) -> Result<()> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(parse_error(
            path,
            line,
            format!(
                "vertex {index} has a non-finite coordinate: {}",
                short_point(p)
            ),
        ))
    }
}

/// Fails on the first face index that is not below `vertex_count`. `shown_base` is added to
/// indices in the message so that they read as in the file (1 for OBJ).
fn check_face_range(
    faces: &[Vec<usize>],
    face_lines: &[usize],
    vertex_count: usize,
    shown_base: usize,
    path: &Path,
) -> Result<()> {
    for (f, (face, &line)) in faces.iter().zip(face_lines).enumerate() {
        if let Some(&v) = face.iter().find(|&&v| v >= vertex_count) {
            return Err(parse_error(
                path,
                line,
                format!(
                    "face {f}: vertex index {} is out of range (the file has {vertex_count} vertices)",
                    v.saturating_add(shown_base)
                ),
            ));
        }
    }
    Ok(())
}

/// A test mesh with awkward coordinates and a hexagon, a quad and a triangle.
#[cfg(test)]
fn sample_mesh() -> PolyMesh {
    let vertices = vec![
        Vec3::new(0.1, -0.0, 1.0 / 3.0),
        Vec3::new(1e-300, 2.5e17, -7.0),
        Vec3::new(std::f64::consts::PI, 1e-7, 123456.789),
        Vec3::new(-1.5, 0.2, 0.3),
        Vec3::new(4.0, 5.0, 6.0),
        Vec3::new(f64::MAX, f64::MIN_POSITIVE, -2.0),
        Vec3::new(7.0, 8.0, 9.0),
        Vec3::new(10.0, 11.0, 12.0),
    ];
    let faces = vec![vec![0, 1, 2, 3, 4, 5], vec![1, 6, 7, 2], vec![5, 4, 7]];
    PolyMesh::new(vertices, faces)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh empty directory under the system temporary directory.
    fn temp_dir(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("honeycomb-io-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create test directory");
        dir
    }

    fn dir_entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .expect("list test directory")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn write_then_read_every_format() {
        let dir = temp_dir("roundtrip");
        let mesh = sample_mesh();
        for name in ["m.obj", "m.off", "m.ply", "UPPER.OBJ", "Mixed.Ply"] {
            let path = dir.join(name);
            write_mesh(&path, &mesh).expect("write");
            let loaded = read_mesh(&path).expect("read");
            assert_eq!(loaded.mesh, mesh, "{name}");
            assert!(loaded.warnings.is_empty(), "{name}: {:?}", loaded.warnings);
        }
        // Only the targets remain: no temporary files left behind.
        assert_eq!(
            dir_entries(&dir),
            ["Mixed.Ply", "UPPER.OBJ", "m.obj", "m.off", "m.ply"]
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn unknown_extension_is_rejected() {
        let err = read_mesh(Path::new("points.xyz")).unwrap_err().to_string();
        assert!(err.contains("unknown mesh format '.xyz'"), "{err}");
        assert!(err.contains(".obj, .off or .ply"), "{err}");
        let err = read_mesh(Path::new("mesh")).unwrap_err().to_string();
        assert!(err.contains("no file extension"), "{err}");
        let err = write_mesh(Path::new("out.stl"), &sample_mesh())
            .unwrap_err()
            .to_string();
        assert!(err.contains("unknown mesh format '.stl'"), "{err}");
    }

    #[test]
    fn missing_file_is_an_io_error_naming_the_path() {
        let err = read_mesh(Path::new("/nonexistent/dir/mesh.obj")).unwrap_err();
        assert!(matches!(err, Error::Io { .. }));
        assert!(err.to_string().contains("/nonexistent/dir/mesh.obj"));
    }

    #[test]
    fn failed_write_keeps_the_old_file_and_removes_the_temporary() {
        let dir = temp_dir("atomic");
        let path = dir.join("out.obj");
        std::fs::write(&path, "old").expect("write old file");
        let err = write_atomically(&path, |w| {
            w.write_all(b"partial")?;
            Err(std::io::Error::other("disk full"))
        })
        .unwrap_err();
        assert!(err.to_string().contains("disk full"), "{err}");
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "old");
        assert_eq!(dir_entries(&dir), ["out.obj"]);

        write_atomically(&path, |w| w.write_all(b"new")).expect("write");
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "new");
        assert_eq!(dir_entries(&dir), ["out.obj"]);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn write_into_missing_directory_fails_cleanly() {
        let err = write_mesh(Path::new("/nonexistent/dir/out.off"), &sample_mesh()).unwrap_err();
        assert!(matches!(err, Error::Io { .. }));
        assert!(err.to_string().contains("/nonexistent/dir/out.off"));
    }
}
