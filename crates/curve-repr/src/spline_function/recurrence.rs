//! The three-moment equations of a spline function and their solution by Han's forward and
//! backward recurrences (Han et al. Eq. 4–10), O(n).
//!
//! Rows are indexed from 0 here (Han counts from 1). Row i of the n × n system reads
//! `lower_i·c_{i−1} + diag_i·c_i + upper_i·c_{i+1} = rhs_i`; the interior rows are Han Eq. 4
//! (typo corrected as in `papers/README.md`: the last term is h_i·c_{i+1}),
//!
//! h_{i−1}c_{i−1} + 2(h_{i−1} + h_i)c_i + h_i c_{i+1} = m_i − m_{i−1},
//!
//! and the first and last rows are the [`EndCondition`]'s.
//!
//! Forward elimination turns row i into c_i + a_i c_{i+1} = b_i (Han Eq. 5–6 generalised to
//! any first row: a_i = upper_i / p_i with the pivot p_i = diag_i − lower_i a_{i−1});
//! backward elimination turns it into c_i + a*_i c_{i−1} = b*_i (Eq. 7–8, a*_i = lower_i / p*_i,
//! p*_i = diag_i − upper_i a*_{i+1}). Han's runout start a_1 = −1, b_1 = 0 is the row
//! c_1 − c_2 = 0; a natural start gives a_1 = 0 and a clamped one a_1 = 1/2.
//!
//! **Why |a_i| < 1/2 in the interior.** The first factor is −1, 0 or 1/2, so |a_0| ≤ 1 and
//! a_0 ≤ 1/2. If a_{i−1} ≤ 1/2 then p_i = 2h_{i−1} + 2h_i − h_{i−1}a_{i−1} ≥ 1.5h_{i−1} + 2h_i > 2h_i
//! and 0 < a_i = h_i / p_i < 1/2; by induction this holds for every interior row, and the
//! same argument runs backwards for a*_i. This is what makes the unit-spline sensitivities
//! decay like 2^{−|i−j|} (see [`sensitivity`](super::sensitivity)).

use super::EndCondition;
use crate::{Error, Result};

/// The end condition as actually imposed: runout on two points has one free parameter and is
/// replaced by the natural rows (the straight line, the least-energy member; see
/// [`EndCondition::ParabolicRunout`]).
pub(super) fn effective_end(end: EndCondition, n: usize) -> EndCondition {
    match end {
        EndCondition::ParabolicRunout if n < 3 => EndCondition::Natural,
        other => other,
    }
}

/// Interval length h_i = x_{i+1} − x_i. Callers keep i + 1 < x.len().
#[inline]
pub(super) fn step(x: &[f64], i: usize) -> f64 {
    x[i + 1] - x[i]
}

/// Slope m_i = (y_{i+1} − y_i)/h_i of the chord over interval i.
#[inline]
pub(super) fn chord_slope(x: &[f64], y: &[f64], i: usize) -> f64 {
    (y[i + 1] - y[i]) / step(x, i)
}

/// Coefficients (lower_i, diag_i, upper_i) of row i. Callers keep n ≥ 2 and i < n, and pass
/// the [`effective_end`].
pub(super) fn row(x: &[f64], end: EndCondition, i: usize) -> (f64, f64, f64) {
    let n = x.len();
    if i == 0 {
        match end {
            EndCondition::ParabolicRunout => (0.0, 1.0, -1.0),
            EndCondition::Natural => (0.0, 1.0, 0.0),
            EndCondition::Clamped { .. } => {
                let h = step(x, 0);
                (0.0, 2.0 * h, h)
            }
        }
    } else if i + 1 == n {
        match end {
            EndCondition::ParabolicRunout => (-1.0, 1.0, 0.0),
            EndCondition::Natural => (0.0, 1.0, 0.0),
            EndCondition::Clamped { .. } => {
                let h = step(x, n - 2);
                (h, 2.0 * h, 0.0)
            }
        }
    } else {
        let before = step(x, i - 1);
        let after = step(x, i);
        (before, 2.0 * (before + after), after)
    }
}

