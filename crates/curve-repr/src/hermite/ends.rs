//! End conditions of a parametric cubic spline in Hermite form.

use crate::Vector;

/// How the tangent system of a [`HermiteSpline`](super::HermiteSpline) is closed at its ends.
///
/// Zhang–Cheng §2 close Eq. (2) with "two end point conditions" and use the free ends; the
/// others are the usual alternatives (Okada keeps end tangents, Han's runout for functions).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum HermiteEnds<const D: usize> {
    /// Free ends, C''(t_0) = C''(t_n) = 0: the natural spline of Zhang–Cheng §2. Rows
    /// 2M_0 + M_1 = 3(P_1 − P_0)/h_0 and M_{n−1} + 2M_n = 3(P_n − P_{n−1})/h_{n−1}.
    /// Needs 2 points.
    #[default]
    Natural,
    /// Given end tangents C'(t_0) = `start`, C'(t_n) = `end` (vectors, with respect to t).
    /// Needs 2 points.
    Clamped {
        /// The tangent C'(t_0).
        start: Vector<D>,
        /// The tangent C'(t_n).
        end: Vector<D>,
    },
    /// Parabolic runout, C''(t_0) = C''(t_1) and C''(t_{n−1}) = C''(t_n): the first and last
    /// segments are parabolas (C''' = 0 there). Rows M_0 + M_1 = 2(P_1 − P_0)/h_0 and
    /// M_{n−1} + M_n = 2(P_n − P_{n−1})/h_{n−1}. Needs 3 points (with two, both rows coincide).
    ParabolicRunout,
    /// A closed, periodic C2 curve: the segment P_{n} → P_0 closes it, every knot is
    /// interior and the system is cyclic. The parameters have one more entry than the points
    /// (see [`Parametrization::closed_parameters`](crate::Parametrization::closed_parameters)).
    /// Needs 3 points.
    Closed,
}

impl<const D: usize> HermiteEnds<D> {
    /// The smallest number of data points the end condition allows.
    pub fn min_points(&self) -> usize {
        match self {
            HermiteEnds::Natural | HermiteEnds::Clamped { .. } => 2,
            HermiteEnds::ParabolicRunout | HermiteEnds::Closed => 3,
        }
    }

    /// Whether the curve is closed.
    pub fn is_closed(&self) -> bool {
        matches!(self, HermiteEnds::Closed)
    }

    /// A short name for error messages.
    pub(super) fn name(&self) -> &'static str {
        match self {
            HermiteEnds::Natural => "a natural Hermite spline",
            HermiteEnds::Clamped { .. } => "a clamped Hermite spline",
            HermiteEnds::ParabolicRunout => "a Hermite spline with parabolic runout",
            HermiteEnds::Closed => "a closed Hermite spline",
        }
    }

    /// Row 0 of the tangent system, given the first chord slope d_0 = (P_1 − P_0)/h_0:
    /// `(diag, upper, rhs)` of diag·M_0 + upper·M_1 = rhs. `None` for a closed curve.
    pub(super) fn start_row(&self, slope: Vector<D>) -> Option<(f64, f64, Vector<D>)> {
        match self {
            HermiteEnds::Natural => Some((2.0, 1.0, slope * 3.0)),
            HermiteEnds::Clamped { start, .. } => Some((1.0, 0.0, *start)),
            HermiteEnds::ParabolicRunout => Some((1.0, 1.0, slope * 2.0)),
            HermiteEnds::Closed => None,
        }
    }

    /// Row n of the tangent system, given the last chord slope d_{n−1}:
    /// `(lower, diag, rhs)` of lower·M_{n−1} + diag·M_n = rhs. `None` for a closed curve.
    pub(super) fn end_row(&self, slope: Vector<D>) -> Option<(f64, f64, Vector<D>)> {
        match self {
            HermiteEnds::Natural => Some((1.0, 2.0, slope * 3.0)),
            HermiteEnds::Clamped { end, .. } => Some((0.0, 1.0, *end)),
            HermiteEnds::ParabolicRunout => Some((1.0, 1.0, slope * 2.0)),
            HermiteEnds::Closed => None,
        }
    }
}
