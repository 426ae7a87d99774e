//! Tridiagonal and cyclic tridiagonal solvers (Thomas algorithm), O(n), written once.
//!
//! Row i of the system reads `lower[i]·x[i−1] + diag[i]·x[i] + upper[i]·x[i+1] = rhs[i]`;
//! `lower[0]` and `upper[n−1]` are ignored for the open system and are the corner entries of
//! the cyclic one. The right-hand side may be scalars or vectors (one solve for every
//! coordinate of a parametric spline).
//!
//! No pivoting: the systems of cubic interpolation are diagonally dominant, for which the
//! Thomas algorithm is stable. A pivot that vanishes, or is tiny against its row, is reported
//! as [`Error::Singular`] rather than divided by.

use std::ops::{Add, Mul, Sub};

use crate::{Error, Result};

/// Values a tridiagonal system can be solved for: `f64` or a vector of them.
pub trait Field: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self> {}
impl<T: Copy + Add<Output = T> + Sub<Output = T> + Mul<f64, Output = T>> Field for T {}

/// Relative size below which a pivot counts as zero.
const PIVOT_TOLERANCE: f64 = 1e-14;

fn check_lengths(n: usize, lower: &[f64], upper: &[f64], rhs_len: usize) -> Result<()> {
    for (what, len) in [
        ("lower diagonal", lower.len()),
        ("upper diagonal", upper.len()),
        ("right-hand side", rhs_len),
    ] {
        if len != n {
            return Err(Error::LengthMismatch {
                what,
                expected: n,
                got: len,
            });
        }
    }
    Ok(())
}

/// Solves the open tridiagonal system. O(n) time, O(n) extra memory.
///
/// Fails with [`Error::LengthMismatch`] on inconsistent lengths and [`Error::Singular`] on a
/// vanishing pivot or a non-finite coefficient.
pub fn solve<T: Field>(lower: &[f64], diag: &[f64], upper: &[f64], rhs: &[T]) -> Result<Vec<T>> {
    let n = diag.len();
    check_lengths(n, lower, upper, rhs.len())?;
    let mut x = rhs.to_vec();
    let mut upper_prime = vec![0.0; n];
    solve_in_place(lower, diag, upper, &mut x, &mut upper_prime)?;
    Ok(x)
}

/// [`solve`] without allocating: `values` holds the right-hand side on entry and the
/// solution on success (unspecified on failure); `upper_prime` (at least as long as
/// `diag`) is scratch. The same operations in the same order as [`solve`], so the same
/// bits.
///
/// Fails like [`solve`].
pub fn solve_in_place<T: Field>(
    lower: &[f64],
    diag: &[f64],
    upper: &[f64],
    values: &mut [T],
    upper_prime: &mut [f64],
) -> Result<()> {
    let n = diag.len();
    check_lengths(n, lower, upper, values.len())?;
    if upper_prime.len() < n {
        return Err(Error::LengthMismatch {
            what: "scratch",
            expected: n,
            got: upper_prime.len(),
        });
    }
    if n == 0 {
        return Ok(());
    }
    let singular = Error::Singular {
        what: "solving a tridiagonal system",
    };
    let mut pivot = diag[0];
    let scale = |i: usize| diag[i].abs() + lower[i].abs() + upper[i].abs();
    if !pivot.is_finite() || pivot.abs() <= PIVOT_TOLERANCE * scale(0) {
        return Err(singular);
    }
    upper_prime[0] = upper[0] / pivot;
    values[0] = values[0] * (1.0 / pivot);
    for i in 1..n {
        pivot = diag[i] - lower[i] * upper_prime[i - 1];
        if !pivot.is_finite() || pivot.abs() <= PIVOT_TOLERANCE * scale(i) {
            return Err(singular);
        }
        upper_prime[i] = upper[i] / pivot;
        values[i] = (values[i] - values[i - 1] * lower[i]) * (1.0 / pivot);
    }
    for i in (0..n - 1).rev() {
        values[i] = values[i] - values[i + 1] * upper_prime[i];
    }
    Ok(())
}

