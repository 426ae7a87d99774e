//! Unit-spline sensitivities c̃_i^j = ∂c_i/∂y_j (Han et al. §3.3, Eq. 12–17), O(1) per entry
//! after O(n) precomputation.
//!
//! The unit spline function b_j is the spline (same x, same end condition, homogeneous: for
//! [`Clamped`](super::EndCondition::Clamped) zero end slopes) through the unit data vector
//! e_j; its c-values are the column c̃^j, and moving y_j by γ adds γ·c̃^j to c (Eq. 13). The
//! column solves A c̃^j = g^j, where g^j = ∂rhs/∂y_j is non-zero only in rows j−1, j, j+1.
//!
//! **Closed form, every end condition, every j (0-based here).** Forward elimination of g^j
//! leaves b_i = 0 for i < j − 1 and b_{j−1} = g_{j−1}/p_{j−1}; backward elimination leaves
//! b*_i = 0 for i > j + 1 and b*_{j+1} = g_{j+1}/p*_{j+1}. Row j then gives (Eq. 9 for g^j,
//! which is Eq. 14 when g^j is the interior pattern)
//!
//! c̃_j^j = (g_j − lower_j b_{j−1} − upper_j b*_{j+1}) / (diag_j − lower_j a_{j−1} − upper_j a*_{j+1}),
//!
//! then c̃_{j−1}^j = b_{j−1} − a_{j−1} c̃_j^j and c̃_{j+1}^j = b*_{j+1} − a*_{j+1} c̃_j^j (Eq. 15),
//! and outwards c̃_i^j = −a_i c̃_{i+1}^j for i < j − 1 (Eq. 16), c̃_i^j = −a*_i c̃_{i−1}^j for
//! i > j + 1 (Eq. 17). Written with g^j instead of Han's printed interior pattern, this is
//! right also where the printed Eq. 14–15 are not (papers/README.md): at j = 2 and j = n − 1
//! (Han's 1-based numbering) the end rows of runout and natural carry no data (g = 0 there),
//! at the end points j = 1, n themselves, and for clamped ends, whose end rows do carry data
//! (g_1 = ∓1/h_1 for j = 1, 2). Every entry is tested against a full solve with y = e_j.
//!
//! In the interior (g_{j−1} = 1/h_{j−1}, g_{j+1} = 1/h_j, and lower_j/p_{j−1} = a_{j−1}/h_{j−1})
//! the form above reduces to the printed Eq. 14–15. At Han's j = 2 (and symmetrically
//! j = n − 1) it gives, with Han's 1-based indices:
//!
//! - natural (a_1 = 0, g_1 = 0) and clamped (a_1 = 1/2, g_1 = 1/h_1, so g_1/p_1 = a_1/h_1): the
//!   printed Eq. 14–15 hold unchanged;
//! - parabolic runout (a_1 = −1, g_1 = 0): they do not. The correct entries are
//!   c̃_2^2 = −(1/h_1 + (1 + a*_3)/h_2) / (3h_1 + 2h_2 − a*_3 h_2) and c̃_1^2 = c̃_2^2, where the
//!   printed Eq. 14 drops the 1/h_1 term (its 1 + a_1 is 0) and Eq. 15 adds −1/h_1².
//!   Mirrored at j = n − 1: c̃_{n−1}^{n−1} = −((1 + a_{n−2})/h_{n−2} + 1/h_{n−1}) /
//!   (2h_{n−2} + 3h_{n−1} − a_{n−2}h_{n−2}) and c̃_n^{n−1} = c̃_{n−1}^{n−1}.
//!
//! At the end points themselves (j = 1, n; Han leaves them out) runout and natural have
//! g_1 = 0, g_2 = 1/h_1, clamped has g_1 = −1/h_1, g_2 = 1/h_1; the same form covers them.
//!
//! **Decay.** 0 < a_i, a*_i < 1/2 in the interior (proof in the `recurrence` module);
//! only the end factors a_1, a*_n (−1 for runout, 0 natural, 1/2 clamped) can reach 1 in
//! magnitude, so for |i − j| ≥ 2
//!
//! |c̃_i^j| ≤ 2 · max(|c̃_{j−1}^j|, |c̃_{j+1}^j|) · 2^{−(|i−j|−1)}.
//!
//! **Long products.** The products Π a_k over long ranges underflow, and computing them costs
//! O(|i − j|); `LogProducts` keeps prefix sums of ln|a_k| in double-double (so that a short
//! range near the end of a long spline is not the difference of two large, rounded sums),
//! with prefix counts of negative and zero factors for the sign.

use super::recurrence::rhs_derivative;
use super::SplineFunction;

/// Prefix sums over a sequence of factors f_k that give any product Π_{k∈[start,end)} f_k in
/// O(1), without underflow to 0/0: ln|f_k| summed in double-double, signs and zeros counted.
#[derive(Clone, Debug)]
pub(super) struct LogProducts {
    /// High part of Σ_{k<i} ln|f_k| (zeros skipped).
    high: Vec<f64>,
    /// Low part (accumulated rounding errors of `high`).
    low: Vec<f64>,
    /// #{k < i : f_k < 0}.
    negatives: Vec<u32>,
    /// #{k < i : f_k = 0}.
    zeros: Vec<u32>,
}

