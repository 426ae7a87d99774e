//! Methods: the traits a method implements ([`CurveMethod`], [`SurfaceMethod`], or the easy
//! path [`StrategySettings`]), the settings they are configured by ([`Settings`]), and the
//! catalogue's entry for one ([`MethodEntry`]): name, paper, summary, the parameter table
//! derived from the settings' schema, defaults, and running.

use std::marker::PhantomData;
use std::sync::Arc;

use curve_repr::Vector;
use fairness::curvature::CurvatureForm;
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::Value;

use super::frame::{check_coordinates, Frame};
use super::job::{CurveJob, CurveKind, CurvePoints, CurveRun, SurfaceJob, SurfaceRun};
use super::parameters::{GivenValue, ParameterMap};
use super::schema::{self, ParameterInfo};
use crate::{Error, FairingStrategy, Pipeline, Refusal, Result};

/// The most characters of a given value (or of a deserialiser's message quoting it) that a
/// one-line message echoes.
const ECHO: usize = 120;

/// A method's settings: the one source of its parameters (GUIDE.md's conventions: serde with
/// `default, deny_unknown_fields, rename_all = "kebab-case"`, a doc comment per field whose
/// first line is its meaning, `Default` = the chosen defaults).
pub trait Settings:
    Serialize + DeserializeOwned + schemars::JsonSchema + Default + Clone + Send + Sync + 'static
{
    /// Refuses out-of-range values ([`Error::BadParameter`] or [`Error::BadValue`], naming
    /// the parameter). Default: accept everything that deserialises.
    fn validate(&self) -> Result<()> {
        Ok(())
    }
}

/// Whether a method fairs curves or surfaces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MethodKind {
    /// Curves (functions or parametric, 2D or 3D).
    Curve,
    /// Surface grids.
    Surface,
}

impl MethodKind {
    /// `curve` or `surface`.
    pub fn name(self) -> &'static str {
        match self {
            MethodKind::Curve => "curve",
            MethodKind::Surface => "surface",
        }
    }
}

/// What a method is: its name, what it fairs, where it comes from, what it does.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodInfo {
    /// The name `--method` and `[[stage]] method = ...` take.
    pub name: String,
    /// Curves or surfaces (set by the catalogue when registered).
    pub kind: MethodKind,
    /// The paper (or baseline) it comes from, short.
    pub paper: String,
    /// One line on what it does.
    pub summary: String,
}

impl MethodInfo {
    /// A method called `name` doing `summary` (kind set when registered; no paper).
    pub fn new(name: impl Into<String>, summary: impl Into<String>) -> Self {
        MethodInfo {
            name: name.into(),
            kind: MethodKind::Curve,
            paper: String::new(),
            summary: summary.into(),
        }
    }

    /// Sets the paper.
    pub fn with_paper(mut self, paper: impl Into<String>) -> Self {
        self.paper = paper.into();
        self
    }
}

/// A curve method with full control over its run (every built-in is one).
///
/// The catalogue reads the parameters from [`Settings`](Self::Settings), refuses `--points`
/// for a method that does not [take them](Self::takes_bad_points), calls
/// [`check`](Self::check) before [`run`](Self::run), and checks the result (same length and
/// dimension, finite, fixed points bit for bit, tolerance band) after it.
pub trait CurveMethod: Send + Sync + 'static {
    /// The settings (parameters) of the method.
    type Settings: Settings;

    /// Whether `--points` (bad points) means something to this method. Default false: the
    /// catalogue refuses bad points before the method runs.
    fn takes_bad_points(&self) -> bool {
        false
    }

    /// Whether the method fairs planar curves only (a declared capability: the catalogue
    /// refuses spatial points with [`Refusal::Dimension`] before [`check`](Self::check), and
    /// a front end lists the method as planar-only). Default false.
    fn planar_only(&self) -> bool {
        false
    }

    /// What the method refuses, before anything runs: kinds, dimensions, end clamps, closed
    /// curves, combinations of settings ([`Error::Refused`] naming the method, or
    /// [`Error::BadValue`] naming a parameter). Default: accept.
    fn check(&self, settings: &Self::Settings, job: &CurveJob) -> Result<()> {
        let _ = (settings, job);
        Ok(())
    }

    /// Fairs the job's points.
    fn run(&self, settings: &Self::Settings, job: &CurveJob) -> Result<CurveRun>;
}

/// A surface method.
pub trait SurfaceMethod: Send + Sync + 'static {
    /// The settings (parameters) of the method.
    type Settings: Settings;

    /// Whether `--points` means something to this method. Default false.
    fn takes_bad_points(&self) -> bool {
        false
    }

    /// What the method refuses, before anything runs. Default: accept.
    fn check(&self, settings: &Self::Settings, job: &SurfaceJob) -> Result<()> {
        let _ = (settings, job);
        Ok(())
    }

    /// Fairs the job's grid.
    fn run(&self, settings: &Self::Settings, job: &SurfaceJob) -> Result<SurfaceRun>;
}

