//! A finished honeycomb as the exporters see it: the structure, its surface and its measures,
//! read once from a structure directory.

use super::read_structure;
use super::Units;
use crate::error::{Error, Result};
use crate::mesh::{read_mesh, Connectivity, PolyMesh};
use crate::report::Report;
use crate::structure::{measure, per_wall_worse_end, Honeycomb, Measures};
use crate::surface::Surface;
use std::path::{Path, PathBuf};

pub struct Model {
    pub honeycomb: Honeycomb,
    pub conn: Connectivity,
    /// Measured against `surface`.
    pub measures: Measures,
    /// The design surface S, or M itself where the directory holds none.
    pub surface: Surface,
    /// S as a mesh, when the directory (or the caller) gave one.
    pub surface_mesh: Option<PolyMesh>,
    /// Where S came from: a file, or "base mesh M".
    pub surface_source: String,
    pub units: Units,
}

impl Model {
    /// Reads `DIR/structure.json` and S (`surface`, else `DIR/surface.obj` when present, else M
    /// itself), refusing a structure that is not a honeycomb: a fabricator must not cut one.
    pub fn read(dir: &Path, surface: Option<&Path>, units: Units) -> Result<Model> {
        let (honeycomb, _) = read_structure(dir)?;
        let path: Option<PathBuf> = match surface {
            Some(p) => Some(p.to_path_buf()),
            None => Some(dir.join("surface.obj")).filter(|p| p.is_file()),
        };
        let surface_mesh = match &path {
            Some(p) => Some(read_mesh(p)?.mesh),
            None => None,
        };
        let mut model = Model::new(honeycomb, surface_mesh, units)?;
        refuse_unless_honeycomb(dir, &model.measures)?;
        if let Some(p) = path {
            model.surface_source = p.display().to_string();
        }
        Ok(model)
    }

    /// A model of a honeycomb already in memory, with S as given (else M itself); unlike
    /// `read`, it does not check that the structure is a honeycomb.
    pub fn new(
        honeycomb: Honeycomb,
        surface_mesh: Option<PolyMesh>,
        units: Units,
    ) -> Result<Model> {
        let conn = Connectivity::build(&honeycomb.base)?;
        let surface = Surface::from_mesh(surface_mesh.as_ref().unwrap_or(&honeycomb.base))?;
        let measures = measure(&honeycomb, &surface);
        let surface_source = match surface_mesh {
            Some(_) => "surface mesh".into(),
            None => "base mesh M".into(),
        };
        Ok(Model {
            honeycomb,
            conn,
            measures,
            surface,
            surface_mesh,
            surface_source,
            units,
        })
    }

    /// Per wall, the larger axis-to-normal angle (degrees) of its two nodes: how far the wall
    /// leans from standing across S.
    pub fn wall_lean_deg(&self) -> Vec<f64> {
        per_wall_worse_end(&self.honeycomb.edges, &self.measures.axis_normal_per_node)
    }
}

/// Reads a structure directory and checks that it is a honeycomb (every node within the angle
/// tolerance, every wall within the planarity tolerance), as the fronts that build on one need.
pub fn read_honeycomb(dir: &Path) -> Result<(Honeycomb, Connectivity, Measures)> {
    let (h, conn) = read_structure(dir)?;
    // Omega and delta do not depend on S; M stands in for it.
    let measures = measure(&h, &Surface::from_mesh(&h.base)?);
    refuse_unless_honeycomb(dir, &measures)?;
    Ok((h, conn, measures))
}

fn refuse_unless_honeycomb(dir: &Path, measures: &Measures) -> Result<()> {
    if Report::within_tolerances(measures) {
        return Ok(());
    }
    Err(Error::Parse {
        path: dir.join("structure.json"),
        line: 0,
        message: format!(
            "not a honeycomb: {}",
            Report::tolerance_summary(measures, false)
        ),
    })
}
