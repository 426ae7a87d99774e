//! The faired result as a CAD file (`-o FILE.igs|.step|.dxf`, `--cad FORMAT` in the command): the method's
//! own representation converted exactly by `fair-cad`, or a least-squares rebuild of it
//! (`--control-points`, `--fit-tolerance`).
//!
//! Which curve is written: the report's `curve` record, read back as the curve it describes
//! (a NURBS of `nurbs-weights` and `sapidis-farin`, the Hermite spline of `strain-energy`,
//! Okada's Ferguson chain of `batten`, the natural spline of `smoothing-spline`, the spline
//! function or interpolating cubic of `two-phase`), provided the faired points lie on it to
//! 1e-9 of their size; otherwise (a record of another kind, or none) the interpolating spline
//! of the faired points that the report measures, which is exact for what `fair` measures. A
//! surface is the bicubic spline surface on the record's knots. The report's `cad` object
//! says which (`representation`), with the deviation and the curvature counts of what was
//! written.

use cad::{CadCurve, CadSettings, CadSurface, Format, Shape, WriteOptions};
use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings, CubicPieces, NurbsCurve, Vec3, Vector};
use serde_json::{json, Value};

use fairing::catalog::{CurveKind, CurvePoints, Grid};

use crate::error::{Error, Result};

/// Relative accuracy (of the points' size) to which the faired points must lie on the
/// method's own curve for it to be written; the conversions are exact up to rounding.
pub const ON_CURVE: f64 = 1e-9;

/// What to write as CAD: the format, the file (`-` for standard output) and the export
/// settings. Made by [`target`], which checks them.
#[derive(Debug, Clone, PartialEq)]
pub struct CadTarget {
    /// The format: asked for, else the file's extension.
    pub format: Format,
    /// The file.
    pub path: String,
    /// Rebuild and header settings.
    pub settings: CadSettings,
}

/// What a front end was asked to write (the command's `-o`, `--cad`, `--control-points`,
/// `--fit-tolerance`), before [`target`] checks it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CadRequest {
    /// The output file (`-o`).
    pub output: Option<String>,
    /// The format asked for (`--cad`); `None`: by the output's extension.
    pub format: Option<Format>,
    /// Rebuild with this many control points.
    pub control_points: Option<usize>,
    /// Rebuild to this largest deviation.
    pub fit_tolerance: Option<f64>,
    /// The length unit the file declares (`--cad-units`; the coordinates are written as
    /// they are, in this unit); `None`: millimetres.
    pub units: Option<cad::Units>,
    /// The STEP application protocol (`--step-schema`); `None`: AP214.
    pub step_schema: Option<cad::StepSchema>,
    /// The run is a batch of curves (which writes points, never CAD).
    pub batch: bool,
}

impl CadRequest {
    /// The CAD format asked for, if any: [`format`](Self::format), else the output's
    /// extension.
    pub fn format_of(&self) -> Option<Format> {
        self.format
            .or_else(|| self.output.as_deref().and_then(Format::from_path))
    }
}

