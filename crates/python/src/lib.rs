//! Python bindings of the fair framework: the package `fairspline` (its native part,
//! `fairspline._native`).
//!
//! `pip install ./crates/python` builds and installs it (maturin). The functions mirror the
//! command: `curve` is `fair curve`, `surface` is `fair surface`, `inspect` is
//! `fair inspect`, `methods` is `fair methods` and `pipeline` takes the config files
//! `--config` takes. The results are the command's bit for bit: the same faired points and a
//! report dict with exactly the fields of its JSON report.
//!
//! `Catalog` (in `catalog.rs`) holds the same catalogue, to which a Python user adds
//! strategies and criteria written in Python ([`callables`]: the library's own traits,
//! calling back into Python); [`init_module`] builds the module over a Rust user's catalogue.
//!
//! This file only converts between Python and Rust: argument checking that Python alone can
//! do (shapes, dtypes, types of the options), NumPy arrays in and out, errors to exceptions,
//! and the GIL released while the framework runs. Every call into the framework goes through
//! [`backend`].
//!
//! Copies: a C-contiguous float64 array is read in place (one copy into the framework's own
//! point type, made while the GIL is held so that no other thread can change the array
//! underneath); results are handed to NumPy without a copy (the array owns the `Vec`).

pub mod backend;
pub mod callables;
mod catalog;

use std::sync::Arc;

use backend::{Config, Coordinates, Failure, Faired, Options};
use callables::Sink;
use fairing::catalog::{Catalog, GivenValue};
use numpy::ndarray::{Array2, Array3};
use numpy::{
    IntoPyArray, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString};

/// A failure of the framework as a Python exception: `ValueError` for bad input (what the
/// command exits 2 for), `RuntimeError` for a failure of the framework itself.
pub(crate) fn to_py_error(failure: Failure) -> PyErr {
    if failure.bad_input {
        PyValueError::new_err(failure.message)
    } else {
        PyRuntimeError::new_err(failure.message)
    }
}

/// Runs `work` with the GIL released; a panic becomes a `RuntimeError` (never a crash).
pub(crate) fn without_gil<T: Send>(
    py: Python<'_>,
    work: impl FnOnce() -> backend::Result<T> + Send,
) -> PyResult<T> {
    let outcome = py.detach(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(work)));
    match outcome {
        Ok(result) => result.map_err(to_py_error),
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown failure".into());
            Err(PyRuntimeError::new_err(format!("internal error: {message}")))
        }
    }
}

/// An array of float64 values from `value` with its shape, or a `ValueError` naming `what`.
///
/// float64 arrays are read in place when C-contiguous; other real dtypes (integers, float32)
/// are converted by NumPy; anything else (complex, bool, strings, objects, ragged lists) is
/// refused.
pub(crate) fn float_array(value: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<f64>, Vec<usize>)> {
    let py = value.py();
    let numpy = py.import("numpy")?;
    let array = match value.cast::<PyUntypedArray>() {
        Ok(array) => array.clone(),
        Err(_) => numpy
            .call_method1("asarray", (value,))
            .map_err(|e| PyValueError::new_err(format!("{what}: not an array of numbers: {e}")))?
            .cast_into::<PyUntypedArray>()
            .map_err(|e| PyValueError::new_err(format!("{what}: not an array of numbers: {e}")))?,
    };
    let dtype = array.dtype();
    let array = match dtype.kind() {
        b'f' if dtype.is_equiv_to(&numpy::dtype::<f64>(py)) => array,
        b'f' | b'i' | b'u' => array
            .call_method1("astype", ("float64",))?
            .cast_into::<PyUntypedArray>()?,
        _ => {
            return Err(PyValueError::new_err(format!(
                "{what}: the dtype must be real numbers (float64, or a float or integer type NumPy converts), not {}",
                dtype.str()?
            )))
        }
    };
    let array = array.cast::<PyArrayDyn<f64>>()?.readonly();
    let shape = array.shape().to_vec();
    // `as_slice` also accepts Fortran order, whose memory order is not the row order.
    let values = match array.as_slice() {
        Ok(slice) if array.is_c_contiguous() => slice.to_vec(),
        _ => array.as_array().iter().copied().collect(),
    };
    Ok((values, shape))
}

