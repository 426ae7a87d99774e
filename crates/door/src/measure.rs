//! Fairness measures of a curve or a surface, as docs/CONTRACT.md "Definitions" says, through the
//! `fairness` crate's `summary` module. Both `fair inspect` and the
//! report's `before`/`after` use them.
//!
//! - function kind: the spline function with parabolic runout, Han's x–c polyline;
//! - parametric kind: the natural cubic spline with chord-length parameters (2D or 3D);
//! - surface kind: the bicubic spline surface with chord-length averaged knots.
//!
//! Besides the report's numbers each measurement carries what the plot shows: the spline
//! sampled densely, its curvature comb, z per data point and the curvature plot (the x–c
//! polyline for the function kind, κ(t) for the parametric kind).
//!
//! Errors of the numerical crates become [`Error::Representation`] or [`Error::Invalid`]
//! (exit status 2) with the path [`POINTS`]; [`in_file`] puts the input's name there.

use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings, Curve, EndCondition, HermiteSpline};
use curve_repr::{SplineFunction, Vec2, Vec3, Vector};
use fairness::summary;
use fairness::{CurvatureForm, FairnessSummary, XcPolyline};

use fairing::catalog::{CurveKind, CurvePoints, Grid};

use crate::error::{Error, Result};
use crate::report::Measures;

/// The path that measurement errors carry until [`in_file`] names the input.
pub const POINTS: &str = "the points";

/// The most samples drawn along a curve (a few per interval, at least 2).
const MAX_SAMPLES: usize = 4000;

/// A curvature comb in the plane: points, unit normals and signed curvatures.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CombData {
    /// Points on the curve (usually densely sampled).
    pub points: Vec<[f64; 2]>,
    /// Unit normals there.
    pub normals: Vec<[f64; 2]>,
    /// Signed curvature there.
    pub curvature: Vec<f64>,
}

/// A curvature plot: a line and the values at the data points (Han's x–c polyline for a
/// function, κ over the chord-length parameter for a parametric curve).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CurvaturePlot {
    /// Panel title.
    pub title: String,
    /// The abscissa's name (`x`, or `t` the chord-length parameter).
    pub x_label: String,
    /// The ordinate's name (`c = y''/6`, or `κ`).
    pub y_label: String,
    /// The plotted line.
    pub line: Vec<[f64; 2]>,
    /// The values at the data points.
    pub knots: Vec<[f64; 2]>,
}

/// What measuring a curve gives: the report's numbers and what the plot can show.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CurveMeasurement {
    /// The report's measures.
    pub measures: Measures,
    /// The spline through the points, as the report's `curve` value.
    pub curve: serde_json::Value,
    /// The spline sampled densely, for the plot (in the plot's plane: (x, z) for 3D points).
    pub samples: Option<Vec<[f64; 2]>>,
    /// Its curvature comb.
    pub comb: Option<CombData>,
    /// z_i per data point (0 at the two ends, where no jump is defined).
    pub z: Option<Vec<f64>>,
    /// The curvature plot.
    pub curvature: Option<CurvaturePlot>,
}

/// What measuring a surface gives.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SurfaceMeasurement {
    /// The report's measures.
    pub measures: Measures,
    /// The surface, as the report's `curve` value.
    pub surface: serde_json::Value,
    /// z_ij over the grid (rows i, columns j; 0 on the border, where Eq. 26 is not defined).
    pub z: Option<Vec<Vec<f64>>>,
}

/// Puts `file` in place of [`POINTS`] in a measurement error, so that the message names the
/// input; other errors are returned unchanged.
pub fn in_file(error: Error, file: &str) -> Error {
    match error {
        Error::Representation { path, source } if path == POINTS => Error::Representation {
            path: file.to_string(),
            source,
        },
        Error::Invalid { path, message } if path == POINTS => Error::Invalid {
            path: file.to_string(),
            message,
        },
        other => other,
    }
}

