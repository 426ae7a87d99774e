//! Extending the catalogue as a user does: a settings struct declared with `settings!`, one
//! registration line, a planar-only strategy declared as such, a criterion with one name, and
//! a function's x kept by the framework whatever the method does.

use curve_repr::{Curve, Vec2, Vec3};
use fairing::catalog::{
    contract, Catalog, CriterionEntry, CurveJob, CurveKind, CurvePoints, MethodInfo, MethodKind,
    PlanarStrategySettings, StrategySettings,
};
use fairing::{Constraints, Error, FairingState, FairingStrategy, Refusal, Result, StepOutcome};
use fairness::FnCriterion;

fairing::settings! {
    /// Moves every free point by a fixed offset, once.
    pub struct Shift {
        /// The offset along x.
        pub dx: f64 = 1e-3,
        /// The offset along y.
        pub dy: f64 = 2e-3,
    }
}

impl StrategySettings for Shift {
    fn strategy<const D: usize>(&self, _: &CurveJob) -> Result<Box<dyn FairingStrategy<D>>> {
        Ok(Box::new(self.clone()))
    }
}

impl<const D: usize> FairingStrategy<D> for Shift {
    fn name(&self) -> &str {
        "shift"
    }
    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        for i in 0..state.len() {
            let mut target = state.points()[i];
            target[0] += self.dx;
            target[1] += self.dy;
            if state.is_movable(i) {
                state.move_point(i, target)?;
            }
        }
        Ok(StepOutcome::done(None))
    }
}

fairing::settings! {
    /// Halves every free point's y, once (a strategy written for planar points only).
    pub struct HalveY {
        /// Unused.
        pub factor: f64 = 0.5,
    }
}

struct Halver(f64);

impl FairingStrategy<2> for Halver {
    fn name(&self) -> &str {
        "halve-y"
    }
    fn step(&mut self, state: &mut FairingState<2>) -> Result<StepOutcome> {
        for i in 0..state.len() {
            let p = state.points()[i];
            if state.is_movable(i) {
                state.move_point(i, Vec2::new(p.x, p.y * self.0))?;
            }
        }
        Ok(StepOutcome::done(None))
    }
}

impl PlanarStrategySettings for HalveY {
    fn strategy(&self, _: &CurveJob) -> Result<Box<dyn FairingStrategy<2>>> {
        Ok(Box::new(Halver(self.factor)))
    }
}

fn catalog() -> Catalog {
    let mut catalog = Catalog::builtin();
    catalog.register_strategy::<Shift>(MethodInfo::new("shift", "moves every point by an offset"));
    catalog.register_planar_strategy::<HalveY>(MethodInfo::new("halve-y", "halves y"));
    catalog
}

fn wave(n: usize) -> Vec<Vec2> {
    (0..n)
        .map(|i| {
            let x = i as f64 / (n - 1) as f64;
            Vec2::new(x, (3.0 * x).sin())
        })
        .collect()
}

fn run(
    catalog: &Catalog,
    method: &str,
    points: &CurvePoints,
    kind: CurveKind,
) -> Result<fairing::catalog::CurveRun> {
    let entry = catalog.method(MethodKind::Curve, method)?;
    let constraints = Constraints::default();
    let job = CurveJob {
        method,
        points,
        kind,
        constraints: &constraints,
        bad_points: &[],
        catalog,
    };
    entry.fair_curve(entry.defaults(), &job)
}

#[test]
fn a_strategy_declared_with_the_macro_keeps_the_contract() {
    let catalog = catalog();
    contract::assert_curve_method(&catalog, "shift");
    contract::assert_curve_method(&catalog, "halve-y");
    let shift = catalog.method(MethodKind::Curve, "shift").unwrap();
    let names: Vec<&str> = shift.parameters().iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["dx", "dy"]);
    assert_eq!(shift.defaults()["dy"], 2e-3);
}

#[test]
fn a_function_s_x_is_kept_by_the_framework() {
    let catalog = catalog();
    let input = CurvePoints::Planar(wave(12));
    let function = run(&catalog, "shift", &input, CurveKind::Function).unwrap();
    let (a, b) = (
        input.as_dimension::<2>().unwrap(),
        function.points.as_dimension::<2>().unwrap(),
    );
    for (p, q) in a.iter().zip(b) {
        assert_eq!(p.x.to_bits(), q.x.to_bits(), "x moved: {} -> {}", p.x, q.x);
        assert!((q.y - p.y - 2e-3).abs() < 1e-12, "y not moved by the strategy");
    }
    assert_eq!(function.moved.len(), a.len());
    // A parametric curve's x is a coordinate like any other: moved.
    let parametric = run(&catalog, "shift", &input, CurveKind::Parametric).unwrap();
    let c = parametric.points.as_dimension::<2>().unwrap();
    assert!(a.iter().zip(c).all(|(p, q)| (q.x - p.x - 1e-3).abs() < 1e-12));
}

#[test]
fn a_planar_only_strategy_is_declared_and_refuses_spatial_points() {
    let catalog = catalog();
    let halve = catalog.method(MethodKind::Curve, "halve-y").unwrap();
    assert!(halve.planar_only());
    assert!(!catalog.method(MethodKind::Curve, "shift").unwrap().planar_only());
    // The built-ins declare themselves too: two-phase is Han's planar method.
    assert!(catalog
        .method(MethodKind::Curve, "two-phase")
        .unwrap()
        .planar_only());
    assert!(!catalog
        .method(MethodKind::Curve, "jump-lsq")
        .unwrap()
        .planar_only());
    let spatial = CurvePoints::Spatial((0..6).map(|i| Vec3::new(i as f64, (i * i) as f64, 0.5)).collect());
    for method in ["halve-y", "two-phase"] {
        match run(&catalog, method, &spatial, CurveKind::Parametric) {
            Err(Error::Refused {
                what: Refusal::Dimension,
                method: name,
                ..
            }) => assert_eq!(name, method),
            other => panic!("{method}: {other:?}"),
        }
    }
    let planar = run(
        &catalog,
        "halve-y",
        &CurvePoints::Planar(wave(8)),
        CurveKind::Parametric,
    )
    .unwrap();
    assert_eq!(planar.moved.len(), 7, "every point but the one on y = 0");
}

/// The number of pieces of the curve, for either dimension.
struct Pieces;

impl<const D: usize> fairness::Criterion<dyn Curve<D>> for Pieces {
    fn name(&self) -> &str {
        "pieces"
    }
    fn evaluate(&self, curve: &dyn Curve<D>) -> fairness::Result<f64> {
        Ok(curve.breaks().len().saturating_sub(1) as f64)
    }
}

#[test]
fn a_criterion_has_one_name() {
    let entry = CriterionEntry::of(Pieces, "the number of pieces");
    assert_eq!(entry.name(), "pieces");
    assert!(entry.applies_to(2) && entry.applies_to(3));
    let mut catalog = Catalog::new();
    catalog.register_criterion(entry);
    let spline = curve_repr::HermiteSpline::natural(&wave(9)).unwrap();
    let any = fairing::catalog::AnyCurve::new::<2, _>(spline).unwrap();
    assert_eq!(catalog.criteria_of(&any)["pieces"].as_ref().unwrap(), &8.0);
}

#[test]
#[should_panic(expected = "criterion entry `length` holds an implementation named `chord`")]
fn a_criterion_registered_under_another_name_is_refused() {
    let chord = FnCriterion::<dyn Curve<2>, _>::new("chord", |_: &(dyn Curve<2> + 'static)| Ok(1.0));
    Catalog::new().register_criterion(CriterionEntry::new("length", "the chord").planar(chord));
}