/// Curve points: an `(n, 2)` or `(n, 3)` array.
pub(crate) fn curve_points(value: &Bound<'_, PyAny>) -> PyResult<Coordinates> {
    let (values, shape) = float_array(value, backend::POINTS)?;
    match shape.as_slice() {
        [_, d @ (2 | 3)] => Ok(Coordinates {
            dimension: *d,
            values,
        }),
        _ => Err(PyValueError::new_err(format!(
            "{}: a curve is an (n, 2) or (n, 3) array, got shape {}",
            backend::POINTS,
            shape_text(&shape)
        ))),
    }
}

/// A surface grid: an `(m, n, 3)` array; returns the points and (m, n).
fn grid_points(value: &Bound<'_, PyAny>) -> PyResult<(Coordinates, usize, usize)> {
    let (values, shape) = float_array(value, backend::GRID)?;
    match shape.as_slice() {
        [m, n, 3] => Ok((Coordinates { dimension: 3, values }, *m, *n)),
        _ => Err(PyValueError::new_err(format!(
            "{}: a surface grid is an (m, n, 3) array, got shape {}",
            backend::GRID,
            shape_text(&shape)
        ))),
    }
}

pub(crate) fn shape_text(shape: &[usize]) -> String {
    match shape {
        [one] => format!("({one},)"),
        _ => format!(
            "({})",
            shape.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")
        ),
    }
}

/// `params=`: a dict of parameter names and values: numbers and booleans as the JSON values
/// they are, strings as text (what `--set NAME=VALUE` carries, which the catalogue reads
/// against the parameter's schema).
pub(crate) fn params_argument(params: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<(String, GivenValue)>> {
    let Some(params) = params.filter(|p| !p.is_none()) else {
        return Ok(Vec::new());
    };
    let dict = params
        .cast::<PyDict>()
        .map_err(|_| PyTypeError::new_err("params: a dict of parameter names and values"))?;
    let number = |x: f64| match serde_json::Number::from_f64(x) {
        Some(n) => GivenValue::Json(serde_json::Value::Number(n)),
        // NaN and infinities have no JSON value: the catalogue refuses their text by name.
        None => GivenValue::Text(format!("{x:?}")),
    };
    let mut out = Vec::with_capacity(dict.len());
    for (key, value) in dict.iter() {
        let name: String = key
            .extract()
            .map_err(|_| PyTypeError::new_err("params: parameter names are strings"))?;
        let given = if value.is_instance_of::<PyBool>() {
            GivenValue::Json(serde_json::Value::Bool(value.extract::<bool>()?))
        } else if value.is_instance_of::<PyInt>() {
            match value.extract::<i64>() {
                Ok(i) => GivenValue::Json(serde_json::Value::from(i)),
                Err(_) => GivenValue::Text(value.str()?.to_string()),
            }
        } else if value.is_instance_of::<PyFloat>() {
            number(value.extract::<f64>()?)
        } else if value.is_instance_of::<PyString>() {
            GivenValue::Text(value.extract::<String>()?)
        } else if let Ok(x) = value.extract::<f64>() {
            // NumPy scalars and other numbers.
            number(x)
        } else {
            return Err(PyValueError::new_err(format!(
                "params: `{name}` must be a number, a boolean or a string, not {}",
                value.get_type().name()?
            )));
        };
        out.push((name, given));
    }
    Ok(out)
}

/// `fixed=`/`points_to_fix=`: point indices from 0; for a grid of `columns` columns an index
/// may also be a pair (i, j).
fn indices_argument(
    value: Option<&Bound<'_, PyAny>>,
    what: &str,
    columns: Option<usize>,
) -> PyResult<Option<Vec<usize>>> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(None);
    };
    let items = value
        .try_iter()
        .map_err(|_| PyTypeError::new_err(format!("{what}: a sequence of point indices")))?;
    let mut out = Vec::new();
    for item in items {
        let item = item?;
        if let Ok(index) = item.extract::<i64>() {
            out.push(non_negative(index, what)?);
            continue;
        }
        match (columns, item.extract::<(i64, i64)>()) {
            (Some(columns), Ok((i, j))) => {
                let (i, j) = (non_negative(i, what)?, non_negative(j, what)?);
                if j >= columns {
                    return Err(PyValueError::new_err(format!(
                        "{what}: column j = {j} of ({i}, {j}) is past the last column ({columns} columns)"
                    )));
                }
                out.push(i * columns + j);
            }
            _ => {
                let expected = if columns.is_some() {
                    "point indices k = i * columns + j or pairs (i, j)"
                } else {
                    "point indices (integers from 0)"
                };
                return Err(PyValueError::new_err(format!(
                    "{what}: {} is not an index; expected {expected}",
                    item.repr()?
                )));
            }
        }
    }
    Ok(Some(out))
}

