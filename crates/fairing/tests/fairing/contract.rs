//! The contract every method of the catalogue keeps, checked for all of them with one test
//! body (truck's style): on random point sets of both dimensions and both kinds, under every
//! kind of constraint, a method either fairs — the output has the input's length and
//! dimension, no NaN, fixed points and clamped ends bit for bit, every point within the
//! tolerance band and its restraining radius — or refuses with an error naming the method;
//! it never panics. A method registered by a user gets the same check for free (the test
//! registers one).

use curve_repr::Vec2;
use fairing::catalog::{
    contract, Catalog, CurveJob, CurveKind, CurvePoints, MethodKind, ParameterMap, Settings, Strategy,
    StrategySettings,
};
use fairing::{Constraints, FairingState, FairingStrategy, Result, StepOutcome};
use rand::{RngExt, SeedableRng};

/// A user's strategy: every free interior point a third of the way to its neighbours' midpoint.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
struct ShrinkSettings {
    /// Passes over the points.
    passes: usize,
}

impl Default for ShrinkSettings {
    fn default() -> Self {
        ShrinkSettings { passes: 3 }
    }
}

impl Settings for ShrinkSettings {}

struct Shrink {
    passes: usize,
}

impl<const D: usize> FairingStrategy<D> for Shrink {
    fn name(&self) -> &str {
        "shrink"
    }
    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        for i in 1..state.len().saturating_sub(1) {
            let p = state.points();
            let target = p[i] + ((p[i - 1] + p[i + 1]) / 2.0 - p[i]) / 3.0;
            state.move_point(i, target)?;
        }
        self.passes = self.passes.saturating_sub(1);
        Ok(if self.passes == 0 {
            StepOutcome::done(None)
        } else {
            StepOutcome::running(None)
        })
    }
}

impl StrategySettings for ShrinkSettings {
    fn strategy<const D: usize>(&self, _: &CurveJob) -> Result<Box<dyn FairingStrategy<D>>> {
        Ok(Box::new(Shrink { passes: self.passes }))
    }
}

fn catalog() -> Catalog {
    let mut catalog = Catalog::builtin();
    catalog.register_curve(
        fairing::catalog::MethodInfo::new("shrink", "a user's test strategy"),
        Strategy::<ShrinkSettings>::new(),
    );
    catalog
}

/// Short runs: the contract holds after any number of steps.
fn quick(catalog: &Catalog, kind: MethodKind, name: &str) -> serde_json::Value {
    let entry = catalog.method(kind, name).unwrap();
    let mut given = ParameterMap::new();
    for limit in ["max-iterations", "max-steps", "max-passes"] {
        if entry.parameter(limit).is_some() {
            given.insert_text(limit, "15", "test");
        }
    }
    entry.settings(&given).unwrap()
}

/// The library's public contract check (`fairing::catalog::contract`), on every curve
/// method, the user's `shrink` included.
#[test]
fn every_curve_method_keeps_the_contract() {
    let catalog = catalog();
    let names: Vec<String> = catalog
        .methods(MethodKind::Curve)
        .map(|m| m.name().to_owned())
        .collect();
    assert!(names.len() >= 9, "{names:?}");
    assert!(names.iter().any(|n| n == "shrink"));
    for name in &names {
        contract::assert_curve_method(&catalog, name);
    }
}

#[test]
fn every_surface_method_keeps_the_contract() {
    let catalog = catalog();
    let names: Vec<String> = catalog
        .methods(MethodKind::Surface)
        .map(|m| m.name().to_owned())
        .collect();
    assert!(!names.is_empty());
    for name in &names {
        if let Err(failure) = contract::check_surface_method(&catalog, name) {
            panic!("{failure}");
        }
    }
}

/// The check can fail: a strategy that refuses every input is caught, named, with its case.
#[test]
fn the_contract_check_catches_a_moved_fixed_point() {
    let mut catalog = Catalog::builtin();
    catalog.register_curve(
        fairing::catalog::MethodInfo::new("cheat", "refuses everything"),
        Strategy::<CheatSettings>::new(),
    );
    let failure = contract::check_curve_method(&catalog, "cheat").unwrap_err();
    assert_eq!(failure.method, "cheat");
    assert!(failure.case.contains("with none"), "{failure}");
    assert!(
        failure.to_string().contains("refused without constraints"),
        "{failure}"
    );
    assert!(contract::check_curve_method(&catalog, "no-such-method").is_err());
}

/// A strategy breaking the contract: it refuses even unconstrained planar points.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
struct CheatSettings {}

impl Settings for CheatSettings {}

struct Cheat;

impl<const D: usize> FairingStrategy<D> for Cheat {
    fn name(&self) -> &str {
        "cheat"
    }
    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        let _ = state;
        Err(fairing::strategy_error("cheat", "refuses every input"))
    }
}

