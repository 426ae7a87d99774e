//! The contract every method of the catalogue keeps, checked for all of them with one test
//! body (truck's style): on random point sets of both dimensions and both kinds, under every
//! kind of constraint, a method either fairs — the output has the input's length and
//! dimension, no NaN, fixed points and clamped ends bit for bit, every point within the
//! tolerance band and its restraining radius — or refuses with an error naming the method;
//! it never panics. A method registered by a user gets the same check for free (the test
//! registers one).

use std::panic::{catch_unwind, AssertUnwindSafe};

use curve_repr::{Vec2, Vec3, Vector};
use fairing::catalog::{
    Catalog, CurveJob, CurveKind, CurvePoints, Grid, MethodKind, ParameterMap, Settings, Strategy,
    StrategySettings, SurfaceJob,
};
use fairing::{Constraints, EndClamp, FairingState, FairingStrategy, Result, StepOutcome};
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

/// Noisy samples of a sine (x increasing) and of a helix.
fn planar(seed: u64, n: usize) -> Vec<Vec2> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let mut x = 0.0;
    (0..n)
        .map(|_| {
            x += 0.5 + rng.random::<f64>();
            Vec2::new(x, (0.3 * x).sin() * 4.0 + 0.05 * (rng.random::<f64>() - 0.5))
        })
        .collect()
}

fn spatial(seed: u64, n: usize) -> Vec<Vec3> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    (0..n)
        .map(|k| {
            let t = 0.35 * k as f64;
            let e = 0.03 * (rng.random::<f64>() - 0.5);
            Vec3::new(3.0 * t.cos() + e, 3.0 * t.sin() - e, 0.8 * t + e)
        })
        .collect()
}

