//! The contract every curve and surface method keeps, as a public check a user's own test
//! calls on its own method (`docs/CONTRACT.md`).
//!
//! On seeded noisy point sets of both dimensions and both kinds, under every kind of
//! constraint, a method either fairs — the output has the input's length and dimension, no
//! NaN, fixed points and clamped ends bit for bit, every point within the tolerance band and
//! its restraining radius, a kebab-case termination — or refuses with an error naming the
//! method; it never panics. Without constraints on planar points every method fairs. The
//! runs are short (15 iterations, steps or passes where the method has such a limit): the
//! contract holds after any number of steps. Cost: 42 short runs per seed, two seeds.
//!
//! ```
//! use fairing::catalog::{contract, Catalog};
//! contract::check_curve_method(&Catalog::builtin(), "two-phase").unwrap();
//! ```

use std::fmt;
use std::panic::{catch_unwind, AssertUnwindSafe};

use curve_repr::{Vec2, Vec3, Vector};

use super::{Catalog, CurveJob, CurveKind, CurvePoints, Grid, MethodKind, ParameterMap, SurfaceJob};
use crate::{Constraints, EndClamp, Error, Refusal};

/// A broken promise: which method, on which case, and what went wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ContractFailure {
    /// The method's name.
    pub method: String,
    /// The case: points, seed and constraints.
    pub case: String,
    /// What was broken.
    pub message: String,
}

impl fmt::Display for ContractFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} on {}: {}", self.method, self.case, self.message)
    }
}

impl std::error::Error for ContractFailure {}

/// Seeds of the cases; fixed, so a failure is reproducible.
const SEEDS: [u64; 2] = [1, 2];
/// Points per curve case.
const POINTS: usize = 24;

/// SplitMix64: a deterministic source of the cases' noise, in [0, 1).
struct Noise(u64);

