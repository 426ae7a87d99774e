//! The cubic spline tangent solve of Zhang–Cheng §2 (Eq. 2), over given knots, for scalar or
//! vector values: natural (free) ends, or periodic for a closed grid line.
//!
//! A cubic Hermite spline C through values P_0..P_N at knots t_0 < … < t_N with tangents
//! M_0..M_N (Eq. 1) is C2 when, for i = 1..N−1 (Eq. 2),
//!
//! a_i M_{i−1} + 2 M_i + b_i M_{i+1} = 3 a_i (P_i − P_{i−1}) / h_{i−1} + 3 b_i (P_{i+1} − P_i) / h_i,
//!
//! with h_i = t_{i+1} − t_i, a_i = h_i / (h_{i−1} + h_i), b_i = h_{i−1} / (h_{i−1} + h_i). (The
//! paper writes the right-hand side as −3a_i/h_{i−1} P_{i−1} + c_i P_i + 3b_i/h_i P_{i+1} with
//! c_i = 3(a_i/h_{i−1} − b_i/h_i): the same.) The free (natural) ends C''(t_0) = C''(t_N) = 0
//! read 2 M_0 + M_1 = 3 (P_1 − P_0)/h_0 and M_{N−1} + 2 M_N = 3 (P_N − P_{N−1})/h_{N−1}. With
//! two values the solution is M_0 = M_1 = (P_1 − P_0)/h_0: the straight line.
//!
//! A **periodic** line (a closed grid line, P_N = P_0: the last value repeats the first) has
//! Eq. 2 at every knot t_0..t_{N−1} with indices taken mod N (h_{−1} = h_{N−1},
//! P_{−1} = P_{N−1}) and M_N = M_0: the cyclic system of N unknowns, C2 across the seam too.
//!
//! The matrix depends on the knots only, so a [`NaturalSplineSystem`] is set up once per knot
//! vector and solved for every grid line. Each solve is O(N) (Thomas algorithm, or
//! Sherman–Morrison over two of them for the cyclic system); the matrix is strictly diagonally
//! dominant (diagonal 2, off-diagonals summing to at most 1), so it is never singular.

use crate::tridiagonal::{self, Field};
use crate::{Error, Result};

/// The tridiagonal system of Eq. 2 with natural end rows, or the cyclic one of a closed line,
/// for one knot vector.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct NaturalSplineSystem {
    /// Knot spacings h_i = t_{i+1} − t_i, length N.
    steps: Vec<f64>,
    lower: Vec<f64>,
    diag: Vec<f64>,
    upper: Vec<f64>,
    /// Whether the line is closed (the cyclic system over t_0..t_{N−1}).
    periodic: bool,
}

impl NaturalSplineSystem {
    /// Sets up the natural (`periodic` false) or the periodic system for knots that the caller
    /// has checked to be finite and strictly increasing: at least two, or four for a periodic
    /// line (three distinct values and the repeat). O(N).
    pub(crate) fn with_periodic(knots: &[f64], periodic: bool) -> Result<Self> {
        let count = knots.len();
        let needed = if periodic { 4 } else { 2 };
        if count < needed {
            return Err(Error::TooFewPoints {
                what: if periodic {
                    "a closed cubic spline (three distinct values and the repeated first)"
                } else {
                    "a natural cubic spline"
                },
                needed,
                got: count,
            });
        }
        let steps: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
        if periodic {
            let n = count - 1;
            let mut lower = vec![0.0; n];
            let diag = vec![2.0; n];
            let mut upper = vec![0.0; n];
            for i in 0..n {
                let (before, after) = (steps[(i + n - 1) % n], steps[i]);
                let sum = before + after;
                lower[i] = after / sum;
                upper[i] = before / sum;
            }
            return Ok(Self {
                steps,
                lower,
                diag,
                upper,
                periodic,
            });
        }
        let mut lower = vec![0.0; count];
        let mut diag = vec![2.0; count];
        let mut upper = vec![0.0; count];
        upper[0] = 1.0;
        lower[count - 1] = 1.0;
        for i in 1..count - 1 {
            let (before, after) = (steps[i - 1], steps[i]);
            let sum = before + after;
            lower[i] = after / sum;
            upper[i] = before / sum;
            diag[i] = 2.0;
        }
        Ok(Self {
            steps,
            lower,
            diag,
            upper,
            periodic,
        })
    }