/// The easy path to a curve method: settings that build a [`FairingStrategy`] for points of
/// either dimension. Registered with [`Strategy`]; the catalogue runs the strategy through a
/// [`Pipeline`] with the job's constraints and reports iterations, moves, time and
/// termination.
///
/// ```
/// use fairing::catalog::{Catalog, MethodInfo, Settings, Strategy, StrategySettings, CurveJob};
/// use fairing::{FairingState, FairingStrategy, Result, StepOutcome};
/// use curve_repr::Vector;
///
/// /// Does nothing, once.
/// #[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
/// #[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
/// struct IdleSettings {
///     /// Steps at most.
///     steps: usize,
/// }
/// impl Settings for IdleSettings {}
///
/// struct Idle;
/// impl<const D: usize> FairingStrategy<D> for Idle {
///     fn name(&self) -> &str { "idle" }
///     fn step(&mut self, _: &mut FairingState<D>) -> Result<StepOutcome> { Ok(StepOutcome::done(None)) }
/// }
///
/// impl StrategySettings for IdleSettings {
///     fn strategy<const D: usize>(&self, _: &CurveJob) -> Result<Box<dyn FairingStrategy<D>>> {
///         Ok(Box::new(Idle))
///     }
/// }
///
/// let mut catalog = Catalog::builtin();
/// catalog.register_curve(MethodInfo::new("idle", "does nothing"), Strategy::<IdleSettings>::new());
/// assert!(catalog.table().contains("idle"));
/// ```
pub trait StrategySettings: Settings {
    /// The strategy for points of dimension `D` (2 or 3).
    fn strategy<const D: usize>(&self, job: &CurveJob) -> Result<Box<dyn FairingStrategy<D>>>
    where
        Vector<D>: CurvatureForm;

    /// The pipeline's step limit. Default [`Pipeline::DEFAULT_MAX_ITERATIONS`].
    fn max_iterations(&self) -> usize {
        Pipeline::<2>::DEFAULT_MAX_ITERATIONS
    }

    /// Whether `--points` means something to the strategy. Default false.
    fn takes_bad_points(&self) -> bool {
        false
    }

    /// What the method refuses, before anything runs. Default: accept (the strategy's own
    /// [`FairingStrategy::supports`] is asked too).
    fn check(&self, job: &CurveJob) -> Result<()> {
        let _ = job;
        Ok(())
    }
}

/// The easy path for a strategy that fairs planar curves only (it implements
/// [`FairingStrategy<2>`] alone): the same as [`StrategySettings`] without the dimension
/// parameter. Registered with [`Catalog::register_planar_strategy`]; the method is declared
/// planar-only ([`CurveMethod::planar_only`]), so the catalogue refuses spatial points for it.
///
/// [`Catalog::register_planar_strategy`]: super::Catalog::register_planar_strategy
pub trait PlanarStrategySettings: Settings {
    /// The strategy for planar points.
    fn strategy(&self, job: &CurveJob) -> Result<Box<dyn FairingStrategy<2>>>;

    /// The pipeline's step limit. Default [`Pipeline::DEFAULT_MAX_ITERATIONS`].
    fn max_iterations(&self) -> usize {
        Pipeline::<2>::DEFAULT_MAX_ITERATIONS
    }

    /// Whether `--points` means something to the strategy. Default false.
    fn takes_bad_points(&self) -> bool {
        false
    }

    /// What the method refuses, before anything runs (besides spatial points). Default:
    /// accept (the strategy's own [`FairingStrategy::supports`] is asked too).
    fn check(&self, job: &CurveJob) -> Result<()> {
        let _ = job;
        Ok(())
    }
}

/// The [`CurveMethod`] of a [`PlanarStrategySettings`] type (see
/// [`Catalog::register_planar_strategy`](super::Catalog::register_planar_strategy)).
pub struct PlanarStrategy<S>(PhantomData<fn() -> S>);

impl<S> PlanarStrategy<S> {
    /// The adapter.
    pub fn new() -> Self {
        PlanarStrategy(PhantomData)
    }
}

impl<S> Default for PlanarStrategy<S> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: PlanarStrategySettings> CurveMethod for PlanarStrategy<S> {
    type Settings = S;

    fn takes_bad_points(&self) -> bool {
        S::default().takes_bad_points()
    }

    fn planar_only(&self) -> bool {
        true
    }

