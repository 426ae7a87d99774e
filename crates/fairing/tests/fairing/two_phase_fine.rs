//! Han §4.1 Phase 2 (fine fairing) and the alternation of both phases: each case reaches the
//! paper's target on a fresh spline solve; the ill-posed Case 2 is solved well-posed; full
//! passes never increase Infl_num / Vib_num; the long-run option.

use curve_repr::{EndCondition, SplineFunction};
use fairing::two_phase::phase2::absorption_factors;
use fairing::two_phase::{
    coarse_pass, detect_fine, fair_function, fine_displacement, fine_pass, full_pass, Case, CaseKind,
    TwoPhaseSettings,
};
use fairness::xc::XcPolyline;
use proptest::prelude::*;

/// Strongly non-uniform knots (12 points): around points 2 … 7 the spacings 0.5, 4, 2, 0.5, 4
/// make Case 2's system at (4, 5) well conditioned (the sine of its rows' angle is ≈ 1; with
/// mildly non-uniform knots it is ≈ 0.01 and the well-posed rule takes over).
fn knots(n: usize) -> Vec<f64> {
    assert_eq!(n, 12);
    vec![0.0, 1.0, 2.0, 2.5, 6.5, 8.5, 9.0, 13.0, 14.0, 15.0, 16.0, 17.0]
}

fn uniform(n: usize) -> Vec<f64> {
    (0..n).map(|k| 0.5 * k as f64).collect()
}

/// y through `x` whose runout spline has the given c (needs c_0 = c_1, c_{n−2} = c_{n−1}):
/// m from the three-moment equations (Han Eq. 4, corrected)
/// h_{i−1}c_{i−1} + 2(h_{i−1}+h_i)c_i + h_i c_{i+1} = m_i − m_{i−1}, then y from m.
fn y_with_c(x: &[f64], c: &[f64]) -> Vec<f64> {
    let n = x.len();
    assert_eq!(c[0], c[1]);
    assert_eq!(c[n - 2], c[n - 1]);
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let mut m = vec![0.3; n - 1];
    for i in 1..n - 1 {
        m[i] = m[i - 1] + h[i - 1] * c[i - 1] + 2.0 * (h[i - 1] + h[i]) * c[i] + h[i] * c[i + 1];
    }
    let mut y = vec![0.0; n];
    for i in 0..n - 1 {
        y[i + 1] = y[i] + h[i] * m[i];
    }
    let xc = XcPolyline::of_points(x, &y).unwrap();
    for (a, b) in xc.c.iter().zip(c) {
        assert!((a - b).abs() < 1e-9, "construction: {a} vs {b}");
    }
    y
}

fn fresh_c(x: &[f64], y: &[f64]) -> Vec<f64> {
    XcPolyline::of_points(x, y).unwrap().c
}

fn apply(y: &[f64], moves: &[(usize, f64)]) -> Vec<f64> {
    let mut y = y.to_vec();
    for &(k, g) in moves {
        y[k] += g;
    }
    y
}

fn spline(x: &[f64], y: &[f64]) -> SplineFunction {
    SplineFunction::new(x, y, EndCondition::ParabolicRunout).unwrap()
}

/// c patterns (runout ends) and the case expected: (c, first, kind, last).
fn patterns() -> Vec<(Vec<f64>, usize, CaseKind, Option<usize>)> {
    let s = |v: &[f64]| v.iter().map(|a| 0.01 * a).collect::<Vec<f64>>();
    let small = s(&[1.0, 1.0, 2.0, 1.5, 2.0, -0.4, 1.5, 1.0, 2.0, 1.0, 1.0, 1.0]);
    let large = s(&[1.0, 1.0, 2.0, 1.5, -0.3, -0.6, 1.5, 1.0, 2.0, 1.0, 1.0, 1.0]);
    let left = s(&[-0.5, -0.5, 1.0, 2.0, 1.5, 1.0, 1.5, 1.0, 2.0, 1.0, 1.0, 1.0]);
    let right: Vec<f64> = left.iter().rev().copied().collect();
    vec![
        (small, 5, CaseKind::SmallCurve, None),
        (large, 4, CaseKind::LargeCurve, Some(5)),
        (left, 0, CaseKind::LargeCurveEnd, Some(1)),
        (right, 10, CaseKind::LargeCurveEnd, Some(11)),
    ]
}

