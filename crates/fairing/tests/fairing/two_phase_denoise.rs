//! The noise pre-pass of two-phase fairing (`denoise`): every variant keeps the kept points
//! bit for bit, honours the allowed distances, smooths towards the clean curve, and refuses
//! bad input with an error.

use std::f64::consts::PI;

use curve_repr::Vec2;
use fairing::strategies::CurveEnds;
use fairing::two_phase::{
    denoise, denoise_by, denoise_curve, denoise_curve_by, CurvePrepass, Denoise, Limits, Prepass, Projection,
    TwoPhase, TwoPhaseSettings,
};
use fairing::{Constraints, EndClamp, Pipeline};
use fairness::XcPolyline;

const SMOOTHING: [Denoise; 3] = [Denoise::Gcv, Denoise::JumpLsq, Denoise::JumpLsqGcv];

/// Deterministic noise in [−σ√3, σ√3) (standard deviation σ) from an LCG.
pub(super) fn noise(seed: u64, count: usize, sigma: f64) -> Vec<f64> {
    let mut state = seed.wrapping_mul(2862933555777941757).wrapping_add(3037000493);
    (0..count)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
            (2.0 * u - 1.0) * sigma * 3f64.sqrt()
        })
        .collect()
}

fn rms(a: &[f64], b: &[f64]) -> f64 {
    (a.iter().zip(b).map(|(a, b)| (a - b).powi(2)).sum::<f64>() / a.len() as f64).sqrt()
}

#[test]
fn the_function_pre_pass_keeps_kept_points_bit_for_bit_and_nears_the_clean_curve() {
    let n = 200;
    let x: Vec<f64> = (0..n).map(|k| 0.1 * k as f64).collect();
    let clean: Vec<f64> = x.iter().map(|x| (x / 2.0).sin()).collect();
    let y: Vec<f64> = clean.iter().zip(noise(7, n, 0.01)).map(|(c, e)| c + e).collect();
    let keep = |k: usize| k == 0 || k + 1 == n || k == 77;
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &keep,
        allowed: &free,
    };
    for mode in SMOOTHING {
        let smooth = denoise(mode, &x, &y, &limits).unwrap();
        for k in [0, 77, n - 1] {
            assert_eq!(smooth[k].to_bits(), y[k].to_bits(), "{mode:?}: point {k} moved");
        }
        let (before, after) = (rms(&y, &clean), rms(&smooth, &clean));
        assert!(after < 0.6 * before, "{mode:?}: RMS to clean {before} -> {after}");
    }
    assert_eq!(denoise(Denoise::Off, &x, &y, &limits).unwrap(), y);
}

/// Beyond its limit of points (`MAX_PREPASS_POINTS`, 2 000) a function's
/// pre-pass fits the means of bins of consecutive points (`two_phase::bins`): 2 000 bins
/// first, four times as many while the fit keeps more than one degree of freedom per 20 bins,
/// up to `MAX_BINS` and one bin per point. Here the limit is 6 000 on 24 000 points. On
/// sin(20x) over [0, 20] (64 waves) 2 000 bins of 12 points are 31 per wave: their means
/// alone lose (kw)²/24 = 0.17 % of the amplitude (w the bin width), 0.6σ in RMS at σ = 0.002,
/// and the fit on them keeps far more than 100 degrees of freedom, so the bins must be
/// refined for the fit to come near the clean curve; sin(x/2) keeps its first 2 000. The kept
/// points (the ends and a fixed point, bins of their own) come back bit for bit. (Checked to
/// fail without the refinement, when refinement stopped at the limit: sin(20x) then ended
/// 0.59σ from the clean curve, against 0.16σ refined to 6 000 bins.) A limit below 4 points
/// is refused.
#[test]
fn a_function_beyond_the_prepass_limit_is_fitted_on_bins_that_resolve_it() {
    let n = 24_000;
    let sigma = 0.002;
    let x: Vec<f64> = (0..n).map(|k| 20.0 * k as f64 / (n - 1) as f64).collect();
    let fixed = n / 2 + 1;
    let keep = |k: usize| k == 0 || k + 1 == n || k == fixed;
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &keep,
        allowed: &free,
    };
    let prepass = Prepass::gcv(1.0).with_max_points(6_000);
    for (wave, seed) in [(0.5, 1), (20.0, 2)] {
        let clean: Vec<f64> = x.iter().map(|x| (wave * x).sin()).collect();
        // The kept points are exact (a noisy one would bend the fit to itself).
        let y: Vec<f64> = clean
            .iter()
            .zip(noise(seed, n, sigma))
            .enumerate()
            .map(|(k, (c, e))| if keep(k) { *c } else { c + e })
            .collect();
        let smooth = denoise_by(Denoise::JumpLsqGcv, prepass, &x, &y, &limits).unwrap();
        for k in [0, fixed, n - 1] {
            assert_eq!(
                smooth[k].to_bits(),
                y[k].to_bits(),
                "sin({wave}x): point {k} moved"
            );
        }
        assert!(smooth.iter().all(|v| v.is_finite()));
        let after = rms(&smooth, &clean);
        assert!(
            after < 0.3 * sigma,
            "sin({wave}x): RMS to the clean curve {after}"
        );
    }
}