    fn check(&self, settings: &S, job: &CurveJob) -> Result<()> {
        settings.check(job)?;
        match job.points {
            CurvePoints::Planar(_) => settings.strategy(job)?.supports(job.constraints),
            CurvePoints::Spatial(_) => Err(planar_refusal(job.method)),
        }
    }

    fn run(&self, settings: &S, job: &CurveJob) -> Result<CurveRun> {
        match job.points {
            CurvePoints::Planar(p) => {
                run_strategy(settings.strategy(job)?, p, job, settings.max_iterations())
            }
            CurvePoints::Spatial(_) => Err(planar_refusal(job.method)),
        }
    }
}

/// Puts the input's x back into every faired point of a function (`x` is the abscissa, not
/// a coordinate a method may move); true when some x had moved. O(n).
fn keep_x(input: &CurvePoints, faired: &mut CurvePoints) -> bool {
    let (CurvePoints::Planar(a), CurvePoints::Planar(b)) = (input, faired) else {
        return false;
    };
    let mut moved = false;
    for (p, q) in a.iter().zip(b.iter_mut()) {
        if q.x.to_bits() != p.x.to_bits() {
            q.x = p.x;
            moved = true;
        }
    }
    moved
}

/// The refusal of spatial points by a planar-only method.
fn planar_refusal(method: &str) -> Error {
    Error::Refused {
        method: method.to_owned(),
        what: Refusal::Dimension,
        reason: "fairs planar curves (x, y) only; the input has 3 coordinates".into(),
    }
}

/// The [`CurveMethod`] of a [`StrategySettings`] type: register it with
/// `catalog.register_curve(info, Strategy::<MySettings>::new())`.
pub struct Strategy<S>(PhantomData<fn() -> S>);

impl<S> Strategy<S> {
    /// The adapter.
    pub fn new() -> Self {
        Strategy(PhantomData)
    }
}

impl<S> Default for Strategy<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// Runs `strategy` on the job's points of dimension `D` through a [`Pipeline`] (open curve,
/// the job's constraints, `max_iterations` steps at most, no trace).
pub fn run_strategy<const D: usize>(
    strategy: Box<dyn FairingStrategy<D> + '_>,
    points: &[Vector<D>],
    job: &CurveJob,
    max_iterations: usize,
) -> Result<CurveRun> {
    let result = Pipeline::new(strategy)
        .with_constraints(job.constraints.clone())
        .with_max_iterations(max_iterations)
        .with_trace(false)
        .run(points.to_vec())?;
    Ok(CurveRun::from_result(result))
}

impl<S: StrategySettings> CurveMethod for Strategy<S> {
    type Settings = S;

    fn takes_bad_points(&self) -> bool {
        S::default().takes_bad_points()
    }

    fn check(&self, settings: &S, job: &CurveJob) -> Result<()> {
        settings.check(job)?;
        match job.points {
            CurvePoints::Planar(_) => settings.strategy::<2>(job)?.supports(job.constraints),
            CurvePoints::Spatial(_) => settings.strategy::<3>(job)?.supports(job.constraints),
        }
    }

    fn run(&self, settings: &S, job: &CurveJob) -> Result<CurveRun> {
        match job.points {
            CurvePoints::Planar(p) => {
                run_strategy(settings.strategy::<2>(job)?, p, job, settings.max_iterations())
            }
            CurvePoints::Spatial(p) => {
                run_strategy(settings.strategy::<3>(job)?, p, job, settings.max_iterations())
            }
        }
    }
}

/// A method with its settings type erased: what the catalogue stores.
pub(crate) trait ErasedMethod: Send + Sync {
    fn schema(&self) -> Value;
    fn defaults(&self) -> Value;
    fn key_order(&self) -> Vec<String>;
    /// Deserialises complete settings, and validates them when `validate` is set.
    fn accept(&self, settings: &Value, validate: bool) -> Result<()>;
    fn takes_bad_points(&self) -> bool;
    fn planar_only(&self) -> bool;
    fn check_curve(&self, settings: &Value, job: &CurveJob) -> Result<()>;
    fn run_curve(&self, settings: &Value, job: &CurveJob) -> Result<CurveRun>;
    fn check_surface(&self, settings: &Value, job: &SurfaceJob) -> Result<()>;
    fn run_surface(&self, settings: &Value, job: &SurfaceJob) -> Result<SurfaceRun>;
}

fn read<S: Settings>(settings: &Value) -> Result<S> {
    let typed = deserialize::<S>(settings)?;
    typed.validate()?;
    Ok(typed)
}

fn deserialize<S: Settings>(settings: &Value) -> Result<S> {
    serde_json::from_value(settings.clone()).map_err(|e| Error::Parameter {
        origin: "settings".into(),
        message: e.to_string(),
    })
}

