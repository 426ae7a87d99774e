//! Windowed update of a spline function after some y_j move (Han Eq. 13 truncated), O(window)
//! per moved point.

use super::recurrence::chord_slope;
use super::SplineFunction;
use crate::{Error, Result};

/// Entries of a sensitivity column kept on each side of the moved point by
/// [`SplineFunction::set_y`].
///
/// Beyond it every c̃_i^j is below 2 · max(|c̃_{j−1}^j|, |c̃_{j+1}^j|) · 2^{−64} ≈ 1e-19 of the
/// move's own effect (the decay bound of [`sensitivity`](super::sensitivity)), far below the
/// rounding of the update itself.
pub const UPDATE_WINDOW: usize = 64;

impl SplineFunction {
    /// Sets y_j to a new value for every `(j, new y_j)` in `moves` (in order; a repeated index
    /// ends at its last value) and updates c by c ← c + (new − old)·c̃^j (Han Eq. 13), truncated
    /// to [`UPDATE_WINDOW`] entries on each side of j. O(window) per move, independent of n.
    ///
    /// The result equals a full rebuild up to rounding (each update adds a few ulps of the
    /// change); call [`rebuild`](SplineFunction::rebuild) now and then to clear what
    /// accumulates over very many updates.
    ///
    /// Fails with [`Error::IndexOutOfRange`] on an index ≥ n, [`Error::NonFinite`] on a
    /// non-finite value, and [`Error::InvalidMove`] if the move overflows a chord slope or c.
    /// A failure leaves y unchanged and c as before (bit for bit when no windowed update
    /// preceded it since the last build; otherwise up to that update's rounding, c being
    /// rebuilt from y).
    pub fn set_y(&mut self, moves: &[(usize, f64)]) -> Result<()> {
        self.set_y_within(moves, UPDATE_WINDOW)
    }

    /// [`set_y`](SplineFunction::set_y) with the sensitivity columns truncated to `window`
    /// (at least 1) entries on each side of each moved point instead of [`UPDATE_WINDOW`]:
    /// every neglected entry is below 2 · max(|c̃_{j−1}^j|, |c̃_{j+1}^j|) · 2^{−window} of the
    /// move's own effect (0.27^window for uniform knots). For callers that make very many
    /// small moves and [`rebuild`](SplineFunction::rebuild) afterwards. O(window) per move.
    pub fn set_y_within(&mut self, moves: &[(usize, f64)], window: usize) -> Result<()> {
        let n = self.x.len();
        for &(index, value) in moves {
            if index >= n {
                return Err(Error::IndexOutOfRange {
                    what: "data points",
                    index,
                    len: n,
                });
            }
            if !value.is_finite() {
                return Err(Error::NonFinite { what: "y", index });
            }
        }
        // Up to 8 moves (the usual case) are written in place without allocating; if one
        // overflows, y is restored and c rebuilt from it (the same solve that made it, so c is
        // as before up to the rounding of earlier windowed updates). More moves take the path
        // that saves every overwritten value.
        let mut saved = [(0usize, 0.0f64); 8];
        if moves.len() > saved.len() {
            return self.set_y_saving(moves, window);
        }
        for (k, &(j, value)) in moves.iter().enumerate() {
            saved[k] = (j, self.y[j]);
            let delta = value - self.y[j];
            self.y[j] = value;
            let finite = delta.is_finite()
                && self.slopes_are_finite_around(j)
                && (delta == 0.0 || self.add_column_within(j, delta, window));
            if !finite {
                for &(j, old) in saved[..=k].iter().rev() {
                    self.y[j] = old;
                }
                self.rebuild()?;
                return Err(Error::InvalidMove {
                    index: j,
                    reason: "the move overflows",
                });
            }
        }
        Ok(())
    }

    /// c ← c + δ · c̃^j over `window` (≥ 1) entries on each side of j, the column generated in
    /// place by the recurrences Eq. 16–17 ([`Column::add`], the entries of
    /// [`sensitivity_column`](SplineFunction::sensitivity_column), without allocating).
    /// Callers keep j < n. Returns whether every updated entry is finite.
    fn add_column_within(&mut self, j: usize, delta: f64, window: usize) -> bool {
        let n = self.x.len();
        let window = window.max(1);
        let column = Column {
            central: self.central[j],
            forward: &self.elimination.forward_factor,
            backward: &self.elimination.backward_factor,
        };
        column.add(j, delta, window, 0, &mut self.c);
        let (first, last) = (j.saturating_sub(window), (j + window).min(n - 1));
        self.c[first..=last].iter().all(|c| c.is_finite())
    }