impl StrategySettings for CheatSettings {
    fn strategy<const D: usize>(&self, _: &CurveJob) -> Result<Box<dyn FairingStrategy<D>>> {
        Ok(Box::new(Cheat))
    }
}

/// A noisy ellipse of `n` distinct points with its first point repeated as the last.
fn closed_ellipse(seed: u64, n: usize) -> Vec<Vec2> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let mut points: Vec<Vec2> = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            let r = 1.0 + 0.01 * (rng.random::<f64>() - 0.5);
            Vec2::new(2.0 * r * t.cos(), r * t.sin())
        })
        .collect();
    points.push(points[0]);
    points
}

/// A repeated first point means closed for every curve method (issue 44): each returns a
/// polygon whose last point is its first, bit for bit, or refuses naming the method and
/// the closed curve; with `closed = true` given too (where the method has the parameter)
/// the repeat is not taken for two coincident points.
#[test]
fn every_curve_method_keeps_a_repeated_first_point_closed() {
    let catalog = catalog();
    let points = CurvePoints::Planar(closed_ellipse(5, 40));
    let constraints = Constraints::default();
    for entry in catalog.methods(MethodKind::Curve) {
        let name = entry.name();
        let mut variants = vec![("as given", quick(&catalog, MethodKind::Curve, name))];
        if entry.parameter("closed").is_some() {
            let mut given = ParameterMap::new();
            for limit in ["max-iterations", "max-steps", "max-passes"] {
                if entry.parameter(limit).is_some() {
                    given.insert_text(limit, "15", "test");
                }
            }
            given.insert_text("closed", "true", "test");
            variants.push(("closed = true", entry.settings(&given).unwrap()));
        }
        for (label, settings) in variants {
            let what = format!("{name} ({label}) on a closed ellipse");
            let job = CurveJob {
                method: name,
                points: &points,
                kind: CurveKind::Parametric,
                constraints: &constraints,
                bad_points: &[],
                catalog: &catalog,
            };
            match entry.fair_curve(&settings, &job) {
                Ok(run) => {
                    let CurvePoints::Planar(faired) = &run.points else {
                        panic!("{what}: the dimension changed");
                    };
                    assert_eq!(faired.len(), 41, "{what}: length");
                    assert_eq!(faired[0], faired[40], "{what}: the curve was opened");
                }
                Err(e) => {
                    let message = e.to_string();
                    assert!(
                        message.contains(name) && message.contains("closed"),
                        "{what}: `{message}` is not a refusal naming the method and the closed curve"
                    );
                }
            }
        }
    }
}

/// A one-stage plan of a curve method with [`quick`]'s settings.
fn quick_plan(catalog: &Catalog, name: &str) -> fairing::catalog::Plan {
    fairing::catalog::Plan {
        kind: MethodKind::Curve,
        stages: vec![fairing::catalog::Stage {
            method: name.to_owned(),
            given: ParameterMap::new(),
            settings: quick(catalog, MethodKind::Curve, name),
        }],
        constraints: Default::default(),
    }
}

/// A closed teardrop: a noisy arc of radius 1 round the origin from 40° to 320° closed by two
/// straight edges to a sharp tip at (2, 0) (a turn of about 100°), the tip first and repeated
/// last; `n` points on the arc, 8 on each edge.
fn teardrop(seed: u64, n: usize) -> Vec<Vec2> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let mut noise = || 0.002 * (rng.random::<f64>() - 0.5);
    let tip = Vec2::new(2.0, 0.0);
    let (start, end) = (40f64.to_radians(), 320f64.to_radians());
    let at = |t: f64| Vec2::new(t.cos(), t.sin());
    let mut points = vec![tip];
    for k in 1..8 {
        let w = k as f64 / 8.0;
        let p = tip * (1.0 - w) + at(start) * w;
        points.push(Vec2::new(p.x + noise(), p.y + noise()));
    }
    for k in 0..n {
        let t = start + (end - start) * k as f64 / (n - 1) as f64;
        let p = at(t);
        points.push(Vec2::new(p.x + noise(), p.y + noise()));
    }
    for k in 1..8 {
        let w = k as f64 / 8.0;
        let p = at(end) * (1.0 - w) + tip * w;
        points.push(Vec2::new(p.x + noise(), p.y + noise()));
    }
    points.push(tip);
    points
}

