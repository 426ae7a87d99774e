//! Curve and surface representations for fairing.
//!
//! The first axis of the fairing framework: how measured points become a curve or a surface.
//! Every later piece (indicators in `fairness`, strategies in `fairing`) works through the
//! traits defined here:
//!
//! - [`Curve`]: a parametric curve in `D` dimensions with derivatives of order 0–3, evaluated
//!   from either side of a break point (third-derivative jumps need both sides).
//! - [`Interpolant`]: a curve that passes through data points at known parameters and can be
//!   rebuilt cheaply after some of them move, which every fairing strategy needs.
//! - [`Surface`]: a parametric surface in 3D with partial derivatives.
//!
//! Representations: [`SplineFunction`] (Han et al.), [`HermiteSpline`] (Zhang–Cheng, Okada),
//! [`NurbsCurve`] (Nowacki et al.), [`BicubicSplineSurface`] (Zhang–Cheng §4) and
//! [`NurbsSurface`].
//!
//! Numbers are `f64` throughout; points and vectors are nalgebra's [`SVector`](nalgebra::SVector).
//! No input makes this crate panic: every constructor validates its input and returns
//! [`Error`].

pub mod bicubic_surface;
pub mod bspline;
pub mod convert;
pub mod curve;
pub mod error;
pub mod hermite;
pub mod kind;
pub mod number;
pub mod nurbs_curve;
pub mod nurbs_surface;
pub mod parametrization;
pub mod spline_function;
pub mod surface;
pub mod tridiagonal;
pub mod vector;

pub use bicubic_surface::{BicubicSplineSurface, BicubicSurfaceSettings, GridTopology, NodeJump, Poles};
pub use bspline::KnotVector;
pub use convert::{CubicPieces, JoinRule};
pub use curve::{Curve, Interpolant, Side};
pub use error::{Error, Result};
pub use hermite::{HermiteEnds, HermiteSettings, HermiteSpline};
pub use kind::CurveKind;
pub use nurbs_curve::{Interpolation, InterpolationSettings, NurbsCurve, NurbsInterpolant};
pub use nurbs_surface::NurbsSurface;
pub use parametrization::Parametrization;
pub use spline_function::{EndCondition, SplineFunction};
pub use surface::Surface;
pub use vector::{Vec2, Vec3, Vector};
