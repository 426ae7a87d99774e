//! Rebuild with few control points (Rhino's Rebuild/Fit): the least-squares B-spline of The
//! NURBS Book §9.4.1 (Eq. 9.63–9.69, see `curve_repr::nurbs_curve::fit`) through the faired
//! points, with a stated number of control points or the fewest within a distance, and a
//! check that the rebuild does not bring back the wiggles the fairing removed.
//!
//! - A function y(x) is rebuilt as a function: y is fitted over x and the control abscissae
//!   are the Greville points, so x(t) = t still ([`NurbsCurve::least_squares_graph`]); its
//!   deviations are vertical, |Δy|, as the function kind measures displacement.
//! - A parametric curve is fitted over the faired curve's own parameters (chord length for
//!   the natural spline), in 2D when it is planar.
//! - A closed curve is fitted through its closing point too (start and end interpolated);
//!   the rebuilt curve is closed with a C0 seam.
//!
//! The curvature counts compare like with like: both curves are sampled at the parameters
//! of the faired points (the knots of the exact curve), and counted with the rule of the
//! `fair` report: for a function, inflections and vibrations of (x_k, y''(x_k)), Han's x–c
//! polyline with c = y''/6; for a parametric curve, of (t_k, κ(t_k)) (inflections only in
//! 2D). On the exact faired curve these are the report's own counts of the faired points.

use curve_repr::nurbs_curve::fit::{graph_of, max_control_count};
use curve_repr::{Curve, NurbsCurve, Side, Vec2, Vec3, Vector};
use fairness::curvature::CurvatureForm;
use fairness::jumps::vibration_count;
use fairness::sign_changes;

use crate::model::{lift_curve, planar_curve, CadCurve, CurveKind};
use crate::{Error, Result};

/// What a rebuild aims for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RebuildTarget {
    /// Exactly this many control points.
    ControlPoints(usize),
    /// The fewest control points whose largest deviation from the faired points is at most
    /// this distance.
    Tolerance(f64),
}

/// Curvature sign changes of a curve sampled at the faired points' parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct CurvatureCounts {
    /// Sign changes of the curvature (of y'' for a function); `null` for a 3D curve.
    pub inflections: Option<usize>,
    /// Sign changes of Han's e (the curvature's second divided differences).
    pub vibrations: usize,
}

/// What a rebuild did and how it compares with the faired curve.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct RebuildReport {
    /// Control points of the curve written.
    pub control_points: usize,
    /// Its degree.
    pub degree: usize,
    /// max_k |Q_k − C(ū_k)| over the faired points Q_k at their parameters ū_k (vertical
    /// |Δy| for a function): an upper bound of each point's distance from the curve.
    pub max_deviation: f64,
    /// The distance asked for (`--fit-tolerance`), if any.
    pub fit_tolerance: Option<f64>,
    /// `true` when no fit with at most half as many control points as points met the
    /// tolerance, so the exact faired curve was written instead (its deviation is rounding).
    pub exact_fallback: bool,
    /// Counts of the exact faired curve.
    pub faired: CurvatureCounts,
    /// Counts of the curve written.
    pub rebuilt: CurvatureCounts,
    /// `true` when the rebuilt curve has more inflections or vibrations than the faired one:
    /// the rebuild brought wiggles back (more control points, or a smaller tolerance, help).
    pub wiggles_back: bool,
}

/// The data a rebuild fits: the faired points and their parameters, with the curve's end
/// points added where its domain reaches beyond them (the closing point of a closed curve).
fn data(curve: &CadCurve) -> (Vec<Vec3>, Vec<f64>) {
    let (mut points, mut parameters) = curve.sample_points(4);
    let (start, end) = curve.curve.domain();
    if parameters.first().is_none_or(|&t| t > start) {
        points.insert(0, curve.curve.point(start));
        parameters.insert(0, start);
    }
    if parameters.last().is_none_or(|&t| t < end) {
        points.push(curve.curve.point(end));
        parameters.push(end);
    }
    (points, parameters)
}

