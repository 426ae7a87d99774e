//! Han §4.1 Phase 1 (coarse fairing): each case reaches the paper's target, checked against a
//! fresh spline solve; passes never increase Infl_num / Vib_num; fixed points never move.

use curve_repr::{EndCondition, SplineFunction, Vec2};
use fairing::two_phase::{
    coarse_pass, detect, displacement, Case, CaseKind, CountGuard, TwoPhase, TwoPhaseSettings,
};
use fairing::{Constraints, EndClamp, Error, FairingStrategy, Pipeline};
use fairness::xc::XcPolyline;
use proptest::prelude::*;

/// Non-uniform knots.
fn knots(n: usize) -> Vec<f64> {
    (0..n).map(|k| k as f64 + 0.3 * (k as f64).sin()).collect()
}

/// y through `x` whose runout spline has the given e at the interior points 1 … n − 2
/// (Σ e = 0 is needed so that c_{n−2} = c_{n−1}). Builds c from e, then y from the
/// three-moment equations (Han Eq. 4, corrected): h_{i−1}c_{i−1} + 2(h_{i−1}+h_i)c_i + h_i c_{i+1}
/// = m_i − m_{i−1}.
fn y_with_e(x: &[f64], e: &[f64]) -> Vec<f64> {
    let n = x.len();
    assert_eq!(e.len(), n - 2);
    assert!(e.iter().sum::<f64>().abs() < 1e-12);
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let mut c = vec![0.1; n];
    let mut slope = 0.0;
    for k in 1..n - 1 {
        slope += e[k - 1];
        c[k + 1] = c[k] + slope * h[k];
    }
    let mut m = vec![0.0; n - 1];
    for i in 1..n - 1 {
        m[i] = m[i - 1] + h[i - 1] * c[i - 1] + 2.0 * (h[i - 1] + h[i]) * c[i] + h[i] * c[i + 1];
    }
    let mut y = vec![0.0; n];
    for i in 0..n - 1 {
        y[i + 1] = y[i] + h[i] * m[i];
    }
    // Sanity: the spline of y has this e.
    let xc = XcPolyline::of_points(x, &y).unwrap();
    for (a, b) in xc.e.iter().zip(e) {
        assert!((a - b).abs() < 1e-9, "construction: {a} vs {b}");
    }
    y
}

/// e at point i of the spline through (x, y), solved from scratch.
fn fresh_e(x: &[f64], y: &[f64], i: usize) -> f64 {
    XcPolyline::of_points(x, y).unwrap().e[i - 1]
}

fn apply(y: &[f64], moves: &[(usize, f64)]) -> Vec<f64> {
    let mut y = y.to_vec();
    for &(k, g) in moves {
        y[k] += g;
    }
    y
}

/// The patterns (scaled by 0.01) and the case expected at `at`.
fn patterns() -> Vec<(Vec<f64>, usize, CaseKind, Option<usize>)> {
    let s = |v: &[f64]| v.iter().map(|a| 0.01 * a).collect::<Vec<_>>();
    let rev = |v: &[f64]| v.iter().rev().map(|a| 0.01 * a).collect::<Vec<_>>();
    let small = [1.0, 1.0, 1.0, 1.0, 1.0, -1.0, -1.0, -1.0, -1.0, -1.0];
    let medium = [1.0, 1.0, 1.0, 1.0, -3.0, 1.0, 1.0, 1.0, -2.0, -2.0];
    let large = [1.0, 1.0, 1.0, -2.0, -2.0, 1.0, 1.0, 1.0, -1.0, -1.0];
    let medium_end = [-3.0, 1.0, 1.0, 1.0, 1.0, 1.0, -1.0, -1.0, -1.0, 1.0];
    let large_end = [-2.0, -2.0, 1.0, 1.0, 1.0, 1.0, 1.0, -1.0, -1.0, 1.0];
    vec![
        (s(&small), 5, CaseKind::Small, Some(6)),
        (s(&medium), 5, CaseKind::Medium, None),
        (s(&large), 4, CaseKind::Large, Some(5)),
        (s(&medium_end), 1, CaseKind::MediumEnd, None),
        (rev(&medium_end), 10, CaseKind::MediumEnd, None),
        (s(&large_end), 1, CaseKind::LargeEnd, Some(2)),
        (rev(&large_end), 9, CaseKind::LargeEnd, Some(10)),
    ]
}

