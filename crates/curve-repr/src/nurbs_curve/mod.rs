//! Non-uniform rational B-spline (NURBS) curves in 2D and 3D.
//!
//! The representation of Nowacki et al. (FAIRSHAPE 1996, §3): a cubic NUBS interpolating the
//! data (built by [`Interpolation`], The NURBS Book A9.1) is rewritten as a NURBS with unit
//! weights, and the weights are then optimised with the interpolation conditions kept
//! ([`Interpolation::solve`]). Evaluation follows The NURBS Book: homogeneous derivatives from
//! the basis derivatives (A2.3, A3.2 applied to weighted points) and the rational derivatives
//! by Eq. 4.8 (A4.2).

mod conic;
pub mod fit;
pub mod generic;
mod interpolate;
mod knot_ops;

pub use fit::{fit_knots, max_control_count, ToleranceFit};
pub use generic::{rational_derivatives, RationalCurve};
pub use interpolate::{Interpolation, InterpolationSettings, NurbsInterpolant};

use serde::ser::SerializeStruct;

use crate::bspline::KnotVector;
use crate::curve::MAX_ORDER;
use crate::{Curve, Error, Result, Side, Vector};

/// A NURBS curve C(u) = Σ N_{i,p}(u) w_i P_i / Σ N_{i,p}(u) w_i of degree p ≥ 1 on a clamped
/// knot vector, in `D` dimensions.
///
/// Invariants (checked by [`NurbsCurve::new`]): a valid [`KnotVector`] for the number of
/// control points, finite control points, finite positive weights (so the denominator is
/// positive everywhere and evaluation never divides by zero).
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsCurve<const D: usize> {
    knots: KnotVector,
    control_points: Vec<Vector<D>>,
    weights: Vec<f64>,
    /// w_i P_i, the Cartesian part of the homogeneous control points.
    weighted: Vec<Vector<D>>,
}

/// Binomial coefficient C(n, k) as f64 (small n only: derivative orders).
pub(crate) fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Checks that weights are finite and positive.
pub(crate) fn check_weights(weights: &[f64]) -> Result<()> {
    match weights.iter().position(|&w| !(w > 0.0 && w.is_finite())) {
        Some(index) => Err(Error::BadWeight {
            index,
            value: weights[index],
        }),
        None => Ok(()),
    }
}