/// Right-hand side of row i: m_i − m_{i−1} inside, the end condition's value at the ends.
pub(super) fn rhs(x: &[f64], y: &[f64], end: EndCondition, i: usize) -> f64 {
    let n = x.len();
    if i == 0 {
        match end {
            EndCondition::Clamped { start_slope, .. } => chord_slope(x, y, 0) - start_slope,
            _ => 0.0,
        }
    } else if i + 1 == n {
        match end {
            EndCondition::Clamped { end_slope, .. } => end_slope - chord_slope(x, y, n - 2),
            _ => 0.0,
        }
    } else {
        chord_slope(x, y, i) - chord_slope(x, y, i - 1)
    }
}

/// ∂rhs_i/∂y_j, non-zero only for |i − j| ≤ 1: the unit data vector's right-hand side (the
/// system that defines Han's unit spline function b_j, §3.3).
pub(super) fn rhs_derivative(x: &[f64], end: EndCondition, i: usize, j: usize) -> f64 {
    let n = x.len();
    if i >= n || j >= n || i.abs_diff(j) > 1 {
        return 0.0;
    }
    let clamped = matches!(end, EndCondition::Clamped { .. });
    if i == 0 {
        if !clamped {
            return 0.0;
        }
        let h = step(x, 0);
        return if j == 0 { -1.0 / h } else { 1.0 / h };
    }
    if i + 1 == n {
        if !clamped {
            return 0.0;
        }
        let h = step(x, n - 2);
        return if j == n - 1 { -1.0 / h } else { 1.0 / h };
    }
    if j + 1 == i {
        1.0 / step(x, i - 1)
    } else if j == i {
        -1.0 / step(x, i) - 1.0 / step(x, i - 1)
    } else {
        1.0 / step(x, i)
    }
}

/// The forward and backward elimination factors of the system (Han Eq. 5 and 7, with their
/// pivots), which depend on x and the end condition only, not on y.
#[derive(Clone, Debug)]
pub(super) struct Elimination {
    /// a_i: forward factor, row i reads c_i + a_i c_{i+1} = b_i after forward elimination.
    pub forward_factor: Vec<f64>,
    /// p_i: forward pivot, the denominator of Eq. 5–6.
    pub forward_pivot: Vec<f64>,
    /// a*_i: backward factor, row i reads c_i + a*_i c_{i−1} = b*_i after backward elimination.
    pub backward_factor: Vec<f64>,
    /// p*_i: backward pivot, the denominator of Eq. 7–8.
    pub backward_pivot: Vec<f64>,
    /// The denominator of Eq. 9 (and 14): diag_j − lower_j a_{j−1} − upper_j a*_{j+1}.
    pub meeting_pivot: Vec<f64>,
}

fn check_pivot(pivot: f64, scale: f64) -> Result<()> {
    if pivot.is_finite() && pivot.abs() > 1e-14 * scale {
        Ok(())
    } else {
        Err(Error::Singular {
            what: "eliminating the three-moment equations",
        })
    }
}

impl Elimination {
    /// Computes every factor and pivot. O(n). Callers keep n ≥ 2 and pass the
    /// [`effective_end`].
    pub(super) fn new(x: &[f64], end: EndCondition) -> Result<Self> {
        let n = x.len();
        let mut forward_factor = Vec::with_capacity(n);
        let mut forward_pivot = Vec::with_capacity(n);
        let mut previous = 0.0;
        for i in 0..n {
            let (lower, diag, upper) = row(x, end, i);
            let pivot = diag - lower * previous;
            check_pivot(pivot, diag.abs() + lower.abs() + upper.abs())?;
            previous = upper / pivot;
            forward_pivot.push(pivot);
            forward_factor.push(previous);
        }
        let mut backward_factor = vec![0.0; n];
        let mut backward_pivot = vec![0.0; n];
        let mut next = 0.0;
        for i in (0..n).rev() {
            let (lower, diag, upper) = row(x, end, i);
            let pivot = diag - upper * next;
            check_pivot(pivot, diag.abs() + lower.abs() + upper.abs())?;
            next = lower / pivot;
            backward_pivot[i] = pivot;
            backward_factor[i] = next;
        }
        let mut meeting_pivot = Vec::with_capacity(n);
        for j in 0..n {
            let (lower, diag, upper) = row(x, end, j);
            let before = if j > 0 { lower * forward_factor[j - 1] } else { 0.0 };
            let after = if j + 1 < n {
                upper * backward_factor[j + 1]
            } else {
                0.0
            };
            let pivot = diag - before - after;
            check_pivot(pivot, diag.abs() + lower.abs() + upper.abs())?;
            meeting_pivot.push(pivot);
        }
        Ok(Self {
            forward_factor,
            forward_pivot,
            backward_factor,
            backward_pivot,
            meeting_pivot,
        })
    }