#[test]
fn each_case_is_detected_where_constructed() {
    let x = knots(12);
    for (e, at, kind, second) in patterns() {
        let y = y_with_e(&x, &e);
        let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        assert_eq!(
            detect(&spline, at),
            Some(Case {
                kind,
                first: at,
                second
            }),
            "{kind:?} at {at}"
        );
        // The point before a specific pattern is not claimed by the small case.
        if kind != CaseKind::Small && at > 1 {
            assert!(detect(&spline, at - 1).is_none_or(|c| c.kind != CaseKind::Small));
        }
    }
}

/// The defining conditions of Han's rules, checked on a fresh spline solve: with λ = 1 the
/// targeted e (or the product ẽ_i ẽ_{i+1}) is zero; with λ = 0.8 the targeted e keeps exactly
/// 20 % of its value (e is linear in y).
#[test]
fn each_case_reaches_the_paper_target() {
    let x = knots(12);
    for (e, at, kind, second) in patterns() {
        let y = y_with_e(&x, &e);
        let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        let case = detect(&spline, at).unwrap();
        let full = displacement(&spline, case, 1.0).unwrap();
        let part = displacement(&spline, case, 0.8).unwrap();
        let y1 = apply(&y, &full);
        let y8 = apply(&y, &part);
        let targets: Vec<usize> = match kind {
            CaseKind::Small => {
                // ẽ_i ẽ_{i+1} = 0: the one of the two that vanishes is the target.
                let k = second.unwrap();
                let (a, b) = (fresh_e(&x, &y1, at), fresh_e(&x, &y1, k));
                assert!(a.abs().min(b.abs()) < 1e-9, "{kind:?}: {a} {b}");
                // γ_i = σ, γ_{i+1} = −σ.
                assert_eq!(full[0].1, -full[1].1);
                vec![if a.abs() < b.abs() { at } else { k }]
            }
            _ => std::iter::once(at).chain(second).collect(),
        };
        for t in targets {
            let before = fresh_e(&x, &y, t);
            assert!(fresh_e(&x, &y1, t).abs() < 1e-9, "{kind:?} λ = 1 at {t}");
            let after = fresh_e(&x, &y8, t);
            assert!(
                (after - 0.2 * before).abs() < 1e-9 * before.abs().max(1e-3),
                "{kind:?} λ = 0.8: {after} vs {}",
                0.2 * before
            );
        }
        // Only the case's points move.
        for &(k, _) in &full {
            assert!(k == at || Some(k) == second);
        }
    }
}

#[test]
fn small_case_takes_the_root_of_smaller_size() {
    let x = knots(12);
    let e: Vec<f64> = [1.0, 1.0, 1.0, 1.0, 3.0, -1.0, -1.0, -1.0, -1.0, -3.0]
        .iter()
        .map(|a| 0.01 * a)
        .collect();
    let y = y_with_e(&x, &e);
    let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
    let case = detect(&spline, 5).unwrap();
    assert_eq!(case.kind, CaseKind::Small);
    let sigma = displacement(&spline, case, 1.0).unwrap()[0].1.abs();
    // Both roots, by bisection-free direct check: each zeroes one of the two e.
    for t in [5, 6] {
        let g = |s: f64| fresh_e(&x, &apply(&y, &[(5, s), (6, -s)]), t);
        let root = -g(0.0) / (g(1.0) - g(0.0));
        assert!(sigma <= root.abs() + 1e-12);
    }
}

