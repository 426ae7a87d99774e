//! STEP (ISO 10303-21) of AP214 or AP242: `B_SPLINE_CURVE_WITH_KNOTS` and
//! `B_SPLINE_SURFACE_WITH_KNOTS`, rational as complex instances.
//!
//! - [`write()`]: one product whose shape is a geometrically bounded wireframe representation
//!   (a `GEOMETRIC_CURVE_SET` of the curves) or, with surfaces, a geometrically bounded
//!   surface representation (a `GEOMETRIC_SET`), in a context that carries the length unit
//!   and the model's uncertainty. A curve whose weights are all equal is written as
//!   `B_SPLINE_CURVE_WITH_KNOTS`, otherwise as the complex instance
//!   `(BOUNDED_CURVE() B_SPLINE_CURVE(…) B_SPLINE_CURVE_WITH_KNOTS(…) CURVE()
//!   GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE(…) REPRESENTATION_ITEM(…))`;
//!   surfaces likewise. Reals with the shortest digits that read back bit for bit.
//! - [`read`]: every B-spline curve and surface (simple or rational complex instances), the
//!   length unit and the uncertainty. A curve inside a `TRIMMED_CURVE` with parameter trims is
//!   cut to them (by knot insertion, exactly); curves that bound a face (`SURFACE_CURVE`,
//!   `SEAM_CURVE`) and curves with 2D points (parameter-space curves) are skipped.

mod parse;
mod read;
mod write;

pub use read::read;
pub use write::write;
