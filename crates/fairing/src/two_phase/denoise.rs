//! The noise pre-pass of two-phase fairing (not in the paper; [`Denoise`]).
//!
//! Han's rules are local and assume "minor offsets" (§3.3): each case moves a few points just
//! enough to give a run of c or e the sign of its neighbours. On measured data whose noise
//! dominates the curvature (a scan, a digitised line: c_i carries noise of order σ/h², which
//! on dense data is many times the curve's own c), the phases do reach few sign changes, but
//! only by moving points about as far as the noise, in patterns that fit the sign rules and
//! not the curve, so the result stays far from the true curve. The pre-pass removes the noise
//! first, the way the smoothing spline does, and leaves to the phases what they are made for:
//! the inflections and curvature vibrations a smoothing spline leaves (measured in
//! [`TwoPhaseSettings::denoise`](super::TwoPhaseSettings::denoise)).
//!
//! The data are replaced by the cubic smoothing spline's values ([`SmoothingSpline`], csaps's
//! convention) with p chosen by generalised cross-validation of the free fit (every weight
//! 1); at that p, points that may not move (the ends, fixed points) get weight +∞ and are
//! interpolated bit for bit. (GCV of the fit with the noisy ends interpolated asks for far
//! less smoothing: p = 0.9991 against 0.737 on 10^5 points of y = sin(x/2) + N(0, 0.01²),
//! 363 inflections left against 3; the clean curve has 1.) A point that a bound
//! (the tolerance band, a restraining radius) would not let go as far has its weight raised,
//! 2·(distance/allowed)² times per round, and the spline refitted at the same p (at most
//! [`MAX_REWEIGHTS`] rounds), as [`SmoothingSplineFairing`](crate::strategies::SmoothingSplineFairing)
//! does; the caller's constraints clip what is still outside. O(n) per GCV evaluation, about
//! 100 of them, and per round.

use std::f64::consts::PI;

use curve_repr::{Parametrization, Vec2, Vector};

use crate::strategies::{SmoothingRule, SmoothingSettings, SmoothingSpline};
use crate::Result;

/// Whether two-phase fairing first removes the data's noise
/// ([`TwoPhaseSettings::denoise`](super::TwoPhaseSettings::denoise)).
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    Hash,
    serde::Serialize,
    serde::Deserialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Denoise {
    /// The paper: the phases work on the data points as given.
    Off,
    /// A smoothing spline with p chosen by generalised cross-validation, once, before the
    /// phases (module doc).
    #[default]
    Gcv,
}

impl Denoise {
    /// `off` or `gcv`.
    pub fn name(self) -> &'static str {
        match self {
            Denoise::Off => "off",
            Denoise::Gcv => "gcv",
        }
    }
}

/// Rounds of reweighting for points that must stay within a bound, at most.
pub const MAX_REWEIGHTS: usize = 60;

/// Where a point may go: `keep(i)` (interpolated exactly) and the distance `allowed(i)` it
/// may move (+∞ for none).
pub struct Limits<'a> {
    /// Whether point i must not move.
    pub keep: &'a dyn Fn(usize) -> bool,
    /// How far point i may move.
    pub allowed: &'a dyn Fn(usize) -> f64,
}

impl Limits<'_> {
    /// No bound but the kept points.
    fn weights(&self, n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| if (self.keep)(i) { f64::INFINITY } else { 1.0 })
            .collect()
    }
}

/// The smoothing spline's values at `t` for `data`, p by GCV, the limits honoured by
/// reweighting (module doc); kept points returned bit for bit. O(n) per evaluation.
fn bounded_fit<const D: usize>(t: &[f64], data: &[Vector<D>], limits: &Limits<'_>) -> Result<Vec<Vector<D>>> {
    let n = data.len();
    let mut weights = limits.weights(n);
    let settings = SmoothingSettings::default().with_rule(SmoothingRule::Gcv);
    // p by GCV of the free fit: with the noisy ends interpolated, GCV asks for far less
    // smoothing (p = 0.9991 against 0.737 on 10^5 points of a noisy sine, 363 inflections
    // left against 7).
    let p = SmoothingSpline::fit(t, data, &settings)?.p();
    let settings = settings.with_p(p);
    let mut fit = SmoothingSpline::fit(t, data, &settings.clone().with_weights(weights.clone()))?;
    for _ in 0..MAX_REWEIGHTS {
        let mut violated = false;
        for (i, w) in weights.iter_mut().enumerate() {
            let allowed = (limits.allowed)(i);
            let distance = (fit.values()[i] - data[i]).norm();
            if w.is_finite() && distance > allowed {
                violated = true;
                *w = if allowed > 0.0 {
                    *w * 2.0 * (distance / allowed).powi(2)
                } else {
                    f64::INFINITY
                };
            }
        }
        if !violated {
            break;
        }
        fit = SmoothingSpline::fit(t, data, &settings.clone().with_weights(weights.clone()))?;
    }
    Ok(fit
        .values()
        .iter()
        .zip(data)
        .enumerate()
        .map(|(i, (v, old))| if (limits.keep)(i) { *old } else { *v })
        .collect())
}

