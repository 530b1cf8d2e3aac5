//! `import honeycomb`: the library's front door for Python.
//!
//! Only translation: Python values into the front door's types ([`Surface`], [`BaseMesh`],
//! [`Options`], [`PipelineOptions`], a [`Progress`]) and an [`Outcome`] back as numpy arrays
//! and dicts. Keyword options go to [`Options`] through serde, so their names, defaults and
//! checks are the library's.

use honeycomb::export::{
    export, parse_sheet, read_structure, ExportOptions, Format, Model, Units, Up,
};
use honeycomb::init::{Align, BoundaryMode, CellSize, Flattener, Method};
use honeycomb::mesh::PolyMesh;
use honeycomb::report::Report;
use honeycomb::structure::{measure, Honeycomb};
use honeycomb::{
    BaseMesh, Cancel, Edit, EditSession, Error, Options, Outcome, PipelineOptions, Progress,
    SessionOptions, Step, Surface, Vec3, Workspace,
};
use numpy::{
    IntoPyArray, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyReadonlyArray2, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{
    PyFileNotFoundError, PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyValueError,
};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

pyo3::create_exception!(
    honeycomb,
    Cancelled,
    pyo3::exceptions::PyException,
    "The progress callback returned False: the work stopped before its next iteration."
);

/// The library's error as the Python exception that fits it.
fn py_err(e: Error) -> PyErr {
    let message = e.to_string();
    match e {
        Error::Option { .. }
        | Error::Parameter(_)
        | Error::Mesh(_)
        | Error::Unsuited(_)
        | Error::Parse { .. } => PyValueError::new_err(message),
        Error::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(message)
        }
        Error::Io { .. } => PyOSError::new_err(message),
        Error::Cancelled => PyKeyboardInterrupt::new_err(message),
        _ => PyRuntimeError::new_err(message),
    }
}

/// Keyword options as [`Options`]: each field deserialized alone first, so that a bad value
/// is named by its field (serde names only unknown fields), then all together.
fn options(py: Python<'_>, kwargs: &Bound<'_, PyDict>) -> PyResult<Options> {
    let json = py.import("json")?;
    // numpy arrays and scalars have tolist(); anything else is left to json's own error.
    let default = py.eval(c"lambda o: o.tolist()", None, None)?;
    let dumps = |value: &Bound<'_, PyAny>| -> PyResult<String> {
        let kw = PyDict::new(py);
        kw.set_item("default", &default)?;
        json.call_method("dumps", (value,), Some(&kw))?.extract()
    };
    for (key, value) in kwargs.iter() {
        let one = PyDict::new(py);
        one.set_item(&key, &value)?;
        let text = dumps(one.as_any())
            .map_err(|e| PyValueError::new_err(format!("invalid option {key}: {e}")))?;
        serde_json::from_str::<Options>(&text)
            .map_err(|e| PyValueError::new_err(format!("invalid option {key}: {e}")))?;
    }
    let text = dumps(kwargs.as_any())?;
    let options: Options = serde_json::from_str(&text)
        .map_err(|e| PyValueError::new_err(format!("invalid options: {e}")))?;
    options.validate().map_err(py_err)?;
    Ok(options)
}

/// An (n, 3) array of points from any array-like.
fn points(py: Python<'_>, what: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<Vec3>> {
    let np = py.import("numpy")?;
    let kw = PyDict::new(py);
    kw.set_item("dtype", "float64")?;
    let array = np.call_method("ascontiguousarray", (obj,), Some(&kw))?;
    let array: PyReadonlyArray2<f64> = array.extract().map_err(|_| {
        PyValueError::new_err(format!("{what}: expected an (n, 3) array of numbers"))
    })?;
    let view = array.as_array();
    if view.ncols() != 3 {
        return Err(PyValueError::new_err(format!(
            "{what}: expected an (n, 3) array, got shape {:?}",
            view.shape()
        )));
    }
    Ok(view
        .rows()
        .into_iter()
        .map(|r| Vec3::new(r[0], r[1], r[2]))
        .collect())
}

