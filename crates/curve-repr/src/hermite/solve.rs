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

    /// Row `i` (0 ≤ i < number of points) of the tangent system, from the current points,
    /// given the chord slope of the segment before `i` when the caller has it (the row
    /// before computed it); returns the slope of segment `i` too when it was computed, for
    /// the row after. The same operations as computing each slope anew, so the same bits,
    /// with one chord slope per row instead of two.
    pub(super) fn row_with(
        &self,
        i: usize,
        previous_slope: Option<Vector<D>>,
    ) -> (Row<D>, Option<Vector<D>>) {
        let count = self.points.len();
        if !self.is_closed() {
            if i == 0 {
                let slope = self.chord_slope(0);
                if let Some((diag, upper, rhs)) = self.ends.start_row(slope) {
                    let row = Row {
                        lower: 0.0,
                        diag,
                        upper,
                        rhs,
                    };
                    return (row, Some(slope));
                }
            } else if i + 1 == count {
                let slope = previous_slope.unwrap_or_else(|| self.chord_slope(i - 1));
                if let Some((lower, diag, rhs)) = self.ends.end_row(slope) {
                    let row = Row {
                        lower,
                        diag,
                        upper: 0.0,
                        rhs,
                    };
                    return (row, None);
                }
            }
        }
        let previous = if i == 0 { count - 1 } else { i - 1 };
        let (h0, h1) = (self.step(previous), self.step(i));
        let a = h1 / (h0 + h1);
        let b = h0 / (h0 + h1);
        let before = previous_slope.unwrap_or_else(|| self.chord_slope(previous));
        let after = self.chord_slope(i);
        let row = Row {
            lower: a,
            diag: 2.0,
            upper: b,
            rhs: (before * a + after * b) * 3.0,
        };
        (row, Some(after))
    }
}

/// Solves Eq. (2) with the end rows for every tangent: O(n) (cyclic for a closed curve).
///
/// Fails with [`Error::Singular`] if the solver meets a vanishing pivot and with
/// [`Error::NonFinite`] if a tangent overflows.
pub(super) fn tangents<const D: usize>(spline: &HermiteSpline<D>) -> Result<Vec<Vector<D>>> {
    let count = spline.points.len();
    let mut lower = vec![0.0; count];
    let mut diag = vec![0.0; count];
    let mut upper = vec![0.0; count];
    let mut rhs = vec![Vector::<D>::zeros(); count];
    rows_into(spline, 0, &mut lower, &mut diag, &mut upper, &mut rhs);
    let solution = if spline.is_closed() {
        tridiagonal::solve_cyclic(&lower, &diag, &upper, &rhs)?
    } else {
        tridiagonal::solve(&lower, &diag, &upper, &rhs)?
    };
    check_tangents(&solution)?;
    Ok(solution)
}

/// [`tangents`] of an open curve into the spline's tangents, solved in its workspace (grown
/// as needed): the same rows and the same elimination as [`tridiagonal::solve`], so the
/// same bits, without allocating. The tangents are written only when the solve succeeds.
pub(super) fn open_tangents_in_place<const D: usize>(spline: &mut HermiteSpline<D>) -> Result<()> {
    let count = spline.points.len();
    let mut workspace = std::mem::take(&mut spline.workspace);
    if workspace.values.len() < count {
        workspace.numbers.resize(4 * count, 0.0);
        workspace.values.resize(count, Vector::<D>::zeros());
    }
    let (lower, rest) = workspace.numbers[..4 * count].split_at_mut(count);
    let (diag, rest) = rest.split_at_mut(count);
    let (upper, scratch) = rest.split_at_mut(count);
    let values = &mut workspace.values[..count];
    rows_into(spline, 0, lower, diag, upper, values);
    let solved = tridiagonal::solve_in_place(lower, diag, upper, values, scratch)
        .and_then(|()| check_tangents(values));
    if solved.is_ok() {
        spline.tangents.clear();
        spline.tangents.extend_from_slice(values);
    }
    spline.workspace = workspace;
    solved
}