impl<const D: usize> NurbsCurve<D> {
    /// A NURBS curve of `degree` with the full clamped knot vector `knots`, `control_points`
    /// (Cartesian, not multiplied by the weights) and `weights`.
    ///
    /// Fails with [`Error::LengthMismatch`] when the weights do not match the control points,
    /// [`Error::BadKnots`] / [`Error::BadDegree`] / [`Error::TooFewPoints`] as
    /// [`KnotVector::new`], [`Error::NonFinite`] on a non-finite control point and
    /// [`Error::BadWeight`] on a weight that is not finite and positive. O(n).
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        control_points: Vec<Vector<D>>,
        weights: Vec<f64>,
    ) -> Result<Self> {
        if weights.len() != control_points.len() {
            return Err(Error::LengthMismatch {
                what: "weights",
                expected: control_points.len(),
                got: weights.len(),
            });
        }
        let knots = KnotVector::new(degree, knots, control_points.len())?;
        Self::from_parts(knots, control_points, weights)
    }

    /// A non-rational B-spline (NUBS): [`NurbsCurve::new`] with unit weights.
    pub fn non_rational(degree: usize, knots: Vec<f64>, control_points: Vec<Vector<D>>) -> Result<Self> {
        let weights = vec![1.0; control_points.len()];
        Self::new(degree, knots, control_points, weights)
    }

    /// Builds from a validated knot vector; checks lengths, points and weights.
    pub(crate) fn from_parts(
        knots: KnotVector,
        control_points: Vec<Vector<D>>,
        weights: Vec<f64>,
    ) -> Result<Self> {
        for (what, len) in [
            ("control points", control_points.len()),
            ("weights", weights.len()),
        ] {
            if len != knots.control_count() {
                return Err(Error::LengthMismatch {
                    what,
                    expected: knots.control_count(),
                    got: len,
                });
            }
        }
        crate::vector::check_finite(&control_points)?;
        check_weights(&weights)?;
        let weighted = control_points.iter().zip(&weights).map(|(p, &w)| p * w).collect();
        Ok(Self {
            knots,
            control_points,
            weights,
            weighted,
        })
    }

    /// The same curve with new weights (control points kept), e.g. the NUBS → NURBS step of
    /// Nowacki et al. Fails like [`NurbsCurve::new`]. O(n).
    pub fn with_weights(&self, weights: Vec<f64>) -> Result<Self> {
        Self::from_parts(self.knots.clone(), self.control_points.clone(), weights)
    }

    /// Replaces control point `index` and its weight, the knots kept: the in-place form of a
    /// knot operation done on a window of the curve (Sapidis–Farin's step changes one
    /// control point of a long curve). The homogeneous point is w P as [`NurbsCurve::new`]
    /// computes it, so the curve is bit for bit the one `new` would build from the same
    /// points and weights.
    ///
    /// Fails with [`Error::IndexOutOfRange`], [`Error::NonFinite`] on a non-finite point or
    /// [`Error::BadWeight`] on a weight that is not finite and positive (the curve is then
    /// unchanged). O(1).
    pub fn set_control_point(&mut self, index: usize, point: Vector<D>, weight: f64) -> Result<()> {
        let len = self.control_points.len();
        if index >= len {
            return Err(Error::IndexOutOfRange {
                what: "control points",
                index,
                len,
            });
        }
        if point.iter().any(|c| !c.is_finite()) {
            return Err(Error::NonFinite { what: "point", index });
        }
        if !(weight > 0.0 && weight.is_finite()) {
            return Err(Error::BadWeight { index, value: weight });
        }
        self.control_points[index] = point;
        self.weights[index] = weight;
        self.weighted[index] = point * weight;
        Ok(())
    }

    /// The degree p.
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The knot vector.
    pub fn knot_vector(&self) -> &KnotVector {
        &self.knots
    }

    /// All knots u_0 … u_m.
    pub fn knots(&self) -> &[f64] {
        self.knots.knots()
    }

    /// The control points P_i (Cartesian).
    pub fn control_points(&self) -> &[Vector<D>] {
        &self.control_points
    }

    /// The weights w_i.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// C(u) and its derivatives of order 1 … `order` (any order; those above the degree of the
    /// numerator and denominator still follow from Eq. 4.8), as limits from `side` at a knot.
    ///
    /// Homogeneous derivatives A^{(k)} = Σ N^{(k)}_i w_i P_i, w^{(k)} = Σ N^{(k)}_i w_i (A3.2
    /// on the weighted points), then The NURBS Book Eq. 4.8 / A4.2:
    /// C^{(k)} = (A^{(k)} − Σ_{i=1}^{k} C(k,i) w^{(i)} C^{(k−i)}) / w. O(p² + order·p + order²).
    ///
    /// This is [`rational_derivatives`] with `T = f64`: the one evaluation code path, shared
    /// with the generic [`RationalCurve`].
    pub fn derivatives(&self, u: f64, order: usize, side: Side) -> Vec<Vector<D>> {
        generic::rational_derivatives::<f64, D>(&self.knots, u, order, side, |i| {
            Some(((*self.weighted.get(i)?).into(), *self.weights.get(i)?))
        })
        .into_iter()
        .map(Vector::<D>::from)
        .collect()
    }

    /// The same curve over the scalar `T` ([`RationalCurve`]): weights and homogeneous
    /// control points lifted to `T`, e.g. to seed dual numbers. O(n).
    pub fn to_generic<T: num_traits::Float>(&self) -> RationalCurve<T, D> {
        RationalCurve {
            knots: self.knots.clone(),
            weighted: self
                .weighted
                .iter()
                .map(|q| std::array::from_fn(|c| generic::lift(q[c])))
                .collect(),
            weights: self.weights.iter().map(|&w| generic::lift(w)).collect(),
        }
    }

    /// The point C(u) (from the right at a knot; continuous anyway). O(p²).
    pub fn point(&self, u: f64) -> Vector<D> {
        self.derivatives(u, 0, Side::Right)[0]
    }
}

impl<const D: usize> Curve<D> for NurbsCurve<D> {
    /// (u_p, u_{m−p}).
    fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }

    /// Value and derivatives 1–3 from `side`: at an interior knot `Side::Left` uses the span
    /// ending there, `Side::Right` the span starting there.
    fn jet(&self, t: f64, side: Side) -> [Vector<D>; 4] {
        let d = self.derivatives(t, MAX_ORDER, side);
        [d[0], d[1], d[2], d[3]]
    }

    /// The distinct knots.
    fn breaks(&self) -> Vec<f64> {
        self.knots.distinct()
    }
}

impl<const D: usize> serde::Serialize for NurbsCurve<D> {
    /// `{"type": "nurbs", "degree", "knots", "control_points": [[x, y(, z)], …], "weights"}`,
    /// the `curve` object of the `fair` report.
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        let points: Vec<Vec<f64>> = self
            .control_points
            .iter()
            .map(|p| p.iter().copied().collect())
            .collect();
        let mut s = serializer.serialize_struct("NurbsCurve", 5)?;
        s.serialize_field("type", "nurbs")?;
        s.serialize_field("degree", &self.degree())?;
        s.serialize_field("knots", self.knots())?;
        s.serialize_field("control_points", &points)?;
        s.serialize_field("weights", &self.weights)?;
        s.end()
    }
}