fn non_negative(index: i64, what: &str) -> PyResult<usize> {
    usize::try_from(index).map_err(|_| PyValueError::new_err(format!("{what}: index {index} is negative")))
}

/// A serde_json value as the Python object `json.loads` would make of its text.
pub(crate) fn to_python<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    use serde_json::Value;
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Number(n) => {
            if let Some(i) = n.as_i64() {
                i.into_pyobject(py)?.into_any()
            } else if let Some(u) = n.as_u64() {
                u.into_pyobject(py)?.into_any()
            } else {
                n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any()
            }
        }
        Value::String(s) => PyString::new(py, s).into_any(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(to_python(py, item)?)?;
            }
            list.into_any()
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (k, v) in map {
                dict.set_item(k, to_python(py, v)?)?;
            }
            dict.into_any()
        }
    })
}

/// A faired curve: `points`, an (n, d) float64 array, and `report`, the command's JSON report
/// as a dict.
#[pyclass(frozen, module = "fairspline", name = "FairedCurve")]
pub struct FairedCurve {
    points: Py<PyAny>,
    report: Py<PyAny>,
    /// The report's `curve` and `kind`, for `export_cad`.
    record: serde_json::Value,
    kind: Option<String>,
}

#[pymethods]
impl FairedCurve {
    /// The faired points, an (n, d) float64 array (same count and order as given).
    #[getter]
    fn points(&self, py: Python<'_>) -> Py<PyAny> {
        self.points.clone_ref(py)
    }

    /// The report: a dict with exactly the fields of `fair curve --report`.
    #[getter]
    fn report(&self, py: Python<'_>) -> Py<PyAny> {
        self.report.clone_ref(py)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let report = self.report.bind(py);
        Ok(format!(
            "FairedCurve(method={}, n={}, iterations={}, s_d={}, m_d={})",
            report.get_item("method")?.repr()?,
            report.get_item("n")?,
            report.get_item("iterations")?,
            report.get_item("s_d")?,
            report.get_item("m_d")?
        ))
    }
}

/// A faired surface: `grid`, an (m, n, 3) float64 array, and `report`, the command's JSON
/// report as a dict.
#[pyclass(frozen, module = "fairspline", name = "FairedSurface")]
pub struct FairedSurface {
    grid: Py<PyAny>,
    report: Py<PyAny>,
    /// The report's `curve` (the bicubic surface), for `export_cad`.
    record: serde_json::Value,
}

#[pymethods]
impl FairedSurface {
    /// The faired grid, an (m, n, 3) float64 array.
    #[getter]
    fn grid(&self, py: Python<'_>) -> Py<PyAny> {
        self.grid.clone_ref(py)
    }

    /// The report: a dict with exactly the fields of `fair surface --report`.
    #[getter]
    fn report(&self, py: Python<'_>) -> Py<PyAny> {
        self.report.clone_ref(py)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let report = self.report.bind(py);
        Ok(format!(
            "FairedSurface(method={}, n={}, iterations={}, s_d={}, m_d={})",
            report.get_item("method")?.repr()?,
            report.get_item("n")?,
            report.get_item("iterations")?,
            report.get_item("s_d")?,
            report.get_item("m_d")?
        ))
    }
}

pub(crate) fn faired_curve(py: Python<'_>, faired: Faired) -> PyResult<FairedCurve> {
    let Coordinates { dimension, values } = faired.points;
    let rows = values.len() / dimension;
    let array = Array2::from_shape_vec((rows, dimension), values)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error: {e}")))?
        .into_pyarray(py);
    Ok(FairedCurve {
        points: array.into_any().unbind(),
        report: to_python(py, &faired.report)?.unbind(),
        record: faired.report["curve"].clone(),
        kind: faired.report["kind"].as_str().map(str::to_owned),
    })
}

fn faired_surface(py: Python<'_>, faired: Faired, rows: usize, columns: usize) -> PyResult<FairedSurface> {
    let array = Array3::from_shape_vec((rows, columns, 3), faired.points.values)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error: {e}")))?
        .into_pyarray(py);
    Ok(FairedSurface {
        grid: array.into_any().unbind(),
        report: to_python(py, &faired.report)?.unbind(),
        record: faired.report["curve"].clone(),
    })
}