fn schema_of<S: Settings>() -> Value {
    serde_json::to_value(schemars::schema_for!(S)).unwrap_or_default()
}

/// The default settings of `S` as JSON (what a curve and a surface adapter both report).
fn defaults_of<S: Settings>() -> Value {
    serde_json::to_value(S::default()).unwrap_or_default()
}

/// Whether `settings` deserialise as `S` (and, with `validate`, pass its range checks).
fn accept_as<S: Settings>(settings: &Value, validate: bool) -> Result<()> {
    let typed = deserialize::<S>(settings)?;
    if validate {
        typed.validate()?;
    }
    Ok(())
}

pub(crate) struct CurveAdapter<M>(pub M);
pub(crate) struct SurfaceAdapter<M>(pub M);

impl<M: CurveMethod> ErasedMethod for CurveAdapter<M> {
    fn schema(&self) -> Value {
        schema_of::<M::Settings>()
    }
    fn defaults(&self) -> Value {
        defaults_of::<M::Settings>()
    }
    fn key_order(&self) -> Vec<String> {
        schema::key_order(&M::Settings::default())
    }
    fn accept(&self, settings: &Value, validate: bool) -> Result<()> {
        accept_as::<M::Settings>(settings, validate)
    }
    fn takes_bad_points(&self) -> bool {
        self.0.takes_bad_points()
    }
    fn planar_only(&self) -> bool {
        self.0.planar_only()
    }
    fn check_curve(&self, settings: &Value, job: &CurveJob) -> Result<()> {
        self.0.check(&read(settings)?, job)
    }
    fn run_curve(&self, settings: &Value, job: &CurveJob) -> Result<CurveRun> {
        self.0.run(&read(settings)?, job)
    }
    fn check_surface(&self, _: &Value, job: &SurfaceJob) -> Result<()> {
        Err(not_kind(job.method, "curves"))
    }
    fn run_surface(&self, _: &Value, job: &SurfaceJob) -> Result<SurfaceRun> {
        Err(not_kind(job.method, "curves"))
    }
}

impl<M: SurfaceMethod> ErasedMethod for SurfaceAdapter<M> {
    fn schema(&self) -> Value {
        schema_of::<M::Settings>()
    }
    fn defaults(&self) -> Value {
        defaults_of::<M::Settings>()
    }
    fn key_order(&self) -> Vec<String> {
        schema::key_order(&M::Settings::default())
    }
    fn accept(&self, settings: &Value, validate: bool) -> Result<()> {
        accept_as::<M::Settings>(settings, validate)
    }
    fn takes_bad_points(&self) -> bool {
        self.0.takes_bad_points()
    }
    fn planar_only(&self) -> bool {
        false
    }
    fn check_curve(&self, _: &Value, job: &CurveJob) -> Result<()> {
        Err(not_kind(job.method, "surfaces"))
    }
    fn run_curve(&self, _: &Value, job: &CurveJob) -> Result<CurveRun> {
        Err(not_kind(job.method, "surfaces"))
    }
    fn check_surface(&self, settings: &Value, job: &SurfaceJob) -> Result<()> {
        self.0.check(&read(settings)?, job)
    }
    fn run_surface(&self, settings: &Value, job: &SurfaceJob) -> Result<SurfaceRun> {
        self.0.run(&read(settings)?, job)
    }
}

fn not_kind(method: &str, fairs: &str) -> Error {
    Error::Refused {
        method: method.to_owned(),
        what: Refusal::Kind,
        reason: format!("fairs {fairs} only"),
    }
}

/// One method of the catalogue: what it is, its parameters and defaults, and how to run it.
#[derive(Clone)]
pub struct MethodEntry {
    pub(crate) info: MethodInfo,
    pub(crate) method: Arc<dyn ErasedMethod>,
    pub(crate) schema: Value,
    pub(crate) defaults: Value,
    pub(crate) pinned: Vec<String>,
    pub(crate) parameters: Vec<ParameterInfo>,
}

impl std::fmt::Debug for MethodEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MethodEntry")
            .field("info", &self.info)
            .field("parameters", &self.parameters.len())
            .finish()
    }
}

impl MethodEntry {
    /// An entry for `method` with its own defaults.
    pub(crate) fn new(info: MethodInfo, method: Arc<dyn ErasedMethod>) -> MethodEntry {
        let mut entry = MethodEntry {
            schema: method.schema(),
            defaults: method.defaults(),
            info,
            method,
            pinned: Vec::new(),
            parameters: Vec::new(),
        };
        entry.parameters = entry.derive_parameters();
        entry
    }

