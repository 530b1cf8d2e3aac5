//! Text files of 3D vectors (light directions, prescribed node axes): one vector per line as
//! three numbers separated by whitespace and/or commas; `#` starts a comment; blank lines are
//! skipped.

use super::Vec3;
use crate::error::{Error, Result};
use crate::mesh::io::{read_file, text_lines};
use std::path::Path;

/// Every vector of the file with its 1-based line number. A line without exactly three numbers
/// and a non-finite number are errors naming the line; text that is not UTF-8 names its line.
pub fn read_vectors(path: &Path) -> Result<Vec<(usize, Vec3)>> {
    let bad = |line: usize, message: String| Error::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let bytes = read_file(path)?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let line = 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        bad(line, "not UTF-8 text".to_string())
    })?;
    let mut vectors = Vec::new();
    for (index, raw) in text_lines(text).enumerate() {
        let line = index + 1;
        let content = raw.split('#').next().unwrap_or("");
        let words: Vec<&str> = content
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|w| !w.is_empty())
            .collect();
        if words.is_empty() {
            continue;
        }
        if words.len() != 3 {
            return Err(bad(
                line,
                format!(
                    "expected a direction as 3 numbers (x y z), found {} fields",
                    words.len()
                ),
            ));
        }
        let mut xyz = [0.0; 3];
        for (value, word) in xyz.iter_mut().zip(&words) {
            *value = word
                .parse::<f64>()
                .map_err(|_| bad(line, format!("`{word}` is not a number")))?;
            if !value.is_finite() {
                return Err(bad(line, format!("`{word}` is not a finite number")));
            }
        }
        vectors.push((line, Vec3::new(xyz[0], xyz[1], xyz[2])));
    }
    Ok(vectors)
}

/// Reads prescribed node axes: one direction per base-mesh vertex, in vertex order; `0 0 0`
/// leaves a vertex free. The count must match.
pub fn read_axes(path: &Path, num_vertices: usize) -> Result<Vec<Vec3>> {
    let vectors = read_vectors(path)?;
    if vectors.len() != num_vertices {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line: vectors.get(num_vertices).map_or(0, |&(line, _)| line),
            message: format!(
                "{} axes for a base mesh of {num_vertices} vertices: expected one per vertex",
                vectors.len()
            ),
        });
    }
    Ok(vectors.into_iter().map(|(_, a)| a).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_byte_order_mark_and_every_line_ending_read_alike() {
        let dir = std::env::temp_dir().join(format!("honeycomb-vectors-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let text = "# sun positions\n0 0 1\n\n1, 0, 1\n";
        // The mark must not make the first line a word that is not a number.
        for (name, variant) in [
            ("lf.txt", text.to_string()),
            ("bom.txt", format!("\u{feff}{text}")),
            (
                "bom-vector.txt",
                "\u{feff}0 0 1\n\n1, 0, 1\n".replace("\n\n", "\n#\n"),
            ),
            ("cr.txt", format!("\u{feff}{}", text.replace('\n', "\r"))),
            ("crlf.txt", text.replace('\n', "\r\n")),
        ] {
            let path = dir.join(name);
            std::fs::write(&path, variant).unwrap();
            let read = read_vectors(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
            let vectors: Vec<Vec3> = read.iter().map(|&(_, v)| v).collect();
            assert_eq!(
                vectors,
                [Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 1.0)],
                "{name}"
            );
            // Line numbers count the lines as written, the mark's line too.
            let lines: Vec<usize> = read.iter().map(|&(line, _)| line).collect();
            let expected = if name == "bom-vector.txt" {
                [1, 3]
            } else {
                [2, 4]
            };
            assert_eq!(lines, expected, "{name}");
        }
        let axes = dir.join("axes.txt");
        std::fs::write(&axes, "\u{feff}0 0 1\r0 0 0\r").unwrap();
        assert_eq!(read_axes(&axes, 2).unwrap().len(), 2);
        std::fs::remove_dir_all(&dir).ok();
    }
}