/// Beyond its default limit (2 000 points) a function's pre-pass fits bin means and reads
/// them back through the quintic spline: on 10^4 noisy points of sin(2x) over [0, 20]
/// (σ = 0.01) the pre-pass alone ends with the clean curve's inflections, at most twice its
/// vibrations (Han's x–c polyline, runout ends) and within 0.1σ of it (measured: 12 and 24,
/// the clean curve's, at 0.07σ). Read back through the natural cubic spline instead, the
/// points of each bin lie on one cubic, the output's e_i there are round-off of either sign:
/// checked to fail, with 14 inflections and 7 060 vibrations at the same distance.
#[test]
fn a_binned_function_is_read_back_with_the_clean_curves_vibrations() {
    let (n, sigma) = (10_000, 0.01);
    let settings = TwoPhaseSettings::default();
    let prepass = TwoPhaseSettings::function_prepass();
    assert!(
        n > prepass.max_points,
        "the default limit does not bin {n} points"
    );
    let x: Vec<f64> = (0..n).map(|k| 20.0 * k as f64 / (n - 1) as f64).collect();
    let clean: Vec<f64> = x.iter().map(|x| (2.0 * x).sin()).collect();
    let y: Vec<f64> = clean.iter().zip(noise(5, n, sigma)).map(|(c, e)| c + e).collect();
    let none = |_: usize| false;
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &none,
        allowed: &free,
    };
    let smooth = denoise_by(settings.denoise, prepass, &x, &y, &limits).unwrap();
    let (fitted, truth) = (
        XcPolyline::of_points(&x, &smooth).unwrap(),
        XcPolyline::of_points(&x, &clean).unwrap(),
    );
    assert_eq!(fitted.inflections(), truth.inflections(), "inflections");
    assert!(
        fitted.vibrations() <= 2 * truth.vibrations(),
        "{} vibrations against the clean curve's {}",
        fitted.vibrations(),
        truth.vibrations()
    );
    let after = rms(&smooth, &clean);
    assert!(after < 0.1 * sigma, "RMS to the clean curve {after}");
}

/// Beyond its limit (`MAX_CURVE_PREPASS_POINTS`) an arbitrary curve's pre-pass fits bin means
/// too, and reads each point back at a parameter between its bin's centre and the next, so
/// the points keep their order along the curve: on data as dense as their noise (here σ =
/// 0.01, spacings 1.2e-3 and 3.1e-3) the noise alone would scramble it. Open (a noisy arc of
/// radius 2 over 270°, 8 000 points, limit 2 000, ends and a fixed point kept) and closed (a
/// noisy circle, 4 000 points, limit 1 000, a fixed point kept): kept points bit for bit,
/// angles strictly increasing, within 0.1σ of the clean circle.
#[test]
fn a_curve_beyond_the_prepass_limit_is_fitted_on_bins_and_keeps_its_order() {
    let sigma = 0.01;
    for (closed, n, limit) in [(false, 8_000, 2_000), (true, 4_000, 1_000)] {
        let prepass = Prepass::gcv(1.4).with_max_points(limit);
        let fixed = n / 3 + 1;
        let sweep = if closed { 2.0 * PI } else { 1.5 * PI };
        let steps = if closed { n } else { n - 1 };
        let clean: Vec<Vec2> = (0..n)
            .map(|k| {
                let t = sweep * k as f64 / steps as f64;
                Vec2::new(2.0 * t.cos(), 2.0 * t.sin())
            })
            .collect();
        let keep = |k: usize| k == fixed || (!closed && (k == 0 || k + 1 == n));
        let free = |_: usize| f64::INFINITY;
        let limits = Limits {
            keep: &keep,
            allowed: &free,
        };
        let (ex, ey) = (noise(11, n, sigma), noise(12, n, sigma));
        let points: Vec<Vec2> = (0..n)
            .map(|k| {
                if keep(k) {
                    clean[k]
                } else {
                    clean[k] + Vec2::new(ex[k], ey[k])
                }
            })
            .collect();
        let rules = CurvePrepass::new(Denoise::JumpLsqGcv, Projection::FootPoint)
            .with_prepass(prepass)
            .with_ends(CurveEnds::Runout);
        let faired = denoise_curve_by(&rules, &points, closed, &limits).unwrap();
        for k in (0..n).filter(|&k| keep(k)) {
            assert_eq!(faired[k], points[k], "closed {closed}: kept point {k} moved");
        }
        let angle = |p: Vec2| p.y.atan2(p.x).rem_euclid(2.0 * PI);
        for k in 1..n {
            let step = (angle(faired[k]) - angle(faired[k - 1])).rem_euclid(2.0 * PI);
            assert!(
                step > 0.0 && step < 0.01,
                "closed {closed}: points {} and {k} out of order",
                k - 1
            );
        }
        let radial = (faired.iter().map(|p| (p.norm() - 2.0).powi(2)).sum::<f64>() / n as f64).sqrt();
        assert!(radial < 0.1 * sigma, "closed {closed}: radial RMS {radial}");
    }
}