/// κ (signed in 2D) or, for a function, y'' = (x'y'' − y'x'')/x'³ at each parameter.
fn curvature_values(
    curve: &NurbsCurve<3>,
    dimension: usize,
    kind: CurveKind,
    parameters: &[f64],
) -> Result<Vec<f64>> {
    if kind == CurveKind::Function {
        return parameters
            .iter()
            .map(|&t| {
                let [_, d1, d2, _] = curve.jet(t, Side::Right);
                let value = (d1.x * d2.y - d1.y * d2.x) / (d1.x * d1.x * d1.x);
                if value.is_finite() {
                    Ok(value)
                } else {
                    Err(Error::Unsupported(format!(
                        "the curve is not a function of x at parameter {t} (x' = {})",
                        d1.x
                    )))
                }
            })
            .collect();
    }
    if dimension == 2 {
        let planar = planar_curve(curve)?;
        values::<2>(&planar, parameters)
    } else {
        values::<3>(curve, parameters)
    }
}

fn values<const D: usize>(curve: &NurbsCurve<D>, parameters: &[f64]) -> Result<Vec<f64>>
where
    Vector<D>: CurvatureForm,
{
    parameters
        .iter()
        .map(|&t| Ok(fairness::curvature::curvature_at(curve, t, Side::Right)?))
        .collect()
}

/// The counts of `curve` sampled at `parameters` (see the [module documentation](self)).
pub fn curvature_counts(
    curve: &NurbsCurve<3>,
    dimension: usize,
    kind: CurveKind,
    parameters: &[f64],
) -> Result<CurvatureCounts> {
    let values = curvature_values(curve, dimension, kind, parameters)?;
    let abscissae: Vec<f64> = match kind {
        CurveKind::Function => parameters.iter().map(|&t| curve.point(t).x).collect(),
        CurveKind::Parametric => parameters.to_vec(),
    };
    let inflections = (kind == CurveKind::Function || dimension == 2).then(|| sign_changes(&values));
    Ok(CurvatureCounts {
        inflections,
        vibrations: vibration_count(&abscissae, &values)?,
    })
}

fn planar_points(points: &[Vec3]) -> Vec<Vec2> {
    points.iter().map(|p| Vec2::new(p.x, p.y)).collect()
}

/// A fit of `count` control points (or, with `tolerance`, the fewest that meet it) of the
/// data, as a 3D curve, with its deviation and whether the tolerance was met.
fn fit(
    curve: &CadCurve,
    points: &[Vec3],
    parameters: &[f64],
    degree: usize,
    target: RebuildTarget,
) -> Result<(NurbsCurve<3>, f64, bool)> {
    match curve.kind {
        CurveKind::Function => {
            let y: Vec<Vector<1>> = points.iter().map(|p| Vector::<1>::new(p.y)).collect();
            let (scalar, deviation, met) = match target {
                RebuildTarget::ControlPoints(n) => {
                    let f = NurbsCurve::<1>::least_squares(&y, parameters, degree, n)?;
                    let d = curve_repr::nurbs_curve::fit::max_deviation(&f, &y, parameters);
                    (f, d, true)
                }
                RebuildTarget::Tolerance(tol) => {
                    let f = NurbsCurve::<1>::least_squares_within(&y, parameters, degree, tol)?;
                    (f.curve, f.max_deviation, f.tolerance_met)
                }
            };
            Ok((lift_curve(&graph_of(&scalar)?)?, deviation, met))
        }
        CurveKind::Parametric if curve.dimension == 2 => {
            let (c, d, met) = fit_points(&planar_points(points), parameters, degree, target)?;
            Ok((lift_curve(&c)?, d, met))
        }
        CurveKind::Parametric => fit_points(points, parameters, degree, target),
    }
}

fn fit_points<const D: usize>(
    points: &[Vector<D>],
    parameters: &[f64],
    degree: usize,
    target: RebuildTarget,
) -> Result<(NurbsCurve<D>, f64, bool)> {
    Ok(match target {
        RebuildTarget::ControlPoints(n) => {
            let c = NurbsCurve::least_squares(points, parameters, degree, n)?;
            let d = curve_repr::nurbs_curve::fit::max_deviation(&c, points, parameters);
            (c, d, true)
        }
        RebuildTarget::Tolerance(tol) => {
            let f = NurbsCurve::least_squares_within(points, parameters, degree, tol)?;
            (f.curve, f.max_deviation, f.tolerance_met)
        }
    })
}

