//! Two-phase's curve pre-pass where jump-lsq's λ stops at its precision limit, against
//! jump-lsq run alone with the pre-pass's GCV trace factor γ (not a setting of jump-lsq, so
//! these tests live inside the crate).

use std::f64::consts::PI;

use curve_repr::Vec2;

use crate::strategies::CurveEnds;
use crate::two_phase::{
    denoise_curve_by, CurvePrepass, Denoise, Limits, Prepass, Projection, TwoPhaseSettings,
};
use crate::Constraints;

/// Deterministic noise in [−σ√3, σ√3) (standard deviation σ) from an LCG.
fn noise(seed: u64, count: usize, sigma: f64) -> Vec<f64> {
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

/// A curve whose jump-lsq fit stops at the precision limit, as the pre-pass sees it.
struct LimitedCurve {
    /// The pre-pass's points (`jump-lsq-gcv`, runout ends, no projection, no limits).
    prepass: Vec<Vec2>,
    /// jump-lsq's own fit with the pre-pass's settings.
    jump: crate::strategies::jump_lsq::Faired<2>,
    /// The cubic smoothing spline (p by GCV) over windowed chord lengths spanning the fit's
    /// knots ([`windowed_knots`]).
    cubic: crate::strategies::SmoothingSpline<2>,
    /// The cubic's score V_γ = (RSS/(2n)) / (1 − γ tr A/n)² (tr A read back from GCV's V₁ =
    /// n RSS / (n − tr A)²).
    v_cubic: f64,
}

/// Parameters over [a, b] from chords over windows of 2w + 1 points (cut at the ends), the
/// window the least power of 2 for which the tenth-smallest-percentile chord reaches 20 σ̂, σ̂
/// the RMS residual per coordinate of `fitted` (two-phase's `windowed_chord_knots`, written
/// again from its definition): point i's step is its chord over the window's point count,
/// and each knot step the mean of its two points' steps.
fn windowed_knots(noisy: &[Vec2], fitted: &[Vec2], a: f64, b: f64) -> Vec<f64> {
    let n = noisy.len();
    let rss: f64 = noisy
        .iter()
        .zip(fitted)
        .map(|(p, f)| (p - f).norm_squared())
        .sum();
    let sigma = (rss / (2 * n) as f64).sqrt();
    let chord = |i: usize, w: usize| {
        let (lo, hi) = (i.saturating_sub(w), (i + w).min(n - 1));
        (noisy[hi] - noisy[lo]).norm() / (hi - lo) as f64
    };
    let length = |i: usize, w: usize| chord(i, w) * ((i + w).min(n - 1) - i.saturating_sub(w)) as f64;
    let mut w = 1;
    while w < n / 8 {
        let mut lengths: Vec<f64> = (0..n).map(|i| length(i, w)).collect();
        lengths.sort_by(f64::total_cmp);
        if lengths[n / 10] >= 20.0 * sigma {
            break;
        }
        w *= 2;
    }
    let mut t = vec![0.0];
    for i in 1..n {
        t.push(t[i - 1] + 0.5 * (chord(i - 1, w) + chord(i, w)));
    }
    let total = t[n - 1];
    t.iter().map(|v| a + (b - a) * v / total).collect()
}

/// [`LimitedCurve`] of `noisy` (`closed`: periodic) with GCV's factor `gamma`.
fn limited_curve(noisy: &[Vec2], closed: bool, gamma: f64) -> LimitedCurve {
    use crate::strategies::jump_lsq;
    use crate::strategies::{
        CurveDomain, JumpLsqSettings, LambdaRule, SmoothingRule, SmoothingSettings, SmoothingSpline,
    };
    let none = |_: usize| false;
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &none,
        allowed: &free,
    };
    let rules = CurvePrepass::new(Denoise::JumpLsqGcv, Projection::Off)
        .with_prepass(Prepass::gcv(gamma))
        .with_ends(CurveEnds::Runout);
    let prepass = denoise_curve_by(&rules, noisy, closed, &limits).unwrap();
    let jump = jump_lsq::fair(
        noisy,
        noisy,
        &Constraints::default(),
        CurveDomain::Parametric,
        closed,
        &JumpLsqSettings::default()
            .with_rule(LambdaRule::Gcv)
            .with_gcv_gamma(gamma)
            .with_curve_ends(CurveEnds::Runout)
            .with_closed(closed),
    )
    .unwrap();
    let n = noisy.len();
    let t = windowed_knots(noisy, &jump.points, jump.knots[0], jump.knots[n - 1]);
    let cubic = SmoothingSpline::fit(
        &t,
        noisy,
        &SmoothingSettings::default().with_rule(SmoothingRule::Gcv),
    )
    .unwrap();
    let m = n as f64;
    let rss: f64 = cubic
        .values()
        .iter()
        .zip(noisy)
        .map(|(f, d)| (f - d).norm_squared())
        .sum();
    let trace = m - (m * rss / cubic.gcv().unwrap()).sqrt();
    let v_cubic = (rss / (2.0 * m)) / (1.0 - gamma * trace / m).powi(2);
    LimitedCurve {
        prepass,
        jump,
        cubic,
        v_cubic,
    }
}