/// The options shared by curves and surfaces, checked for their Python types.
#[allow(clippy::too_many_arguments)]
pub(crate) fn options(
    method: Option<String>,
    kind: Option<String>,
    params: Option<&Bound<'_, PyAny>>,
    fixed: Option<&Bound<'_, PyAny>>,
    points_to_fix: Option<&Bound<'_, PyAny>>,
    tolerance: Option<f64>,
    clamp_ends: Option<String>,
    closed: bool,
    columns: Option<usize>,
) -> PyResult<Options> {
    Ok(Options {
        method,
        kind,
        params: params_argument(params)?,
        fixed: indices_argument(fixed, "fixed", columns)?,
        bad_points: indices_argument(points_to_fix, "points_to_fix", columns)?,
        tolerance,
        clamp_ends,
        config: None,
        closed,
        corners: None,
    })
}

/// `corners=`: `None` or `"auto"` (detected), `"none"`, or a sequence of point indices.
pub(crate) fn corners_argument(
    value: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<fairing::corners::Corners>> {
    use fairing::corners::Corners;
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(None);
    };
    if let Ok(text) = value.extract::<String>() {
        return Corners::named(&text).map(Some).ok_or_else(|| {
            PyValueError::new_err(format!(
                "corners: `{text}` is not auto, none or a sequence of point indices"
            ))
        });
    }
    Ok(indices_argument(Some(value), "corners", None)?.map(Corners::At))
}

/// Fair a curve, as `fair curve` does.
///
/// points: an (n, 2) or (n, 3) array of float64 (other real dtypes are converted).
/// method: a curve method of `fairspline.methods()`; default jump-lsq.
/// kind: "function", "parametric" or "auto" (None): a function when x increases strictly.
/// params: the method's parameters, {"name": value} (what `--set name=value` takes).
/// fixed: indices of points that must not move.
/// points_to_fix: indices of the bad points, for the interactive methods (`--points`).
/// tolerance: no point moves farther than this.
/// clamp_ends: "g0" (end points), "g1" (and tangents), "g2" (and curvatures).
/// corners: "auto" (None: detected), "none", or indices of points kept as corners (G0 breaks;
///     each piece between two corners is faired alone), as `--corners`.
/// closed: the points are a closed loop (the last joins the first). Methods with a `closed`
///     parameter (two-phase) get closed=true; the others get the loop as the command takes a
///     closed curve, its first point repeated at the end (the report, the command's for that
///     input, counts the repeat in `n`; the returned points do not repeat it).
///
/// Returns a FairedCurve with `.points` (n, d) and `.report` (the command's JSON report).
/// Raises ValueError for bad input (the command's message), RuntimeError if the framework
/// itself fails. The GIL is released while the curve is faired.
#[pyfunction]
#[pyo3(signature = (points, method=None, kind=None, params=None, fixed=None, points_to_fix=None, tolerance=None, clamp_ends=None, closed=false, corners=None))]
#[allow(clippy::too_many_arguments)]
fn curve(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    method: Option<String>,
    kind: Option<String>,
    params: Option<&Bound<'_, PyAny>>,
    fixed: Option<&Bound<'_, PyAny>>,
    points_to_fix: Option<&Bound<'_, PyAny>>,
    tolerance: Option<f64>,
    clamp_ends: Option<String>,
    closed: bool,
    corners: Option<&Bound<'_, PyAny>>,
) -> PyResult<FairedCurve> {
    let coordinates = curve_points(points)?;
    let mut options = options(
        method,
        kind,
        params,
        fixed,
        points_to_fix,
        tolerance,
        clamp_ends,
        closed,
        None,
    )?;
    options.corners = corners_argument(corners)?;
    run_curve(py, backend::catalog(), None, &coordinates, &options)
}

/// Fairs `coordinates` with `catalog`'s methods. With a `sink` (a `Catalog` that holds Python
/// methods), the calls of that catalogue run one at a time, and an exception a Python
/// callable raised during the run is raised here, as the `__cause__` of a RuntimeError whose
/// message names the strategy or criterion.
pub(crate) fn run_curve(
    py: Python<'_>,
    catalog: &Catalog,
    sink: Option<&Arc<Sink>>,
    coordinates: &Coordinates,
    options: &Options,
) -> PyResult<FairedCurve> {
    let (faired, kept) = without_gil(py, || {
        let _one_at_a_time = sink.map(|s| s.call());
        let faired = backend::fair_curve(catalog, coordinates, options);
        Ok((faired, sink.and_then(|s| s.take())))
    })?;
    raise_kept(py, kept)?;
    faired_curve(py, faired.map_err(to_py_error)?)
}

