//! Polylines a designer draws for the hex edges to follow (OBJ `v` and `l` records), and the
//! direction the lattice takes from them or from the boundary.

use crate::error::{Error, Result};
use crate::geometry::Vec3;
use crate::mesh::io::{read_file, text_lines};
use std::path::Path;

/// The polylines of an OBJ file's `l` records (1-based or negative indices into its `v`).
pub fn read_strokes(path: &Path) -> Result<Vec<Vec<Vec3>>> {
    let bad = |line: usize, message: String| Error::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let bytes = read_file(path)?;
    let text = std::str::from_utf8(&bytes).map_err(|_| bad(0, "not UTF-8 text".into()))?;
    let mut vertices = Vec::new();
    let mut lines = Vec::new();
    for (number, line) in text_lines(text).enumerate().map(|(i, l)| (i + 1, l)) {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let xyz: Vec<f64> = words
                    .take(3)
                    .map(|w| w.parse::<f64>())
                    .collect::<std::result::Result<_, _>>()
                    .map_err(|_| bad(number, format!("`{line}`: expected v x y z")))?;
                match xyz[..] {
                    [x, y, z] if xyz.iter().all(|c| c.is_finite()) => {
                        vertices.push(Vec3::new(x, y, z))
                    }
                    _ => {
                        return Err(bad(
                            number,
                            format!("`{line}`: expected three finite numbers"),
                        ))
                    }
                }
            }
            Some("l") => {
                let mut polyline = Vec::new();
                for w in words {
                    let index: i64 = w
                        .split('/')
                        .next()
                        .and_then(|i| i.parse().ok())
                        .ok_or_else(|| bad(number, format!("`{w}` is not a vertex index")))?;
                    let resolved = if index < 0 {
                        vertices.len() as i64 + index
                    } else {
                        index - 1
                    };
                    let v = usize::try_from(resolved)
                        .ok()
                        .and_then(|i| vertices.get(i).copied())
                        .ok_or_else(|| {
                            bad(
                                number,
                                format!(
                                    "vertex index {index} out of range ({} vertices so far)",
                                    vertices.len()
                                ),
                            )
                        })?;
                    polyline.push(v);
                }
                if polyline.len() >= 2 {
                    lines.push(polyline);
                }
            }
            _ => {}
        }
    }
    if lines.is_empty() {
        return Err(bad(
            0,
            "no polyline (`l` record with two or more vertices) to align with".into(),
        ));
    }
    Ok(lines)
}

/// The direction (radians, modulo 60 degrees) that a hexagonal lattice's edges best follow
/// for these planar segments: the 6-fold mean of their directions, weighted by length.
/// `None` when the segments give no preference (e.g. a circle).
pub fn sixfold_mean(segments: impl IntoIterator<Item = ([f64; 2], [f64; 2])>) -> Option<f64> {
    let (mut c, mut s, mut total) = (0.0, 0.0, 0.0);
    for (a, b) in segments {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let length = (dx * dx + dy * dy).sqrt();
        if length > 0.0 && length.is_finite() {
            let phi = dy.atan2(dx);
            c += length * (6.0 * phi).cos();
            s += length * (6.0 * phi).sin();
            total += length;
        }
    }
    (total > 0.0 && (c * c + s * s).sqrt() > 1e-3 * total).then(|| s.atan2(c) / 6.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sixfold_mean_follows_a_lattice_direction() {
        // Segments along 10 degrees and 70 degrees (60 apart: the same lattice direction).
        let seg = |deg: f64| {
            let t = deg.to_radians();
            ([0.0, 0.0], [t.cos(), t.sin()])
        };
        let mean = sixfold_mean([seg(10.0), seg(70.0), seg(190.0)]).unwrap();
        assert!(
            (mean.to_degrees() - 10.0).abs() < 1e-9,
            "{}",
            mean.to_degrees()
        );
        // A regular 12-gon has no preferred direction mod 60 degrees... except its own; a
        // full circle of many segments has none.
        let circle: Vec<_> = (0..360).map(|k| seg(k as f64)).collect();
        assert!(sixfold_mean(circle).is_none());
    }

    #[test]
    fn strokes_are_read_with_their_errors_named() {
        let dir = std::env::temp_dir().join(format!("honeycomb-strokes-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let good = dir.join("good.obj");
        std::fs::write(&good, "v 0 0 0\nv 1 0 0\nv 2 1 0\nl 1 2 -1\n").unwrap();
        let lines = read_strokes(&good).unwrap();
        assert_eq!(lines.len(), 1);
        assert_eq!(lines[0].len(), 3);
        assert_eq!(lines[0][2], Vec3::new(2.0, 1.0, 0.0));
        let bad = dir.join("bad.obj");
        std::fs::write(&bad, "v 0 0 0\nl 1 5\n").unwrap();
        let e = read_strokes(&bad).unwrap_err().to_string();
        assert!(
            e.contains("bad.obj") && e.contains('2') && e.contains("out of range"),
            "{e}"
        );
        let none = dir.join("none.obj");
        std::fs::write(&none, "v 0 0 0\n").unwrap();
        assert!(read_strokes(&none)
            .unwrap_err()
            .to_string()
            .contains("no polyline"));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn strokes_with_a_byte_order_mark_or_any_line_ending_read_alike() {
        let dir =
            std::env::temp_dir().join(format!("honeycomb-strokes-bom-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let text = "v 0 0 0\nv 1 0 0\nv 2 1 0\nl 1 2 3\n";
        // The mark must not hide the first `v` record (the polyline would lose a vertex).
        for (name, variant) in [
            ("lf.obj", text.to_string()),
            ("bom.obj", format!("\u{feff}{text}")),
            ("cr.obj", format!("\u{feff}{}", text.replace('\n', "\r"))),
            ("crlf.obj", text.replace('\n', "\r\n")),
        ] {
            let path = dir.join(name);
            std::fs::write(&path, variant).unwrap();
            let lines = read_strokes(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(lines.len(), 1, "{name}");
            assert_eq!(
                lines[0],
                [
                    Vec3::new(0.0, 0.0, 0.0),
                    Vec3::new(1.0, 0.0, 0.0),
                    Vec3::new(2.0, 1.0, 0.0)
                ],
                "{name}"
            );
        }
        std::fs::remove_dir_all(&dir).ok();
    }
}
