//! The honeycomb's walls (or the quads that cap it) as a picture a designer reads at a glance:
//! polygons filled by a measure (painter's order, far ones first), a title, a verdict against
//! the measure's tolerance, a colour bar with ticks and unit, an axis triad and a scale bar.

use super::colormap::{nice_ticks, OVER};
use super::legend::{axis_triad, colour_bar, scale_bar, Ramp};
use super::scene::{Scene, Shape, TextStyle};
use super::view::Camera;
use crate::error::rounded;
use crate::geometry::Vec3;
use crate::structure::Honeycomb;

/// What the colours mean, with one value per wall (or per quad).
pub struct Coloring<'a> {
    /// The picture's title: what is drawn and by which measure.
    pub title: String,
    /// The measure's name and what it means.
    pub measure: &'a str,
    pub meaning: &'a str,
    pub unit: &'a str,
    /// What is drawn, in the plural ("walls", "quads"), for the verdict.
    pub items: &'a str,
    /// One value per wall (or quad), in drawing order.
    pub values: &'a [f64],
    /// Values above it are flagged red; the calm ramp spans 0 to it.
    pub tolerance: Option<f64>,
}

impl Coloring<'_> {
    /// "all 2334 walls within 0.001" or "17 of 2334 walls over 0.1 deg (worst 3.2 deg)"; for a
    /// measure without a tolerance, its mean and largest value.
    pub fn verdict(&self) -> String {
        let (n, items) = (self.values.len(), self.items);
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        let worst = self.values.iter().copied().fold(0.0, f64::max);
        match self.tolerance {
            Some(t) => {
                let over = self.over(t);
                if over == 0 {
                    format!("all {n} {items} within {}{unit}", rounded(t, 3))
                } else {
                    format!(
                        "{over} of {n} {items} over {}{unit} (worst {}{unit})",
                        rounded(t, 3),
                        rounded(worst, 3)
                    )
                }
            }
            None => {
                let mean = self.values.iter().sum::<f64>() / n.max(1) as f64;
                format!(
                    "{n} {items}: mean {}{unit}, largest {}{unit}",
                    rounded(mean, 3),
                    rounded(worst, 3)
                )
            }
        }
    }

    /// How many walls are over `tolerance` (a NaN is).
    fn over(&self, tolerance: f64) -> usize {
        self.values
            .iter()
            .filter(|&&v| v > tolerance || v.is_nan())
            .count()
    }

    /// The ramp the walls are painted with.
    fn ramp(&self) -> Ramp {
        match self.tolerance {
            Some(t) => Ramp::Tolerance(t),
            None => {
                let largest = self
                    .values
                    .iter()
                    .copied()
                    .filter(|v| v.is_finite())
                    .fold(0.0, f64::max);
                Ramp::Range(*nice_ticks(largest).last().unwrap_or(&1.0))
            }
        }
    }
}

const BAR: f64 = 170.0;
const MARGIN: f64 = 20.0;
/// Room for the title and the verdict above the drawing, and the triad and scale bar below.
const TOP: f64 = 58.0;
const BOTTOM: f64 = 64.0;

/// The walls of `h`, each the quad over its edge, `width` pixels wide (the height follows the
/// model's aspect).
pub fn walls_scene(h: &Honeycomb, coloring: &Coloring, camera: Camera, width: u32) -> Scene {
    let walls: Vec<Vec<Vec3>> = (0..h.edges.len()).map(|e| h.wall(e).to_vec()).collect();
    polygons_scene(&walls, "wall", coloring, camera, width)
}

/// `polygons` (model coordinates, one value each in `coloring`; `class` names them in an SVG)
/// filled by their values, far ones first, with the title, verdict and legends, `width` pixels
/// wide.
pub fn polygons_scene(
    polygons: &[Vec<Vec3>],
    class: &'static str,
    coloring: &Coloring,
    camera: Camera,
    width: u32,
) -> Scene {
    let projected: Vec<Vec<Vec3>> = polygons
        .iter()
        .map(|p| p.iter().map(|&q| camera.project(q)).collect())
        .collect();
    let (lo, hi) = projected.iter().flatten().fold(
        (
            Vec3::new(f64::MAX, f64::MAX, 0.0),
            Vec3::new(f64::MIN, f64::MIN, 0.0),
        ),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let drawing = width as f64 - BAR - 2.0 * MARGIN;
    let span = (hi.x - lo.x).max(hi.y - lo.y).max(1e-300);
    let k = drawing / span;
    let height = ((hi.y - lo.y) * k + TOP + BOTTOM).max(320.0).round();
    let to_screen = |p: Vec3| {
        (
            MARGIN + (p.x - lo.x) * k,
            height - BOTTOM - (p.y - lo.y) * k,
        )
    };

    // Strokes thin with the polygons, so that at thousands of them the colours still show.
    let sides = projected.iter().map(|p| p.len()).sum::<usize>().max(1);
    let side_px = projected
        .iter()
        .flat_map(|p| (0..p.len()).map(move |i| (p[i], p[(i + 1) % p.len()])))
        .map(|(a, b)| {
            let (p, q) = (to_screen(a), to_screen(b));
            (q.0 - p.0).hypot(q.1 - p.1)
        })
        .sum::<f64>()
        / sides as f64;
    let stroke = (0.04 * side_px).clamp(0.1, 0.8);

    let ramp = coloring.ramp();
    let mut order: Vec<usize> = (0..projected.len()).collect();
    let depth =
        |i: usize| projected[i].iter().map(|p| p.z).sum::<f64>() / projected[i].len() as f64;
    order.sort_by(|&i, &j| depth(i).total_cmp(&depth(j)));

    let mut scene = Scene::new(width, height as u32);
    for i in order {
        scene.shapes.push(Shape::Polygon {
            points: projected[i].iter().map(|&p| to_screen(p)).collect(),
            fill: Some(ramp.colour(coloring.values[i])),
            stroke: Some(((40, 40, 40), stroke)),
            class: Some(class),
            opacity: 1.0,
        });
    }
    scene.shapes.push(Shape::Text {
        x: MARGIN,
        y: MARGIN + 8.0,
        size: 16.0,
        text: coloring.title.clone(),
        style: TextStyle {
            bold: true,
            ..TextStyle::default()
        },
    });
    let over = coloring.tolerance.is_some_and(|t| coloring.over(t) > 0);
    scene.shapes.push(Shape::Text {
        x: MARGIN,
        y: MARGIN + 28.0,
        size: 13.0,
        text: coloring.verdict(),
        style: TextStyle {
            fill: if over { OVER } else { (34, 34, 34) },
            ..TextStyle::default()
        },
    });
    colour_bar(
        &mut scene,
        &ramp,
        (coloring.measure, coloring.meaning, coloring.unit),
        (width as f64 - BAR + 16.0, TOP + 10.0),
        (height - TOP - BOTTOM - 10.0).max(160.0),
    );
    axis_triad(&mut scene, &camera, (MARGIN + 28.0, height - 30.0));
    scale_bar(&mut scene, span, k, (MARGIN + 80.0, height - 24.0), drawing);
    scene
}
