//! Every method of the built-in catalogue is scale- and translation-equivariant: the same
//! points scaled by 2^k and shifted give the result scaled and shifted.
//!
//! Two properties, because floating point makes them different:
//! - scaling by an exact power of two changes no digit, so a run on 2^k·p gives 2^k times the
//!   run on p *bit for bit* (the catalogue's reference frame scales exactly with the data);
//! - a shift by s of an arbitrary input rounds it once, by up to ε·|s|, and a method that
//!   chooses (which point to move, when to stop) may carry that rounding far: that is the
//!   method's sensitivity, not the frame's. So the inputs and shifts here lie on a grid of
//!   2^−20 with |p + s| < 2^21, where p + s is exact. Data within a few extents of the origin
//!   are only scaled by the frame, farther they are centred: every far shift then gives the
//!   frame the same numbers, and a run shifted by s is the run shifted by 1024, moved by
//!   s − 1024, to the rounding of mapping the result back, 4·ε·(|s| + 1024 + size). Without the frame the
//!   methods differed by up to 10^−2 of the size at ×8 and failed outright at 2^±45.
//!
//! A refusal must be the same refusal at every scale and shift.

use curve_repr::{Vec2, Vec3};
use fairing::catalog::{
    Catalog, CurveJob, CurveKind, CurvePoints, Grid, MethodKind, ParameterMap, SurfaceJob,
};
use fairing::Constraints;
use proptest::prelude::*;

/// A noisy arc of `n` points with x increasing (so a function and a curve), from `seed`.
fn arc(n: usize, seed: u64) -> Vec<Vec2> {
    let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    let mut noise = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    (0..n)
        .map(|i| {
            let x = i as f64 / (n - 1) as f64 * 3.0;
            Vec2::new(x + 0.02 * noise(), (0.9 * x).sin() + 0.03 * noise())
        })
        .collect()
}

fn grid(seed: u64) -> Grid {
    let rows = 5;
    let columns = 5;
    let bumps = arc(rows * columns, seed);
    Grid {
        rows,
        columns,
        points: (0..rows * columns)
            .map(|k| {
                let (i, j) = ((k / columns) as f64, (k % columns) as f64);
                Vec3::new(
                    i + 0.01 * bumps[k].x,
                    j,
                    0.3 * (0.7 * i).sin() * (0.5 * j).cos() + 0.05 * bumps[k].y,
                )
            })
            .collect(),
    }
}

/// `x` on the grid of 2^−20, where sums with a shift below 2^20 are exact.
fn on_grid(x: f64) -> f64 {
    (x * 1_048_576.0).round() / 1_048_576.0
}

/// 2^k · (p + shift), the shift given per coordinate.
fn moved(rows: &[Vec<f64>], k: i32, shift: f64) -> Vec<Vec<f64>> {
    rows.iter()
        .map(|r| r.iter().map(|x| (x + shift) * 2f64.powi(k)).collect())
        .collect()
}

type Outcome = Result<Vec<Vec<f64>>, String>;

fn run_curve(catalog: &Catalog, method: &str, kind: CurveKind, rows: &[Vec<f64>]) -> Outcome {
    let points = CurvePoints::Planar(rows.iter().map(|r| Vec2::new(r[0], r[1])).collect());
    let constraints = Constraints::default();
    let entry = catalog.method(MethodKind::Curve, method).unwrap();
    let settings = entry.settings(&ParameterMap::default()).unwrap();
    let job = CurveJob {
        method,
        points: &points,
        kind,
        constraints: &constraints,
        bad_points: &[],
        catalog,
    };
    entry
        .fair_curve(&settings, &job)
        .map(|run| run.points.rows())
        .map_err(|e| e.to_string())
}

fn run_surface(catalog: &Catalog, method: &str, rows: &[Vec<f64>]) -> Outcome {
    let grid = Grid {
        rows: 5,
        columns: 5,
        points: rows.iter().map(|r| Vec3::new(r[0], r[1], r[2])).collect(),
    };
    let constraints = Constraints::default();
    let entry = catalog.method(MethodKind::Surface, method).unwrap();
    let settings = entry.settings(&ParameterMap::default()).unwrap();
    let job = SurfaceJob {
        method,
        grid: &grid,
        constraints: &constraints,
        bad_points: &[],
        catalog,
    };
    entry
        .fair_surface(&settings, &job)
        .map(|run| run.grid.points.iter().map(|p| vec![p.x, p.y, p.z]).collect())
        .map_err(|e| e.to_string())
}

