//! A picture of the spherical image (paper Figs. 4-5): the node axes as points of the unit
//! sphere seen along their mean direction, the cells as spherical polygons; zero-area cells
//! light, the others (|area| >= pi/3 by Proposition 1) strong, violations red.

use super::scene::{Rgb, Scene, Shape};
use crate::analysis::SphericalImage;
use crate::geometry::Vec3;

const MARGIN: f64 = 30.0;

pub fn spherical_scene(
    faces: &[Vec<usize>],
    axes: &[Vec3],
    image: &SphericalImage,
    width: u32,
) -> Scene {
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
    let to_screen = |x: f64, y: f64| (w / 2.0 + r * x, w / 2.0 - r * y);
    let violating: std::collections::HashSet<usize> =
        image.proposition1_violations.iter().copied().collect();

    let mut scene = Scene::new(width, width);
    scene.shapes.push(Shape::Circle {
        cx: w / 2.0,
        cy: w / 2.0,
        r,
        stroke: (153, 153, 153),
    });
    // Non-zero cells last, on top of the zero-area ones.
    let mut order: Vec<&crate::analysis::CellImage> = image.per_cell.iter().collect();
    order.sort_by(|a, b| a.area.abs().total_cmp(&b.area.abs()));
    for cell in order {
        let pts: Vec<(f64, f64, f64)> =
            faces[cell.cell].iter().map(|&v| project(axes[v])).collect();
        if pts.iter().any(|p| p.2 < 0.0) {
            continue;
        }
        let (class, fill, stroke) = if violating.contains(&cell.cell) {
            ("violation", Some(VIOLATION), (128, 0, 0))
        } else if cell.area.abs() <= image.tolerance {
            ("zero-area", None, ZERO)
        } else {
            ("nonzero-area", Some(NONZERO), (138, 90, 0))
        };
        scene.shapes.push(Shape::Polygon {
            points: pts.iter().map(|&(x, y, _)| to_screen(x, y)).collect(),
            fill,
            stroke: Some((stroke, 0.6)),
            class: Some(class),
            opacity: 0.6,
        });
    }
    let legend = [
        (ZERO, format!("zero area: {}", image.zero_area_cells)),
        (
            NONZERO,
            format!(
                "|area| >= pi/3: {}",
                image.cells - image.zero_area_cells - image.proposition1_violations.len()
            ),
        ),
        (
            VIOLATION,
            format!(
                "Proposition 1 violated: {}",
                image.proposition1_violations.len()
            ),
        ),
    ];
    for (k, (c, text)) in legend.into_iter().enumerate() {
        let y = 20.0 + 16.0 * k as f64;
        scene.shapes.push(Shape::Rect {
            x: 10.0,
            y: y - 9.0,
            w: 10.0,
            h: 10.0,
            fill: c,
            class: None,
        });
        scene.shapes.push(Shape::Text {
            x: 26.0,
            y,
            size: 12.0,
            text,
        });
    }
    scene
}

const ZERO: Rgb = (122, 166, 194);
const NONZERO: Rgb = (242, 177, 52);
const VIOLATION: Rgb = (224, 48, 48);
