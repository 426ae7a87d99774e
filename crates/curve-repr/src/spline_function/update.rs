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
    /// Fails, leaving the spline unchanged, with [`Error::IndexOutOfRange`] on an index ≥ n,
    /// [`Error::NonFinite`] on a non-finite value, and [`Error::InvalidMove`] if the move
    /// overflows a chord slope or c.
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