#[test]
fn a_pass_on_a_pattern_applies_its_case() {
    let x = knots(12);
    for (e, at, kind, _) in patterns() {
        let y = y_with_e(&x, &e);
        let mut spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        let report = coarse_pass(&mut spline, &TwoPhaseSettings::paper(), &|_| true).unwrap();
        assert!(!report.reverted);
        assert!(
            report.cases.iter().any(|c| c.kind == kind && c.first == at),
            "{kind:?}: {:?}",
            report.cases
        );
    }
}

fn noisy(n: usize, amplitude: f64, seed: u64) -> (Vec<f64>, Vec<f64>) {
    use rand::SeedableRng;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let x: Vec<f64> = (0..n).map(|k| 0.1 * k as f64).collect();
    let y = x
        .iter()
        .map(|t| (t / 2.0).sin() + amplitude * (rng.random::<f64>() - 0.5))
        .collect();
    (x, y)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn a_pass_never_increases_the_counts(n in 8usize..200, amplitude in 0.0f64..0.05, seed in 0u64..1000, lambda in 0.3f64..1.0) {
        let (x, y) = noisy(n, amplitude, seed);
        let before = XcPolyline::of_points(&x, &y).unwrap();
        let mut spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        let settings = TwoPhaseSettings::paper().with_coarse_lambda(lambda);
        let fixed = |k: usize| k % 7 != 3;
        let report = coarse_pass(&mut spline, &settings, &fixed).unwrap();
        let after = XcPolyline::of_points(&x, spline.y()).unwrap();
        prop_assert!(after.vibrations() <= before.vibrations());
        prop_assert!(after.inflections() <= before.inflections());
        for (k, (new, old)) in spline.y().iter().zip(&y).enumerate() {
            if k % 7 == 3 || k == 0 || k == n - 1 {
                prop_assert_eq!(new, old);
            }
        }
        prop_assert!(report.moves.iter().all(|&(k, _)| k % 7 != 3));
    }
}

#[test]
fn strategy_honours_fixed_points_and_rejects_g1() {
    let (x, y) = noisy(120, 0.02, 7);
    let points: Vec<Vec2> = x.iter().zip(&y).map(|(a, b)| Vec2::new(*a, *b)).collect();
    let fixed = [5usize, 40, 41, 77];
    let result = Pipeline::new(TwoPhase::default())
        .with_constraints(
            Constraints::default()
                .with_fixed(fixed)
                .with_end_clamp(EndClamp::G0),
        )
        .with_max_iterations(50)
        .run(points.clone())
        .unwrap();
    for &k in fixed.iter().chain(&[0, 119]) {
        assert_eq!(result.points[k], points[k]);
    }
    for (p, q) in result.points.iter().zip(&points) {
        assert_eq!(p.x, q.x);
    }
    let before = XcPolyline::of_points(&x, &y).unwrap();
    let faired_y: Vec<f64> = result.points.iter().map(|p| p.y).collect();
    let after = XcPolyline::of_points(&x, &faired_y).unwrap();
    assert!(
        after.vibrations() < before.vibrations(),
        "{} -> {}",
        before.vibrations(),
        after.vibrations()
    );
    assert!(after.inflections() <= before.inflections());

    let clamp = TwoPhase::default().supports(&Constraints::default().with_end_clamp(EndClamp::G1));
    assert!(matches!(clamp, Err(Error::ConstraintUnsupported { .. })));
}

#[test]
fn bad_settings_are_rejected() {
    let (x, y) = noisy(20, 0.02, 1);
    let mut spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
    for s in [
        TwoPhaseSettings::paper().with_coarse_lambda(0.0),
        TwoPhaseSettings::paper().with_coarse_lambda(f64::NAN),
        TwoPhaseSettings::paper().with_alpha_divisor(0.0),
        TwoPhaseSettings::paper().with_alpha_divisor(f64::INFINITY),
        TwoPhaseSettings::paper().with_max_passes(0),
    ] {
        assert!(matches!(
            coarse_pass(&mut spline, &s, &|_| true),
            Err(Error::BadParameter { .. })
        ));
    }
}

