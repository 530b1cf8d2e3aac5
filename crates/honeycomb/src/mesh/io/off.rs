//! Object File Format (OFF) and its variants with per-vertex extras (`COFF`, `NOFF`, `STOFF`,
//! ...): one vertex per line, then one face per line as `k i1 .. ik [colour]`.

use super::{
    before, capacity, check_face_range, parse_error, parse_position, text_lines,
    write_counted_body, LoadedMesh,
};
use crate::error::Result;
use crate::mesh::PolyMesh;
use std::io::Write;
use std::path::Path;

/// Parses OFF text; `path` only names the file in messages.
pub fn parse_off(text: &str, path: &Path) -> Result<LoadedMesh> {
    // Significant lines with their 1-based numbers: comments stripped, blank lines skipped.
    let mut lines = text_lines(text).enumerate().filter_map(|(i, raw)| {
        let content = before(raw, '#');
        (!content.trim().is_empty()).then_some((i + 1, content))
    });
    let Some((header_line, header)) = lines.next() else {
        return Err(parse_error(path, 0, "empty file"));
    };
    let mut tokens = header.split_whitespace();
    check_keyword(tokens.next().unwrap_or(""), path, header_line)?;
    if tokens.clone().next() == Some("BINARY") {
        return Err(parse_error(
            path,
            header_line,
            "binary OFF is not supported; convert the file to ASCII OFF, OBJ or PLY",
        ));
    }
    // The counts may follow the keyword on the same line.
    let (count_line, mut counts) = if tokens.clone().next().is_some() {
        (header_line, tokens)
    } else {
        let (line, content) = lines.next().ok_or_else(|| {
            parse_error(path, header_line, "the vertex and face counts are missing")
        })?;
        (line, content.split_whitespace())
    };
    let mut count = |what: &str| -> Result<usize> {
        let token = counts.next().unwrap_or("nothing");
        token.parse().map_err(|_| {
            parse_error(
                path,
                count_line,
                format!("expected the {what} count, found '{token}'"),
            )
        })
    };
    let vertex_count = count("vertex")?;
    let face_count = count("face")?;

    let mut vertices = Vec::with_capacity(capacity(vertex_count, text.len(), "0 0 0\n".len()));
    // The first line read as a vertex that reads like a face: a vertex count too large takes
    // face lines for vertices, and the file then ends early.
    let mut face_like = None;
    for i in 0..vertex_count {
        let (line, content) = lines
            .next()
            .ok_or_else(|| truncated(path, vertex_count, "vertices", i, face_like))?;
        if face_like.is_none() && reads_like_a_face(content) {
            face_like = Some((i, line));
        }
        // Only x, y, z are read: NOFF normals, COFF colours etc. follow them on the line.
        vertices.push(parse_position(
            &mut content.split_whitespace(),
            i,
            path,
            line,
        )?);
    }

    let face_capacity = capacity(face_count, text.len(), "3 0 1 2\n".len());
    let mut faces = Vec::with_capacity(face_capacity);
    let mut face_lines = Vec::with_capacity(face_capacity);
    for f in 0..face_count {
        let (line, content) = lines
            .next()
            .ok_or_else(|| truncated(path, face_count, "faces", f, face_like))?;
        faces.push(parse_face(content, f, path, line)?);
        face_lines.push(line);
    }

    let mut warnings = Vec::new();
    let extra_lines = lines.count();
    if extra_lines > 0 {
        warnings.push(format!(
            "{}: {extra_lines} lines after the last face ignored (the header says {face_count} faces)",
            path.display()
        ));
    }
    // Some tools write 1-based indices. Without index 0 and with an index equal to the vertex
    // count, 0-based reading is impossible while 1-based reading uses every index.
    let uses_zero = faces.iter().flatten().any(|&v| v == 0);
    let max_index = faces.iter().flatten().copied().max();
    if !uses_zero && max_index == Some(vertex_count) {
        for v in faces.iter_mut().flatten() {
            *v -= 1;
        }
        warnings.push(format!(
            "{}: face indices are 1-based (no index 0, max index = vertex count = {vertex_count}); \
             read as 1-based",
            path.display()
        ));
    }
    check_face_range(&faces, &face_lines, vertex_count, 0, path)?;
    Ok(LoadedMesh {
        mesh: PolyMesh::new(vertices, faces),
        warnings,
    })
}

/// Accepts `OFF` with any of the prefixes for per-vertex extras: `ST` (texture coordinates),
/// `C` (colour), `N` (normal). `4` (homogeneous) and `n` (other dimensions) change the
/// coordinate layout and are rejected.
fn check_keyword(keyword: &str, path: &Path, line: usize) -> Result<()> {
    let Some(prefix) = keyword.strip_suffix("OFF") else {
        return Err(parse_error(
            path,
            line,
            format!("not an OFF file: expected the 'OFF' header, found '{keyword}'"),
        ));
    };
    if prefix.contains(['4', 'n']) {
        return Err(parse_error(
            path,
            line,
            format!("'{keyword}' (homogeneous or non-3D coordinates) is not supported"),
        ));
    }
    if !prefix.chars().all(|c| "STCN".contains(c)) {
        return Err(parse_error(
            path,
            line,
            format!("unknown OFF variant '{keyword}'"),
        ));
    }
    Ok(())
}

