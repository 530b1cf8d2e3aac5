//! `export`: a honeycomb's files for fabrication and exchange, written into one folder that
//! appears whole.

use super::sheets::draw;
use super::{csv, dxf, obj, svg, Frame, Model, Units, Up};
use crate::error::{check_positive_length, rounded, short_number, Error, Result};
use crate::fabrication::{
    bill_of_materials, lay_out, node_rows, unroll, wall_rows, Bom, EndCut, Sheet,
};
use crate::mesh::{OutputDir, Outputs, Verdict};
use serde::Serialize;
use std::path::{Path, PathBuf};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    Glb,
    Obj,
    Dxf,
    Svg,
    Csv,
}

impl Format {
    pub const ALL: [Format; 5] = [
        Format::Glb,
        Format::Obj,
        Format::Dxf,
        Format::Svg,
        Format::Csv,
    ];

    /// `glb`, `obj`, `dxf`, `svg`, `csv`, `all`, or several joined by commas.
    pub fn parse_list(text: &str) -> Result<Vec<Format>> {
        let mut formats = Vec::new();
        for word in text.split(',').map(|w| w.trim().to_ascii_lowercase()) {
            let more: &[Format] = match word.as_str() {
                "glb" => &[Format::Glb],
                "obj" => &[Format::Obj],
                "dxf" => &[Format::Dxf],
                "svg" => &[Format::Svg],
                "csv" => &[Format::Csv],
                "all" => &Format::ALL,
                _ => {
                    return Err(Error::option(
                        "format",
                        text,
                        format!(
                            "unknown format {word:?}; expected glb, obj, dxf, svg, csv or all \
                             (or several joined by commas)"
                        ),
                    ))
                }
            };
            for f in more {
                if !formats.contains(f) {
                    formats.push(*f);
                }
            }
        }
        Ok(formats)
    }

    /// The files a format writes.
    pub fn files(self) -> &'static [&'static str] {
        match self {
            Format::Glb => &["structure.glb"],
            Format::Obj => &["structure.obj", "structure.mtl"],
            Format::Dxf => &["panels.dxf"],
            Format::Svg => &["panels.svg"],
            Format::Csv => &["walls.csv", "nodes.csv", "bom.csv"],
        }
    }
}

#[derive(Clone, Debug)]
pub struct ExportOptions {
    pub formats: Vec<Format>,
    /// The length one model unit stands for.
    pub units: Units,
    /// The up axis of the OBJ and CSV files (glTF is always Y up).
    pub up: Up,
    /// Plate thickness (model units): the panels' ends are cut for the 120-degree node.
    pub material_thickness: Option<f64>,
    /// Sheet size (model units); by default 2.5 m x 1.25 m.
    pub sheet: Option<Sheet>,
    /// Largest height of the panel labels (model units; each panel's shrink to fit it); by
    /// default a fifth of the median wall height.
    pub label_height: Option<f64>,
}

impl Default for ExportOptions {
    fn default() -> ExportOptions {
        ExportOptions {
            formats: Format::ALL.to_vec(),
            units: Units::M,
            up: Up::Z,
            material_thickness: None,
            sheet: None,
            label_height: None,
        }
    }
}

/// What `export` wrote (also `export.json`).
#[derive(Clone, Debug, Serialize)]
pub struct Exported {
    pub dir: PathBuf,
    pub files: Vec<String>,
    pub units: Units,
    pub up: Up,
    /// Where S (for the walls' angle to the cladding) came from.
    pub surface: String,
    pub material_thickness: Option<f64>,
    /// Per end of every panel: faces set back this far from the node axis (square cut), or
    /// bevelled `end_bevel_deg` from square on both faces.
    pub end_setback: Option<f64>,
    pub end_bevel_deg: Option<f64>,
    pub sheet: [f64; 2],
    pub sheets: usize,
    pub gap: f64,
    pub label_height: f64,
    pub bom: Bom,
}