/// Checks a CAD request (before anything runs) and returns what to write, or `None` for no
/// CAD output. Refused, exit status 2 naming the option: `--control-points` or
/// `--fit-tolerance` without a CAD output, `--cad` without `-o`, `--cad` against a CAD
/// extension of another format, a batch, DXF or a rebuild for a surface, and settings the
/// library refuses (both rebuild options, fewer than 4 control points).
pub fn target(request: &CadRequest, surface: bool) -> Result<Option<CadTarget>> {
    let rebuild_option = match (request.control_points, request.fit_tolerance) {
        (Some(_), _) => Some("--control-points"),
        (None, Some(_)) => Some("--fit-tolerance"),
        (None, None) => None,
    };
    let Some(format) = request.format_of() else {
        return match rebuild_option {
            Some(option) => Err(Error::Argument {
                option,
                message: "rebuilds the curve written to a CAD file: give -o FILE.igs|.step|.dxf or --cad FORMAT with -o".into(),
            }),
            None if request.units.is_some() => Err(Error::Argument {
                option: "--cad-units",
                message: "is the unit a CAD file declares: give -o FILE.igs|.step|.dxf or --cad FORMAT with -o".into(),
            }),
            None if request.step_schema.is_some() => Err(Error::Argument {
                option: "--step-schema",
                message: "applies to a STEP file: give -o FILE.step".into(),
            }),
            None => Ok(None),
        };
    };
    if request.step_schema.is_some() && format != Format::Step {
        return Err(Error::Argument {
            option: "--step-schema",
            message: format!("applies to STEP files; this writes {format}"),
        });
    }
    let option = if request.format.is_some() { "--cad" } else { "-o" };
    let Some(path) = request.output.clone() else {
        return Err(Error::Argument {
            option: "--cad",
            message: format!(
                "writes the {format} file that -o names (-o - for standard output); no -o given"
            ),
        });
    };
    if let (Some(asked), Some(named)) = (request.format, Format::from_path(&path)) {
        if asked != named {
            return Err(Error::Argument {
                option: "--cad",
                message: format!(
                    "`{asked}`, but -o `{path}` is a {named} file by its extension; give one format"
                ),
            });
        }
    }
    if request.batch {
        return Err(Error::Argument {
            option,
            message: "a batch writes points; CAD files are written for one curve at a time (fair curve FILE -o OUT.igs)".into(),
        });
    }
    if surface {
        if format == Format::Dxf {
            return Err(Error::Argument {
                option,
                message: "DXF has no exact B-spline surface; write the surface as .igs or .step".into(),
            });
        }
        if let Some(option) = rebuild_option {
            return Err(Error::Argument {
                option,
                message: "rebuilds curves; a surface is written exactly".into(),
            });
        }
    }
    let defaults = CadSettings::default();
    let settings = CadSettings {
        control_points: request.control_points,
        fit_tolerance: request.fit_tolerance,
        units: request.units.unwrap_or(defaults.units),
        step_schema: request.step_schema.unwrap_or(defaults.step_schema),
        ..defaults
    };
    settings
        .validate()
        .map_err(|e| cad_error(e, option, rebuild_option))?;
    Ok(Some(CadTarget {
        format,
        path,
        settings,
    }))
}

/// A name for the shape in a CAD file: the input file's stem (`curve` for standard input).
pub fn stem(source: &str) -> String {
    match std::path::Path::new(source).file_stem().and_then(|s| s.to_str()) {
        Some(s) if source != "-" && !s.is_empty() => s.to_string(),
        _ => "curve".to_string(),
    }
}

/// A `fair-cad` error as the command's: a refused parameter names its option (exit status 2),
/// anything else is internal.
fn cad_error(error: cad::Error, format_option: &'static str, rebuild_option: Option<&'static str>) -> Error {
    match &error {
        cad::Error::BadParameter { name, .. } => Error::Argument {
            option: match *name {
                "control-points" => "--control-points",
                "fit-tolerance" => "--fit-tolerance",
                _ => rebuild_option.unwrap_or(format_option),
            },
            message: error.to_string(),
        },
        cad::Error::Unsupported(_) | cad::Error::UnknownFormat(_) => Error::Argument {
            option: rebuild_option.unwrap_or(format_option),
            message: error.to_string(),
        },
        cad::Error::Io { path, message } => Error::Write {
            path: path.clone(),
            reason: message.clone(),
        },
        _ => match rebuild_option {
            Some(option) => Error::Argument {
                option,
                message: error.to_string(),
            },
            None => Error::Internal {
                message: format!("CAD export: {error}"),
            },
        },
    }
}

/// A CAD file made: its text and the report's `cad` object.
#[derive(Debug, Clone, PartialEq)]
pub struct CadOutput {
    /// The file's text (IGES, STEP and DXF are ASCII).
    pub text: String,
    /// The report's `cad` object.
    pub summary: Value,
}

fn f64s(value: &Value) -> Option<Vec<f64>> {
    value.as_array()?.iter().map(Value::as_f64).collect()
}

