//! The arbitrary-curve guard of [`SegmentedFairing`] ([`CurveGuard`]): segment moves that make
//! the whole curve's own inflection or vibration counts worse are refused, moves that lower
//! the inflections are kept, and `off` applies every move (Han §4.2.4 as printed).

use std::f64::consts::PI;

use curve_repr::Vec2;
use fairing::{curve_counts, CurveGuard, Pipeline, Result, SegmentedFairing};

/// (inflections, vibrations) of the parametric kind, by the fairness crate's summary.
fn summary_counts(points: &[Vec2]) -> (usize, usize) {
    let s = fairness::summary::parametric(points).unwrap();
    (s.inflections.unwrap(), s.vibrations.unwrap())
}

/// A segment fairer: y over x, the fixed flags.
type Fairer = fn(&[f64], &mut [f64], &[bool]) -> Result<()>;

/// 61 points on a half circle of radius 1 (more than one segment at the default 120° limit).
fn half_circle() -> Vec<Vec2> {
    (0..61)
        .map(|k| {
            let t = PI * k as f64 / 60.0;
            Vec2::new(t.cos(), t.sin())
        })
        .collect()
}

fn run(points: &[Vec2], guard: CurveGuard, fairer: Fairer) -> Vec<Vec2> {
    Pipeline::new(
        SegmentedFairing::new(fairer)
            .with_passes(3)
            .with_curve_guard(guard),
    )
    .with_max_iterations(3)
    .run(points.to_vec())
    .unwrap()
    .points
}

/// A "fairer" that adds a zigzag of 0.002 to every movable interior point of a segment.
fn zigzag(_x: &[f64], y: &mut [f64], fixed: &[bool]) -> Result<()> {
    let n = y.len();
    for j in 1..n - 1 {
        if !fixed[j] {
            y[j] += if j % 2 == 0 { 0.002 } else { -0.002 };
        }
    }
    Ok(())
}

/// A fairer that averages every movable interior point with its neighbours (1, 2, 1)/4.
fn average(_x: &[f64], y: &mut [f64], fixed: &[bool]) -> Result<()> {
    let old = y.to_vec();
    for j in 1..y.len() - 1 {
        if !fixed[j] {
            y[j] = 0.25 * (old[j - 1] + 2.0 * old[j] + old[j + 1]);
        }
    }
    Ok(())
}

#[test]
fn curve_counts_are_the_parametric_summary_counts() {
    let mut points = half_circle();
    for (k, p) in points.iter_mut().enumerate() {
        *p *= 1.0 + 0.003 * ((7 * k * k + 3 * k) % 11) as f64 / 11.0;
    }
    let counts = curve_counts(&points).unwrap();
    assert_eq!(counts, summary_counts(&points));
    assert!(counts.0 > 0 && counts.1 > 0, "{counts:?}");
    assert_eq!(curve_counts(&points[..2]), None);
    let mut repeated = points.clone();
    repeated[5] = repeated[4];
    assert_eq!(curve_counts(&repeated), None);
}

#[test]
fn moves_that_add_vibrations_are_refused() {
    let points = half_circle();
    let before = summary_counts(&points);
    let off = run(&points, CurveGuard::Off, zigzag);
    let worse = summary_counts(&off);
    assert!(
        worse.0 > before.0 && worse.1 > before.1,
        "{before:?} -> {worse:?}"
    );
    for guard in [CurveGuard::Local, CurveGuard::Pass] {
        assert_eq!(run(&points, guard, zigzag), points, "{guard:?}");
    }
}

#[test]
fn moves_that_remove_inflections_are_kept() {
    // A dent of 0.02 towards the centre at point 30 puts inflections on the half circle (the
    // dent's two and the spline's ringing around it).
    let mut points = half_circle();
    points[30] *= 0.98;
    let before = summary_counts(&points);
    assert!(before.0 >= 2, "{before:?}");
    let local = run(&points, CurveGuard::Local, average);
    let after = summary_counts(&local);
    assert_ne!(local, points);
    assert!(after.0 < before.0, "{before:?} -> {after:?}");
    assert!(summary_counts(&run(&points, CurveGuard::Pass, average)).0 <= before.0);
}
