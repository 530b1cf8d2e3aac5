//! What makes a picture readable on its own: the colour bar with ticks and unit, an axis triad
//! and a scale bar.

use super::colormap::{calm, color, nice_length, OVER};
use super::scene::{Scene, Shape, TextStyle};
use super::view::Camera;
use crate::error::rounded;
use crate::geometry::Vec3;

/// How values map to colours.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ramp {
    /// Calm from 0 to the tolerance, red above.
    Tolerance(f64),
    /// The colour map from 0 to this (a round number).
    Range(f64),
}

impl Ramp {
    /// The largest value on the ramp: the tolerance, or the range's top.
    fn top(&self) -> f64 {
        match *self {
            Ramp::Tolerance(t) | Ramp::Range(t) => t,
        }
    }

    /// A value's colour: the calm ramp up to the tolerance and red beyond it, or the full
    /// colour map over the range.
    pub fn colour(&self, v: f64) -> (u8, u8, u8) {
        match *self {
            Ramp::Tolerance(t) if v <= t => calm(v / t),
            Ramp::Tolerance(_) => OVER,
            Ramp::Range(top) => color(v / top),
        }
    }
}

/// The colour bar at `at` (its top left), `height` pixels tall: the measure's name, what it
/// means and its unit above it, ticks beside it.
pub fn colour_bar(
    scene: &mut Scene,
    ramp: &Ramp,
    (name, meaning, unit): (&str, &str, &str),
    at: (f64, f64),
    height: f64,
) {
    let (x, top) = at;
    let heading = if unit.is_empty() {
        name.to_string()
    } else {
        format!("{name} ({unit})")
    };
    scene.shapes.push(Shape::Text {
        x,
        y: top,
        size: 13.0,
        text: heading,
        style: TextStyle {
            bold: true,
            ..TextStyle::default()
        },
    });
    // The meaning, broken into lines that fit the bar's column.
    let mut lines: Vec<String> = Vec::new();
    for word in meaning.split(' ') {
        match lines.last_mut() {
            Some(line) if line.len() + word.len() < 26 => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    for (k, line) in lines.iter().enumerate() {
        scene.shapes.push(Shape::text(
            x,
            top + 15.0 + 12.0 * k as f64,
            10.0,
            line.clone(),
        ));
    }
    let bar_top = top + 24.0 + 12.0 * lines.len() as f64;
    let top_value = ramp.top();
    let over_box = match ramp {
        Ramp::Tolerance(_) => 22.0,
        Ramp::Range(_) => 0.0,
    };
    if over_box > 0.0 {
        scene.shapes.push(Shape::Rect {
            x,
            y: bar_top,
            w: 22.0,
            h: 16.0,
            fill: OVER,
            class: Some("over"),
        });
        let tol = rounded(top_value, 3);
        scene.shapes.push(Shape::text(
            x + 28.0,
            bar_top + 12.0,
            11.0,
            format!("> {tol}: over tolerance"),
        ));
    }
    let (y0, h) = (
        bar_top + over_box,
        (height - (bar_top - top) - over_box - 10.0).max(60.0),
    );
    let steps = 32;
    for i in 0..steps {
        let t = 1.0 - (i as f64 + 0.5) / steps as f64;
        let fill = ramp.colour(t * ramp.top());
        scene.shapes.push(Shape::Rect {
            x,
            y: y0 + h * i as f64 / steps as f64,
            w: 22.0,
            h: h / steps as f64 + 0.5,
            fill,
            class: Some("colour-bar"),
        });
    }
    let ticks: Vec<f64> = match *ramp {
        Ramp::Tolerance(t) => vec![0.0, 0.5 * t, t],
        Ramp::Range(r) => super::colormap::nice_ticks(r),
    };
    for v in ticks {
        let y = y0 + h * (1.0 - v / top_value);
        scene.shapes.push(Shape::Line {
            from: (x + 22.0, y),
            to: (x + 27.0, y),
            stroke: (34, 34, 34),
            width: 1.0,
        });
        scene
            .shapes
            .push(Shape::text(x + 30.0, y + 4.0, 11.0, rounded(v, 3)));
    }
}

/// X, Y and Z of the model as seen, from `at`.
pub fn axis_triad(scene: &mut Scene, camera: &Camera, at: (f64, f64)) {
    let axes = [
        ("X", Vec3::new(1.0, 0.0, 0.0), (200, 40, 40)),
        ("Y", Vec3::new(0.0, 1.0, 0.0), (40, 150, 40)),
        ("Z", Vec3::new(0.0, 0.0, 1.0), (40, 70, 200)),
    ];
    for (name, axis, colour) in axes {
        let p = camera.project(axis);
        let to = (at.0 + 22.0 * p.x, at.1 - 22.0 * p.y);
        scene.shapes.push(Shape::Line {
            from: at,
            to,
            stroke: colour,
            width: 2.0,
        });
        scene.shapes.push(Shape::Text {
            x: at.0 + 30.0 * p.x,
            y: at.1 - 30.0 * p.y + 4.0,
            size: 11.0,
            text: name.into(),
            style: TextStyle {
                fill: colour,
                bold: true,
                anchor: "middle",
            },
        });
    }
}

/// A bar of a round model length, about a fifth of the drawing wide.
pub fn scale_bar(scene: &mut Scene, span: f64, pixels_per_unit: f64, at: (f64, f64), drawing: f64) {
    let length = nice_length(0.2 * span);
    let px = (length * pixels_per_unit).min(drawing);
    let (x, y) = at;
    let ink = (34, 34, 34);
    scene.shapes.push(Shape::Line {
        from: (x, y),
        to: (x + px, y),
        stroke: ink,
        width: 2.0,
    });
    for end in [x, x + px] {
        scene.shapes.push(Shape::Line {
            from: (end, y - 5.0),
            to: (end, y + 5.0),
            stroke: ink,
            width: 1.5,
        });
    }
    scene.shapes.push(Shape::text(
        x + px + 8.0,
        y + 4.0,
        11.0,
        format!("{} model units", rounded(length, 3)),
    ));
}
