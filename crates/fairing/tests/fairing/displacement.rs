//! The data bound of `fairing::displacement`: the noise estimate finds the noise it was given
//! (and none on clean curves), the decimal step is read from typed data, and the largest move
//! is found and compared with the bound; a function's noise is read vertically, at any
//! spacing, so a fairing that moves its points by the noise stays within the bound.

use std::f64::consts::PI;

use curve_repr::{Vec2, Vec3};
use fairing::displacement::{
    data_bound, decimal_quantum, largest_move, noise_estimate, noise_estimate_as, unasked_move,
    unasked_move_as, vertical_noise_estimate, NoiseModel, NOISE_BOUND_OFFSET,
};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

fn noisy<const D: usize>(
    clean: &[curve_repr::Vector<D>],
    sigma: f64,
    seed: u64,
) -> Vec<curve_repr::Vector<D>> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, sigma).unwrap();
    clean
        .iter()
        .map(|p| p.map(|c| c + normal.sample(&mut rng)))
        .collect()
}

#[test]
fn the_noise_estimate_finds_the_noise_it_was_given() {
    let circle: Vec<Vec2> = (0..2000)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / 2000.0;
            Vec2::new(50.0 * a.cos(), 30.0 * a.sin())
        })
        .collect();
    let helix: Vec<Vec3> = (0..2000)
        .map(|k| {
            let a = 0.02 * k as f64;
            Vec3::new(5.0 * a.cos(), 5.0 * a.sin(), 0.5 * a)
        })
        .collect();
    for sigma in [1e-4, 1e-3, 1e-2] {
        for seed in 0..3 {
            let planar = noise_estimate(&noisy(&circle, sigma, seed));
            let spatial = noise_estimate(&noisy(&helix, sigma, seed + 10));
            for (what, estimate) in [("planar", planar), ("spatial", spatial)] {
                assert!(
                    (estimate / sigma - 1.0).abs() < 0.12,
                    "{what}: {estimate} for σ = {sigma}"
                );
            }
        }
    }
    // Clean samples of smooth curves have (almost) no noise.
    assert!(noise_estimate(&circle) < 1e-6);
    // The helix's offset from each chord (κh²/8 ≈ 2.5e-4) turns with its normal by 0.02 rad
    // a step, so its differences are ≈ 5e-6 without noise: a tenth of the smallest σ tried.
    assert!(noise_estimate(&helix) < 1e-5, "{}", noise_estimate(&helix));
    // A few outliers do not move the median-based estimate.
    let mut bumped = noisy(&circle, 1e-3, 5);
    for k in [100, 700, 1300] {
        bumped[k].y += 0.5;
    }
    assert!((noise_estimate(&bumped) / 1e-3 - 1.0).abs() < 0.12);
    assert_eq!(noise_estimate(&circle[..3]), 0.0);
}

#[test]
fn the_decimal_step_is_read_from_typed_data() {
    let typed = |decimals: i32| -> Vec<Vec2> {
        (0..40)
            .map(|k| {
                let x = (0.123_456_789 * k as f64 * 10f64.powi(decimals)).round() / 10f64.powi(decimals);
                let y = ((k as f64).sin() * 10f64.powi(decimals)).round() / 10f64.powi(decimals);
                // As a file would give it: the decimal text read back.
                Vec2::new(format!("{x}").parse().unwrap(), format!("{y}").parse().unwrap())
            })
            .collect()
    };
    for decimals in [0, 2, 4, 6] {
        assert_eq!(
            decimal_quantum(&typed(decimals)),
            10f64.powi(-decimals),
            "{decimals}"
        );
    }
    let computed: Vec<Vec2> = (0..40)
        .map(|k| Vec2::new(k as f64 * PI, (k as f64).sqrt()))
        .collect();
    assert_eq!(decimal_quantum(&computed), 0.0);
    // A small arc typed with nine decimals: its step, not 1 (every coordinate is below 1e-3,
    // so each once passed for a multiple of 1 to within 1e-3).
    let small: Vec<Vec2> = typed(3)
        .iter()
        .map(|p| {
            Vec2::new(
                format!("{:.9}", p.x * 1e-6).parse().unwrap(),
                format!("{:.9}", p.y * 1e-6).parse().unwrap(),
            )
        })
        .collect();
    assert_eq!(decimal_quantum(&small), 1e-9);
}

