//! Windowed update of the tangents after data points move.
//!
//! The tangents are linear in the points, M = A⁻¹ R(P), and a move of P_j changes the
//! right-hand side only in rows j − 1, j, j + 1. Beyond them the change δM solves the
//! homogeneous rows a_k δM_{k−1} + 2 δM_k + b_k δM_{k+1} = 0, so (to the right; mirror it to
//! the left) δM_k = ρ_k δM_{k−1} with ρ_k = −a_k/(2 + b_k ρ_{k+1}). Every ρ lies in [−1, 1]
//! (the far end gives 0, −½ or −1), hence |ρ_k| ≤ a_k/(2 − b_k) ≤ ½ and, one knot further from
//! the end, |ρ_k| ≤ q_k = a_k/(2 − b_k/2) (< ½ always; 2/7 ≈ 0.286 for uniform knots, whose
//! exact rate is 2 − √3 ≈ 0.268). The window grows from the moved point until the product of
//! the q_k falls below [`WINDOW_TOLERANCE`]; tangents outside it stay as they are, and the
//! rows inside are solved with those outside values held fixed. Since a_k + b_k = 1 < 2, the
//! error this makes inside the window is at most the neglected change at its border, i.e.
//! about 1e-17 of the largest tangent change. The window is at most ~57 knots per side for
//! any knot spacing (1/2 per knot, the worst case of a knot next to a much shorter
//! interval), ~31 for uniform knots. Windows of several moves that touch are merged; a window
//! that covers a closed curve's every row falls back to the full cyclic solve.

use super::{solve, HermiteSpline};
use crate::{Error, Result, Vector};

/// Relative size of tangent change below which the window stops.
pub const WINDOW_TOLERANCE: f64 = 1e-17;

/// Bound on |δM_k/δM_{k∓1}| at interior row k, going right (`forward`) or left.
fn decay<const D: usize>(spline: &HermiteSpline<D>, k: usize, forward: bool) -> f64 {
    let count = spline.points.len();
    let previous = if k == 0 { count - 1 } else { k - 1 };
    let (h0, h1) = (spline.step(previous), spline.step(k));
    let a = h1 / (h0 + h1);
    let b = h0 / (h0 + h1);
    let q = if forward {
        a / (2.0 - 0.5 * b)
    } else {
        b / (2.0 - 0.5 * a)
    };
    if q.is_finite() {
        q
    } else {
        1.0
    }
}

/// The window of rows, as an unwrapped interval `[lo, hi]` (a closed curve's rows wrap
/// modulo the point count), whose tangents a move of point `j` changes by more than
/// [`WINDOW_TOLERANCE`] relative.
fn window_of<const D: usize>(spline: &HermiteSpline<D>, j: usize) -> (isize, isize) {
    let count = spline.points.len() as isize;
    let j = j as isize;
    let wrap = |k: isize| k.rem_euclid(count) as usize;
    if spline.is_closed() {
        let (mut lo, mut hi) = (j - 1, j + 1);
        let mut product = 1.0;
        while product > WINDOW_TOLERANCE && hi - j < count {
            hi += 1;
            product *= decay(spline, wrap(hi), true);
        }
        let mut product = 1.0;
        while product > WINDOW_TOLERANCE && j - lo < count {
            lo -= 1;
            product *= decay(spline, wrap(lo), false);
        }
        (lo, hi)
    } else {
        let last = count - 1;
        let (mut lo, mut hi) = ((j - 1).max(0), (j + 1).min(last));
        let mut product = 1.0;
        while hi < last && product > WINDOW_TOLERANCE {
            hi += 1;
            if hi + 1 >= last {
                hi = last;
                break;
            }
            product *= decay(spline, hi as usize, true);
        }
        let mut product = 1.0;
        while lo > 0 && product > WINDOW_TOLERANCE {
            lo -= 1;
            if lo <= 1 {
                lo = 0;
                break;
            }
            product *= decay(spline, lo as usize, false);
        }
        (lo, hi)
    }
}

/// Validates `moves`, applies them and updates the tangents window by window; on failure
/// restores the points and tangents.
pub(super) fn move_points<const D: usize>(
    spline: &mut HermiteSpline<D>,
    moves: &[(usize, Vector<D>)],
) -> Result<()> {
    let count = spline.points.len();
    for &(index, position) in moves {
        if index >= count {
            return Err(Error::IndexOutOfRange {
                what: "data points",
                index,
                len: count,
            });
        }
        if position.iter().any(|c| !c.is_finite()) {
            return Err(Error::NonFinite { what: "point", index });
        }
    }
    if moves.is_empty() {
        return Ok(());
    }
    let old_points: Vec<(usize, Vector<D>)> = moves.iter().map(|&(i, _)| (i, spline.points[i])).collect();
    for &(index, position) in moves {
        spline.points[index] = position;
    }
    let result = update_tangents(spline, moves);
    if result.is_err() {
        for &(index, position) in old_points.iter().rev() {
            spline.points[index] = position;
        }
    }
    result
}

/// Merges sorted intervals that overlap or touch (no row left between them).
fn merge(sorted: &[(isize, isize)]) -> Vec<(isize, isize)> {
    let mut merged: Vec<(isize, isize)> = Vec::with_capacity(sorted.len());
    for &(lo, hi) in sorted {
        match merged.last_mut() {
            Some(last) if lo <= last.1 + 1 => last.1 = last.1.max(hi),
            _ => merged.push((lo, hi)),
        }
    }
    merged
}