/// `face_like`: the first line read as a vertex that reads like a face (vertex, line).
fn truncated(
    path: &Path,
    expected: usize,
    what: &str,
    found: usize,
    face_like: Option<(usize, usize)>,
) -> crate::error::Error {
    let hint = match face_like {
        Some((vertex, line)) => format!(
            "; line {line}, read as vertex {vertex}, reads like a face: is the vertex count \
             {vertex} rather than the header's?"
        ),
        None => String::new(),
    };
    parse_error(
        path,
        0,
        format!(
            "truncated file: the header says {expected} {what}, but only {found} were found{hint}"
        ),
    )
}

/// `k i1 .. ik ...`: a vertex count of at least 3 followed by at least that many integers.
/// (A plain OFF vertex line has three numbers, so this never takes one for a face.)
fn reads_like_a_face(content: &str) -> bool {
    let mut tokens = content.split_whitespace();
    let Some(Ok(k)) = tokens.next().map(str::parse::<usize>) else {
        return false;
    };
    k >= 3
        && tokens
            .take(k)
            .filter(|t| t.parse::<usize>().is_ok())
            .count()
            == k
}

/// Reads `k i1 .. ik`; anything after the indices (a colour) is ignored.
fn parse_face(content: &str, face: usize, path: &Path, line: usize) -> Result<Vec<usize>> {
    let mut tokens = content.split_whitespace();
    let first = tokens.next().unwrap_or("");
    let k: usize = first.parse().map_err(|_| {
        parse_error(
            path,
            line,
            format!("face {face}: expected its vertex count, found '{first}'"),
        )
    })?;
    if k < 3 {
        return Err(parse_error(
            path,
            line,
            format!("face {face} has {k} vertices; a face needs at least 3"),
        ));
    }
    let mut indices = Vec::with_capacity(k.min(content.len()));
    for listed in 0..k {
        let token = tokens.next().ok_or_else(|| {
            parse_error(
                path,
                line,
                format!("face {face} announces {k} vertices but lists {listed}"),
            )
        })?;
        indices.push(token.parse().map_err(|_| {
            parse_error(
                path,
                line,
                format!("face {face}: '{token}' is not a vertex index"),
            )
        })?);
    }
    Ok(indices)
}

/// Writes plain `OFF` (0-based indices, edge count 0) with coordinates in full precision.
pub fn write_off(w: &mut dyn Write, mesh: &PolyMesh) -> std::io::Result<()> {
    writeln!(w, "OFF")?;
    writeln!(w, "{} {} 0", mesh.vertices.len(), mesh.faces.len())?;
    write_counted_body(w, mesh)
}

#[cfg(test)]
mod tests {
    use super::super::sample_mesh;
    use super::*;
    use crate::geometry::Vec3;

    fn parse(text: &str) -> Result<LoadedMesh> {
        parse_off(text, Path::new("test.off"))
    }