fn from_fairness(error: fairness::Error) -> Error {
    match error {
        fairness::Error::Curve(source) => Error::Representation {
            path: POINTS.into(),
            source,
        },
        other => Error::Invalid {
            path: POINTS.into(),
            message: other.to_string(),
        },
    }
}

fn from_curve_repr(source: curve_repr::Error) -> Error {
    Error::Representation {
        path: POINTS.into(),
        source,
    }
}

/// The report's measures of a summary: energies (and their accuracy) only where they were
/// measured (curves whose integrands are finite).
fn measures(summary: &FairnessSummary, with_energies: bool) -> Measures {
    let accuracy = summary.energy_accuracy.filter(|_| with_energies);
    Measures {
        inflections: summary.inflections,
        vibrations: summary.vibrations,
        e_s: summary.e_s,
        max_z: summary.max_z,
        energies: accuracy.map(|_| summary.energies),
        energy_accuracy: accuracy,
        criteria: Default::default(),
    }
}

/// Sample parameters: `per` points per interval of `breaks`, the last break included.
fn sample_parameters(breaks: &[f64]) -> Vec<(usize, f64)> {
    let intervals = breaks.len().saturating_sub(1).max(1);
    let per = (MAX_SAMPLES / intervals).clamp(2, 16);
    let mut t: Vec<(usize, f64)> = Vec::with_capacity(per * intervals + 1);
    t.extend(
        breaks
            .windows(2)
            .enumerate()
            .flat_map(|(i, w)| (0..per).map(move |k| (i, w[0] + (w[1] - w[0]) * k as f64 / per as f64))),
    );
    t.extend(breaks.len().checked_sub(2).map(|i| (i, breaks[i + 1])));
    t
}

/// z per data point from the interior jumps: 0 at both ends.
fn padded(interior: impl IntoIterator<Item = f64>) -> Vec<f64> {
    let mut z = vec![0.0];
    z.extend(interior);
    z.push(0.0);
    z
}

/// Measures a curve of the given kind (docs/CONTRACT.md "Definitions"), with what a plot shows.
/// O(n).
pub fn curve(kind: CurveKind, points: &CurvePoints) -> Result<CurveMeasurement> {
    curve_with(kind, points, Detail::ALL)
}

/// What of a [`CurveMeasurement`] besides the measures and z to make.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Detail {
    /// The plot's samples, comb and curvature line (`samples`, `comb`, `curvature`).
    pub plot: bool,
    /// The report's `curve` record (else `Value::Null`).
    pub record: bool,
}

impl Detail {
    /// Everything.
    pub const ALL: Detail = Detail {
        plot: true,
        record: true,
    };
}

/// [`curve`], with the plot's samples, comb and curvature line only when `detail.plot` is set
/// (`samples`, `comb` and `curvature` are `None` otherwise) and the `curve` record only when
/// `detail.record` is (else `Value::Null`): at 10⁶ points they are two million evaluations
/// and a few hundred MB that only a picture or a written report needs. The measures and z
/// are the same either way. O(n).
pub fn curve_with(kind: CurveKind, points: &CurvePoints, detail: Detail) -> Result<CurveMeasurement> {
    match (kind, points) {
        (CurveKind::Function, CurvePoints::Planar(p)) => function(p, detail),
        (CurveKind::Function, CurvePoints::Spatial(_)) => Err(Error::Invalid {
            path: POINTS.into(),
            message: "the function kind needs planar points x,y".into(),
        }),
        (CurveKind::Parametric, CurvePoints::Planar(p)) => {
            parametric(p, |v| [v.x, v.y], planar_normal, detail)
        }
        (CurveKind::Parametric, CurvePoints::Spatial(p)) => {
            parametric(p, |v| [v.x, v.z], spatial_normal, detail)
        }
    }
}