/// Parses `WxH` (model units).
pub fn parse_sheet(text: &str) -> Result<Sheet> {
    let bad =
        |why: &str| Error::option("sheet", text, format!("{why}; expected WxH, e.g. 2.5x1.25"));
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| bad("no x between width and height"))?;
    let number = |s: &str| {
        s.trim()
            .parse::<f64>()
            .map_err(|_| bad(&format!("{s:?} is not a number")))
    };
    let (width, height) = (number(w)?, number(h)?);
    if !(width.is_finite() && height.is_finite() && width > 0.0 && height > 0.0) {
        return Err(bad("width and height must be positive lengths"));
    }
    Ok(Sheet { width, height })
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(0.0)
}

/// Writes the files of `options.formats` for `model` into the folder `out`, which they replace
/// whole (an earlier folder holding files no run writes is kept as `OUT.previous`). `inputs`
/// are files `out` must not hold.
pub fn export(
    model: &Model,
    options: &ExportOptions,
    out: &Path,
    inputs: &[&Path],
) -> Result<Exported> {
    let h = &model.honeycomb;
    if options.formats.is_empty() {
        return Err(Error::Parameter("--format: no format given".into()));
    }
    let cut = match options.material_thickness {
        Some(t) => {
            check_positive_length("material_thickness", t)?;
            Some(EndCut::new(t))
        }
        None => None,
    };
    let panels = unroll(h, cut);
    if let Some(c) = cut {
        // Both ends set back must leave some of the panel's bottom and top.
        // Written so that a NaN (a plate too thick for the numbers) counts as nothing left.
        let leaves_some = |p: &&crate::fabrication::Panel| {
            let [a, b, c2, d] = p.cut;
            b[0] - a[0] > 0.0 && c2[0] - d[0] > 0.0 && p.cut.iter().flatten().all(|x| x.is_finite())
        };
        if let Some(p) = panels.iter().find(|p| !leaves_some(p)) {
            return Err(Error::option(
                "material_thickness",
                rounded(c.thickness, 6),
                format!(
                    "its end cuts (each {} back from a node axis) leave nothing of wall W{} ({} \
                     long): give a thinner plate",
                    rounded(c.setback, 4),
                    p.edge,
                    rounded(
                        (h.base.vertices[p.nodes[1]] - h.base.vertices[p.nodes[0]]).norm(),
                        4
                    )
                ),
            ));
        }
    }
    let sheet = match options.sheet {
        Some(s) => s,
        None => Sheet {
            width: 2.5 / options.units.metres(),
            height: 1.25 / options.units.metres(),
        },
    };
    // A sheet thousands of times a panel's size holds nothing a cutter takes, and its
    // coordinates would drown the panels' in round-off.
    let largest = panels
        .iter()
        .map(|p| {
            let (lo, hi) = p.bounds();
            (hi[0] - lo[0]).max(hi[1] - lo[1])
        })
        .fold(0.0, f64::max);
    if sheet.width.max(sheet.height) > 1e4 * largest {
        return Err(Error::option(
            "sheet",
            format!("{}x{}", rounded(sheet.width, 4), rounded(sheet.height, 4)),
            format!(
                "more than 10000 times the largest panel ({}): give a sheet a cutter takes",
                rounded(largest, 4)
            ),
        ));
    }
    let gap = match cut {
        Some(c) => 2.0 * c.thickness,
        None => 0.01 * sheet.width.min(sheet.height),
    };
    let label_height = match options.label_height {
        Some(l) => {
            check_positive_length("label_height", l)?;
            l
        }
        None => 0.2 * median(h.depths().collect()),
    };
    if label_height > sheet.height {
        return Err(Error::option(
            "label_height",
            rounded(label_height, 6),
            format!("taller than the sheet ({})", rounded(sheet.height, 6)),
        ));
    }
    let needs_layout = options
        .formats
        .iter()
        .any(|f| matches!(f, Format::Dxf | Format::Svg));
    // One drawing of the sheets serves both panels.dxf and panels.svg.
    let drawings = if needs_layout {
        let gap_from = if cut.is_some() {
            "2 x --material-thickness"
        } else {
            "1% of the sheet"
        };
        let layout = lay_out(&panels, sheet, gap, gap_from)?;
        Some(draw(
            &panels,
            &layout,
            label_height,
            cut,
            options.units.name(),
        ))
    } else {
        None
    };
    let walls = wall_rows(h, &model.conn, &model.surface);
    let bom = bill_of_materials(
        h,
        &walls,
        &model.measures,
        options.units.name(),
        options.units.millimetre(),
    );
    let frame = Frame {
        scale: 1.0,
        up: options.up,
    };

    let dir = OutputDir::begin(out, inputs)?;
    let mut files = Vec::new();
    let mut exported = Exported {
        dir: out.to_path_buf(),
        files: Vec::new(),
        units: options.units,
        up: options.up,
        surface: model.surface_source.clone(),
        material_thickness: cut.map(|c| c.thickness),
        end_setback: cut.map(|c| c.setback),
        end_bevel_deg: cut.map(|c| c.bevel_deg),
        sheet: [sheet.width, sheet.height],
        sheets: drawings.as_ref().map_or(0, |d| d.sheets.len()),
        gap,
        label_height,
        bom,
    };
    dir.finish(Verdict::Passed, |staging| {
        let mut outputs = Outputs::new();
        let mut file =
            |name: &str, write: &mut dyn FnMut(&mut dyn std::io::Write) -> std::io::Result<()>| {
                files.push(name.to_string());
                outputs.file(&staging.join(name), |w| write(w))
            };
        for format in &options.formats {
            match format {
                Format::Glb => {
                    let bytes = super::glb_bytes(model)?;
                    file("structure.glb", &mut |w| w.write_all(&bytes))?;
                }
                Format::Obj => {
                    file("structure.obj", &mut |w| obj::write_obj(w, model, frame))?;
                    file("structure.mtl", &mut |w| obj::write_mtl(w))?;
                }
                Format::Dxf | Format::Svg => {
                    let drawings = drawings.as_ref().expect("drawn for dxf and svg");
                    if *format == Format::Dxf {
                        file("panels.dxf", &mut |w| {
                            dxf::write_dxf(w, drawings, options.units)
                        })?;
                    } else {
                        let text = svg::svg_text(drawings, options.units);
                        file("panels.svg", &mut |w| w.write_all(text.as_bytes()))?;
                    }
                }
                Format::Csv => {
                    file("walls.csv", &mut |w| csv::write_walls(w, &walls))?;
                    let nodes = node_rows(h, &model.conn, &model.measures);
                    file("nodes.csv", &mut |w| csv::write_nodes(w, &nodes, frame))?;
                    let extra = bom_extra(&exported);
                    file("bom.csv", &mut |w| csv::write_bom(w, &exported.bom, &extra))?;
                }
            }
        }
        files.push("export.json".into());
        exported.files = files.clone();
        super::stage_json(&mut outputs, &staging.join("export.json"), &exported)?;
        outputs.commit()
    })?;
    Ok(exported)
}

/// The rows of `bom.csv` after the bill's own: the layout and the end cut.
fn bom_extra(e: &Exported) -> Vec<(&'static str, String)> {
    let mut rows = vec![
        ("sheet_width", short_number(e.sheet[0])),
        ("sheet_height", short_number(e.sheet[1])),
    ];
    if e.sheets > 0 {
        rows.push(("sheets", e.sheets.to_string()));
    }
    if let (Some(t), Some(s), Some(b)) = (e.material_thickness, e.end_setback, e.end_bevel_deg) {
        rows.push(("material_thickness", short_number(t)));
        rows.push(("end_setback", short_number(s)));
        rows.push(("end_bevel_deg", short_number(b)));
    }
    rows
}
