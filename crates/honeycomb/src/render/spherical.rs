//! A map of the spherical image (paper Figs. 4-5): the node axes as points of the unit sphere in
//! Lambert's equal-area projection, the hemisphere around the mean axis beside the opposite
//! one, the cells as spherical polygons: zero-area cells as outlines, cells of |area| >= pi/3
//! (Proposition 1) filled, violations red, each kind counted in the legend.

use super::scene::{Rgb, Scene, Shape, TextStyle};
use crate::analysis::SphericalImage;
use crate::geometry::Vec3;

const MARGIN: f64 = 24.0;
const TOP: f64 = 70.0;
const BOTTOM: f64 = 96.0;

/// The two disks' centres, the mean axis and the screen axes of the projection.
struct Map {
    toward: Vec3,
    right: Vec3,
    up: Vec3,
    /// Pixels per unit of the projection (a cap of angle theta has its rim at 2 sin(theta/2)).
    scale: f64,
    /// The angle (degrees) from the centre that the disks' rim stands for, and its radius in
    /// the projection.
    cap_deg: f64,
    rim: f64,
    near: (f64, f64),
    far: (f64, f64),
}

impl Map {
    /// Screen point of axis `a` in the disk of the hemisphere `near` or the far one (seen from
    /// outside the sphere on that side, so the far disk is mirrored left to right).
    fn at(&self, a: Vec3, near: bool) -> (f64, f64) {
        let (centre, c, sign) = if near {
            (self.near, self.toward, 1.0)
        } else {
            (self.far, -self.toward, -1.0)
        };
        let (x, y) = (sign * a.dot(self.right), a.dot(self.up));
        let lateral = x.hypot(y);
        // Equal-area: a cap of angle theta around the centre maps to a disk of radius
        // 2 sin(theta / 2).
        // A corner on the other hemisphere (a cell across the rim) stays on the rim.
        let rho = (2.0 * (1.0 - a.dot(c)).max(0.0)).sqrt().min(self.rim);
        let (dx, dy) = if lateral > 1e-15 {
            (x / lateral * rho, y / lateral * rho)
        } else {
            (0.0, 0.0)
        };
        (centre.0 + self.scale * dx, centre.1 - self.scale * dy)
    }
}

