//! The end-of-curve and segment-join cases that left inflections in Han's arbitrary-curve
//! pipeline, each constructed: a wrong-sign run of c touching a segment's end (longer than
//! the paper's two-point end case), at the left and the right end; the same run at the ends
//! of an open curve and at a join between two segments of the partition. The paper's rules
//! leave each of them; the defaults remove them.

use std::f64::consts::PI;

use curve_repr::{EndCondition, SplineFunction, Vec2};
use fairing::two_phase::{
    detect_fine, fine_displacement, Case, CaseKind, MoveCap, TwoPhase, TwoPhaseSettings,
};
use fairing::{curve_counts, partition, CurveGuard, PartitionSettings, Pipeline, SegmentedFairing};
use fairness::xc::XcPolyline;

fn uniform(n: usize) -> Vec<f64> {
    (0..n).map(|k| 0.5 * k as f64).collect()
}

/// y through `x` whose runout spline has the given c (c_0 = c_1, c_{n−2} = c_{n−1}), from the
/// three-moment equations (Han Eq. 4) integrated from y_0 = 0, slope 0.3.
fn y_with_c(x: &[f64], c: &[f64]) -> Vec<f64> {
    let n = x.len();
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let mut m = vec![0.3; n - 1];
    for i in 1..n - 1 {
        m[i] = m[i - 1] + h[i - 1] * c[i - 1] + 2.0 * (h[i - 1] + h[i]) * c[i] + h[i] * c[i + 1];
    }
    let mut y = vec![0.0; n];
    for i in 0..n - 1 {
        y[i + 1] = y[i] + h[i] * m[i];
    }
    y
}

fn fresh_c(x: &[f64], y: &[f64]) -> Vec<f64> {
    XcPolyline::of_points(x, y).unwrap().c
}

/// The end-run move on a fresh spline: the end point stays, the run takes α = |first flank
/// value|/5 with the flank's sign, the flank is scaled by one factor in [1/5, 1), c beyond the
/// flank is unchanged, and the end's sign change is gone.
fn check_end_run(c: &[f64], first: usize, last: usize) {
    let x = uniform(c.len());
    let y = y_with_c(&x, c);
    let s = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
    // The paper's end case is a run of exactly two followed by two of the other sign: not this.
    assert_eq!(detect_fine(&s, first, 2), None);
    let case = detect_fine(&s, first, 8).unwrap();
    assert_eq!(
        case,
        Case {
            kind: CaseKind::EndRun,
            first,
            second: Some(last)
        }
    );
    let settings = TwoPhaseSettings::paper().with_max_run(8);
    let moves = fine_displacement(&s, case, &settings).unwrap();
    let n = c.len();
    let end = if first == 0 { 0 } else { n - 1 };
    assert!(
        moves.iter().all(|&(k, _)| k != end && k != n - 1 - end),
        "{moves:?}"
    );
    let mut moved = y.clone();
    for &(k, g) in &moves {
        moved[k] += g;
    }
    let (c0, c1) = (fresh_c(&x, &y), fresh_c(&x, &moved));
    let flank_first = if first == 0 { last + 1 } else { first - 1 };
    let alpha = c0[flank_first].abs() / 5.0 * c0[flank_first].signum();
    for (k, value) in c1.iter().enumerate().take(last + 1).skip(first) {
        assert!((value - alpha).abs() < 1e-12, "run at {k}: {value} vs {alpha}");
    }
    let touched: Vec<usize> = moves.iter().map(|m| m.0).collect();
    let (lo, hi) = (*touched.iter().min().unwrap(), *touched.iter().max().unwrap());
    let flank: Vec<usize> = if first == 0 {
        (last + 1..=hi).collect()
    } else {
        (lo..first).collect()
    };
    assert!(!flank.is_empty());
    let ratios: Vec<f64> = flank.iter().map(|&k| c1[k] / c0[k]).collect();
    assert!(ratios.iter().all(|r| (r - ratios[0]).abs() < 1e-9), "{ratios:?}");
    assert!(ratios[0] >= 0.2 - 1e-12 && ratios[0] < 1.0, "{}", ratios[0]);
    for k in (0..n).filter(|k| !(first..=last).contains(k) && !flank.contains(k)) {
        assert!(
            (c1[k] - c0[k]).abs() < 1e-12,
            "c changed at {k}: {} vs {}",
            c1[k],
            c0[k]
        );
    }
    let count = |y: &[f64]| XcPolyline::of_points(&x, y).unwrap().inflections();
    assert_eq!(count(&moved) + 1, count(&y));
}