/// Merges the windows of the moved points and solves each; falls back to a full solve when
/// the windows of a closed curve cover it. Tangents are written only after every solve
/// succeeded.
fn update_tangents<const D: usize>(
    spline: &mut HermiteSpline<D>,
    moves: &[(usize, Vector<D>)],
) -> Result<()> {
    let count = spline.points.len() as isize;
    let mut windows: Vec<(isize, isize)> = moves.iter().map(|&(j, _)| window_of(spline, j)).collect();
    if spline.is_closed() {
        // Normalise so that lo ∈ [0, count); a window as long as the curve means a full solve.
        for window in &mut windows {
            let shift = window.0.div_euclid(count) * count;
            *window = (window.0 - shift, window.1 - shift);
        }
    }
    windows.sort_unstable();
    let mut merged = merge(&windows);
    if spline.is_closed() {
        // The last window may wrap onto the first (and the grown first onto the next).
        while merged.len() > 1 {
            let (first, last) = (merged[0], merged[merged.len() - 1]);
            if last.1 + 1 < first.0 + count {
                break;
            }
            merged.pop();
            merged[0] = (last.0 - count, first.1.max(last.1 - count));
            merged = merge(&merged);
        }
        // A window must leave at least two rows outside it.
        let covered: isize = merged.iter().map(|(lo, hi)| hi - lo + 1).sum();
        if covered >= count - 1 {
            return spline.rebuild();
        }
    }
    let mut solutions = Vec::with_capacity(merged.len());
    for &(lo, hi) in &merged {
        let start = lo.rem_euclid(count) as usize;
        let len = (hi - lo + 1) as usize;
        solutions.push((start, solve::window(spline, start, len)?));
    }
    let total = spline.points.len();
    for (start, values) in solutions {
        for (k, value) in values.into_iter().enumerate() {
            spline.tangents[(start + k) % total] = value;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{HermiteEnds, HermiteSettings, Interpolant, Parametrization, Vec2};

    fn wave(n: usize) -> Vec<Vec2> {
        (0..n)
            .map(|i| {
                let t = i as f64;
                Vec2::new(t + 0.4 * (t * 0.7).sin(), (t * 0.3).sin() + 0.2 * (t * 2.1).cos())
            })
            .collect()
    }

    /// The bound on the decay: a unit move at the middle of a long uniform spline changes
    /// tangents k knots away by at most (2/7)^k relative, and by about (2 − √3)^k.
    #[test]
    fn tangent_changes_decay_geometrically() {
        let points = wave(201);
        let settings = HermiteSettings::default().with_parametrization(Parametrization::Uniform);
        let before = HermiteSpline::new(&points, &settings).unwrap();
        let mut after = before.clone();
        after
            .move_points(&[(100, points[100] + Vec2::new(0.0, 1.0))])
            .unwrap();
        after.rebuild().unwrap();
        let change = |k: usize| (after.tangents[k] - before.tangents[k]).norm();
        let near = change(101);
        for distance in 2..25 {
            let ratio = change(100 + distance) / near;
            assert!(
                ratio <= (2.0f64 / 7.0).powi(distance as i32 - 1),
                "distance {distance}"
            );
            if distance > 12 {
                continue;
            }
            let rate = (change(100 + distance) / change(100 + distance - 1)).abs();
            assert!(
                (rate - (2.0 - 3f64.sqrt())).abs() < 1e-6,
                "distance {distance}: {rate}"
            );
        }
    }

    #[test]
    fn windows_are_local_and_clipped_at_the_ends() {
        let spline = HermiteSpline::natural(&wave(500)).unwrap();
        let (lo, hi) = window_of(&spline, 250);
        assert!(hi - lo < 130, "{lo}..{hi}");
        assert!(lo > 100 && hi < 400);
        assert_eq!(window_of(&spline, 0).0, 0);
        assert_eq!(window_of(&spline, 499).1, 499);
    }

    #[test]
    fn bad_moves_are_errors_and_change_nothing() {
        let mut spline = HermiteSpline::natural(&wave(10)).unwrap();
        let before = spline.clone();
        assert!(matches!(
            spline.move_points(&[(1, Vec2::new(0.0, 0.0)), (10, Vec2::new(0.0, 0.0))]),
            Err(Error::IndexOutOfRange { index: 10, .. })
        ));
        assert!(matches!(
            spline.move_points(&[(3, Vec2::new(f64::NAN, 0.0))]),
            Err(Error::NonFinite { index: 3, .. })
        ));
        assert_eq!(spline, before);
        // An overflowing move fails and is undone.
        assert!(spline.move_points(&[(4, Vec2::new(1e308, -1e308))]).is_err());
        assert_eq!(spline, before);
    }

    #[test]
    fn small_closed_curves_fall_back_to_the_full_solve() {
        let settings = HermiteSettings::default().with_ends(HermiteEnds::Closed);
        let points = wave(7);
        let mut spline = HermiteSpline::new(&points, &settings).unwrap();
        spline.move_points(&[(6, Vec2::new(3.0, 3.0))]).unwrap();
        let mut moved = points.clone();
        moved[6] = Vec2::new(3.0, 3.0);
        let settings = settings.with_parameters(spline.knots().to_vec());
        let rebuilt = HermiteSpline::new(&moved, &settings).unwrap();
        for (a, b) in spline.tangents().iter().zip(rebuilt.tangents()) {
            assert!((a - b).norm() < 1e-12 * b.norm().max(1.0));
        }
    }
}