/// The first exception a Python callable raised during a call (taken from its catalogue's
/// sink before the next call can run), as the `__cause__` of a RuntimeError naming the
/// strategy or criterion.
pub(crate) fn raise_kept(py: Python<'_>, kept: Option<(String, PyErr)>) -> PyResult<()> {
    match kept {
        Some((line, error)) => {
            let raised = PyRuntimeError::new_err(line);
            raised.set_cause(py, Some(error));
            Err(raised)
        }
        None => Ok(()),
    }
}

/// Fair a surface grid, as `fair surface` does.
///
/// grid: an (m, n, 3) array of float64, grid[i, j] = P_ij.
/// method: a surface method of `fairspline.methods()`; default jump-lsq.
/// params: the method's parameters, {"name": value}.
/// fixed, points_to_fix: grid points, as indices k = i * n + j or pairs (i, j).
/// tolerance: no point moves farther than this.
/// clamp_ends: "g0" keeps the grid's boundary (g1 and g2 are refused).
///
/// Returns a FairedSurface with `.grid` (m, n, 3) and `.report`.
#[pyfunction]
#[pyo3(signature = (grid, method=None, params=None, fixed=None, points_to_fix=None, tolerance=None, clamp_ends=None))]
#[allow(clippy::too_many_arguments)]
fn surface(
    py: Python<'_>,
    grid: &Bound<'_, PyAny>,
    method: Option<String>,
    params: Option<&Bound<'_, PyAny>>,
    fixed: Option<&Bound<'_, PyAny>>,
    points_to_fix: Option<&Bound<'_, PyAny>>,
    tolerance: Option<f64>,
    clamp_ends: Option<String>,
) -> PyResult<FairedSurface> {
    let (coordinates, rows, columns) = grid_points(grid)?;
    let options = options(
        method,
        None,
        params,
        fixed,
        points_to_fix,
        tolerance,
        clamp_ends,
        false,
        Some(columns),
    )?;
    let faired = without_gil(py, || {
        backend::fair_surface(backend::catalog(), &coordinates, rows, columns, &options)
    })?;
    faired_surface(py, faired, rows, columns)
}

/// Measure a curve or a surface without changing it, as `fair inspect` does.
///
/// points: an (n, 2)/(n, 3) curve, or an (m, n, 3) grid (a surface).
/// kind: for curves, "function", "parametric" or "auto" (None).
///
/// Returns the report dict (method "inspect", `after` equal to `before`, nothing moved).
#[pyfunction]
#[pyo3(signature = (points, kind=None))]
fn inspect(py: Python<'_>, points: &Bound<'_, PyAny>, kind: Option<String>) -> PyResult<Py<PyAny>> {
    let (values, shape) = float_array(points, backend::POINTS)?;
    let report = match shape.as_slice() {
        [_, d @ (2 | 3)] => {
            let coordinates = Coordinates {
                dimension: *d,
                values,
            };
            without_gil(py, || {
                backend::inspect_curve(backend::catalog(), &coordinates, kind.as_deref())
            })?
        }
        [m, n, 3] => {
            if kind.as_deref().is_some_and(|k| k != "auto") {
                return Err(PyValueError::new_err(
                    "kind: the input is a surface grid; kind is for curves",
                ));
            }
            let (m, n) = (*m, *n);
            let coordinates = Coordinates { dimension: 3, values };
            without_gil(py, || backend::inspect_surface(&coordinates, m, n))?
        }
        _ => {
            return Err(PyValueError::new_err(format!(
            "{}: a curve is an (n, 2) or (n, 3) array and a surface grid an (m, n, 3) array, got shape {}",
            backend::POINTS,
            shape_text(&shape)
        )))
        }
    };
    Ok(to_python(py, &report)?.unbind())
}

