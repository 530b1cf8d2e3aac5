//! An SVG picture of a honeycomb: wall quads filled by a measure (painter's order, far walls
//! first), the edges of M dark and of M' light, and a colour bar.

use super::colormap::{color, Scale};
use super::view::View;
use crate::geometry::Vec3;
use crate::structure::Honeycomb;
use std::fmt::Write;

/// What the colours mean, with one value per wall.
pub struct Coloring<'a> {
    pub label: &'a str,
    pub per_wall: &'a [f64],
}

const BAR: f64 = 140.0;
const MARGIN: f64 = 20.0;

fn hex((r, g, b): (u8, u8, u8)) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// The picture as SVG text, `width` pixels wide (the height follows the model's aspect).
pub fn svg(h: &Honeycomb, coloring: &Coloring, view: View, width: u32) -> String {
    let project = |p: Vec3| view.project(p);
    let base: Vec<Vec3> = h.base.vertices.iter().map(|&p| project(p)).collect();
    let offset: Vec<Vec3> = h.offset.vertices.iter().map(|&p| project(p)).collect();
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

    let scale = Scale::of(coloring.per_wall);
    let mut order: Vec<usize> = (0..h.edges.len()).collect();
    let depth = |e: usize| {
        let [a, b] = h.edges[e];
        base[a].z + base[b].z + offset[a].z + offset[b].z
    };
    order.sort_by(|&e, &f| depth(e).total_cmp(&depth(f)));

    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for e in order {
        let [a, b] = h.edges[e];
        let pts: Vec<String> = [base[a], base[b], offset[b], offset[a]]
            .iter()
            .map(|&p| {
                let (x, y) = to_screen(p);
                format!("{x:.1},{y:.1}")
            })
            .collect();
        let fill = hex(color(scale.position(coloring.per_wall[e])));
        let _ = writeln!(
            s,
            r##"<polygon points="{}" fill="{fill}" stroke="#222" stroke-width="0.4"/>"##,
            pts.join(" ")
        );
    }
    colour_bar(&mut s, &scale, coloring.label, width as f64, height);
    s.push_str("</svg>\n");
    s
}

fn colour_bar(s: &mut String, scale: &Scale, label: &str, width: f64, height: f64) {
    let (x, top, bar_h) = (
        width - BAR + 20.0,
        MARGIN + 30.0,
        (height - 2.0 * MARGIN - 60.0).max(100.0),
    );
    // The measure's name, and its explanation in brackets on a second line.
    let (name, note) = label.split_once(" (").map_or((label, ""), |(n, r)| (n, r));
    let _ = writeln!(
        s,
        r#"<text x="{x}" y="{}" font-family="sans-serif" font-size="13">{name}</text>"#,
        MARGIN + 2.0
    );
    if !note.is_empty() {
        let _ = writeln!(
            s,
            r#"<text x="{x}" y="{}" font-family="sans-serif" font-size="10">({note}</text>"#,
            MARGIN + 16.0
        );
    }
    let steps = 32;
    for i in 0..steps {
        let t = 1.0 - (i as f64 + 0.5) / steps as f64;
        let y = top + bar_h * i as f64 / steps as f64;
        let _ = writeln!(
            s,
            r#"<rect class="colour-bar" x="{x}" y="{y:.1}" width="22" height="{:.1}" fill="{}"/>"#,
            bar_h / steps as f64 + 0.5,
            hex(color(t))
        );
    }
    for t in [0.0, 0.5, 1.0] {
        let y = top + bar_h * (1.0 - t);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{:.1}" font-family="sans-serif" font-size="11">{:.2e}</text>"#,
            x + 28.0,
            y + 4.0,
            scale.value(t)
        );
    }
    if scale.log {
        let _ = writeln!(
            s,
            r#"<text x="{x}" y="{:.1}" font-family="sans-serif" font-size="10">log scale</text>"#,
            top + bar_h + 18.0
        );
    }
}
