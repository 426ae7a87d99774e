//! Rational B-spline evaluation written once over the scalar `T: num_traits::Float`.
//!
//! The knots (and so the basis functions N_{i,p}(u) of The NURBS Book A2.3) stay `f64`; the
//! weights w_i and the homogeneous control points Q_i = w_i P_i are `T`. With `T = f64` this is
//! the evaluation behind [`NurbsCurve::derivatives`](super::NurbsCurve::derivatives) (one code
//! path); with a forward-mode dual number (e.g. `num_dual::Dual64`) the same code carries the
//! derivative of C(u), C′(u), C″(u) with respect to whatever the weights or points depend on,
//! which is how a fairness criterion is differentiated exactly with respect to the weights.

use num_traits::Float;

use super::binomial;
use crate::bspline::{basis_derivatives, KnotVector};
use crate::{Error, Result, Side};

/// `x` as a `T` (exact for `f64`; NaN if `T` cannot represent it, which no `Float` fails to).
#[inline]
pub fn lift<T: Float>(x: f64) -> T {
    T::from(x).unwrap_or_else(T::nan)
}

/// C(u) and its derivatives of order 1 … `order` of the rational B-spline on `knots` whose
/// homogeneous control points are given by `control(i) = Some((w_i P_i, w_i))` (`None` reads
/// as a missing point and contributes nothing, as an index out of range would).
///
/// Homogeneous derivatives A^{(k)} = Σ N^{(k)}_i Q_i, w^{(k)} = Σ N^{(k)}_i w_i (A3.2 on the
/// weighted points), then The NURBS Book Eq. 4.8 / A4.2:
/// C^{(k)} = (A^{(k)} − Σ_{i=1}^{k} C(k,i) w^{(i)} C^{(k−i)}) / w.
/// `side` picks the span at an interior knot ([`KnotVector::span`]).
/// O(p² + order·p + order²) operations on `T`.
pub fn rational_derivatives<T: Float, const D: usize>(
    knots: &KnotVector,
    u: f64,
    order: usize,
    side: Side,
    control: impl Fn(usize) -> Option<([T; D], T)>,
) -> Vec<[T; D]> {
    let p = knots.degree();
    let span = knots.span(u, side);
    let basis = basis_derivatives(knots.knots(), p, span, u, order);
    let first = span - p;
    let mut numerator = vec![[T::zero(); D]; order + 1];
    let mut denominator = vec![T::zero(); order + 1];
    for (k, row) in basis.iter().enumerate() {
        for (j, &n) in row.iter().enumerate() {
            if let Some((q, w)) = control(first + j) {
                let n: T = lift(n);
                for c in 0..D {
                    numerator[k][c] = numerator[k][c] + q[c] * n;
                }
                denominator[k] = denominator[k] + w * n;
            }
        }
    }
    let mut out: Vec<[T; D]> = Vec::with_capacity(order + 1);
    for k in 0..=order {
        let mut v = numerator[k];
        for i in 1..=k {
            let factor = lift::<T>(binomial(k, i)) * denominator[i];
            for c in 0..D {
                v[c] = v[c] - out[k - i][c] * factor;
            }
        }
        for x in v.iter_mut() {
            *x = *x / denominator[0];
        }
        out.push(v);
    }
    out
}

/// A rational B-spline curve over the scalar `T`: f64 knots, homogeneous control points
/// Q_i = w_i P_i and weights w_i in `T`. The generic twin of [`NurbsCurve`](super::NurbsCurve)
/// for differentiating through evaluation (no positivity check on `T`: the caller's weights
/// are those of a valid curve, perturbed infinitesimally).
#[derive(Clone, Debug, PartialEq)]
pub struct RationalCurve<T, const D: usize> {
    pub(super) knots: KnotVector,
    pub(super) weighted: Vec<[T; D]>,
    pub(super) weights: Vec<T>,
}

impl<T: Float, const D: usize> RationalCurve<T, D> {
    /// The curve on `knots` with homogeneous control points `weighted` (w_i P_i) and `weights`.
    /// Fails with [`Error::LengthMismatch`] when either length is not the knot vector's
    /// control-point count. O(1).
    pub fn new(knots: KnotVector, weighted: Vec<[T; D]>, weights: Vec<T>) -> Result<Self> {
        for (what, len) in [("control points", weighted.len()), ("weights", weights.len())] {
            if len != knots.control_count() {
                return Err(Error::LengthMismatch {
                    what,
                    expected: knots.control_count(),
                    got: len,
                });
            }
        }
        Ok(Self {
            knots,
            weighted,
            weights,
        })
    }

    /// The knot vector.
    pub fn knot_vector(&self) -> &KnotVector {
        &self.knots
    }

    /// The homogeneous control points w_i P_i.
    pub fn weighted_points(&self) -> &[[T; D]] {
        &self.weighted
    }

    /// The weights w_i.
    pub fn weights(&self) -> &[T] {
        &self.weights
    }

    /// C(u), C′(u), …, C^{(order)}(u) from `side` ([`rational_derivatives`]).
    /// O(p² + order·p + order²).
    pub fn derivatives(&self, u: f64, order: usize, side: Side) -> Vec<[T; D]> {
        rational_derivatives(&self.knots, u, order, side, |i| {
            Some((*self.weighted.get(i)?, *self.weights.get(i)?))
        })
    }
}
