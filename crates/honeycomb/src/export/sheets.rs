//! The panels on their sheets as a drawing: outlines, lines and labels on named layers, in sheet
//! coordinates (model units, y up). `panels.dxf` and `panels.svg` write the same drawing.

use crate::fabrication::{side, EndCut, Layout, Panel, Point};

/// The width of a character of the labels' sans-serif font, in text heights (a generous
/// average, so that a label is no wider than its room).
const CHAR_WIDTH: f64 = 0.65;

/// Where a shape goes: the cutter follows CUT; LABEL is engraved or drawn; BEVEL marks the ridge
/// of a bevelled end (the node axis); SHEET is the sheet's border.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layer {
    Cut,
    Label,
    Bevel,
    Sheet,
}

impl Layer {
    pub const ALL: [Layer; 4] = [Layer::Cut, Layer::Label, Layer::Bevel, Layer::Sheet];

    pub fn name(self) -> &'static str {
        match self {
            Layer::Cut => "CUT",
            Layer::Label => "LABEL",
            Layer::Bevel => "BEVEL",
            Layer::Sheet => "SHEET",
        }
    }
}

#[derive(Clone, Debug)]
pub enum Shape {
    /// A closed outline.
    Outline(Vec<Point>),
    Line(Point, Point),
    /// Text centred on `at`, turned `rotation_deg` anticlockwise.
    Text {
        at: Point,
        height: f64,
        rotation_deg: f64,
        text: String,
    },
}

#[derive(Clone, Debug)]
pub struct Item {
    pub layer: Layer,
    pub shape: Shape,
}

/// One drawing per sheet.
#[derive(Clone, Debug)]
pub struct SheetDrawings {
    pub width: f64,
    pub height: f64,
    pub sheets: Vec<Vec<Item>>,
}

/// Draws every placed panel: its cut outline, the ridge lines of bevelled ends, its label
/// `W<edge>` in the middle and its nodes `N<i>` at the ends, all inside the panel (at most
/// `label_height` tall); each sheet has its border and a title line naming the end cut.
pub fn draw(
    panels: &[Panel],
    layout: &Layout,
    label_height: f64,
    cut: Option<EndCut>,
    unit: &str,
) -> SheetDrawings {
    let mut sheets: Vec<Vec<Item>> = vec![Vec::new(); layout.sheets];
    let item = |layer, shape| Item { layer, shape };
    for (k, sheet) in sheets.iter_mut().enumerate() {
        let (w, h) = (layout.sheet.width, layout.sheet.height);
        sheet.push(item(
            Layer::Sheet,
            Shape::Outline(vec![[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]]),
        ));
        let how = match cut {
            Some(c) => format!(
                "ends: plate {} {unit}, faces set back {:.4} {unit} from the axis (square cut), or bevel {} deg from square to the axis",
                c.thickness, c.setback, c.bevel_deg
            ),
            None => "ends on the node axes (no material thickness given)".into(),
        };
        sheet.push(item(
            Layer::Label,
            Shape::Text {
                at: [w / 2.0, h - layout.gap / 2.0],
                height: (layout.gap * 0.4).min(label_height),
                rotation_deg: 0.0,
                text: format!("sheet {} of {}; {how}", k + 1, layout.sheets),
            },
        ));
    }
    for placed in &layout.placed {
        let panel = &panels[placed.panel];
        let items = &mut sheets[placed.sheet];
        let place = |p: Point| placed.place(p);
        items.push(item(
            Layer::Cut,
            Shape::Outline(panel.cut.iter().map(|&p| place(p)).collect()),
        ));
        let o = panel.outline;
        // The ridge of a bevelled end lies on the node axis, where the end was set back.
        for (p, q, end) in [(o[0], o[3], panel.cut[0]), (o[1], o[2], panel.cut[1])] {
            if end != p {
                items.push(item(Layer::Bevel, Shape::Line(place(p), place(q))));
            }
        }
        let rotation_deg = if placed.turned { 90.0 } else { 0.0 };
        let labels = [
            format!("N{}", panel.nodes[0]),
            format!("W{}", panel.edge),
            format!("N{}", panel.nodes[1]),
        ];
        // Along the line through the ends' midpoints, inside the cut outline: the three labels
        // side by side, shrunk where the panel is too short or too low for `label_height`.
        let c = panel.cut;
        let (a, b) = (mid(c[0], c[3], 0.5), mid(c[1], c[2], 0.5));
        let length = (b[0] - a[0]).hypot(b[1] - a[1]);
        let low = side(c[0], c[3]).min(side(c[1], c[2]));
        let chars: usize = labels.iter().map(|l| l.chars().count()).sum();
        let height = label_height
            .min(0.8 * length / (CHAR_WIDTH * chars as f64 + 2.0))
            .min(0.5 * low);
        let mut along = 0.1 * length;
        let spare = 0.8 * length - CHAR_WIDTH * height * chars as f64;
        for label in labels {
            let w = CHAR_WIDTH * height * label.chars().count() as f64;
            let at = mid(a, b, (along + 0.5 * w) / length);
            items.push(item(
                Layer::Label,
                Shape::Text {
                    at: place(at),
                    height,
                    rotation_deg,
                    text: label,
                },
            ));
            along += w + 0.5 * spare;
        }
    }
    SheetDrawings {
        width: layout.sheet.width,
        height: layout.sheet.height,
        sheets,
    }
}

/// The point a share `t` of the way from `p` to `q`.
fn mid(p: Point, q: Point, t: f64) -> Point {
    [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]
}