/// The pre-pass on a function segment y(x) (module doc): the new y. `Denoise::Off`, or fewer
/// than 4 points, returns y unchanged. O(n) per GCV evaluation.
///
/// Errors: x not strictly increasing, non-finite values (the smoothing spline's errors).
pub fn denoise(mode: Denoise, x: &[f64], y: &[f64], limits: &Limits<'_>) -> Result<Vec<f64>> {
    if mode == Denoise::Off || x.len() < 4 {
        return Ok(y.to_vec());
    }
    let data: Vec<Vector<1>> = y.iter().map(|&v| Vector::<1>::new(v)).collect();
    Ok(bounded_fit(x, &data, limits)?.iter().map(|v| v[0]).collect())
}

/// A turn (radians) from which the point of a closed curve where the direction turns most is
/// a corner (an airfoil's trailing edge) that [`denoise_curve`] keeps as the seam of its fit.
pub const CORNER_TURN: f64 = PI / 4.0;

/// How many points away [`denoise_curve`] measures a closed curve's turns (between the chords
/// P_{i−3}P_i and P_iP_{i+3}).
pub const CORNER_REACH: usize = 3;

/// The pre-pass on a planar curve (arbitrary curves, Han §4.2): both coordinates smoothed over
/// the chord-length parameters, one p for the curve by generalised cross-validation, the
/// limits honoured (module doc). O(n) per GCV evaluation.
///
/// An open curve is fitted as it is. A closed curve (last point joined to the first) is
/// fitted as an open one that starts and ends at a seam point, kept: at the point of the
/// largest turn (measured over [`CORNER_REACH`] points) if that turn is a corner (at least
/// [`CORNER_TURN`]), which then stays sharp;
/// otherwise it is fitted twice, with seams half a curve apart, and the two fits are blended
/// with weights sin²(πk/n) and cos²(πk/n) (k the position from the first seam), so that each
/// point takes the fit in which it lies far from the seam, where the fit's natural end
/// conditions do not bend it. `Denoise::Off` or fewer than 4 points return the points.
///
/// Errors: repeated consecutive points, non-finite values.
pub fn denoise_curve(mode: Denoise, points: &[Vec2], closed: bool, limits: &Limits<'_>) -> Result<Vec<Vec2>> {
    let n = points.len();
    if mode == Denoise::Off || n < 4 {
        return Ok(points.to_vec());
    }
    // One open fit of the points in `order` (a closed walk repeats its first point last).
    let fit = |order: &[usize]| -> Result<Vec<Vec2>> {
        let sequence: Vec<Vec2> = order.iter().map(|&i| points[i]).collect();
        let last = order.len() - 1;
        let keep = |k: usize| (limits.keep)(order[k]) || (closed && (k == 0 || k == last));
        let allowed = |k: usize| (limits.allowed)(order[k]);
        let t = Parametrization::ChordLength.parameters(&sequence)?;
        let values = bounded_fit(
            &t,
            &sequence,
            &Limits {
                keep: &keep,
                allowed: &allowed,
            },
        )?;
        let mut out = points.to_vec();
        for (k, &i) in order
            .iter()
            .enumerate()
            .take(if closed { last } else { last + 1 })
        {
            out[i] = values[k];
        }
        Ok(out)
    };
    if !closed {
        let order: Vec<usize> = (0..n).collect();
        return fit(&order);
    }
    // The turn between the chords to the points CORNER_REACH away: at a dense, noisy nose
    // the turn from one point to the next can exceed that of a real corner.
    let reach = CORNER_REACH.min((n - 1) / 2).max(1);
    let turn = |i: usize| {
        let (p, q, r) = (points[(i + n - reach) % n], points[i], points[(i + reach) % n]);
        let (e, f) = (q - p, r - q);
        (e.x * f.y - e.y * f.x).atan2(e.dot(&f)).abs()
    };
    let (seam, largest) =
        (0..n).map(|i| (i, turn(i))).fold(
            (0, f64::NEG_INFINITY),
            |best, c| if c.1 > best.1 { c } else { best },
        );
    let around = |start: usize| -> Vec<usize> { (0..=n).map(|k| (start + k) % n).collect() };
    let first = fit(&around(seam))?;
    if largest >= CORNER_TURN {
        return Ok(first);
    }
    let second = fit(&around((seam + n / 2) % n))?;
    Ok((0..n)
        .map(|i| {
            if (limits.keep)(i) {
                return points[i];
            }
            let k = (i + n - seam) % n;
            let w = (PI * k as f64 / n as f64).sin().powi(2);
            first[i] * w + second[i] * (1.0 - w)
        })
        .collect())
}
