//! Wavefront OBJ: `v` and `f` records. Everything else (normals, texture coordinates, groups,
//! materials, `l` polylines, which are read elsewhere) is ignored.

use super::{before, check_face_range, parse_error, parse_position, text_lines, LoadedMesh};
use crate::error::Result;
use crate::mesh::PolyMesh;
use std::io::Write;
use std::path::Path;

/// Parses OBJ text; `path` only names the file in messages.
pub fn parse_obj(text: &str, path: &Path) -> Result<LoadedMesh> {
    if text_lines(text).all(|line| line.trim().is_empty()) {
        return Err(parse_error(path, 0, "empty file"));
    }
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    let mut face_lines = Vec::new();
    for (i, raw) in text_lines(text).enumerate() {
        let line = i + 1;
        let mut tokens = before(raw, '#').split_whitespace();
        match tokens.next() {
            Some("v") => {
                let p = parse_position(&mut tokens, vertices.len(), path, line)?;
                vertices.push(p);
            }
            Some("f") => {
                faces.push(parse_face(tokens, faces.len(), vertices.len(), path, line)?);
                face_lines.push(line);
            }
            _ => {}
        }
    }
    if vertices.is_empty() && faces.is_empty() {
        // Read lossily, binary data shows as NULs and replacement characters.
        let binary = text.contains(['\0', char::REPLACEMENT_CHARACTER]);
        return Err(parse_error(
            path,
            0,
            if binary {
                "not a text OBJ file (binary data): is it another format?"
            } else {
                "no vertex (`v`) or face (`f`) records"
            },
        ));
    }
    // Positive indices may refer to vertices defined later, so they are checked at the end.
    check_face_range(&faces, &face_lines, vertices.len(), 1, path)?;
    Ok(LoadedMesh {
        mesh: PolyMesh::new(vertices, faces),
        warnings: Vec::new(),
    })
}

/// Reads the vertex references of face `face` (`a`, `a/b`, `a//c` or `a/b/c`) as 0-based
/// indices; negative ones count back from the last of the `defined` vertices so far.
fn parse_face<'a>(
    tokens: impl Iterator<Item = &'a str>,
    face: usize,
    defined: usize,
    path: &Path,
    line: usize,
) -> Result<Vec<usize>> {
    let mut indices = Vec::new();
    for token in tokens {
        let k: i64 = before(token, '/').parse().map_err(|_| {
            parse_error(
                path,
                line,
                format!("face {face}: '{token}' is not a vertex index"),
            )
        })?;
        let index = match k {
            0 => {
                return Err(parse_error(
                    path,
                    line,
                    format!("face {face}: vertex index 0 is invalid (OBJ indices start at 1)"),
                ))
            }
            // Beyond usize only on 32-bit targets: saturate and let the range check report it.
            k if k > 0 => usize::try_from(k - 1).unwrap_or(usize::MAX),
            k => usize::try_from(defined as i64 + k).map_err(|_| {
                parse_error(
                    path,
                    line,
                    format!(
                        "face {face}: relative index {k} points before the first vertex \
                         ({defined} vertices defined so far)"
                    ),
                )
            })?,
        };
        indices.push(index);
    }
    if indices.len() < 3 {
        return Err(parse_error(
            path,
            line,
            format!(
                "face {face} has {} vertices; a face needs at least 3",
                indices.len()
            ),
        ));
    }
    Ok(indices)
}

