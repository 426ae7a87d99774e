//! The tangent system of Zhang–Cheng Eq. (2) and its O(n) solution.
//!
//! C2 continuity at an interior knot i, C''_{i−1}(t_i) = C''_i(t_i), reads (Eq. 2)
//!
//! a_i M_{i−1} + 2 M_i + b_i M_{i+1} = 3 (a_i d_{i−1} + b_i d_i),
//!
//! a_i = h_i/(h_{i−1} + h_i), b_i = h_{i−1}/(h_{i−1} + h_i), d_k = (P_{k+1} − P_k)/h_k: the
//! printed right-hand side −3a_i/h_{i−1} P_{i−1} + c_i P_i + 3b_i/h_i P_{i+1} with
//! c_i = 3(a_i/h_{i−1} − b_i/h_i), regrouped by chords. Rows 0 and n come from the end
//! condition ([`HermiteEnds`](super::HermiteEnds)); a closed curve has only interior rows and
//! a cyclic system. The matrix is diagonally dominant (strictly except the runout rows), so
//! the Thomas algorithm without pivoting is stable.

use super::HermiteSpline;
use crate::tridiagonal;
use crate::{Error, Result, Vector};

/// One row of the system: lower·M_{i−1} + diag·M_i + upper·M_{i+1} = rhs.
#[derive(Clone, Copy, Debug)]
pub(super) struct Row<const D: usize> {
    pub(super) lower: f64,
    pub(super) diag: f64,
    pub(super) upper: f64,
    pub(super) rhs: Vector<D>,
}

impl<const D: usize> HermiteSpline<D> {
    /// The chord slope d_k = (P_{k+1} − P_k)/h_k of segment k.
    pub(super) fn chord_slope(&self, segment: usize) -> Vector<D> {
        (self.points[self.next(segment)] - self.points[segment]) / self.step(segment)
    }

    /// Row `i` (0 ≤ i < number of points) of the tangent system, from the current points.
    pub(super) fn row(&self, i: usize) -> Row<D> {
        let count = self.points.len();
        let open_end = |ends: Option<(f64, f64, Vector<D>)>, at_start: bool| {
            ends.map(|(first, second, rhs)| {
                if at_start {
                    Row {
                        lower: 0.0,
                        diag: first,
                        upper: second,
                        rhs,
                    }
                } else {
                    Row {
                        lower: first,
                        diag: second,
                        upper: 0.0,
                        rhs,
                    }
                }
            })
        };
        if !self.is_closed() {
            if i == 0 {
                if let Some(row) = open_end(self.ends.start_row(self.chord_slope(0)), true) {
                    return row;
                }
            } else if i + 1 == count {
                if let Some(row) = open_end(self.ends.end_row(self.chord_slope(i - 1)), false) {
                    return row;
                }
            }
        }
        let previous = if i == 0 { count - 1 } else { i - 1 };
        let (h0, h1) = (self.step(previous), self.step(i));
        let a = h1 / (h0 + h1);
        let b = h0 / (h0 + h1);
        Row {
            lower: a,
            diag: 2.0,
            upper: b,
            rhs: (self.chord_slope(previous) * a + self.chord_slope(i) * b) * 3.0,
        }
    }
}

/// Solves Eq. (2) with the end rows for every tangent: O(n) (cyclic for a closed curve).
///
/// Fails with [`Error::Singular`] if the solver meets a vanishing pivot and with
/// [`Error::NonFinite`] if a tangent overflows.
pub(super) fn tangents<const D: usize>(spline: &HermiteSpline<D>) -> Result<Vec<Vector<D>>> {
    let count = spline.points.len();
    let mut lower = Vec::with_capacity(count);
    let mut diag = Vec::with_capacity(count);
    let mut upper = Vec::with_capacity(count);
    let mut rhs = Vec::with_capacity(count);
    for i in 0..count {
        let row = spline.row(i);
        lower.push(row.lower);
        diag.push(row.diag);
        upper.push(row.upper);
        rhs.push(row.rhs);
    }
    let solution = if spline.is_closed() {
        tridiagonal::solve_cyclic(&lower, &diag, &upper, &rhs)?
    } else {
        tridiagonal::solve(&lower, &diag, &upper, &rhs)?
    };
    check_tangents(&solution)?;
    Ok(solution)
}

/// Solves rows `start..start + len` (indices modulo the point count for a closed curve) for
/// their tangents, holding the tangents just outside the window at their current values.
/// O(len). The window must not cover a closed curve's every row.
pub(super) fn window<const D: usize>(
    spline: &HermiteSpline<D>,
    start: usize,
    len: usize,
) -> Result<Vec<Vector<D>>> {
    let count = spline.points.len();
    let index = |k: usize| (start + k) % count;
    let mut lower = Vec::with_capacity(len);
    let mut diag = Vec::with_capacity(len);
    let mut upper = Vec::with_capacity(len);
    let mut rhs = Vec::with_capacity(len);
    for k in 0..len {
        let row = spline.row(index(k));
        lower.push(row.lower);
        diag.push(row.diag);
        upper.push(row.upper);
        rhs.push(row.rhs);
    }
    if len == 0 {
        return Ok(Vec::new());
    }
    // Boundary tangents move to the right-hand side (their coefficients are 0 at open ends).
    if lower[0] != 0.0 {
        let outside = spline.tangents[(start + count - 1) % count];
        rhs[0] -= outside * lower[0];
        lower[0] = 0.0;
    }
    let last = len - 1;
    if upper[last] != 0.0 {
        let outside = spline.tangents[index(len)];
        rhs[last] -= outside * upper[last];
        upper[last] = 0.0;
    }
    let solution = tridiagonal::solve(&lower, &diag, &upper, &rhs)?;
    check_tangents(&solution)?;
    Ok(solution)
}

fn check_tangents<const D: usize>(tangents: &[Vector<D>]) -> Result<()> {
    match tangents.iter().position(|m| m.iter().any(|c| !c.is_finite())) {
        Some(index) => Err(Error::NonFinite {
            what: "tangent",
            index,
        }),
        None => Ok(()),
    }
}
