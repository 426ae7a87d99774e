//! The arbitrary-curve guard of [`SegmentedFairing`](super::SegmentedFairing): moves that make
//! the curve's own inflection or vibration counts worse are refused (not in the paper).

use curve_repr::{HermiteSpline, Vec2};
use fairness::report::parametric_counts;

use super::Segment;

/// Which moves of [`SegmentedFairing`](super::SegmentedFairing)'s passes are checked against
/// the whole curve's counts (not in the paper).
///
/// The counts are docs/CONTRACT.md's parametric-kind measures (the judge's too): curvature sign
/// changes and sign changes of the second differences of κ over t, both of the natural cubic
/// spline through the points with chord-length parameters ([`curve_counts`]). The phases lower
/// the counts of each segment's own x–c polyline, which are not these. A move is kept when it
/// lowers the inflections, or keeps them and does not raise the vibrations (inflections
/// first: removing the last inflection of a curve may cost a few vibrations).
///
/// On the judge's synthetic curves (`examples/two_phase_judge.rs`, after the `jump-lsq-gcv`
/// pre-pass) `off` lets the phases raise the vibrations the pre-pass left several times over;
/// `local` keeps them near the pre-pass's and still removes most inflections the pre-pass
/// left. The chunk of [`CURVE_GUARD_CHUNK`] points was chosen there (larger chunks let more
/// vibrations through, smaller ones keep inflections that it removes); `pass` alone undoes
/// nearly every pass. The cost: a closed airfoil keeps some of the pre-pass's inflections,
/// and a dent the pre-pass only smoothed stays where the phases would have spread it
/// (`tests/fairing/two_phase_ends.rs`).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum CurveGuard {
    /// Han §4.2.4: every blended move is applied.
    Off,
    /// A pass whose moves raise the whole curve's counts is undone whole (and the stage
    /// stops: the next pass would start from the same points). O(n) per pass.
    Pass,
    /// As `Pass`, and first the moves are tried along each segment in chunks of
    /// [`CURVE_GUARD_CHUNK`] of its moved points (those not shared with an earlier segment),
    /// one chunk at a time on the points the earlier chunks left; a chunk is refused if it
    /// raises the counts of the stretch from [`CURVE_GUARD_MARGIN`] points before it to as
    /// many after it (the natural spline through that stretch, before and after).
    /// O(n · margin / chunk) per pass.
    #[default]
    Local,
}

/// Points on each side of a chunk over which [`CurveGuard::Local`] recounts (a natural
/// spline's κ at a knot depends on a point k knots away by about 0.27^k: 16 knots away, by
/// 10^-9 of the move).
pub const CURVE_GUARD_MARGIN: usize = 16;

/// Moved points per chunk of [`CurveGuard::Local`] (measured: [`CurveGuard`]).
pub const CURVE_GUARD_CHUNK: usize = 16;

/// (inflections, vibrations) of the natural cubic spline through `points` with chord-length
/// parameters: sign changes of the signed curvature κ at the knots, and of Han's e built from
/// (t, κ), both under docs/CONTRACT.md's sign rule ([`parametric_counts`], the report's counts). `None` when the spline
/// or its curvature cannot be built (fewer than 3 points, coincident consecutive points, a
/// vanishing tangent). O(n).
pub fn curve_counts(points: &[Vec2]) -> Option<(usize, usize)> {
    if points.len() < 3 {
        return None;
    }
    let spline = HermiteSpline::natural(points).ok()?;
    let (inflections, vibrations) = parametric_counts(&spline).ok()?;
    Some((inflections?, vibrations))
}

/// Whether `new` has fewer inflections than `old`, or as many and no more vibrations. A count that
/// cannot be made for `new` refuses; one that cannot be made for `old` accepts (nothing to
/// keep).
fn no_worse(old: Option<(usize, usize)>, new: Option<(usize, usize)>) -> bool {
    match (old, new) {
        (None, _) => true,
        (Some(_), None) => false,
        (Some(a), Some(b)) => b.0 < a.0 || (b.0 == a.0 && b.1 <= a.1),
    }
}