fn vectors<const D: usize>(value: &Value) -> Option<Vec<Vector<D>>> {
    value
        .as_array()?
        .iter()
        .map(|row| {
            let row = f64s(row)?;
            (row.len() == D).then(|| Vector::<D>::from_iterator(row))
        })
        .collect()
}

/// Cumulative chord length of `points`, from 0.
fn chord_breaks<const D: usize>(points: &[Vector<D>]) -> Vec<f64> {
    let mut breaks = Vec::with_capacity(points.len());
    let mut total = 0.0;
    breaks.push(0.0);
    for w in points.windows(2) {
        total += (w[1] - w[0]).norm();
        breaks.push(total);
    }
    breaks
}

/// The natural cubic spline of values y_i and second derivatives M_i at knots t_i, as
/// tangents for the Hermite form: S'(t_i) = Δy/h − h(2M_i + M_{i+1})/6 on the right of each
/// knot, Δy/h + h(M_{i−1} + 2M_i)/6 at the last. Exact: the cubic on each span is fixed by
/// its end values and second derivatives.
fn natural_tangents<const D: usize>(t: &[f64], y: &[Vector<D>], m: &[Vector<D>]) -> Option<Vec<Vector<D>>> {
    let n = t.len();
    if n < 2 || y.len() != n || m.len() != n {
        return None;
    }
    let mut tangents: Vec<Vector<D>> = (0..n - 1)
        .map(|i| {
            let h = t[i + 1] - t[i];
            (y[i + 1] - y[i]) / h - (m[i] * 2.0 + m[i + 1]) * (h / 6.0)
        })
        .collect();
    let h = t[n - 1] - t[n - 2];
    tangents.push((y[n - 1] - y[n - 2]) / h + (m[n - 2] + m[n - 1] * 2.0) * (h / 6.0));
    Some(tangents)
}

/// The curve the report's `curve` record describes, through the faired `points`; `None`
/// when the record is of another kind or does not fit the points.
fn method_curve<const D: usize>(record: &Value, points: &[Vector<D>]) -> Option<CadCurve> {
    let by_x = record.get("parametrization").and_then(Value::as_str) == Some("x");
    let as_function = |c: CadCurve| if by_x { c.with_kind(CurveKind::Function) } else { c };
    match record.get("type")?.as_str()? {
        "nurbs" => {
            let degree = usize::try_from(record.get("degree")?.as_u64()?).ok()?;
            let curve = NurbsCurve::<D>::new(
                degree,
                f64s(record.get("knots")?)?,
                vectors::<D>(record.get("control_points")?)?,
                f64s(record.get("weights")?)?,
            )
            .ok()?;
            let params = f64s(record.get("params")?)?;
            CadCurve::from_nurbs(&curve, points, &params)
                .ok()
                .map(as_function)
        }
        "hermite" => {
            let knots = f64s(record.get("knots").or_else(|| record.get("params"))?)?;
            let nodes = vectors::<D>(record.get("points")?)?;
            let tangents = vectors::<D>(record.get("tangents")?)?;
            let pieces = CubicPieces::from_hermite(&knots, &nodes, &tangents).ok()?;
            let parameters = knots.get(..points.len())?;
            CadCurve::from_pieces(&pieces, points, parameters).ok()
        }
        "natural-cubic-spline" => {
            let knots = f64s(record.get("knots")?)?;
            let values = vectors::<D>(record.get("values")?)?;
            let second = vectors::<D>(record.get("second_derivatives")?)?;
            let tangents = natural_tangents(&knots, &values, &second)?;
            let pieces = CubicPieces::from_hermite(&knots, &values, &tangents).ok()?;
            CadCurve::from_pieces(&pieces, points, &knots)
                .ok()
                .map(as_function)
        }
        "ferguson" => {
            let segments: Vec<[Vector<D>; 4]> = record
                .get("segments")?
                .as_array()?
                .iter()
                .map(|s| vectors::<D>(s)?.try_into().ok())
                .collect::<Option<_>>()?;
            let breaks = chord_breaks(points);
            let pieces = CubicPieces::from_unit_power(&breaks, &segments).ok()?;
            CadCurve::from_pieces(&pieces, points, &breaks).ok()
        }
        // Both are the spline the report measures, built below.
        _ => None,
    }
}