/// Two-phase's default curve pre-pass bins a noisy arc of 3·10^4 points (radius 2 over 270°,
/// σ = 0.01 per coordinate, ends free): the fit has no inflection (the sign of the turn
/// between consecutive chords never changes) and lies within 0.1σ of the circle. With one
/// knot per point (a limit of 10^5 points, the limit before) this draw's fit turned
/// its sign once (checked, 57 s in a debug build; of the draws tried, seeds 21 and 41 had
/// none, and the command's pre-pass left 1, 1 and 2 on three Gaussian draws).
#[test]
fn a_dense_noisy_arc_is_binned_by_default_and_its_fit_has_no_inflection() {
    let (n, sigma) = (30_000, 0.01);
    let rules = TwoPhaseSettings::default().curve_prepass();
    let limit = rules.prepass.max_points;
    assert!(n > limit, "the default limit {limit} does not bin {n} points");
    let clean: Vec<Vec2> = (0..n)
        .map(|k| {
            let t = 1.5 * PI * k as f64 / (n - 1) as f64;
            Vec2::new(2.0 * t.cos(), 2.0 * t.sin())
        })
        .collect();
    let (ex, ey) = (noise(31, n, sigma), noise(32, n, sigma));
    let keep = |_: usize| false;
    let points: Vec<Vec2> = (0..n).map(|k| clean[k] + Vec2::new(ex[k], ey[k])).collect();
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &keep,
        allowed: &free,
    };
    let faired = denoise_curve_by(&rules, &points, false, &limits).unwrap();
    let turns: Vec<f64> = faired
        .windows(3)
        .map(|w| {
            let (a, b) = (w[1] - w[0], w[2] - w[1]);
            a.x * b.y - a.y * b.x
        })
        .collect();
    let changes = turns.windows(2).filter(|t| (t[0] > 0.0) != (t[1] > 0.0)).count();
    assert_eq!(changes, 0, "the fit of the arc turns its sign {changes} times");
    let radial = (faired.iter().map(|p| (p.norm() - 2.0).powi(2)).sum::<f64>() / n as f64).sqrt();
    assert!(radial < 0.1 * sigma, "radial RMS {radial}");
}

#[test]
fn the_pre_pass_honours_the_allowed_distances() {
    let n = 120;
    let x: Vec<f64> = (0..n).map(|k| 0.1 * k as f64).collect();
    let y: Vec<f64> = x
        .iter()
        .zip(noise(3, n, 0.05))
        .map(|(x, e)| (x / 2.0).sin() + e)
        .collect();
    let bound = 0.02;
    let keep = |k: usize| k == 0 || k + 1 == n;
    let allowed = |_: usize| bound;
    let limits = Limits {
        keep: &keep,
        allowed: &allowed,
    };
    for mode in SMOOTHING {
        let smooth = denoise(mode, &x, &y, &limits).unwrap();
        let worst = smooth
            .iter()
            .zip(&y)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        // The free fit moves points by about the noise (0.05), more than the bound.
        assert!(worst <= bound * (1.0 + 1e-9), "{mode:?}: moved {worst}");
        assert!(
            worst > 0.5 * bound,
            "{mode:?}: the bound was not reached ({worst})"
        );
    }
}

