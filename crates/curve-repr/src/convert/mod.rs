//! Exact conversions of the cubic representations into B-splines, the form CAD systems read.
//!
//! Every cubic representation of this crate is a piecewise cubic polynomial, and every
//! piecewise cubic is a cubic B-spline on a knot vector whose interior knots are its break
//! points, each repeated 3 − r times where the pieces join with continuity C^r. Nothing is
//! approximated: the control points are the *blossoms* (polar forms) of the pieces at three
//! consecutive knots (The NURBS Book §A5 and Ramshaw's blossoming principle; de Boor's dual
//! functionals), computed by de Casteljau's algorithm with a different parameter at each level.
//!
//! - [`CubicPieces`]: a piecewise cubic in Bézier form, built from Hermite data
//!   ([`CubicPieces::from_hermite`], a C1 or C2 Hermite or Ferguson chain) or from power-form
//!   segments ([`CubicPieces::from_unit_power`], Okada's Ferguson coefficients), converted by
//!   [`CubicPieces::to_bspline`] with a [`JoinRule`]: double knots everywhere (C1, every
//!   control point a Bézier point of the Hermite form), or single knots where the pieces are
//!   found to join C2 (checked, within a stated tolerance) and double or triple ones elsewhere.
//! - [`SplineFunction::to_bspline`](crate::SplineFunction::to_bspline): y(x) as a planar
//!   curve (x(t), y(t)) with x(t) = t (control abscissae at the Greville points).
//! - [`HermiteSpline::to_bspline`](crate::HermiteSpline::to_bspline): the C2 spline on single
//!   knots (checked); a closed spline as a clamped curve that starts and ends at P_0.
//! - [`BicubicSplineSurface::to_bspline`](crate::BicubicSplineSurface::to_bspline): the
//!   tensor-product C2 surface on single knots in u and v (checked).
//!
//! A NURBS curve or surface is already in the form CAD systems read and is written as it is.
//!
//! Accuracy: the control points are computed in floating point, so the converted curve equals
//! the original to rounding (about 1e-15 relative to the curve's size, tested to 1e-12 over
//! many parameters); the data points lie on it to the same accuracy.

mod function;
mod hermite;
mod pieces;
mod surface;

pub use pieces::{CubicPieces, JoinRule, C2_TOLERANCE};

pub(crate) use pieces::check_breaks as check_increasing;