    /// An entry whose settings schema and defaults are given when the program runs, not
    /// derived from a settings type (see [`Catalog::register_curve_with_schema`]); the
    /// defaults must be settings the method accepts.
    ///
    /// [`Catalog::register_curve_with_schema`]: super::Catalog::register_curve_with_schema
    pub(crate) fn with_schema(
        info: MethodInfo,
        method: Arc<dyn ErasedMethod>,
        schema: Value,
        defaults: Value,
    ) -> Result<MethodEntry> {
        method.accept(&defaults, true)?;
        let mut entry = MethodEntry {
            info,
            method,
            schema,
            defaults,
            pinned: Vec::new(),
            parameters: Vec::new(),
        };
        entry.parameters = entry.derive_parameters();
        Ok(entry)
    }

    /// A preset of this entry: other defaults (merged over these), some parameters pinned
    /// (neither listed nor accepted).
    pub(crate) fn preset(&self, info: MethodInfo, defaults: &Value, pinned: &[&str]) -> Result<MethodEntry> {
        let mut merged = self.defaults.clone();
        let properties = schema::properties(&self.schema);
        if let (Value::Object(base), Value::Object(over)) = (&mut merged, defaults) {
            for (name, value) in over {
                if !properties.contains_key(name) {
                    return Err(Error::UnknownName {
                        origin: format!("preset `{}`", info.name),
                        what: format!("a parameter of `{}`", self.info.name),
                        name: schema::clip(name, 80),
                        known: self.known_names(),
                    });
                }
                base.insert(name.clone(), value.clone());
            }
        }
        self.method.accept(&merged, true)?;
        let mut pinned_all = self.pinned.clone();
        pinned_all.extend(pinned.iter().map(|p| p.to_string()));
        let mut entry = MethodEntry {
            info,
            method: self.method.clone(),
            schema: self.schema.clone(),
            defaults: merged,
            pinned: pinned_all,
            parameters: Vec::new(),
        };
        entry.parameters = entry.derive_parameters();
        Ok(entry)
    }

    fn derive_parameters(&self) -> Vec<ParameterInfo> {
        let properties = schema::properties(&self.schema);
        let mut order = self.method.key_order();
        for name in properties.keys() {
            if !order.contains(name) {
                order.push(name.clone());
            }
        }
        order
            .into_iter()
            .filter(|name| !self.pinned.contains(name))
            .filter_map(|name| {
                let property = properties.get(&name)?.clone();
                let default_value = self.defaults.get(&name).cloned().unwrap_or(Value::Null);
                Some(ParameterInfo {
                    default: schema::value_to_text(&default_value),
                    meaning: schema::meaning(&property, &self.schema),
                    name,
                    default_value,
                    schema: property,
                })
            })
            .collect()
    }

    /// What the method is.
    pub fn info(&self) -> &MethodInfo {
        &self.info
    }

    /// Its name.
    pub fn name(&self) -> &str {
        &self.info.name
    }

    /// Its parameters, in the settings' field order (pinned ones left out).
    pub fn parameters(&self) -> &[ParameterInfo] {
        &self.parameters
    }

    /// The parameter called `name`.
    pub fn parameter(&self, name: &str) -> Option<&ParameterInfo> {
        self.parameters.iter().find(|p| p.name == name)
    }

    /// The JSON Schema of its settings (every field, pinned ones too).
    pub fn schema(&self) -> &Value {
        &self.schema
    }

    /// Its complete default settings (a preset's applied).
    pub fn defaults(&self) -> &Value {
        &self.defaults
    }

    /// Whether `--points` means something to it.
    pub fn takes_bad_points(&self) -> bool {
        self.method.takes_bad_points()
    }

    /// Whether it fairs planar curves only ([`CurveMethod::planar_only`]; false for surface
    /// methods).
    pub fn planar_only(&self) -> bool {
        self.method.planar_only()
    }

    /// Bad points refused unless the method takes them; spatial points refused for a
    /// planar-only method; coordinates the arithmetic cannot square refused.
    fn refuse_before_check(&self, job: &CurveJob) -> Result<()> {
        if !job.bad_points.is_empty() && !self.takes_bad_points() {
            return Err(Error::Refused {
                method: self.info.name.clone(),
                what: Refusal::BadPoints,
                reason: "takes no bad points (it finds what to change itself)".into(),
            });
        }
        if self.planar_only() && job.points.dimension() != 2 {
            return Err(planar_refusal(&self.info.name));
        }
        check_coordinates(job.points.rows().into_iter(), "point")
    }

    fn known_names(&self) -> String {
        let names: Vec<&str> = self.parameters.iter().map(|p| p.name.as_str()).collect();
        if names.is_empty() {
            "it has none".into()
        } else {
            names.join(", ")
        }
    }

