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
pub(super) const WINDOW_TOLERANCE: f64 = 1e-17;

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
fn window_of<const D: usize>(spline: &mut HermiteSpline<D>, j: usize) -> (isize, isize) {
    if spline.workspace.decays.len() != spline.points.len() {
        let decays = decays_of(spline);
        spline.workspace.decays = decays;
    }
    let decays = &spline.workspace.decays;
    let count = spline.points.len() as isize;
    let j = j as isize;
    let wrap = |k: isize| k.rem_euclid(count) as usize;
    if spline.is_closed() {
        let (mut lo, mut hi) = (j - 1, j + 1);
        let mut product = 1.0;
        while product > WINDOW_TOLERANCE && hi - j < count {
            hi += 1;
            product *= decays[wrap(hi)].0;
        }
        let mut product = 1.0;
        while product > WINDOW_TOLERANCE && j - lo < count {
            lo -= 1;
            product *= decays[wrap(lo)].1;
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
            product *= decays[hi as usize].0;
        }
        let mut product = 1.0;
        while lo > 0 && product > WINDOW_TOLERANCE {
            lo -= 1;
            if lo <= 1 {
                lo = 0;
                break;
            }
            product *= decays[lo as usize].1;
        }
        (lo, hi)
    }
}

/// [`decay`] forward and backward at every row where [`window_of`] reads it (every row of a
/// closed curve, the interior rows of an open one; 1 elsewhere, never read). O(n).
fn decays_of<const D: usize>(spline: &HermiteSpline<D>) -> Vec<(f64, f64)> {
    let count = spline.points.len();
    (0..count)
        .map(|k| {
            if spline.is_closed() || (k >= 1 && k + 1 < count) {
                (decay(spline, k, true), decay(spline, k, false))
            } else {
                (1.0, 1.0)
            }
        })
        .collect()
}

/// Moves of at most this many points keep their bookkeeping (old positions, windows) on the
/// stack; more allocate.
const STACK_MOVES: usize = 4;

/// Storage of the windowed solves, kept by the spline between moves so that a move
/// allocates nothing once it has grown to the longest window met. Not part of the spline's
/// value: equal to any other, empty in a clone.
#[derive(Default)]
pub(super) struct Workspace<const D: usize> {
    /// Four f64 per row: the three diagonals and the Thomas algorithm's scratch.
    pub(super) numbers: Vec<f64>,
    /// The right-hand sides, then the tangents.
    pub(super) values: Vec<Vector<D>>,
    /// The decay bounds of [`window_of`] at every row, forward and backward ([`decays_of`]):
    /// they depend on the knots only. Empty until the first move, and after
    /// [`Clone::clone_from`] (which may change the knots).
    pub(super) decays: Vec<(f64, f64)>,
    /// The rows of the tangent system for the current points, where known (filled as the
    /// windowed updates read them): a move of P_j changes only rows j − 1, j, j + 1, so a
    /// window's other rows are copied rather than rebuilt (the same bits:
    /// [`HermiteSpline::row_with`] is what the solve builds). Cleared whenever the points
    /// change otherwise (a failed move, [`Clone::clone_from`],
    /// [`HermiteSpline::refit`]).
    pub(super) rows: Vec<Option<solve::Row<D>>>,
    /// The weights (a_k, b_k) = (h_k, h_{k−1})/(h_{k−1} + h_k) of the rows of an open
    /// natural line, for [`unit_move_tangents`]: they depend on the knots only. Empty until
    /// the first unit move, and after [`Clone::clone_from`].
    pub(super) weights: Vec<(f64, f64)>,
}

impl<const D: usize> PartialEq for Workspace<D> {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl<const D: usize> std::fmt::Debug for Workspace<D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Workspace")
    }
}

/// A move of point `index` (of `count`) to `position`: an index in range, a finite position.
fn check_move<const D: usize>(count: usize, index: usize, position: Vector<D>) -> Result<()> {
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
    Ok(())
}