/// Fairs a ship's table of offsets as one hull, as `fair lines TABLE` does: returns
/// `(report, values)`, the lines report as a dict (the command's `--report`) and the faired
/// offsets as an (n, 3) array of x, half-breadth, height, one row per offset in the report's
/// order. The numerics are `fair_lines`'s; a bad table or setting raises ValueError naming the
/// file and line, a failed fit RuntimeError.
#[pyfunction]
#[pyo3(signature = (path, step=None, tolerance=None, knuckles=None))]
fn lines(
    py: Python<'_>,
    path: std::path::PathBuf,
    step: Option<f64>,
    tolerance: Option<f64>,
    knuckles: Option<Vec<String>>,
) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
    let settings = fair_lines::Settings {
        step,
        tolerance,
        knuckles,
    };
    let outcome = py.detach(|| {
        fair_lines::read_table(&path)
            .and_then(|table| fair_lines::fair(&table, &settings))
            .map(|faired| (fair_lines::write::report_json(&faired), faired.values))
    });
    let (report, values) = outcome.map_err(|e| match e {
        fair_lines::Error::Fit(_) | fair_lines::Error::Cad(_) => PyRuntimeError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    })?;
    let report: serde_json::Value =
        serde_json::from_str(&report).map_err(|e| PyRuntimeError::new_err(format!("internal error: {e}")))?;
    let n = values.len();
    let array = Array2::from_shape_vec((n, 3), values.into_iter().flatten().collect())
        .map_err(|e| PyRuntimeError::new_err(format!("internal error: {e}")))?
        .into_pyarray(py);
    Ok((to_python(py, &report)?.unbind(), array.into_any().unbind()))
}

/// The catalogue of methods, as `fair methods` lists them: a list of dicts with `name`,
/// `kind` ("curve" or "surface"), `paper`, `summary` and `parameters` (each a dict with
/// `name`, `default` as text and `meaning`).
#[pyfunction]
fn methods(py: Python<'_>) -> PyResult<Py<PyAny>> {
    let list = serde_json::Value::Array(backend::methods(backend::catalog()));
    Ok(to_python(py, &list)?.unbind())
}

/// A pipeline from a config, as `fair curve --config FILE` takes it: method parameters (top
/// level or in a table named after the method), `[constraints]` and `[[stage]]`s.
///
/// Build it with `fairspline.pipeline(config)`; call `.curve(points, ...)` (or the pipeline itself)
/// and `.surface(grid, ...)`. Arguments given to the call win over the config's
/// `[constraints]`, as the command line wins over the file.
#[pyclass(frozen, module = "fairspline", name = "Pipeline")]
pub struct Pipeline {
    config: Config,
    /// The `Catalog` object it was made by (its catalogue and sink); `None` for the module's.
    catalog: Option<(Arc<Catalog>, Arc<Sink>)>,
}

#[pymethods]
impl Pipeline {
    /// Fair a curve with this config. Same arguments as `fairspline.curve` but the method and
    /// parameters, which come from the config.
    #[pyo3(signature = (points, kind=None, fixed=None, points_to_fix=None, tolerance=None, clamp_ends=None, closed=false))]
    #[allow(clippy::too_many_arguments)]
    fn curve(
        &self,
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        kind: Option<String>,
        fixed: Option<&Bound<'_, PyAny>>,
        points_to_fix: Option<&Bound<'_, PyAny>>,
        tolerance: Option<f64>,
        clamp_ends: Option<String>,
        closed: bool,
    ) -> PyResult<FairedCurve> {
        let coordinates = curve_points(points)?;
        let mut options = options(
            None,
            kind,
            None,
            fixed,
            points_to_fix,
            tolerance,
            clamp_ends,
            closed,
            None,
        )?;
        options.config = Some(self.config.clone());
        match &self.catalog {
            Some((catalog, sink)) => run_curve(py, catalog, Some(sink), &coordinates, &options),
            None => run_curve(py, backend::catalog(), None, &coordinates, &options),
        }
    }

    /// Same as `.curve(...)`.
    #[pyo3(signature = (points, kind=None, fixed=None, points_to_fix=None, tolerance=None, clamp_ends=None, closed=false))]
    #[allow(clippy::too_many_arguments)]
    fn __call__(
        &self,
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        kind: Option<String>,
        fixed: Option<&Bound<'_, PyAny>>,
        points_to_fix: Option<&Bound<'_, PyAny>>,
        tolerance: Option<f64>,
        clamp_ends: Option<String>,
        closed: bool,
    ) -> PyResult<FairedCurve> {
        self.curve(
            py,
            points,
            kind,
            fixed,
            points_to_fix,
            tolerance,
            clamp_ends,
            closed,
        )
    }