/// Corners stay corners (issue 44): on a closed teardrop every curve method run through the
/// catalogue's plan keeps the detected tip bit for bit and the curve closed (or refuses, naming
/// the closed curve), and the report names the corner; with `--corners none` the default
/// method rounds the tip, moving it inwards.
#[test]
fn every_curve_method_keeps_a_detected_corner() {
    use fairing::catalog::PlanConstraints;
    use fairing::corners::Corners;
    let catalog = catalog();
    let points = teardrop(3, 60);
    let n = points.len();
    let input = CurvePoints::Planar(points.clone());
    let plan_of = |name: &str| quick_plan(&catalog, name);
    for entry in catalog.methods(MethodKind::Curve) {
        let name = entry.name();
        let run = catalog.run_curve_plan(
            &plan_of(name),
            &input,
            CurveKind::Parametric,
            &PlanConstraints::default(),
        );
        match run {
            Ok(run) => {
                let CurvePoints::Planar(faired) = &run.points else {
                    panic!("{name}: the dimension changed");
                };
                if run.represented.is_some() {
                    // nurbs-weights: its own curve over the unchanged points, run whole.
                    assert!(run.moved.is_empty(), "{name}");
                    assert!(!run.extras.contains_key("corners"), "{name}");
                    continue;
                }
                assert_eq!(run.extras["corners"], serde_json::json!([0]), "{name}");
                assert_eq!(faired[0], points[0], "{name}: the tip moved");
                assert_eq!(faired[n - 1], faired[0], "{name}: the curve was opened");
            }
            Err(e) => {
                let message = e.to_string();
                assert!(message.contains("closed"), "{name}: `{message}`");
            }
        }
    }
    let none = PlanConstraints {
        corners: Corners::None,
        ..PlanConstraints::default()
    };
    let rounded = catalog
        .run_curve_plan(&plan_of("jump-lsq"), &input, CurveKind::Parametric, &none)
        .unwrap();
    let CurvePoints::Planar(rounded) = rounded.points else {
        panic!("dimension")
    };
    assert!(rounded[0].x < 2.0 - 1e-3, "the tip at {:?}", rounded[0]);
}

/// A function with a knuckle (a V of slopes −1 and +1 plus a gentle parabola, noisy): every
/// method that fairs functions keeps the knuckle point, the two pieces are faired apart, and
/// declared corners past the last point are refused naming `--corners`.
#[test]
fn a_functions_knuckle_is_kept_and_declared_corners_are_checked() {
    use fairing::catalog::PlanConstraints;
    use fairing::corners::Corners;
    let catalog = catalog();
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    let points: Vec<Vec2> = (0..61)
        .map(|k| {
            let x = k as f64 / 60.0;
            Vec2::new(
                x,
                (x - 0.5).abs() + 0.3 * x * x + 0.002 * (rng.random::<f64>() - 0.5),
            )
        })
        .collect();
    let input = CurvePoints::Planar(points.clone());
    let plan_of = |name: &str| quick_plan(&catalog, name);
    for entry in catalog.methods(MethodKind::Curve) {
        let name = entry.name();
        let Ok(run) = catalog.run_curve_plan(
            &plan_of(name),
            &input,
            CurveKind::Function,
            &PlanConstraints::default(),
        ) else {
            continue;
        };
        let CurvePoints::Planar(faired) = &run.points else {
            panic!("{name}: the dimension changed");
        };
        if run.represented.is_some() {
            // nurbs-weights: its own curve over the unchanged points, run whole.
            assert_eq!(faired[30], points[30], "{name}");
            continue;
        }
        assert_eq!(run.extras["corners"], serde_json::json!([30]), "{name}");
        assert_eq!(run.extras["pieces"].as_array().map(Vec::len), Some(2), "{name}");
        assert_eq!(faired[30], points[30], "{name}: the knuckle moved");
    }
    let past = PlanConstraints {
        corners: Corners::At(vec![61]),
        ..PlanConstraints::default()
    };
    let e = catalog
        .run_curve_plan(&plan_of("jump-lsq"), &input, CurveKind::Function, &past)
        .unwrap_err();
    assert!(
        e.to_string().contains("--corners") && e.to_string().contains("61"),
        "{e}"
    );
}

/// A closed teardrop whose repeated last point is the one fixed: the pieces between corners
/// keep it (and so the first point) bit for bit, for every method that fairs the curve.
#[test]
fn a_fixed_repeated_point_stays_fixed_when_the_curve_is_split_at_corners() {
    use fairing::catalog::PlanConstraints;
    let catalog = catalog();
    let mut points = teardrop(5, 40);
    let n = points.len();
    // Move the only corner off the seam: rotate so that the tip is interior, and repeat.
    points.pop();
    points.rotate_left(10);
    points.push(points[0]);
    let input = CurvePoints::Planar(points.clone());
    let fixed_last = PlanConstraints {
        fixed: vec![n - 1],
        ..PlanConstraints::default()
    };
    for name in ["jump-lsq", "two-phase", "smoothing-spline"] {
        let run = catalog
            .run_curve_plan(
                &quick_plan(&catalog, name),
                &input,
                CurveKind::Parametric,
                &fixed_last,
            )
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let CurvePoints::Planar(faired) = &run.points else {
            panic!("{name}: the dimension changed");
        };
        assert!(
            run.extras["corners"].as_array().is_some_and(|c| !c.is_empty()),
            "{name}"
        );
        assert_eq!(faired[n - 1], points[n - 1], "{name}: the fixed point moved");
        assert_eq!(faired[0], points[0], "{name}: its first copy moved");
    }
}
