//! Fair a curve: check, plan, run the catalogue's method or pipeline, measure before and
//! after, and build the report.
//!
//! Order of checks (so that a user's mistakes are reported before anything runs): the number
//! of points, the kind, the method and its parameters (the catalogue's [`Catalog::plan`]),
//! the constraints; then the plan runs ([`Catalog::run_curve_plan`]: one method or a pipeline
//! of stages), then the measures. Everything about methods — names, parameters, what each
//! refuses — is the catalogue's.

use std::collections::BTreeMap;

use fairing::catalog::{
    AnyCurve, Catalog, ConfigFile, CurveKind, CurvePoints, MethodKind, ParameterMap, Plan, PlanConstraints,
};

use crate::constraints::{self, ConstraintRequest};
use crate::data::CurveData;
use crate::error::{Error, Result};
use crate::kind::{self, KindChoice};
use crate::measure::{self, CurveMeasurement, Detail};
use crate::report::{Energies, Report, ReportKind};

/// The fewest points any curve method works on: curvature-slope jumps e_i need three.
pub const MIN_CURVE_POINTS: usize = 3;

/// The default method for a kind of curve: `jump-lsq` for both. The papers' methods
/// (`two-phase`, `strain-energy`, ...) stay selectable by name.
pub fn default_method(kind: CurveKind) -> &'static str {
    match kind {
        CurveKind::Function | CurveKind::Parametric => "jump-lsq",
    }
}

/// What to do with a curve: the method, its settings, the constraints, the kind.
///
/// A config pipeline with its constraints runs from the library in one call:
///
/// ```
/// use curve_repr::Vec2;
/// use fairing::catalog::{Catalog, ConfigFile, CurvePoints};
/// use fair_door::{CurveData, CurveRequest};
///
/// let points = CurvePoints::Planar((0..30).map(|i| {
///     let x = i as f64 / 29.0;
///     Vec2::new(x, (3.0 * x).sin() + if i % 2 == 0 { 2e-3 } else { -2e-3 })
/// }).collect());
/// let toml = "[constraints]\nfixed = [0, 29]\ntolerance = 0.01\n\n\
///             [[stage]]\nmethod = \"smoothing-spline\"\n\n[[stage]]\nmethod = \"two-phase\"\n";
/// let request = CurveRequest {
///     config: Some(ConfigFile::parse("pipeline.toml", toml).unwrap()),
///     ..CurveRequest::default()
/// };
/// let faired = fair_door::curve(&Catalog::builtin(), &CurveData::new(&points, "points"), &request)?;
/// assert_eq!(faired.report.method, "smoothing-spline+two-phase");
/// assert!(faired.report.m_d <= 0.01);
/// assert_eq!(faired.points.rows()[29], points.rows()[29]);
/// # Ok::<(), fair_door::Error>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct CurveRequest {
    /// The method (or pipeline) by name; `None` for the kind's [`default_method`] or the
    /// config's.
    pub method: Option<String>,
    /// Function, parametric, or detected.
    pub kind: KindChoice,
    /// The method's parameters by name (they win over the config's).
    pub settings: ParameterMap,
    /// A config file: parameters, `[constraints]`, a pipeline of `[[stage]]`s.
    pub config: Option<ConfigFile>,
    /// Fixed points, bad points, tolerance band, end clamp.
    pub constraints: ConstraintRequest,
    /// Also sample the splines for a picture (the measurements' `samples`, `comb`,
    /// `curvature`): O(n) evaluations that only a plot needs.
    pub samples: bool,
}

/// A faired curve: the points, the measurements before and after and the report.
#[derive(Debug, Clone)]
pub struct FairedCurve {
    /// The faired points, in the input's order.
    pub points: CurvePoints,
    /// How they were read and measured.
    pub kind: CurveKind,
    /// The report (its `curve` is the method's representation, which CAD output writes).
    pub report: Report,
    /// The input measured (samples only when asked for).
    pub before: CurveMeasurement,
    /// The result measured.
    pub after: CurveMeasurement,
}

/// `s_d` and `m_d`: the sum and the largest of the distances moved. O(n).
pub fn displacement(before: &CurvePoints, after: &CurvePoints) -> (f64, f64) {
    let (a, b) = (before.rows(), after.rows());
    let distances = a
        .iter()
        .zip(&b)
        .map(|(p, q)| p.iter().zip(q).map(|(u, v)| (u - v).powi(2)).sum::<f64>().sqrt());
    distances.fold((0.0, 0.0), |(sum, max), d| (sum + d, f64::max(max, d)))
}