    /// The complete settings from the defaults and `given`: every name checked against the
    /// parameters (unknown and pinned ones refused with the known ones), text converted by
    /// the schema, each value deserialised and the whole validated; every error names where
    /// the offending value was given.
    pub fn settings(&self, given: &ParameterMap) -> Result<Value> {
        let properties = schema::properties(&self.schema);
        let mut settings = self.defaults.clone();
        for (name, value) in given.iter() {
            let property = match properties.get(name) {
                Some(p) if !self.pinned.contains(name) => p,
                _ => {
                    return Err(Error::UnknownName {
                        origin: value.origin.clone(),
                        what: format!("a parameter of `{}`", self.info.name),
                        name: schema::clip(name, 80),
                        known: self.known_names(),
                    })
                }
            };
            let json = match &value.value {
                GivenValue::Text(text) => schema::text_to_value(text, property, &self.schema),
                GivenValue::Json(Value::String(text)) => schema::text_to_value(text, property, &self.schema),
                GivenValue::Json(v) => v.clone(),
            };
            if let Some(range) = schema::NumberRange::of(property, &self.schema) {
                self.check_range(name, value, &json, &range)?;
            }
            if let Value::Object(map) = &mut settings {
                map.insert(name.clone(), json);
            }
            // Deserialise after each value, so that an error is the value's, at its origin
            // (the ranges are validated once all are in: one may depend on another).
            if let Err(e) = self.method.accept(&settings, false) {
                let message = match e {
                    Error::Parameter { message, .. } => message,
                    other => other.to_string(),
                };
                return Err(Error::Parameter {
                    origin: value.origin.clone(),
                    message: format!(
                        "`{name}` = `{}`: {}",
                        schema::clip(&value.value.text(), ECHO),
                        schema::clip(&message, ECHO)
                    ),
                });
            }
        }
        self.method
            .accept(&settings, true)
            .map_err(|e| parameter_error(e, given))?;
        Ok(settings)
    }

    /// Refuses a number outside the range the parameter's schema declares
    /// ([`Error::OutOfRange`]), or a fraction where it takes integers, naming the method, the
    /// parameter, the value and the range, at the value's origin. `json` is the value as the
    /// schema read it (a text an integer parameter cannot take stays a string). O(1).
    fn check_range(
        &self,
        name: &str,
        value: &super::parameters::Given,
        json: &Value,
        range: &schema::NumberRange,
    ) -> Result<()> {
        let number = match json {
            Value::Number(n) => n.as_f64(),
            Value::String(s) if range.integer => s.trim().parse::<f64>().ok().filter(|x| x.is_finite()),
            _ => None,
        };
        let Some(x) = number else {
            return Ok(());
        };
        let text = schema::clip(&value.value.text(), ECHO);
        if range.integer && x.fract() != 0.0 {
            return Err(Error::Parameter {
                origin: value.origin.clone(),
                message: format!(
                    "`{}`: {name} = {text}: expected {}",
                    self.info.name,
                    range.describe()
                ),
            });
        }
        if !range.contains(x) {
            return Err(Error::OutOfRange {
                origin: value.origin.clone(),
                method: self.info.name.clone(),
                setting: name.to_owned(),
                value: text,
                allowed: range.describe(),
            });
        }
        Ok(())
    }