impl Noise {
    fn new(seed: u64) -> Self {
        Noise(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0x5eed)
    }
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Noisy samples of a sine, x increasing.
fn planar(seed: u64, n: usize) -> Vec<Vec2> {
    let mut noise = Noise::new(seed);
    let mut x = 0.0;
    (0..n)
        .map(|_| {
            x += 0.5 + noise.next();
            Vec2::new(x, (0.3 * x).sin() * 4.0 + 0.05 * (noise.next() - 0.5))
        })
        .collect()
}

/// Noisy samples of a helix.
fn spatial(seed: u64, n: usize) -> Vec<Vec3> {
    let mut noise = Noise::new(seed);
    (0..n)
        .map(|k| {
            let t = 0.35 * k as f64;
            let e = 0.03 * (noise.next() - 0.5);
            Vec3::new(3.0 * t.cos() + e, 3.0 * t.sin() - e, 0.8 * t + e)
        })
        .collect()
}

/// The constraint sets every method is run under, for `n` points.
fn constraint_sets(seed: u64, n: usize) -> Vec<(&'static str, Constraints)> {
    let mut noise = Noise::new(seed ^ 0x5eed);
    let radii: Vec<f64> = (0..n).map(|_| 0.02 * noise.next()).collect();
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

/// The method's settings for short runs.
fn quick(catalog: &Catalog, kind: MethodKind, name: &str) -> crate::Result<serde_json::Value> {
    let entry = catalog.method(kind, name)?;
    let mut given = ParameterMap::new();
    for limit in ["max-iterations", "max-steps", "max-passes"] {
        if entry.parameter(limit).is_some() {
            given.insert_text(limit, "15", "contract");
        }
    }
    entry.settings(&given)
}

/// Length, finiteness, fixed points bit for bit, band and radii held.
fn check_points<const D: usize>(
    original: &[Vector<D>],
    faired: &[Vector<D>],
    constraints: &Constraints,
) -> Result<(), String> {
    if faired.len() != original.len() {
        return Err(format!("{} points in, {} out", original.len(), faired.len()));
    }
    let n = original.len();
    for (i, (p, q)) in original.iter().zip(faired).enumerate() {
        if !q.iter().all(|c| c.is_finite()) {
            return Err(format!("point {i} is not finite"));
        }
        if (constraints.fixed().contains(&i) || constraints.is_clamped_end(i, n)) && p != q {
            return Err(format!("fixed point {i} moved"));
        }
        let distance = (q - p).norm();
        if distance > constraints.allowed_distance(i) {
            return Err(format!(
                "point {i} moved {distance}, allowed {}",
                constraints.allowed_distance(i)
            ));
        }
    }
    Ok(())
}

/// Checks the curve method `name` of `catalog` against the contract (module doc), returning
/// the first broken promise.
pub fn check_curve_method(catalog: &Catalog, name: &str) -> Result<(), ContractFailure> {
    let fail = |case: &str, message: String| ContractFailure {
        method: name.to_owned(),
        case: case.to_owned(),
        message,
    };
    let entry = catalog
        .method(MethodKind::Curve, name)
        .map_err(|e| fail("the catalogue", e.to_string()))?;
    let settings =
        quick(catalog, MethodKind::Curve, name).map_err(|e| fail("its defaults", e.to_string()))?;
    for seed in SEEDS {
        let cases = [
            (
                "planar function",
                CurvePoints::Planar(planar(seed, POINTS)),
                CurveKind::Function,
            ),
            (
                "planar parametric",
                CurvePoints::Planar(planar(seed, POINTS)),
                CurveKind::Parametric,
            ),
            (
                "spatial",
                CurvePoints::Spatial(spatial(seed, POINTS)),
                CurveKind::Parametric,
            ),
        ];
        for (case, points, kind) in &cases {
            for (label, constraints) in constraint_sets(seed, POINTS) {
                let what = format!("{case} (seed {seed}) with {label}");
                let job = CurveJob {
                    method: name,
                    points,
                    kind: *kind,
                    constraints: &constraints,
                    bad_points: &[],
                    catalog,
                };
                let result = catch_unwind(AssertUnwindSafe(|| entry.fair_curve(&settings, &job)))
                    .map_err(|_| fail(&what, "panicked".into()))?;
                match result {
                    Ok(run) => {
                        match (points, &run.points) {
                            (CurvePoints::Planar(a), CurvePoints::Planar(b)) => {
                                check_points(a, b, &constraints)
                            }
                            (CurvePoints::Spatial(a), CurvePoints::Spatial(b)) => {
                                check_points(a, b, &constraints)
                            }
                            _ => Err("the dimension changed".into()),
                        }
                        .map_err(|m| fail(&what, m))?;
                        let kebab = |c: char| c.is_ascii_lowercase() || c == '-';
                        if run.termination.is_empty() || !run.termination.chars().all(kebab) {
                            return Err(fail(
                                &what,
                                format!("termination `{}` is not kebab-case", run.termination),
                            ));
                        }
                        if !(run.elapsed_ms.is_finite() && run.elapsed_ms >= 0.0) {
                            return Err(fail(&what, format!("elapsed time {} ms", run.elapsed_ms)));
                        }
                        if run.moved != points.differences(&run.points) {
                            return Err(fail(
                                &what,
                                "`moved` is not the number of points that moved".into(),
                            ));
                        }
                    }
                    Err(e) => {
                        let message = e.to_string();
                        if !message.contains(name) {
                            return Err(fail(&what, format!("`{message}` does not name the method")));
                        }
                        if label == "none" && *case != "spatial" {
                            return Err(fail(&what, format!("refused without constraints: {message}")));
                        }
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
                catalog,
            };
            let what = format!("bad points (seed {seed})");
            let result = catch_unwind(AssertUnwindSafe(|| entry.fair_curve(&settings, &job)))
                .map_err(|_| fail(&what, "panicked".into()))?;
            match result {
                Ok(_) => return Err(fail(&what, "bad points were not refused".into())),
                Err(
                    e @ Error::Refused {
                        what: Refusal::BadPoints,
                        ..
                    },
                ) if e.to_string().contains(name) => {}
                Err(e) => {
                    return Err(fail(
                        &what,
                        format!("`{e}` is not a bad-points refusal naming the method"),
                    ))
                }
            }
        }
    }
    Ok(())
}

/// [`check_curve_method`], panicking with the broken promise: for a user's `#[test]`.
///
/// # Panics
/// When the method breaks the contract.
pub fn assert_curve_method(catalog: &Catalog, name: &str) {
    if let Err(failure) = check_curve_method(catalog, name) {
        panic!("contract broken: {failure}");
    }
}

/// Checks the surface method `name` of `catalog`: on a seeded noisy 7 × 8 grid under every
/// constraint set it fairs (same grid shape, points checked as for curves, the boundary kept
/// under G0) or refuses naming the method; without constraints it fairs; it never panics.
pub fn check_surface_method(catalog: &Catalog, name: &str) -> Result<(), ContractFailure> {
    let fail = |case: &str, message: String| ContractFailure {
        method: name.to_owned(),
        case: case.to_owned(),
        message,
    };
    let entry = catalog
        .method(MethodKind::Surface, name)
        .map_err(|e| fail("the catalogue", e.to_string()))?;
    let settings =
        quick(catalog, MethodKind::Surface, name).map_err(|e| fail("its defaults", e.to_string()))?;
    let (rows, columns) = (7, 8);
    let mut noise = Noise::new(9);
    let points: Vec<Vec3> = (0..rows * columns)
        .map(|k| {
            let (i, j) = ((k / columns) as f64, (k % columns) as f64);
            Vec3::new(
                i,
                j,
                0.2 * (0.5 * i).sin() * (0.4 * j).cos() + 0.02 * noise.next(),
            )
        })
        .collect();
    let grid = Grid {
        rows,
        columns,
        points,
    };
    for (label, constraints) in constraint_sets(3, rows * columns) {
        let what = format!("a 7 × 8 grid with {label}");
        let job = SurfaceJob {
            method: name,
            grid: &grid,
            constraints: &constraints,
            bad_points: &[],
            catalog,
        };
        let result = catch_unwind(AssertUnwindSafe(|| entry.fair_surface(&settings, &job)))
            .map_err(|_| fail(&what, "panicked".into()))?;
        match result {
            Ok(run) => {
                if (run.grid.rows, run.grid.columns) != (rows, columns) {
                    return Err(fail(&what, "the grid's shape changed".into()));
                }
                check_points(&grid.points, &run.grid.points, &constraints).map_err(|m| fail(&what, m))?;
                if constraints.end_clamp() == EndClamp::G0 {
                    if let Some(k) = grid
                        .boundary()
                        .into_iter()
                        .find(|&k| grid.points[k] != run.grid.points[k])
                    {
                        return Err(fail(&what, format!("boundary point {k} moved")));
                    }
                }
            }
            Err(e) => {
                let message = e.to_string();
                if !message.contains(name) {
                    return Err(fail(&what, format!("`{message}` does not name the method")));
                }
                if label == "none" {
                    return Err(fail(&what, format!("refused without constraints: {message}")));
                }
            }
        }
    }
    Ok(())
}