pub fn spherical_scene(
    faces: &[Vec<usize>],
    axes: &[Vec3],
    image: &SphericalImage,
    width: u32,
    title: &str,
) -> Scene {
    let mean = axes.iter().fold(Vec3::ZERO, |s, &a| s + a);
    let toward = if mean.norm() > 1e-12 {
        mean.normalized()
    } else {
        Vec3::new(0.0, 0.0, 1.0)
    };
    let right = toward.any_orthogonal().normalized();
    let up = toward.cross(right);
    let w = width as f64;
    // The near disk shows the cap the axes take up (so a narrow image is not a speck), the far
    // disk appears only when some axis points away from the mean.
    let widest = axes
        .iter()
        .map(|a| a.dot(toward).clamp(-1.0, 1.0).acos().to_degrees())
        .fold(0.0, f64::max);
    let two = widest > 90.0;
    let cap_deg = if two {
        90.0
    } else {
        ((widest + 2.0) / 10.0).ceil().clamp(1.0, 9.0) * 10.0
    };
    let r = if two {
        ((w - 3.0 * MARGIN) / 4.0).max(40.0)
    } else {
        (0.3 * w).max(60.0)
    };
    let height = (TOP + 2.0 * r + BOTTOM).round();
    let rim = 2.0 * (cap_deg.to_radians() / 2.0).sin();
    let map = Map {
        toward,
        right,
        up,
        scale: r / rim,
        cap_deg,
        rim,
        near: (if two { MARGIN + r } else { w / 2.0 }, TOP + r),
        far: (2.0 * MARGIN + 3.0 * r, TOP + r),
    };
    let mut scene = Scene::new(width, height as u32);
    let bold = TextStyle {
        bold: true,
        ..TextStyle::default()
    };
    scene.shapes.push(Shape::Text {
        x: MARGIN,
        y: 24.0,
        size: 16.0,
        text: title.to_string(),
        style: bold,
    });
    scene.shapes.push(Shape::text(
        MARGIN,
        44.0,
        12.0,
        "node axes on the unit sphere, equal-area projection: cells keep their share of area",
    ));
    let near_caption = if two {
        "hemisphere around the mean axis (+)".to_string()
    } else {
        format!("around the mean axis (+), out to {cap_deg} deg")
    };
    let mut disks = vec![(map.near, near_caption)];
    if two {
        disks.push((map.far, "the opposite hemisphere".to_string()));
    }
    for (centre, caption) in disks {
        scene.shapes.push(Shape::Circle {
            cx: centre.0,
            cy: centre.1,
            r,
            stroke: (153, 153, 153),
        });
        // Circles of equal angle from the centre, labelled.
        let step = if map.cap_deg <= 20.0 { 5.0 } else { 10.0 };
        let mut angle = step;
        while angle < map.cap_deg - 1e-9 {
            let radius = map.scale * 2.0 * (angle.to_radians() / 2.0).sin();
            scene.shapes.push(Shape::Circle {
                cx: centre.0,
                cy: centre.1,
                r: radius,
                stroke: (222, 222, 222),
            });
            scene.shapes.push(Shape::text(
                centre.0 + radius * 0.72 + 3.0,
                centre.1 - radius * 0.69,
                10.0,
                format!("{angle} deg"),
            ));
            angle += step;
        }
        scene.shapes.push(Shape::Text {
            x: centre.0,
            y: centre.1 + r + 18.0,
            size: 12.0,
            text: caption,
            style: TextStyle {
                anchor: "middle",
                ..TextStyle::default()
            },
        });
    }
    let plus = |scene: &mut Scene, (x, y): (f64, f64)| {
        for (from, to) in [((x - 6.0, y), (x + 6.0, y)), ((x, y - 6.0), (x, y + 6.0))] {
            scene.shapes.push(Shape::Line {
                from,
                to,
                stroke: (90, 90, 90),
                width: 1.0,
            });
        }
    };
    plus(&mut scene, map.near);

    let violating: std::collections::HashSet<usize> =
        image.proposition1_violations.iter().copied().collect();
    // Non-zero cells last, on top of the zero-area ones.
    let mut order: Vec<&crate::analysis::CellImage> = image.per_cell.iter().collect();
    order.sort_by(|a, b| a.area.abs().total_cmp(&b.area.abs()));
    for cell in order {
        let points: Vec<Vec3> = faces[cell.cell].iter().map(|&v| axes[v]).collect();
        // On each disk whose hemisphere holds a corner of the cell.
        let sides: Vec<bool> = [true, false]
            .into_iter()
            .filter(|&near| points.iter().any(|a| (a.dot(toward) >= 0.0) == near))
            .filter(|&near| near || two)
            .collect();
        let (class, fill, stroke) = if violating.contains(&cell.cell) {
            ("violation", Some(VIOLATION), (128, 0, 0))
        } else if cell.area.abs() <= image.tolerance {
            ("zero-area", None, ZERO)
        } else {
            ("nonzero-area", Some(NONZERO), (138, 90, 0))
        };
        for &near in &sides {
            scene.shapes.push(Shape::Polygon {
                points: points.iter().map(|&a| map.at(a, near)).collect(),
                fill,
                stroke: Some((stroke, 0.7)),
                class: Some(class),
                opacity: 0.6,
            });
        }
    }
    // Parallel axes make every cell a point: mark where they are, or nothing would show.
    let spread = axes
        .iter()
        .map(|a| a.cross(toward).norm())
        .fold(0.0, f64::max);
    if spread < 1e-9 && !axes.is_empty() {
        let (x, y) = map.near;
        scene.shapes.push(Shape::Polygon {
            points: (0..12)
                .map(|k| {
                    let t = k as f64 * std::f64::consts::TAU / 12.0;
                    (x + 5.0 * t.cos(), y + 5.0 * t.sin())
                })
                .collect(),
            fill: Some(ZERO),
            stroke: Some(((34, 34, 34), 1.0)),
            class: Some("parallel"),
            opacity: 1.0,
        });
        scene.shapes.push(Shape::text(
            x + 10.0,
            y - 8.0,
            12.0,
            format!(
                "all {} node axes parallel: the image is one point",
                axes.len()
            ),
        ));
    }

    let nonzero = image.cells - image.zero_area_cells - image.proposition1_violations.len();
    let legend = [
        (
            ZERO,
            format!(
                "zero area (a curve-like strip, Property 2): {} cells",
                image.zero_area_cells
            ),
        ),
        (
            NONZERO,
            format!("|area| >= pi/3 (Proposition 1): {nonzero} cells"),
        ),
        (
            VIOLATION,
            format!(
                "violations (0 < |area| < pi/3): {} cells",
                image.proposition1_violations.len()
            ),
        ),
    ];
    for (k, (c, text)) in legend.into_iter().enumerate() {
        let y = height - BOTTOM + 40.0 + 17.0 * k as f64;
        scene.shapes.push(Shape::Rect {
            x: MARGIN,
            y: y - 10.0,
            w: 12.0,
            h: 12.0,
            fill: c,
            class: None,
        });
        scene.shapes.push(Shape::text(MARGIN + 18.0, y, 12.0, text));
    }
    scene
}

const ZERO: Rgb = (122, 166, 194);
const NONZERO: Rgb = (242, 177, 52);
const VIOLATION: Rgb = (224, 48, 48);
