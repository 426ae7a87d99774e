//! Strategies chained in one `Pipeline` (one state, the constraints measured from the
//! pipeline's input): a function strategy after a stage that moved x.

use curve_repr::Vec2;
use fairing::strategies::{CurveDomain, SmoothingSettings, SmoothingSplineFairing};
use fairing::two_phase::TwoPhase;
use fairing::{Constraints, EndClamp, Pipeline};

use super::catalog::ua2_180_upper;

/// Issue 15's composition bug: on the UA(2)-180 upper surface with a tolerance of 5e-4, a
/// parametric smoother (which moves x) followed by `TwoPhase` failed with "a constraint
/// moved x of point 5": the tolerance band's projection of Two-Phase's y-only move changed x.
/// Now a move keeps the coordinates it does not change, so x stays where the smoother left
/// it, and the band holds from the pipeline's input.
#[test]
fn a_function_stage_after_one_that_moved_x_keeps_x_and_the_band() {
    let points = ua2_180_upper();
    let smoother = SmoothingSplineFairing::<2>::new(
        SmoothingSettings::default().with_p(0.999),
        CurveDomain::Parametric,
    );
    let tolerance = 5e-4;
    let mut smoothed_only = Pipeline::new(SmoothingSplineFairing::<2>::new(
        SmoothingSettings::default().with_p(0.999),
        CurveDomain::Parametric,
    ))
    .with_constraints(Constraints::default().with_tolerance(tolerance))
    .run(points.clone())
    .unwrap();
    // The smoother moved x of some points (else the test would test nothing).
    let moved_x = smoothed_only
        .points
        .iter()
        .zip(&points)
        .filter(|(a, b)| a.x != b.x)
        .count();
    assert!(moved_x > 5, "{moved_x}");
    let result = Pipeline::new(smoother)
        .then(TwoPhase::default())
        .with_constraints(Constraints::default().with_tolerance(tolerance))
        .run(points.clone())
        .unwrap();
    for (i, (p, q)) in points.iter().zip(&result.points).enumerate() {
        assert!((p - q).norm() <= tolerance, "point {i}: {}", (p - q).norm());
    }
    // Two-Phase moved y only: every x is the smoother's.
    smoothed_only.points.truncate(points.len());
    for (i, (a, b)) in result.points.iter().zip(&smoothed_only.points).enumerate() {
        assert_eq!(a.x, b.x, "x of point {i}");
    }
    assert!(result.stages.len() == 2 && result.stages[1].iterations > 0);
}

/// The projection that keeps unchanged coordinates: the nearest allowed point with the same
/// x, and the plain ball projection when x is the original's.
#[test]
fn a_move_keeps_the_coordinates_it_does_not_change() {
    let c = Constraints::default()
        .with_tolerance(1.0)
        .with_end_clamp(EndClamp::None);
    let original = Vec2::new(0.0, 0.0);
    // x moved by an earlier stage to 0.6: the allowed y at that x is |y| ≤ 0.8.
    let current = Vec2::new(0.6, 0.1);
    let to = c
        .constrain_move_from(1, 3, &original, &current, &Vec2::new(0.6, 5.0))
        .unwrap();
    assert_eq!(to.x, 0.6);
    assert!((to.y - 0.8).abs() < 1e-12 && to.norm() <= 1.0, "{to}");
    // With x at the original's it is the ball projection.
    let here = Vec2::new(0.0, 0.1);
    let a = c
        .constrain_move_from(1, 3, &original, &here, &Vec2::new(0.0, 5.0))
        .unwrap();
    let b = c.constrain_move(1, 3, &original, &Vec2::new(0.0, 5.0)).unwrap();
    assert_eq!(a, b);
    // A move of both coordinates is projected as before.
    let a = c
        .constrain_move_from(1, 3, &original, &current, &Vec2::new(3.0, 4.0))
        .unwrap();
    let b = c.constrain_move(1, 3, &original, &Vec2::new(3.0, 4.0)).unwrap();
    assert_eq!(a, b);
}