/// Polygons as vertex index lists: an (m, k) integer array, or a list of index lists of any
/// lengths.
fn polygons(py: Python<'_>, what: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<Vec<usize>>> {
    let bad = || {
        PyValueError::new_err(format!(
            "{what}: expected lists of non-negative vertex indices"
        ))
    };
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        if array.ndim() == 2 && matches!(array.dtype().kind(), b'i' | b'u') {
            let np = py.import("numpy")?;
            let kw = PyDict::new(py);
            kw.set_item("dtype", "int64")?;
            let array = np.call_method("ascontiguousarray", (obj,), Some(&kw))?;
            let array: PyReadonlyArray2<i64> = array.extract()?;
            return array
                .as_array()
                .rows()
                .into_iter()
                .map(|row| {
                    row.iter()
                        .map(|&i| usize::try_from(i).map_err(|_| bad()))
                        .collect()
                })
                .collect();
        }
        return polygons(py, what, &obj.call_method0("tolist")?);
    }
    let items: Vec<Bound<'_, PyAny>> = obj.extract().map_err(|_| bad())?;
    items
        .iter()
        .map(|item| {
            let item = if item.hasattr("tolist")? {
                item.call_method0("tolist")?
            } else {
                item.clone()
            };
            item.extract::<Vec<usize>>().map_err(|_| bad())
        })
        .collect()
}

/// A mesh given as a path, a `(vertices, faces)` pair or a compas `Mesh` (anything with
/// `to_vertices_and_faces()`); a path is returned as such, to be read by the library.
enum MeshArg {
    Path(PathBuf),
    Mesh(Vec<Vec3>, Vec<Vec<usize>>),
}

fn mesh_arg(py: Python<'_>, what: &str, obj: &Bound<'_, PyAny>) -> PyResult<MeshArg> {
    if let Ok(path) = obj.extract::<PathBuf>() {
        return Ok(MeshArg::Path(path));
    }
    let pair = if obj.hasattr("to_vertices_and_faces")? {
        obj.call_method0("to_vertices_and_faces")?
    } else {
        obj.clone()
    };
    let (vertices, faces): (Bound<'_, PyAny>, Bound<'_, PyAny>) = pair.extract().map_err(|_| {
        PyValueError::new_err(format!(
            "{what}: expected a path, a (vertices, faces) pair or a compas Mesh"
        ))
    })?;
    Ok(MeshArg::Mesh(
        points(py, &format!("{what} vertices"), &vertices)?,
        polygons(py, &format!("{what} faces"), &faces)?,
    ))
}

fn surface_of(arg: MeshArg) -> honeycomb::Result<Surface> {
    match arg {
        MeshArg::Path(path) => Surface::read(&path),
        MeshArg::Mesh(vertices, faces) => Surface::new(PolyMesh::new(vertices, faces)),
    }
}

fn base_of(arg: MeshArg) -> honeycomb::Result<BaseMesh> {
    match arg {
        MeshArg::Path(path) => BaseMesh::read(&path),
        MeshArg::Mesh(vertices, cells) => BaseMesh::new(vertices, cells),
    }
}

/// A step as the dict the progress callback gets.
fn step_dict<'py>(py: Python<'py>, step: Step<'_>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    match step {
        Step::Init => d.set_item("step", "init")?,
        Step::Iteration(solve, number, info) => {
            d.set_item("step", "iteration")?;
            d.set_item("solve", solve)?;
            d.set_item("solve_number", number)?;
            d.set_item("iteration", info.iteration)?;
            d.set_item("max_residual", info.max_residual)?;
            d.set_item("energy", info.energy)?;
            d.set_item("eps", info.eps)?;
        }
    }
    Ok(d)
}

