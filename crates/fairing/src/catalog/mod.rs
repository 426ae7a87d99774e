//! The method catalogue: every method, criterion and local indicator by name, each fact
//! written once.
//!
//! A method's parameters are its settings struct ([`Settings`]: serde + schemars, a doc
//! comment per field); the catalogue derives everything that lists them from its JSON
//! Schema — the table `fair methods` prints ([`Catalog::table`]), `--set` and config files
//! ([`MethodEntry::settings`]), `--print-config` ([`Plan::render`]), the bindings and the web
//! page ([`MethodEntry::parameters`], [`MethodEntry::schema`]). Presets are entries with other
//! defaults ([`Catalog::register_preset`]), never copies of a parameter list.
//!
//! Running is one shape for every method: a [`CurveJob`] (points of either dimension, kind,
//! constraints, bad points) gives a [`CurveRun`] (points, iterations, moved, elapsed time,
//! termination in one kebab-case spelling, the `curve` description, extras, and the
//! method's own curves when they are not the measured spline); a config pipeline is parsed
//! ([`ConfigFile`]) and planned ([`Catalog::plan`]) and run ([`Catalog::run_curve_plan`])
//! here, so the command, the bindings and a Rust program share one path.
//!
//! Adding a method:
//! - a [`FairingStrategy`](crate::FairingStrategy) and a settings struct (declared with
//!   [`settings!`](crate::settings!)) implementing [`StrategySettings`]:
//!   `catalog.register_strategy::<MySettings>(info)`; a strategy for planar curves only
//!   implements [`PlanarStrategySettings`] instead and is registered with
//!   [`register_planar_strategy`](Catalog::register_planar_strategy);
//! - or, for full control of the run and its report, a [`CurveMethod`] (or
//!   [`SurfaceMethod`]) — as every built-in in [`builtin`] is.
//!
//! Each method's page of the user guide (`docs/methods/`) is rendered from its entry
//! ([`MethodEntry::page`]), settings table included.
//!
//! Criteria ([`CriterionEntry`]) and indicators ([`IndicatorEntry`]) are registered the same
//! way; a report's `criteria` lists every registered criterion that applies.

pub mod builtin;
mod config;
pub mod contract;
mod corner_split;
mod criteria;
mod frame;
pub use frame::LARGEST as LARGEST_COORDINATE;
mod job;
mod method;
mod page;
mod parameters;
mod plan;
mod schema;
pub mod value;

use std::collections::BTreeMap;
use std::sync::Arc;

pub use config::{ConfigConstraints, ConfigFile, StageConfig, CONSTRAINTS_KEY, STAGE_KEY};
pub use criteria::{
    builtin_criteria, builtin_indicators, evaluate_all, evaluate_all_with, measure_energies, measured_curve,
    CriterionEntry, CurvatureSlopeJump, IndicatorEntry, OnCurve, SharedCriterion, SharedIndicator,
    ThirdDerivativeJump,
};
pub use job::{
    AnyCurve, CurveJob, CurveKind, CurvePoints, CurveRun, Grid, Represented, SurfaceJob, SurfaceRun,
};
pub use method::{
    run_strategy, CurveMethod, MethodEntry, MethodInfo, MethodKind, PlanarStrategy, PlanarStrategySettings,
    Settings, Strategy, StrategySettings, SurfaceMethod,
};
pub use page::GENERATED_MARKER;
pub use parameters::{Given, GivenValue, ParameterMap};
pub use plan::{Plan, PlanConstraints, Stage};
pub use schema::{check_declared_ranges, NumberRange, ParameterInfo};

use crate::{Error, Result};

/// Every method, criterion and indicator a program knows, by name.
///
/// ```
/// use fairing::catalog::{Catalog, MethodKind};
/// let catalog = Catalog::builtin();
/// let two_phase = catalog.method(MethodKind::Curve, "two-phase").unwrap();
/// assert!(two_phase.parameter("max-passes").is_some());
/// assert!(catalog.method(MethodKind::Curve, "frobnicate").is_err());
/// ```
#[derive(Clone, Debug, Default)]
pub struct Catalog {
    methods: Vec<MethodEntry>,
    criteria: Vec<CriterionEntry>,
    indicators: Vec<IndicatorEntry>,
}

impl Catalog {
    /// An empty catalogue.
    pub fn new() -> Catalog {
        Catalog::default()
    }

    /// Every built-in method (curves: two-phase, strain-energy, kjellander, poliakoff,
    /// batten, nurbs-weights, smoothing-spline, sapidis-farin; surfaces: zhang-cheng,
    /// kjellander), criterion (e1, e2, e3, ek, ek-prime) and indicator
    /// (third-derivative-jump, curvature-slope-jump).
    pub fn builtin() -> Catalog {
        let mut catalog = Catalog::new();
        builtin::register(&mut catalog);
        catalog
    }