    /// Solves for c (Han Eq. 6 forward, then Eq. 10 back substitution c_i = b_i − a_i c_{i+1},
    /// which with Eq. 9 at the last row is the same solution). O(n).
    ///
    /// Fails with [`Error::Singular`] if a value overflows.
    pub(super) fn solve(&self, x: &[f64], y: &[f64], end: EndCondition) -> Result<Vec<f64>> {
        let n = x.len();
        let mut c = Vec::with_capacity(n);
        let mut previous = 0.0;
        for i in 0..n {
            let (lower, _, _) = row(x, end, i);
            previous = (rhs(x, y, end, i) - lower * previous) / self.forward_pivot[i];
            c.push(previous);
        }
        for i in (0..n.saturating_sub(1)).rev() {
            c[i] -= self.forward_factor[i] * c[i + 1];
        }
        if c.iter().all(|v| v.is_finite()) {
            Ok(c)
        } else {
            Err(Error::Singular {
                what: "solving the three-moment equations (a value overflowed)",
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tridiagonal;

    fn sample() -> (Vec<f64>, Vec<f64>) {
        let x = vec![0.0, 0.3, 1.1, 1.5, 2.9, 3.0, 4.2];
        let y = vec![1.0, -0.5, 2.0, 0.25, 1.5, 1.0, -2.0];
        (x, y)
    }

    #[test]
    fn recurrences_agree_with_the_thomas_solver() {
        let (x, y) = sample();
        let n = x.len();
        for end in [
            EndCondition::ParabolicRunout,
            EndCondition::Natural,
            EndCondition::Clamped {
                start_slope: 0.7,
                end_slope: -1.3,
            },
        ] {
            let elimination = Elimination::new(&x, end).unwrap();
            let c = elimination.solve(&x, &y, end).unwrap();
            let (mut lower, mut diag, mut upper, mut right) = (vec![], vec![], vec![], vec![]);
            for i in 0..n {
                let (l, d, u) = row(&x, end, i);
                lower.push(l);
                diag.push(d);
                upper.push(u);
                right.push(rhs(&x, &y, end, i));
            }
            let thomas = tridiagonal::solve(&lower, &diag, &upper, &right).unwrap();
            for i in 0..n {
                assert!(
                    (c[i] - thomas[i]).abs() < 1e-13 * (1.0 + thomas[i].abs()),
                    "{end:?} {i}"
                );
            }
        }
    }

    #[test]
    fn interior_factors_are_below_one_half() {
        let (x, _) = sample();
        let n = x.len();
        for end in [
            EndCondition::ParabolicRunout,
            EndCondition::Natural,
            EndCondition::Clamped {
                start_slope: 0.0,
                end_slope: 0.0,
            },
        ] {
            let e = Elimination::new(&x, end).unwrap();
            for i in 1..n - 1 {
                assert!(e.forward_factor[i] > 0.0 && e.forward_factor[i] < 0.5);
                assert!(e.backward_factor[i] > 0.0 && e.backward_factor[i] < 0.5);
            }
        }
    }

    #[test]
    fn rhs_derivative_is_the_difference_quotient_of_rhs() {
        let (x, y) = sample();
        let n = x.len();
        let end = EndCondition::Clamped {
            start_slope: 0.3,
            end_slope: 0.1,
        };
        for j in 0..n {
            let mut shifted = y.clone();
            shifted[j] += 1.0;
            for i in 0..n {
                let difference = rhs(&x, &shifted, end, i) - rhs(&x, &y, end, i);
                let derivative = rhs_derivative(&x, end, i, j);
                assert!((difference - derivative).abs() < 1e-12 * (1.0 + derivative.abs()));
            }
        }
    }
}