#[test]
fn each_fine_case_is_detected_where_constructed() {
    let x = knots(12);
    for (c, first, kind, second) in patterns() {
        let s = spline(&x, &y_with_c(&x, &c));
        assert_eq!(
            detect_fine(&s, first, 2),
            Some(Case { kind, first, second }),
            "{kind:?}"
        );
        // Nothing else starts a case.
        for i in (0..12).filter(|&i| i != first) {
            assert_eq!(detect_fine(&s, i, 2), None, "{kind:?} at {i}");
        }
    }
}

/// The value Han's α rule aims for, recomputed from fresh spline solves: the α = 0 move is
/// applied, the neighbours read; if they kept their sign, α = (their sign)·min|c̃|/5.
fn alpha_from_fresh(x: &[f64], y: &[f64], moves0: &[(usize, f64)], neighbours: &[usize], goal: f64) -> f64 {
    let c = fresh_c(x, &apply(y, moves0));
    if neighbours.iter().all(|&m| c[m].signum() == goal) {
        goal * neighbours
            .iter()
            .map(|&m| c[m].abs())
            .fold(f64::INFINITY, f64::min)
            / 5.0
    } else {
        0.0
    }
}

/// The defining conditions (Han Phase 2 Cases 1–2 and the end case) on fresh spline solves:
/// the targeted c values equal α exactly (non-uniform knots: Case 2's system is well
/// conditioned and solved exactly); α follows the α rule; only the pattern's points move,
/// with Case 1's ratio −λ. The end cases move point 1 (n − 2), Han's j = 2 (n − 1), where the
/// printed sensitivities Eq. 14–15 are wrong (papers/README.md): reaching α exactly on a fresh
/// solve there checks the corrected ones.
#[test]
fn each_fine_case_reaches_alpha() {
    let x = knots(12);
    let settings = TwoPhaseSettings::paper();
    for (c, first, kind, second) in patterns() {
        let y = y_with_c(&x, &c);
        let s = spline(&x, &y);
        let case = detect_fine(&s, first, 2).unwrap();
        let moves = fine_displacement(&s, case, &settings).unwrap();
        let zero_settings = settings.clone().with_alpha_divisor(f64::INFINITY);
        let last = second.unwrap_or(first);
        let goal = -c[first].signum();
        let (targets, neighbours, moved): (Vec<usize>, Vec<usize>, Vec<usize>) = match kind {
            CaseKind::SmallCurve => (
                vec![first],
                vec![first - 1, first + 1],
                vec![first - 1, first, first + 1],
            ),
            CaseKind::LargeCurve => (
                vec![first, last],
                vec![first - 1, last + 1],
                (first - 1..=last + 1).collect(),
            ),
            _ if first == 0 => (vec![0, 1], vec![2], vec![1]),
            _ => (vec![10, 11], vec![9], vec![10]),
        };
        let mut got: Vec<usize> = moves.iter().map(|m| m.0).collect();
        got.sort_unstable();
        assert_eq!(got, moved, "{kind:?}");
        // α = 0 first (the divisor ∞ leaves α at 0 whatever the neighbours do).
        let moves0 = fine_displacement(&s, case, &zero_settings).unwrap();
        let c0 = fresh_c(&x, &apply(&y, &moves0));
        for &t in &targets {
            assert!(c0[t].abs() < 1e-9, "{kind:?} α = 0: c[{t}] = {}", c0[t]);
        }
        let alpha = alpha_from_fresh(&x, &y, &moves0, &neighbours, goal);
        assert!(alpha != 0.0, "{kind:?}: the pattern keeps its neighbours' sign");
        let c1 = fresh_c(&x, &apply(&y, &moves));
        for &t in &targets {
            assert!(
                (c1[t] - alpha).abs() < 1e-9,
                "{kind:?}: c[{t}] = {} vs α = {alpha}",
                c1[t]
            );
            assert_eq!(c1[t].signum(), goal);
        }
        if kind == CaseKind::SmallCurve {
            let g = |k: usize| moves.iter().find(|m| m.0 == k).unwrap().1;
            assert!((g(first - 1) + 0.75 * g(first)).abs() < 1e-15);
            assert!((g(first + 1) + 0.75 * g(first)).abs() < 1e-15);
        }
        // The inflections of the pattern are gone.
        let before = XcPolyline::of_points(&x, &y).unwrap().inflections();
        let after = XcPolyline::of_points(&x, &apply(&y, &moves))
            .unwrap()
            .inflections();
        assert!(after < before, "{kind:?}: {before} -> {after}");
    }
}

