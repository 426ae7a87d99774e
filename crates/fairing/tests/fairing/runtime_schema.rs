//! A curve method whose settings schema is given when the program runs
//! (`Catalog::register_curve_with_schema`, what the Python bindings' strategies use): its
//! parameters are listed, converted, checked and passed to the run as a typed method's.

use curve_repr::Vec2;
use fairing::catalog::{
    run_strategy, Catalog, CurveJob, CurveKind, CurveMethod, CurvePoints, CurveRun, MethodInfo, MethodKind,
    ParameterMap, Settings,
};
use fairing::{Constraints, Error, FairingState, FairingStrategy, Result, StepOutcome};
use serde_json::{json, Map, Value};

/// Any object: the schema says which names it has.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(transparent)]
struct Loose(Map<String, Value>);

impl Settings for Loose {}

/// Moves point 1 up by the setting `lift`, once.
struct Lift;

struct LiftStep(f64);

impl FairingStrategy<2> for LiftStep {
    fn name(&self) -> &str {
        "lift"
    }
    fn step(&mut self, state: &mut FairingState<2>) -> Result<StepOutcome> {
        let p = state.points()[1];
        state.move_point(1, p + Vec2::new(0.0, self.0))?;
        Ok(StepOutcome::done(None))
    }
}

impl CurveMethod for Lift {
    type Settings = Loose;
    fn run(&self, settings: &Loose, job: &CurveJob) -> Result<CurveRun> {
        let lift = settings.0.get("lift").and_then(Value::as_f64).unwrap_or(f64::NAN);
        match job.points {
            CurvePoints::Planar(p) => run_strategy(Box::new(LiftStep(lift)), p, job, 10),
            CurvePoints::Spatial(_) => Err(Error::Strategy {
                strategy: "lift".into(),
                reason: "planar only".into(),
            }),
        }
    }
}

fn schema() -> Value {
    json!({
        "type": "object",
        "properties": {
            "lift": {"type": "number", "description": "How far point 1 moves up."},
            "label": {"type": "string"},
        },
    })
}

fn catalog() -> Catalog {
    let mut catalog = Catalog::new();
    catalog
        .register_curve_with_schema(
            MethodInfo::new("lift", "moves point 1 up"),
            Lift,
            schema(),
            json!({"lift": 0.0, "label": "x"}),
        )
        .unwrap();
    catalog
}

#[test]
fn the_given_schema_is_the_parameter_table() {
    let catalog = catalog();
    let entry = catalog.method(MethodKind::Curve, "lift").unwrap();
    let lift = entry.parameter("lift").unwrap();
    assert_eq!(
        (lift.meaning.as_str(), lift.default_value.clone()),
        ("How far point 1 moves up", json!(0.0))
    );
    assert!(entry.parameter("label").is_some() && entry.parameter("speed").is_none());
    assert!(catalog.table().contains("lift=0"));
}

#[test]
fn given_values_are_converted_by_the_schema_and_reach_the_run() {
    let catalog = catalog();
    let entry = catalog.method(MethodKind::Curve, "lift").unwrap();
    let points = CurvePoints::Planar((0..5).map(|i| Vec2::new(i as f64, 0.0)).collect());
    let constraints = Constraints::default();
    let job = CurveJob {
        method: "lift",
        points: &points,
        kind: CurveKind::Parametric,
        constraints: &constraints,
        bad_points: &[],
        catalog: &catalog,
    };
    let moved = |text: &str| {
        let settings = entry
            .settings(&ParameterMap::from_sets([("lift", text)]))
            .unwrap();
        assert!(
            settings["lift"].is_number(),
            "`--set lift={text}` is read as the schema's number"
        );
        entry.fair_curve(&settings, &job).unwrap().moved
    };
    assert_eq!(moved("0"), Vec::<usize>::new());
    assert_eq!(moved("0.25"), vec![1]);
    // An unknown name is refused with the known ones.
    let error = entry
        .settings(&ParameterMap::from_sets([("speed", "1")]))
        .unwrap_err();
    assert!(error.to_string().contains("label, lift"), "{error}");
}

#[test]
fn defaults_the_settings_type_refuses_are_refused_at_registration() {
    /// A typed settings struct: no field `lift`.
    #[derive(
        Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
    )]
    #[serde(default, deny_unknown_fields)]
    struct Strict {
        /// A count.
        count: usize,
    }
    impl Settings for Strict {}
    struct Idle;
    impl CurveMethod for Idle {
        type Settings = Strict;
        fn run(&self, _: &Strict, _: &CurveJob) -> Result<CurveRun> {
            unreachable!("never registered")
        }
    }
    let mut catalog = Catalog::new();
    let refused = catalog.register_curve_with_schema(
        MethodInfo::new("idle", "nothing"),
        Idle,
        schema(),
        json!({"lift": 1.0}),
    );
    assert!(refused.is_err());
    assert!(catalog.methods(MethodKind::Curve).next().is_none());
}