#[test]
fn the_curve_pre_pass_keeps_kept_points_and_nears_the_clean_curve_open_and_closed() {
    // An open arc and a closed ellipse (no corner: jump-lsq fits it periodic), noise 0.01.
    let n = 100;
    let arc: Vec<Vec2> = (0..n)
        .map(|k| 1.5 * PI * k as f64 / (n - 1) as f64)
        .map(|a| Vec2::new(2.0 * a.cos(), 2.0 * a.sin()))
        .collect();
    let ellipse: Vec<Vec2> = (0..n)
        .map(|k| 2.0 * PI * k as f64 / n as f64)
        .map(|a| Vec2::new(3.0 * a.cos(), 2.0 * a.sin()))
        .collect();
    let distance = |p: &Vec2, closed: bool| {
        if closed {
            // Radial distance to the ellipse, to first order: |F| / |∇F| for F = (x/3)² + (y/2)² − 1.
            let f = (p.x / 3.0).powi(2) + (p.y / 2.0).powi(2) - 1.0;
            f.abs() / (2.0 * Vec2::new(p.x / 9.0, p.y / 4.0)).norm()
        } else {
            (p.norm() - 2.0).abs()
        }
    };
    for (clean, closed) in [(arc, false), (ellipse, true)] {
        let e = noise(11, 2 * n, 0.01);
        let noisy: Vec<Vec2> = clean
            .iter()
            .enumerate()
            .map(|(k, p)| p + Vec2::new(e[2 * k], e[2 * k + 1]))
            .collect();
        let keep = |k: usize| k == 40 || (!closed && (k == 0 || k + 1 == n));
        let free = |_: usize| f64::INFINITY;
        let limits = Limits {
            keep: &keep,
            allowed: &free,
        };
        let to_curve =
            |p: &[Vec2]| (p.iter().map(|p| distance(p, closed).powi(2)).sum::<f64>() / n as f64).sqrt();
        for mode in SMOOTHING {
            let smooth = denoise_curve(mode, Projection::Off, &noisy, closed, &limits).unwrap();
            for k in (0..n).filter(|&k| keep(k)) {
                assert_eq!(smooth[k], noisy[k], "{mode:?} closed {closed}: point {k} moved");
            }
            let (before, after) = (to_curve(&noisy), to_curve(&smooth));
            // The discrepancy rule moves the points by the whole noise vector, tangential
            // part included, and on these curves smooths the shape as much as it removes
            // noise (measured: arc 0.0106 -> 0.0081, ellipse 0.0106 -> 0.0107); the GCV
            // variants end about twice as close.
            if mode != Denoise::JumpLsq {
                assert!(
                    after < 0.6 * before,
                    "{mode:?} closed {closed}: {before} -> {after}"
                );
            }
        }
    }
}

/// The turn (radians) at `points[i]` of a closed polygon between the chords to the points
/// three away (the pre-pass's corner measure).
fn turn(points: &[Vec2], i: usize) -> f64 {
    let n = points.len();
    let (p, q, r) = (points[(i + n - 3) % n], points[i], points[(i + 3) % n]);
    let (e, f) = (q - p, r - q);
    (e.x * f.y - e.y * f.x).atan2(e.dot(&f)).abs()
}

#[test]
fn a_closed_curves_corner_is_fitted_from_both_sides_and_stays_sharp() {
    // The loop of Han's strophoid: closed, a 90° corner at the node (0, 0), point 0; noise of
    // 0.03 on every point (the judge's `strophoid-loop`), eight draws.
    let strophoid = |t: f64| {
        let d = t * t + 1.0;
        Vec2::new(10.0 * (t * t * t - t) / d, 10.0 * (t * t - 1.0) / d)
    };
    let n = 96;
    let clean: Vec<Vec2> = (0..n)
        .map(|k| strophoid(-1.0 + 2.0 * k as f64 / n as f64))
        .collect();
    let free = |_: usize| f64::INFINITY;
    for mode in SMOOTHING {
        let (mut data, mut fitted) = (0.0, 0.0);
        for seed in 1..=8 {
            let e = noise(seed, 2 * n, 0.03);
            let noisy: Vec<Vec2> = (0..n)
                .map(|k| clean[k] + Vec2::new(e[2 * k], e[2 * k + 1]))
                .collect();
            let keep = |_: usize| false;
            let limits = Limits {
                keep: &keep,
                allowed: &free,
            };
            let smooth = denoise_curve(mode, Projection::FootPoint, &noisy, true, &limits).unwrap();
            // The corner estimated from both branches is nearer the node than its data point
            // (a kept data point would be exactly as far) ...
            let (before, after) = ((noisy[0] - clean[0]).norm(), (smooth[0] - clean[0]).norm());
            assert!(after < before, "{mode:?} seed {seed}: corner {before} -> {after}");
            (data, fitted) = (data + before, fitted + after);
            // ... and stays a corner: the turn there within 0.1 of the clean curve's (84° over
            // the chords three points away).
            let (sharp, clean_turn) = (turn(&smooth, 0), turn(&clean, 0));
            assert!(
                (sharp - clean_turn).abs() < 0.1,
                "{mode:?} seed {seed}: turn at the corner {sharp} (clean {clean_turn})"
            );
            // A kept corner stays bit for bit.
            let keep = |k: usize| k == 0;
            let limits = Limits {
                keep: &keep,
                allowed: &free,
            };
            let kept = denoise_curve(mode, Projection::FootPoint, &noisy, true, &limits).unwrap();
            assert_eq!(kept[0], noisy[0], "{mode:?} seed {seed}: the kept corner moved");
        }
        // Over the draws, by a third at least (measured: 0.33, 0.66, 0.68 of the data's
        // distance for jump-lsq, jump-lsq-gcv, gcv).
        assert!(
            fitted < 0.75 * data,
            "{mode:?}: corners {data} -> {fitted} in all"
        );
    }
}

