//! B-spline machinery shared by NURBS curves and surfaces: knot vectors and basis functions.
//!
//! Algorithms and equation numbers follow L. Piegl and W. Tiller, *The NURBS Book*, 2nd ed.,
//! Springer 1997 (A2.1–A2.3, Eq. 9.8, Eq. 9.22).

pub mod basis;
pub mod knots;

pub use basis::{basis_derivatives, basis_functions, find_span};
pub use knots::KnotVector;
