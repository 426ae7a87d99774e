//! Clamped knot vectors: validation and construction by averaging.

use crate::{Error, Result, Side};

/// A clamped (open) knot vector u_0 ≤ … ≤ u_m of a B-spline of degree p with n + 1 control
/// points, m = n + p + 1.
///
/// Invariants checked by [`KnotVector::new`]: every knot finite, non-decreasing, length
/// n_ctrl + p + 1, the first and last knots repeated exactly p + 1 times, interior knots of
/// multiplicity at most p, and a domain [u_p, u_{m−p}] of positive length.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct KnotVector {
    degree: usize,
    knots: Vec<f64>,
}

fn bad(reason: String) -> Error {
    Error::BadKnots { reason }
}

impl KnotVector {
    /// Validates `knots` for a B-spline of `degree` ≥ 1 with `control_count` control points.
    ///
    /// Fails with [`Error::BadDegree`] for degree 0, [`Error::TooFewPoints`] when
    /// `control_count` ≤ `degree`, and [`Error::BadKnots`] (with the reason) otherwise. O(m).
    pub fn new(degree: usize, knots: Vec<f64>, control_count: usize) -> Result<Self> {
        if degree == 0 {
            return Err(Error::BadDegree {
                degree,
                reason: "a NURBS needs degree at least 1",
            });
        }
        if control_count < degree + 1 {
            return Err(Error::TooFewPoints {
                what: "a B-spline of this degree",
                needed: degree + 1,
                got: control_count,
            });
        }
        let expected = control_count + degree + 1;
        if knots.len() != expected {
            return Err(bad(format!(
                "{} knots given, {} control points of degree {} need {}",
                knots.len(),
                control_count,
                degree,
                expected
            )));
        }
        if let Some(index) = knots.iter().position(|k| !k.is_finite()) {
            return Err(bad(format!("knot {index} is not finite")));
        }
        if let Some(index) = knots.windows(2).position(|w| w[1] < w[0]) {
            return Err(bad(format!(
                "knots decrease at index {}: {} after {}",
                index + 1,
                knots[index + 1],
                knots[index]
            )));
        }
        let first = knots[0];
        let last = knots[expected - 1];
        let start_multiplicity = knots.iter().take_while(|&&k| k == first).count();
        let end_multiplicity = knots.iter().rev().take_while(|&&k| k == last).count();
        if start_multiplicity != degree + 1 || end_multiplicity != degree + 1 {
            return Err(bad(format!(
                "a clamped knot vector repeats its end knots degree + 1 = {} times, got {} at the start and {} at the end",
                degree + 1,
                start_multiplicity,
                end_multiplicity
            )));
        }
        if last <= first {
            return Err(bad("the domain has zero length".to_string()));
        }
        let interior = &knots[degree + 1..expected - degree - 1];
        let mut run = 0;
        for (i, k) in interior.iter().enumerate() {
            run = if i > 0 && interior[i - 1] == *k {
                run + 1
            } else {
                1
            };
            if run > degree {
                return Err(bad(format!(
                    "interior knot {} has multiplicity above the degree {}",
                    k, degree
                )));
            }
        }
        Ok(Self { degree, knots })
    }

    /// Knots for interpolation by averaging (The NURBS Book Eq. 9.8): p + 1 copies of the
    /// first and last parameter and, for j = 1, …, n − p,
    /// u_{j+p} = (1/p) Σ_{i=j}^{j+p−1} ū_i, where ū_0 … ū_n are the `params`.
    ///
    /// With `end_derivatives` (two extra control points for given end derivatives) the
    /// averaging runs over j = 0, …, n − p + 1 as u_{j+p+1} = (1/p) Σ_{i=j}^{j+p−1} ū_i
    /// (The NURBS Book Eq. 9.22). `params` must be non-decreasing and finite (checked by the
    /// resulting [`KnotVector::new`]). O(n p) with a running sum: O(n).
    pub fn averaged(degree: usize, params: &[f64], end_derivatives: bool) -> Result<Self> {
        let count = params.len();
        let control_count = if end_derivatives { count + 2 } else { count };
        if degree == 0 {
            return Err(Error::BadDegree {
                degree,
                reason: "a NURBS needs degree at least 1",
            });
        }
        if count < 2 || control_count < degree + 1 {
            return Err(Error::TooFewPoints {
                what: "interpolation of this degree",
                needed: if end_derivatives {
                    degree.saturating_sub(1).max(2)
                } else {
                    degree + 1
                },
                got: count,
            });
        }
        let (Some(&first), Some(&last)) = (params.first(), params.last()) else {
            return Err(Error::TooFewPoints {
                what: "interpolation",
                needed: 2,
                got: count,
            });
        };
        let mut knots = Vec::with_capacity(control_count + degree + 1);
        knots.extend(std::iter::repeat_n(first, degree + 1));
        let p = degree as f64;
        // Interior knot count: control_count − p − 1; window of p consecutive parameters
        // starting at index `offset + k`.
        let interior = control_count - degree - 1;
        let offset = if end_derivatives { 0 } else { 1 };
        for k in 0..interior {
            let start = offset + k;
            let sum: f64 = params
                .get(start..start + degree)
                .map_or(f64::NAN, |w| w.iter().sum());
            knots.push(sum / p);
        }
        knots.extend(std::iter::repeat_n(last, degree + 1));
        Self::new(degree, knots, control_count)
    }

    /// The degree p.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// All knots u_0 … u_m.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Number of control points n + 1 = m − p.
    pub fn control_count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parameter domain (u_p, u_{m−p}).
    pub fn domain(&self) -> (f64, f64) {
        let p = self.degree;
        (self.knots[p], self.knots[self.knots.len() - 1 - p])
    }

    /// The distinct knots in increasing order (the curve's break points). O(m).
    pub fn distinct(&self) -> Vec<f64> {
        let mut out: Vec<f64> = Vec::new();
        for &k in &self.knots {
            if out.last() != Some(&k) {
                out.push(k);
            }
        }
        out
    }

    /// The knot span index (The NURBS Book A2.1) for `u`, by binary search, O(log m).
    ///
    /// With `Side::Right` it is the i with u_i ≤ u < u_{i+1}; with `Side::Left` the i with
    /// u_i < u ≤ u_{i+1}, so that at an interior knot the span ending there is used. Outside
    /// the domain the first or last non-empty span is returned (the end piece extends).
    pub fn span(&self, u: f64, side: Side) -> usize {
        super::basis::find_span(&self.knots, self.degree, u, side)
    }
}