/// The deviation of `candidate` from the data, vertical for a function.
fn deviation(kind: CurveKind, candidate: &NurbsCurve<3>, points: &[Vec3], parameters: &[f64]) -> f64 {
    points
        .iter()
        .zip(parameters)
        .map(|(q, &t)| {
            let p = candidate.point(t);
            match kind {
                CurveKind::Function => (q.y - p.y).abs(),
                CurveKind::Parametric => (q - p).norm(),
            }
        })
        .fold(0.0, f64::max)
}

/// Rebuilds `curve` with few control points of `degree` (see the [module
/// documentation](self)) and reports the deviation and the curvature counts before and after.
///
/// With [`RebuildTarget::Tolerance`], when no fit with at most
/// [`max_control_count`] control points meets the tolerance, the exact curve is returned
/// (`exact_fallback`). Fails with [`Error::BadParameter`] for a control-point count the data
/// cannot carry (fewer than degree + 1, or more than two points per knot span allow),
/// [`Error::Unsupported`] for a function whose parameters are not its abscissae (as
/// [`CadCurve::from_spline_function`] makes them), and as the fit and the curvature measures
/// fail. O(m p²) per fit, O(log m) fits for a tolerance.
pub fn rebuild(curve: &CadCurve, target: RebuildTarget, degree: usize) -> Result<(CadCurve, RebuildReport)> {
    let (points, parameters) = data(curve);
    if curve.kind == CurveKind::Function {
        let scale = crate::model::size(&points).max(f64::MIN_POSITIVE);
        if let Some(k) = points
            .iter()
            .zip(&parameters)
            .position(|(p, &t)| (p.x - t).abs() > 1e-12 * scale)
        {
            return Err(Error::Unsupported(format!(
                "a function is rebuilt over its abscissae, but point {k} has x = {} at parameter {}",
                points[k].x, parameters[k]
            )));
        }
    }
    let most = max_control_count(points.len(), degree);
    if let RebuildTarget::ControlPoints(n) = target {
        if n < degree + 1 || n > most {
            return Err(Error::BadParameter {
                name: "control-points",
                value: n.to_string(),
                reason: format!(
                    "between {} (degree + 1) and {most} for {} faired points (a least-squares fit needs two points per knot span); write the exact curve instead of a rebuild with more",
                    degree + 1,
                    points.len()
                ),
            });
        }
    }
    let faired = curvature_counts(&curve.curve, curve.dimension, curve.kind, &parameters)?;
    let (rebuilt, max_deviation, met) = fit(curve, &points, &parameters, degree, target)?;
    let fit_tolerance = match target {
        RebuildTarget::Tolerance(t) => Some(t),
        RebuildTarget::ControlPoints(_) => None,
    };
    if !met {
        let exact = deviation(curve.kind, &curve.curve, &points, &parameters);
        let report = RebuildReport {
            control_points: curve.curve.control_points().len(),
            degree: curve.curve.degree(),
            max_deviation: exact,
            fit_tolerance,
            exact_fallback: true,
            faired,
            rebuilt: faired,
            wiggles_back: false,
        };
        return Ok((curve.clone(), report));
    }
    let counts = curvature_counts(&rebuilt, curve.dimension, curve.kind, &parameters)?;
    let worse = |after: Option<usize>, before: Option<usize>| after.zip(before).is_some_and(|(a, b)| a > b);
    let report = RebuildReport {
        control_points: rebuilt.control_points().len(),
        degree,
        max_deviation,
        fit_tolerance,
        exact_fallback: false,
        faired,
        rebuilt: counts,
        wiggles_back: worse(counts.inflections, faired.inflections) || counts.vibrations > faired.vibrations,
    };
    let out = CadCurve {
        name: curve.name.clone(),
        curve: rebuilt,
        dimension: curve.dimension,
        kind: curve.kind,
        points: curve.points.clone(),
        parameters: curve.parameters.clone(),
    };
    Ok((out, report))
}
