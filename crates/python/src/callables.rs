//! Methods and criteria written in Python, as the library's own traits: a Python strategy is
//! a [`CurveMethod`] whose [`FairingStrategy`] asks a Python callable for proposed points at
//! every step, and a Python criterion is a [`fairness::Criterion`] that hands a sampled curve
//! to a Python callable. The framework keeps its part: each proposed point goes through
//! [`FairingState::move_point`] (fixed points and clamped ends keep their bits, a move is
//! clipped to the tolerance band), the pipeline runs the steps, and the catalogue checks the
//! result and writes the report.
//!
//! The framework runs with the GIL released; each call into Python takes it for the call
//! only ([`Python::attach`]). An exception raised by a callable fails the run with
//! [`Error::Strategy`] naming the strategy (or is kept for a criterion, whose value is then
//! missing), and the exception itself is left in the [`Sink`] so that the binding raises it,
//! with its traceback, once the run is back in Python.

use std::sync::{Arc, Mutex, MutexGuard};

use curve_repr::{Curve, Side, Vector};
use fairing::catalog::{run_strategy, CurveJob, CurveKind, CurveMethod, CurvePoints, CurveRun, Settings};
use fairing::{Error, FairingState, FairingStrategy, Result, StepOutcome};
use numpy::ndarray::{Array1, Array2};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;

/// The exceptions Python callables raised during one call of the binding, each with a line
/// naming the strategy or criterion, and the lock that makes the calls of one catalogue with
/// Python methods run one at a time (they need the GIL at every step anyway).
#[derive(Default)]
pub struct Sink {
    errors: Mutex<Vec<(String, PyErr)>>,
    calls: Mutex<()>,
}

impl Sink {
    /// Keeps `error`, raised by the callable `what` names.
    fn keep(&self, what: String, error: PyErr) {
        self.errors
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push((what, error));
    }

    /// The first exception kept since the last call, and forgets the others. Called with the
    /// call's lock still held, so that it takes the exceptions of its own call only.
    pub fn take(&self) -> Option<(String, PyErr)> {
        let mut errors = self.errors.lock().unwrap_or_else(|e| e.into_inner());
        let first = (!errors.is_empty()).then(|| errors.remove(0));
        errors.clear();
        first
    }

    /// Held for the length of one call of the binding (taken with the GIL released).
    pub fn call(&self) -> MutexGuard<'_, ()> {
        self.calls.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The settings of a Python strategy: the parameters it was registered with, by name, as
/// JSON values. Their schema is made at registration ([`schema_of`]); the catalogue converts,
/// checks names and fills defaults from it, and [`PythonMethod::check`] checks the types.
#[derive(
    Debug,
    Clone,
    Default,
    PartialEq,
    fairing::serde::Serialize,
    fairing::serde::Deserialize,
    fairing::schemars::JsonSchema,
)]
#[serde(crate = "fairing::serde", transparent)]
#[schemars(crate = "fairing::schemars")]
pub struct PythonSettings(pub serde_json::Map<String, Value>);

impl Settings for PythonSettings {}

/// The JSON type a default's value has, for the schema: `number`, `integer`, `boolean` or
/// `string`; `None` for anything else (lists, dicts, None), which a parameter cannot be.
pub fn json_type(value: &Value) -> Option<&'static str> {
    match value {
        Value::Bool(_) => Some("boolean"),
        Value::Number(n) if n.is_i64() || n.is_u64() => Some("integer"),
        Value::Number(_) => Some("number"),
        Value::String(_) => Some("string"),
        _ => None,
    }
}

/// The settings schema of a Python strategy's parameters: each default's JSON type, its
/// meaning and its default.
pub fn schema_of(
    defaults: &serde_json::Map<String, Value>,
    meanings: &serde_json::Map<String, Value>,
) -> Value {
    let properties: serde_json::Map<String, Value> = defaults
        .iter()
        .map(|(name, value)| {
            let mut property = serde_json::json!({
                "type": json_type(value).unwrap_or("string"),
                "default": value,
            });
            if let Some(meaning) = meanings.get(name).and_then(Value::as_str) {
                property["description"] = Value::String(meaning.to_owned());
            }
            (name.clone(), property)
        })
        .collect();
    serde_json::json!({
        "title": "PythonSettings",
        "type": "object",
        "properties": properties,
    })
}

/// A strategy written in Python: the callable, its parameters' types and the step limit.
pub struct PythonMethod {
    /// The name it is registered under.
    pub name: String,
    /// `function(points, context)` → proposed points, or None when it has nothing to do.
    pub function: Arc<Py<PyAny>>,
    /// The defaults it was registered with (their JSON types are the parameters' types).
    pub defaults: serde_json::Map<String, Value>,
    /// Steps at most (calls of the function).
    pub max_steps: usize,
    /// Where its exceptions go.
    pub sink: Arc<Sink>,
}

