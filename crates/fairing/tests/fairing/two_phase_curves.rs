//! Han §4.2 with the two-phase fairer: [`SegmentedFairing`] around [`TwoPhase`] fairs open and
//! closed planar curves; vibrations and inflections fall and the constraints hold.

use std::f64::consts::PI;

use curve_repr::Vec2;
use fairing::two_phase::TwoPhase;
use fairing::{Constraints, Pipeline, SegmentedFairing};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

fn gaussian(seed: u64, n: usize) -> Vec<f64> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, 1.0).unwrap();
    (0..n).map(|_| normal.sample(&mut rng)).collect()
}

/// (inflections, vibrations) of the parametric kind (docs/CONTRACT.md).
fn counts(points: &[Vec2]) -> (usize, usize) {
    let s = fairness::summary::parametric(points).unwrap();
    (s.inflections.unwrap(), s.vibrations.unwrap())
}

#[test]
fn noisy_closed_ellipse() {
    let n = 200;
    let clean: Vec<Vec2> = (0..n)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / n as f64;
            Vec2::new(4.0 * t.cos(), 2.0 * t.sin())
        })
        .collect();
    let noise = gaussian(5, n);
    // Noise along the outward normal, 0.4 % of the semi-minor axis.
    let noisy: Vec<Vec2> = clean
        .iter()
        .zip(&noise)
        .map(|(p, e)| {
            let normal = Vec2::new(p.x / 16.0, p.y / 4.0).normalize();
            p + normal * (0.008 * e)
        })
        .collect();
    let constraints = Constraints::default().with_fixed([7, 150]).with_tolerance(0.02);
    let result = Pipeline::new(SegmentedFairing::new(TwoPhase::default()).with_passes(3))
        .with_closed(true)
        .with_constraints(constraints.clone())
        .run(noisy.clone())
        .unwrap();
    assert!(constraints.check(&noisy, &result.points).is_ok());
    assert_eq!(result.points[7], noisy[7]);
    assert_eq!(result.points[150], noisy[150]);
    let (before, after) = (counts(&noisy), counts(&result.points));
    println!("closed ellipse: (inflections, vibrations) {before:?} -> {after:?}");
    assert!(after.1 < before.1, "vibrations {before:?} -> {after:?}");
    assert!(after.0 < before.0, "inflections {before:?} -> {after:?}");
}

#[test]
fn noisy_open_spiral_arc() {
    // An arc turning by 1.5π: more than one function segment.
    let n = 150;
    let clean: Vec<Vec2> = (0..n)
        .map(|k| {
            let t = 1.5 * PI * k as f64 / (n - 1) as f64;
            let r = 3.0 + 0.3 * t;
            Vec2::new(r * t.cos(), r * t.sin())
        })
        .collect();
    let noise = gaussian(9, n);
    let noisy: Vec<Vec2> = clean
        .iter()
        .zip(&noise)
        .map(|(p, e)| p * (1.0 + 0.002 * e))
        .collect();
    let constraints = Constraints::default().with_fixed([40]).with_tolerance(0.03);
    let result = Pipeline::new(SegmentedFairing::new(TwoPhase::default()).with_passes(3))
        .with_constraints(constraints.clone())
        .run(noisy.clone())
        .unwrap();
    assert!(constraints.check(&noisy, &result.points).is_ok());
    assert_eq!(result.points[40], noisy[40]);
    // The ends of an open curve: the segments never move them; the default's pre-pass fits
    // them (`ends` = `free`) within the tolerance like every point (checked above), and with
    // `ends` = `keep` they stay bit for bit (`two_phase_foot_point`).
    let (before, after) = (counts(&noisy), counts(&result.points));
    println!("open spiral: (inflections, vibrations) {before:?} -> {after:?}");
    assert!(after.1 < before.1, "vibrations {before:?} -> {after:?}");
    assert!(after.0 <= before.0, "inflections {before:?} -> {after:?}");
}
