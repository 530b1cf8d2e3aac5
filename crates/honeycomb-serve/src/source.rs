//! What the editor starts from: a built-in demo, a saved structure directory, or a design
//! surface that gets a hexagonal base mesh first.

use honeycomb::export::read_structure;
use honeycomb::generate::{lifted_hex_patch, Shape};
use honeycomb::interactive::Workspace;
use honeycomb::limits::check_solve_vertices;
use honeycomb::mesh::{read_mesh, PolyMesh};
use honeycomb::{pipeline, PipelineOptions, Progress, Surface, Walls};
use honeycomb::{Error, Result};
use std::path::{Path, PathBuf};

#[derive(Clone, Debug)]
pub enum Source {
    /// A hex mesh lifted onto a built-in surface, with about `vertices` vertices.
    Demo { shape: Shape, vertices: usize },
    /// A structure directory (`structure.json`, and `surface.obj` when it has one).
    Structure(PathBuf),
    /// A design surface: `pipeline` makes a honeycomb of about `cells` cells on it, its
    /// walls standing as `walls` says.
    Surface {
        path: PathBuf,
        cells: usize,
        walls: Walls,
    },
}

impl Source {
    /// A path names a structure directory or a surface file.
    pub fn from_path(path: &Path, cells: usize, walls: Walls) -> Source {
        if path.is_dir() {
            Source::Structure(path.to_path_buf())
        } else {
            Source::Surface {
                path: path.to_path_buf(),
                cells,
                walls,
            }
        }
    }

    pub fn label(&self) -> String {
        match self {
            Source::Demo { shape, vertices } => {
                format!(
                    "demo {} ({vertices} vertices)",
                    format!("{shape:?}").to_lowercase()
                )
            }
            Source::Structure(dir) => dir.display().to_string(),
            Source::Surface { path, cells, walls } => format!(
                "{} ({cells} cells, walls {})",
                path.display(),
                walls.label()
            ),
        }
    }

    pub fn workspace(&self, thickness: Option<f64>) -> Result<Workspace> {
        self.workspace_with_notes(thickness).map(|(ws, _)| ws)
    }

    /// [`Source::workspace`], with what the pipeline changed on the way to it (a surface's
    /// notes), for the front to show.
    pub fn workspace_with_notes(&self, thickness: Option<f64>) -> Result<(Workspace, Vec<String>)> {
        match self {
            Source::Demo { shape, vertices } => {
                check_solve_vertices(&format!("--vertices {vertices}"), *vertices)?;
                let (base, surface) = lifted_hex_patch(*shape, *vertices);
                Ok((
                    Workspace::new(&base, Some(&surface), thickness)?,
                    Vec::new(),
                ))
            }
            Source::Structure(dir) => {
                let (h, _) = read_structure(dir)?;
                let surface = structure_surface(dir)?;
                Ok((Workspace::from_honeycomb(&h, surface.as_ref())?, Vec::new()))
            }
            Source::Surface { path, cells, walls } => {
                let surface = Surface::new(read_mesh(path)?.mesh)?;
                // As `honeycomb pipeline` makes it, so that editing starts from a honeycomb.
                let mut options = PipelineOptions::new(*cells);
                options.options.walls = *walls;
                options.options.thickness = thickness;
                let made = pipeline(&surface, &options, &mut Progress::silent())?;
                if !made.is_honeycomb() {
                    let m = &made.measures;
                    return Err(Error::Solver(format!(
                        "the pipeline made no honeycomb on this surface (omega_max {} deg, \
                         delta_max {}): nothing to edit; `honeycomb pipeline` writes the result \
                         for inspection",
                        honeycomb::error::rounded(m.omega_max_deg, 3),
                        honeycomb::error::rounded(m.delta_max, 3)
                    )));
                }
                let ws = Workspace::from_honeycomb(&made.honeycomb, Some(surface.source_mesh()))?;
                Ok((ws, made.report.notes))
            }
        }
    }
}

/// `DIR/surface.obj` when the directory has one (written by `demo`, `pipeline` and the
/// editor's save).
fn structure_surface(dir: &Path) -> Result<Option<PolyMesh>> {
    let path = dir.join("surface.obj");
    if !path.exists() {
        return Ok(None);
    }
    Ok(Some(read_mesh(&path)?.mesh))
}

/// The folder a save `name` goes to: always directly inside `root`.
pub fn save_dir(root: &Path, name: &str) -> Result<PathBuf> {
    crate::protocol::check_name(name).map_err(Error::Parameter)?;
    Ok(root.join(name))
}