/// The spline the report measures through the faired points.
fn measured_curve<const D: usize>(points: &[Vector<D>], kind: CurveKind) -> Result<CadCurve> {
    let curve = match kind {
        CurveKind::Function => {
            let x: Vec<f64> = points.iter().map(|p| p[0]).collect();
            let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
            CadCurve::measured_function(&x, &y)
        }
        CurveKind::Parametric => CadCurve::measured_parametric(points),
    };
    curve.map_err(|e| Error::Internal {
        message: format!("CAD export: the measured spline: {e}"),
    })
}

/// The largest distance of the curve's data points from the curve at their parameters
/// (vertical |Δy| for a function, as the rebuild measures it).
fn deviation(curve: &CadCurve) -> f64 {
    curve
        .points
        .iter()
        .zip(&curve.parameters)
        .map(|(q, &t)| {
            let p = curve.curve.point(t);
            match curve.kind {
                CurveKind::Function => (q.y - p.y).abs(),
                CurveKind::Parametric => (q - p).norm(),
            }
        })
        .fold(0.0, f64::max)
}

/// The exact faired curve: the method's own when the record gives one the faired points lie
/// on, else the measured spline; with the name of what it is.
pub fn faired_curve(record: &Value, faired: &CurvePoints, kind: CurveKind) -> Result<(CadCurve, String)> {
    fn pick<const D: usize>(
        record: &Value,
        points: &[Vector<D>],
        kind: CurveKind,
    ) -> Result<(CadCurve, String)> {
        let lifted: Vec<Vec3> = points
            .iter()
            .map(|p| Vec3::from_fn(|i, _| if i < D { p[i] } else { 0.0 }))
            .collect();
        let scale = cad::model::size(&lifted).max(f64::MIN_POSITIVE);
        let own = method_curve(record, points).filter(|c| {
            c.points.len() == points.len()
                && deviation(&c.clone().with_kind(CurveKind::Parametric)) <= ON_CURVE * scale
        });
        let name = record.get("type").and_then(Value::as_str).unwrap_or("");
        match own {
            Some(curve) => Ok((curve, name.to_string())),
            None => {
                let spline = measured_curve(points, kind)?;
                let what = match (name, kind) {
                    ("spline-function" | "interpolating-cubic", _) => name.to_string(),
                    (_, CurveKind::Function) => "measured-spline-function".to_string(),
                    (_, CurveKind::Parametric) => "measured-natural-cubic".to_string(),
                };
                Ok((spline, what))
            }
        }
    }
    match faired {
        CurvePoints::Planar(p) => pick(record, p, kind),
        CurvePoints::Spatial(p) => pick(record, p, kind),
    }
}

/// The exact faired surface: the bicubic spline surface on the record's knots when the grid
/// lies on it, else on chord-length averaged knots (the surface the report measures).
pub fn faired_surface(record: &Value, grid: &Grid) -> Result<(CadSurface, String)> {
    let rows: Vec<Vec<Vec3>> = grid.points.chunks(grid.columns).map(<[Vec3]>::to_vec).collect();
    let own = (|| {
        if record.get("type")?.as_str()? != "bicubic" {
            return None;
        }
        let settings = BicubicSurfaceSettings::default()
            .with_u_knots(f64s(record.get("u_knots")?)?)
            .with_v_knots(f64s(record.get("v_knots")?)?);
        let surface = BicubicSplineSurface::with_settings(&rows, &settings).ok()?;
        CadSurface::from_bicubic(&surface).ok()
    })();
    let scale = cad::model::size(&grid.points).max(f64::MIN_POSITIVE);
    let on_surface = |s: &CadSurface| {
        s.u_parameters.iter().enumerate().all(|(i, &u)| {
            s.v_parameters
                .iter()
                .enumerate()
                .all(|(j, &v)| (s.point_at(u, v) - rows[i][j]).norm() <= ON_CURVE * scale)
        })
    };
    match own.filter(on_surface) {
        Some(surface) => Ok((surface, "bicubic".into())),
        None => CadSurface::measured(&rows)
            .map(|s| (s, "measured-bicubic".into()))
            .map_err(|e| Error::Internal {
                message: format!("CAD export: the measured surface: {e}"),
            }),
    }
}