#[test]
fn a_wrong_sign_run_at_the_left_end_is_absorbed_with_the_end_point_kept() {
    let mut c = vec![0.01; 30];
    for v in c.iter_mut().take(4) {
        *v = -0.003;
    }
    c[20] = -0.004;
    c[21] = -0.004;
    check_end_run(&c, 0, 3);
}

#[test]
fn a_wrong_sign_run_at_the_right_end_is_absorbed_with_the_end_point_kept() {
    let mut c = vec![-0.02; 26];
    for v in c.iter_mut().skip(23) {
        *v = 0.005;
    }
    check_end_run(&c, 23, 25);
}

/// An end run as long as the run after it is not taken for noise (the shorter run is).
#[test]
fn an_end_run_longer_than_its_neighbour_is_no_case() {
    let x = uniform(30);
    let mut c = vec![0.01; 30];
    for v in c.iter_mut().take(6) {
        *v = -0.004;
    }
    for v in c.iter_mut().skip(6).take(3) {
        *v = 0.003;
    }
    for v in c.iter_mut().skip(9).take(3) {
        *v = -0.004;
    }
    let s = SplineFunction::new(&x, &y_with_c(&x, &c), EndCondition::ParabolicRunout).unwrap();
    assert_eq!(detect_fine(&s, 0, 8), None);
}

/// Inflections of the planar polygon (docs/CONTRACT.md's parametric count) and where they are.
fn inflections(points: &[Vec2]) -> usize {
    fairness::summary::parametric(points)
        .unwrap()
        .inflections
        .unwrap()
}

/// A circular arc of radius 3 over 200°, 61 points, with three consecutive points pushed
/// outwards by `depth` from `first` on: a dent whose curvature has the wrong sign on a run
/// of three or more points.
fn dented_arc(first: usize, depth: f64) -> Vec<Vec2> {
    (0..61)
        .map(|k| {
            let a = 200f64.to_radians() * k as f64 / 60.0;
            let r = if (first..first + 3).contains(&k) {
                3.0 + depth
            } else {
                3.0
            };
            Vec2::new(r * a.cos(), r * a.sin())
        })
        .collect()
}

fn faired(points: &[Vec2], settings: TwoPhaseSettings, partition: PartitionSettings) -> Vec<Vec2> {
    Pipeline::new(
        SegmentedFairing::new(TwoPhase::new(settings))
            .with_partition(partition)
            .with_passes(SegmentedFairing::<TwoPhase>::DEFAULT_PASSES),
    )
    .run(points.to_vec())
    .unwrap()
    .points
}

#[test]
fn a_dent_at_the_curve_end_is_removed() {
    let points = dented_arc(1, 0.02);
    assert!(inflections(&points) > 0);
    let paper = faired(&points, TwoPhaseSettings::paper(), PartitionSettings::paper());
    assert!(inflections(&paper) > 0, "the paper's rules leave the end dent");
    let default = faired(&points, TwoPhaseSettings::default(), PartitionSettings::default());
    assert_eq!(inflections(&default), 0);
}

