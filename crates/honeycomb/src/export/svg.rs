//! `panels.svg`: the sheets one below the other in one SVG file, each an Inkscape page, with
//! one group (Inkscape layer) per layer. Lengths are in model units (the viewBox); the page
//! size carries the unit.

use super::sheets::{Layer, Shape, SheetDrawings};
use super::Units;
use crate::render::escape;
use std::fmt::Write as _;

/// The space between two sheets, as a share of a sheet's height.
const SHEET_SPACING: f64 = 0.1;

pub fn svg_text(drawings: &SheetDrawings, units: Units) -> String {
    let (w, h) = (drawings.width, drawings.height);
    let step = h * (1.0 + SHEET_SPACING);
    let n = drawings.sheets.len().max(1);
    let total = step * (n - 1) as f64 + h;
    // SVG knows mm, cm and in; metres and feet are given in mm.
    let (unit, per) = match units {
        Units::Mm => ("mm", 1.0),
        Units::Cm => ("cm", 1.0),
        Units::In => ("in", 1.0),
        Units::M => ("mm", 1000.0),
        Units::Ft => ("mm", 304.8),
    };
    let stroke = (w.min(h) * 0.0005).max(1e-9);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" xmlns:sodipodi="http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd" width="{}{unit}" height="{}{unit}" viewBox="0 0 {w} {total}">"#,
        w * per,
        total * per
    );
    s.push_str("<sodipodi:namedview>\n");
    for k in 0..n {
        let _ = writeln!(
            s,
            r#"<inkscape:page id="page{}" x="0" y="{}" width="{w}" height="{h}"/>"#,
            k + 1,
            k as f64 * step
        );
    }
    s.push_str("</sodipodi:namedview>\n");
    for layer in Layer::ALL {
        let (colour, dash) = match layer {
            Layer::Cut => ("#d00000", ""),
            Layer::Label => ("#0040c0", ""),
            Layer::Bevel => ("#008000", r#" stroke-dasharray="4 2""#),
            Layer::Sheet => ("#808080", ""),
        };
        let _ = writeln!(
            s,
            r#"<g id="{0}" inkscape:groupmode="layer" inkscape:label="{0}" fill="none" stroke="{colour}" stroke-width="{stroke}"{dash}>"#,
            layer.name()
        );
        for (k, items) in drawings.sheets.iter().enumerate() {
            // SVG's y runs down: flip each sheet within its page.
            let top = k as f64 * step;
            let at = |p: [f64; 2]| (p[0], top + h - p[1]);
            for item in items.iter().filter(|i| i.layer == layer) {
                match &item.shape {
                    Shape::Outline(points) => {
                        let coords: Vec<String> = points
                            .iter()
                            .map(|&p| {
                                let (x, y) = at(p);
                                format!("{x},{y}")
                            })
                            .collect();
                        let _ = writeln!(s, r#"<polygon points="{}"/>"#, coords.join(" "));
                    }
                    Shape::Line(p, q) => {
                        let ((x1, y1), (x2, y2)) = (at(*p), at(*q));
                        let _ = writeln!(s, r#"<line x1="{x1}" y1="{y1}" x2="{x2}" y2="{y2}"/>"#);
                    }
                    Shape::Text {
                        at: p,
                        height,
                        rotation_deg,
                        text,
                    } => {
                        let (x, y) = at(*p);
                        let _ = writeln!(
                            s,
                            r#"<text x="{x}" y="{y}" font-size="{height}" font-family="sans-serif" text-anchor="middle" dominant-baseline="middle" fill="{colour}" stroke="none" transform="rotate({} {x} {y})">{}</text>"#,
                            -rotation_deg,
                            escape(text)
                        );
                    }
                }
            }
        }
        s.push_str("</g>\n");
    }
    s.push_str("</svg>\n");
    s
}