    /// The knot spacings h_i.
    pub(crate) fn steps(&self) -> &[f64] {
        &self.steps
    }

    /// Whether the line is closed.
    pub(crate) fn is_periodic(&self) -> bool {
        self.periodic
    }

    /// The tangents M_0..M_N of the natural (or periodic) cubic spline through `values` (one
    /// per knot; for a periodic line the last is taken to repeat the first and is not read).
    /// O(N).
    ///
    /// Fails with [`Error::LengthMismatch`] when `values` does not have one entry per knot.
    pub(crate) fn tangents<T: Field>(&self, values: &[T]) -> Result<Vec<T>> {
        let count = self.steps.len() + 1;
        if values.len() != count {
            return Err(Error::LengthMismatch {
                what: "values of a natural cubic spline",
                expected: count,
                got: values.len(),
            });
        }
        let h = &self.steps;
        if self.periodic {
            let n = count - 1;
            let value = |i: usize| values[i % n];
            let rhs: Vec<T> = (0..n)
                .map(|i| {
                    let previous = (i + n - 1) % n;
                    let before = (value(i) - value(previous)) * (3.0 * self.lower[i] / h[previous]);
                    let after = (value(i + 1) - value(i)) * (3.0 * self.upper[i] / h[i]);
                    before + after
                })
                .collect();
            let mut tangents = tridiagonal::solve_cyclic(&self.lower, &self.diag, &self.upper, &rhs)?;
            tangents.push(tangents[0]);
            return Ok(tangents);
        }
        let mut rhs = Vec::with_capacity(count);
        rhs.push((values[1] - values[0]) * (3.0 / h[0]));
        for i in 1..count - 1 {
            let before = (values[i] - values[i - 1]) * (3.0 * self.lower[i] / h[i - 1]);
            let after = (values[i + 1] - values[i]) * (3.0 * self.upper[i] / h[i]);
            rhs.push(before + after);
        }
        rhs.push((values[count - 1] - values[count - 2]) * (3.0 / h[count - 2]));
        tridiagonal::solve(&self.lower, &self.diag, &self.upper, &rhs)
    }
}

/// Second derivatives at the two ends of the cubic Hermite segment (Eq. 1) with end values
/// `p0`, `p1`, end tangents `m0`, `m1` and length `h`:
/// C''(t_i) = (6(P_1 − P_0)/h − 4M_0 − 2M_1)/h and C''(t_{i+1}) = (6(P_0 − P_1)/h + 2M_0 + 4M_1)/h.
pub(crate) fn segment_second_derivatives<T: Field>(p0: T, m0: T, m1: T, p1: T, h: f64) -> (T, T) {
    let slope = (p1 - p0) * (1.0 / h);
    let start = (slope * 6.0 - m0 * 4.0 - m1 * 2.0) * (1.0 / h);
    let end = (m0 * 2.0 + m1 * 4.0 - slope * 6.0) * (1.0 / h);
    (start, end)
}