#[test]
fn a_dent_at_a_segment_join_is_removed() {
    // Where the default partition of the clean arc joins its first two segments: the dent's
    // three points lie in the overlap, the last of them the first segment's end point.
    let clean = dented_arc(0, 0.0);
    let segments = partition(&clean, false, &PartitionSettings::default()).unwrap();
    assert!(segments.len() >= 2);
    let join = *segments[0].indices.last().unwrap();
    assert!(segments[1].indices[0] <= join - 2, "the dent lies in the overlap");
    let points = dented_arc(join - 2, 0.02);
    assert!(inflections(&points) > 0);
    let paper = faired(&points, TwoPhaseSettings::paper(), PartitionSettings::default());
    assert!(
        inflections(&paper) > 0,
        "the paper's rules leave the dent at the join"
    );
    let default = faired(&points, TwoPhaseSettings::default(), PartitionSettings::default());
    assert_eq!(inflections(&default), 0);
    // The phases as printed (the curve guard off, and no cap of a case's move at the data
    // bound, which on this arc, exact but for the dent, refuses the moves that fill it): the
    // dent is filled, not moved elsewhere; every point ends near the arc.
    let unguarded = Pipeline::new(
        SegmentedFairing::new(TwoPhase::new(
            TwoPhaseSettings::default().with_move_cap(MoveCap::Spacing),
        ))
        .with_passes(SegmentedFairing::<TwoPhase>::DEFAULT_PASSES)
        .with_curve_guard(CurveGuard::Off),
    )
    .run(points.clone())
    .unwrap()
    .points;
    assert_eq!(inflections(&unguarded), 0);
    for (k, p) in unguarded.iter().enumerate() {
        assert!((p.norm() - 3.0).abs() < 0.02, "point {k} at radius {}", p.norm());
    }
    // The default's guard keeps the curve's counts no worse than that. Measured cost: it
    // refuses the phases' spreading of the dent (30 vibrations against the pre-pass's 26), so
    // the pre-pass's smoothed dent stays (peak 0.022 outwards at point 36, against 0.014).
    let (guarded, spread) = (curve_counts(&default).unwrap(), curve_counts(&unguarded).unwrap());
    assert!(
        guarded.0 <= spread.0 && guarded.1 <= spread.1,
        "{guarded:?} against {spread:?}"
    );
    let _ = PI;
}

/// Dense noisy data (2·10^4 points of y = sin(x/2) + N(0, 0.01²) over [0, 4π], spacing
/// 6.3e-4, fifteen times below the noise): with the defaults two-phase ends within 1.5× the
/// clean curve's inflections (1, or 2 when the random steps end past 4π), moving no point beyond the data's noise bound and ending far
/// closer to the clean curve than the noise. What it takes (each measured on this data): the
/// pre-pass's p chosen by GCV of the free fit (with the noisy ends interpolated GCV chose p
/// = 0.9991, ~360 inflections left at 10^5 points), runs of any length (the pre-pass leaves
/// end runs of 500–650 points) and moves up to the noise (the end run's move, 8e-4, is above
/// half a spacing). The paper's settings leave thousands.
#[test]
fn dense_noisy_data_end_with_the_clean_curves_inflections() {
    use fairing::displacement::{unasked_move_as, NoiseModel};
    use fairing::two_phase::counts;
    let n = 20_000;
    let sigma = 0.01;
    for seed in 0..2 {
        // The same draws as before, from the one generator of this data.
        let (noisy, clean) = crate::displacement::noisy_sine(n, sigma, seed);
        let fair = |settings: TwoPhaseSettings| {
            let passes = settings.max_passes;
            Pipeline::new(TwoPhase::new(settings))
                .with_max_iterations(passes)
                .run(noisy.clone())
                .unwrap()
                .points
        };
        let truth = counts(&runout_spline(&clean)).1;
        assert!((1..=2).contains(&truth), "{truth}");
        let faired = fair(TwoPhaseSettings::default());
        let inflections = counts(&runout_spline(&faired)).1;
        assert!(
            inflections as f64 <= 1.5 * truth as f64,
            "seed {seed}: {inflections}"
        );
        let rms = vertical_rms(&faired, &clean);
        assert!(rms < 0.2 * sigma, "seed {seed}: RMS {rms}");
        let unasked = unasked_move_as(&noisy, &faired, None, NoiseModel::Vertical).unwrap();
        assert!(!unasked.largest.exceeds, "seed {seed}: {unasked:?}");
        if seed == 0 {
            let paper = counts(&runout_spline(&fair(
                TwoPhaseSettings::paper().with_max_passes(5),
            )))
            .1;
            assert!(paper > 100, "seed {seed}: the paper's rules left {paper}");
        }
    }
}