    /// Fair a surface grid with this config (one method; `[[stage]]`s are for curves).
    #[pyo3(signature = (grid, fixed=None, points_to_fix=None, tolerance=None, clamp_ends=None))]
    fn surface(
        &self,
        py: Python<'_>,
        grid: &Bound<'_, PyAny>,
        fixed: Option<&Bound<'_, PyAny>>,
        points_to_fix: Option<&Bound<'_, PyAny>>,
        tolerance: Option<f64>,
        clamp_ends: Option<String>,
    ) -> PyResult<FairedSurface> {
        let (coordinates, rows, columns) = grid_points(grid)?;
        let mut options = options(
            None,
            None,
            None,
            fixed,
            points_to_fix,
            tolerance,
            clamp_ends,
            false,
            Some(columns),
        )?;
        options.config = Some(self.config.clone());
        let catalog = self.catalog.as_ref().map_or(backend::catalog(), |(c, _)| &**c);
        let faired = without_gil(py, || {
            backend::fair_surface(catalog, &coordinates, rows, columns, &options)
        })?;
        faired_surface(py, faired, rows, columns)
    }

    fn __repr__(&self) -> String {
        format!("Pipeline({:?})", self.config.name())
    }
}

/// A pipeline from a config, as `fair curve --config` takes it.
///
/// config: a dict (the JSON form of the config), a str of TOML (or JSON) text, or a path
///     (os.PathLike) to a .toml or .json file.
///
/// Returns a Pipeline; `fairspline.pipeline(c).curve(points)` is `fair curve FILE --config c`.
#[pyfunction]
fn pipeline(py: Python<'_>, config: &Bound<'_, PyAny>) -> PyResult<Pipeline> {
    Ok(Pipeline {
        config: parse_config(py, config)?,
        catalog: None,
    })
}

/// A config from a dict, TOML text or a path (see [`pipeline`]).
pub(crate) fn parse_config(py: Python<'_>, config: &Bound<'_, PyAny>) -> PyResult<Config> {
    let os = py.import("os")?;
    let parsed = if config.is_instance_of::<PyDict>() {
        let text: String = py
            .import("json")?
            .call_method1("dumps", (config,))
            .map_err(|e| PyValueError::new_err(format!("config: the dict is not JSON: {e}")))?
            .extract()?;
        Config::parse("config.json", &text)
    } else if config.is_instance_of::<PyString>() {
        Config::parse("config", &config.extract::<String>()?)
    } else if config.is_instance(&os.getattr("PathLike")?)? {
        let path: String = os.call_method1("fspath", (config,))?.extract()?;
        Config::read(&path)
    } else {
        return Err(PyTypeError::new_err(
            "config: a dict, a str of TOML text, or a path to a .toml or .json file",
        ));
    };
    parsed.map_err(to_py_error)
}

/// The default methods: {"function": ..., "parametric": ..., "surface": ...}.
#[pyfunction]
fn default_methods(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let dict = PyDict::new(py);
    for (kind, name) in backend::default_methods() {
        dict.set_item(kind, name)?;
    }
    Ok(dict)
}