/// The shift every far shift is compared with: beyond [`NEAR`] extents of the origin the
/// frame centres the data, so that all far shifts give the frame the same numbers.
const REFERENCE_SHIFT: f64 = 1024.0;

/// Checks the two properties for one input and one method run by `run`.
fn check(name: &str, rows: &[Vec<f64>], k: i32, shift: f64, run: impl Fn(&[Vec<f64>]) -> Outcome) {
    let shifted = moved(rows, 0, shift);
    let at_unit = run(&shifted);
    let at_scale = run(&moved(&shifted, k, 0.0));
    match (&at_unit, &at_scale) {
        (Ok(a), Ok(b)) => {
            for (p, q) in a.iter().zip(b) {
                for (x, y) in p.iter().zip(q) {
                    assert_eq!(
                        (x * 2f64.powi(k)).to_bits(),
                        y.to_bits(),
                        "{name} at 2^{k}: {x} → {y}"
                    );
                }
            }
        }
        (Err(a), Err(b)) => assert_eq!(a.split(':').next(), b.split(':').next(), "{name} at 2^{k}"),
        _ => panic!("{name}: at ×1 {at_unit:?}, at 2^{k} {at_scale:?}"),
    }
    let reference = run(&moved(rows, 0, REFERENCE_SHIFT));
    let size = rows.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let bound = 4.0 * f64::EPSILON * (shift.abs() + REFERENCE_SHIFT + size);
    match (&reference, &at_unit) {
        (Ok(a), Ok(b)) => {
            for (i, (p, q)) in a.iter().zip(b).enumerate() {
                for (x, y) in p.iter().zip(q) {
                    let error = (x - REFERENCE_SHIFT + shift - y).abs();
                    assert!(
                        error <= bound,
                        "{name} shifted by {shift}: point {i} off by {error:e} > {bound:e}"
                    );
                }
            }
        }
        (Err(a), Err(b)) => assert_eq!(
            a.split(':').next(),
            b.split(':').next(),
            "{name} shifted by {shift}"
        ),
        _ => panic!("{name}: shifted by {REFERENCE_SHIFT} {reference:?}, by {shift} {at_unit:?}"),
    }
}

/// A far shift: at least 2^7 (beyond `NEAR` extents of these inputs, whose coordinates are
/// below 4), at most 10^6, either sign.
fn far(shift: f64) -> f64 {
    on_grid(shift.signum() * (128.0 + shift.abs()))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn curve_methods_commute_with_scaling_and_shifting(seed in 0u64..1000, k in -40i32..=40, shift in -1e6f64..1e6) {
        let catalog = Catalog::builtin();
        let rows: Vec<Vec<f64>> = arc(12, seed).iter().map(|p| vec![on_grid(p.x), on_grid(p.y)]).collect();
        let shift = far(shift);
        for method in catalog.methods(MethodKind::Curve) {
            for kind in [CurveKind::Function, CurveKind::Parametric] {
                let name = format!("{} ({})", method.name(), kind.name());
                check(&name, &rows, k, shift, |r| run_curve(&catalog, method.name(), kind, r));
            }
        }
    }

    #[test]
    fn surface_methods_commute_with_scaling_and_shifting(seed in 0u64..1000, k in -40i32..=40, shift in -1e6f64..1e6) {
        let catalog = Catalog::builtin();
        let rows: Vec<Vec<f64>> = grid(seed).points.iter().map(|p| vec![on_grid(p.x), on_grid(p.y), on_grid(p.z)]).collect();
        let shift = far(shift);
        for method in catalog.methods(MethodKind::Surface) {
            check(method.name(), &rows, k, shift, |r| run_surface(&catalog, method.name(), r));
        }
    }
}

#[test]
fn coordinates_beyond_what_squares_are_refused_naming_the_point() {
    let catalog = Catalog::builtin();
    let mut rows: Vec<Vec<f64>> = arc(12, 7).iter().map(|p| vec![p.x, p.y]).collect();
    rows[4][1] = 1e300;
    for method in catalog.methods(MethodKind::Curve) {
        let message = run_curve(&catalog, method.name(), CurveKind::Parametric, &rows).unwrap_err();
        assert!(
            message.contains("point 4 has the coordinate 1e300"),
            "{}: {message}",
            method.name()
        );
    }
}