#[test]
fn the_data_bound_grows_with_the_count_and_never_falls_below_the_step() {
    let line: Vec<Vec2> = (0..100).map(|k| Vec2::new(k as f64, 0.5 * k as f64)).collect();
    let bound = data_bound(&line);
    assert_eq!(bound.noise, 0.0);
    assert_eq!(bound.quantum, 0.1);
    assert_eq!(bound.bound, 0.1);
    // Spacing 0.05: the curvature's own change between neighbours (h³/2 · |κ'| ≈ 6e-5) is
    // far below the noise, which the estimate then finds (sparser samples of the sine leave
    // curvature in the differences and read larger, as its doc says).
    let wavy: Vec<Vec2> = (0..400)
        .map(|k| Vec2::new(0.05 * k as f64, (0.05 * k as f64).sin()))
        .collect();
    let data = noisy(&wavy, 0.01, 3);
    let bound = data_bound(&data);
    let factor = NOISE_BOUND_OFFSET + (2.0 * 400f64.ln()).sqrt();
    assert!((bound.bound - factor * bound.noise).abs() <= 1e-15 * bound.bound);
    assert!(
        bound.bound > 4.0 * 0.01 && bound.bound < 7.0 * 0.01,
        "{}",
        bound.bound
    );
}

#[test]
fn the_largest_move_is_found_and_compared() {
    let data: Vec<Vec2> = (0..10).map(|k| Vec2::new(k as f64, 0.0)).collect();
    let mut faired = data.clone();
    faired[3].y = 0.3;
    faired[7] += Vec2::new(0.3, 0.4);
    let largest = largest_move(&data, &faired, 0.45).unwrap();
    assert_eq!(largest.index, 7);
    assert!((largest.distance - 0.5).abs() < 1e-15);
    assert!(largest.exceeds);
    assert!(!largest_move(&data, &faired, 0.5).unwrap().exceeds);
    assert!(largest_move(&data, &faired[..9], 1.0).is_err());
    assert!(largest_move::<2>(&[], &[], 1.0).is_err());
    faired[2].x = f64::NAN;
    assert!(largest_move(&data, &faired, 1.0).is_err());
}

/// The points with N(0, σ²) added to y only.
fn noisy_y(clean: &[Vec2], sigma: f64, seed: u64) -> Vec<Vec2> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, sigma).unwrap();
    clean
        .iter()
        .map(|p| Vec2::new(p.x, p.y + normal.sample(&mut rng)))
        .collect()
}

/// y = sin(x/2) + N(0, σ²) on n points over [0, 4π], the steps (0.5 + U(0, 1)) · 4π/n (the
/// issue's dense file when n = 10^5 and σ = 0.01), and its clean twin.
pub(crate) fn noisy_sine(n: usize, sigma: f64, seed: u64) -> (Vec<Vec2>, Vec<Vec2>) {
    use rand::RngExt;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, sigma).unwrap();
    let mut x = 0.0;
    let (mut noisy, mut clean) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for _ in 0..n {
        x += (0.5 + rng.random::<f64>()) * 4.0 * PI / n as f64;
        let y = (x / 2.0).sin();
        clean.push(Vec2::new(x, y));
        noisy.push(Vec2::new(x, y + normal.sample(&mut rng)));
    }
    (noisy, clean)
}