/// Writes `v` and `f` records (1-based indices) with coordinates in full precision.
pub fn write_obj(w: &mut dyn Write, mesh: &PolyMesh) -> std::io::Result<()> {
    writeln!(
        w,
        "# honeycomb: {} vertices, {} faces",
        mesh.vertices.len(),
        mesh.faces.len()
    )?;
    for v in &mesh.vertices {
        writeln!(w, "v {} {} {}", v.x, v.y, v.z)?;
    }
    for f in &mesh.faces {
        write!(w, "f")?;
        for &i in f {
            write!(w, " {}", i + 1)?;
        }
        writeln!(w)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::sample_mesh;
    use super::*;
    use crate::geometry::Vec3;

    fn parse(text: &str) -> Result<LoadedMesh> {
        parse_obj(text, Path::new("test.obj"))
    }

    fn error(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    #[test]
    fn round_trip_keeps_every_bit() {
        let mesh = sample_mesh();
        let mut bytes = Vec::new();
        write_obj(&mut bytes, &mesh).unwrap();
        let loaded = parse(&String::from_utf8(bytes).unwrap()).unwrap();
        assert_eq!(loaded.mesh, mesh);
        assert!(loaded.warnings.is_empty());
    }

    #[test]
    fn reads_every_face_reference_form_and_ignores_other_records() {
        let text = "\u{feff}# a quad and a hexagon\r\n\
                    mtllib x.mtl\r\n\
                    o thing\n\
                    v 0 0 0\n\
                    v 1 0 0 1.0\n\
                    v 1 1 0 0.5 0.5 0.5\n\
                    v 0 1 0 # trailing comment\n\
                    vn 0 0 1\n\
                    vt 0.5 0.5\n\
                    g group\n\
                    s off\n\
                    usemtl red\n\
                    f 1 2/1 3//1 4/1/1\n\
                    l 1 2 3\n\
                    v 2 0 0\n\
                    v 2 1 0\n\
                    f -5 -4 -2 -1 -3 -6\n";
        let mesh = parse(text).unwrap().mesh;
        assert_eq!(mesh.vertices.len(), 6);
        assert_eq!(mesh.vertices[2], Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(mesh.faces, vec![vec![0, 1, 2, 3], vec![1, 2, 4, 5, 3, 0]]);
    }

    #[test]
    fn every_line_ending_reads_alike() {
        let lf = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let expected = parse(lf).unwrap().mesh;
        assert_eq!(expected.faces, vec![vec![0, 1, 2]]);
        for text in [lf.replace('\n', "\r\n"), lf.replace('\n', "\r")] {
            assert_eq!(parse(&text).unwrap().mesh, expected, "{text:?}");
        }
        // Line numbers count CR-only lines too.
        let err = error("v 0 0 0\rv 1 0 0\rv 0 x 0\r");
        assert!(err.contains("test.obj:3: vertex 2: 'x'"), "{err}");
    }

    #[test]
    fn faces_may_refer_to_later_vertices() {
        let mesh = parse("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap().mesh;
        assert_eq!(mesh.faces, vec![vec![0, 1, 2]]);
    }

    #[test]
    fn empty_file() {
        assert!(error("").contains("empty file"));
        assert!(error(" \n\t\n").contains("empty file"));
        assert!(error("# only a comment\no name\n").contains("no vertex (`v`) or face (`f`)"));
        let binary = String::from_utf8_lossy(&[0x7f, 0x45, 0x4c, 0x46, 0, 0xff, 0xfe]);
        assert!(error(&binary).contains("not a text OBJ file"));
    }

    #[test]
    fn non_numeric_coordinate_names_the_line() {
        let err = error("v 0 0 0\n\nv 1 abc 0\n");
        assert!(err.contains("test.obj:3:"), "{err}");
        assert!(err.contains("vertex 1: 'abc' is not a number"), "{err}");
    }

    #[test]
    fn missing_coordinate() {
        let err = error("v 0 0\n");
        assert!(
            err.contains(":1:") && err.contains("vertex 0 has 2 coordinates"),
            "{err}"
        );
    }

    #[test]
    fn non_finite_coordinate_names_vertex_and_line() {
        let err = error("v 0 0 0\nv 1 NaN 0\n");
        assert!(err.contains(":2:"), "{err}");
        assert!(
            err.contains("vertex 1 has a non-finite coordinate"),
            "{err}"
        );
        let err = error("v inf 0 0\n");
        assert!(
            err.contains("vertex 0 has a non-finite coordinate: (inf"),
            "{err}"
        );
    }

    #[test]
    fn out_of_range_index_names_face_and_line() {
        let err = error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n");
        assert!(err.contains(":5:"), "{err}");
        assert!(
            err.contains("face 1: vertex index 4 is out of range (the file has 3 vertices)"),
            "{err}"
        );
    }

    #[test]
    fn bad_indices() {
        let err = error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
        assert!(
            err.contains(":4:") && err.contains("index 0 is invalid"),
            "{err}"
        );
        let err = error("v 0 0 0\nv 1 0 0\nf -1 -2 -3\n");
        assert!(
            err.contains(":3:") && err.contains("relative index -3"),
            "{err}"
        );
        let err = error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n");
        assert!(err.contains("face 0: 'x' is not a vertex index"), "{err}");
        let err = error("v 0 0 0\nv 1 0 0\nf 1 2\n");
        assert!(err.contains("face 0 has 2 vertices"), "{err}");
        let err = error("f 1 2 99999999999999999999\n");
        assert!(err.contains("not a vertex index"), "{err}");
    }

    #[test]
    fn no_prefix_of_a_valid_file_panics() {
        let mut bytes = Vec::new();
        write_obj(&mut bytes, &sample_mesh()).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        for end in (0..=text.len()).filter(|&e| text.is_char_boundary(e)) {
            let _ = parse(&text[..end]);
        }
    }
}
