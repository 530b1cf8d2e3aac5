//! The WebSocket messages between the page and the editor, as JSON text frames.

use honeycomb::export::{Format, Units};
use honeycomb::interactive::{Edit, View, Watch, Watched, Workspace};
use honeycomb::Vec3;
use serde::Deserialize;
use serde_json::{json, Value};

/// Largest message the server reads (a drag is under 200 bytes).
pub const MAX_MESSAGE_BYTES: usize = 64 * 1024;

/// A message from the page. `stroke` numbers a drag gesture: its messages share one undo step,
/// and a newer one replaces an older one that is still being solved.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ClientMessage {
    /// Mode (i): move a base-mesh vertex (towards `target`, kept on S), its neighbours up to
    /// `radius` rings along, and re-optimize.
    DragVertex {
        vertex: usize,
        target: [f64; 3],
        #[serde(default)]
        radius: usize,
        stroke: Option<u64>,
    },
    /// Mode (ii): slide a vertex by `distance` along its node axis; no optimization.
    Slide {
        vertex: usize,
        distance: f64,
        stroke: Option<u64>,
    },
    /// Mode (iii): turn the node axis of `vertex` to `direction`, spread over `radius` rings.
    DragAxis {
        vertex: usize,
        direction: [f64; 3],
        radius: usize,
        stroke: Option<u64>,
    },
    // Empty braces, not unit variants: serde lets a unit variant of a tagged enum through with
    // any extra fields, and a page that sends `{"type": "undo", "steps": 3}` should hear that
    // `steps` means nothing here.
    Undo {},
    Redo {},
    /// Stop the running solve where it stands.
    Cancel {},
    /// Write the current structure to the save folder under `name`.
    Save {
        name: String,
    },
    /// Go on editing a structure saved under `name`.
    Load {
        name: String,
    },
    /// Make the honeycomb again from the input: a design surface with about `cells` cells,
    /// M' at `thickness` (model units). Either may be left out (as it is now); `cells` needs a
    /// design surface, `thickness` a surface or the demo (a structure keeps its own).
    Remake {
        cells: Option<usize>,
        thickness: Option<f64>,
    },
}

impl ClientMessage {
    pub fn parse(text: &str) -> Result<ClientMessage, String> {
        if text.len() > MAX_MESSAGE_BYTES {
            return Err(format!(
                "message of {} bytes: the limit is {MAX_MESSAGE_BYTES}",
                text.len()
            ));
        }
        serde_json::from_str(text).map_err(|e| format!("malformed message: {e}"))
    }

    /// The message as an error about it names it: its type, and the vertex, stroke or name
    /// that tell it from others of its type.
    pub fn label(&self) -> String {
        let stroke = |s: &Option<u64>| s.map_or(String::new(), |s| format!(", stroke {s}"));
        match self {
            ClientMessage::DragVertex {
                vertex, stroke: s, ..
            } => {
                format!("drag_vertex (vertex {vertex}{})", stroke(s))
            }
            ClientMessage::Slide {
                vertex, stroke: s, ..
            } => {
                format!("slide (vertex {vertex}{})", stroke(s))
            }
            ClientMessage::DragAxis {
                vertex, stroke: s, ..
            } => {
                format!("drag_axis (vertex {vertex}{})", stroke(s))
            }
            ClientMessage::Undo {} => "undo".into(),
            ClientMessage::Redo {} => "redo".into(),
            ClientMessage::Cancel {} => "cancel".into(),
            ClientMessage::Save { name } => format!("save {name:?}"),
            ClientMessage::Load { name } => format!("load {name:?}"),
            ClientMessage::Remake { .. } => "remake".into(),
        }
    }