/// Validates `moves`, applies them and updates the tangents window by window; on failure
/// restores the points and tangents. Returns the rows whose tangents were re-solved (see
/// [`HermiteSpline::move_points_within`](super::HermiteSpline::move_points_within)).
pub(super) fn move_points<const D: usize>(
    spline: &mut HermiteSpline<D>,
    moves: &[(usize, Vector<D>)],
) -> Result<Option<(usize, usize)>> {
    let count = spline.points.len();
    for &(index, position) in moves {
        check_move(count, index, position)?;
    }
    if moves.is_empty() {
        return Ok(None);
    }
    let mut small = [(0, Vector::<D>::zeros()); STACK_MOVES];
    let mut large = Vec::new();
    let old_points: &mut [(usize, Vector<D>)] = if moves.len() <= STACK_MOVES {
        &mut small[..moves.len()]
    } else {
        large.resize(moves.len(), (0, Vector::<D>::zeros()));
        &mut large
    };
    for (old, &(index, position)) in old_points.iter_mut().zip(moves) {
        *old = (index, spline.points[index]);
        spline.points[index] = position;
    }
    // The rows a moved point enters (its own and its neighbours') are built anew.
    let rows = &mut spline.workspace.rows;
    if rows.len() == count {
        for &(index, _) in moves {
            let previous = if index == 0 { count - 1 } else { index - 1 };
            let next = if index + 1 == count { 0 } else { index + 1 };
            for row in [previous, index, next] {
                rows[row] = None;
            }
        }
    }
    let result = update_tangents(spline, moves);
    if result.is_err() {
        for &(index, position) in old_points.iter().rev() {
            spline.points[index] = position;
        }
        spline.workspace.rows.clear();
    }
    result
}

/// Solves every window (`total` rows in all) into the workspace's first `total` rows, in order.
fn solve_windows<const D: usize>(
    spline: &HermiteSpline<D>,
    windows: &[(isize, isize)],
    total: usize,
    workspace: &mut Workspace<D>,
    cached: bool,
) -> Result<()> {
    let count = spline.points.len() as isize;
    if cached && workspace.rows.len() != count as usize {
        workspace.rows.clear();
        workspace.rows.resize(count as usize, None);
    }
    let mut cache = cached.then_some(&mut workspace.rows[..]);
    let (lower, rest) = workspace.numbers[..4 * total].split_at_mut(total);
    let (diag, rest) = rest.split_at_mut(total);
    let (upper, scratch) = rest.split_at_mut(total);
    let values = &mut workspace.values[..total];
    let mut offset = 0;
    for &(lo, hi) in windows {
        let start = lo.rem_euclid(count) as usize;
        let range = offset..offset + (hi - lo + 1) as usize;
        let rows = solve::WindowRows {
            lower: &mut lower[range.clone()],
            diag: &mut diag[range.clone()],
            upper: &mut upper[range.clone()],
            scratch: &mut scratch[range.clone()],
            values: &mut values[range.clone()],
        };
        solve::window(spline, start, rows, cache.as_deref_mut())?;
        offset = range.end;
    }
    Ok(())
}

/// Merges sorted intervals that overlap or touch (no row left between them) in place;
/// returns how many are left, at the front.
fn merge(intervals: &mut [(isize, isize)]) -> usize {
    let mut len = 0;
    for k in 0..intervals.len() {
        let (lo, hi) = intervals[k];
        if len > 0 && lo <= intervals[len - 1].1 + 1 {
            intervals[len - 1].1 = intervals[len - 1].1.max(hi);
        } else {
            intervals[len] = (lo, hi);
            len += 1;
        }
    }
    len
}

/// The rows whose tangents moves of the points `moves` name change: the windows of the
/// moved points, merged, into the front of `windows` (one slot per move; their number
/// returned), unwrapped intervals in order (a closed curve's rows wrap modulo the point
/// count); `None` when the windows of a closed curve cover it (then every row is re-solved,
/// by the full cyclic solve).
fn plan<const D: usize>(
    spline: &mut HermiteSpline<D>,
    moves: &[(usize, Vector<D>)],
    windows: &mut [(isize, isize)],
) -> Option<usize> {
    let count = spline.points.len() as isize;
    for (window, &(j, _)) in windows.iter_mut().zip(moves) {
        *window = window_of(spline, j);
    }
    if spline.is_closed() {
        // Normalise so that lo ∈ [0, count); a window as long as the curve means a full solve.
        for window in windows.iter_mut() {
            let shift = window.0.div_euclid(count) * count;
            *window = (window.0 - shift, window.1 - shift);
        }
    }
    windows.sort_unstable();
    let mut merged = merge(windows);
    if spline.is_closed() {
        // The last window may wrap onto the first (and the grown first onto the next).
        while merged > 1 {
            let (first, last) = (windows[0], windows[merged - 1]);
            if last.1 + 1 < first.0 + count {
                break;
            }
            merged -= 1;
            windows[0] = (last.0 - count, first.1.max(last.1 - count));
            merged = merge(&mut windows[..merged]);
        }
        // A window must leave at least two rows outside it.
        let covered: isize = windows[..merged].iter().map(|(lo, hi)| hi - lo + 1).sum();
        if covered >= count - 1 {
            return None;
        }
    }
    Some(merged)
}