/// The constant third derivative of the cubic Hermite segment (Eq. 1):
/// C''' = (12(P_0 − P_1)/h + 6(M_0 + M_1))/h².
pub(crate) fn segment_third_derivative<T: Field>(p0: T, m0: T, m1: T, p1: T, h: f64) -> T {
    ((p0 - p1) * (12.0 / h) + (m0 + m1) * 6.0) * (1.0 / (h * h))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Second derivative of the Hermite segment at both ends, by the Hermite basis directly.
    fn hermite_second(p0: f64, m0: f64, m1: f64, p1: f64, h: f64, s: f64) -> f64 {
        // φ0'' = 12s − 6, φ1'' = 6s − 4, ψ1'' = 6s − 2, ψ0'' = 6 − 12s (derivatives in s).
        ((12.0 * s - 6.0) * p0 + (6.0 * s - 4.0) * h * m0 + (6.0 * s - 2.0) * h * m1 + (6.0 - 12.0 * s) * p1)
            / (h * h)
    }

    #[test]
    fn tangents_make_the_spline_c2_with_free_ends() {
        let knots = [0.0, 0.3, 1.1, 1.5, 2.9, 3.0];
        let values = [1.0, -0.5, 2.0, 0.25, 1.75, -1.0];
        let system = NaturalSplineSystem::with_periodic(&knots, false).unwrap();
        let m = system.tangents(&values).unwrap();
        let h = system.steps();
        let n = knots.len() - 1;
        // Defining conditions: C'' continuous at interior knots, zero at both ends.
        let first = hermite_second(values[0], m[0], m[1], values[1], h[0], 0.0);
        let last = hermite_second(values[n - 1], m[n - 1], m[n], values[n], h[n - 1], 1.0);
        assert!(first.abs() < 1e-12 && last.abs() < 1e-12, "{first} {last}");
        for i in 1..n {
            let left = hermite_second(values[i - 1], m[i - 1], m[i], values[i], h[i - 1], 1.0);
            let right = hermite_second(values[i], m[i], m[i + 1], values[i + 1], h[i], 0.0);
            assert!((left - right).abs() < 1e-12, "knot {i}: {left} vs {right}");
            let (_, end) = segment_second_derivatives(values[i - 1], m[i - 1], m[i], values[i], h[i - 1]);
            let (start, _) = segment_second_derivatives(values[i], m[i], m[i + 1], values[i + 1], h[i]);
            assert!((end - left).abs() < 1e-12 && (start - right).abs() < 1e-12);
        }
    }

    #[test]
    fn periodic_tangents_make_the_closed_spline_c2_at_every_knot_and_the_seam() {
        let knots = [0.0, 0.4, 1.1, 1.5, 2.9, 3.3];
        // The last value repeats the first (a closed line); it is not read.
        let values = [1.0, -0.5, 2.0, 0.25, 1.75, 1.0];
        let system = NaturalSplineSystem::with_periodic(&knots, true).unwrap();
        let m = system.tangents(&values).unwrap();
        let h = system.steps();
        let n = knots.len() - 1;
        assert_eq!(m.len(), n + 1);
        assert_eq!(m[n], m[0]);
        for i in 0..n {
            let previous = (i + n - 1) % n;
            let left = hermite_second(values[previous], m[previous], m[i], values[i], h[previous], 1.0);
            let right = hermite_second(values[i], m[i], m[i + 1], values[(i + 1) % n], h[i], 0.0);
            assert!((left - right).abs() < 1e-12, "knot {i}: {left} vs {right}");
        }
        // A constant closed line has zero tangents; too few knots are refused.
        let flat = system.tangents(&[3.0; 6]).unwrap();
        assert!(flat.iter().all(|t| t.abs() < 1e-15));
        assert!(NaturalSplineSystem::with_periodic(&[0.0, 1.0, 2.0], true).is_err());
    }

    #[test]
    fn two_values_give_a_straight_line() {
        let system = NaturalSplineSystem::with_periodic(&[1.0, 3.0], false).unwrap();
        let m = system.tangents(&[5.0, 1.0]).unwrap();
        assert_eq!(m, vec![-2.0, -2.0]);
    }

    #[test]
    fn third_derivative_matches_the_basis() {
        // φ0''' = 12, φ1''' = 6, ψ1''' = 6, ψ0''' = −12 (in s); divide by h³ and scale M by h.
        let (p0, m0, m1, p1, h) = (0.7, -1.3, 2.2, 0.1, 0.4);
        let expected = (12.0 * p0 + 6.0 * h * m0 + 6.0 * h * m1 - 12.0 * p1) / (h * h * h);
        assert!((segment_third_derivative(p0, m0, m1, p1, h) - expected).abs() < 1e-10);
    }

    #[test]
    fn wrong_lengths_are_errors() {
        assert!(NaturalSplineSystem::with_periodic(&[1.0], false).is_err());
        let system = NaturalSplineSystem::with_periodic(&[0.0, 1.0, 2.0], false).unwrap();
        assert!(matches!(
            system.tangents(&[1.0, 2.0]),
            Err(Error::LengthMismatch { .. })
        ));
    }
}