impl CurveMethod for PythonMethod {
    type Settings = PythonSettings;

    /// Each parameter's value has its default's type (an integer is a number too).
    fn check(&self, settings: &PythonSettings, _: &CurveJob) -> Result<()> {
        for (name, default) in &self.defaults {
            let Some(value) = settings.0.get(name) else {
                continue;
            };
            let expected = json_type(default);
            let fits = match (expected, json_type(value)) {
                (Some("number"), Some("integer")) => true,
                (a, b) => a == b,
            };
            if !fits {
                return Err(Error::BadValue {
                    name: name.clone(),
                    message: format!(
                        "`{value}` is not a {} (the type of its default, {default})",
                        expected.unwrap_or("value")
                    ),
                });
            }
        }
        Ok(())
    }

    fn run(&self, settings: &PythonSettings, job: &CurveJob) -> Result<CurveRun> {
        let strategy = || PythonStrategy {
            name: self.name.clone(),
            function: self.function.clone(),
            sink: self.sink.clone(),
            settings: settings.0.clone(),
            kind: job.kind,
            step: 0,
        };
        match job.points {
            CurvePoints::Planar(p) => run_strategy(Box::new(strategy()), p, job, self.max_steps),
            CurvePoints::Spatial(p) => run_strategy(Box::new(strategy()), p, job, self.max_steps),
        }
    }
}

/// One run of a Python strategy: the pipeline calls [`step`](FairingStrategy::step), which
/// calls the function once.
struct PythonStrategy {
    name: String,
    function: Arc<Py<PyAny>>,
    sink: Arc<Sink>,
    settings: serde_json::Map<String, Value>,
    kind: CurveKind,
    step: usize,
}

/// Points as an (n, D) float64 array.
fn points_array<'py, const D: usize>(py: Python<'py>, points: &[Vector<D>]) -> PyResult<Bound<'py, PyAny>> {
    let values: Vec<f64> = points.iter().flat_map(|p| p.iter().copied()).collect();
    let array = Array2::from_shape_vec((points.len(), D), values)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("internal error: {e}")))?;
    Ok(array.into_pyarray(py).into_any())
}

impl PythonStrategy {
    /// Calls the function on the state's points: the proposed points, or `None` for "done".
    fn propose<const D: usize>(
        &self,
        py: Python<'_>,
        state: &FairingState<D>,
    ) -> PyResult<Option<Vec<Vector<D>>>> {
        let n = state.len();
        let fixed: Vec<usize> = (0..n).filter(|&i| !state.is_movable(i)).collect();
        let context = PyDict::new(py);
        context.set_item("original", points_array(py, state.original())?)?;
        context.set_item("fixed", Array1::from_vec(fixed).into_pyarray(py))?;
        context.set_item("tolerance", state.constraints().tolerance())?;
        context.set_item(
            "settings",
            crate::to_python(py, &Value::Object(self.settings.clone()))?,
        )?;
        context.set_item("step", self.step)?;
        context.set_item("kind", self.kind.name())?;
        context.set_item("name", &self.name)?;
        let context = py
            .import("types")?
            .getattr("SimpleNamespace")?
            .call((), Some(&context))?;
        let proposed = self
            .function
            .bind(py)
            .call1((points_array(py, state.points())?, context))?;
        if proposed.is_none() {
            return Ok(None);
        }
        let what = format!("the points strategy `{}` returned", self.name);
        let (values, shape) = crate::float_array(&proposed, &what)?;
        if shape != [n, D] {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "{what}: shape {} where the points are ({n}, {D})",
                crate::shape_text(&shape)
            )));
        }
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "{what}: point {} has a coordinate that is not finite ({})",
                k / D,
                values[k]
            )));
        }
        Ok(Some(
            values
                .chunks_exact(D)
                .map(Vector::<D>::from_column_slice)
                .collect(),
        ))
    }

    fn step_in<const D: usize>(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        let proposed = Python::attach(|py| self.propose(py, state));
        self.step += 1;
        let proposed = match proposed {
            Ok(Some(points)) => points,
            Ok(None) => return Ok(StepOutcome::done(None)),
            Err(error) => {
                let line = format!("strategy `{}`: the Python function raised {error}", self.name);
                self.sink.keep(line.clone(), error);
                return Err(Error::Strategy {
                    strategy: self.name.clone(),
                    reason: format!("the Python function raised an exception ({line})"),
                });
            }
        };
        let mut moved = false;
        for (i, mut p) in proposed.into_iter().enumerate() {
            if self.kind == CurveKind::Function {
                // A function's x is its abscissa, not the strategy's to move.
                p[0] = state.points()[i][0];
            }
            if p != state.points()[i] && state.is_movable(i) {
                let before = state.points()[i];
                moved |= state.move_point(i, p)? != before;
            }
        }
        Ok(if moved {
            StepOutcome::running(None)
        } else {
            StepOutcome::done(None)
        })
    }
}