/// The curve pre-pass when jump-lsq's λ stops at its precision limit under GCV: noisy arcs
/// as dense as their noise (radius 2 over 270°, σ = 0.01 in each coordinate; spacing 0.0094
/// at 500 points). The pre-pass keeps jump-lsq's fit at the limit or the cubic smoothing
/// spline over windowed chord lengths spanning the fit's knots ([`windowed_knots`]),
/// whichever has the lower GCV score V_γ = (RSS/(2n)) / (1 − γ tr A/n)²: at 500 points
/// jump-lsq's, at 2 000 the cubic's. Either comes within a fifth of the noise of the clean
/// arc. The cubic over the noisy points' chord lengths, which the pre-pass used to fall back
/// to, all but interpolates (two-phase then left the arc as noisy as it came: 175
/// inflections, RMS 0.0096 to the clean arc, on a Gaussian draw of 500 points). On an arc
/// sampled unevenly (2 000 points, spacings in a ratio of 4.3) the cubic over uniform
/// parameters, the pre-pass's choice before the windowed chords, smooths the dense part
/// less in arc length and ends farther from the clean arc than the cubic over the windowed
/// chords.
#[test]
fn a_limited_curve_fit_is_weighed_against_the_cubic_over_windowed_chords() {
    use crate::strategies::smoothing_spline::fit_parametric;
    use crate::strategies::{SmoothingRule, SmoothingSettings};
    let (sigma, radius) = (0.01, 2.0);
    let gamma = TwoPhaseSettings::default().curve_prepass().prepass.gcv_gamma;
    let mut winners = Vec::new();
    for (n, uneven) in [(500, false), (2_000, false), (2_000, true)] {
        let e = noise(if uneven { 17 } else { 13 }, 2 * n, sigma);
        // Uneven: s = u + 0.625 sin(2πu)/(2π), normalised, spacings from 0.375 to 1.625.
        let along = |u: f64| {
            if uneven {
                u + 0.625 * (2.0 * PI * u).sin() / (2.0 * PI)
            } else {
                u
            }
        };
        let noisy: Vec<Vec2> = (0..n)
            .map(|k| {
                let t = 1.5 * PI * along(k as f64 / (n - 1) as f64);
                Vec2::new(radius * t.cos() + e[2 * k], radius * t.sin() + e[2 * k + 1])
            })
            .collect();
        let case = limited_curve(&noisy, false, gamma);
        assert!(case.jump.report.lambda_limited, "n {n}: {:?}", case.jump.report);
        let (v_jump, v_cubic) = (case.jump.report.gcv.unwrap(), case.v_cubic);
        let expected = if v_jump <= v_cubic {
            winners.push("jump");
            case.jump.points
        } else {
            winners.push("cubic");
            case.cubic.values().to_vec()
        };
        assert!(
            case.prepass == expected,
            "n {n}: the pre-pass is not the fit of least GCV (jump {v_jump:e}, cubic {v_cubic:e})"
        );
        let m = n as f64;
        let rms =
            |points: &[Vec2]| (points.iter().map(|p| (p.norm() - radius).powi(2)).sum::<f64>() / m).sqrt();
        assert!(
            rms(&case.prepass) < 0.2 * sigma,
            "n {n}: RMS {} (noisy {})",
            rms(&case.prepass),
            rms(&noisy)
        );
        if uneven {
            let (a, b) = (case.jump.knots[0], case.jump.knots[n - 1]);
            let t: Vec<f64> = (0..n).map(|i| a + (b - a) * i as f64 / (n - 1) as f64).collect();
            let settings = SmoothingSettings::default().with_rule(SmoothingRule::Gcv);
            let uniform = crate::strategies::SmoothingSpline::fit(&t, &noisy, &settings).unwrap();
            assert!(
                rms(case.cubic.values()) < 0.9 * rms(uniform.values()),
                "uneven: windowed {} against uniform {}",
                rms(case.cubic.values()),
                rms(uniform.values())
            );
        }
        // Over the noisy chord lengths the cubic all but interpolates.
        let chordal = fit_parametric(
            &noisy,
            &SmoothingSettings::default().with_rule(SmoothingRule::Gcv),
        )
        .unwrap();
        assert!(chordal.p() > 0.999, "n {n}: p {}", chordal.p());
        assert!(
            rms(chordal.values()) > 0.5 * sigma,
            "n {n}: chordal RMS {}",
            rms(chordal.values())
        );
    }
    assert_eq!(winners, ["jump", "cubic", "cubic"]);
}

/// A closed curve as dense as its noise (a circle of radius 2, 500 points, σ = 0.01 per
/// coordinate): jump-lsq's periodic fit stops at its precision limit, and the pre-pass keeps
/// it where its GCV score is no higher than that of the open cubic smoothing spline of the
/// same points over uniform parameters (here), else gives way to the seam blend of two open
/// fits. It used to give way always, to open cubics over the noisy chord lengths.
#[test]
fn a_limited_periodic_fit_is_kept_where_gcv_scores_it_lower() {
    use crate::curve_counts;
    let (n, sigma, radius) = (500, 0.01, 2.0);
    let e = noise(17, 2 * n, sigma);
    let noisy: Vec<Vec2> = (0..n)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / n as f64;
            Vec2::new(radius * t.cos() + e[2 * k], radius * t.sin() + e[2 * k + 1])
        })
        .collect();
    let case = limited_curve(
        &noisy,
        true,
        TwoPhaseSettings::default().curve_prepass().prepass.gcv_gamma,
    );
    assert!(case.jump.report.lambda_limited, "{:?}", case.jump.report);
    let (v_jump, v_cubic) = (case.jump.report.gcv.unwrap(), case.v_cubic);
    assert!(v_jump <= v_cubic, "jump {v_jump:e}, cubic {v_cubic:e}");
    assert!(
        case.prepass == case.jump.points,
        "the pre-pass is not jump-lsq's periodic fit"
    );
    // The clean circle's 0 inflections, counted on the closed sequence opened at two points
    // half a circle apart.
    for start in [0, n / 2] {
        let open: Vec<Vec2> = (0..=n).map(|k| case.prepass[(start + k) % n]).collect();
        assert_eq!(curve_counts(&open).unwrap().0, 0, "opened at {start}");
    }
}