/// Runs `work` without the GIL. At every step the GIL is taken back to look for Ctrl-C and
/// to call `callback`; either raising, or the callback returning False, stops the work
/// before its next iteration and is raised here.
fn run<F>(py: Python<'_>, callback: Option<Py<PyAny>>, work: F) -> PyResult<Outcome>
where
    F: FnOnce(&mut Progress) -> honeycomb::Result<Outcome> + Send,
{
    let cancel = Cancel::new();
    let stopped: Mutex<Option<PyErr>> = Mutex::new(None);
    let result = py.detach(|| {
        let inside = cancel.clone();
        let mut progress = Progress::new(|step| {
            if inside.is_cancelled() {
                return;
            }
            Python::attach(|py| {
                let outcome = py.check_signals().and_then(|()| match &callback {
                    Some(f) => {
                        let answer = f.call1(py, (step_dict(py, step)?,))?;
                        let answer = answer.bind(py).cast::<PyBool>().map(|b| b.is_true());
                        if matches!(answer, Ok(false)) {
                            Err(Cancelled::new_err("stopped by the progress callback"))
                        } else {
                            Ok(())
                        }
                    }
                    None => Ok(()),
                });
                if let Err(e) = outcome {
                    *stopped.lock().unwrap() = Some(e);
                    inside.cancel();
                }
            });
        })
        .with_cancel(cancel.clone());
        work(&mut progress)
    });
    // An error raised by the callback (or Ctrl-C) wins, whatever the work ended with.
    if let Some(e) = stopped.lock().unwrap().take() {
        return Err(e);
    }
    result.map_err(py_err)
}

/// Makes a honeycomb on a design surface from nothing else.
///
/// `surface`: a path (OBJ, OFF, PLY), a `(vertices, faces)` pair or a compas Mesh. `walls`:
/// "across", "uniform", "free" or a direction (x, y, z) for every node axis. `cells`:
/// about this many cells (or `edge_length` in model units); `method`: "flatten" or "field";
/// `flatten`: "arap", "lscm" or "project" (default: the pipeline's choice); `boundary`:
/// "trim" or "keep" the cells S's border cuts; `align`: "boundary", "none" or a polyline
/// file of strokes; `seed` shifts the lattice (as `honeycomb pipeline`'s flags). Other keyword arguments are the options of `honeycomb
/// optimize` by their field names (`w_fair` for `--w-fair`). `progress(step: dict)` is
/// called at every step; returning False stops the work (`honeycomb.Cancelled`).
#[pyfunction]
#[pyo3(
    signature = (surface, cells=1500, walls=None, *, edge_length=None, method="flatten", flatten=None, boundary="trim", align="boundary", seed=0, progress=None, **options),
    text_signature = "(surface, cells=1500, walls='across', *, edge_length=None, method='flatten', flatten=None, boundary='trim', align='boundary', seed=0, progress=None, **options)"
)]
#[allow(clippy::too_many_arguments)]
fn pipeline(
    py: Python<'_>,
    surface: &Bound<'_, PyAny>,
    cells: usize,
    walls: Option<&Bound<'_, PyAny>>,
    edge_length: Option<f64>,
    method: &str,
    flatten: Option<&str>,
    boundary: &str,
    align: &str,
    seed: u64,
    progress: Option<Py<PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<HoneycombResult> {
    let kwargs = options.cloned().unwrap_or_else(|| PyDict::new(py));
    match walls {
        Some(walls) => kwargs.set_item("walls", walls)?,
        None => kwargs.set_item("walls", "across")?,
    }
    let options = self::options(py, &kwargs)?;
    let mut pipeline_options = PipelineOptions::new(cells);
    pipeline_options.init.size = match edge_length {
        Some(l) => CellSize::EdgeLength(l),
        None => CellSize::Cells(cells),
    };
    let named =
        |field: &str, m: String| PyValueError::new_err(format!("invalid option {field}: {m}"));
    let init = &mut pipeline_options.init;
    init.method = method.parse::<Method>().map_err(|m| named("method", m))?;
    if let Some(f) = flatten {
        if init.method == Method::Field {
            return Err(named(
                "flatten",
                "picks how method flatten flattens; method field does not flatten".into(),
            ));
        }
        init.flattener = f.parse::<Flattener>().map_err(|m| named("flatten", m))?;
    }
    init.boundary = boundary
        .parse::<BoundaryMode>()
        .map_err(|m| named("boundary", m))?;
    init.align = Align::parse(align).map_err(py_err)?;
    init.seed = seed;
    pipeline_options.init_chosen = flatten.is_some() || init.method == Method::Field;
    pipeline_options.options = options;
    let surface = mesh_arg(py, "surface", surface)?;
    let surface = py.detach(|| surface_of(surface)).map_err(py_err)?;
    let outcome = run(py, progress, |progress| {
        honeycomb::pipeline(&surface, &pipeline_options, progress)
    })?;
    HoneycombResult::of(py, outcome, Some(&surface))
}

/// Optimizes a hexagonal (trivalent) base mesh into a honeycomb on `surface` (default: the
/// base mesh itself).
///
/// `base`, `surface`: a path, a `(vertices, faces)` pair or a compas Mesh. Keyword arguments
/// are the options of `honeycomb optimize` by their field names; `progress` as for
/// `pipeline`.
#[pyfunction]
#[pyo3(signature = (base, surface=None, *, progress=None, **options))]
fn optimize(
    py: Python<'_>,
    base: &Bound<'_, PyAny>,
    surface: Option<&Bound<'_, PyAny>>,
    progress: Option<Py<PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<HoneycombResult> {
    let kwargs = options.cloned().unwrap_or_else(|| PyDict::new(py));
    let options = self::options(py, &kwargs)?;
    let base = mesh_arg(py, "base", base)?;
    let surface = surface.map(|s| mesh_arg(py, "surface", s)).transpose()?;
    let (base, surface) = py
        .detach(|| -> honeycomb::Result<_> {
            let base = base_of(base)?;
            let surface = match surface {
                Some(s) => surface_of(s)?,
                None => Surface::of_base(&base)?,
            };
            Ok((base, surface))
        })
        .map_err(py_err)?;
    let outcome = run(py, progress, |progress| {
        honeycomb::optimize(&base, &surface, &options, progress)
    })?;
    HoneycombResult::of(py, outcome, Some(&surface))
}

/// Reads a structure directory written by `save` or by the CLI's `optimize` or `pipeline`
/// (`structure.json`, and `report.json` for the verdict) and measures it on `surface`: the
/// one given, else the directory's `surface.obj` (a pipeline's), else its own mesh M.
#[pyfunction]
#[pyo3(signature = (dir, surface=None))]
fn read(
    py: Python<'_>,
    dir: PathBuf,
    surface: Option<&Bound<'_, PyAny>>,
) -> PyResult<HoneycombResult> {
    let surface = surface.map(|s| mesh_arg(py, "surface", s)).transpose()?;
    let (honeycomb, measures, surface) = py
        .detach(|| -> honeycomb::Result<_> {
            let (h, _) = read_structure(&dir)?;
            let kept = dir.join("surface.obj");
            let surface = match surface {
                Some(s) => surface_of(s)?,
                None if kept.is_file() => Surface::read(&kept)?,
                None => Surface::of_base(&BaseMesh::from_mesh(h.base.clone())?)?,
            };
            let measures = measure(&h, &surface);
            Ok((h, measures, design_mesh(&surface)))
        })
        .map_err(py_err)?;
    let path = dir.join("report.json");
    let text = std::fs::read_to_string(&path).map_err(|source| {
        py_err(Error::Io {
            path: path.clone(),
            source,
        })
    })?;
    let report = json_loads(py, &text)?;
    let is_honeycomb = report
        .get_item("honeycomb")
        .and_then(|v| v.extract::<bool>())
        .map_err(|_| PyValueError::new_err(format!("{}: no honeycomb verdict", path.display())))?;
    Ok(HoneycombResult {
        arrays: Arrays::of(py, &honeycomb)?,
        honeycomb,
        surface,
        outcome: None,
        is_honeycomb,
        why: None,
        measures: to_json(py, &measures)?,
        report: report.unbind(),
    })
}

fn json_loads<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

fn to_json<T: serde::Serialize>(py: Python<'_>, value: &T) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(json_loads(py, &text)?.unbind())
}

/// A honeycomb: its meshes as numpy arrays, its measures and report as dicts.
#[pyclass(name = "Result", module = "honeycomb", frozen)]
struct HoneycombResult {
    honeycomb: Honeycomb,
    arrays: Arrays,
    /// The design surface it was made on (`None`: M itself), for `export`.
    surface: Option<PolyMesh>,
    /// What `save` writes; `None` for a structure read back.
    outcome: Option<Outcome>,
    is_honeycomb: bool,
    why: Option<String>,
    measures: Py<PyAny>,
    report: Py<PyAny>,
}

/// S's mesh unless S is the base mesh itself.
fn design_mesh(surface: &Surface) -> Option<PolyMesh> {
    (!surface.is_base()).then(|| surface.source_mesh().clone())
}

impl HoneycombResult {
    fn of(
        py: Python<'_>,
        outcome: Outcome,
        surface: Option<&Surface>,
    ) -> PyResult<HoneycombResult> {
        Ok(HoneycombResult {
            arrays: Arrays::of(py, &outcome.honeycomb)?,
            honeycomb: outcome.honeycomb.clone(),
            surface: surface.and_then(design_mesh),
            is_honeycomb: outcome.is_honeycomb(),
            why: outcome.verdict.why.clone(),
            measures: to_json(py, &outcome.measures)?,
            report: to_json(py, &outcome.report)?,
            outcome: Some(outcome),
        })
    }
}

/// A result's arrays, made once: every access returns the same read-only array.
struct Arrays {
    vertices: Py<PyArray2<f64>>,
    offset_vertices: Py<PyArray2<f64>>,
    edges: Py<PyArray2<i64>>,
    wall_normals: Py<PyArray2<f64>>,
    node_axes: Py<PyArray2<f64>>,
}

impl Arrays {
    fn of(py: Python<'_>, h: &Honeycomb) -> PyResult<Arrays> {
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
fn read_only<T: numpy::Element>(array: Bound<'_, PyArray2<T>>) -> PyResult<Py<PyArray2<T>>> {
    let kw = PyDict::new(array.py());
    kw.set_item("write", false)?;
    array.call_method("setflags", (), Some(&kw))?;
    Ok(array.unbind())
}

/// Points as an (n, 3) float64 array.
fn points_array<'py>(
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

/// A point or direction (x, y, z) from any array-like.
fn point(py: Python<'_>, what: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec3> {
    let np = py.import("numpy")?;
    let p = np
        .call_method1("reshape", (obj, (1, 3)))
        .map_err(|_| PyValueError::new_err(format!("{what}: expected three numbers (x, y, z)")))?;
    Ok(points(py, what, &p)?[0])
}

/// Live editing of a honeycomb (the paper's three modes): each edit re-optimizes (or, for a
/// slide, moves one vertex) and returns the result; with undo and redo.
#[pyclass(name = "EditSession", module = "honeycomb", frozen)]
struct PyEditSession {
    session: Mutex<EditSession>,
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
                design_mesh(&session.workspace().model_surface),
            )
        });
        let is_honeycomb = Report::within_tolerances(&view.measures);
        Ok(HoneycombResult {
            surface,
            is_honeycomb,
            why: (!is_honeycomb).then(|| Report::tolerance_summary(&view.measures, false)),
            measures: to_json(py, &view.measures)?,
            arrays: Arrays::of(py, &view.honeycomb)?,
            honeycomb: view.honeycomb,
            outcome: None,
            report: py.None(),
        })
    }
}

#[pymodule]
#[pyo3(name = "honeycomb")]
fn honeycomb_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(pipeline, m)?)?;
    m.add_function(wrap_pyfunction!(optimize, m)?)?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_class::<HoneycombResult>()?;
    m.add_class::<PyEditSession>()?;
    m.add("Cancelled", m.py().get_type::<Cancelled>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