#[test]
fn the_pre_pass_refuses_bad_input() {
    let keep = |_: usize| false;
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &keep,
        allowed: &free,
    };
    let x = [0.0, 1.0, 1.0, 2.0, 3.0, 4.0];
    let y = [0.0, 1.0, 0.5, 0.2, 0.1, 0.0];
    let mut nan = y;
    nan[3] = f64::NAN;
    let x_ok = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
    for mode in SMOOTHING {
        assert!(denoise(mode, &x, &y, &limits).is_err(), "{mode:?}: repeated x");
        assert!(denoise(mode, &x_ok, &nan, &limits).is_err(), "{mode:?}: NaN");
        let points: Vec<Vec2> = x.iter().zip(&y).map(|(&x, &y)| Vec2::new(x, y)).collect();
        let mut repeated = points.clone();
        repeated[2] = repeated[1];
        assert!(
            denoise_curve(mode, Projection::Off, &repeated, false, &limits).is_err(),
            "{mode:?}: repeated point"
        );
    }
}

#[test]
fn two_phase_with_the_jump_lsq_pre_pass_keeps_fixed_points_and_the_tolerance() {
    let n = 150;
    let e = noise(9, n, 0.02);
    let points: Vec<Vec2> = (0..n)
        .map(|k| 0.1 * k as f64)
        .zip(e)
        .map(|(x, e)| Vec2::new(x, (x / 2.0).sin() + e))
        .collect();
    let tolerance = 0.015;
    for mode in [Denoise::JumpLsq, Denoise::JumpLsqGcv] {
        let settings = TwoPhaseSettings::default().with_denoise(mode);
        let result = Pipeline::new(TwoPhase::new(settings))
            .with_constraints(
                Constraints::default()
                    .with_fixed([30, 90])
                    .with_end_clamp(EndClamp::G0)
                    .with_tolerance(tolerance),
            )
            .with_max_iterations(50)
            .run(points.clone())
            .unwrap();
        for k in [0, 30, 90, n - 1] {
            assert_eq!(result.points[k], points[k], "{mode:?}: point {k} moved");
        }
        for (k, (a, b)) in result.points.iter().zip(&points).enumerate() {
            assert_eq!(a.x.to_bits(), b.x.to_bits(), "{mode:?}: x of {k} moved");
            assert!(
                (a.y - b.y).abs() <= tolerance * (1.0 + 1e-12),
                "{mode:?}: point {k}"
            );
        }
    }
}

/// 200 points of y = sin(x/2) + noise of σ = 0.01, x = 0.1 k, the last point 0.05 (5σ) too
/// high; with the clean curve.
fn sine_with_a_bad_end() -> (Vec<Vec2>, Vec<f64>) {
    let n = 200;
    let x: Vec<f64> = (0..n).map(|k| 0.1 * k as f64).collect();
    let clean: Vec<f64> = x.iter().map(|x| (x / 2.0).sin()).collect();
    let mut y: Vec<f64> = clean.iter().zip(noise(4, n, 0.01)).map(|(c, e)| c + e).collect();
    y[n - 1] = clean[n - 1] + 0.05;
    (x.iter().zip(&y).map(|(&x, &y)| Vec2::new(x, y)).collect(), clean)
}

fn two_phase(points: &[Vec2], settings: TwoPhaseSettings, constraints: Constraints) -> Vec<Vec2> {
    Pipeline::new(TwoPhase::new(settings))
        .with_constraints(constraints)
        .with_max_iterations(50)
        .run(points.to_vec())
        .unwrap()
        .points
}