/// A large curve vibration at (5, 6) of 14 uniform points.
fn uniform_pattern() -> Vec<f64> {
    [
        1.0, 1.0, 1.2, 1.1, 1.0, -0.3, -0.6, 1.0, 1.1, 1.3, 1.0, 1.2, 1.0, 1.0,
    ]
    .iter()
    .map(|v| 0.01 * v)
    .collect()
}

/// Han's Case 2 system on uniform knots: its rows are equal (singular), so the printed rule
/// has no solution; the well-posed rule brings both members to α or beyond, the worse one to
/// α exactly, with a bounded move.
#[test]
fn case_two_on_uniform_knots_is_well_posed() {
    let x = uniform(14);
    let y = y_with_c(&x, &uniform_pattern());
    let s = spline(&x, &y);
    let case = detect_fine(&s, 5, 2).unwrap();
    assert_eq!(case.kind, CaseKind::LargeCurve);
    // The printed system: rows (Σ c̃_k^{5,6}, Σ c̃_k^{4,7}) for k = 5, 6 are parallel.
    let row = |k: usize| {
        (
            s.sensitivity(k, 5) + s.sensitivity(k, 6),
            s.sensitivity(k, 4) + s.sensitivity(k, 7),
        )
    };
    let ((a, b), (d, e)) = (row(5), row(6));
    assert!(
        (a * e - b * d).abs() < 1e-3 * a.hypot(b) * d.hypot(e),
        "not singular: {a} {b} {d} {e}"
    );
    let settings = TwoPhaseSettings::paper();
    let moves = fine_displacement(&s, case, &settings).unwrap();
    let c1 = fresh_c(&x, &apply(&y, &moves));
    let moves0 = fine_displacement(&s, case, &settings.clone().with_alpha_divisor(f64::INFINITY)).unwrap();
    let alpha = alpha_from_fresh(&x, &y, &moves0, &[4, 7], 1.0);
    assert!(alpha > 0.0);
    // Both reach α or beyond; the worse (c_6 = −0.6, further from α) exactly.
    assert!(
        c1[5] >= alpha - 1e-9 && c1[6] >= alpha - 1e-9,
        "{} {}",
        c1[5],
        c1[6]
    );
    assert!((c1[6] - alpha).abs() < 1e-9);
    // The paper's ansatz γ_5 = γ_6 = σ, γ_4 = γ_7 = τ, with τ = 2σ/3 (the bump on uniform
    // knots); the move is of the size of the c values' change.
    let g = |k: usize| moves.iter().find(|m| m.0 == k).unwrap().1;
    assert!((g(5) - g(6)).abs() < 1e-15 && (g(4) - g(7)).abs() < 1e-15);
    assert!((g(4) - 2.0 / 3.0 * g(5)).abs() < 1e-12 * g(5).abs());
    // Within the pass's default size guard (0.5 h, h = 0.5), so a pass applies it.
    assert!(moves.iter().all(|m| m.1.abs() <= 0.25), "{moves:?}");
    // The neighbours keep their sign (the α rule applied). The points beyond them (3, 8) take
    // the compensation (∫ y'' = 0 over a local move) and may change sign: the pass's count
    // guard judges that, not this rule.
    assert!(c1[4] > 0.0 && c1[7] > 0.0);
}

fn noisy(n: usize, amplitude: f64, seed: u64) -> (Vec<f64>, Vec<f64>) {
    use rand::SeedableRng;
    use rand_distr::Distribution;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let normal = rand_distr::Normal::new(0.0, 1.0).unwrap();
    let x: Vec<f64> = (0..n).map(|k| 0.1 * k as f64).collect();
    let y = x
        .iter()
        .map(|t| (t / 2.0).sin() + amplitude * normal.sample(&mut rng))
        .collect();
    (x, y)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    /// A full pass (coarse then fine) never increases Infl_num, nor Vib_num with the paper's
    /// rules (docs/CONTRACT.md counts on a fresh solve); fixed points and the ends never move. With the
    /// long-run option the fine pass guards inflections only and may trade vibrations for
    /// them, so only Infl_num is asserted there.
    #[test]
    fn a_full_pass_never_increases_the_counts(n in 8usize..200, amplitude in 0.0f64..0.05, seed in 0u64..1000, long in proptest::bool::ANY) {
        let (x, y) = noisy(n, amplitude, seed);
        let before = XcPolyline::of_points(&x, &y).unwrap();
        let mut s = spline(&x, &y);
        let settings = TwoPhaseSettings::paper().with_max_run(if long { 12 } else { 2 });
        let movable = |k: usize| k % 7 != 3;
        let (coarse, fine) = full_pass(&mut s, &settings, &movable).unwrap();
        let after = XcPolyline::of_points(&x, s.y()).unwrap();
        prop_assert!(long || after.vibrations() <= before.vibrations());
        prop_assert!(after.inflections() <= before.inflections());
        for (k, (new, old)) in s.y().iter().zip(&y).enumerate() {
            if k % 7 == 3 || k == 0 || k == n - 1 {
                prop_assert_eq!(new, old);
            }
        }
        prop_assert!(coarse.moves.iter().chain(&fine.moves).all(|&(k, _)| k % 7 != 3));
    }
}