    /// Adds δ · c̃_k^j, truncated to `window` (≥ 1) entries on each side of j as
    /// [`set_y_within`](SplineFunction::set_y_within) truncates it, to `out[k − first]` for
    /// every such k in `first .. first + out.len()`; the spline is not changed. With `out`
    /// holding c over that range and δ = (new y_j) − y_j, `out` ends with what `set_y_within`
    /// would leave there, bit for bit (both run the same generator), so that a caller can judge a
    /// move before making it. Out-of-range j adds nothing. O(window).
    pub fn add_column_to(&self, j: usize, delta: f64, window: usize, first: usize, out: &mut [f64]) {
        if j >= self.x.len() {
            return;
        }
        let column = Column {
            central: self.central[j],
            forward: &self.elimination.forward_factor,
            backward: &self.elimination.backward_factor,
        };
        column.add(j, delta, window.max(1), first, out);
    }

    /// [`set_y_within`](SplineFunction::set_y_within) that saves every value it overwrites, so
    /// that a move that overflows leaves the spline exactly as it was.
    fn set_y_saving(&mut self, moves: &[(usize, f64)], window: usize) -> Result<()> {
        // Everything overwritten, in order, to undo a move that overflows.
        let mut saved_y: Vec<(usize, f64)> = Vec::with_capacity(moves.len());
        let mut saved_c: Vec<(usize, Vec<f64>)> = Vec::with_capacity(moves.len());
        for &(j, value) in moves {
            let Some(&old) = self.y.get(j) else { continue };
            let delta = value - old;
            saved_y.push((j, old));
            self.y[j] = value;
            if delta == 0.0 {
                continue;
            }
            let column = match self.sensitivity_column(j, window) {
                Some(column) if delta.is_finite() && self.slopes_are_finite_around(j) => column,
                _ => {
                    self.undo(saved_y, saved_c);
                    return Err(Error::InvalidMove {
                        index: j,
                        reason: "the move overflows",
                    });
                }
            };
            let range = column.first..column.first + column.values.len();
            let Some(window) = self.c.get_mut(range) else {
                continue;
            };
            saved_c.push((column.first, window.to_vec()));
            let mut finite = true;
            for (c, s) in window.iter_mut().zip(&column.values) {
                *c += delta * s;
                finite &= c.is_finite();
            }
            if !finite {
                self.undo(saved_y, saved_c);
                return Err(Error::InvalidMove {
                    index: j,
                    reason: "the move overflows the second derivatives",
                });
            }
        }
        Ok(())
    }

    /// Whether the chord slopes m_{j−1}, m_j next to point j and their difference are finite
    /// (a full rebuild would overflow otherwise).
    fn slopes_are_finite_around(&self, j: usize) -> bool {
        let n = self.x.len();
        let before = (j > 0).then(|| chord_slope(&self.x, &self.y, j - 1));
        let after = (j + 1 < n).then(|| chord_slope(&self.x, &self.y, j));
        let finite = |m: Option<f64>| m.is_none_or(f64::is_finite);
        finite(before) && finite(after) && finite(before.zip(after).map(|(b, a)| a - b))
    }

    /// Restores saved y and c values, latest first, so that the oldest value of an entry
    /// saved twice wins.
    fn undo(&mut self, saved_y: Vec<(usize, f64)>, saved_c: Vec<(usize, Vec<f64>)>) {
        for (j, old) in saved_y.into_iter().rev() {
            if let Some(y) = self.y.get_mut(j) {
                *y = old;
            }
        }
        for (first, values) in saved_c.into_iter().rev() {
            if let Some(window) = self.c.get_mut(first..first + values.len()) {
                window.copy_from_slice(&values);
            }
        }
    }
}