#[test]
fn free_ends_bring_a_noisy_end_point_nearer_the_clean_curve() {
    let (points, clean) = sine_with_a_bad_end();
    let n = points.len();
    // The error over the last 20 points (the kept end drags its neighbours).
    let end_error = |faired: &[Vec2]| {
        let tail: Vec<f64> = faired[n - 20..].iter().map(|p| p.y).collect();
        rms(&tail, &clean[n - 20..])
    };
    let default = two_phase(&points, TwoPhaseSettings::default(), Constraints::default());
    let kept = two_phase(
        &points,
        TwoPhaseSettings::default(),
        Constraints::default().with_end_clamp(EndClamp::G0),
    );
    assert_eq!(kept[n - 1], points[n - 1], "a G0 clamp moved the end point");
    let (free_end, kept_end) = ((default[n - 1].y - clean[n - 1]).abs(), 0.05);
    assert!(free_end < 0.5 * kept_end, "end point error {free_end}");
    let (free_tail, kept_tail) = (end_error(&default), end_error(&kept));
    // The end point's own error is halved at least; its neighbours, which the outlier drags
    // either way (a fit's free end follows it part of the way), no farther.
    assert!(
        free_tail < kept_tail,
        "RMS over the last 20 points: free {free_tail}, keep {kept_tail}"
    );
    eprintln!("end point error {free_end} (kept 0.05); last 20: {free_tail} against {kept_tail}");
}

#[test]
fn free_ends_still_keep_clamped_ends_and_fixed_points_bit_for_bit() {
    let (points, _) = sine_with_a_bad_end();
    let n = points.len();
    for mode in [Denoise::Gcv, Denoise::JumpLsq, Denoise::JumpLsqGcv] {
        let settings = TwoPhaseSettings::default().with_denoise(mode);
        let clamped = two_phase(
            &points,
            settings.clone(),
            Constraints::default()
                .with_end_clamp(EndClamp::G0)
                .with_fixed([60]),
        );
        let fixed = two_phase(
            &points,
            settings,
            Constraints::default().with_fixed([0, 60, n - 1]),
        );
        for faired in [&clamped, &fixed] {
            for k in [0, 60, n - 1] {
                assert_eq!(faired[k].x.to_bits(), points[k].x.to_bits(), "{mode:?}: x of {k}");
                assert_eq!(faired[k].y.to_bits(), points[k].y.to_bits(), "{mode:?}: y of {k}");
            }
        }
        assert_ne!(clamped[1], points[1], "{mode:?}: nothing moved");
    }
}

/// The factor γ on the trace of `jump-lsq-gcv`'s GCV: γ = 1 is [`denoise`] and
/// [`denoise_curve`] bit for bit; the curves' pre-pass's (> 1) smooths more, on a function and
/// on a curve; the other pre-passes ignore it; γ below 1 is refused with an error.
#[test]
fn gcv_gamma_of_the_pre_pass() {
    let gamma = TwoPhaseSettings::default().curve_prepass().prepass.gcv_gamma;
    assert!(gamma > 1.0, "{gamma}");
    assert_eq!(TwoPhaseSettings::function_prepass().gcv_gamma, 1.0);
    let n = 200;
    let x: Vec<f64> = (0..n).map(|k| 0.1 * k as f64).collect();
    let y: Vec<f64> = x
        .iter()
        .zip(noise(7, n, 0.01))
        .map(|(x, e)| (x / 2.0).sin() + e)
        .collect();
    let none = |_: usize| false;
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &none,
        allowed: &free,
    };
    let moved = |a: &[f64]| a.iter().zip(&y).map(|(a, b)| (a - b).abs()).sum::<f64>();
    let plain = denoise(Denoise::JumpLsqGcv, &x, &y, &limits).unwrap();
    assert_eq!(
        denoise_by(Denoise::JumpLsqGcv, Prepass::gcv(1.0), &x, &y, &limits).unwrap(),
        plain
    );
    let smoother = denoise_by(Denoise::JumpLsqGcv, Prepass::gcv(gamma), &x, &y, &limits).unwrap();
    assert!(
        moved(&smoother) > moved(&plain),
        "{} against {}",
        moved(&smoother),
        moved(&plain)
    );
    for mode in [Denoise::Gcv, Denoise::JumpLsq, Denoise::Off] {
        assert_eq!(
            denoise_by(mode, Prepass::gcv(gamma), &x, &y, &limits).unwrap(),
            denoise(mode, &x, &y, &limits).unwrap(),
            "{mode:?}"
        );
    }
    // A noisy arc: radius 2 over 270°, 100 points.
    let e = noise(5, 2 * 100, 0.01);
    let arc: Vec<Vec2> = (0..100)
        .map(|k| {
            let t = 1.5 * PI * k as f64 / 99.0;
            Vec2::new(2.0 * t.cos() + e[2 * k], 2.0 * t.sin() + e[2 * k + 1])
        })
        .collect();
    let shift = |a: &[Vec2]| a.iter().zip(&arc).map(|(a, b)| (a - b).norm()).sum::<f64>();
    let mode = Denoise::JumpLsqGcv;
    let plain = denoise_curve(mode, Projection::Off, &arc, false, &limits).unwrap();
    let with_gamma = |gamma: f64| {
        let rules = CurvePrepass::new(mode, Projection::Off).with_prepass(Prepass::gcv(gamma));
        denoise_curve_by(&rules, &arc, false, &limits).unwrap()
    };
    assert_eq!(with_gamma(1.0), plain);
    let smoother = with_gamma(gamma);
    assert!(
        shift(&smoother) > shift(&plain),
        "{} against {}",
        shift(&smoother),
        shift(&plain)
    );
    assert!(denoise_by(mode, Prepass::gcv(0.5), &x, &y, &limits).is_err());
}

