//! `panels.dxf`: the sheets side by side in one drawing (AutoCAD 2000 format, which every CAD
//! program and laser cutter's software opens), with closed polylines and text on the layers
//! CUT, LABEL, BEVEL and SHEET, and the units in `$INSUNITS`.

use super::sheets::{Layer, Shape, SheetDrawings};
use super::Units;
use dxf::entities::{Entity, EntityType, Line, LwPolyline, Text};
use dxf::enums::{AcadVersion, HorizontalTextJustification, VerticalTextJustification};
use dxf::{Color, Drawing, LwPolylineVertex, Point};

/// The space between two sheets, as a share of a sheet's width.
const SHEET_SPACING: f64 = 0.1;

pub fn write_dxf(
    w: &mut dyn std::io::Write,
    drawings: &SheetDrawings,
    units: Units,
) -> std::io::Result<()> {
    let mut drawing = Drawing::new();
    drawing.header.version = AcadVersion::R2000;
    drawing.header.default_drawing_units = match units {
        Units::Mm => dxf::enums::Units::Millimeters,
        Units::Cm => dxf::enums::Units::Centimeters,
        Units::M => dxf::enums::Units::Meters,
        Units::In => dxf::enums::Units::Inches,
        Units::Ft => dxf::enums::Units::Feet,
    };
    for (layer, colour) in Layer::ALL.iter().zip([1u8, 5, 3, 8]) {
        drawing.add_layer(dxf::tables::Layer {
            name: layer.name().into(),
            color: Color::from_index(colour),
            ..Default::default()
        });
    }
    let step = drawings.width * (1.0 + SHEET_SPACING);
    for (k, items) in drawings.sheets.iter().enumerate() {
        let dx = k as f64 * step;
        let at = |p: [f64; 2]| Point::new(p[0] + dx, p[1], 0.0);
        for item in items {
            let specific = match &item.shape {
                Shape::Outline(points) => {
                    let mut polyline = LwPolyline {
                        vertices: points
                            .iter()
                            .map(|p| LwPolylineVertex {
                                x: p[0] + dx,
                                y: p[1],
                                ..Default::default()
                            })
                            .collect(),
                        ..Default::default()
                    };
                    polyline.set_is_closed(true);
                    EntityType::LwPolyline(polyline)
                }
                Shape::Line(p, q) => EntityType::Line(Line::new(at(*p), at(*q))),
                Shape::Text {
                    at: p,
                    height,
                    rotation_deg,
                    text,
                } => EntityType::Text(Text {
                    // Middle-centre justified text is placed by its second alignment point.
                    location: at(*p),
                    second_alignment_point: at(*p),
                    text_height: *height,
                    rotation: *rotation_deg,
                    value: text.clone(),
                    horizontal_text_justification: HorizontalTextJustification::Center,
                    vertical_text_justification: VerticalTextJustification::Middle,
                    ..Default::default()
                }),
            };
            let mut entity = Entity::new(specific);
            entity.common.layer = item.layer.name().into();
            drawing.add_entity(entity);
        }
    }
    drawing.save(w).map_err(std::io::Error::other)
}