/// The function kind: the runout spline function y(x), its x–c polyline.
fn function(points: &[Vec2], detail: Detail) -> Result<CurveMeasurement> {
    let x: Vec<f64> = points.iter().map(|p| p.x).collect();
    let y: Vec<f64> = points.iter().map(|p| p.y).collect();
    let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).map_err(from_curve_repr)?;
    // The record and the plot's samples are made while the summary's quadrature runs on
    // rayon's threads.
    let (summary, drawn) = rayon::join(
        || summary::function_of(&spline).map_err(from_fairness),
        || function_drawing(&spline, x, y, detail),
    );
    // The summary's error first, as when the two ran one after the other.
    let summary = summary?;
    let mut measurement = drawn?;
    measurement.measures = measures(&summary, true);
    Ok(measurement)
}

/// Everything of a function's [`CurveMeasurement`] but the measures: z, and as `detail` says
/// the `curve` record and the samples, comb and x–c plot. O(n).
fn function_drawing(
    spline: &SplineFunction,
    x: Vec<f64>,
    y: Vec<f64>,
    detail: Detail,
) -> Result<CurveMeasurement> {
    let xc = XcPolyline::of_spline(spline).map_err(from_fairness)?;
    let mut measurement = CurveMeasurement {
        z: Some(padded(xc.e.iter().map(|e| 6.0 * e.abs()))),
        ..CurveMeasurement::default()
    };
    if detail.plot {
        let mut samples = Vec::new();
        let mut comb = CombData::default();
        for (piece, t) in sample_parameters(&x) {
            let [value, slope, second, _] = spline.jet_in(piece, t);
            let speed = (1.0 + slope * slope).sqrt();
            let kappa = second / (speed * speed * speed);
            if value.is_finite() && kappa.is_finite() && speed.is_finite() {
                samples.push([t, value]);
                comb.points.push([t, value]);
                comb.normals.push([-slope / speed, 1.0 / speed]);
                comb.curvature.push(kappa);
            }
        }
        let line: Vec<[f64; 2]> = x.iter().zip(&xc.c).map(|(x, c)| [*x, *c]).collect();
        measurement.samples = Some(samples);
        measurement.comb = Some(comb);
        measurement.curvature = Some(CurvaturePlot {
            title: "x–c polyline (c = y''/6)".into(),
            x_label: "x".into(),
            y_label: "c".into(),
            knots: line.clone(),
            line,
        });
    }
    if detail.record {
        measurement.curve = serde_json::json!({
            "type": "spline-function",
            "end_condition": "parabolic-runout",
            "x": x,
            "y": y,
            "c": xc.c,
        });
    }
    Ok(measurement)
}

/// The unit left normal of a planar curve from its first derivative.
fn planar_normal(jet: &[Vec2; 4]) -> Option<[f64; 2]> {
    let d = jet[1];
    let norm = d.norm();
    (norm > 0.0 && norm.is_finite()).then(|| [-d.y / norm, d.x / norm])
}

/// The principal normal of a spatial curve seen in the (x, z) plane, unit length there.
fn spatial_normal(jet: &[Vec3; 4]) -> Option<[f64; 2]> {
    let (d1, d2) = (jet[1], jet[2]);
    let speed2 = d1.norm_squared();
    if !(speed2 > 0.0 && speed2.is_finite()) {
        return None;
    }
    let normal = d2 - d1 * (d2.dot(&d1) / speed2);
    let projected = [normal.x, normal.z];
    let norm = projected[0].hypot(projected[1]);
    (norm > 1e-12 * normal.norm() && norm > 0.0).then(|| [projected[0] / norm, projected[1] / norm])
}

/// The parametric kind: the natural chord-length spline.
fn parametric<const D: usize>(
    points: &[Vector<D>],
    project: fn(&Vector<D>) -> [f64; 2],
    normal: fn(&[Vector<D>; 4]) -> Option<[f64; 2]>,
    detail: Detail,
) -> Result<CurveMeasurement>
where
    Vector<D>: CurvatureForm,
{
    let spline = HermiteSpline::natural(points).map_err(from_curve_repr)?;
    let (summary, drawn) = rayon::join(
        || summary::parametric_of(&spline).map_err(from_fairness),
        || parametric_drawing(&spline, points, project, normal, detail),
    );
    // The summary's error first, as when the two ran one after the other.
    let summary = summary?;
    let mut measurement = drawn?;
    measurement.measures = measures(&summary, true);
    Ok(measurement)
}