/// Solves the cyclic system, whose row 0 also holds `lower[0]·x[n−1]` and row n−1 also
/// `upper[n−1]·x[0]`, by the Sherman–Morrison formula over two open solves. O(n).
///
/// Needs n ≥ 3. Fails like [`solve`], and with [`Error::Singular`] when the rank-one
/// correction is singular.
pub fn solve_cyclic<T: Field>(lower: &[f64], diag: &[f64], upper: &[f64], rhs: &[T]) -> Result<Vec<T>> {
    let n = diag.len();
    check_lengths(n, lower, upper, rhs.len())?;
    if n < 3 {
        return Err(Error::TooFewPoints {
            what: "a cyclic tridiagonal system",
            needed: 3,
            got: n,
        });
    }
    let alpha = upper[n - 1];
    let beta = lower[0];
    // A = B + u vᵀ with u = (γ, 0, …, 0, α), v = (1, 0, …, 0, β/γ).
    let gamma = -diag[0];
    let mut modified = diag.to_vec();
    modified[0] -= gamma;
    modified[n - 1] -= alpha * beta / gamma;
    let mut lower_open = lower.to_vec();
    lower_open[0] = 0.0;
    let mut upper_open = upper.to_vec();
    upper_open[n - 1] = 0.0;
    let y = solve(&lower_open, &modified, &upper_open, rhs)?;
    let mut u = vec![0.0; n];
    u[0] = gamma;
    u[n - 1] = alpha;
    let z = solve(&lower_open, &modified, &upper_open, &u)?;
    let denominator = 1.0 + z[0] + beta / gamma * z[n - 1];
    if !denominator.is_finite() || denominator.abs() <= PIVOT_TOLERANCE {
        return Err(Error::Singular {
            what: "solving a cyclic tridiagonal system",
        });
    }
    let vy = y[0] + y[n - 1] * (beta / gamma);
    Ok(y.iter()
        .zip(&z)
        .map(|(&yi, &zi)| yi - vy * (zi / denominator))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec2;

    fn residual(lower: &[f64], diag: &[f64], upper: &[f64], x: &[f64], rhs: &[f64], cyclic: bool) -> f64 {
        let n = diag.len();
        (0..n)
            .map(|i| {
                let mut r = diag[i] * x[i] - rhs[i];
                if i > 0 {
                    r += lower[i] * x[i - 1];
                } else if cyclic {
                    r += lower[0] * x[n - 1];
                }
                if i + 1 < n {
                    r += upper[i] * x[i + 1];
                } else if cyclic {
                    r += upper[n - 1] * x[0];
                }
                r.abs()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn open_and_cyclic_systems_are_solved() {
        let n = 9;
        let lower: Vec<f64> = (0..n).map(|i| 1.0 + 0.1 * i as f64).collect();
        let upper: Vec<f64> = (0..n).map(|i| 0.5 + 0.05 * i as f64).collect();
        let diag: Vec<f64> = (0..n).map(|i| 4.0 + (i % 3) as f64).collect();
        let rhs: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let x = solve(&lower, &diag, &upper, &rhs).unwrap();
        assert!(residual(&lower, &diag, &upper, &x, &rhs, false) < 1e-14);
        let x = solve_cyclic(&lower, &diag, &upper, &rhs).unwrap();
        assert!(residual(&lower, &diag, &upper, &x, &rhs, true) < 1e-14);
    }

    #[test]
    fn vector_right_hand_sides_solve_each_coordinate() {
        let lower = [0.0, 1.0, 1.0];
        let diag = [4.0, 4.0, 4.0];
        let upper = [1.0, 1.0, 0.0];
        let rhs = [Vec2::new(1.0, 2.0), Vec2::new(3.0, 4.0), Vec2::new(5.0, 6.0)];
        let x = solve(&lower, &diag, &upper, &rhs).unwrap();
        let xs = solve(&lower, &diag, &upper, &[1.0, 3.0, 5.0]).unwrap();
        let ys = solve(&lower, &diag, &upper, &[2.0, 4.0, 6.0]).unwrap();
        for i in 0..3 {
            assert_eq!(x[i], Vec2::new(xs[i], ys[i]));
        }
    }

    #[test]
    fn singular_and_mismatched_systems_are_errors() {
        assert!(matches!(
            solve(&[0.0, 1.0], &[1.0, 1.0], &[1.0, 0.0], &[1.0, 1.0]),
            Err(Error::Singular { .. })
        ));
        assert!(matches!(
            solve(&[0.0], &[1.0, 1.0], &[1.0, 0.0], &[1.0, 1.0]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            solve(&[0.0], &[f64::NAN], &[0.0], &[1.0]),
            Err(Error::Singular { .. })
        ));
    }
}