#[test]
fn fine_pass_removes_the_pattern_inflections() {
    let x = knots(12);
    for (c, _, kind, _) in patterns() {
        let y = y_with_c(&x, &c);
        let mut s = spline(&x, &y);
        let before = XcPolyline::of_points(&x, &y).unwrap().inflections();
        let report = fine_pass(&mut s, &TwoPhaseSettings::paper(), &|_| true).unwrap();
        assert!(
            report.cases.iter().any(|c| c.kind == kind),
            "{kind:?}: {report:?}"
        );
        let after = XcPolyline::of_points(&x, s.y()).unwrap().inflections();
        assert!(after < before, "{kind:?}: {before} -> {after}");
    }
}

/// The long-run option against the faithful rule on a dense noisy sine (n = 2000, noise
/// N(0, 0.01²), h = 0.1): both reduce the inflections; the option leaves fewer, within 1.5×
/// the clean sine's count (the "close to the clean curve's count"; the faithful rule
/// ends at ~15×). The 10^4 and 10^5 numbers are printed by `examples/two_phase_runs.rs`.
#[test]
fn long_runs_leave_fewer_inflections() {
    let (x, y) = noisy(2000, 0.01, 3);
    let clean: Vec<f64> = x.iter().map(|t| (t / 2.0).sin()).collect();
    let clean_count = XcPolyline::of_points(&x, &clean).unwrap().inflections();
    let rms = |y: &[f64]| {
        let sum: f64 = y.iter().zip(&clean).map(|(a, b)| (a - b) * (a - b)).sum();
        (sum / y.len() as f64).sqrt()
    };
    let before = XcPolyline::of_points(&x, &y).unwrap();
    let run = |settings: TwoPhaseSettings| {
        let mut s = spline(&x, &y);
        fair_function(&mut s, &settings, &|_| true).unwrap();
        (XcPolyline::of_points(&x, s.y()).unwrap(), rms(s.y()))
    };
    let (faithful, _) = run(TwoPhaseSettings::paper());
    let (option, _) = run(TwoPhaseSettings::paper().with_max_run(64));
    println!(
        "inflections {} -> {} (faithful), {} (runs ≤ 64), clean {clean_count}; \
         vibrations {} -> {}, {}; rms {:.2e}",
        before.inflections(),
        faithful.inflections(),
        option.inflections(),
        before.vibrations(),
        faithful.vibrations(),
        option.vibrations(),
        rms(&y),
    );
    assert!(faithful.inflections() < before.inflections());
    assert!(faithful.vibrations() < before.vibrations());
    assert!(option.inflections() < faithful.inflections());
    assert!(
        2 * option.inflections() <= 3 * clean_count,
        "{} against the clean {clean_count}",
        option.inflections()
    );
}

/// The long-run option's full-pass guard: replayed pass by pass, no full pass raises
/// Infl_num (docs/CONTRACT.md count on a fresh solve), and a pass whose unguarded coarse half would
/// (marked `reverted` on its coarse report) ends exactly where a coarse pass with the count
/// guards on, then the fine pass, take the spline from the state before it (replayed on a
/// copy, y compared bit for bit). The run below meets such a pass (the redo is exercised,
/// not assumed).
#[test]
fn a_long_run_full_pass_that_adds_inflections_is_redone_guarded() {
    let (x, y) = noisy(2000, 0.01, 3);
    let settings = TwoPhaseSettings::paper().with_max_run(64);
    let inflections = |y: &[f64]| XcPolyline::of_points(&x, y).unwrap().inflections();
    let mut s = spline(&x, &y);
    let mut redone = 0;
    for _ in 0..50 {
        let before = s.clone();
        let (coarse, _) = full_pass(&mut s, &settings, &|_| true).unwrap();
        assert!(inflections(s.y()) <= inflections(before.y()));
        if coarse.reverted {
            let mut replay = before.clone();
            coarse_pass(&mut replay, &settings, &|_| true).unwrap();
            fine_pass(&mut replay, &settings, &|_| true).unwrap();
            assert!(replay
                .y()
                .iter()
                .zip(s.y())
                .all(|(a, b)| a.to_bits() == b.to_bits()));
            redone += 1;
        }
    }
    assert!(redone > 0, "no full pass was redone in 50");
}

