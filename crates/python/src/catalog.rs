//! `fairspline.Catalog`: the module's catalogue (the built-ins, or a Rust user's), to which a
//! Python user adds strategies and criteria written in Python ([`crate::callables`]) and
//! runs them as the built-ins run: alone, in a config pipeline after a built-in, with the
//! same constraints and the same report.

use std::sync::Arc;

use fairing::catalog::{Catalog, CriterionEntry, MethodInfo, MethodKind};
use fairing::Pipeline as LibraryPipeline;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use serde_json::Value;

use crate::backend;
use crate::callables::{json_type, schema_of, PythonCriterion, PythonMethod, Sink};
use crate::{
    curve_points, options, params_argument, parse_config, raise_kept, run_curve, to_py_error, to_python,
    without_gil, FairedCurve, Pipeline,
};

/// A catalogue of methods and criteria: `Catalog()` starts with the module's (the built-ins,
/// `fairspline.methods()`), and `add_strategy` / `add_criterion` add methods and criteria
/// written in Python. `curve` and `pipeline` run them as the module's functions run the
/// built-ins: the framework applies the constraints (fixed points kept bit for bit, moves
/// clipped to the tolerance band), runs the pipeline and writes the report, whose `criteria`
/// hold every criterion of the catalogue, the Python ones included.
#[pyclass(module = "fairspline", name = "Catalog")]
pub struct PyCatalog {
    catalog: Arc<Catalog>,
    sink: Arc<Sink>,
}

/// A name a method or criterion can be registered under: letters, digits, `-` and `_`.
fn check_name(name: &str, what: &str) -> PyResult<()> {
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
    {
        return Err(PyValueError::new_err(format!(
            "{what}: `{name}` must be letters, digits, `-` or `_`"
        )));
    }
    Ok(())
}

/// The first line of `function`'s docstring, or "".
fn first_doc_line(function: &Bound<'_, PyAny>) -> PyResult<String> {
    let doc = function
        .py()
        .import("inspect")?
        .call_method1("getdoc", (function,))?;
    if doc.is_none() {
        return Ok(String::new());
    }
    Ok(doc
        .extract::<String>()?
        .lines()
        .next()
        .unwrap_or_default()
        .trim()
        .to_owned())
}

