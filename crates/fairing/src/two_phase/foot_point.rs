//! Foot points of the data on the noise pre-pass's fitted curve (not in the paper;
//! [`Projection`]).
//!
//! The pre-pass of an arbitrary curve ([`denoise_curve`](super::denoise_curve)) fits both
//! coordinates over the chord-length parameters t_i of the noisy points and returns the fit's
//! values C(t_i). The noise moves the parameters as well as the points: a point displaced
//! along the curve gets a parameter displaced with it, and its value C(t_i) lies where the
//! parameter says, not where the point is nearest. That tangential part of the move costs
//! displacement (S_d) and brings the point no nearer to the curve. The foot point F_i, the
//! point of C nearest to the data point Q_i, keeps only the normal part: |F_i − Q_i| ≤
//! |C(t_i) − Q_i|. This is the step of Hoschek's parameter correction (Hoschek 1988,
//! "Intrinsic parametrization for approximation") that finds the foot points, without the
//! refit; OpenCASCADE's smoothing as the judge runs it returns the same foot points
//! (`occt.py`, `closest_points`).
//!
//! The search for F_i is local, so that the order of the points is kept: over the window
//! [t_i − ρ·h_{i−1}, t_i + ρ·h_i] (h the spans next to t_i, ρ = [`WINDOW`] < 1/2), which holds
//! two cubic pieces of the fit and never overlaps a neighbour's window; the closed curve's
//! windows wrap around its seam. On each piece the squared distance is sampled and its
//! stationary point refined by safeguarded Newton steps on g(u) = (C(u) − Q)·C′(u). The
//! result is never farther from Q_i than C(t_i) (the value itself is a candidate and is
//! returned bit for bit unless a candidate is strictly nearer), so every bound that C(t_i)
//! honoured (a restraining radius, a tolerance band around Q_i) still holds. O(1) per point
//! (two pieces, [`SAMPLES`] samples and at most [`NEWTON_STEPS`] steps each): O(n).

use curve_repr::{Curve, HermiteSpline, Vec2};

/// Whether the noise pre-pass of an arbitrary curve replaces its fit's values by the foot
/// points of the data on the fitted curve
/// ([`TwoPhaseSettings::curve_prepass`](super::TwoPhaseSettings::curve_prepass), foot-point).
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
pub enum Projection {
    /// The fit's values at the data's chord-length parameters (the pre-pass before
    /// projection; the paper has no pre-pass).
    Off,
    /// Each free point becomes the foot point of its data point on the fitted curve, searched
    /// near its own parameter ([module doc](self)). The default (measured in
    /// [`TwoPhaseSettings::curve_prepass`](super::TwoPhaseSettings::curve_prepass)).
    #[default]
    FootPoint,
    /// Hoschek's parameter correction: the curve is refitted on the foot-point parameters of
    /// the data on the previous fit
    /// ([`CORRECTION_ROUNDS`](super::CORRECTION_ROUNDS) times), then projected as
    /// `foot-point`.
    ParameterCorrection,
}

impl Projection {
    /// `off`, `foot-point` or `parameter-correction`.
    pub fn name(self) -> &'static str {
        match self {
            Projection::Off => "off",
            Projection::FootPoint => "foot-point",
            Projection::ParameterCorrection => "parameter-correction",
        }
    }
}

/// The fraction ρ of each span next to a point's parameter that its foot-point search covers
/// (below 1/2: the windows of neighbours never meet, so the order is kept strictly).
pub const WINDOW: f64 = 0.45;

/// Samples of the squared distance on each half window before the Newton refinement.
pub const SAMPLES: usize = 8;

/// Safeguarded Newton steps of the refinement, at most.
pub const NEWTON_STEPS: usize = 40;

/// One foot point: its parameter on the curve and the point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FootPoint {
    /// The parameter u of the foot point (for a closed curve it may lie up to
    /// ρ·h before t_0, on the closing piece).
    pub parameter: f64,
    /// C(u), or the curve's data point itself where no point of the window is strictly nearer.
    pub point: Vec2,
}