impl<const D: usize> FairingStrategy<D> for PythonStrategy {
    fn name(&self) -> &str {
        &self.name
    }

    /// Calls the function once and moves every movable point it proposed to move, through
    /// [`FairingState::move_point`] (for a function y(x), its y only: x keeps its bits);
    /// done when the function returns None or nothing moves.
    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        self.step_in(state)
    }
}

/// Parameters at which a Python criterion sees the curve, per piece between breaks.
pub const SAMPLES_PER_PIECE: usize = 16;

/// A criterion written in Python: `function(curve)` → a number, where `curve` holds samples
/// of the measured curve: `t`, `points`, `d1`, `d2`, `d3` and `breaks`, arrays.
#[derive(Clone)]
pub struct PythonCriterion {
    /// The name it is registered under.
    pub name: String,
    /// The callable.
    pub function: Arc<Py<PyAny>>,
    /// Where its exceptions go.
    pub sink: Arc<Sink>,
}

/// The curve as a Python object with arrays: `t` (parameters: every break and
/// [`SAMPLES_PER_PIECE`] − 1 more, equally spaced, inside each piece), `points`, `d1`, `d2`,
/// `d3` (the derivatives there, (m, D) each; at a break those of the piece starting there,
/// at the last one those of the last piece) and `breaks`. O(pieces · SAMPLES_PER_PIECE).
fn samples<'py, const D: usize>(py: Python<'py>, curve: &dyn Curve<D>) -> PyResult<Bound<'py, PyAny>> {
    let breaks = curve.breaks();
    let mut t = Vec::with_capacity(breaks.len() * SAMPLES_PER_PIECE);
    for w in breaks.windows(2) {
        t.extend((0..SAMPLES_PER_PIECE).map(|j| w[0] + (w[1] - w[0]) * j as f64 / SAMPLES_PER_PIECE as f64));
    }
    if let Some(&last) = breaks.last() {
        t.push(last);
    }
    let mut jets: [Vec<Vector<D>>; 4] = Default::default();
    for (k, &tk) in t.iter().enumerate() {
        let side = if k + 1 == t.len() { Side::Left } else { Side::Right };
        for (order, value) in curve.jet(tk, side).into_iter().enumerate() {
            jets[order].push(value);
        }
    }
    let namespace = PyDict::new(py);
    namespace.set_item("t", Array1::from_vec(t).into_pyarray(py))?;
    for (key, values) in ["points", "d1", "d2", "d3"].into_iter().zip(&jets) {
        namespace.set_item(key, points_array(py, values)?)?;
    }
    namespace.set_item("breaks", Array1::from_vec(breaks).into_pyarray(py))?;
    py.import("types")?
        .getattr("SimpleNamespace")?
        .call((), Some(&namespace))
}

impl PythonCriterion {
    fn value<const D: usize>(&self, curve: &dyn Curve<D>) -> fairness::Result<f64> {
        let outcome = Python::attach(|py| -> PyResult<f64> {
            let value: f64 = self.function.bind(py).call1((samples(py, curve)?,))?.extract()?;
            if value.is_finite() {
                Ok(value)
            } else {
                Err(pyo3::exceptions::PyValueError::new_err(format!(
                    "returned {value}, not a finite number"
                )))
            }
        });
        outcome.map_err(|error| {
            let line = format!("criterion `{}`: the Python function raised {error}", self.name);
            self.sink.keep(line, error);
            fairness::Error::InvalidSetting {
                what: "a Python criterion",
                reason: "its function raised an exception",
            }
        })
    }
}

impl fairness::Criterion<dyn Curve<2>> for PythonCriterion {
    fn name(&self) -> &str {
        &self.name
    }
    fn evaluate(&self, curve: &dyn Curve<2>) -> fairness::Result<f64> {
        self.value(curve)
    }
}

impl fairness::Criterion<dyn Curve<3>> for PythonCriterion {
    fn name(&self) -> &str {
        &self.name
    }
    fn evaluate(&self, curve: &dyn Curve<3>) -> fairness::Result<f64> {
        self.value(curve)
    }
}