/// Knuth's TwoSum: s = fl(a + b) and the exact error a + b − s.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let error = (a - (s - bb)) + (b - bb);
    (s, error)
}

impl LogProducts {
    /// Prefix sums over `factors`, O(n).
    pub(super) fn new(factors: &[f64]) -> Self {
        let n = factors.len();
        let mut high = Vec::with_capacity(n + 1);
        let mut low = Vec::with_capacity(n + 1);
        let mut negatives = Vec::with_capacity(n + 1);
        let mut zeros = Vec::with_capacity(n + 1);
        let (mut h, mut l, mut neg, mut zero) = (0.0, 0.0, 0u32, 0u32);
        high.push(h);
        low.push(l);
        negatives.push(neg);
        zeros.push(zero);
        for &f in factors {
            if f == 0.0 {
                zero = zero.wrapping_add(1);
            } else {
                let (s, e) = two_sum(h, f.abs().ln());
                h = s;
                l += e;
                if f < 0.0 {
                    neg = neg.wrapping_add(1);
                }
            }
            high.push(h);
            low.push(l);
            negatives.push(neg);
            zeros.push(zero);
        }
        Self {
            high,
            low,
            negatives,
            zeros,
        }
    }

    /// Π f_k over k in [start, end); 1 for an empty range. Callers keep start ≤ end ≤ n.
    pub(super) fn product(&self, start: usize, end: usize) -> f64 {
        if start >= end {
            return 1.0;
        }
        if self.zeros[end] != self.zeros[start] {
            return 0.0;
        }
        let log = (self.high[end] - self.high[start]) + (self.low[end] - self.low[start]);
        let magnitude = log.exp();
        if (self.negatives[end].wrapping_sub(self.negatives[start])) % 2 == 1 {
            -magnitude
        } else {
            magnitude
        }
    }

    /// Π (−f_k) over k in [start, end).
    pub(super) fn alternating_product(&self, start: usize, end: usize) -> f64 {
        let p = self.product(start, end);
        if end.saturating_sub(start) % 2 == 1 {
            -p
        } else {
            p
        }
    }
}

/// A column of the sensitivity matrix, truncated to the window where it is not negligible.
#[derive(Clone, Debug, PartialEq)]
pub struct SensitivityColumn {
    /// Index of the first entry.
    pub first: usize,
    /// c̃_i^j for i = first, first + 1, …; every entry outside is below the window's bound.
    pub values: Vec<f64>,
}

/// Distances |i − j| up to which [`SplineFunction::sensitivity`] multiplies the elimination
/// factors directly instead of going through the logarithms.
const SHORT_RANGE: usize = 8;

impl SplineFunction {
    /// The three central entries (c̃_{j−1}^j, c̃_j^j, c̃_{j+1}^j) (Eq. 14–15 generalised, see
    /// the module doc), as cached at construction; entries that do not exist (j = 0 or n − 1)
    /// are 0. Callers keep j < n. O(1).
    #[inline]
    fn central_sensitivities(&self, j: usize) -> [f64; 3] {
        self.central[j]
    }

    /// [`central_sensitivities`](Self::central_sensitivities) computed from the elimination
    /// (run once per j at construction). Callers keep j < n.
    pub(super) fn compute_central_sensitivities(&self, j: usize) -> [f64; 3] {
        let n = self.x.len();
        let x = &self.x;
        let end = self.effective_end();
        let e = &self.elimination;
        let (lower, _, upper) = super::recurrence::row(x, end, j);
        let before = if j > 0 {
            rhs_derivative(x, end, j - 1, j) / e.forward_pivot[j - 1]
        } else {
            0.0
        };
        let after = if j + 1 < n {
            rhs_derivative(x, end, j + 1, j) / e.backward_pivot[j + 1]
        } else {
            0.0
        };
        let centre = (rhs_derivative(x, end, j, j) - lower * before - upper * after) / e.meeting_pivot[j];
        let previous = if j > 0 {
            before - e.forward_factor[j - 1] * centre
        } else {
            0.0
        };
        let next = if j + 1 < n {
            after - e.backward_factor[j + 1] * centre
        } else {
            0.0
        };
        [previous, centre, next]
    }

