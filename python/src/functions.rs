//! `pipeline`, `optimize` and `read`.

use crate::inputs::{base_of, mesh_arg, surface_of};
use crate::progress::run;
use crate::py_err;
use crate::result::{json_loads, to_json, Arrays, HoneycombResult};
use honeycomb::export::read_structure;
use honeycomb::init::{Align, BoundaryMode, CellSize, Flattener, Method};
use honeycomb::structure::measure;
use honeycomb::{BaseMesh, Error, PipelineOptions, Surface};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// Makes a honeycomb on a design surface from nothing else.
///
/// `surface`: a path (OBJ, OFF, PLY), a `(vertices, faces)` pair or a compas Mesh. `walls`:
/// "across", "uniform", "free" or a direction (x, y, z) for every node axis. `cells`:
/// about this many cells (or `edge_length` in model units); `method`: "flatten" or "field";
/// `flatten`: "arap", "lscm" or "project" (default: the pipeline's choice); `boundary`:
/// "trim" or "keep" the cells S's border cuts; `align`: "boundary", "curvature", "none" or a
/// polyline file of strokes (default: "boundary", "curvature" for zigzag or flattest quads); `seed` shifts the lattice; `even_cells`: None (uneven cells of walls across S evened), True (the same, refused with other walls) or False (the cells as fitted), as `honeycomb pipeline`'s flags. Other keyword arguments are the options of `honeycomb
/// optimize` by their field names (`w_fair` for `--w-fair`). `progress(step: dict)` is
/// called at every step; returning False stops the work (`honeycomb.Cancelled`).
#[pyfunction]
#[pyo3(
    signature = (surface, cells=1500, walls=None, *, edge_length=None, method="flatten", flatten=None, boundary="trim", align=None, seed=0, even_cells=None, progress=None, **options),
    text_signature = "(surface, cells=1500, walls='across', *, edge_length=None, method='flatten', flatten=None, boundary='trim', align=None, seed=0, even_cells=None, progress=None, **options)"
)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn pipeline(
    py: Python<'_>,
    surface: &Bound<'_, PyAny>,
    cells: usize,
    walls: Option<&Bound<'_, PyAny>>,
    edge_length: Option<f64>,
    method: &str,
    flatten: Option<&str>,
    boundary: &str,
    align: Option<&str>,
    seed: u64,
    even_cells: Option<bool>,
    progress: Option<Py<PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<HoneycombResult> {
    let kwargs = options.cloned().unwrap_or_else(|| PyDict::new(py));
    match walls {
        Some(walls) => kwargs.set_item("walls", walls)?,
        None => kwargs.set_item("walls", "across")?,
    }
    let options = crate::inputs::options(py, &kwargs)?;
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
    if let Some(align) = align {
        init.align = Align::parse(align).map_err(py_err)?;
    }
    init.seed = seed;
    pipeline_options.init_chosen = flatten.is_some() || init.method == Method::Field;
    pipeline_options.align_chosen = align.is_some();
    pipeline_options.even_cells = even_cells;
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
pub(crate) fn optimize(
    py: Python<'_>,
    base: &Bound<'_, PyAny>,
    surface: Option<&Bound<'_, PyAny>>,
    progress: Option<Py<PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<HoneycombResult> {
    let kwargs = options.cloned().unwrap_or_else(|| PyDict::new(py));
    let options = crate::inputs::options(py, &kwargs)?;
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
pub(crate) fn read(
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
            Ok((h, measures, surface.design_mesh().cloned()))
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
        unmet: None,
        measures: to_json(py, &measures)?,
        report: report.unbind(),
    })
}