/// Write a faired result (or points as they are) as an exact B-spline into a CAD file, as
/// `fair curve -o FILE.igs` does.
///
/// result: a FairedCurve or FairedSurface (its method's own curve or surface is written), or
///     an (n, 2)/(n, 3) curve or (m, n, 3) grid taken as already faired (written as the
///     interpolating spline the report measures).
/// path: the file; its extension (.igs/.iges, .step/.stp, .dxf) chooses the format unless
///     `format` is given.
/// format: "iges", "step" or "dxf" (DXF holds curves only).
/// control_points, fit_tolerance: rebuild a curve with N control points, or with the fewest
///     within that distance of every faired point (least squares; not for surfaces).
/// kind: for points, "function", "parametric" or "auto" (None); a result keeps its own.
///
/// Returns the report's `cad` dict (format, file, representation, exact, control_points,
/// max_deviation, the curvature counts of the faired and the written curve, wiggles_back).
/// Raises ValueError for a bad combination (the command's message, naming the argument).
#[pyfunction]
#[pyo3(signature = (result, path, format=None, control_points=None, fit_tolerance=None, kind=None))]
fn export_cad(
    py: Python<'_>,
    result: &Bound<'_, PyAny>,
    path: std::path::PathBuf,
    format: Option<String>,
    control_points: Option<usize>,
    fit_tolerance: Option<f64>,
    kind: Option<String>,
) -> PyResult<Py<PyAny>> {
    let request = backend::CadRequest {
        path: path.display().to_string(),
        format,
        control_points,
        fit_tolerance,
    };
    let summary = if let Ok(curve) = result.cast::<FairedCurve>() {
        let curve = curve.get();
        if kind.is_some() {
            return Err(PyValueError::new_err(
                "kind: a faired result keeps the kind it was faired as; give kind= with points only",
            ));
        }
        let coordinates = curve_points(curve.points.bind(py))?;
        let (record, kind) = (curve.record.clone(), curve.kind.clone());
        without_gil(py, || {
            backend::export_cad_curve(&coordinates, &record, kind.as_deref(), &request)
        })?
    } else if let Ok(surface) = result.cast::<FairedSurface>() {
        let surface = surface.get();
        let (coordinates, rows, columns) = grid_points(surface.grid.bind(py))?;
        let record = surface.record.clone();
        without_gil(py, || {
            backend::export_cad_surface(&coordinates, rows, columns, &record, &request)
        })?
    } else {
        let (_, shape) = float_array(result, backend::POINTS)?;
        let null = serde_json::Value::Null;
        if shape.len() == 3 {
            let (coordinates, rows, columns) = grid_points(result)?;
            without_gil(py, || {
                backend::export_cad_surface(&coordinates, rows, columns, &null, &request)
            })?
        } else {
            let coordinates = curve_points(result)?;
            without_gil(py, || {
                backend::export_cad_curve(&coordinates, &null, kind.as_deref(), &request)
            })?
        }
    };
    Ok(to_python(py, &summary)?.unbind())
}

/// Read an IGES, STEP or DXF file (ours, OpenCASCADE's, ezdxf's).
///
/// path: the file; format: "iges", "step" or "dxf" (None: by the extension).
///
/// Returns a dict: "units", "tolerance", "curves" (each "name", "degree", "knots",
/// "control_points" [[x, y, z], …], "weights") and "surfaces" (each "name", "degrees",
/// "u_knots", "v_knots", "control_points" rows of [x, y, z], "weights" rows), every number
/// as written (the round trip is exact).
#[pyfunction]
#[pyo3(signature = (path, format=None))]
fn read_cad(py: Python<'_>, path: std::path::PathBuf, format: Option<String>) -> PyResult<Py<PyAny>> {
    let path = path.display().to_string();
    let model = without_gil(py, || backend::read_cad(&path, format.as_deref()))?;
    Ok(to_python(py, &model)?.unbind())
}

/// Fills `module` (a package's native module) with the package's functions and classes, over
/// the catalogue `make()` makes: the module's functions, `methods()` and `Catalog()` then
/// have the methods and criteria of that catalogue. The package's own module is this over
/// [`Catalog::builtin`]; a Rust user's crate exposes its own methods to Python by calling it
/// from its own `#[pymodule]` with its catalogue's constructor (docs/python.md, "A Rust
/// catalogue in Python").
///
/// The first call of a process decides the catalogue (one extension module per process).
pub fn init_module(module: &Bound<'_, PyModule>, make: fn() -> Catalog) -> PyResult<()> {
    backend::install(make);
    module.add_function(wrap_pyfunction!(curve, module)?)?;
    module.add_function(wrap_pyfunction!(surface, module)?)?;
    module.add_function(wrap_pyfunction!(inspect, module)?)?;
    module.add_function(wrap_pyfunction!(lines, module)?)?;
    module.add_function(wrap_pyfunction!(methods, module)?)?;
    module.add_function(wrap_pyfunction!(pipeline, module)?)?;
    module.add_function(wrap_pyfunction!(default_methods, module)?)?;
    module.add_function(wrap_pyfunction!(export_cad, module)?)?;
    module.add_function(wrap_pyfunction!(read_cad, module)?)?;
    module.add_class::<FairedCurve>()?;
    module.add_class::<FairedSurface>()?;
    module.add_class::<Pipeline>()?;
    module.add_class::<catalog::PyCatalog>()?;
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

/// The native module `fairspline._native` over the built-in catalogue; `fairspline`
/// re-exports it. Behind the default feature `module`, so that a Rust user's crate that
/// builds its own module with [`init_module`] (without default features) exports no second
/// module.
#[cfg(feature = "module")]
#[pymodule]
#[pyo3(name = "_native")]
fn fair_python(module: &Bound<'_, PyModule>) -> PyResult<()> {
    init_module(module, Catalog::builtin)
}
