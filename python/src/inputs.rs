//! Python values into the front door's types: options, points, polygons, meshes.

use crate::py_err;
use honeycomb::mesh::PolyMesh;
use honeycomb::{BaseMesh, Options, Surface, Vec3};
use numpy::{PyArrayDescrMethods, PyReadonlyArray2, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// Keyword options as [`Options`]: each field deserialized alone first, so that a bad value
/// is named by its field (serde names only unknown fields), then all together.
pub(crate) fn options(py: Python<'_>, kwargs: &Bound<'_, PyDict>) -> PyResult<Options> {
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
pub(crate) fn points(py: Python<'_>, what: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<Vec3>> {
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
pub(crate) fn polygons(
    py: Python<'_>,
    what: &str,
    obj: &Bound<'_, PyAny>,
) -> PyResult<Vec<Vec<usize>>> {
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
pub(crate) enum MeshArg {
    Path(PathBuf),
    Mesh(Vec<Vec3>, Vec<Vec<usize>>),
}

pub(crate) fn mesh_arg(py: Python<'_>, what: &str, obj: &Bound<'_, PyAny>) -> PyResult<MeshArg> {
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

pub(crate) fn surface_of(arg: MeshArg) -> honeycomb::Result<Surface> {
    match arg {
        MeshArg::Path(path) => Surface::read(&path),
        MeshArg::Mesh(vertices, faces) => Surface::new(PolyMesh::new(vertices, faces)),
    }
}

pub(crate) fn base_of(arg: MeshArg) -> honeycomb::Result<BaseMesh> {
    match arg {
        MeshArg::Path(path) => BaseMesh::read(&path),
        MeshArg::Mesh(vertices, cells) => BaseMesh::new(vertices, cells),
    }
}

/// A point or direction (x, y, z) from any array-like.
pub(crate) fn point(py: Python<'_>, what: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec3> {
    let np = py.import("numpy")?;
    let p = np
        .call_method1("reshape", (obj, (1, 3)))
        .map_err(|_| PyValueError::new_err(format!("{what}: expected three numbers (x, y, z)")))?;
    Ok(points(py, what, &p)?[0])
}
