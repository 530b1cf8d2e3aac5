//! `honeycomb.Result`: a honeycomb as numpy arrays and dicts.

use crate::py_err;
use honeycomb::export::{export, parse_sheet, ExportOptions, Format, Model, Units, Up};
use honeycomb::mesh::PolyMesh;
use honeycomb::structure::Honeycomb;
use honeycomb::{Outcome, Surface, Vec3};
use numpy::{IntoPyArray, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::{Path, PathBuf};

pub(crate) fn json_loads<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

pub(crate) fn to_json<T: serde::Serialize>(py: Python<'_>, value: &T) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(json_loads(py, &text)?.unbind())
}

/// A honeycomb: its meshes as numpy arrays, its measures and report as dicts.
#[pyclass(name = "Result", module = "honeycomb", frozen)]
pub(crate) struct HoneycombResult {
    pub(crate) honeycomb: Honeycomb,
    pub(crate) arrays: Arrays,
    /// The design surface it was made on (`None`: M itself), for `export`.
    pub(crate) surface: Option<PolyMesh>,
    /// What `save` writes; `None` for a structure read back.
    pub(crate) outcome: Option<Outcome>,
    pub(crate) is_honeycomb: bool,
    pub(crate) why: Option<String>,
    pub(crate) unmet: Option<String>,
    pub(crate) measures: Py<PyAny>,
    pub(crate) report: Py<PyAny>,
}

impl HoneycombResult {
    pub(crate) fn of(
        py: Python<'_>,
        outcome: Outcome,
        surface: Option<&Surface>,
    ) -> PyResult<HoneycombResult> {
        Ok(HoneycombResult {
            arrays: Arrays::of(py, &outcome.honeycomb)?,
            honeycomb: outcome.honeycomb.clone(),
            surface: surface.and_then(|s| s.design_mesh().cloned()),
            is_honeycomb: outcome.is_honeycomb(),
            why: outcome.verdict.why.clone(),
            unmet: outcome.verdict.unmet.clone(),
            measures: to_json(py, &outcome.measures)?,
            report: to_json(py, &outcome.report)?,
            outcome: Some(outcome),
        })
    }
}

/// A result's arrays, made once: every access returns the same read-only array.
pub(crate) struct Arrays {
    pub(crate) vertices: Py<PyArray2<f64>>,
    pub(crate) offset_vertices: Py<PyArray2<f64>>,
    pub(crate) edges: Py<PyArray2<i64>>,
    pub(crate) wall_normals: Py<PyArray2<f64>>,
    pub(crate) node_axes: Py<PyArray2<f64>>,
}

impl Arrays {
    pub(crate) fn of(py: Python<'_>, h: &Honeycomb) -> PyResult<Arrays> {
        let edges: Vec<i64> = h
            .edges
            .iter()
            .flat_map(|&[a, b]| [a as i64, b as i64])
            .collect();
        let edges = edges.into_pyarray(py).reshape([h.edges.len(), 2])?;
        Ok(Arrays {
            vertices: read_only(points_array(py, h.base.vertices.iter().copied())?)?,
            offset_vertices: read_only(points_array(py, h.offset.vertices.iter().copied())?)?,
            edges: read_only(edges)?,
            wall_normals: read_only(points_array(
                py,
                (0..h.edges.len()).map(|e| h.wall_normal(e)),
            )?)?,
            node_axes: read_only(points_array(py, h.axes.iter().copied())?)?,
        })
    }
}

/// `array` with numpy's write flag off: it is shared by every access.
pub(crate) fn read_only<T: numpy::Element>(
    array: Bound<'_, PyArray2<T>>,
) -> PyResult<Py<PyArray2<T>>> {
    let kw = PyDict::new(array.py());
    kw.set_item("write", false)?;
    array.call_method("setflags", (), Some(&kw))?;
    Ok(array.unbind())
}

/// Points as an (n, 3) float64 array.
pub(crate) fn points_array<'py>(
    py: Python<'py>,
    points: impl ExactSizeIterator<Item = Vec3>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = points.len();
    let flat: Vec<f64> = points.flat_map(|p| [p.x, p.y, p.z]).collect();
    flat.into_pyarray(py).reshape([n, 3])
}

