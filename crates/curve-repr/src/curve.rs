//! The [`Curve`] and [`Interpolant`] traits every representation implements.

use crate::{Result, Vector};

/// The side from which a derivative is taken at a break point.
///
/// Piecewise polynomial curves are only C2 at their knots: the third derivative jumps, and
/// fairness indicators (Zhang–Cheng Eq. 17, Sapidis–Farin's curvature-slope jump) are
/// differences of the two one-sided limits. Away from break points both sides agree.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Side {
    /// The limit from smaller parameters, t → t⁻.
    Left,
    /// The limit from larger parameters, t → t⁺ (the convention of SciPy's `CubicSpline`).
    #[default]
    Right,
}

/// The highest derivative order a [`Curve`] reports.
pub const MAX_ORDER: usize = 3;

/// A parametric curve in `D` dimensions.
///
/// Implementors provide [`jet`](Curve::jet), the value and first three derivatives at one
/// parameter from one side, and [`breaks`](Curve::breaks), the parameters where polynomial
/// (or rational) pieces join. Everything else has a default.
///
/// Outside its domain a curve extends its end piece; callers that care check
/// [`domain`](Curve::domain).
///
/// A spline *function* y(x) is a curve in 2D, its graph (x, y(x)) with parameter x, so that
/// every criterion written for curves applies to it too.
pub trait Curve<const D: usize> {
    /// The parameter interval `(start, end)`, with `start < end`.
    fn domain(&self) -> (f64, f64);

    /// Value and derivatives of order 1, 2 and 3 at `t`, as limits from `side`.
    ///
    /// At a break point `Side::Left` gives the limits of the piece ending there and
    /// `Side::Right` those of the piece starting there; at the domain's ends the only piece
    /// there is used, whatever the side.
    fn jet(&self, t: f64, side: Side) -> [Vector<D>; 4];

    /// The break points: parameters where pieces join, increasing, both ends included.
    fn breaks(&self) -> Vec<f64>;

    /// [`jet`](Self::jet) at `t` on piece `piece` (the one from `breaks()[piece]` to
    /// `breaks()[piece + 1]`, `t` normally inside it): the same values as `jet(t,
    /// Side::Right)` there, without searching for the piece. For code that walks the pieces in
    /// order (measuring 10⁶ pieces, sampling a plot). The default searches; curves that index
    /// their pieces directly override it in O(1).
    fn jet_on_piece(&self, piece: usize, t: f64) -> [Vector<D>; 4] {
        let _ = piece;
        self.jet(t, Side::Right)
    }

    /// The point at `t`.
    fn eval(&self, t: f64) -> Vector<D> {
        self.jet(t, Side::Right)[0]
    }

    /// The derivative of order `order` (0 to [`MAX_ORDER`]) at `t`, from the right at a break.
    ///
    /// Returns `None` for orders above [`MAX_ORDER`].
    fn derivative(&self, t: f64, order: usize) -> Option<Vector<D>> {
        (order <= MAX_ORDER).then(|| self.jet(t, Side::Right)[order])
    }
}

/// A curve that interpolates data points and can be rebuilt after some of them move.
///
/// Every fairing strategy moves data points and needs the curve through the moved points.
/// [`move_points`](Interpolant::move_points) keeps the parameters of the data points fixed
/// (the fairing papers keep the knots fixed while they move points) and costs, where the
/// representation allows it, time proportional to the neighbourhood the move changes, not to
/// the number of points.
pub trait Interpolant<const D: usize>: Curve<D> {
    /// Number of data points.
    fn point_count(&self) -> usize;

    /// Data point `index`. Callers keep `index < point_count()`.
    fn point(&self, index: usize) -> Vector<D>;

    /// The parameter at which the curve passes through data point `index`.
    fn parameter(&self, index: usize) -> f64;

    /// All data points, in order.
    fn points(&self) -> Vec<Vector<D>> {
        (0..self.point_count()).map(|i| self.point(i)).collect()
    }

    /// All data parameters, in order.
    fn parameters(&self) -> Vec<f64> {
        (0..self.point_count()).map(|i| self.parameter(i)).collect()
    }

    /// Moves data points `(index, new position)` and rebuilds the curve through them,
    /// keeping every parameter.
    ///
    /// Fails, leaving the curve unchanged, on an index out of range, a non-finite position,
    /// or a move the representation cannot make.
    fn move_points(&mut self, moves: &[(usize, Vector<D>)]) -> Result<()>;
}