/// Solves the merged `windows` into the spline's workspace (grown as needed), in order;
/// returns the rows solved in all.
fn solve_planned<const D: usize>(
    spline: &mut HermiteSpline<D>,
    windows: &[(isize, isize)],
    cached: bool,
) -> Result<usize> {
    let total = windows
        .iter()
        .map(|(lo, hi)| (hi - lo + 1) as usize)
        .sum::<usize>();
    let mut workspace = std::mem::take(&mut spline.workspace);
    if workspace.values.len() < total {
        workspace.numbers.resize(4 * total, 0.0);
        workspace.values.resize(total, Vector::<D>::zeros());
    }
    let solved = solve_windows(spline, windows, total, &mut workspace, cached);
    spline.workspace = workspace;
    solved.map(|()| total)
}

/// Merges the windows of the moved points and solves each; falls back to a full solve when
/// the windows of a closed curve cover it. Tangents are written only after every solve
/// succeeded. Returns the first and last row re-solved (a closed curve's rows wrap: then
/// the first may be the larger), `(0, count − 1)` after a full solve.
fn update_tangents<const D: usize>(
    spline: &mut HermiteSpline<D>,
    moves: &[(usize, Vector<D>)],
) -> Result<Option<(usize, usize)>> {
    let count = spline.points.len() as isize;
    let mut small = [(0isize, 0isize); STACK_MOVES];
    let mut large = Vec::new();
    let windows: &mut [(isize, isize)] = if moves.len() <= STACK_MOVES {
        &mut small[..moves.len()]
    } else {
        large.resize(moves.len(), (0, 0));
        &mut large
    };
    let Some(merged) = plan(spline, moves, windows) else {
        spline.rebuild()?;
        return Ok(Some((0, count as usize - 1)));
    };
    let windows = &windows[..merged];
    solve_planned(spline, windows, true)?;
    let total = spline.points.len();
    let mut offset = 0;
    for &(lo, hi) in windows {
        let start = lo.rem_euclid(count) as usize;
        let len = (hi - lo + 1) as usize;
        // The rows start.. to the end of the line, then (round a closed one) from row 0.
        let values = &spline.workspace.values[offset..offset + len];
        let first = len.min(total - start);
        spline.tangents[start..start + first].copy_from_slice(&values[..first]);
        spline.tangents[..len - first].copy_from_slice(&values[first..]);
        offset += len;
    }
    let (first, last) = (windows[0].0, windows[windows.len() - 1].1);
    Ok(Some((
        first.rem_euclid(count) as usize,
        last.rem_euclid(count) as usize,
    )))
}

/// The tangents a move of point `index` to `position` gives, without making it (see
/// [`HermiteSpline::tangents_after_move`](super::HermiteSpline::tangents_after_move)):
/// `(first row, rows)`, their tangents in the workspace's first `rows` values.
pub(super) fn tangents_after_move<const D: usize>(
    spline: &mut HermiteSpline<D>,
    index: usize,
    position: Vector<D>,
) -> Result<(usize, usize)> {
    let count = spline.points.len();
    check_move(count, index, position)?;
    let old = std::mem::replace(&mut spline.points[index], position);
    let mut window = [(0isize, 0isize)];
    let result = match plan(spline, &[(index, position)], &mut window) {
        Some(_) => solve_planned(spline, &window, false)
            .map(|rows| (window[0].0.rem_euclid(count as isize) as usize, rows)),
        None => solve::tangents(spline).map(|all| {
            let values = &mut spline.workspace.values;
            values.clear();
            values.extend_from_slice(&all);
            (0, count)
        }),
    };
    spline.points[index] = old;
    result
}