/// The function pre-pass when jump-lsq's λ stops at its precision limit under GCV: it keeps
/// the fit (jump-lsq's at the limit or the cubic smoothing spline's, p by GCV) whose GCV score
/// V = (RSS/n) / (1 − tr A/n)² is the lower. Evenly spaced y = sin(x/2) over [0, 20] with
/// noise: on both data sets jump-lsq's GCV still falls at λ_max; at 1 000 points and σ = 0.1
/// its fit at the limit scores lower, at 2 000 points and σ = 0.05 the cubic's does.
#[test]
fn a_limited_jump_fit_gives_way_to_the_cubic_where_gcv_scores_the_cubic_lower() {
    use fairing::strategies::jump_lsq;
    use fairing::strategies::{
        CurveDomain, JumpLsqSettings, LambdaRule, SmoothingRule, SmoothingSettings, SmoothingSpline,
    };
    let none = |_: usize| false;
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &none,
        allowed: &free,
    };
    let mut winners = Vec::new();
    for (n, sigma, seed) in [(1_000, 0.1, 3), (2_000, 0.05, 3)] {
        let x: Vec<f64> = (0..n).map(|k| 20.0 * k as f64 / (n - 1) as f64).collect();
        let y: Vec<f64> = x
            .iter()
            .zip(noise(seed, n, sigma))
            .map(|(x, e)| (x / 2.0).sin() + e)
            .collect();
        let points: Vec<curve_repr::Vector<2>> = x
            .iter()
            .zip(&y)
            .map(|(&x, &y)| curve_repr::Vector::<2>::new(x, y))
            .collect();
        let jump = jump_lsq::fair(
            &points,
            &points,
            &Constraints::default(),
            CurveDomain::Function,
            false,
            &JumpLsqSettings::default().with_rule(LambdaRule::Gcv),
        )
        .unwrap();
        assert!(jump.report.lambda_limited, "n {n}: {:?}", jump.report);
        let column: Vec<curve_repr::Vector<1>> = y.iter().map(|&v| curve_repr::Vector::<1>::new(v)).collect();
        let cubic = SmoothingSpline::fit(
            &x,
            &column,
            &SmoothingSettings::default().with_rule(SmoothingRule::Gcv),
        )
        .unwrap();
        let (v_jump, v_cubic) = (jump.report.gcv.unwrap(), cubic.gcv().unwrap());
        let prepass = denoise_by(Denoise::JumpLsqGcv, Prepass::gcv(1.0), &x, &y, &limits).unwrap();
        let expected: Vec<f64> = if v_jump <= v_cubic {
            winners.push("jump");
            jump.points.iter().map(|p| p[1]).collect()
        } else {
            winners.push("cubic");
            cubic.values().iter().map(|v| v[0]).collect()
        };
        assert_eq!(
            prepass, expected,
            "n {n}: V {v_jump:e} (jump) against {v_cubic:e} (cubic)"
        );
    }
    // Both branches are taken.
    assert_eq!(winners, ["jump", "cubic"]);
}

/// σ̂ of `values` as jump-lsq estimates it, written out here: 1.4826 · MAD of the third
/// differences / √20.
fn third_difference_sigma(values: &[f64]) -> f64 {
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        let m = v.len() / 2;
        if v.len() % 2 == 1 {
            v[m]
        } else {
            0.5 * (v[m - 1] + v[m])
        }
    };
    let mut d: Vec<f64> = values
        .windows(4)
        .map(|w| w[3] - 3.0 * w[2] + 3.0 * w[1] - w[0])
        .collect();
    let centre = median(&mut d);
    let mut spread: Vec<f64> = d.iter().map(|v| (v - centre).abs()).collect();
    1.4826 * median(&mut spread) / 20f64.sqrt()
}