/// Prints the numbers of the report (run with --nocapture); asserts only the monotonicity.
#[test]
fn numbers_on_a_noisy_sine() {
    for (n, amplitude, lambda, guard) in [
        (200usize, 0.01, 0.8, CountGuard::Local),
        (1000, 0.01, 0.8, CountGuard::Local),
        (1000, 0.001, 0.8, CountGuard::Local),
        (1000, 0.01, 1.0, CountGuard::Local),
        (1000, 0.01, 0.8, CountGuard::Pass),
        (1000, 0.001, 0.8, CountGuard::Pass),
        (1000, 0.01, 0.8, CountGuard::Off),
        (1000, 0.001, 0.8, CountGuard::Off),
    ] {
        let (x, y) = noisy(n, amplitude, 42);
        let before = XcPolyline::of_points(&x, &y).unwrap();
        let mut spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        let settings = TwoPhaseSettings::paper()
            .with_coarse_lambda(lambda)
            .with_count_guard(guard);
        let (mut passes, mut skipped, mut reverted, mut undone) = (0, 0, 0, 0);
        let mut kinds = std::collections::BTreeMap::new();
        let mut after_one = None;
        for _ in 0..50 {
            passes += 1;
            let r = coarse_pass(&mut spline, &settings, &|_| true).unwrap();
            skipped += r.skipped;
            undone += r.undone_by_count_guard;
            reverted += usize::from(r.reverted);
            for c in &r.cases {
                *kinds.entry(format!("{:?}", c.kind)).or_insert(0usize) += 1;
            }
            if after_one.is_none() {
                after_one = Some(XcPolyline::of_points(&x, spline.y()).unwrap().vibrations());
            }
            if r.moves.is_empty() {
                break;
            }
        }
        let after = XcPolyline::of_points(&x, spline.y()).unwrap();
        let max_move = spline
            .y()
            .iter()
            .zip(&y)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        println!(
            "n={n} noise={amplitude} λ={lambda} guard={guard:?}: vibrations {} -> {:?} (1 pass) -> {}, inflections {} -> {}, passes {passes}, max |Δy| {max_move:.4}, cases {kinds:?}, skipped {skipped} (count guard {undone}), reverted passes {reverted}",
            before.vibrations(),
            after_one,
            after.vibrations(),
            before.inflections(),
            after.inflections()
        );
        if guard != CountGuard::Off {
            assert!(after.vibrations() <= before.vibrations());
            assert!(after.inflections() <= before.inflections());
        }
    }
}

/// The printed medium end condition "e_2e_3 < 0 and e_3e_4 < 0" (1-based) isolates e_3, which
/// the interior Case 2 handles; the end case is read as "e_2 differs from e_3 and e_4".
#[test]
fn printed_medium_end_pattern_is_the_interior_case() {
    let x = knots(12);
    let e: Vec<f64> = [-1.0, 1.0, -1.0, -1.0, -1.0, 1.0, 1.0, 1.0, 1.0, -1.0]
        .iter()
        .map(|a| 0.01 * a)
        .collect();
    let y = y_with_e(&x, &e);
    let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
    assert_ne!(detect(&spline, 1).map(|c| c.kind), Some(CaseKind::MediumEnd));
    assert_eq!(detect(&spline, 2).map(|c| c.kind), Some(CaseKind::Medium));
}

/// The size guard: with patterns whose moves are far beyond half the spacing nothing moves
/// and the cases are counted as skipped.
#[test]
fn move_guard_skips_large_moves() {
    let x = knots(12);
    for (e, ..) in patterns() {
        // The same pattern a million times taller: the same cases, moves a million times
        // larger, the spacing unchanged.
        let y: Vec<f64> = y_with_e(&x, &e).iter().map(|v| v * 1e6).collect();
        let mut spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        let settings = TwoPhaseSettings::paper();
        let report = coarse_pass(&mut spline, &settings, &|_| true).unwrap();
        assert!(report.moves.is_empty());
        assert!(report.skipped > 0);
        assert_eq!(spline.y(), &y[..]);
    }
}