/// The constraint sets every method is run under, for `n` points.
fn constraint_sets(seed: u64, n: usize) -> Vec<(&'static str, Constraints)> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ 0x5eed);
    let radii: Vec<f64> = (0..n).map(|_| 0.02 * rng.random::<f64>()).collect();
    vec![
        ("none", Constraints::default()),
        ("fixed", Constraints::default().with_fixed([3, n / 2, n - 4])),
        ("tolerance", Constraints::default().with_tolerance(0.01)),
        (
            "fixed+tolerance+g0",
            Constraints::default()
                .with_fixed([5])
                .with_tolerance(0.02)
                .with_end_clamp(EndClamp::G0),
        ),
        ("radii", Constraints::default().with_restraining_radii(radii)),
        ("g1", Constraints::default().with_end_clamp(EndClamp::G1)),
        ("g2", Constraints::default().with_end_clamp(EndClamp::G2)),
    ]
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

fn check_points<const D: usize>(
    what: &str,
    original: &[Vector<D>],
    faired: &[Vector<D>],
    constraints: &Constraints,
) {
    assert_eq!(faired.len(), original.len(), "{what}: length");
    let n = original.len();
    for (i, (p, q)) in original.iter().zip(faired).enumerate() {
        assert!(q.iter().all(|c| c.is_finite()), "{what}: point {i} is not finite");
        if constraints.fixed().contains(&i) || constraints.is_clamped_end(i, n) {
            assert_eq!(p, q, "{what}: fixed point {i} moved");
        }
        let distance = (q - p).norm();
        assert!(
            distance <= constraints.allowed_distance(i),
            "{what}: point {i} moved {distance}, allowed {}",
            constraints.allowed_distance(i)
        );
    }
}

#[test]
fn every_curve_method_keeps_the_contract() {
    let catalog = catalog();
    let names: Vec<String> = catalog
        .methods(MethodKind::Curve)
        .map(|m| m.name().to_owned())
        .collect();
    assert!(names.len() >= 9, "{names:?}");
    let n = 24;
    for seed in [1, 2] {
        let cases = [
            (
                "planar function",
                CurvePoints::Planar(planar(seed, n)),
                CurveKind::Function,
            ),
            (
                "planar parametric",
                CurvePoints::Planar(planar(seed, n)),
                CurveKind::Parametric,
            ),
            (
                "spatial",
                CurvePoints::Spatial(spatial(seed, n)),
                CurveKind::Parametric,
            ),
        ];
        for name in &names {
            let entry = catalog.method(MethodKind::Curve, name).unwrap();
            let settings = quick(&catalog, MethodKind::Curve, name);
            for (case, points, kind) in &cases {
                for (label, constraints) in constraint_sets(seed, n) {
                    let what = format!("{name} on {case} (seed {seed}) with {label}");
                    let job = CurveJob {
                        method: name,
                        points,
                        kind: *kind,
                        constraints: &constraints,
                        bad_points: &[],
                        catalog: &catalog,
                    };
                    let result = catch_unwind(AssertUnwindSafe(|| entry.fair_curve(&settings, &job)))
                        .unwrap_or_else(|_| panic!("{what}: panicked"));
                    match result {
                        Ok(run) => {
                            match (points, &run.points) {
                                (CurvePoints::Planar(a), CurvePoints::Planar(b)) => {
                                    check_points(&what, a, b, &constraints)
                                }
                                (CurvePoints::Spatial(a), CurvePoints::Spatial(b)) => {
                                    check_points(&what, a, b, &constraints)
                                }
                                _ => panic!("{what}: the dimension changed"),
                            }
                            assert!(!run.termination.is_empty(), "{what}: no termination");
                            assert!(
                                run.termination
                                    .chars()
                                    .all(|c| c.is_ascii_lowercase() || c == '-'),
                                "{what}: termination `{}` is not kebab-case",
                                run.termination
                            );
                            assert!(run.elapsed_ms.is_finite() && run.elapsed_ms >= 0.0);
                            assert_eq!(run.moved, points.differences(&run.points), "{what}: moved");
                        }
                        Err(e) => {
                            let message = e.to_string();
                            assert!(
                                message.contains(name.as_str()),
                                "{what}: `{message}` does not name the method"
                            );
                            // Without constraints on planar points every method fairs.
                            assert!(
                                !(label == "none" && *case != "spatial"),
                                "{what}: failed without constraints: {message}"
                            );
                        }
                    }
                }
            }
            // Bad points for a method that takes none: refused, naming the method.
            if !entry.takes_bad_points() {
                let constraints = Constraints::default();
                let job = CurveJob {
                    method: name,
                    points: &cases[1].1,
                    kind: CurveKind::Parametric,
                    constraints: &constraints,
                    bad_points: &[4],
                    catalog: &catalog,
                };
                let e = entry.fair_curve(&settings, &job).unwrap_err();
                assert!(
                    matches!(
                        e,
                        fairing::Error::Refused {
                            what: fairing::Refusal::BadPoints,
                            ..
                        }
                    ),
                    "{name}: {e}"
                );
                assert!(e.to_string().contains(name.as_str()), "{e}");
            }
        }
    }
}

#[test]
fn every_surface_method_keeps_the_contract() {
    let catalog = catalog();
    let (rows, columns) = (7, 8);
    let mut rng = rand::rngs::StdRng::seed_from_u64(9);
    let points: Vec<Vec3> = (0..rows * columns)
        .map(|k| {
            let (i, j) = ((k / columns) as f64, (k % columns) as f64);
            Vec3::new(
                i,
                j,
                0.2 * (0.5 * i).sin() * (0.4 * j).cos() + 0.02 * rng.random::<f64>(),
            )
        })
        .collect();
    let grid = Grid {
        rows,
        columns,
        points,
    };
    for entry in catalog.methods(MethodKind::Surface) {
        let name = entry.name();
        let settings = quick(&catalog, MethodKind::Surface, name);
        for (label, constraints) in constraint_sets(3, rows * columns) {
            let what = format!("{name} with {label}");
            let job = SurfaceJob {
                method: name,
                grid: &grid,
                constraints: &constraints,
                bad_points: &[],
                catalog: &catalog,
            };
            let result = catch_unwind(AssertUnwindSafe(|| entry.fair_surface(&settings, &job)))
                .unwrap_or_else(|_| panic!("{what}: panicked"));
            match result {
                Ok(run) => {
                    assert_eq!((run.grid.rows, run.grid.columns), (rows, columns), "{what}");
                    check_points(&what, &grid.points, &run.grid.points, &constraints);
                    if constraints.end_clamp() == EndClamp::G0 {
                        for k in grid.boundary() {
                            assert_eq!(
                                grid.points[k], run.grid.points[k],
                                "{what}: boundary point {k} moved"
                            );
                        }
                    }
                }
                Err(e) => {
                    let message = e.to_string();
                    assert!(
                        message.contains(name),
                        "{what}: `{message}` does not name the method"
                    );
                    assert!(label != "none", "{what}: failed without constraints: {message}");
                }
            }
        }
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