    /// The settings' value of the parameter `name` (pinned or not).
    pub fn value_of<'a>(&self, settings: &'a Value, name: &str) -> Option<&'a Value> {
        settings.get(name)
    }

    /// The settings without the pinned parameters: what a report and a printed config list.
    pub fn visible(&self, settings: &Value) -> serde_json::Map<String, Value> {
        let mut out = serde_json::Map::new();
        for p in &self.parameters {
            if let Some(v) = settings.get(&p.name) {
                out.insert(p.name.clone(), v.clone());
            }
        }
        out
    }

    /// Runs the method on a curve with complete `settings` (from [`settings`](Self::settings)):
    /// bad points refused unless the method takes them, the method's check, the run, then the
    /// result checked against the job (length, dimension, finite values, constraints).
    pub fn fair_curve(&self, settings: &Value, job: &CurveJob) -> Result<CurveRun> {
        if self.info.kind != super::MethodKind::Curve {
            return Err(not_kind(&self.info.name, "surfaces"));
        }
        let job = CurveJob {
            method: &self.info.name,
            ..*job
        };
        self.refuse_before_check(&job)?;
        // The method runs in the reference frame (see `frame`), its result mapped back.
        let frame = Frame::of(&job.points.rows());
        let points = frame.curve_points_to_frame(job.points);
        let constraints = frame.constraints_to_frame(job.constraints);
        let framed = CurveJob {
            points: &points,
            constraints: &constraints,
            ..job
        };
        let framed_settings = &frame.settings_to_frame(settings);
        let mark = frame.mark();
        let outcome = self
            .method
            .check_curve(framed_settings, &framed)
            .and_then(|()| self.method.run_curve(framed_settings, &framed))
            .map_err(|e| refusal(e, &self.info.name));
        drop(mark);
        outcome
            .map(|mut run| {
                run.points = frame.curve_points_from_frame(job.points, &points, &run.points);
                match (job.points, &mut run.points) {
                    (CurvePoints::Planar(a), CurvePoints::Planar(b)) => {
                        Frame::hold_band(job.constraints, settings, a, b)
                    }
                    (CurvePoints::Spatial(a), CurvePoints::Spatial(b)) => {
                        Frame::hold_band(job.constraints, settings, a, b)
                    }
                    _ => {}
                }
                // A function's x is the framework's to keep, not each method's: a method that
                // moved x (the parametric ones) has its y kept at the input's x, and its own
                // curve, which passed through the moved points, is no longer the result's.
                if job.kind == CurveKind::Function && keep_x(job.points, &mut run.points) {
                    run.represented = None;
                    run.curve = Value::Null;
                }
                // Mapping back may round a tiny move away: `moved` is what differs now.
                run.moved = job.points.differences(&run.points);
                run.curve = frame.record_from_frame(std::mem::take(&mut run.curve));
                run.extras = std::mem::take(&mut run.extras)
                    .into_iter()
                    .map(|(k, v)| {
                        let v = frame.extra_from_frame(&k, v);
                        (k, v)
                    })
                    .collect();
                run.represented = run.represented.map(|r| frame.represented_from_frame(r));
                run
            })
            .and_then(|run| check_run(&self.info.name, &job, run))
            .and_then(|run| keep_closed(&self.info.name, &job, run))
    }

    /// Checks what [`fair_curve`](Self::fair_curve) checks before running, without running.
    pub fn check_curve(&self, settings: &Value, job: &CurveJob) -> Result<()> {
        let job = CurveJob {
            method: &self.info.name,
            ..*job
        };
        self.refuse_before_check(&job)?;
        self.method
            .check_curve(settings, &job)
            .map_err(|e| refusal(e, &self.info.name))
    }

    /// Runs the method on a surface grid with complete `settings`.
    pub fn fair_surface(&self, settings: &Value, job: &SurfaceJob) -> Result<SurfaceRun> {
        let job = SurfaceJob {
            method: &self.info.name,
            ..*job
        };
        if !job.bad_points.is_empty() && !self.takes_bad_points() {
            return Err(Error::Refused {
                method: self.info.name.clone(),
                what: Refusal::BadPoints,
                reason: "takes no bad points".into(),
            });
        }
        if !job.constraints.joins().is_empty() && self.info.name != crate::strategies::surface_jump_lsq::NAME
        {
            return Err(Error::Refused {
                method: self.info.name.clone(),
                what: Refusal::Join,
                reason: "holds no edge to a neighbour (joins are the surface jump-lsq's)".into(),
            });
        }
        check_coordinates(job.grid.points.iter().map(|p| vec![p.x, p.y, p.z]), "grid point")?;
        let frame = Frame::of(
            &job.grid
                .points
                .iter()
                .map(|p| vec![p.x, p.y, p.z])
                .collect::<Vec<_>>(),
        );
        let grid = frame.grid_to_frame(job.grid);
        let constraints = frame.constraints_to_frame(job.constraints);
        let framed = SurfaceJob {
            grid: &grid,
            constraints: &constraints,
            ..job
        };
        let framed_settings = &frame.settings_to_frame(settings);
        let mark = frame.mark();
        let outcome = self
            .method
            .check_surface(framed_settings, &framed)
            .and_then(|()| self.method.run_surface(framed_settings, &framed))
            .map_err(|e| refusal(e, &self.info.name));
        drop(mark);
        let mut run = outcome?;
        if run.grid.points.len() == grid.points.len() {
            run.grid = frame.grid_from_frame(job.grid, &grid, &run.grid);
            Frame::hold_band(job.constraints, settings, &job.grid.points, &mut run.grid.points);
            keep_held_seam_repeats(&job, &mut run.grid.points);
            run.moved = (0..grid.points.len())
                .filter(|&k| run.grid.points[k] != job.grid.points[k])
                .collect();
        }
        run.surface = frame.record_from_frame(std::mem::take(&mut run.surface));
        run.extras = std::mem::take(&mut run.extras)
            .into_iter()
            .map(|(k, v)| {
                let v = frame.extra_from_frame(&k, v);
                (k, v)
            })
            .collect();
        if (run.grid.rows, run.grid.columns) != (job.grid.rows, job.grid.columns)
            || run.grid.points.len() != job.grid.points.len()
        {
            return Err(Error::Strategy {
                strategy: self.info.name.clone(),
                reason: "changed the grid's size".into(),
            });
        }
        job.constraints.check(&job.grid.points, &run.grid.points)?;
        Ok(run)
    }
}

