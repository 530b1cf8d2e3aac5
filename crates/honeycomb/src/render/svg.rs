//! The honeycomb's walls as a picture: wall quads filled by a measure (painter's order, far
//! walls first) and a colour bar.

use super::colormap::{color, Scale};
use super::scene::{Scene, Shape};
use super::view::View;
use crate::geometry::Vec3;
use crate::structure::Honeycomb;

/// What the colours mean, with one value per wall.
pub struct Coloring<'a> {
    pub label: &'a str,
    pub per_wall: &'a [f64],
    /// A linear scale from 0 (angles), where errors spanning decades get a log scale.
    pub linear: bool,
}

const BAR: f64 = 140.0;
const MARGIN: f64 = 20.0;

/// The picture, `width` pixels wide (the height follows the model's aspect).
pub fn walls_scene(h: &Honeycomb, coloring: &Coloring, view: View, width: u32) -> Scene {
    let base: Vec<Vec3> = h.base.vertices.iter().map(|&p| view.project(p)).collect();
    let offset: Vec<Vec3> = h.offset.vertices.iter().map(|&p| view.project(p)).collect();
    let (lo, hi) = base.iter().chain(&offset).fold(
        (
            Vec3::new(f64::MAX, f64::MAX, 0.0),
            Vec3::new(f64::MIN, f64::MIN, 0.0),
        ),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let drawing = width as f64 - BAR - 2.0 * MARGIN;
    let span = (hi.x - lo.x).max(hi.y - lo.y).max(1e-300);
    let k = drawing / span;
    let height = ((hi.y - lo.y) * k + 2.0 * MARGIN).max(260.0).round();
    let to_screen = |p: Vec3| {
        (
            MARGIN + (p.x - lo.x) * k,
            height - MARGIN - (p.y - lo.y) * k,
        )
    };

    let scale = if coloring.linear {
        Scale::linear_from_zero(coloring.per_wall)
    } else {
        Scale::of(coloring.per_wall)
    };
    let mut order: Vec<usize> = (0..h.edges.len()).collect();
    let depth = |e: usize| {
        let [a, b] = h.edges[e];
        base[a].z + base[b].z + offset[a].z + offset[b].z
    };
    order.sort_by(|&e, &f| depth(e).total_cmp(&depth(f)));

    let mut scene = Scene::new(width, height as u32);
    for e in order {
        let [a, b] = h.edges[e];
        scene.shapes.push(Shape::Polygon {
            points: [base[a], base[b], offset[b], offset[a]]
                .map(to_screen)
                .to_vec(),
            fill: Some(color(scale.position(coloring.per_wall[e]))),
            stroke: Some(((34, 34, 34), 0.4)),
            class: None,
            opacity: 1.0,
        });
    }
    colour_bar(&mut scene, &scale, coloring.label, width as f64, height);
    scene
}

fn colour_bar(scene: &mut Scene, scale: &Scale, label: &str, width: f64, height: f64) {
    let (x, top, bar_h) = (
        width - BAR + 20.0,
        MARGIN + 30.0,
        (height - 2.0 * MARGIN - 60.0).max(100.0),
    );
    // The measure's name, and its explanation in brackets on a second line.
    let (name, note) = label.split_once(" (").unwrap_or((label, ""));
    let text = |x: f64, y: f64, size: f64, text: String| Shape::Text { x, y, size, text };
    scene
        .shapes
        .push(text(x, MARGIN + 2.0, 13.0, name.to_string()));
    if !note.is_empty() {
        scene
            .shapes
            .push(text(x, MARGIN + 16.0, 10.0, format!("({note}")));
    }
    let steps = 32;
    for i in 0..steps {
        let t = 1.0 - (i as f64 + 0.5) / steps as f64;
        scene.shapes.push(Shape::Rect {
            x,
            y: top + bar_h * i as f64 / steps as f64,
            w: 22.0,
            h: bar_h / steps as f64 + 0.5,
            fill: color(t),
            class: Some("colour-bar"),
        });
    }
    for t in [0.0, 0.5, 1.0] {
        let y = top + bar_h * (1.0 - t) + 4.0;
        scene
            .shapes
            .push(text(x + 28.0, y, 11.0, format!("{:.2e}", scale.value(t))));
    }
    if scale.log {
        scene
            .shapes
            .push(text(x, top + bar_h + 18.0, 10.0, "log scale".into()));
    }
}
