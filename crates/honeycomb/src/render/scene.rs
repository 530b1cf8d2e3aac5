//! A picture as a list of shapes, written as SVG text or rasterized into a PNG. Texts appear
//! in SVG only (no font is embedded for PNG).

use super::png;
use std::fmt::Write;

pub type Rgb = (u8, u8, u8);

pub enum Shape {
    Polygon {
        points: Vec<(f64, f64)>,
        fill: Option<Rgb>,
        stroke: Option<(Rgb, f64)>,
        class: Option<&'static str>,
        opacity: f64,
    },
    Rect {
        x: f64,
        y: f64,
        w: f64,
        h: f64,
        fill: Rgb,
        class: Option<&'static str>,
    },
    Circle {
        cx: f64,
        cy: f64,
        r: f64,
        stroke: Rgb,
    },
    Text {
        x: f64,
        y: f64,
        size: f64,
        text: String,
    },
}

pub struct Scene {
    pub width: u32,
    pub height: u32,
    pub shapes: Vec<Shape>,
}

fn hex((r, g, b): Rgb) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

impl Scene {
    pub fn new(width: u32, height: u32) -> Scene {
        Scene {
            width,
            height,
            shapes: Vec::new(),
        }
    }

    pub fn to_svg(&self) -> String {
        let (w, h) = (self.width, self.height);
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
        );
        let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
        let class_attr = |c: &Option<&str>| c.map_or(String::new(), |c| format!(r#" class="{c}""#));
        for shape in &self.shapes {
            match shape {
                Shape::Polygon {
                    points,
                    fill,
                    stroke,
                    class,
                    opacity,
                } => {
                    let pts: Vec<String> = points
                        .iter()
                        .map(|(x, y)| format!("{x:.1},{y:.1}"))
                        .collect();
                    let fill = fill.map_or("none".to_string(), hex);
                    let stroke = stroke.map_or(String::new(), |(c, w)| {
                        format!(r#" stroke="{}" stroke-width="{w}""#, hex(c))
                    });
                    let opacity = if *opacity < 1.0 {
                        format!(r#" fill-opacity="{opacity}""#)
                    } else {
                        String::new()
                    };
                    let _ = writeln!(
                        s,
                        r#"<polygon{} points="{}" fill="{fill}"{opacity}{stroke}/>"#,
                        class_attr(class),
                        pts.join(" ")
                    );
                }
                Shape::Rect {
                    x,
                    y,
                    w,
                    h,
                    fill,
                    class,
                } => {
                    let _ = writeln!(
                        s,
                        r#"<rect{} x="{x:.1}" y="{y:.1}" width="{w:.1}" height="{h:.1}" fill="{}"/>"#,
                        class_attr(class),
                        hex(*fill)
                    );
                }
                Shape::Circle { cx, cy, r, stroke } => {
                    let _ = writeln!(
                        s,
                        r#"<circle cx="{cx}" cy="{cy}" r="{r}" fill="none" stroke="{}" stroke-width="1"/>"#,
                        hex(*stroke)
                    );
                }
                Shape::Text { x, y, size, text } => {
                    let _ = writeln!(
                        s,
                        r#"<text x="{x:.1}" y="{y:.1}" font-family="sans-serif" font-size="{size}">{text}</text>"#
                    );
                }
            }
        }
        s.push_str("</svg>\n");
        s
    }

    /// The scene rasterized (fills, outlines, no text) and encoded as PNG.
    pub fn to_png(&self) -> Vec<u8> {
        let mut canvas = png::Canvas::new(self.width, self.height);
        for shape in &self.shapes {
            match shape {
                Shape::Polygon {
                    points,
                    fill,
                    stroke,
                    opacity,
                    ..
                } => {
                    if let Some(c) = fill {
                        canvas.fill_polygon(points, *c, *opacity);
                    }
                    if let Some((c, _)) = stroke {
                        for k in 0..points.len() {
                            canvas.line(points[k], points[(k + 1) % points.len()], *c);
                        }
                    }
                }
                Shape::Rect {
                    x, y, w, h, fill, ..
                } => {
                    let pts = [(*x, *y), (x + w, *y), (x + w, y + h), (*x, y + h)];
                    canvas.fill_polygon(&pts, *fill, 1.0);
                }
                Shape::Circle { cx, cy, r, stroke } => {
                    let n = 360;
                    for k in 0..n {
                        let (a, b) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
                        let at = |t: f64| {
                            let t = t * std::f64::consts::TAU;
                            (cx + r * t.cos(), cy + r * t.sin())
                        };
                        canvas.line(at(a), at(b), *stroke);
                    }
                }
                Shape::Text { .. } => {}
            }
        }
        canvas.encode()
    }
}