/// A dict of parameter names and JSON values (`settings=` and `docs=`).
fn json_map(value: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<serde_json::Map<String, Value>> {
    let mut map = serde_json::Map::new();
    for (name, given) in params_argument(value).map_err(|_| {
        PyTypeError::new_err(format!(
            "{what}: a dict of names and numbers, booleans or strings"
        ))
    })? {
        let value = match given {
            fairing::catalog::GivenValue::Json(v) => v,
            fairing::catalog::GivenValue::Text(t) => Value::String(t),
        };
        map.insert(name, value);
    }
    Ok(map)
}

#[pymethods]
impl PyCatalog {
    /// The module's catalogue: every built-in method and criterion.
    #[new]
    fn new() -> Self {
        PyCatalog {
            catalog: Arc::new(backend::catalog().clone()),
            sink: Arc::new(Sink::default()),
        }
    }

    /// The methods, as `fairspline.methods()` lists them (name, kind, paper, summary,
    /// parameters with default, meaning and JSON Schema), read from the catalogue.
    fn methods(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let list = Value::Array(backend::methods(&self.catalog));
        Ok(to_python(py, &list)?.unbind())
    }

    /// The criteria: a list of dicts with `name` and `summary` (every one is in a report's
    /// `before.criteria` and `after.criteria`).
    fn criteria(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let list: Vec<Value> = self
            .catalog
            .criteria()
            .iter()
            .map(|c| serde_json::json!({"name": c.name(), "summary": c.summary()}))
            .collect();
        Ok(to_python(py, &Value::Array(list))?.unbind())
    }

    /// Adds a curve strategy written in Python (replacing a method of the same name).
    ///
    /// function(points, context) -> proposed points, an (n, d) array, or None when it has
    ///     nothing left to do. `points` is an (n, d) float64 array of the current points;
    ///     `context` has `original` (the points the stage started from), `fixed` (indices of
    ///     the points that may not move: fixed points and clamped ends), `tolerance` (the
    ///     band, or None), `settings` (this run's parameters, a dict), `step` (from 0),
    ///     `kind` ("function" or "parametric") and `name`. The points are in the framework's
    ///     reference frame (centred, scaled by a power of two), and so is `tolerance`.
    ///     Each proposed point goes through the framework's constraints: a frozen point keeps
    ///     its bits, a move is clipped to the tolerance band, and a function's x is kept (its
    ///     y alone moves). The run stops when the
    ///     function returns None, when nothing moved in a step, or after `max_steps` steps.
    /// summary: one line on what it does (default: the first line of its docstring).
    /// settings: its parameters and their defaults, {"name": value} (numbers, booleans,
    ///     strings); `params=` and config stages then set them, checked for their type.
    /// docs: what each parameter means, {"name": "meaning"}.
    /// max_steps: steps at most (default: the library pipeline's limit).
    /// paper: where the method comes from.
    #[pyo3(signature = (name, function, summary=None, settings=None, docs=None, max_steps=None, paper=None))]
    #[allow(clippy::too_many_arguments)]
    fn add_strategy(
        &mut self,
        name: &str,
        function: &Bound<'_, PyAny>,
        summary: Option<String>,
        settings: Option<&Bound<'_, PyAny>>,
        docs: Option<&Bound<'_, PyAny>>,
        max_steps: Option<usize>,
        paper: Option<String>,
    ) -> PyResult<()> {
        check_name(name, "name")?;
        if !function.is_callable() {
            return Err(PyTypeError::new_err(format!(
                "function: strategy `{name}` needs a callable function(points, context)"
            )));
        }
        let defaults = json_map(settings, "settings")?;
        if let Some((key, _)) = defaults.iter().find(|(_, v)| json_type(v).is_none()) {
            return Err(PyValueError::new_err(format!(
                "settings: `{key}` must default to a number, a boolean or a string"
            )));
        }
        let meanings = json_map(docs, "docs")?;
        if let Some(key) = meanings.keys().find(|k| !defaults.contains_key(*k)) {
            return Err(PyValueError::new_err(format!(
                "docs: `{key}` is not one of the settings ({})",
                defaults.keys().cloned().collect::<Vec<_>>().join(", ")
            )));
        }
        let max_steps = max_steps.unwrap_or(LibraryPipeline::<2>::DEFAULT_MAX_ITERATIONS);
        if max_steps == 0 {
            return Err(PyValueError::new_err("max_steps: at least 1"));
        }
        let summary = match summary {
            Some(s) => s,
            None => first_doc_line(function)?,
        };
        let mut info = MethodInfo::new(name, summary);
        if let Some(paper) = paper {
            info = info.with_paper(paper);
        }
        let method = PythonMethod {
            name: name.to_owned(),
            function: Arc::new(function.clone().unbind()),
            defaults: defaults.clone(),
            max_steps,
            sink: self.sink.clone(),
        };
        let schema = schema_of(&defaults, &meanings);
        Arc::make_mut(&mut self.catalog)
            .register_curve_with_schema(info, method, schema, Value::Object(defaults))
            .map_err(|e| PyValueError::new_err(format!("strategy `{name}`: {e}")))?;
        Ok(())
    }

    /// Adds a criterion written in Python (replacing one of the same name): every report's
    /// `before.criteria` and `after.criteria` then hold its value, and methods that take
    /// `criterion=NAME` can use it.
    ///
    /// function(curve) -> a finite number. `curve` has arrays `t` (parameters: every break
    ///     and 15 more inside each piece), `points`, `d1`, `d2`, `d3` ((m, d) each: the
    ///     curve and its derivatives there) and `breaks`.
    /// summary: one line on what it measures (default: its docstring's first line).
    #[pyo3(signature = (name, function, summary=None))]
    fn add_criterion(
        &mut self,
        name: &str,
        function: &Bound<'_, PyAny>,
        summary: Option<String>,
    ) -> PyResult<()> {
        check_name(name, "name")?;
        if !function.is_callable() {
            return Err(PyTypeError::new_err(format!(
                "function: criterion `{name}` needs a callable function(curve)"
            )));
        }
        let summary = match summary {
            Some(s) => s,
            None => first_doc_line(function)?,
        };
        let criterion = PythonCriterion {
            name: name.to_owned(),
            function: Arc::new(function.clone().unbind()),
            sink: self.sink.clone(),
        };
        Arc::make_mut(&mut self.catalog).register_criterion(
            CriterionEntry::new(name, summary)
                .planar(criterion.clone())
                .spatial(criterion),
        );
        Ok(())
    }

    /// Fair a curve with this catalogue's methods: the arguments of `fairspline.curve`.
    #[pyo3(signature = (points, method=None, kind=None, params=None, fixed=None, points_to_fix=None, tolerance=None, clamp_ends=None, closed=false, corners=None))]
    #[allow(clippy::too_many_arguments)]
    fn curve(
        &self,
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
        options.corners = crate::corners_argument(corners)?;
        run_curve(py, &self.catalog, Some(&self.sink), &coordinates, &options)
    }

    /// Measure a curve without changing it, as `fairspline.inspect` does, with this
    /// catalogue's criteria (the Python ones included) in the report's `criteria`.
    #[pyo3(signature = (points, kind=None))]
    fn inspect(
        &self,
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        kind: Option<String>,
    ) -> PyResult<Py<PyAny>> {
        let coordinates = curve_points(points)?;
        let (catalog, sink) = (&self.catalog, &self.sink);
        let (report, kept) = without_gil(py, || {
            let _one_at_a_time = sink.call();
            let report = backend::inspect_curve(catalog, &coordinates, kind.as_deref());
            Ok((report, sink.take()))
        })?;
        raise_kept(py, kept)?;
        Ok(to_python(py, &report.map_err(to_py_error)?)?.unbind())
    }

    /// A pipeline over this catalogue from a config (what `fairspline.pipeline` takes): its
    /// `[[stage]]`s may name built-in and Python methods alike.
    fn pipeline(&self, py: Python<'_>, config: &Bound<'_, PyAny>) -> PyResult<Pipeline> {
        Ok(Pipeline {
            config: parse_config(py, config)?,
            catalog: Some((self.catalog.clone(), self.sink.clone())),
        })
    }

    /// Whether the catalogue has a method or a criterion called `name`.
    fn __contains__(&self, name: &str) -> bool {
        self.catalog.method(MethodKind::Curve, name).is_ok()
            || self.catalog.method(MethodKind::Surface, name).is_ok()
            || self.catalog.criteria().iter().any(|c| c.name() == name)
    }

    fn __repr__(&self) -> String {
        let names: Vec<String> = [MethodKind::Curve, MethodKind::Surface]
            .into_iter()
            .flat_map(|k| self.catalog.methods(k).map(|m| m.name().to_owned()))
            .collect();
        let criteria: Vec<&str> = self.catalog.criteria().iter().map(|c| c.name()).collect();
        format!(
            "Catalog(methods=[{}], criteria=[{}])",
            names.join(", "),
            criteria.join(", ")
        )
    }
}