    /// The edit and its stroke, for the three editing modes.
    pub fn edit(&self) -> Option<(Edit, Option<u64>)> {
        let v3 = |a: &[f64; 3]| Vec3::new(a[0], a[1], a[2]);
        match self {
            ClientMessage::DragVertex {
                vertex,
                target,
                radius,
                stroke,
            } => Some((
                Edit::MoveVertex {
                    vertex: *vertex,
                    target: v3(target),
                    radius: *radius,
                },
                *stroke,
            )),
            ClientMessage::Slide {
                vertex,
                distance,
                stroke,
            } => Some((
                Edit::SlideVertex {
                    vertex: *vertex,
                    distance: *distance,
                },
                *stroke,
            )),
            ClientMessage::DragAxis {
                vertex,
                direction,
                radius,
                stroke,
            } => Some((
                Edit::TurnAxis {
                    vertex: *vertex,
                    direction: v3(direction),
                    radius: *radius,
                },
                *stroke,
            )),
            _ => None,
        }
    }
}

/// A save name: a plain folder name, nothing that could climb out of the save folder.
pub fn check_name(name: &str) -> Result<&str, String> {
    let ok = !name.is_empty()
        && name.len() <= 64
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    if ok {
        Ok(name)
    } else {
        Err(format!(
            "save name {name:?}: use 1 to 64 letters, digits, '-' or '_'"
        ))
    }
}

/// The files a page may download (`GET /download/FILE`), their content type and the export
/// format that writes them: `honeycomb export`'s files, made from the current state.
pub const DOWNLOADS: [(&str, &str, Format); 8] = [
    ("structure.glb", "model/gltf-binary", Format::Glb),
    ("structure.obj", "model/obj", Format::Obj),
    ("structure.mtl", "model/mtl", Format::Obj),
    ("panels.dxf", "image/vnd.dxf", Format::Dxf),
    ("panels.svg", "image/svg+xml", Format::Svg),
    ("walls.csv", "text/csv; charset=utf-8", Format::Csv),
    ("nodes.csv", "text/csv; charset=utf-8", Format::Csv),
    ("bom.csv", "text/csv; charset=utf-8", Format::Csv),
];

/// The content type and format of a download, or why there is none.
pub fn download(file: &str) -> Result<(&'static str, Format), String> {
    DOWNLOADS
        .iter()
        .find(|(name, _, _)| *name == file)
        .map(|&(_, mime, format)| (mime, format))
        .ok_or_else(|| {
            let names: Vec<&str> = DOWNLOADS.iter().map(|d| d.0).collect();
            format!(
                "no download {file:?}: the downloads are {}",
                names.join(", ")
            )
        })
}

/// The units of a download from its query (`units=mm`; by default one model unit is a metre):
/// the length one model unit stands for, as `honeycomb export --units` takes it.
pub fn download_units(query: Option<&str>) -> Result<Units, String> {
    let mut units = Units::default();
    for pair in query.unwrap_or("").split('&').filter(|p| !p.is_empty()) {
        match pair.split_once('=') {
            Some(("units", value)) => {
                units = Units::parse(value)
                    .map_err(|_| format!("units {value:?}: expected {}", Units::NAMES))?
            }
            _ => {
                return Err(format!(
                    "query {pair:?}: a download takes only units=mm|cm|m|in|ft"
                ))
            }
        }
    }
    Ok(units)
}

fn flat(points: &[Vec3]) -> Vec<f32> {
    points
        .iter()
        .flat_map(|p| [p.x as f32, p.y as f32, p.z as f32])
        .collect()
}

/// What the page's remake controls may change: the cell count of a design surface (its
/// value now), the thickness of a surface or the demo.
#[derive(Clone, Copy, Debug, Default)]
pub struct Remakes {
    pub cells: Option<usize>,
    pub thickness: bool,
}

