//! The panels on their sheets as a drawing: outlines, lines and labels on named layers, in sheet
//! coordinates (model units, y up). `panels.dxf` and `panels.svg` write the same drawing.

use crate::fabrication::{EndCut, Layout, Panel, Point};

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
/// `W<edge>` in the middle and its nodes `N<i>` near the ends; each sheet has its border and a
/// title line naming the end cut.
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
        let mid = |p: Point, q: Point, t: f64| [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
        let centre = mid(mid(o[0], o[2], 0.5), mid(o[1], o[3], 0.5), 0.5);
        let text = |at: Point, text: String| Shape::Text {
            at: place(at),
            height: label_height,
            rotation_deg,
            text,
        };
        items.push(item(Layer::Label, text(centre, format!("W{}", panel.edge))));
        // The node ids sit inside each end, halfway up.
        let end_a = mid(mid(o[0], o[3], 0.5), centre, 0.25);
        let end_b = mid(mid(o[1], o[2], 0.5), centre, 0.25);
        items.push(item(
            Layer::Label,
            text(end_a, format!("N{}", panel.nodes[0])),
        ));
        items.push(item(
            Layer::Label,
            text(end_b, format!("N{}", panel.nodes[1])),
        ));
    }
    SheetDrawings {
        width: layout.sheet.width,
        height: layout.sheet.height,
        sheets,
    }
}