/// A closed net's repeated line is its first line written again, so that the seam stays closed
/// exactly; but the input's may repeat it only to round-off (within the topology's
/// coincidence tolerance). A held node there (fixed, or on the boundary under `g0`) that the
/// method wrote as its twin's copy is given back its input bit for bit, as held nodes are
/// promised: the seam then stays as closed at that node as the input was. O(m·n).
fn keep_held_seam_repeats(job: &SurfaceJob, points: &mut [curve_repr::Vec3]) {
    let (rows, columns) = (job.grid.rows, job.grid.columns);
    let input = &job.grid.points;
    if rows * columns != input.len() || points.len() != input.len() || rows < 2 || columns < 2 {
        return;
    }
    let topology = curve_repr::GridTopology::detect(input, rows, columns);
    if !topology.closed_u && !topology.closed_v {
        return;
    }
    let held: std::collections::BTreeSet<(usize, usize)> = job.fixed_nodes();
    for &(i, j) in &held {
        let k = i * columns + j;
        let twin = if topology.closed_v && j + 1 == columns {
            Some(i * columns)
        } else if topology.closed_u && i + 1 == rows {
            Some(j)
        } else {
            None
        };
        if let Some(t) = twin {
            if points[k] == points[t] && points[k] != input[k] {
                points[k] = input[k];
            }
        }
    }
}

/// An error of the settings' validation, at the origin of the parameter it names.
pub(crate) fn parameter_error(error: Error, given: &ParameterMap) -> Error {
    match error {
        Error::BadParameter { name, value, reason } => {
            let name = name.replace('_', "-");
            Error::Parameter {
                origin: given.origin_of(&name),
                message: format!("`{name}` = `{value}` {reason}"),
            }
        }
        Error::BadValue { name, message } => Error::Parameter {
            origin: given.origin_of(&name),
            message: format!("`{name}`: {message}"),
        },
        other => other,
    }
}

/// A strategy's "cannot honour" as the method's refusal (the command names the option).
fn refusal(error: Error, method: &str) -> Error {
    match error {
        Error::ConstraintUnsupported { constraint, .. } => {
            let what = if constraint.starts_with("end clamp") {
                Refusal::EndClamp
            } else if constraint.contains("closed") {
                Refusal::Closed
            } else {
                Refusal::Parameters
            };
            Error::Refused {
                method: method.to_owned(),
                what,
                reason: format!("cannot honour {constraint}"),
            }
        }
        other => other,
    }
}

/// A parametric polygon whose last point repeats its first is a closed curve for every
/// method: a result that opened it (first and last points no longer equal) is refused,
/// saying so, rather than written.
fn keep_closed(method: &str, job: &CurveJob, run: CurveRun) -> Result<CurveRun> {
    fn ends_equal<const D: usize>(p: &[Vector<D>]) -> bool {
        p.len() > 2 && p.first() == p.last()
    }
    let equal = |points: &CurvePoints| match points {
        CurvePoints::Planar(p) => ends_equal(p),
        CurvePoints::Spatial(p) => ends_equal(p),
    };
    if job.kind != CurveKind::Parametric || !equal(job.points) || equal(&run.points) {
        return Ok(run);
    }
    Err(Error::Refused {
        method: method.to_owned(),
        what: Refusal::Closed,
        reason: "cannot keep a closed curve closed (the input's last point repeats its first, and \
                 the method moved the two apart); fix both with --fixed 0,LAST to fair it with \
                 the seam held"
            .into(),
    })
}

/// The contract every curve method's result keeps, checked for all of them: the input's
/// length and dimension, finite coordinates, and the constraints (fixed points bit for bit,
/// tolerance band, restraining radii).
fn check_run(method: &str, job: &CurveJob, run: CurveRun) -> Result<CurveRun> {
    if run.points.len() != job.points.len() || run.points.dimension() != job.points.dimension() {
        return Err(Error::Strategy {
            strategy: method.to_owned(),
            reason: format!(
                "returned {} points of dimension {} for {} of dimension {}",
                run.points.len(),
                run.points.dimension(),
                job.points.len(),
                job.points.dimension()
            ),
        });
    }
    match (job.points, &run.points) {
        (CurvePoints::Planar(a), CurvePoints::Planar(b)) => job.constraints.check(a, b)?,
        (CurvePoints::Spatial(a), CurvePoints::Spatial(b)) => job.constraints.check(a, b)?,
        _ => {}
    }
    Ok(run)
}