    fn insert(&mut self, entry: MethodEntry) {
        let kind = entry.info.kind;
        match self
            .methods
            .iter_mut()
            .find(|m| m.info.kind == kind && m.info.name == entry.info.name)
        {
            Some(slot) => *slot = entry,
            None => self.methods.push(entry),
        }
    }

    /// Registers a curve method (replacing one of the same name).
    pub fn register_curve<M: CurveMethod>(&mut self, mut info: MethodInfo, method: M) -> &mut Self {
        info.kind = MethodKind::Curve;
        self.insert(MethodEntry::new(info, Arc::new(method::CurveAdapter(method))));
        self
    }

    /// Registers the strategy that the settings `S` build, as a curve method of both
    /// dimensions (the same as `register_curve(info, Strategy::<S>::new())`).
    pub fn register_strategy<S: StrategySettings>(&mut self, info: MethodInfo) -> &mut Self {
        self.register_curve(info, Strategy::<S>::new())
    }

    /// Registers the planar-only strategy that the settings `S` build: a curve method that
    /// declares itself planar-only ([`CurveMethod::planar_only`]), so that spatial points are
    /// refused before it runs and front ends list it as planar.
    pub fn register_planar_strategy<S: PlanarStrategySettings>(&mut self, info: MethodInfo) -> &mut Self {
        self.register_curve(info, PlanarStrategy::<S>::new())
    }

    /// Registers a curve method whose parameters are known only when the program runs (a
    /// method written in another language, as the Python bindings' strategies are):
    /// `schema` is the JSON Schema of its settings object (`properties`, each with a `type`
    /// and a `description` whose first line is its meaning), `defaults` its complete default
    /// settings. `M::Settings` must deserialise every object the schema admits (a map of
    /// values). The entry then lists, converts and checks its parameters as a typed one does.
    ///
    /// Errors: defaults that `M::Settings` refuses.
    pub fn register_curve_with_schema<M: CurveMethod>(
        &mut self,
        mut info: MethodInfo,
        method: M,
        schema: serde_json::Value,
        defaults: serde_json::Value,
    ) -> Result<&mut Self> {
        info.kind = MethodKind::Curve;
        let method = Arc::new(method::CurveAdapter(method));
        self.insert(MethodEntry::with_schema(info, method, schema, defaults)?);
        Ok(self)
    }

    /// Registers a surface method (replacing one of the same name).
    pub fn register_surface<M: SurfaceMethod>(&mut self, mut info: MethodInfo, method: M) -> &mut Self {
        info.kind = MethodKind::Surface;
        self.insert(MethodEntry::new(info, Arc::new(method::SurfaceAdapter(method))));
        self
    }

    /// Registers a preset of the `kind` method `base`: the same method under `info`'s name
    /// with `defaults` (a JSON object of parameter values) over the base's, and the
    /// parameters named in `pinned` fixed at those values (neither listed nor accepted).
    ///
    /// Errors: an unknown base, a default that is not a parameter of it or that it refuses.
    pub fn register_preset(
        &mut self,
        kind: MethodKind,
        base: &str,
        mut info: MethodInfo,
        defaults: serde_json::Value,
        pinned: &[&str],
    ) -> Result<&mut Self> {
        info.kind = kind;
        let entry = self.method(kind, base)?.preset(info, &defaults, pinned)?;
        self.insert(entry);
        Ok(self)
    }

    /// Registers a criterion (replacing one of the same name).
    ///
    /// # Panics
    /// When an implementation's [`name`](fairness::Criterion::name) differs from the entry's:
    /// a criterion has one name (a program's construction error, caught when the catalogue is
    /// built, before any input is read; [`CriterionEntry::of`] cannot make it).
    pub fn register_criterion(&mut self, entry: CriterionEntry) -> &mut Self {
        if let Some(other) = entry.other_name() {
            panic!(
                "criterion entry `{}` holds an implementation named `{other}`: a criterion has one name (use CriterionEntry::of)",
                entry.name()
            );
        }
        match self.criteria.iter_mut().find(|c| c.name() == entry.name()) {
            Some(slot) => *slot = entry,
            None => self.criteria.push(entry),
        }
        self
    }

    /// Registers a local indicator (replacing one of the same name).
    pub fn register_indicator(&mut self, entry: IndicatorEntry) -> &mut Self {
        match self.indicators.iter_mut().find(|c| c.name() == entry.name()) {
            Some(slot) => *slot = entry,
            None => self.indicators.push(entry),
        }
        self
    }

    /// The `kind` method called `name`; [`Error::WrongKind`] when only a method of the other
    /// kind has the name (`zhang-cheng` for a curve), else [`Error::UnknownMethod`]; both list
    /// the known ones.
    pub fn method(&self, kind: MethodKind, name: &str) -> Result<&MethodEntry> {
        if let Some(entry) = self
            .methods
            .iter()
            .find(|m| m.info.kind == kind && m.info.name == name)
        {
            return Ok(entry);
        }
        let known = self
            .methods(kind)
            .map(MethodEntry::name)
            .collect::<Vec<_>>()
            .join(", ");
        match self.methods.iter().find(|m| m.info.name == name) {
            Some(other) => Err(Error::WrongKind {
                name: name.to_owned(),
                kind: kind.name(),
                fairs: other.info.kind.name(),
                known,
            }),
            None => Err(Error::UnknownMethod {
                name: schema::clip(name, 80),
                kind: kind.name(),
                known,
            }),
        }
    }