#[pymethods]
impl HoneycombResult {
    /// The vertices of M, the mesh on the design surface: (n, 3) float64, read-only (the same
    /// array at every access; copy it to change it).
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.vertices.bind(py).clone()
    }

    /// The vertices of M', at the thickness along the node axes: (n, 3) float64, read-only.
    #[getter]
    fn offset_vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.offset_vertices.bind(py).clone()
    }

    /// The cells, each a list of vertex indices in order (boundary cells may have fewer than
    /// six).
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        PyList::new(py, &self.honeycomb.base.faces)
    }

    /// The edges (one wall each): (m, 2) int64 vertex indices, read-only.
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        self.arrays.edges.bind(py).clone()
    }

    /// The unit normal of each edge's wall (as seen from its first vertex): (m, 3) float64,
    /// read-only.
    #[getter]
    fn wall_normals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.wall_normals.bind(py).clone()
    }

    /// The unit node axis at each vertex, along which the walls meet: (n, 3) float64,
    /// read-only.
    #[getter]
    fn node_axes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.arrays.node_axes.bind(py).clone()
    }

    /// The distance between M and M' along the node axes (model units).
    #[getter]
    fn thickness(&self) -> f64 {
        self.honeycomb.thickness
    }

    /// The measures (report.json's "measures"): omega, delta, closeness, axis to normal, ...
    #[getter]
    fn measures(&self, py: Python<'_>) -> Py<PyAny> {
        self.measures.clone_ref(py)
    }

    /// The report, with the keys of report.json.
    #[getter]
    fn report(&self, py: Python<'_>) -> Py<PyAny> {
        self.report.clone_ref(py)
    }

    /// Whether every node is within the 120-degree tolerance and every wall planar.
    #[getter]
    fn is_honeycomb(&self) -> bool {
        self.is_honeycomb
    }

    /// Why the result is not a honeycomb, in a sentence; None for a honeycomb.
    #[getter]
    fn why(&self) -> Option<String> {
        self.why.clone()
    }

    /// What a honeycomb falls short of that was asked (a shading device's share of the
    /// light), in a sentence; None when all is met, and for a structure read back (its
    /// report's `shading.met` says) or an edit session's.
    #[getter]
    fn unmet(&self) -> Option<String> {
        self.unmet.clone()
    }

    /// Writes the structure files into `dir` for a honeycomb, else into `dir.failed`;
    /// returns where they went.
    fn save(&self, py: Python<'_>, dir: PathBuf) -> PyResult<PathBuf> {
        let Some(outcome) = &self.outcome else {
            return Err(PyValueError::new_err(
                "only a result of pipeline or optimize can be saved (one read back is saved \
                 already; an edit session's is not measured against a report)",
            ));
        };
        py.detach(|| outcome.save(Path::new(&dir))).map_err(py_err)
    }

    /// Files for fabrication and exchange, as `honeycomb export` writes them into `dir`
    /// (replaced whole): `format` is glb, obj, dxf, svg, csv or all, or several joined by
    /// commas; `units` what one model unit is (mm, cm, m, in, ft); `up` z or y for OBJ;
    /// `material_thickness` the plates' thickness (end cuts); `sheet` "WxH" for the panel
    /// layout; `label_height` the labels' height. Returns the names of the files written.
    #[pyo3(signature = (dir, format="all", *, units="m", up="z", material_thickness=None, sheet=None, label_height=None))]
    #[allow(clippy::too_many_arguments)]
    fn export(
        &self,
        py: Python<'_>,
        dir: PathBuf,
        format: &str,
        units: &str,
        up: &str,
        material_thickness: Option<f64>,
        sheet: Option<&str>,
        label_height: Option<f64>,
    ) -> PyResult<Vec<String>> {
        let options = ExportOptions {
            formats: Format::parse_list(format).map_err(py_err)?,
            units: Units::parse(units).map_err(py_err)?,
            up: Up::parse(up).map_err(py_err)?,
            material_thickness,
            sheet: sheet.map(parse_sheet).transpose().map_err(py_err)?,
            label_height,
        };
        let (honeycomb, surface) = (self.honeycomb.clone(), self.surface.clone());
        py.detach(|| {
            let model = Model::new(honeycomb, surface, options.units)?;
            export(&model, &options, &dir, &[])
        })
        .map(|exported| exported.files)
        .map_err(py_err)
    }

    /// The honeycomb as a compas `Mesh` (M), with the vertex attributes `node_axis` and
    /// `offset` (the vertex of M') and the edge attribute `wall_normal` (as seen from the
    /// edge's first vertex in `edges`). Needs compas (ImportError naming it otherwise).
    fn to_compas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let compas = py.import("compas.datastructures").map_err(|e| {
            pyo3::exceptions::PyImportError::new_err(format!(
                "to_compas needs the compas package (pip install compas): {e}"
            ))
        })?;
        let h = &self.honeycomb;
        let xyz = |p: Vec3| [p.x, p.y, p.z];
        let vertices: Vec<[f64; 3]> = h.base.vertices.iter().map(|&p| xyz(p)).collect();
        let mesh = compas
            .getattr("Mesh")?
            .call_method1("from_vertices_and_faces", (vertices, &h.base.faces))?;
        for (v, (&axis, &offset)) in h.axes.iter().zip(&h.offset.vertices).enumerate() {
            mesh.call_method1("vertex_attribute", (v, "node_axis", xyz(axis)))?;
            mesh.call_method1("vertex_attribute", (v, "offset", xyz(offset)))?;
        }
        for (e, &[a, b]) in h.edges.iter().enumerate() {
            mesh.call_method1(
                "edge_attribute",
                ((a, b), "wall_normal", xyz(h.wall_normal(e))),
            )?;
        }
        Ok(mesh)
    }

    /// Writes a Rhino 3dm file: M and M' (cells of more than four sides as triangle fans) and
    /// the wall quads, each on its own layer ("M", "M'", "walls"). Needs rhino3dm
    /// (ImportError naming it otherwise).
    fn to_3dm(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let r3 = py.import("rhino3dm").map_err(|e| {
            pyo3::exceptions::PyImportError::new_err(format!(
                "to_3dm needs the rhino3dm package (pip install rhino3dm): {e}"
            ))
        })?;
        let file = r3.getattr("File3dm")?.call0()?;
        let h = &self.honeycomb;
        let walls = h.walls();
        for (name, mesh) in [("M", &h.base), ("M'", &h.offset), ("walls", &walls)] {
            let layer = r3.getattr("Layer")?.call0()?;
            layer.setattr("Name", name)?;
            let index = file.getattr("Layers")?.call_method1("Add", (layer,))?;
            let rhino = r3.getattr("Mesh")?.call0()?;
            let vertices = rhino.getattr("Vertices")?;
            for p in &mesh.vertices {
                vertices.call_method1("Add", (p.x, p.y, p.z))?;
            }
            let faces = rhino.getattr("Faces")?;
            for face in &mesh.faces {
                match face[..] {
                    [a, b, c] => faces.call_method1("AddFace", (a, b, c))?,
                    [a, b, c, d] => faces.call_method1("AddFace", (a, b, c, d))?,
                    _ => {
                        for k in 1..face.len() - 1 {
                            faces.call_method1("AddFace", (face[0], face[k], face[k + 1]))?;
                        }
                        continue;
                    }
                };
            }
            let attributes = r3.getattr("ObjectAttributes")?.call0()?;
            attributes.setattr("LayerIndex", index)?;
            file.getattr("Objects")?
                .call_method1("AddMesh", (rhino, attributes))?;
        }
        let path = path.to_string_lossy().into_owned();
        if !file.call_method1("Write", (&path, 7))?.extract::<bool>()? {
            return Err(PyOSError::new_err(format!(
                "{path}: rhino3dm could not write it"
            )));
        }
        Ok(())
    }

    fn __repr__(&self) -> String {
        format!(
            "<honeycomb.Result: {} vertices, {} cells, {}>",
            self.honeycomb.base.vertices.len(),
            self.honeycomb.base.faces.len(),
            if self.is_honeycomb {
                "a honeycomb"
            } else {
                "not a honeycomb"
            }
        )
    }
}