    /// The sensitivity c̃_i^j = ∂c_i/∂y_j of Han Eq. 13–17: how much c_i = y''(x_i)/6 changes per
    /// unit move of y_j, x and end condition fixed. Indices from 0 (Han's c̃_{i+1}^{j+1}).
    ///
    /// Valid for every end condition and every j, ends included (the printed Eq. 14–15 hold
    /// only away from the ends; see the module doc of `sensitivity` for the form used). For
    /// [`Clamped`](super::EndCondition::Clamped) the end slopes are held, so the column is the
    /// spline through e_j with zero end slopes. O(1): products over long ranges come from
    /// prefix sums of logarithms. Indices out of range give 0 (no such point, no influence).
    pub fn sensitivity(&self, i: usize, j: usize) -> f64 {
        let n = self.x.len();
        if i >= n || j >= n {
            return 0.0;
        }
        let [previous, centre, next] = self.central_sensitivities(j);
        if i == j {
            centre
        } else if i + 1 == j {
            previous
        } else if i == j + 1 {
            next
        } else if i == 0 && j >= 2 {
            // The end entry from its neighbour, so that c̃_0 = c̃_1 holds exactly for runout
            // (a_0 = −1) whichever way the neighbour is computed.
            -self.sensitivity(1, j) * self.elimination.forward_factor[0]
        } else if i + 1 == n && j + 2 < n {
            -self.sensitivity(n - 2, j) * self.elimination.backward_factor[n - 1]
        } else if i < j {
            // c̃_i = c̃_{j−1} Π_{k=i}^{j−2} (−a_k)  (Eq. 16); short ranges multiplied directly
            // (exact to rounding, no exp), long ones through the logarithms.
            if j - i <= SHORT_RANGE {
                let a = &self.elimination.forward_factor;
                (i..j - 1).rev().fold(previous, |value, k| -value * a[k])
            } else {
                previous * self.forward_log.alternating_product(i, j - 1)
            }
        } else if i - j <= SHORT_RANGE {
            let a = &self.elimination.backward_factor;
            (j + 2..=i).fold(next, |value, k| -value * a[k])
        } else {
            // c̃_i = c̃_{j+1} Π_{k=j+2}^{i} (−a*_k)  (Eq. 17)
            next * self.backward_log.alternating_product(j + 2, i + 1)
        }
    }

    /// The column c̃^j truncated to `window` entries on each side of j (fewer at the ends),
    /// computed by the recurrences Eq. 16–17 directly (more accurate than the logarithms,
    /// O(window)). Outside the window every entry is below
    /// 2 · max(|c̃_{j−1}^j|, |c̃_{j+1}^j|) · 2^{−window}. Returns `None` for j out of range.
    pub fn sensitivity_column(&self, j: usize, window: usize) -> Option<SensitivityColumn> {
        let n = self.x.len();
        if j >= n {
            return None;
        }
        let [previous, centre, next] = self.central_sensitivities(j);
        let first = j.saturating_sub(window.max(1));
        let last = (j + window.max(1)).min(n - 1);
        let mut values = vec![0.0; last - first + 1];
        values[j - first] = centre;
        if j > first {
            let a = &self.elimination.forward_factor;
            let mut value = previous;
            values[j - 1 - first] = value;
            for i in (first..j - 1).rev() {
                value *= -a[i];
                values[i - first] = value;
            }
        }
        if j < last {
            let a = &self.elimination.backward_factor;
            let mut value = next;
            values[j + 1 - first] = value;
            for i in j + 2..=last {
                value *= -a[i];
                values[i - first] = value;
            }
        }
        Some(SensitivityColumn { first, values })
    }
}

#[cfg(test)]
mod tests {
    use super::super::EndCondition;
    use super::*;

    /// Han's Eq. 14 as printed, 0-based: the centre entry of column j.
    fn printed_eq_14(spline: &SplineFunction, j: usize) -> f64 {
        let x = spline.x();
        let e = &spline.elimination;
        let (before, after) = (x[j] - x[j - 1], x[j + 1] - x[j]);
        let numerator =
            -((1.0 + e.forward_factor[j - 1]) / before + (1.0 + e.backward_factor[j + 1]) / after);
        numerator
            / (2.0 * (before + after) - e.forward_factor[j - 1] * before - e.backward_factor[j + 1] * after)
    }

    #[test]
    fn printed_eq_14_holds_inside_and_next_to_the_ends_except_for_runout() {
        let x = [0.0, 0.7, 1.0, 2.2, 2.5, 4.0, 4.1];
        let n = x.len();
        let y = [0.0; 7];
        for end in [
            EndCondition::ParabolicRunout,
            EndCondition::Natural,
            EndCondition::Clamped {
                start_slope: 0.0,
                end_slope: 0.0,
            },
        ] {
            let spline = SplineFunction::new(&x, &y, end).unwrap();
            for j in 1..n - 1 {
                let exact = spline.sensitivity(j, j);
                let agrees = (printed_eq_14(&spline, j) - exact).abs() < 1e-12 * exact.abs();
                let next_to_an_end = j == 1 || j == n - 2;
                let runout = end == EndCondition::ParabolicRunout;
                assert_eq!(agrees, !(runout && next_to_an_end), "{end:?} j = {j}");
            }
        }
        // The corrected runout entry next to the start (module doc, 1-based there).
        let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        let (h1, h2) = (x[1] - x[0], x[2] - x[1]);
        let a3 = spline.elimination.backward_factor[2];
        let corrected = -(1.0 / h1 + (1.0 + a3) / h2) / (3.0 * h1 + 2.0 * h2 - a3 * h2);
        assert!((spline.sensitivity(1, 1) - corrected).abs() < 1e-13 * corrected.abs());
        assert_eq!(spline.sensitivity(0, 1), spline.sensitivity(1, 1));
    }
}