/// The header options for `target`'s file (its name recorded inside, its STEP schema).
fn options(target: &CadTarget) -> WriteOptions {
    let path = target.path.as_str();
    let file_name = if path == "-" {
        String::new()
    } else {
        std::path::Path::new(path)
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default()
            .to_string()
    };
    WriteOptions {
        file_name,
        step_schema: target.settings.step_schema,
        ..WriteOptions::default()
    }
}

fn counts(c: &cad::CurvatureCounts) -> Value {
    json!({ "inflections": c.inflections, "vibrations": c.vibrations })
}

/// Writes the faired curve as `target` asks: the exact curve ([`faired_curve`]) or its
/// rebuild. The `cad` object: `format`, `file`, `units`, `tolerance` (written into the
/// file), `representation` (which curve), `exact` (the file holds the faired curve itself),
/// `degree`, `control_points`, `max_deviation` (largest distance of a faired point from the
/// written curve at its parameter, |Δy| for a function), `fit_tolerance`, `exact_fallback`,
/// `faired` and `written` curvature counts at the faired points' parameters, `wiggles_back`.
pub fn export_curve(
    target: &CadTarget,
    record: &Value,
    faired: &CurvePoints,
    kind: CurveKind,
    name: &str,
) -> Result<CadOutput> {
    let rebuild_option = match (target.settings.control_points, target.settings.fit_tolerance) {
        (Some(_), _) => Some("--control-points"),
        (None, Some(_)) => Some("--fit-tolerance"),
        _ => None,
    };
    let (curve, representation) = faired_curve(record, faired, kind)?;
    let curve = curve.with_name(name);
    let options = options(target);
    let export = cad::export(
        &Shape::Curve(curve.clone()),
        target.format,
        &target.settings,
        &options,
    )
    .map_err(|e| cad_error(e, "-o", rebuild_option))?;
    let written = export.model.curves.first().ok_or_else(|| Error::Internal {
        message: "CAD export wrote no curve".into(),
    })?;
    let (faired_counts, written_counts, max_deviation, exact, fallback, wiggles) = match &export.rebuild {
        Some(r) => (
            r.faired,
            r.rebuilt,
            r.max_deviation,
            r.exact_fallback,
            r.exact_fallback,
            r.wiggles_back,
        ),
        None => {
            let c =
                cad::rebuild::curvature_counts(&curve.curve, curve.dimension, curve.kind, &curve.parameters)
                    .map_err(|e| Error::Internal {
                        message: format!("CAD export: curvature counts: {e}"),
                    })?;
            (c, c, deviation(&curve), true, false, false)
        }
    };
    let summary = json!({
        "format": target.format,
        "file": target.path,
        "units": export.model.units,
        "tolerance": export.model.tolerance,
        "representation": representation,
        "exact": exact,
        "degree": written.curve.degree(),
        "control_points": written.curve.control_points().len(),
        "max_deviation": max_deviation,
        "fit_tolerance": target.settings.fit_tolerance,
        "exact_fallback": fallback,
        "faired": counts(&faired_counts),
        "written": counts(&written_counts),
        "wiggles_back": wiggles,
    });
    Ok(CadOutput {
        text: export.text,
        summary,
    })
}