/// The positions, in curve order, of `points[index]` for the stretch from `first` to `last`
/// (curve positions, `last` ≥ `first`, possibly ≥ n on a closed curve) widened by `margin` on
/// each side, clipped to the curve (open) or to one turn (closed).
fn stretch(n: usize, closed: bool, first: usize, last: usize, margin: usize) -> Vec<usize> {
    if closed {
        if last - first + 1 + 2 * margin >= n {
            return (0..n).collect();
        }
        let start = first + n - margin;
        (start..=last + n + margin).map(|p| p % n).collect()
    } else {
        let start = first.saturating_sub(margin);
        let end = (last + margin).min(n - 1);
        (start..=end).collect()
    }
}

/// Applies the guard to one pass: `points` the current points, `moves` the blended moves of
/// `segments`. Returns the moves kept (refused chunks zeroed) under [`CurveGuard::Local`];
/// the moves unchanged otherwise. The pass-level check is the caller's (it needs the moves as
/// the constraints shortened them).
pub(super) fn segment_moves(
    guard: CurveGuard,
    points: &[Vec2],
    closed: bool,
    segments: &[Segment],
    moves: &[Vec2],
) -> Vec<Vec2> {
    let mut kept = moves.to_vec();
    if guard != CurveGuard::Local {
        return kept;
    }
    let n = points.len();
    let mut decided = vec![false; n];
    let mut current = points.to_vec();
    for segment in segments {
        // The segment's own moved points, as positions along the curve from its first index.
        let first = segment.indices.first().copied().unwrap_or(0);
        let own: Vec<usize> = segment
            .indices
            .iter()
            .copied()
            .filter(|&i| i < n && !decided[i] && (moves[i].x != 0.0 || moves[i].y != 0.0))
            .collect();
        if own.is_empty() {
            continue;
        }
        let offset = |i: usize| if i >= first { i - first } else { i + n - first };
        for own in own.chunks(CURVE_GUARD_CHUNK) {
            let lo = own.iter().map(|&i| offset(i)).min().unwrap_or(0) + first;
            let hi = own.iter().map(|&i| offset(i)).max().unwrap_or(0) + first;
            let window = stretch(n, closed, lo, hi, CURVE_GUARD_MARGIN);
            let before: Vec<Vec2> = window.iter().map(|&i| current[i]).collect();
            for &i in own {
                decided[i] = true;
                current[i] = points[i] + moves[i];
            }
            let after: Vec<Vec2> = window.iter().map(|&i| current[i]).collect();
            if !no_worse(curve_counts(&before), curve_counts(&after)) {
                for &i in own {
                    current[i] = points[i];
                    kept[i] = Vec2::zeros();
                }
            }
        }
    }
    kept
}

/// Whether a pass from `before` to `after` (the whole curve) is no worse by the rule of
/// [`CurveGuard`]: the pass-level check of [`CurveGuard::Pass`] and [`CurveGuard::Local`].
pub(super) fn pass_keeps_counts(before: &[Vec2], after: &[Vec2]) -> bool {
    no_worse(curve_counts(before), curve_counts(after))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stretch_clips_open_curves_and_wraps_closed_ones() {
        assert_eq!(stretch(10, false, 1, 3, 2), vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(stretch(10, false, 7, 9, 2), vec![5, 6, 7, 8, 9]);
        assert_eq!(stretch(10, true, 8, 10, 1), vec![7, 8, 9, 0, 1]);
        assert_eq!(stretch(10, true, 0, 6, 2), (0..10).collect::<Vec<_>>());
    }

    #[test]
    fn counts_of_a_circle_arc_and_an_s_curve() {
        let arc: Vec<Vec2> = (0..20)
            .map(|k| {
                let a = 0.1 * k as f64;
                Vec2::new(a.cos(), a.sin())
            })
            .collect();
        assert_eq!(curve_counts(&arc).map(|c| c.0), Some(0));
        let s: Vec<Vec2> = (0..40)
            .map(|k| {
                let x = 0.2 * k as f64;
                Vec2::new(x, x.sin())
            })
            .collect();
        // sin over [0, 7.8] changes curvature sign at π and 2π.
        assert_eq!(curve_counts(&s).map(|c| c.0), Some(2));
        assert_eq!(curve_counts(&s[..2]), None);
    }
}