/// The topology and the design surface, sent once per connection and after a load.
/// The topology comes from the workspace: it is the same for every state, so no solve or
/// measure is needed to send it.
/// With a variant, its `name` and, for quads, the `quads` that cap the cells (corners of M).
pub fn mesh_message(
    ws: &Workspace,
    source: &str,
    remakes: Remakes,
    watch: Option<&Watch>,
) -> Value {
    let surface = &ws.model_surface;
    let triangles: Vec<usize> = surface.triangles().iter().flatten().copied().collect();
    let thickness = ws.depths.iter().sum::<f64>() / ws.depths.len().max(1) as f64;
    json!({
        "type": "mesh",
        "source": source,
        "thickness": thickness,
        "remake": { "cells": remakes.cells, "thickness": remakes.thickness },
        "vertices": ws.base.vertices.len(),
        "faces": ws.base.faces,
        "edges": ws.conn.edges,
        "surface": { "vertices": flat(surface.vertices()), "triangles": triangles },
        "variant": watch.map(|w| json!({
            "name": w.name(),
            "quads": match w {
                Watch::Quads { quads, .. } => Some(quads),
                _ => None,
            },
        })),
    })
}

/// Where an update stands in its edit.
pub struct UpdateInfo {
    pub seq: u64,
    pub stroke: Option<u64>,
    pub iteration: usize,
    /// The edit's solve has ended (converged or out of steps), or there was none.
    pub done: bool,
    /// Milliseconds of the last solver step.
    pub step_ms: f64,
    /// Milliseconds since the edit's message was read.
    pub edit_ms: f64,
    /// The page whose gesture an undo would take back (pages undo only their own), if any.
    pub undo_page: Option<u64>,
    /// The page whose gesture a redo would bring back, if any.
    pub redo_page: Option<u64>,
}

/// The geometry and measures after a step (or an instant edit).
/// With `watched`, the variant's measure ([`Watched`]) as `variant`.
pub fn state_message(view: &View, info: &UpdateInfo, watched: Option<&Watched>) -> Value {
    let (h, m) = (&view.honeycomb, &view.measures);
    let mut state = json!({
        "type": "state",
        "seq": info.seq,
        "stroke": info.stroke,
        "iteration": info.iteration,
        "done": info.done,
        "step_ms": info.step_ms,
        "edit_ms": info.edit_ms,
        "undo_page": info.undo_page,
        "redo_page": info.redo_page,
        "base": flat(&h.base.vertices),
        "offset": flat(&h.offset.vertices),
        "omega": m.omega_per_node.iter().map(|&x| x as f32).collect::<Vec<_>>(),
        "delta": m.delta_per_wall.iter().map(|&x| x as f32).collect::<Vec<_>>(),
        "axis": m.axis_normal_per_node.iter().map(|&x| x as f32).collect::<Vec<_>>(),
        "measures": {
            "omega_max_deg": m.omega_max_deg,
            "omega_avg_deg": m.omega_avg_deg,
            "delta_max": m.delta_max,
            "delta_avg": m.delta_avg,
            "closeness_max": m.closeness_max,
            "closeness_avg": m.closeness_avg,
            "axis_normal_mean_deg": m.axis_normal_deg.mean,
            "axis_normal_max_deg": m.axis_normal_deg.max,
            "mean_edge_length": m.mean_edge_length,
        },
    });
    if let Some(w) = watched {
        state["variant"] = serde_json::to_value(w).unwrap_or(Value::Null);
    }
    match non_finite_field(&state) {
        Some(key) => error_message(&format!(
            "the state after this step has a{} {key} value that is not a finite number; not \
             sent (undo the last edit)",
            if key.starts_with(['a', 'e', 'i', 'o', 'u']) {
                "n"
            } else {
                ""
            }
        )),
        None => state,
    }
}

/// The numeric fields of a state message: every value in them must be finite.
const NUMERIC_FIELDS: [&str; 6] = ["base", "offset", "omega", "delta", "axis", "measures"];

/// The first of a state's [`NUMERIC_FIELDS`] holding a value that is not a finite number.
/// JSON has no inf or NaN (serde_json writes null): a page would draw nonsense from it.
fn non_finite_field(state: &Value) -> Option<&'static str> {
    NUMERIC_FIELDS
        .into_iter()
        .find(|&key| has_null(&state[key]))
}

fn has_null(value: &Value) -> bool {
    match value {
        Value::Null => true,
        Value::Array(items) => items.iter().any(has_null),
        Value::Object(fields) => fields.values().any(has_null),
        _ => false,
    }
}

