//! Measure a curve or a surface and change nothing: the report has the shape of a fairing's,
//! with `method` `inspect`, `after` equal to `before` and nothing moved.

use std::collections::BTreeMap;

use fairing::catalog::{Catalog, CurveKind};

use crate::curve::{criteria, MIN_CURVE_POINTS};
use crate::data::{CurveData, GridData};
use crate::error::Result;
use crate::kind::{self, KindChoice};
use crate::measure::{self, CurveMeasurement, Detail, SurfaceMeasurement};
use crate::report::{Energies, Report, ReportKind};

/// A curve measured: how it was read, the measurement (what a picture shows) and the report.
#[derive(Debug, Clone)]
pub struct CurveInspection {
    /// The kind it was measured as.
    pub kind: CurveKind,
    /// The measurement (samples as [`Detail`] asked).
    pub measured: CurveMeasurement,
    /// The report, checked finite.
    pub report: Report,
}

/// A grid measured.
#[derive(Debug, Clone)]
pub struct SurfaceInspection {
    /// The measurement.
    pub measured: SurfaceMeasurement,
    /// The report, checked finite.
    pub report: Report,
}

/// Measures a curve read as `kind`: `detail` says whether to sample it for a picture and
/// whether to build the report's `curve` record (O(n) values a report not written need not
/// build; else `null`). Errors name `data.source`.
pub fn curve(
    catalog: &Catalog,
    data: &CurveData<'_>,
    kind: KindChoice,
    detail: Detail,
) -> Result<CurveInspection> {
    data.require_at_least(MIN_CURVE_POINTS, "a curve")?;
    let kind = kind::resolve(kind, data)?;
    let mut measured =
        measure::curve_with(kind, data.points, detail).map_err(|e| measure::in_file(e, data.source))?;
    let mut measures = measured.measures.clone();
    measures.criteria = curve_criteria(catalog, kind, data, measures.energies.as_ref())?;
    measured.measures.criteria = measures.criteria.clone();
    let report = Report::inspection(
        ReportKind::from(kind),
        data.len(),
        measures,
        std::mem::take(&mut measured.curve),
    );
    report.check_finite()?;
    Ok(CurveInspection {
        kind,
        measured,
        report,
    })
}

/// Measures a grid. Errors name `data.source`.
pub fn surface(data: &GridData<'_>) -> Result<SurfaceInspection> {
    data.require_grid()?;
    let mut measured = measure::surface(data.grid).map_err(|e| measure::in_file(e, data.source))?;
    let report = Report::inspection(
        ReportKind::Surface,
        data.grid.points.len(),
        measured.measures.clone(),
        std::mem::take(&mut measured.surface),
    );
    report.check_finite()?;
    Ok(SurfaceInspection { measured, report })
}

/// Every registered criterion that applies, on the spline measured for `data` read as
/// `kind`, whose energies are `energies` (the report's `criteria`; those that are energies
/// are read from `energies`, the spline is built again only for the others; a criterion
/// that fails is left out). O(n) per criterion that is not an energy.
pub fn curve_criteria(
    catalog: &Catalog,
    kind: CurveKind,
    data: &CurveData<'_>,
    energies: Option<&Energies>,
) -> Result<BTreeMap<String, f64>> {
    let mut failed = BTreeMap::new();
    criteria(
        catalog,
        data.points.dimension(),
        energies,
        || fairing::catalog::measured_curve(kind, data.points),
        data.source,
        &mut failed,
    )
}
