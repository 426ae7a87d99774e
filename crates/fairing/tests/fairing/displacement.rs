//! The data bound of `fairing::displacement`: the noise estimate finds the noise it was given
//! (and none on clean curves), the decimal step is read from typed data, and the largest move
//! is found and compared with the bound.

use std::f64::consts::PI;

use curve_repr::{Vec2, Vec3};
use fairing::displacement::{data_bound, decimal_quantum, largest_move, noise_estimate, NOISE_BOUND_OFFSET};
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