/// Everything of a parametric curve's [`CurveMeasurement`] but the measures (see
/// [`function_drawing`]). O(n).
fn parametric_drawing<const D: usize>(
    spline: &HermiteSpline<D>,
    points: &[Vector<D>],
    project: fn(&Vector<D>) -> [f64; 2],
    normal: fn(&[Vector<D>; 4]) -> Option<[f64; 2]>,
    detail: Detail,
) -> Result<CurveMeasurement>
where
    Vector<D>: CurvatureForm,
{
    let breaks = spline.breaks();
    let jumps = fairness::jumps::third_derivative_jumps(spline).map_err(from_fairness)?;
    let mut measurement = CurveMeasurement {
        z: Some(padded(jumps)),
        ..CurveMeasurement::default()
    };
    if detail.plot {
        let kappa = fairness::curvature::curvature_at_breaks(spline).map_err(from_fairness)?;
        let (samples, comb, curvature) = parametric_samples(spline, &breaks, &kappa, project, normal);
        measurement.samples = Some(samples);
        measurement.comb = Some(comb);
        measurement.curvature = Some(curvature);
    }
    if detail.record {
        let rows: Vec<Vec<f64>> = points.iter().map(|p| p.iter().copied().collect()).collect();
        let tangents: Vec<Vec<f64>> = spline
            .tangents()
            .iter()
            .map(|p| p.iter().copied().collect())
            .collect();
        measurement.curve = serde_json::json!({
            "type": "hermite",
            "ends": "natural",
            "parametrization": "chord-length",
            "params": breaks,
            "points": rows,
            "tangents": tangents,
        });
    }
    Ok(measurement)
}

/// A parametric curve's plot samples, comb and curvature line.
fn parametric_samples<const D: usize>(
    spline: &HermiteSpline<D>,
    breaks: &[f64],
    kappa: &[f64],
    project: fn(&Vector<D>) -> [f64; 2],
    normal: fn(&[Vector<D>; 4]) -> Option<[f64; 2]>,
) -> (Vec<[f64; 2]>, CombData, CurvaturePlot)
where
    Vector<D>: CurvatureForm,
{
    let mut samples = Vec::new();
    let mut comb = CombData::default();
    let mut kappa_line = Vec::new();
    for (piece, t) in sample_parameters(breaks) {
        let jet = spline.jet_on_piece(piece, t);
        let point = project(&jet[0]);
        if !(point[0].is_finite() && point[1].is_finite()) {
            continue;
        }
        samples.push(point);
        if let Some(k) = CurvatureForm::curvature(&jet[1], &jet[2]).filter(|k| k.is_finite()) {
            kappa_line.push([t, k]);
            if let Some(n) = normal(&jet) {
                comb.points.push(point);
                comb.normals.push(n);
                comb.curvature.push(k);
            }
        }
    }
    let curvature = CurvaturePlot {
        title: "curvature κ(t), t chord length".into(),
        x_label: "t".into(),
        y_label: "κ".into(),
        line: kappa_line,
        knots: breaks.iter().zip(kappa).map(|(t, k)| [*t, *k]).collect(),
    };
    (samples, comb, curvature)
}

