//! The door of the fairing library: the three jobs every front end does — fair a curve, fair a
//! surface, measure (inspect) — typed, with no text in between, and the CAD export of their
//! results.
//!
//! The command (`fair-cli`), its local server (`fair serve`) and the Python package are thin
//! adapters over these functions: each reads its own input (files, JSON requests, NumPy
//! arrays), lends the points to the door with the name messages give them ([`CurveData`],
//! [`GridData`]), and writes what comes back ([`FairedCurve`], [`FairedSurface`],
//! [`CurveInspection`], [`SurfaceInspection`]: the points, the measurements and the
//! [`Report`]) in its own way.
//!
//! ```
//! use curve_repr::Vec2;
//! use fairing::catalog::{Catalog, CurvePoints};
//! use fair_door::{CurveData, CurveRequest};
//!
//! let points = CurvePoints::Planar((0..20).map(|i| {
//!     let x = i as f64 * 0.1;
//!     Vec2::new(x, x.sin() + if i % 2 == 0 { 1e-3 } else { -1e-3 })
//! }).collect());
//! let faired = fair_door::curve(&Catalog::builtin(), &CurveData::new(&points, "points"), &CurveRequest::default())?;
//! assert_eq!(faired.report.method, "jump-lsq");
//! assert_eq!(faired.points.len(), 20);
//! # Ok::<(), fair_door::Error>(())
//! ```
//!
//! What lives here, once: the report type ([`report`]), kind detection ([`kind`]), which
//! spline measures which input ([`measure`]), the constraints' checks ([`constraints`]), the
//! exact CAD curve or surface of a result ([`cad`]) and the one error type ([`Error`]).

pub mod cad;
pub mod constraints;
pub mod curve;
pub mod data;
pub mod error;
pub mod inspect;
pub mod kind;
pub mod measure;
pub mod report;
pub mod surface;

pub use constraints::ConstraintRequest;
pub use curve::{curve, CurveRequest, FairedCurve};
pub use data::{CurveData, GridData};
pub use error::{Error, Result};
pub use inspect::{CurveInspection, SurfaceInspection};
pub use kind::KindChoice;
pub use report::Report;
pub use surface::{surface, FairedSurface, SurfaceRequest};

/// Measures a curve (see [`inspect::curve`]).
pub use inspect::curve as inspect_curve;
/// Measures a grid (see [`inspect::surface`]).
pub use inspect::surface as inspect_surface;
