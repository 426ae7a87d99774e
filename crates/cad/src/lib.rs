//! Faired shapes into CAD: exact B-splines written and read as IGES, STEP and DXF, and a
//! least-squares rebuild with few control points.
//!
//! A naval architect fairs points in order to model with them: the faired curve must reach
//! Rhino, FreeCAD, CATIA or OpenCASCADE as a curve, not as points to be splined again (which
//! would undo the fairing's curvature). This crate
//!
//! 1. turns each representation of `curve-repr` into an exact B-spline ([`CadCurve`],
//!    [`CadSurface`]; the conversions are `curve_repr::convert`): a spline function with
//!    x(t) = t, a Hermite spline on single knots (double where only C1), the NURBS of the
//!    weight method as it is, the bicubic spline surface on single knots;
//! 2. writes and reads them: [`iges`] (5.3, entities 126 and 128), [`step`] (AP214/AP242,
//!    `B_SPLINE_CURVE_WITH_KNOTS`, rational complex instances, `B_SPLINE_SURFACE_WITH_KNOTS`),
//!    [`dxf`] (R2000 `SPLINE`), with the unit and a tolerance in the header. Reals are written
//!    with the shortest digits that read back bit for bit, so a round trip returns the same
//!    knots, weights and control points to the last bit in all three formats;
//! 3. rebuilds a curve with few control points ([`rebuild()`], The NURBS Book Eq. 9.63–9.69)
//!    and says whether the rebuild brought wiggles back.
//!
//! Every file the workspace writes goes through [`atomic`]: complete or not at all.
//!
//! The command needs one call, [`export()`] (or [`export_to_path`]): the faired shape, a
//! [`Format`] (from `-o`'s extension or `--cad`), [`CadSettings`] (unit, tolerance,
//! `--control-points`, `--fit-tolerance`), header [`WriteOptions`].
//!
//! ```
//! use cad::{CadCurve, CadSettings, Format, Shape, WriteOptions};
//! use curve_repr::{HermiteSpline, Vec2};
//!
//! let points = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.6), Vec2::new(2.5, 0.8), Vec2::new(4.0, 0.1)];
//! let spline = HermiteSpline::natural(&points)?;
//! let shape = Shape::Curve(CadCurve::from_hermite(&spline)?.with_name("wl3"));
//! let file = cad::export(&shape, Format::Step, &CadSettings::default(), &WriteOptions::default())?;
//! let back = cad::read(&file.text, Format::Step)?;
//! // The same knots and control points, to the last bit.
//! assert_eq!(back.curves[0].curve, file.model.curves[0].curve);
//! # Ok::<(), cad::Error>(())
//! ```

pub mod atomic;
pub mod dxf;
pub mod error;
pub mod export;
pub mod iges;
pub mod model;
pub mod number;
pub mod options;
pub mod rebuild;
pub mod step;
pub mod units;

pub use error::{Error, Result};
pub use export::{
    export, export_to_path, read, read_path, write, CadSettings, Export, ExportSummary, Format,
};
pub use model::{CadCurve, CadModel, CadSurface, CurveKind, Shape};
pub use options::{StepSchema, Timestamp, WriteOptions};
pub use rebuild::{rebuild, CurvatureCounts, RebuildReport, RebuildTarget};
pub use units::Units;