/// Rows `start`, `start + 1`, … (modulo the point count for a closed curve; as many as the
/// slices hold) of the system, as [`HermiteSpline::row_with`] gives them (the same
/// operations, so the same bits), with the right-hand sides in `values`. An interior row
/// takes the knot step and the chord slope of the segment before it from the row before,
/// so each row computes one step, two weights and one slope. O(rows).
fn rows_into<const D: usize>(
    spline: &HermiteSpline<D>,
    start: usize,
    lower: &mut [f64],
    diag: &mut [f64],
    upper: &mut [f64],
    values: &mut [Vector<D>],
) {
    let count = spline.points.len();
    let closed = spline.is_closed();
    // The knot step and the chord slope of the segment ending at the row, when known.
    let mut carried: Option<(f64, Vector<D>)> = None;
    let mut i = start;
    for k in 0..values.len() {
        if !closed && (i == 0 || i + 1 == count) {
            let (row, next) = spline.row_with(i, carried.map(|(_, slope)| slope));
            lower[k] = row.lower;
            diag[k] = row.diag;
            upper[k] = row.upper;
            values[k] = row.rhs;
            carried = next.map(|slope| (spline.step(i), slope));
        } else {
            let previous = if i == 0 { count - 1 } else { i - 1 };
            let (h0, before) =
                carried.unwrap_or_else(|| (spline.step(previous), spline.chord_slope(previous)));
            let h1 = spline.step(i);
            let a = h1 / (h0 + h1);
            let b = h0 / (h0 + h1);
            let after = (spline.points[spline.next(i)] - spline.points[i]) / h1;
            lower[k] = a;
            diag[k] = 2.0;
            upper[k] = b;
            values[k] = (before * a + after * b) * 3.0;
            carried = Some((h1, after));
        }
        i += 1;
        if i == count {
            i = 0;
        }
    }
}

/// Storage of a windowed solve, one entry per row of the window: the system's three
/// diagonals, the Thomas algorithm's scratch and the right-hand side, which the solve
/// overwrites with the tangents. Borrowed from the spline's workspace.
pub(super) struct WindowRows<'a, const D: usize> {
    pub(super) lower: &'a mut [f64],
    pub(super) diag: &'a mut [f64],
    pub(super) upper: &'a mut [f64],
    pub(super) scratch: &'a mut [f64],
    pub(super) values: &'a mut [Vector<D>],
}

/// Solves rows `start..start + len` (indices modulo the point count for a closed curve,
/// `len` the length of `rows`' slices) for their tangents, the rows taken from `cache`
/// where it knows them (see the workspace's `rows`) and built from the points otherwise, holding the tangents just outside
/// the window at their current values; the tangents are left in `rows.values`. O(len), no
/// allocation. The window must not cover a closed curve's every row.
pub(super) fn window<const D: usize>(
    spline: &HermiteSpline<D>,
    start: usize,
    rows: WindowRows<'_, D>,
    cache: Option<&mut [Option<Row<D>>]>,
) -> Result<()> {
    let WindowRows {
        lower,
        diag,
        upper,
        scratch,
        values,
    } = rows;
    let len = values.len();
    let count = spline.points.len();
    let index = |k: usize| (start + k) % count;
    if len == 0 {
        return Ok(());
    }
    match cache {
        // The rows known for the current points copied, the others built (by `row_with`,
        // the same bits as `rows_into`) and kept.
        Some(cache) => {
            let mut i = start;
            for k in 0..len {
                let row = *cache[i].get_or_insert_with(|| spline.row_with(i, None).0);
                lower[k] = row.lower;
                diag[k] = row.diag;
                upper[k] = row.upper;
                values[k] = row.rhs;
                i += 1;
                if i == count {
                    i = 0;
                }
            }
        }
        None => rows_into(spline, start, lower, diag, upper, values),
    }
    // Boundary tangents move to the right-hand side (their coefficients are 0 at open ends).
    if lower[0] != 0.0 {
        let outside = spline.tangents[(start + count - 1) % count];
        values[0] -= outside * lower[0];
        lower[0] = 0.0;
    }
    let last = len - 1;
    if upper[last] != 0.0 {
        let outside = spline.tangents[index(len)];
        values[last] -= outside * upper[last];
        upper[last] = 0.0;
    }
    tridiagonal::solve_in_place(lower, diag, upper, values, scratch)?;
    check_tangents(values)
}

pub(super) fn check_tangents<const D: usize>(tangents: &[Vector<D>]) -> Result<()> {
    match tangents.iter().position(|m| m.iter().any(|c| !c.is_finite())) {
        Some(index) => Err(Error::NonFinite {
            what: "tangent",
            index,
        }),
        None => Ok(()),
    }
}
