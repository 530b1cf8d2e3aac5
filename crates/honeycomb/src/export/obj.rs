//! `structure.obj` with `structure.mtl`: one file that Rhino, Blender and other tools open,
//! with one object per part (`surface`, `base`, `offset`, `node_axes`) and per wall (`W<edge>`,
//! in the group `walls`), each with its material.

use super::{Frame, Model, Up};
use crate::geometry::Vec3;
use crate::mesh::PolyMesh;
use std::io::Write;

/// The materials `structure.mtl` defines: name and diffuse colour.
const MATERIALS: [(&str, [f64; 3]); 5] = [
    ("surface", [0.75, 0.75, 0.75]),
    ("base", [0.25, 0.25, 0.3]),
    ("offset", [0.55, 0.55, 0.6]),
    ("walls", [0.85, 0.65, 0.35]),
    ("node_axes", [0.8, 0.1, 0.1]),
];

pub fn write_mtl(w: &mut dyn Write) -> std::io::Result<()> {
    writeln!(w, "# honeycomb structure materials")?;
    for (name, [r, g, b]) in MATERIALS {
        writeln!(
            w,
            "newmtl {name}\nKd {r} {g} {b}\nd {}\n",
            if name == "surface" { 0.5 } else { 1.0 }
        )?;
    }
    Ok(())
}

/// Counts the vertices written so far: OBJ indices are global and start at 1.
struct ObjWriter<'a> {
    w: &'a mut dyn Write,
    frame: Frame,
    written: usize,
}

impl ObjWriter<'_> {
    fn vertices(&mut self, points: &[Vec3]) -> std::io::Result<usize> {
        let first = self.written + 1;
        for &p in points {
            let [x, y, z] = self.frame.point(p);
            writeln!(self.w, "v {x} {y} {z}")?;
        }
        self.written += points.len();
        Ok(first)
    }

    fn mesh(&mut self, name: &str, material: &str, mesh: &PolyMesh) -> std::io::Result<()> {
        writeln!(self.w, "o {name}\nusemtl {material}")?;
        let first = self.vertices(&mesh.vertices)?;
        for face in &mesh.faces {
            let ids: Vec<String> = face.iter().map(|&v| (first + v).to_string()).collect();
            writeln!(self.w, "f {}", ids.join(" "))?;
        }
        Ok(())
    }
}

pub fn write_obj(w: &mut dyn Write, model: &Model, frame: Frame) -> std::io::Result<()> {
    let h = &model.honeycomb;
    let up = match frame.up {
        Up::Z => "Z up (model axes; Blender: import with Up Axis Z and Forward Axis Y)",
        Up::Y => "Y up (turned from the model's Z up; Blender's default import settings)",
    };
    writeln!(
        w,
        "# honeycomb structure: {} cells, {} walls, {} nodes\n# units: {}\n# {up}\n# objects: surface (S), base (M), offset (M'), node_axes, and one object W<edge> per wall (group walls)\nmtllib structure.mtl",
        h.base.faces.len(),
        h.edges.len(),
        h.base.vertices.len(),
        model.units.name()
    )?;
    let mut out = ObjWriter {
        w,
        frame,
        written: 0,
    };
    if let Some(surface) = &model.surface_mesh {
        out.mesh("surface", "surface", surface)?;
    }
    out.mesh("base", "base", &h.base)?;
    out.mesh("offset", "offset", &h.offset)?;
    writeln!(out.w, "o node_axes\nusemtl node_axes")?;
    let base = out.vertices(&h.base.vertices)?;
    let offset = out.vertices(&h.offset.vertices)?;
    for v in 0..h.base.vertices.len() {
        writeln!(out.w, "l {} {}", base + v, offset + v)?;
    }
    for e in 0..h.edges.len() {
        writeln!(out.w, "o W{e}\ng walls\nusemtl walls")?;
        let first = out.vertices(&h.wall(e))?;
        writeln!(
            out.w,
            "f {} {} {} {}",
            first,
            first + 1,
            first + 2,
            first + 3
        )?;
    }
    Ok(())
}
