//! `walls.csv`, `nodes.csv` and `bom.csv`: one row per wall, per node, and per item of the bill
//! of materials. Lengths in model units, angles in degrees; positions and directions in the
//! file frame's axes. Numbers round-trip, in exponent notation where they are very small or
//! very large.

use super::Frame;
use crate::error::short_number;
use crate::fabrication::{Bom, NodeRow, WallRow};
use std::io::Write;

fn writer(w: &mut dyn Write) -> csv::Writer<&mut dyn Write> {
    csv::Writer::from_writer(w)
}

fn done(mut w: csv::Writer<&mut dyn Write>) -> std::io::Result<()> {
    w.flush()
}

fn cell(id: Option<usize>) -> String {
    id.map_or(String::new(), |c| c.to_string())
}

pub fn write_walls(w: &mut dyn Write, rows: &[WallRow]) -> std::io::Result<()> {
    let mut out = writer(w);
    out.write_record([
        "wall",
        "i",
        "j",
        "cell_left",
        "cell_right",
        "length",
        "length_offset",
        "height_i",
        "height_j",
        "end_angle_i_deg",
        "end_angle_j_deg",
        "surface_angle_deg",
        "area",
        "delta",
    ])?;
    for r in rows {
        out.write_record([
            r.wall.to_string(),
            r.i.to_string(),
            r.j.to_string(),
            cell(r.cell_left),
            cell(r.cell_right),
            short_number(r.length),
            short_number(r.length_offset),
            short_number(r.height_i),
            short_number(r.height_j),
            short_number(r.end_angle_i_deg),
            short_number(r.end_angle_j_deg),
            short_number(r.surface_angle_deg),
            short_number(r.area),
            short_number(r.delta),
        ])?;
    }
    done(out)
}

pub fn write_nodes(w: &mut dyn Write, rows: &[NodeRow], frame: Frame) -> std::io::Result<()> {
    let mut out = writer(w);
    let mut header: Vec<String> = [
        "node",
        "x",
        "y",
        "z",
        "axis_x",
        "axis_y",
        "axis_z",
        "axis_length",
        "valence",
    ]
    .map(String::from)
    .to_vec();
    for k in 1..=3 {
        header.push(format!("wall_{k}"));
        for c in ["x", "y", "z"] {
            header.push(format!("wall_{k}_{c}"));
        }
    }
    header.push("omega_deg".into());
    out.write_record(&header)?;
    for r in rows {
        let p = frame.point(crate::Vec3::from_slice(&r.position));
        let a = frame.direction(crate::Vec3::from_slice(&r.axis));
        let mut record: Vec<String> = vec![r.node.to_string()];
        record.extend(p.iter().chain(&a).map(|&x| short_number(x)));
        record.push(short_number(r.axis_length));
        record.push(r.walls.len().to_string());
        for k in 0..3 {
            match (r.walls.get(k), r.wall_directions.get(k)) {
                (Some(e), Some(d)) => {
                    record.push(e.to_string());
                    let d = frame.direction(crate::Vec3::from_slice(d));
                    record.extend(d.iter().map(|&x| short_number(x)));
                }
                _ => record.extend(std::iter::repeat_n(String::new(), 4)),
            }
        }
        record.push(short_number(r.omega_deg));
        out.write_record(&record)?;
    }
    done(out)
}

/// `extra`: more (item, value) rows after the bill's own (the layout's sheets, the end cut).
pub fn write_bom(w: &mut dyn Write, bom: &Bom, extra: &[(&str, String)]) -> std::io::Result<()> {
    let mut out = writer(w);
    out.write_record(["item", "value"])?;
    let rows = [
        ("units", bom.units.to_string()),
        ("walls", bom.walls.to_string()),
        ("nodes", bom.nodes.to_string()),
        ("cells", bom.cells.to_string()),
        ("total_wall_area", short_number(bom.total_wall_area)),
        ("total_edge_length", short_number(bom.total_edge_length)),
        (
            "distinct_wall_lengths",
            bom.distinct_wall_lengths.to_string(),
        ),
        ("node_types", bom.node_types.to_string()),
        ("omega_max_deg", short_number(bom.omega_max_deg)),
    ];
    for (item, value) in rows.iter().chain(extra) {
        out.write_record([item, value.as_str()])?;
    }
    done(out)
}
