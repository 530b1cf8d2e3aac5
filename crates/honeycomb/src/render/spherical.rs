//! A picture of the spherical image (paper Figs. 4-5): the node axes as points of the unit
//! sphere seen along their mean direction, the cells as spherical polygons; zero-area cells
//! light, the others (|area| >= pi/3 by Proposition 1) strong, violations red.

use crate::analysis::SphericalImage;
use crate::geometry::Vec3;
use std::fmt::Write;

const MARGIN: f64 = 30.0;

pub fn svg_spherical(
    faces: &[Vec<usize>],
    axes: &[Vec3],
    image: &SphericalImage,
    width: u32,
) -> String {
    let mean = axes.iter().fold(Vec3::ZERO, |s, &a| s + a);
    let toward = if mean.norm() > 1e-12 {
        mean.normalized()
    } else {
        Vec3::new(0.0, 0.0, 1.0)
    };
    let right = toward.any_orthogonal();
    let up = toward.cross(right);
    // Points on the far side would overlap the near ones: only the visible hemisphere is drawn.
    let project = |a: Vec3| (a.dot(right), a.dot(up), a.dot(toward));
    let w = width as f64;
    let r = (w - 2.0 * MARGIN) / 2.0;
    let to_screen = |(x, y): (f64, f64)| (w / 2.0 + r * x, w / 2.0 - r * y);
    let violating: std::collections::HashSet<usize> =
        image.proposition1_violations.iter().copied().collect();

    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{width}" viewBox="0 0 {width} {width}">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r##"<circle cx="{}" cy="{}" r="{r}" fill="none" stroke="#999" stroke-width="1"/>"##,
        w / 2.0,
        w / 2.0
    );
    // Non-zero cells last, on top of the zero-area ones.
    let mut order: Vec<&crate::analysis::CellImage> = image.per_cell.iter().collect();
    order.sort_by(|a, b| a.area.abs().total_cmp(&b.area.abs()));
    for cell in order {
        let pts: Vec<(f64, f64, f64)> =
            faces[cell.cell].iter().map(|&v| project(axes[v])).collect();
        if pts.iter().any(|p| p.2 < 0.0) {
            continue;
        }
        let points: Vec<String> = pts
            .iter()
            .map(|&(x, y, _)| {
                let (sx, sy) = to_screen((x, y));
                format!("{sx:.1},{sy:.1}")
            })
            .collect();
        let (class, fill, stroke) = if violating.contains(&cell.cell) {
            ("violation", "#e03030", "#800000")
        } else if cell.area.abs() <= image.tolerance {
            ("zero-area", "none", "#7aa6c2")
        } else {
            ("nonzero-area", "#f2b134", "#8a5a00")
        };
        let _ = writeln!(
            s,
            r#"<polygon class="{class}" points="{}" fill="{fill}" fill-opacity="0.6" stroke="{stroke}" stroke-width="0.6"/>"#,
            points.join(" ")
        );
    }
    let legend = [
        ("#7aa6c2", format!("zero area: {}", image.zero_area_cells)),
        (
            "#f2b134",
            format!(
                "|area| >= pi/3: {}",
                image.cells - image.zero_area_cells - image.proposition1_violations.len()
            ),
        ),
        (
            "#e03030",
            format!(
                "Proposition 1 violated: {}",
                image.proposition1_violations.len()
            ),
        ),
    ];
    for (k, (c, text)) in legend.iter().enumerate() {
        let y = 20.0 + 16.0 * k as f64;
        let _ = writeln!(
            s,
            r#"<rect x="10" y="{}" width="10" height="10" fill="{c}"/>"#,
            y - 9.0
        );
        let _ = writeln!(
            s,
            r#"<text x="26" y="{y}" font-family="sans-serif" font-size="12">{text}</text>"#
        );
    }
    s.push_str("</svg>\n");
    s
}