impl SplineFunction {
    /// The y change that changes c by exactly `dc` on the points `first .. first + dc.len()`
    /// and nowhere else: δy on the same points, δy = 0 elsewhere. O(dc.len()).
    ///
    /// A local y change has a local c change only for special δc: with r = T δc the change
    /// of the right-hand sides of the three-moment rows (Han Eq. 4,
    /// h_{k−1}δc_{k−1} + 2(h_{k−1} + h_k)δc_k + h_k δc_{k+1} = δm_k − δm_{k−1}), the slope
    /// changes δm_k = Σ_{l ≤ k} r_l must vanish after the window (Σ_k r_k = 0, "∫ δy'' = 0")
    /// and so must δy_{k+1} = Σ_{l ≤ k} h_l δm_l (Σ_k x_k r_k = 0 given the first, "∫ x δy'' = 0").
    /// [`moment_weights`](SplineFunction::moment_weights) gives these two conditions as
    /// weights on δc.
    ///
    /// The window must keep two points from each end (first ≥ 2, last ≤ n − 3), so that no end
    /// row (any [`EndCondition`](super::EndCondition)) changes. Fails with
    /// [`Error::InvalidMove`] if it does not, or if `dc` violates the two conditions by more
    /// than 1e-9 of its scale (then no local y change gives it), and with
    /// [`Error::NonFinite`] on a non-finite entry.
    pub fn local_y_change(&self, first: usize, dc: &[f64]) -> Result<Vec<f64>> {
        let n = self.x.len();
        let last = first + dc.len().max(1) - 1;
        if dc.is_empty() || first < 2 || last + 3 > n {
            return Err(Error::InvalidMove {
                index: first,
                reason: "a local change of c must keep two points from each end",
            });
        }
        if let Some(k) = dc.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                what: "change of c",
                index: first + k,
            });
        }
        let x = &self.x;
        let h = |k: usize| x[k + 1] - x[k];
        let at = |k: usize| {
            if (first..=last).contains(&k) {
                dc[k - first]
            } else {
                0.0
            }
        };
        // Rows first − 1 … last + 1 change; integrate twice from δy_{first−1} = 0.
        let (mut slope, mut dy) = (0.0, 0.0);
        let (mut r_scale, mut dy_scale) = (0.0f64, 0.0f64);
        let mut out = Vec::with_capacity(dc.len());
        for k in first - 1..=last + 1 {
            let r = h(k - 1) * at(k - 1) + 2.0 * (h(k - 1) + h(k)) * at(k) + h(k) * at(k + 1);
            r_scale = r_scale.max(r.abs());
            slope += r;
            dy += h(k) * slope;
            dy_scale = dy_scale.max(dy.abs());
            if k < last {
                out.push(dy);
            }
        }
        // Now slope = δm_{last+1} and dy = δy_{last+2}; both must vanish.
        let span = x[last + 1] - x[first - 1];
        if slope.abs() > 1e-9 * r_scale * dc.len() as f64
            || dy.abs() > 1e-9 * (dy_scale + r_scale * span * span)
        {
            return Err(Error::InvalidMove {
                index: first,
                reason: "the change of c is not the change of a local y move (its two moments do not vanish)",
            });
        }
        Ok(out)
    }

    /// The weights (w1_j, w2_j) of the two conditions on a local change of c
    /// ([`local_y_change`](SplineFunction::local_y_change)): Σ_j w1_j δc_j = 0 and
    /// Σ_j w2_j δc_j = 0 with w1_j = 3(h_{j−1} + h_j) (the column sums of the three-moment
    /// rows) and w2_j = (x_{j−1} − o)h_{j−1} + 2(x_j − o)(h_{j−1} + h_j) + (x_{j+1} − o)h_j (the
    /// same rows weighted by x − o; o is any origin, chosen near the window for accuracy).
    /// Callers keep 1 ≤ j ≤ n − 2. O(1).
    pub fn moment_weights(&self, j: usize, origin: f64) -> (f64, f64) {
        let x = &self.x;
        let (before, after) = (x[j] - x[j - 1], x[j + 1] - x[j]);
        let w1 = 3.0 * (before + after);
        let w2 = (x[j - 1] - origin) * before
            + 2.0 * (x[j] - origin) * (before + after)
            + (x[j + 1] - origin) * after;
        (w1, w2)
    }
}

