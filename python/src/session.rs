//! `honeycomb.EditSession`: the editor's three modes from a script.

use crate::inputs::{base_of, mesh_arg, point, surface_of};
use crate::py_err;
use crate::result::{to_json, Arrays, HoneycombResult};
use honeycomb::export::read_structure;
use honeycomb::report::Report;
use honeycomb::{Edit, EditSession, SessionOptions, Surface, Workspace};
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Mutex;

/// Live editing of a honeycomb (the paper's three modes): each edit re-optimizes (or, for a
/// slide, moves one vertex) and returns the result; with undo and redo.
#[pyclass(name = "EditSession", module = "honeycomb", frozen)]
pub(crate) struct PyEditSession {
    pub(crate) session: Mutex<EditSession>,
}

impl PyEditSession {
    /// Applies `edit` and runs its solve to the end, without the GIL.
    fn edit(&self, py: Python<'_>, edit: Edit) -> PyResult<HoneycombResult> {
        let applied = py
            .detach(|| -> honeycomb::Result<_> {
                let mut session = self.session.lock().unwrap();
                let applied = session.apply(edit, None)?;
                session.finish()?;
                Ok(applied)
            })
            .map_err(py_err)?;
        if let Some(warning) = applied.warning {
            let message = std::ffi::CString::new(warning).unwrap_or_default();
            PyErr::warn(
                py,
                &py.get_type::<pyo3::exceptions::PyUserWarning>(),
                &message,
                1,
            )?;
        }
        self.result(py)
    }
}

#[pymethods]
impl PyEditSession {
    /// Optimizes `base` (a path, a `(vertices, faces)` pair or a compas Mesh) on `surface`
    /// (default: itself) into a honeycomb to edit, M' at `thickness` (model units; default 0.3
    /// mean edge lengths). A structure directory (`save`'s) goes on being edited from its walls
    /// with `EditSession.read(dir)`.
    #[new]
    #[pyo3(signature = (base, surface=None, *, thickness=None))]
    fn new(
        py: Python<'_>,
        base: &Bound<'_, PyAny>,
        surface: Option<&Bound<'_, PyAny>>,
        thickness: Option<f64>,
    ) -> PyResult<PyEditSession> {
        let base = mesh_arg(py, "base", base)?;
        let surface = surface.map(|s| mesh_arg(py, "surface", s)).transpose()?;
        let session = py
            .detach(|| -> honeycomb::Result<EditSession> {
                let base = base_of(base)?;
                let surface = surface.map(surface_of).transpose()?;
                let ws = Workspace::new(
                    base.mesh(),
                    surface.as_ref().map(|s| s.source_mesh()),
                    thickness,
                )?;
                EditSession::new(ws, SessionOptions::default())
            })
            .map_err(py_err)?;
        Ok(PyEditSession {
            session: Mutex::new(session),
        })
    }

    /// A structure directory to go on editing, its walls the start; `surface` as for `read`.
    #[staticmethod]
    #[pyo3(signature = (dir, surface=None))]
    fn read(
        py: Python<'_>,
        dir: PathBuf,
        surface: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyEditSession> {
        let surface = surface.map(|s| mesh_arg(py, "surface", s)).transpose()?;
        let session = py
            .detach(|| -> honeycomb::Result<EditSession> {
                let (h, _) = read_structure(&dir)?;
                let kept = dir.join("surface.obj");
                let surface = match surface {
                    Some(s) => Some(surface_of(s)?),
                    None if kept.is_file() => Some(Surface::read(&kept)?),
                    None => None,
                };
                let ws = Workspace::from_honeycomb(&h, surface.as_ref().map(|s| s.source_mesh()))?;
                EditSession::new(ws, SessionOptions::default())
            })
            .map_err(py_err)?;
        Ok(PyEditSession {
            session: Mutex::new(session),
        })
    }

    /// Mode (i): `vertex` goes to the point of the surface closest to `target` and is held
    /// there, the vertices up to `radius` rings away moving along; re-optimizes.
    #[pyo3(signature = (vertex, target, radius=0))]
    fn move_vertex(
        &self,
        py: Python<'_>,
        vertex: usize,
        target: &Bound<'_, PyAny>,
        radius: usize,
    ) -> PyResult<HoneycombResult> {
        let target = point(py, "target", target)?;
        self.edit(
            py,
            Edit::MoveVertex {
                vertex,
                target,
                radius,
            },
        )
    }

    /// Mode (ii): `vertex` moves `distance` along its node axis (towards M' when positive);
    /// nothing is optimized.
    fn slide_vertex(
        &self,
        py: Python<'_>,
        vertex: usize,
        distance: f64,
    ) -> PyResult<HoneycombResult> {
        self.edit(py, Edit::SlideVertex { vertex, distance })
    }

    /// Mode (iii): the node axis of `vertex` turns to `direction`, the axes up to `radius`
    /// rings away following; re-optimizes with the axes as targets.
    #[pyo3(signature = (vertex, direction, radius=0))]
    fn turn_axis(
        &self,
        py: Python<'_>,
        vertex: usize,
        direction: &Bound<'_, PyAny>,
        radius: usize,
    ) -> PyResult<HoneycombResult> {
        let direction = point(py, "direction", direction)?;
        self.edit(
            py,
            Edit::TurnAxis {
                vertex,
                direction,
                radius,
            },
        )
    }

    /// Back to the state before the last edit; False when there is none.
    fn undo(&self) -> bool {
        self.session.lock().unwrap().undo()
    }

    /// The edit undone last, again; False when there is none.
    fn redo(&self) -> bool {
        self.session.lock().unwrap().redo()
    }

    /// The honeycomb as it stands, measured (no report: `report` is None).
    #[getter]
    fn result(&self, py: Python<'_>) -> PyResult<HoneycombResult> {
        let (view, surface) = py.detach(|| {
            let session = self.session.lock().unwrap();
            (
                session.view(),
                session.workspace().model_surface.design_mesh().cloned(),
            )
        });
        let is_honeycomb = Report::within_tolerances(&view.measures);
        Ok(HoneycombResult {
            surface,
            is_honeycomb,
            why: (!is_honeycomb).then(|| Report::tolerance_summary(&view.measures, false)),
            unmet: None,
            measures: to_json(py, &view.measures)?,
            arrays: Arrays::of(py, &view.honeycomb)?,
            honeycomb: view.honeycomb,
            outcome: None,
            report: py.None(),
        })
    }
}
