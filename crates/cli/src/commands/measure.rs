//! SEAM: fairness measures of a curve or a surface (the `fairness` crate).
//!
//! The lead wires these to the indicators and criteria: DESIGN.md defines every field of
//! [`Measures`] for each kind. Both `fair inspect` and the report's `before`/`after` use them.

use crate::error::{Error, Result};
use crate::input::{Grid, Points};
use crate::kind::CurveKind;
use crate::plots::CombData;
use crate::report::Measures;

/// What measuring a curve gives: the report's numbers and what the plot can show.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CurveMeasurement {
    /// The report's measures.
    pub measures: Measures,
    /// The spline through the points, as the report's `curve` value.
    pub curve: serde_json::Value,
    /// The spline sampled densely, for the plot.
    pub samples: Option<Vec<[f64; 2]>>,
    /// Its curvature comb.
    pub comb: Option<CombData>,
    /// z_i per data point.
    pub z: Option<Vec<f64>>,
}

/// What measuring a surface gives.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SurfaceMeasurement {
    /// The report's measures.
    pub measures: Measures,
    /// The surface, as the report's `curve` value.
    pub surface: serde_json::Value,
    /// z_ij over the grid (rows i, columns j), for the plot.
    pub z: Option<Vec<Vec<f64>>>,
}

/// Measures a curve of the given kind (DESIGN.md "Definitions").
pub fn curve(kind: CurveKind, points: &Points) -> Result<CurveMeasurement> {
    let _ = (kind, points);
    Err(Error::NotAvailable {
        what: "the curve indicators (crate fairness)".into(),
    })
}

/// Measures a surface grid (DESIGN.md "Definitions", surface kind).
pub fn surface(grid: &Grid) -> Result<SurfaceMeasurement> {
    let _ = grid;
    Err(Error::NotAvailable {
        what: "the surface indicators (crate fairness)".into(),
    })
}
