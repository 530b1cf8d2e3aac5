//! What the editor starts from: a built-in demo, a saved structure directory, or a design
//! surface that gets a hexagonal base mesh first.

use honeycomb::export::read_structure;
use honeycomb::generate::{lifted_hex_patch, Shape};
use honeycomb::interactive::{Watch, Workspace};
use honeycomb::limits::check_solve_vertices;
use honeycomb::mesh::{read_mesh, PolyMesh};
use honeycomb::{pipeline, Options, PipelineOptions, Progress, Surface};
use honeycomb::{Error, Result};
use std::path::{Path, PathBuf};

#[derive(Clone, Debug)]
pub enum Source {
    /// A hex mesh lifted onto a built-in surface, with about `vertices` vertices.
    Demo { shape: Shape, vertices: usize },
    /// A structure directory (`structure.json`, and `surface.obj` when it has one).
    Structure(PathBuf),
    /// A design surface: `pipeline` makes a honeycomb of about `cells` cells on it, its
    /// walls and its variant as `options` say.
    Surface {
        path: PathBuf,
        cells: usize,
        options: Box<Options>,
        /// Uneven cells of walls across S evened or not (`pipeline --even-cells`,
        /// `--no-even-cells`); `None`: the pipeline's default.
        even_cells: Option<bool>,
    },
}

/// What the editor starts from: the workspace, what the pipeline changed on the way to it
/// (a surface's notes), and what its variant is judged by.
pub struct Made {
    pub ws: Workspace,
    pub notes: Vec<String>,
    pub watch: Option<Watch>,
}

impl Source {
    /// A path names a structure directory or a surface file.
    pub fn from_path(path: &Path, cells: usize, options: Options) -> Source {
        if path.is_dir() {
            Source::Structure(path.to_path_buf())
        } else {
            Source::Surface {
                path: path.to_path_buf(),
                cells,
                options: Box::new(options),
                even_cells: None,
            }
        }
    }

    /// This source with a design surface's uneven cells evened or not (`pipeline
    /// --even-cells`, `--no-even-cells`); other sources have their cells.
    pub fn with_even_cells(mut self, even: Option<bool>) -> Source {
        if let Source::Surface { even_cells, .. } = &mut self {
            *even_cells = even;
        }
        self
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
            Source::Surface {
                path,
                cells,
                options,
                even_cells,
            } => format!(
                "{} ({cells} cells, walls {}{}{})",
                path.display(),
                options.walls.label(),
                match even_cells {
                    Some(true) => ", cells evened",
                    Some(false) => ", cells as fitted",
                    None => "",
                },
                match options.variant.name() {
                    Some(name) => format!(", {name}"),
                    None => String::new(),
                }
            ),
        }
    }

    pub fn workspace(&self, thickness: Option<f64>) -> Result<Workspace> {
        self.made(thickness).map(|made| made.ws)
    }

    /// [`Source::workspace`], with what the pipeline changed on the way to it and what its
    /// variant is judged by.
    pub fn made(&self, thickness: Option<f64>) -> Result<Made> {
        let plain = |ws| Made {
            ws,
            notes: Vec::new(),
            watch: None,
        };
        match self {
            Source::Demo { shape, vertices } => {
                check_solve_vertices(&format!("--vertices {vertices}"), *vertices)?;
                let (base, surface) = lifted_hex_patch(*shape, *vertices);
                Ok(plain(Workspace::new(&base, Some(&surface), thickness)?))
            }
            Source::Structure(dir) => {
                let (h, _) = read_structure(dir)?;
                let surface = structure_surface(dir)?;
                Ok(plain(Workspace::from_honeycomb(&h, surface.as_ref())?))
            }
            Source::Surface {
                path,
                cells,
                options,
                even_cells,
            } => {
                let surface = Surface::new(read_mesh(path)?.mesh)?;
                // As `honeycomb pipeline` makes it, so that editing starts from a honeycomb.
                let mut pipeline_options = PipelineOptions::new(*cells);
                pipeline_options.options = (**options).clone();
                pipeline_options.even_cells = *even_cells;
                if thickness.is_some() {
                    pipeline_options.options.thickness = thickness;
                }
                let made = pipeline(&surface, &pipeline_options, &mut Progress::silent())?;
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
                let mut notes = made.report.notes.clone();
                notes.extend(made.verdict.unmet.clone());
                let watch = Watch::of(&made, &options.variant);
                let mut ws =
                    Workspace::from_honeycomb(&made.honeycomb, Some(surface.source_mesh()))?;
                if watch.is_some() {
                    ws = ws.as_it_is();
                }
                Ok(Made { ws, notes, watch })
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