pub fn error_message(message: &str) -> Value {
    json!({ "type": "error", "message": message })
}

/// Something the page shows until the next edit: the edit went through, but not all the way.
pub fn warning_message(message: &str) -> Value {
    json!({ "type": "warning", "message": message })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_null_anywhere_in_a_state_is_found() {
        let finite = json!({"base": [0.0, 1.0], "measures": {"omega_max_deg": 0.5}});
        assert!(!has_null(&finite["base"]) && !has_null(&finite["measures"]));
        // serde_json writes a non-finite number as null.
        let broken = json!({"base": [0.0, f32::INFINITY], "measures": {"delta_max": f64::NAN}});
        assert!(has_null(&broken["base"]) && has_null(&broken["measures"]));
    }

    #[test]
    fn a_state_with_a_non_finite_axis_angle_is_not_sent() {
        let state = |axis: f32| {
            json!({
                "base": [0.0, 1.0], "offset": [0.0, 1.0], "omega": [0.5], "delta": [1e-9],
                "axis": [3.0, axis], "measures": {"omega_max_deg": 0.5},
            })
        };
        assert_eq!(non_finite_field(&state(12.5)), None);
        // The axis angles (the colour by axis) must not go out as null.
        for axis in [f32::NAN, f32::INFINITY] {
            assert_eq!(non_finite_field(&state(axis)), Some("axis"), "{axis}");
        }
    }

    #[test]
    fn a_label_tells_a_message_from_others_of_its_type() {
        let m = json!({"type": "drag_axis", "vertex": 7, "direction": [0, 0, 1], "radius": 2, "stroke": 3});
        let parsed = ClientMessage::parse(&m.to_string()).unwrap();
        assert_eq!(parsed.label(), "drag_axis (vertex 7, stroke 3)");
        let save = ClientMessage::parse(r#"{"type": "save", "name": "a"}"#).unwrap();
        assert_eq!(save.label(), r#"save "a""#);
    }

    /// Every message type reads in its plain form and refuses a field it does not have.
    #[test]
    fn every_message_refuses_a_field_it_does_not_have() {
        let plain = [
            json!({"type": "drag_vertex", "vertex": 1, "target": [0, 0, 1]}),
            json!({"type": "slide", "vertex": 1, "distance": 0.1}),
            json!({"type": "drag_axis", "vertex": 1, "direction": [0, 0, 1], "radius": 2}),
            json!({"type": "undo"}),
            json!({"type": "redo"}),
            json!({"type": "cancel"}),
            json!({"type": "save", "name": "a"}),
            json!({"type": "load", "name": "a"}),
            json!({"type": "remake", "cells": 300, "thickness": 0.1}),
        ];
        for m in plain {
            assert!(ClientMessage::parse(&m.to_string()).is_ok(), "{m}");
            let mut extra = m.clone();
            extra["steps"] = json!(3);
            let e = ClientMessage::parse(&extra.to_string()).unwrap_err();
            assert!(e.contains("unknown field `steps`"), "{extra}: {e}");
        }
    }
}

#[cfg(test)]
mod download_tests {
    use super::*;

    #[test]
    fn every_export_file_is_a_download_and_nothing_else() {
        for format in Format::ALL {
            for file in format.files() {
                assert_eq!(download(file).unwrap().1, format, "{file}");
            }
        }
        assert_eq!(download_units(None).unwrap(), Units::M);
        assert_eq!(download_units(Some("units=mm")).unwrap(), Units::Mm);
        let e = download_units(Some("units=furlong")).unwrap_err();
        assert!(e.contains("expected mm, cm, m, in or ft"), "{e}");
        let e = download_units(Some("scale=2")).unwrap_err();
        assert!(e.contains("only units="), "{e}");
        for bad in ["export.json", "../structure.glb", "", "structure.GLB"] {
            let e = download(bad).unwrap_err();
            assert!(e.contains("the downloads are structure.glb"), "{e}");
        }
    }
}