/// The foot points of `targets` (Q_i) on `curve` (its data point P_i at parameter t_i belongs
/// to Q_i), searched in the window of t_i ([module doc](self)); a point with `keep(i)`
/// returns P_i at t_i bit for bit. Each result is no farther from Q_i than P_i, and the
/// parameters increase strictly (by index; a closed curve's point 0 may lie before t_0, on
/// the closing piece, which still precedes point 1). O(n).
///
/// `targets` has one point per data point of `curve`; extra targets are ignored, and data
/// points without a target are returned as they are.
pub fn foot_points(
    curve: &HermiteSpline<2>,
    targets: &[Vec2],
    keep: &dyn Fn(usize) -> bool,
) -> Vec<FootPoint> {
    let points = curve.points();
    let t = curve.parameters();
    let knots = curve.knots();
    let n = points.len();
    let closed = curve.is_closed();
    let segments = curve.segment_count();
    (0..n)
        .map(|i| {
            let own = FootPoint {
                parameter: t[i],
                point: points[i],
            };
            let Some(&target) = targets.get(i) else {
                return own;
            };
            if keep(i) || segments == 0 {
                return own;
            }
            let mut best = (own, (points[i] - target).norm_squared());
            // The piece before t_i (segment i − 1; the closing one for point 0 of a closed
            // curve, shifted by the period) and the piece after it (segment i, if any).
            let before = if i > 0 {
                let h = t[i] - t[i - 1];
                Some((i - 1, t[i] - WINDOW * h, t[i], 0.0))
            } else if closed {
                let period = knots[segments] - knots[0];
                let h = knots[segments] - t[n - 1];
                Some((segments - 1, t[0] - WINDOW * h, t[0], period))
            } else {
                None
            };
            let after = (i < segments).then(|| {
                let h = knots[i + 1] - t[i];
                (i, t[i], t[i] + WINDOW * h, 0.0)
            });
            for (segment, a, b, shift) in before.into_iter().chain(after) {
                let jet = |u: f64| curve.jet_on_piece(segment, u + shift);
                if let Some((u, d2)) = nearest_on_piece(&jet, target, a, b) {
                    if d2 < best.1 {
                        best = (
                            FootPoint {
                                parameter: u,
                                point: jet(u)[0],
                            },
                            d2,
                        );
                    }
                }
            }
            best.0
        })
        .collect()
}

/// The parameter in [a, b] of the point of one cubic piece nearest to `q` and its squared
/// distance: the best of [`SAMPLES`] + 1 samples, refined by safeguarded Newton steps on
/// g(u) = (C(u) − q)·C′(u) in the bracket of the neighbouring samples. `None` for an empty
/// or non-finite window.
fn nearest_on_piece(jet: &dyn Fn(f64) -> [Vec2; 4], q: Vec2, a: f64, b: f64) -> Option<(f64, f64)> {
    if !(a.is_finite() && b.is_finite() && b > a) {
        return None;
    }
    let distance2 = |u: f64| (jet(u)[0] - q).norm_squared();
    let at = |j: usize| a + (b - a) * j as f64 / SAMPLES as f64;
    let (mut best_j, mut best) = (0, distance2(a));
    for j in 1..=SAMPLES {
        let d = distance2(at(j));
        if d < best {
            (best_j, best) = (j, d);
        }
    }
    let mut best_u = at(best_j);
    // The minimum lies between the neighbouring samples (or at an end of the window).
    let (mut lo, mut hi) = (at(best_j.saturating_sub(1)), at((best_j + 1).min(SAMPLES)));
    let mut u = best_u;
    for _ in 0..NEWTON_STEPS {
        let [c, d1, d2, _] = jet(u);
        let r = c - q;
        let g = r.dot(&d1);
        let slope = d1.dot(&d1) + r.dot(&d2);
        if g == 0.0 {
            break;
        }
        // g < 0: the distance still falls with u, so the minimum lies to the right.
        if g < 0.0 {
            lo = u;
        } else {
            hi = u;
        }
        let newton = u - g / slope;
        let next = if slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if next == u || (hi - lo) <= 4.0 * f64::EPSILON * (b - a).max(u.abs()) {
            u = next;
            break;
        }
        u = next;
    }
    for candidate in [u, lo, hi] {
        let d = distance2(candidate);
        if d < best {
            (best_u, best) = (candidate, d);
        }
    }
    Some((best_u, best))
}