/// Writes the faired surface as `target` asks (exactly). The `cad` object as for a curve,
/// `control_points` counting the net (rows × columns), `max_deviation` the grid's from the
/// surface at its parameters, no counts.
pub fn export_surface(target: &CadTarget, record: &Value, grid: &Grid, name: &str) -> Result<CadOutput> {
    let (surface, representation) = faired_surface(record, grid)?;
    let surface = surface.with_name(name);
    let max_deviation = surface
        .u_parameters
        .iter()
        .enumerate()
        .flat_map(|(i, &u)| {
            let surface = &surface;
            surface.v_parameters.iter().enumerate().map(move |(j, &v)| {
                (surface.point_at(u, v) - surface.points[i * surface.v_parameters.len() + j]).norm()
            })
        })
        .fold(0.0, f64::max);
    let options = options(target);
    let export = cad::export(
        &Shape::Surface(surface),
        target.format,
        &target.settings,
        &options,
    )
    .map_err(|e| cad_error(e, "-o", None))?;
    let summary = export.summary();
    let net = export.model.surfaces.first().map(|s| s.surface.net_size());
    Ok(CadOutput {
        text: export.text,
        summary: json!({
            "format": target.format,
            "file": target.path,
            "units": export.model.units,
            "tolerance": export.model.tolerance,
            "representation": representation,
            "exact": true,
            "degree": summary.degree,
            "control_points": summary.control_points,
            "net": net.map(|(r, c)| [r, c]),
            "max_deviation": max_deviation,
        }),
    })
}