#[test]
fn the_vertical_noise_estimate_finds_the_noise_of_a_function_at_any_spacing() {
    // (points, σ, relative error allowed): dense (σ/h from 0.08 to 8000) and sparse; the
    // median of n values has a relative spread of about 1.2/√n, the allowance 4 of those.
    for (n, tolerance) in [(100_000, 0.03), (2_000, 0.12), (200, 0.3)] {
        for sigma in [1e-4, 1e-2, 1.0] {
            for seed in 0..2 {
                let (noisy, _) = noisy_sine(n, sigma, seed);
                let estimate = vertical_noise_estimate(&noisy);
                assert!(
                    (estimate / sigma - 1.0).abs() < tolerance,
                    "n = {n}, σ = {sigma}: {estimate}"
                );
                assert_eq!(noise_estimate_as(&noisy, NoiseModel::Vertical), estimate);
            }
        }
    }
    // Where the noise dwarfs the spacing the normal offsets read far too small (the reason
    // for the vertical model): 10^5 points, σ = 0.01, h ≈ 1.3e-4.
    let (dense, clean) = noisy_sine(100_000, 0.01, 7);
    assert!(noise_estimate(&dense) < 0.1 * 0.01, "{}", noise_estimate(&dense));
    // A clean function has (almost) none: its third divided differences are y‴/6.
    assert!(
        vertical_noise_estimate(&clean) < 1e-9,
        "{}",
        vertical_noise_estimate(&clean)
    );
    let parabola: Vec<Vec2> = (0..50)
        .map(|k| {
            let x = (k as f64 * 0.37).powf(1.3);
            Vec2::new(x, 2.0 - x + 0.5 * x * x)
        })
        .collect();
    // A parabola at uneven spacing has none (to rounding: y reaches 1e3 here).
    let top = parabola.iter().fold(0.0f64, |m, p| m.max(p.y.abs()));
    assert!(
        vertical_noise_estimate(&parabola) < 1e-13 * top,
        "{} of {top}",
        vertical_noise_estimate(&parabola)
    );
    // Outliers and a sharp bend do not move it (the median).
    let (mut bumped, _) = noisy_sine(2_000, 1e-3, 3);
    for k in [100, 700, 1300] {
        bumped[k].y += 0.5;
    }
    assert!((vertical_noise_estimate(&bumped) / 1e-3 - 1.0).abs() < 0.12);
    // Uneven sparse spacing (cosine, 61 points of an airfoil-like surface).
    let upper: Vec<Vec2> = (0..61)
        .map(|k| {
            let x = (1.0 - (PI * k as f64 / 60.0).cos()) / 2.0;
            Vec2::new(
                x,
                0.6 * (0.2969 * x.sqrt() - 0.126 * x - 0.3516 * x * x + 0.2843 * x.powi(3)),
            )
        })
        .collect();
    // Its nose (y ~ √x) bends the first few differences; the median over seeds is the noise.
    let mut estimates: Vec<f64> = (0..21)
        .map(|seed| vertical_noise_estimate(&noisy_y(&upper, 3e-4, seed)))
        .collect();
    estimates.sort_by(f64::total_cmp);
    assert!((estimates[10] / 3e-4 - 1.0).abs() < 0.1, "{estimates:?}");
    assert_eq!(vertical_noise_estimate(&upper[..3]), 0.0);
    assert_eq!(vertical_noise_estimate::<1>(&[]), 0.0);
}

#[test]
fn a_function_moved_by_its_noise_stays_within_the_data_bound() {
    // The faired function is the clean twin: every point moved by exactly its noise.
    for (n, sigma) in [(100_000, 0.01), (10_000, 1.0), (200, 0.01), (2_000, 1e-4)] {
        let (noisy, clean) = noisy_sine(n, sigma, 11);
        let vertical = unasked_move_as(&noisy, &clean, None, NoiseModel::Vertical).unwrap();
        assert!(!vertical.largest.exceeds, "n = {n}, σ = {sigma}: {vertical:?}");
        assert!((vertical.data.noise / sigma - 1.0).abs() < 0.3, "{vertical:?}");
        // ... and a move of three bounds is still reported.
        let mut far = clean.clone();
        far[n / 2].y += 3.0 * vertical.bound();
        assert!(
            unasked_move_as(&noisy, &far, None, NoiseModel::Vertical)
                .unwrap()
                .largest
                .exceeds
        );
    }
    // The normal offsets said `exceeds` on the dense file (the warning on every dense curve).
    let (noisy, clean) = noisy_sine(100_000, 0.01, 11);
    assert!(unasked_move(&noisy, &clean, None).unwrap().largest.exceeds);
}

#[test]
fn a_function_report_reads_its_noise_vertically() {
    use fairing::catalog::{Catalog, CurveKind, CurvePoints, MethodKind, ParameterMap, PlanConstraints};
    // 10^4 points, σ/h ≈ 8: the smoothing spline moves them by about the noise, and a
    // function's report says that is within the data's bound.
    let (noisy, _) = noisy_sine(10_000, 0.01, 5);
    let catalog = Catalog::builtin();
    let plan = catalog
        .plan(
            MethodKind::Curve,
            Some("smoothing-spline"),
            "smoothing-spline",
            None,
            &ParameterMap::new(),
        )
        .unwrap();
    let input = CurvePoints::Planar(noisy.clone());
    let constraints = PlanConstraints::default();
    let run = catalog
        .run_curve_plan(&plan, &input, CurveKind::Function, &constraints)
        .unwrap();
    let largest = &run.extras["largest_move"];
    let noise = largest["noise"].as_f64().unwrap();
    assert!((noise / 0.01 - 1.0).abs() < 0.1, "{largest}");
    assert_eq!(largest["exceeds"], false, "{largest}");
    assert!(largest["distance"].as_f64().unwrap() > 2.0 * 0.01, "{largest}");
    // The same points as a parametric curve: the normal offsets read the noise too small.
    let run = catalog
        .run_curve_plan(&plan, &input, CurveKind::Parametric, &constraints)
        .unwrap();
    assert!(run.extras["largest_move"]["noise"].as_f64().unwrap() < 0.5 * 0.01);
}