    /// The names of every method, curve and surface, comma-separated (a name both kinds have
    /// once).
    pub fn method_names(&self) -> String {
        let mut names: Vec<&str> = Vec::new();
        for m in &self.methods {
            if !names.contains(&m.name()) {
                names.push(m.name());
            }
        }
        names.join(", ")
    }

    /// Whether a method of either kind is called `name`.
    pub fn has_method(&self, name: &str) -> bool {
        self.methods.iter().any(|m| m.info.name == name)
    }

    /// The methods of `kind`, in registration order.
    pub fn methods(&self, kind: MethodKind) -> impl Iterator<Item = &MethodEntry> {
        self.methods.iter().filter(move |m| m.info.kind == kind)
    }

    /// Every criterion, in registration order.
    pub fn criteria(&self) -> &[CriterionEntry] {
        &self.criteria
    }

    /// Every indicator, in registration order.
    pub fn indicators(&self) -> &[IndicatorEntry] {
        &self.indicators
    }

    /// The criterion called `name` (at `origin`, for the message), or an error listing the
    /// known ones.
    pub fn criterion(&self, name: &str, origin: &str) -> Result<&CriterionEntry> {
        self.criteria
            .iter()
            .find(|c| c.name() == name)
            .ok_or_else(|| Error::UnknownName {
                origin: origin.to_owned(),
                what: "a registered criterion".into(),
                name: schema::clip(name, 80),
                known: self
                    .criteria
                    .iter()
                    .map(CriterionEntry::name)
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// The indicator called `name`, or an error listing the known ones.
    pub fn indicator(&self, name: &str, origin: &str) -> Result<&IndicatorEntry> {
        self.indicators
            .iter()
            .find(|c| c.name() == name)
            .ok_or_else(|| Error::UnknownName {
                origin: origin.to_owned(),
                what: "a registered indicator".into(),
                name: schema::clip(name, 80),
                known: self
                    .indicators
                    .iter()
                    .map(IndicatorEntry::name)
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// Every registered criterion that applies to `curve`, by name, with its value or why it
    /// could not be evaluated.
    pub fn criteria_of(&self, curve: &AnyCurve) -> BTreeMap<String, Result<f64>> {
        evaluate_all(&self.criteria, curve)
    }

    /// [`criteria_of`](Self::criteria_of) for a curve of `dimension` whose energies are
    /// already measured: the criteria that are energies are read from `energies` (no second
    /// integration), and `curve()` is built only if another criterion needs it. What a report
    /// does beside its `energies` block. Fails only when the curve is needed and cannot be
    /// built.
    pub fn criteria_with<C: std::borrow::Borrow<AnyCurve>>(
        &self,
        dimension: usize,
        energies: Option<&fairness::Energies>,
        curve: impl FnOnce() -> Result<C>,
    ) -> Result<BTreeMap<String, Result<f64>>> {
        evaluate_all_with(&self.criteria, dimension, energies, curve)
    }

    /// The table `fair methods` prints: each kind's methods, their parameters indented below
    /// them with defaults and meanings, then the criteria and indicators.
    pub fn table(&self) -> String {
        let width = self.methods.iter().map(|m| m.info.name.len()).max().unwrap_or(0);
        let mut text = String::new();
        for kind in [MethodKind::Curve, MethodKind::Surface] {
            text.push_str(&format!("{} methods:\n", kind.name()));
            for method in self.methods(kind) {
                let paper = if method.info.paper.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", method.info.paper)
                };
                text.push_str(&format!(
                    "  {:width$}  {}{paper}\n",
                    method.info.name, method.info.summary
                ));
                if method.parameters.is_empty() {
                    text.push_str(&format!("  {:width$}    (no parameters)\n", ""));
                }
                for p in &method.parameters {
                    text.push_str(&format!(
                        "  {:width$}    {}={}  {}\n",
                        "", p.name, p.default, p.meaning
                    ));
                }
            }
        }
        let width = self
            .criteria
            .iter()
            .map(|c| c.name().len())
            .chain(self.indicators.iter().map(|c| c.name().len()))
            .max()
            .unwrap_or(0);
        text.push_str("criteria (--set criterion=NAME; every one is in the report's criteria):\n");
        for c in &self.criteria {
            text.push_str(&format!("  {:width$}  {}\n", c.name(), c.summary()));
        }
        text.push_str("indicators (--set indicator=NAME where a method takes one):\n");
        for c in &self.indicators {
            text.push_str(&format!("  {:width$}  {}\n", c.name(), c.summary()));
        }
        text
    }
}