/// The long-run option: a run of four wrong-sign c values between longer, larger flanks is
/// found only with `max_run` ≥ 4. Its move, checked on a fresh spline through the moved points:
/// every member of the run becomes α = (the smaller neighbour)/5 with the neighbours' sign,
/// each flank is scaled by one factor in [1/5, 1), c is unchanged outside the run and its
/// flanks, Infl_num falls by exactly 2, and no narrower pair of flanks could have done it.
#[test]
fn a_long_run_is_absorbed_into_its_flanks() {
    let x = uniform(30);
    let mut c = vec![0.01; 30];
    for (k, v) in [(12, -0.002), (13, -0.003), (14, -0.0035), (15, -0.002)] {
        c[k] = v;
    }
    // A wrong-sign point far away, so that the count does not end at zero.
    c[25] = -0.004;
    let y = y_with_c(&x, &c);
    let s = spline(&x, &y);
    assert_eq!(detect_fine(&s, 12, 2), None);
    let case = detect_fine(&s, 12, 8).unwrap();
    assert_eq!(
        case,
        Case {
            kind: CaseKind::WrongSignRun,
            first: 12,
            second: Some(15)
        }
    );
    let settings = TwoPhaseSettings::paper().with_max_run(8);
    let moves = fine_displacement(&s, case, &settings).unwrap();
    let (lo, hi) = (
        moves.iter().map(|m| m.0).min().unwrap(),
        moves.iter().map(|m| m.0).max().unwrap(),
    );
    assert!(lo < 11 && hi > 16 && lo >= 2 && hi <= 27, "{lo}..{hi}");
    let moved = apply(&y, &moves);
    let c0 = fresh_c(&x, &y);
    let c1 = fresh_c(&x, &moved);
    let alpha = c0[11].abs().min(c0[16].abs()) / 5.0;
    for (k, v) in c1.iter().enumerate().take(16).skip(12) {
        assert!((v - alpha).abs() < 1e-12, "run at {k}: {v} vs {alpha}");
    }
    for (flank, range) in [("left", lo..12), ("right", 16..hi + 1)] {
        let ratios: Vec<f64> = range.map(|k| c1[k] / c0[k]).collect();
        assert!(
            ratios.iter().all(|r| (r - ratios[0]).abs() < 1e-9),
            "{flank}: {ratios:?}"
        );
        assert!(
            ratios[0] >= 0.2 - 1e-12 && ratios[0] < 1.0,
            "{flank}: {}",
            ratios[0]
        );
    }
    for k in (0..lo).chain(hi + 1..30) {
        assert!((c1[k] - c0[k]).abs() < 1e-12, "outside at {k}");
    }
    let count = |y: &[f64]| XcPolyline::of_points(&x, y).unwrap().inflections();
    assert_eq!(count(&moved) + 2, count(&y));
    // The flanks are the shortest that can take the run: every narrower extent, grown one
    // point per side, needs a flank factor outside (0, 4/5] (or a singular system).
    let width = (12 - lo).max(hi - 15);
    // Here one point per flank cannot take the run (so the check below is not empty).
    assert!(width >= 2, "{lo}..={hi}");
    for narrower in 1..width {
        let factors = absorption_factors(&s, 12 - narrower, 12, 15, 15 + narrower, alpha);
        assert!(
            factors.is_none_or(|(l, r)| !(l > 0.0 && l <= 0.8 && r > 0.0 && r <= 0.8)),
            "width {narrower} < {width} would do: {factors:?}"
        );
    }
    // A flank too small to take the run's area (it would have to change sign): refused.
    let mut c2 = c.clone();
    c2[11] = 0.0001;
    c2[10] = -0.01;
    let s2 = spline(&x, &y_with_c(&x, &c2));
    let case2 = detect_fine(&s2, 12, 8).unwrap();
    assert_eq!(fine_displacement(&s2, case2, &settings), None);
}