/// A change of c made by [`SplineFunction::change_c_locally`], kept so that
/// [`SplineFunction::undo_local_change`] can restore y exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalChange {
    first: usize,
    old_y: Vec<f64>,
    dy: Vec<f64>,
    dc: Vec<f64>,
}

impl LocalChange {
    /// The first changed point.
    pub fn first(&self) -> usize {
        self.first
    }

    /// The y change δy_k of the points first, first + 1, … .
    pub fn dy(&self) -> &[f64] {
        &self.dy
    }
}

impl SplineFunction {
    /// Changes c by exactly `dc` on the points `first .. first + dc.len()` and nowhere else,
    /// moving y by [`local_y_change`](SplineFunction::local_y_change): y += δy and c += δc on
    /// those points, no solve. The result is the spline through the moved points up to
    /// rounding. O(dc.len()).
    ///
    /// Fails as `local_y_change` does, and with [`Error::InvalidMove`] (the spline unchanged)
    /// if a moved y or c overflows.
    pub fn change_c_locally(&mut self, first: usize, dc: &[f64]) -> Result<LocalChange> {
        let dy = self.local_y_change(first, dc)?;
        let range = first..first + dc.len();
        let finite = self.y[range.clone()]
            .iter()
            .zip(&dy)
            .all(|(y, d)| (y + d).is_finite())
            && self.c[range.clone()]
                .iter()
                .zip(dc)
                .all(|(c, d)| (c + d).is_finite());
        if !finite {
            return Err(Error::InvalidMove {
                index: first,
                reason: "the local change overflows",
            });
        }
        let old_y = self.y[range.clone()].to_vec();
        for (y, d) in self.y[range.clone()].iter_mut().zip(&dy) {
            *y += d;
        }
        for (c, d) in self.c[range].iter_mut().zip(dc) {
            *c += d;
        }
        Ok(LocalChange {
            first,
            old_y,
            dy,
            dc: dc.to_vec(),
        })
    }

    /// Undoes a [`change_c_locally`](SplineFunction::change_c_locally): y as it was, bit for
    /// bit, and c −= δc (as it was up to rounding). Meant for the change just made; a change
    /// that does not fit this spline's length is ignored. O(len).
    pub fn undo_local_change(&mut self, change: &LocalChange) {
        let range = change.first..change.first + change.old_y.len();
        if let (Some(y), Some(c)) = (self.y.get_mut(range.clone()), self.c.get_mut(range)) {
            y.copy_from_slice(&change.old_y);
            for (c, d) in c.iter_mut().zip(&change.dc) {
                *c -= d;
            }
        }
    }
}

/// What generates the sensitivity column c̃^j of one j: its three central entries and the
/// elimination factors of the recurrences Eq. 16–17.
struct Column<'a> {
    central: [f64; 3],
    forward: &'a [f64],
    backward: &'a [f64],
}

impl Column<'_> {
    /// `out[k − first] += δ · c̃_k^j` for the k within `window` (≥ 1) of j that lie in
    /// `first .. first + out.len()` (and in the n points the factors cover); the entries
    /// outside are generated (the recurrence runs through them) but not written. The one
    /// generator of both [`SplineFunction::add_column_within`] and
    /// [`SplineFunction::add_column_to`], so that a move judged before it is made is the move
    /// made, bit for bit. O(window).
    fn add(&self, j: usize, delta: f64, window: usize, first: usize, out: &mut [f64]) {
        let n = self.forward.len();
        let end = first + out.len();
        let mut put = |k: usize, value: f64| {
            if (first..end).contains(&k) {
                out[k - first] += value;
            }
        };
        let [previous, centre, next] = self.central;
        put(j, delta * centre);
        let low = j.saturating_sub(window).max(first);
        if j > low {
            let mut value = delta * previous;
            put(j - 1, value);
            for i in (low..j - 1).rev() {
                value *= -self.forward[i];
                put(i, value);
            }
        }
        let high = (j + window).min(n - 1).min(end.saturating_sub(1));
        if j < high {
            let mut value = delta * next;
            put(j + 1, value);
            for (k, factor) in self.backward.iter().enumerate().take(high + 1).skip(j + 2) {
                value *= -factor;
                put(k, value);
            }
        }
    }
}