/// The function pre-pass's rule `auto` (`PrepassRule::Auto`) against its defining
/// condition: the GML fit, bit for bit, where that fit moves the points by at most
/// `AUTO_NOISE_FACTOR` σ̂ (RMS; σ̂ recomputed here from the third differences), else the GCV
/// fit, bit for bit. Both branches are taken: 200 points of a noisy sin(x/2) (32 draws, all
/// GML: its displacement is the noise's) and the SC(2)-0714 upper surface of `data/`
/// (tabulated ordinates, where GML smooths many times beyond σ̂ and GCV's fit is kept). The
/// discrepancy pre-pass (`denoise` = `jump-lsq`) ignores the rule. And what it is for: where
/// GCV's score is flat and its minimum falls at far too little smoothing, GML's fit comes
/// nearer the clean curve. Over the 32 draws the mean RMS to the
/// clean curve is lower than GCV's, and on the draw where GCV is farthest (seed 23) by more
/// than 15 % (measured: means 0.00277 → 0.00269; seed 23 0.00394 → 0.00320).
#[test]
fn the_auto_rule_keeps_gmls_fit_within_the_noise_and_gcvs_beyond() {
    use fairing::strategies::{FunctionEnds, AUTO_NOISE_FACTOR};
    use fairing::two_phase::PrepassRule;
    assert_eq!(TwoPhaseSettings::function_prepass().rule, PrepassRule::Auto);
    let none = |_: usize| false;
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &none,
        allowed: &free,
    };
    let fit = |rule, x: &[f64], y: &[f64]| {
        let prepass = Prepass::new(rule, 1.0).with_function_ends(FunctionEnds::Auto);
        denoise_by(Denoise::JumpLsqGcv, prepass, x, y, &limits).unwrap()
    };
    // Whether auto took GML's fit, checked against the condition; the GCV and auto fits.
    let branch = |x: &[f64], y: &[f64]| {
        let (gml, gcv, auto) = (
            fit(PrepassRule::Gml, x, y),
            fit(PrepassRule::Gcv, x, y),
            fit(PrepassRule::Auto, x, y),
        );
        let ratio = rms(&gml, y) / third_difference_sigma(y);
        let within = ratio <= AUTO_NOISE_FACTOR;
        assert_eq!(
            auto,
            if within { &gml } else { &gcv }.clone(),
            "GML's displacement {ratio} σ̂"
        );
        (within, ratio, gcv, auto)
    };
    let n = 200;
    let x: Vec<f64> = (0..n).map(|k| 0.1 * k as f64).collect();
    let clean: Vec<f64> = x.iter().map(|x| (x / 2.0).sin()).collect();
    let mut ratios = Vec::new();
    let (mut gcv_sum, mut auto_sum) = (0.0, 0.0);
    for seed in 1..=32 {
        let y: Vec<f64> = clean
            .iter()
            .zip(noise(seed, n, 0.01))
            .map(|(c, e)| c + e)
            .collect();
        let (within, ratio, gcv, auto) = branch(&x, &y);
        assert!(within, "seed {seed}: GML refused on white noise ({ratio} σ̂)");
        ratios.push(ratio);
        let (gcv, auto) = (rms(&gcv, &clean), rms(&auto, &clean));
        if seed == 23 {
            assert!(
                auto < 0.85 * gcv,
                "seed 23: RMS to the clean curve GCV {gcv}, auto {auto}"
            );
        }
        gcv_sum += gcv;
        auto_sum += auto;
    }
    assert!(
        auto_sum < gcv_sum,
        "mean RMS to the clean curve: GCV {gcv_sum}, auto {auto_sum} (×32)"
    );
    // The rule belongs to `jump-lsq-gcv`: the discrepancy pre-pass ignores it.
    let y: Vec<f64> = clean.iter().zip(noise(1, n, 0.01)).map(|(c, e)| c + e).collect();
    let by_rule = |rule| {
        let prepass = Prepass::new(rule, 1.0).with_function_ends(FunctionEnds::Auto);
        denoise_by(Denoise::JumpLsq, prepass, &x, &y, &limits).unwrap()
    };
    assert_eq!(
        by_rule(PrepassRule::Auto),
        by_rule(PrepassRule::Gcv),
        "denoise = jump-lsq"
    );
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, 0f64), |(l, h), r| (l.min(*r), h.max(*r)));
    println!("noisy sine: GML's displacement {lo:.3}–{hi:.3} σ̂");
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/airfoil_sc20714/sc20714_upper.csv"
    );
    let (x, y): (Vec<f64>, Vec<f64>) = crate::sapidis_farin_data::read(std::path::Path::new(path))
        .iter()
        .map(|p| (p.x, p.y))
        .unzip();
    let (within, ratio, _, _) = branch(&x, &y);
    println!("SC(2)-0714 upper: GML's displacement {ratio:.3} σ̂");
    assert!(!within, "GML kept on tabulated ordinates ({ratio} σ̂)");
}