/// Measures a surface grid (docs/CONTRACT.md "Definitions", surface kind). O(m·n).
pub fn surface(grid: &Grid) -> Result<SurfaceMeasurement> {
    let surface = BicubicSplineSurface::from_flat(
        grid.points.clone(),
        grid.rows,
        grid.columns,
        &BicubicSurfaceSettings::default(),
    )
    .map_err(from_curve_repr)?;
    let summary = summary::surface_of(&surface).map_err(from_fairness)?;
    let z: Vec<Vec<f64>> = (0..grid.rows)
        .map(|i| {
            (0..grid.columns)
                .map(|j| surface.z(i, j).unwrap_or(0.0))
                .collect()
        })
        .collect();
    let points: Vec<[f64; 3]> = grid.points.iter().map(|p| [p.x, p.y, p.z]).collect();
    let record = serde_json::json!({
        "type": "bicubic",
        "parametrization": "chord-length-averaged",
        "rows": grid.rows,
        "columns": grid.columns,
        "u_knots": surface.u_knots(),
        "v_knots": surface.v_knots(),
        "points": points,
    });
    Ok(SurfaceMeasurement {
        measures: measures(&summary, false),
        surface: record,
        z: Some(z),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn function_and_parametric_measures_are_finite() {
        let points = CurvePoints::Planar(
            (0..12)
                .map(|i| Vec2::new(i as f64 * 0.3, (i as f64 * 0.7).sin()))
                .collect(),
        );
        for kind in [CurveKind::Function, CurveKind::Parametric] {
            let m = curve(kind, &points).unwrap();
            assert!(m.measures.e_s.is_finite() && m.measures.e_s > 0.0);
            assert!(m.measures.inflections.is_some() && m.measures.energies.is_some());
            assert_eq!(m.z.as_ref().unwrap().len(), 12);
            let comb = m.comb.unwrap();
            assert_eq!(comb.points.len(), comb.curvature.len());
            assert!(!comb.points.is_empty());
        }
    }

    #[test]
    fn measuring_without_a_plot_gives_the_same_measures_and_record() {
        let planar: Vec<Vec2> = (0..30)
            .map(|i| Vec2::new(i as f64 * 0.2, (i as f64 * 0.5).sin()))
            .collect();
        let spatial: Vec<Vec3> = (0..30)
            .map(|i| {
                let t = i as f64 * 0.3;
                Vec3::new(t.cos(), t.sin(), 0.2 * t)
            })
            .collect();
        for (kind, points) in [
            (CurveKind::Function, CurvePoints::Planar(planar.clone())),
            (CurveKind::Parametric, CurvePoints::Planar(planar)),
            (CurveKind::Parametric, CurvePoints::Spatial(spatial)),
        ] {
            let full = curve(kind, &points).unwrap();
            let drawn = curve_with(
                kind,
                &points,
                Detail {
                    plot: true,
                    record: false,
                },
            )
            .unwrap();
            assert_eq!(drawn.curve, serde_json::Value::Null);
            assert_eq!(
                (drawn.samples.as_ref(), drawn.comb.as_ref()),
                (full.samples.as_ref(), full.comb.as_ref())
            );
            let bare = curve_with(
                kind,
                &points,
                Detail {
                    plot: false,
                    record: true,
                },
            )
            .unwrap();
            assert_eq!(bare.measures, full.measures);
            assert_eq!(bare.curve, full.curve);
            assert_eq!(bare.z, full.z);
            assert!(bare.samples.is_none() && bare.comb.is_none() && bare.curvature.is_none());
            assert!(full.samples.is_some() && full.comb.is_some() && full.curvature.is_some());
        }
    }

    #[test]
    fn repeated_points_name_the_file() {
        let points = CurvePoints::Planar(vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 1.0),
        ]);
        let e = curve(CurveKind::Parametric, &points).unwrap_err();
        let e = in_file(e, "bad.csv");
        assert_eq!(e.exit_code(), 2);
        assert!(e.one_line().starts_with("bad.csv: "), "{}", e.one_line());
    }

    #[test]
    fn spatial_curve_has_no_inflections() {
        let points = CurvePoints::Spatial(
            (0..10)
                .map(|i| {
                    let t = i as f64 * 0.5;
                    Vec3::new(t.cos(), t.sin(), 0.3 * t)
                })
                .collect(),
        );
        let m = curve(CurveKind::Parametric, &points).unwrap();
        assert_eq!(m.measures.inflections, None);
        assert!(m.measures.vibrations.is_some());
    }
}