/// Dense, evenly spaced noisy data with the clean curve's inflections inside (2·10^4 points
/// of y = sin(x/2) over [0, 20], noise σ = 0.01, spacing 1e-3: inflections at 2π, 4π and
/// 6π): two-phase ends within 1.5× the clean curve's 3. jump-lsq's GCV here still falls at
/// λ_max, so the pre-pass compares its fit at the limit with the cubic smoothing spline's
/// by their GCV scores and keeps the cubic's. It used to keep jump-lsq's (its search stopped
/// at a spurious minimum of the trials' rounding just below λ_max), and two-phase ended with
/// 5 here (24 on 10^5 such points).
#[test]
fn dense_evenly_spaced_data_end_with_the_clean_curves_inflections() {
    use fairing::two_phase::counts;
    let (n, sigma) = (20_000, 0.01);
    let clean: Vec<Vec2> = (0..n)
        .map(|k| {
            let x = 20.0 * k as f64 / (n - 1) as f64;
            Vec2::new(x, (x / 2.0).sin())
        })
        .collect();
    let noisy: Vec<Vec2> = clean
        .iter()
        .zip(crate::two_phase_denoise::noise(11, n, sigma))
        .map(|(p, e)| Vec2::new(p.x, p.y + e))
        .collect();
    let truth = counts(&runout_spline(&clean)).1;
    assert_eq!(truth, 3);
    let settings = TwoPhaseSettings::default();
    let faired = Pipeline::new(TwoPhase::new(settings.clone()))
        .with_max_iterations(settings.max_passes)
        .run(noisy)
        .unwrap()
        .points;
    let inflections = counts(&runout_spline(&faired)).1;
    assert!(inflections as f64 <= 1.5 * truth as f64, "{inflections}");
    let rms = vertical_rms(&faired, &clean);
    assert!(rms < 0.1 * sigma, "RMS {rms}");
}

/// The RMS of the y differences of two point sets of a function.
fn vertical_rms(a: &[Vec2], b: &[Vec2]) -> f64 {
    (a.iter().zip(b).map(|(a, b)| (a.y - b.y).powi(2)).sum::<f64>() / a.len() as f64).sqrt()
}

/// The judge's clean sine (`examples/two_phase_judge.rs`): y = sin(x/2), x = 0.1 k, `n` points.
fn judge_sine(n: usize) -> Vec<Vec2> {
    (0..n)
        .map(|k| {
            let x = 0.1 * k as f64;
            Vec2::new(x, (x / 2.0).sin())
        })
        .collect()
}

/// The runout spline function through `p` (the kind two-phase fairs a function with).
fn runout_spline(p: &[Vec2]) -> SplineFunction {
    let (x, y): (Vec<f64>, Vec<f64>) = p.iter().map(|p| (p.x, p.y)).unzip();
    SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap()
}

/// The data-consistency test of the end-run case (`END_RUN_MAX_DEVIANCE` = 0.5 σ̂²), on the
/// judge's own draws of its `sine` (`examples/two_phase_judge.rs`: y = sin(x/2), x = 0.1 k,
/// 200 points, σ = 0.01, the generator seeded with 1000 · seed + 200). The clean curve's third
/// inflection, x = 6π, is eleven points from the end, so its end run is true. Without the test
/// two-phase absorbed that run on every draw and ended with 2 inflections (measured when the
/// bound was a setting; under the 95 % χ²₁ bound 3.84 only draw 4 kept it). The test refuses
/// a move that would raise the residual sum of squares against the data by more than the
/// bound: the clean curve's 3 inflections must stay on at least 7 of the 8 draws (draw 7's
/// run fits the data better absorbed, −0.9 σ̂², so it is taken either way).
#[test]
fn an_end_run_the_data_hold_is_not_absorbed() {
    use fairing::two_phase::counts;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    let n = 200;
    let clean = judge_sine(n);
    let truth = counts(&runout_spline(&clean)).1;
    assert_eq!(truth, 3);
    let mut kept = 0;
    for seed in 1..=8u64 {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed * 1000 + n as u64);
        let normal = Normal::new(0.0, 0.01).unwrap();
        let noisy: Vec<Vec2> = clean
            .iter()
            .map(|p| Vec2::new(p.x, p.y + normal.sample(&mut rng)))
            .collect();
        let default = Pipeline::new(TwoPhase::new(TwoPhaseSettings::default()))
            .with_max_iterations(50)
            .run(noisy.clone())
            .unwrap()
            .points;
        if counts(&runout_spline(&default)).1 == truth {
            kept += 1;
        }
    }
    assert!(kept >= 7, "the true end run kept on {kept} of 8 draws");
}