    fn error(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    fn off_text(mesh: &PolyMesh) -> String {
        let mut bytes = Vec::new();
        write_off(&mut bytes, mesh).unwrap();
        String::from_utf8(bytes).unwrap()
    }

    #[test]
    fn round_trip_keeps_every_bit() {
        let mesh = sample_mesh();
        let loaded = parse(&off_text(&mesh)).unwrap();
        assert_eq!(loaded.mesh, mesh);
        assert!(loaded.warnings.is_empty());
    }

    #[test]
    fn variants_comments_counts_on_header_line_and_colours() {
        let text = "# made by hand\n\
                    COFF 5 2 0\n\
                    \n\
                    0 0 0 255 0 0 255\n\
                    1 0 0 255 0 0 255 # red\n\
                    1 1 0 0 255 0 255\n\
                    0 1 0 0 0 255 255\n\
                    2 0.5 0 0 0 0 255\n\
                    4 0 1 2 3 0.5 0.5 0.5\n\
                    3 1 4 2\n";
        let loaded = parse(text).unwrap();
        assert!(loaded.warnings.is_empty());
        assert_eq!(loaded.mesh.vertices[4], Vec3::new(2.0, 0.5, 0.0));
        assert_eq!(loaded.mesh.faces, vec![vec![0, 1, 2, 3], vec![1, 4, 2]]);

        let text = "NOFF\n3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
        assert_eq!(parse(text).unwrap().mesh.faces, vec![vec![0, 1, 2]]);
    }

    #[test]
    fn hexagon_and_quads() {
        let mut text = String::from("OFF\n8 3 0\n");
        for k in 0..8 {
            text.push_str(&format!("{k} {} 0\n", k * k));
        }
        text.push_str("6 0 1 2 3 4 5\n4 1 6 7 2\n4 3 2 7 6\n");
        let mesh = parse(&text).unwrap().mesh;
        assert_eq!(mesh.faces[0], vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(mesh.faces[2], vec![3, 2, 7, 6]);
    }

    #[test]
    fn one_based_indices_are_detected_with_a_warning() {
        let text = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 1 2 3\n3 1 3 4\n";
        let loaded = parse(text).unwrap();
        assert_eq!(loaded.mesh.faces, vec![vec![0, 1, 2], vec![0, 2, 3]]);
        assert_eq!(loaded.warnings.len(), 1);
        let warning = &loaded.warnings[0];
        assert!(warning.starts_with("test.off: "), "{warning}");
        assert!(warning.contains("face indices are 1-based"), "{warning}");
        assert!(warning.contains("read as 1-based"), "{warning}");
    }

    #[test]
    fn out_of_range_index_names_face_line_and_index() {
        // Index 0 is used, so this is not a 1-based file: 5 is simply out of range.
        let text = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 5\n";
        let err = error(text);
        assert!(err.contains("test.off:8:"), "{err}");
        assert!(
            err.contains("face 1: vertex index 5 is out of range (the file has 4 vertices)"),
            "{err}"
        );
    }

    #[test]
    fn empty_file() {
        assert!(error("").contains("empty file"));
        assert!(error("# only a comment\n\n").contains("empty file"));
    }

    #[test]
    fn truncated_vertices_and_faces() {
        let err = error("OFF\n4 1 0\n0 0 0\n1 0 0\n");
        assert!(
            err.contains("truncated file: the header says 4 vertices, but only 2 were found"),
            "{err}"
        );
        let err = error("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        assert!(
            err.contains("the header says 2 faces, but only 1 were found"),
            "{err}"
        );
    }

    #[test]
    fn a_vertex_count_too_large_points_at_the_first_face() {
        // 5 vertices claimed, 4 given: the first face line is read as vertex 4.
        let text = "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
        let err = error(text);
        assert!(
            err.contains("the header says 2 faces, but only 1 were found; line 7, read as vertex 4, reads like a face: is the vertex count 4"),
            "{err}"
        );
        // The same with CR line endings and a BOM.
        let err = error(&format!("\u{feff}{}", text.replace('\n', "\r")));
        assert!(err.contains("line 7, read as vertex 4"), "{err}");
    }

    #[test]
    fn every_line_ending_reads_alike() {
        let lf = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        let expected = parse(lf).unwrap();
        assert_eq!(expected.mesh.faces, vec![vec![0, 1, 2]]);
        for text in [lf.replace('\n', "\r\n"), lf.replace('\n', "\r")] {
            assert_eq!(parse(&text).unwrap(), expected, "{text:?}");
        }
    }

    #[test]
    fn huge_counts_do_not_allocate() {
        let err = error("OFF 1000000000000000 1000000000000000 0\n0 0 0\n");
        assert!(err.contains("only 1 were found"), "{err}");
    }

    #[test]
    fn non_finite_and_non_numeric_values() {
        let err = error("OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
        assert!(err.contains(":4:"), "{err}");
        assert!(
            err.contains("vertex 1 has a non-finite coordinate"),
            "{err}"
        );
        let err = error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n");
        assert!(
            err.contains(":5:") && err.contains("'zero' is not a number"),
            "{err}"
        );
        let err = error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n");
        assert!(
            err.contains(":6:") && err.contains("'-1' is not a vertex index"),
            "{err}"
        );
        let err = error("OFF\nthree 1 0\n");
        assert!(
            err.contains(":2:") && err.contains("expected the vertex count"),
            "{err}"
        );
    }

    #[test]
    fn malformed_faces() {
        let err = error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n");
        assert!(
            err.contains("face 0 announces 4 vertices but lists 3"),
            "{err}"
        );
        let err = error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
        assert!(err.contains("face 0 has 2 vertices"), "{err}");
    }

    #[test]
    fn bad_headers() {
        assert!(error("PLY\n").contains("expected the 'OFF' header, found 'PLY'"));
        assert!(error("4OFF\n").contains("not supported"));
        assert!(error("OFF BINARY\n").contains("binary OFF is not supported"));
        assert!(error("OFF\n").contains("counts are missing"));
    }

    #[test]
    fn trailing_lines_are_reported() {
        let text = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n";
        let loaded = parse(text).unwrap();
        assert_eq!(loaded.mesh.faces.len(), 1);
        assert!(loaded.warnings[0].contains("1 lines after the last face ignored"));
    }

    #[test]
    fn no_prefix_of_a_valid_file_panics() {
        let text = off_text(&sample_mesh());
        for end in 0..=text.len() {
            let _ = parse(&text[..end]);
        }
    }
}
