//! Fair a surface grid: the same order of checks as a curve; point indices (fixed, bad, the
//! report's `moved`) count the grid row by row from 0 (k = i · columns + j); an end clamp
//! `g0` keeps the grid's boundary. The method and what it refuses are the catalogue's.

use fairing::catalog::{
    Catalog, ConfigFile, Grid, MethodKind, ParameterMap, Plan, PlanConstraints, SurfaceJob,
};

use crate::constraints::{self, ConstraintRequest};
use crate::data::GridData;
use crate::error::{Error, Result};
use crate::measure::{self, SurfaceMeasurement};
use crate::report::{Report, ReportKind};

/// The default surface method: `jump-lsq`, which beat csaps and OpenCASCADE at equal
/// displacement on 55 of 63 held-out noisy nets where Zhang–Cheng beat both on 6 of 30
/// (`docs/experiments/surface-fairing.md`). `zhang-cheng`, the paper's method, stays one
/// `--method` away.
pub const DEFAULT_METHOD: &str = "jump-lsq";

/// What to do with a grid: the method, its settings, the constraints.
#[derive(Debug, Clone, Default)]
pub struct SurfaceRequest {
    /// The method by name; `None` for [`DEFAULT_METHOD`] or the config's.
    pub method: Option<String>,
    /// The method's parameters by name (they win over the config's).
    pub settings: ParameterMap,
    /// A config file: parameters and `[constraints]` (pipelines are for curves).
    pub config: Option<ConfigFile>,
    /// Fixed points, bad points, tolerance band, end clamp.
    pub constraints: ConstraintRequest,
    /// Edges held to neighbours (the surface `jump-lsq` only; [`fairing::strategies::Join`]).
    pub joins: Vec<fairing::strategies::Join>,
}

/// A faired grid: the grid, the measurements before and after and the report.
#[derive(Debug, Clone)]
pub struct FairedSurface {
    /// The faired grid.
    pub grid: Grid,
    /// The report (its `curve` is the surface, which CAD output writes).
    pub report: Report,
    /// The input measured.
    pub before: SurfaceMeasurement,
    /// The result measured.
    pub after: SurfaceMeasurement,
}

/// The plan and constraints a request implies for `data` (checked). What `--print-config`
/// shows.
pub fn plan(
    catalog: &Catalog,
    data: &GridData<'_>,
    request: &SurfaceRequest,
) -> Result<(Plan, PlanConstraints)> {
    data.require_grid()?;
    let plan = catalog
        .plan(
            MethodKind::Surface,
            request.method.as_deref(),
            DEFAULT_METHOD,
            request.config.as_ref(),
            &request.settings,
        )
        .map_err(|e| Error::from_fairing(e, data.source))?;
    let constraints = constraints::resolve(&request.constraints, &plan.constraints, data.grid.points.len())?;
    Ok((plan, constraints))
}

/// Fairs one grid as `request` asks. Every error about the points names `data.source`.
pub fn surface(catalog: &Catalog, data: &GridData<'_>, request: &SurfaceRequest) -> Result<FairedSurface> {
    fair_grid(catalog, data, request).map_err(|e| measure::in_file(e, data.source))
}

fn fair_grid(catalog: &Catalog, data: &GridData<'_>, request: &SurfaceRequest) -> Result<FairedSurface> {
    let (plan, constraints) = plan(catalog, data, request)?;
    let whole = request
        .joins
        .iter()
        .fold(constraints.constraints(constraints.tolerance), |c, j| {
            c.with_join(j.clone())
        });
    let job = SurfaceJob {
        method: &plan.name(),
        grid: data.grid,
        constraints: &whole,
        bad_points: &constraints.bad_points,
        catalog,
    };
    let run = catalog
        .run_surface_plan(&plan, &job)
        .map_err(|e| Error::from_fairing(e, data.source))?;
    let faired = run.grid;
    let before = measure::surface(data.grid)?;
    let after = measure::surface(&faired)?;
    let distances = data
        .grid
        .points
        .iter()
        .zip(&faired.points)
        .map(|(p, q)| (p - q).norm());
    let (s_d, m_d) = distances.fold((0.0, 0.0), |(sum, max), d| (sum + d, f64::max(max, d)));
    let mut extras = run.extras;
    extras.insert("termination".into(), serde_json::json!(run.termination));
    let report = Report {
        method: plan.name(),
        kind: ReportKind::Surface,
        n: data.grid.points.len(),
        iterations: run.iterations,
        before: before.measures.clone(),
        after: after.measures.clone(),
        s_d,
        m_d,
        moved: run.moved,
        elapsed_ms: run.elapsed_ms,
        curve: run.surface,
        params: plan.params(catalog),
        extras,
    };
    Ok(FairedSurface {
        grid: faired,
        report,
        before,
        after,
    })
}