/// [`tangents_after_move`] of point `index` to 1 on a natural open scalar spline whose
/// points are all 0 (see
/// [`HermiteSpline::unit_move_tangents`](super::HermiteSpline::unit_move_tangents)): the
/// window's rows built from the knots and the unit data directly, and the same
/// elimination as [`solve::window`] and [`tridiagonal::solve_in_place`] in the same order,
/// so the same bits, without the general rows' chord slopes of every row, the vector
/// arithmetic and the bookkeeping of a move. `(first row, rows)` as there.
///
/// [`tridiagonal::solve_in_place`]: crate::tridiagonal::solve_in_place
pub(super) fn unit_move_tangents(spline: &mut HermiteSpline<1>, index: usize) -> Result<(usize, usize)> {
    let count = spline.points.len();
    if spline.is_closed() || spline.ends != super::HermiteEnds::Natural || count < 2 || index >= count {
        return tangents_after_move(spline, index, Vector::<1>::new(1.0));
    }
    let (lo, hi) = window_of(spline, index);
    let (lo, hi) = (lo as usize, hi as usize);
    let len = hi - lo + 1;
    let mut workspace = std::mem::take(&mut spline.workspace);
    if workspace.values.len() < len {
        workspace.numbers.resize(4 * len, 0.0);
        workspace.values.resize(len, Vector::<1>::zeros());
    }
    let (lower, rest) = workspace.numbers[..4 * len].split_at_mut(len);
    let (diag, rest) = rest.split_at_mut(len);
    let (upper, scratch) = rest.split_at_mut(len);
    let values = &mut workspace.values[..len];
    let knots = &spline.knots;
    if workspace.weights.len() != count {
        workspace.weights.clear();
        workspace.weights.extend((0..count).map(|k| {
            if k == 0 || k + 1 == count {
                (0.0, 0.0)
            } else {
                let (h0, h1) = (knots[k] - knots[k - 1], knots[k + 1] - knots[k]);
                (h1 / (h0 + h1), h0 / (h0 + h1))
            }
        }));
    }
    let weights = &workspace.weights;
    let point = |k: usize| if k == index { 1.0 } else { 0.0 };
    // The chord slope of segment s, as `chord_slope` computes it from the unit data (0/h =
    // +0 but next to the moved point).
    let slope = |s: usize| (point(s + 1) - point(s)) / (knots[s + 1] - knots[s]);
    // The rows of `row_with`, natural ends. An interior row whose chords both miss the moved
    // point has the right-hand side (+0·a + +0·b)·3 = +0 when the weights are finite.
    for (r, k) in (lo..=hi).enumerate() {
        let (l, d, u, rhs) = if k == 0 {
            (0.0, 2.0, 1.0, slope(0) * 3.0)
        } else if k + 1 == count {
            (1.0, 2.0, 0.0, slope(k - 1) * 3.0)
        } else {
            let (a, b) = weights[k];
            let far = k + 1 < index || k > index + 1;
            let rhs = if far && a.is_finite() && b.is_finite() {
                0.0
            } else {
                (slope(k - 1) * a + slope(k) * b) * 3.0
            };
            (a, 2.0, b, rhs)
        };
        lower[r] = l;
        diag[r] = d;
        upper[r] = u;
        values[r] = Vector::<1>::new(rhs);
    }
    // The tangents just outside the window are those of the zero line: 0 (`solve::window`
    // moves them to the right-hand side all the same, which keeps the signs of zeros).
    if lower[0] != 0.0 {
        values[0] -= Vector::<1>::zeros() * lower[0];
        lower[0] = 0.0;
    }
    if upper[len - 1] != 0.0 {
        values[len - 1] -= Vector::<1>::zeros() * upper[len - 1];
        upper[len - 1] = 0.0;
    }
    let solved = crate::tridiagonal::solve_in_place(lower, diag, upper, values, scratch)
        .and_then(|()| solve::check_tangents(values));
    spline.workspace = workspace;
    solved.map(|()| (lo, len))
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
        let mut spline = HermiteSpline::natural(&wave(500)).unwrap();
        let (lo, hi) = window_of(&mut spline, 250);
        assert!(hi - lo < 130, "{lo}..{hi}");
        assert!(lo > 100 && hi < 400);
        assert_eq!(window_of(&mut spline, 0).0, 0);
        assert_eq!(window_of(&mut spline, 499).1, 499);
    }

    /// `move_points_within` names every row whose tangent changed (and the moved points);
    /// the rows outside keep their tangents bit for bit, and the storage a spline keeps
    /// between moves changes no result.
    #[test]
    fn reported_rows_hold_every_changed_tangent() {
        let mut spline = HermiteSpline::natural(&wave(300)).unwrap();
        let before = spline.clone();
        let moves = [(150, Vec2::new(150.0, 3.0)), (152, Vec2::new(152.0, -2.0))];
        let (first, last) = spline.move_points_within(&moves).unwrap().unwrap();
        assert!(first < 150 && last > 152 && last - first < 160, "{first}..{last}");
        for k in (0..300).filter(|k| !(first..=last).contains(k)) {
            assert_eq!(spline.tangents[k], before.tangents[k], "row {k}");
        }
        for k in [149, 151, 153] {
            assert_ne!(spline.tangents[k], before.tangents[k], "row {k}");
        }
        assert_eq!(spline.move_points_within(&[]).unwrap(), None);
        // A fresh copy (no storage yet) and the used spline give the same bits.
        let mut fresh = spline.clone();
        let again = [(40, Vec2::new(40.0, 1.0))];
        spline.move_points(&again).unwrap();
        fresh.move_points(&again).unwrap();
        assert_eq!(spline, fresh);
        assert!(spline.tangents.iter().zip(&fresh.tangents).all(|(a, b)| a == b));
    }

    /// `tangents_after_move` gives the rows `move_points_within` re-solves and their
    /// tangents bit for bit, and leaves the spline as it was; `unit_move_tangents` on a
    /// zero line is the move of a point to 1 (natural ends by its own rows, other ends by
    /// the general path), on short lines, long ones and closed ones.
    #[test]
    fn trial_moves_are_the_moves_bit_for_bit() {
        let mut spline = HermiteSpline::natural(&wave(200)).unwrap();
        let before = spline.clone();
        for (index, position) in [
            (0, Vec2::new(0.5, 1.0)),
            (77, Vec2::new(70.0, -3.0)),
            (199, Vec2::new(1.0, 2.0)),
        ] {
            let (first, trial) = spline.tangents_after_move(index, position).unwrap();
            let trial = trial.to_vec();
            assert_eq!(spline, before);
            let mut moved = spline.clone();
            let (lo, hi) = moved.move_points_within(&[(index, position)]).unwrap().unwrap();
            assert_eq!((first, first + trial.len() - 1), (lo, hi));
            for (k, t) in trial.iter().enumerate() {
                let m = moved.tangents[first + k];
                assert!(
                    t.iter().zip(m.iter()).all(|(a, b)| a.to_bits() == b.to_bits()),
                    "row {}",
                    first + k
                );
            }
        }
        assert!(spline.tangents_after_move(200, Vec2::zeros()).is_err());
        assert!(spline.tangents_after_move(3, Vec2::new(f64::NAN, 0.0)).is_err());
        let knots: Vec<f64> = (0..=130)
            .map(|k| k as f64 + 0.4 * (k as f64 * 0.7).sin())
            .collect();
        for count in [2, 3, 5, 40, 130] {
            for ends in [
                HermiteEnds::Natural,
                HermiteEnds::ParabolicRunout,
                HermiteEnds::Closed,
            ] {
                if count < ends.min_points() {
                    continue;
                }
                let closed = ends.is_closed();
                let settings = HermiteSettings::new()
                    .with_parameters(knots[..count + usize::from(closed)].to_vec())
                    .with_ends(ends);
                let mut zero =
                    HermiteSpline::<1>::new(&vec![Vector::<1>::zeros(); count], &settings).unwrap();
                for i in 0..count {
                    let (first, unit) = zero.unit_move_tangents(i).unwrap();
                    let unit = unit.to_vec();
                    let mut moved = zero.clone();
                    moved.move_points(&[(i, Vector::<1>::new(1.0))]).unwrap();
                    for k in 0..count {
                        let offset = (k + count - first) % count;
                        let expected = moved.tangents[k][0].to_bits();
                        let got = unit.get(offset).map_or(0.0f64.to_bits(), |t| t[0].to_bits());
                        assert_eq!(got, expected, "{count} points, {ends:?}, move {i}, row {k}");
                    }
                }
            }
        }
    }

    /// The rows a spline keeps between moves change no bit: a long run of moves (single,
    /// adjacent pairs, at the ends, across a closed curve's seam, a failed one) on one
    /// spline gives the tangents and windows of the same moves on a fresh copy (no rows
    /// kept) and of the trial move (rows built from the points every time); a refit gives
    /// the spline built through the new points, and moves after it agree again.
    #[test]
    fn kept_rows_change_no_bit() {
        let bits = |s: &HermiteSpline<2>| -> Vec<u64> {
            s.tangents
                .iter()
                .chain(&s.points)
                .flat_map(|v| v.iter().map(|c| c.to_bits()).collect::<Vec<_>>())
                .collect()
        };
        for ends in [
            HermiteEnds::Natural,
            HermiteEnds::ParabolicRunout,
            HermiteEnds::Clamped {
                start: Vec2::new(1.0, 0.5),
                end: Vec2::new(-0.5, 1.0),
            },
            HermiteEnds::Closed,
        ] {
            let count = 120;
            let settings = HermiteSettings::default().with_ends(ends);
            let mut kept = HermiteSpline::new(&wave(count), &settings).unwrap();
            let mut moves: Vec<Vec<(usize, Vec2)>> = (0..60)
                .map(|k| {
                    let index = (k * 37 + 5) % count;
                    let shift = Vec2::new(0.3 * (k as f64).sin(), 0.2 * (k as f64 * 1.7).cos());
                    vec![(index, kept.points[index] + shift)]
                })
                .collect();
            moves.extend([
                vec![(0, Vec2::new(0.1, 0.4))],
                vec![(count - 1, Vec2::new(119.0, -0.3))],
                vec![(1, Vec2::new(1.2, 0.1)), (2, Vec2::new(2.1, -0.2))],
                vec![(count - 1, Vec2::new(118.8, 0.2)), (0, Vec2::new(-0.1, 0.0))],
                vec![(60, Vec2::new(60.0, 1e308)), (61, Vec2::new(61.0, -1e308))],
                vec![(59, Vec2::new(59.0, 0.5)), (60, Vec2::new(60.2, 0.1))],
                vec![(61, Vec2::new(61.0, 0.3))],
            ]);
            for (step, batch) in moves.iter().enumerate() {
                let mut fresh = kept.clone();
                let trial = (batch.len() == 1).then(|| {
                    let mut copy = kept.clone();
                    let (first, rows) = copy.tangents_after_move(batch[0].0, batch[0].1).unwrap();
                    (first, rows.to_vec())
                });
                let (a, b) = (kept.move_points_within(batch), fresh.move_points_within(batch));
                assert_eq!(a.is_ok(), b.is_ok(), "{ends:?}, step {step}");
                assert_eq!(bits(&kept), bits(&fresh), "{ends:?}, step {step}");
                if let (Ok(wa), Ok(wb)) = (&a, &b) {
                    assert_eq!(wa, wb, "{ends:?}, step {step}");
                }
                if let (Ok(Some((lo, hi))), Some((first, rows))) = (a, trial) {
                    if lo <= hi {
                        assert_eq!((first, first + rows.len() - 1), (lo, hi), "{ends:?}, step {step}");
                        for (k, t) in rows.iter().enumerate() {
                            let m = kept.tangents[first + k];
                            assert!(t.iter().zip(m.iter()).all(|(x, y)| x.to_bits() == y.to_bits()));
                        }
                    }
                }
            }
            // The overflowing pair failed on both and left the points as they were.
            let refit: Vec<Vec2> = wave(count)
                .iter()
                .map(|p| p * 1.5 + Vec2::new(0.0, 0.2))
                .collect();
            kept.refit(&refit).unwrap();
            let rebuilt =
                HermiteSpline::new(&refit, &settings.clone().with_parameters(kept.knots().to_vec())).unwrap();
            assert_eq!(bits(&kept), bits(&rebuilt), "{ends:?}, refit");
            let batch = [(30, Vec2::new(45.0, 2.0))];
            let mut fresh = kept.clone();
            kept.move_points(&batch).unwrap();
            fresh.move_points(&batch).unwrap();
            assert_eq!(bits(&kept), bits(&fresh), "{ends:?}, after the refit");
            assert!(kept.refit(&refit[1..]).is_err());
        }
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
