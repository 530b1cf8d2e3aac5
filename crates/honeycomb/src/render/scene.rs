//! A picture as a list of shapes, written as SVG text or rasterized into a PNG; both carry
//! the same text.

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
    Line {
        from: (f64, f64),
        to: (f64, f64),
        stroke: Rgb,
        width: f64,
    },
    Text {
        x: f64,
        y: f64,
        size: f64,
        text: String,
        style: TextStyle,
    },
}

/// How a text is set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextStyle {
    pub fill: Rgb,
    pub bold: bool,
    /// SVG's text-anchor: "start", "middle" or "end".
    pub anchor: &'static str,
}

impl Default for TextStyle {
    fn default() -> TextStyle {
        TextStyle {
            fill: (34, 34, 34),
            bold: false,
            anchor: "start",
        }
    }
}

impl Shape {
    /// Plain text starting at (x, y).
    pub fn text(x: f64, y: f64, size: f64, text: impl Into<String>) -> Shape {
        Shape::Text {
            x,
            y,
            size,
            text: text.into(),
            style: TextStyle::default(),
        }
    }
}

pub struct Scene {
    pub width: u32,
    pub height: u32,
    pub shapes: Vec<Shape>,
}

/// Text as SVG character data.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
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
                Shape::Line {
                    from,
                    to,
                    stroke,
                    width,
                } => {
                    let _ = writeln!(
                        s,
                        r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{}" stroke-width="{width}" stroke-linecap="round"/>"#,
                        from.0,
                        from.1,
                        to.0,
                        to.1,
                        hex(*stroke)
                    );
                }
                Shape::Text {
                    x,
                    y,
                    size,
                    text,
                    style,
                } => {
                    let weight = if style.bold {
                        r#" font-weight="bold""#
                    } else {
                        ""
                    };
                    let _ = writeln!(
                        s,
                        r#"<text x="{x:.1}" y="{y:.1}" font-family="sans-serif" font-size="{size}" fill="{}" text-anchor="{}"{weight}>{}</text>"#,
                        hex(style.fill),
                        style.anchor,
                        escape(text)
                    );
                }
            }
        }
        s.push_str("</svg>\n");
        s
    }

    /// The scene rasterized from its SVG (antialiased, with its text in an embedded DejaVu
    /// Sans, so every machine draws the same letters) and encoded as a compressed PNG.
    pub fn to_png(&self) -> crate::Result<Vec<u8>> {
        use resvg::{tiny_skia, usvg};
        let mut options = usvg::Options::default();
        {
            let fonts = options.fontdb_mut();
            fonts.load_font_data(dejavu::sans::regular().to_vec());
            fonts.load_font_data(dejavu::sans::bold().to_vec());
            fonts.set_sans_serif_family("DejaVu Sans");
        }
        let failed = |what: String| crate::Error::Parameter(format!("drawing the PNG: {what}"));
        let tree =
            usvg::Tree::from_str(&self.to_svg(), &options).map_err(|e| failed(e.to_string()))?;
        let mut pixmap = tiny_skia::Pixmap::new(self.width, self.height)
            .ok_or_else(|| failed(format!("no {} x {} picture", self.width, self.height)))?;
        resvg::render(
            &tree,
            tiny_skia::Transform::identity(),
            &mut pixmap.as_mut(),
        );
        pixmap.encode_png().map_err(|e| failed(e.to_string()))
    }
}