/// Every criterion of the catalogue that applies to a curve of `dimension` whose energies are
/// `energies`, by name: the criteria that are energies are read from them (no second
/// integration), the others evaluated on the curve `curve()` builds, only if one needs it. A
/// criterion that cannot be evaluated is left out (its reason goes to `failed`); errors name
/// `source`.
pub fn criteria<C: std::borrow::Borrow<AnyCurve>>(
    catalog: &Catalog,
    dimension: usize,
    energies: Option<&Energies>,
    curve: impl FnOnce() -> fairing::Result<C>,
    source: &str,
    failed: &mut BTreeMap<String, String>,
) -> Result<BTreeMap<String, f64>> {
    let values = catalog
        .criteria_with(dimension, energies, curve)
        .map_err(|e| Error::from_fairing(e, source))?;
    let mut out = BTreeMap::new();
    for (name, value) in values {
        match value {
            Ok(v) if v.is_finite() => {
                out.insert(name, v);
            }
            Ok(v) => {
                failed.insert(name, format!("not finite ({v})"));
            }
            Err(e) => {
                failed.insert(name, e.to_string());
            }
        }
    }
    Ok(out)
}

/// The kind, plan and constraints a request implies for `data` (checked: enough points, the
/// kind, the method and its parameters, the constraints' indices). What `--print-config`
/// shows.
pub fn plan(
    catalog: &Catalog,
    data: &CurveData<'_>,
    request: &CurveRequest,
) -> Result<(CurveKind, Plan, PlanConstraints)> {
    data.require_at_least(MIN_CURVE_POINTS, "a curve")?;
    let kind = kind::resolve(request.kind, data)?;
    let plan = catalog
        .plan(
            MethodKind::Curve,
            request.method.as_deref(),
            default_method(kind),
            request.config.as_ref(),
            &request.settings,
        )
        .map_err(|e| Error::from_fairing(e, data.source))?;
    let constraints = constraints::resolve(&request.constraints, &plan.constraints, data.len())?;
    Ok((kind, plan, constraints))
}

/// Fairs one curve as `request` asks: the faired points, both measurements and the report.
///
/// Every error about the points names `data.source` (and the line, when known).
pub fn curve(catalog: &Catalog, data: &CurveData<'_>, request: &CurveRequest) -> Result<FairedCurve> {
    fair_points(catalog, data, request).map_err(|e| measure::in_file(e, data.source))
}

/// [`curve`], errors about the points not yet named after the source.
fn fair_points(catalog: &Catalog, data: &CurveData<'_>, request: &CurveRequest) -> Result<FairedCurve> {
    let (kind, plan, constraints) = plan(catalog, data, request)?;
    let run = catalog
        .run_curve_plan(&plan, data.points, kind, &constraints)
        .map_err(|e| Error::from_fairing(e, data.source))?;
    let faired = run.points;
    let detail = Detail {
        plot: request.samples,
        record: true,
    };
    let mut before = measure::curve_with(kind, data.points, detail)?;
    let mut after = measure::curve_with(kind, &faired, detail)?;
    // Criteria on the curve as represented: the method's own curves when it has them, else
    // the spline the report measures (whose energies are already in the measures).
    let mut failed = BTreeMap::new();
    let dimension = data.points.dimension();
    match &run.represented {
        Some(represented) => {
            for (measures, curve) in [
                (&mut before.measures, &represented.before),
                (&mut after.measures, &represented.after),
            ] {
                // The method's own curve (rational pieces): every energy adaptive, each with
                // its accuracy; where an integrand is not finite, no energies.
                let measured = fairing::catalog::measure_energies(curve).ok();
                measures.energies = measured.map(|m| m.values);
                measures.energy_accuracy = measured.map(|m| m.accuracy);
                measures.criteria = criteria(
                    catalog,
                    dimension,
                    measures.energies.as_ref(),
                    || Ok(curve),
                    data.source,
                    &mut failed,
                )?;
            }
        }
        None => {
            for (measures, points) in [
                (&mut before.measures, data.points),
                (&mut after.measures, &faired),
            ] {
                measures.criteria = criteria(
                    catalog,
                    dimension,
                    measures.energies.as_ref(),
                    || fairing::catalog::measured_curve(kind, points),
                    data.source,
                    &mut failed,
                )?;
            }
        }
    }
    let (s_d, m_d) = displacement(data.points, &faired);
    let mut extras = run.extras;
    extras.insert("termination".into(), serde_json::json!(run.termination));
    if !failed.is_empty() {
        extras.insert("criteria_failed".into(), serde_json::json!(failed));
    }
    let report = Report {
        method: plan.name(),
        kind: ReportKind::from(kind),
        n: data.len(),
        iterations: run.iterations,
        before: before.measures.clone(),
        after: after.measures.clone(),
        s_d,
        m_d,
        moved: run.moved,
        elapsed_ms: run.elapsed_ms,
        // Every method's report has a curve: the method's own representation, or the spline
        // the report measures when the method gives none.
        curve: if run.curve.is_null() {
            after.curve.clone()
        } else {
            run.curve
        },
        params: plan.params(catalog),
        extras,
    };
    Ok(FairedCurve {
        points: faired,
        kind,
        report,
        before,
        after,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::Vec2;

    #[test]
    fn displacement_sums_and_maxes_distances() {
        let a = CurvePoints::Planar(vec![Vec2::new(0., 0.), Vec2::new(1., 0.), Vec2::new(2., 0.)]);
        let b = CurvePoints::Planar(vec![Vec2::new(0., 0.), Vec2::new(1., 3.), Vec2::new(5., 4.)]);
        assert_eq!(displacement(&a, &b), (8.0, 5.0));
    }
}