/// Samples the first surface of the IGES or STEP file `path` into a net that meets edge
/// `edge` of `grid` (a `--join` neighbour given as a CAD surface).
///
/// The CAD surface's boundary curve nearest to the edge's nodes is found (each of the four
/// sampled at 256 parameters); each edge node is projected onto it (the nearest sample, then
/// golden section between its neighbours), and the net's first row is the curve at those
/// parameters, so it passes through the points of the CAD edge nearest to ours. Its other
/// rows run at as many parameters, evenly spaced across the CAD surface, as `grid` has lines
/// across the edge. The join is then held to this net's bicubic surface, which follows the
/// CAD surface to its sampling. O(k · 256 + k · r) evaluations for k edge nodes and r rows.
///
/// Errors: the file cannot be read, holds no surface, or the surface is degenerate.
pub fn neighbour_net(
    path: &str,
    grid: &[Vec<Vec3>],
    edge: fairing::strategies::JoinEdge,
) -> Result<Vec<Vec<Vec3>>> {
    use curve_repr::Surface;
    use fairing::strategies::JoinEdge;
    let invalid = |message: String| Error::Invalid {
        path: path.to_owned(),
        message,
    };
    let model = match cad::read_path(path, None) {
        Ok(model) => model,
        Err(cad::Error::Io { message, .. }) => {
            return Err(Error::Read {
                path: path.to_owned(),
                reason: message,
            })
        }
        Err(e) => return Err(invalid(e.to_string())),
    };
    let surface = &model
        .surfaces
        .first()
        .ok_or_else(|| invalid("holds no surface to join to".into()))?
        .surface;
    let (rows, columns) = (grid.len(), grid.first().map_or(0, Vec::len));
    let ours: Vec<Vec3> = match edge {
        JoinEdge::U0 => grid[0].clone(),
        JoinEdge::U1 => grid[rows - 1].clone(),
        JoinEdge::V0 => grid.iter().map(|r| r[0]).collect(),
        JoinEdge::V1 => grid.iter().map(|r| r[columns - 1]).collect(),
    };
    let across = if matches!(edge, JoinEdge::U0 | JoinEdge::U1) {
        rows
    } else {
        columns
    };
    let ((u0, u1), (v0, v1)) = surface.domain();
    // A CAD edge: (fixed parameter is u?, its value, the other end of that parameter).
    let edges = [(true, u0, u1), (true, u1, u0), (false, v0, v1), (false, v1, v0)];
    let at = |fixed_u: bool, fixed: f64, t: f64| {
        if fixed_u {
            surface.eval(fixed, t)
        } else {
            surface.eval(t, fixed)
        }
    };
    const SAMPLES: usize = 256;
    let mut best: Option<(f64, usize)> = None;
    for (e, &(fixed_u, fixed, _)) in edges.iter().enumerate() {
        let (a, b) = if fixed_u { (v0, v1) } else { (u0, u1) };
        let samples: Vec<Vec3> = (0..=SAMPLES)
            .map(|k| at(fixed_u, fixed, a + (b - a) * k as f64 / SAMPLES as f64))
            .collect();
        let total: f64 = ours
            .iter()
            .map(|p| {
                samples
                    .iter()
                    .map(|q| (p - q).norm())
                    .fold(f64::INFINITY, f64::min)
            })
            .sum();
        if total.is_finite() && best.is_none_or(|(d, _)| total < d) {
            best = Some((total, e));
        }
    }
    let (_, e) = best.ok_or_else(|| invalid("its surface does not evaluate to finite points".into()))?;
    let (fixed_u, fixed, opposite) = edges[e];
    let (a, b) = if fixed_u { (v0, v1) } else { (u0, u1) };
    let distance = |p: &Vec3, t: f64| (at(fixed_u, fixed, t) - p).norm();
    let parameters: Vec<f64> = ours
        .iter()
        .map(|p| {
            let step = (b - a) / SAMPLES as f64;
            let k = (0..=SAMPLES)
                .min_by(|&i, &j| {
                    let (ti, tj) = (a + step * i as f64, a + step * j as f64);
                    distance(p, ti).total_cmp(&distance(p, tj))
                })
                .unwrap_or(0);
            let (mut lo, mut hi) = (
                (a + step * k as f64 - step).max(a),
                (a + step * k as f64 + step).min(b),
            );
            let ratio = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..60 {
                let (c, d) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
                if distance(p, c) < distance(p, d) {
                    hi = d;
                } else {
                    lo = c;
                }
            }
            0.5 * (lo + hi)
        })
        .collect();
    let net: Vec<Vec<Vec3>> = (0..across)
        .map(|r| {
            let s = fixed + (opposite - fixed) * r as f64 / (across - 1) as f64;
            parameters.iter().map(|&t| at(fixed_u, s, t)).collect()
        })
        .collect();
    if net.iter().flatten().any(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(invalid("its surface does not evaluate to finite points".into()));
    }
    Ok(net)
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::Vec2;

    #[test]
    fn natural_tangents_are_the_cubic_s_derivatives() {
        // y = t³ − 3t on knots 0, 1, 3 is not natural, but any cubic's values and second
        // derivatives give its own tangents: y' = 3t² − 3, y'' = 6t.
        let t = [0.0, 1.0, 3.0];
        let y: Vec<Vector<1>> = t.iter().map(|&t| Vector::<1>::new(t * t * t - 3.0 * t)).collect();
        let m: Vec<Vector<1>> = t.iter().map(|&t| Vector::<1>::new(6.0 * t)).collect();
        let d = natural_tangents(&t, &y, &m).unwrap();
        for (k, &t) in t.iter().enumerate() {
            assert!((d[k][0] - (3.0 * t * t - 3.0)).abs() < 1e-12, "{k}: {}", d[k][0]);
        }
    }

    #[test]
    fn an_unknown_record_falls_back_to_the_measured_spline() {
        let points = CurvePoints::Planar(vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.5),
            Vec2::new(2.0, 0.2),
            Vec2::new(3.0, 0.9),
        ]);
        let (curve, what) = faired_curve(&json!({"type": "mystery"}), &points, CurveKind::Function).unwrap();
        assert_eq!(what, "measured-spline-function");
        assert!(deviation(&curve) <= 1e-15);
        // A NURBS record that does not pass through the points is not written.
        let wrong = json!({"type": "nurbs", "degree": 1, "knots": [0.0, 0.0, 1.0, 1.0],
            "control_points": [[0.0, 5.0], [3.0, 5.0]], "weights": [1.0, 1.0], "params": [0.0, 0.3, 0.6, 1.0]});
        let (_, what) = faired_curve(&wrong, &points, CurveKind::Parametric).unwrap();
        assert_eq!(what, "measured-natural-cubic");
    }
}
