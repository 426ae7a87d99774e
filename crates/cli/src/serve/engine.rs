//! The server's one door to the fairing code: the methods and their parameters, fairing a
//! curve or a surface, inspecting one.
//!
//! Everything runs through the command's own code path — [`curve::process`],
//! [`surface::process`], [`measure`] and [`Report::inspection`] as `fair inspect` uses them —
//! so that a report from the page is the report `fair curve` writes for the same points,
//! method, parameters and constraints (`elapsed_ms` aside). A request's parameters and
//! constraints are turned into the command line they stand for ([`FairArgs`]).
//!
//! The methods, their parameters and defaults come from the library's catalogue (the one the
//! command was started with), so a method registered by a program is on the page too.

use std::collections::BTreeMap;

use fairing::catalog::{Catalog, CurveJob, CurvePoints, MethodEntry, MethodKind};

use crate::args::{ClampEnds, FairArgs, IndexList, KindArg, Setting};
use crate::commands::{curve, measure, surface};
use crate::error::{Error, Result};
use crate::input::grid::Grid;
use crate::input::{CurveInput, InputFormat, Points, SurfaceInput};
use crate::kind::{self, CurveKind};
use crate::report::{Report, ReportKind};

/// What to run: a method, its parameters and the constraints.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Job {
    /// The method; `None` for the command's default for the kind of input.
    pub method: Option<String>,
    /// Parameter values by name (numbers, strings or booleans; `null` = the default).
    pub params: BTreeMap<String, serde_json::Value>,
    /// Fixed points, bad points, tolerance, ends.
    pub constraints: JobConstraints,
}

/// The constraints of a [`Job`], as `--fixed`, `--points`, `--tolerance`, `--clamp-ends`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct JobConstraints {
    /// Points that must not move (from 0; grid points counted row by row).
    pub fixed: Vec<usize>,
    /// The bad points for the interactive methods.
    pub points: Vec<usize>,
    /// No point moves farther than this.
    pub tolerance: Option<f64>,
    /// What is kept at the ends.
    pub clamp_ends: Option<ClampEnds>,
}

/// A faired curve.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveResult {
    /// The faired points, same count and order.
    pub points: Points,
    /// The command's report.
    pub report: Report,
    /// The kind the measures were taken for.
    pub kind: CurveKind,
}

/// A faired surface.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceResult {
    /// The faired grid, same size.
    pub grid: Grid,
    /// The command's report.
    pub report: Report,
}

/// Whether the method refuses spatial curves: asked of the method itself (its check on four
/// points in 3D with its defaults), so that a registered method answers for itself.
fn planar_only(catalog: &Catalog, entry: &MethodEntry) -> bool {
    if entry.info().kind != MethodKind::Curve {
        return false;
    }
    let points = CurvePoints::Spatial(
        (0..4)
            .map(|i| curve_repr::Vec3::new(i as f64, (i * i) as f64, 0.5 * i as f64))
            .collect(),
    );
    let constraints = fairing::Constraints::default();
    let job = CurveJob {
        method: entry.name(),
        points: &points,
        kind: fairing::catalog::CurveKind::Parametric,
        constraints: &constraints,
        bad_points: &[],
        catalog,
    };
    matches!(
        entry.check_curve(entry.defaults(), &job),
        Err(fairing::Error::Refused {
            what: fairing::Refusal::Dimension,
            ..
        })
    )
}

/// A method's parameters as a JSON Schema object: each property's own schema (from the
/// method's settings type) with its `default` and `description`, and the settings' `$defs`
/// that enumerations refer to.
fn schema(entry: &MethodEntry) -> serde_json::Value {
    let properties: serde_json::Map<String, serde_json::Value> = entry
        .parameters()
        .iter()
        .map(|p| {
            let mut property = match &p.schema {
                serde_json::Value::Object(map) => map.clone(),
                _ => serde_json::Map::new(),
            };
            property.insert("description".into(), serde_json::json!(p.meaning));
            property.insert("default".into(), p.default_value.clone());
            (p.name.clone(), serde_json::Value::Object(property))
        })
        .collect();
    let mut object = serde_json::json!({
        "type": "object",
        "properties": properties,
        "additionalProperties": false,
    });
    if let Some(defs) = entry.schema().get("$defs") {
        object["$defs"] = defs.clone();
    }
    object
}

/// Every method of `catalog`: name, `kind` (curve or surface), paper, summary, whether it
/// takes bad points (`takes_points`), whether it fairs planar curves only, and its parameters
/// as a JSON Schema; plus the default method for each kind of input.
pub fn methods(catalog: &Catalog) -> serde_json::Value {
    let list: Vec<serde_json::Value> = [MethodKind::Curve, MethodKind::Surface]
        .into_iter()
        .flat_map(|kind| catalog.methods(kind))
        .map(|m| {
            serde_json::json!({
                "name": m.name(),
                "kind": m.info().kind.name(),
                "paper": m.info().paper,
                "summary": m.info().summary,
                "takes_points": m.takes_bad_points(),
                "planar_only": planar_only(catalog, m),
                "schema": schema(m),
            })
        })
        .collect();
    serde_json::json!({
        "methods": list,
        "defaults": {
            "function": curve::default_method(CurveKind::Function),
            "parametric": curve::default_method(CurveKind::Parametric),
            "surface": surface::DEFAULT_METHOD,
        },
    })
}

/// A parameter value as the text `--set` would carry. `null` means "the default" (`None`).
fn setting_text(name: &str, value: &serde_json::Value) -> Result<Option<String>> {
    let text = match value {
        serde_json::Value::Null => return Ok(None),
        serde_json::Value::Number(n) => n.to_string(),
        serde_json::Value::Bool(b) => b.to_string(),
        serde_json::Value::String(s) if !s.trim().is_empty() => s.trim().to_string(),
        serde_json::Value::String(_) => {
            return Err(Error::Parameter {
                origin: "params".into(),
                message: format!("`{name}` is empty"),
            })
        }
        _ => {
            return Err(Error::Parameter {
                origin: "params".into(),
                message: format!("`{name}` must be a number, a string or a boolean"),
            })
        }
    };
    Ok(Some(text))
}

/// The command line a job stands for (`fair curve` / `fair surface` options; no files).
pub(crate) fn arguments(job: &Job, kind: KindArg) -> Result<FairArgs> {
    let mut settings = Vec::new();
    for (name, value) in &job.params {
        if let Some(value) = setting_text(name, value)? {
            settings.push(Setting {
                name: name.clone(),
                value,
            });
        }
    }
    let list = |option: &'static str, indices: &[usize]| -> Result<Option<IndexList>> {
        if indices.is_empty() {
            return Ok(None);
        }
        let mut seen = indices.to_vec();
        seen.sort_unstable();
        if let Some(pair) = seen.windows(2).find(|w| w[0] == w[1]) {
            return Err(Error::Argument {
                option,
                message: format!("index {} appears twice", pair[0]),
            });
        }
        Ok(Some(IndexList(indices.to_vec())))
    };
    if let Some(tolerance) = job.constraints.tolerance {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::Argument {
                option: "--tolerance",
                message: format!("{tolerance} must be a finite number greater than 0"),
            });
        }
    }
    Ok(FairArgs {
        input: "-".into(),
        method: job.method.clone(),
        kind,
        columns: None,
        config: None,
        settings,
        fixed: list("--fixed", &job.constraints.fixed)?,
        points: list("--points", &job.constraints.points)?,
        tolerance: job.constraints.tolerance,
        clamp_ends: job.constraints.clamp_ends,
        output: None,
        report: None,
        plot: None,
        quiet: true,
        print_config: false,
        batch: false,
        cad: Default::default(),
    })
}

/// Points from a request, named `name` in messages, as if read from a JSON file.
pub fn curve_input(name: &str, points: Points) -> CurveInput {
    CurveInput {
        points,
        format: InputFormat::Json { document: None },
        source: name.to_string(),
        lines: Vec::new(),
        notes: Vec::new(),
    }
}

/// A grid from a request, named `name` in messages, as if read from an `i,j,x,y,z` file
/// whose indices start at 0, row by row.
pub fn surface_input(name: &str, grid: Grid) -> SurfaceInput {
    let order = (0..grid.rows)
        .flat_map(|i| (0..grid.columns).map(move |j| (i, j)))
        .collect();
    SurfaceInput {
        grid,
        offset: (0, 0),
        order,
        header: None,
        delimiter: crate::input::Delimiter::Comma,
        source: name.to_string(),
        lines: Vec::new(),
    }
}

fn curve_kind(kind: ReportKind) -> Result<CurveKind> {
    match kind {
        ReportKind::Function => Ok(CurveKind::Function),
        ReportKind::Parametric => Ok(CurveKind::Parametric),
        ReportKind::Surface => Err(Error::Internal {
            message: "a curve's report says surface".into(),
        }),
    }
}

/// Fairs a curve as `fair curve` does with the job's options. O(the method).
pub fn fair_curve(catalog: &Catalog, input: &CurveInput, kind: KindArg, job: &Job) -> Result<CurveResult> {
    let args = arguments(job, kind)?;
    let faired = curve::process(catalog, input, &args, None)?;
    faired.report.check_finite()?;
    // The command writes the points in the input's format, here a JSON array written with the
    // shortest digits that read back exactly: reading it back gives the faired f64s unchanged.
    let rows: Vec<Vec<f64>> = serde_json::from_str(&faired.points_text).map_err(|e| Error::Internal {
        message: format!("faired points: {e}"),
    })?;
    let points = Points::from_rows(input.points.dimension(), &rows).ok_or_else(|| Error::Internal {
        message: "faired points of another dimension".into(),
    })?;
    Ok(CurveResult {
        points,
        kind: curve_kind(faired.report.kind)?,
        report: faired.report,
    })
}

/// Fairs a surface as `fair surface` does with the job's options. O(the method).
pub fn fair_surface(catalog: &Catalog, input: &SurfaceInput, job: &Job) -> Result<SurfaceResult> {
    let args = arguments(job, KindArg::Auto)?;
    let faired = surface::process(catalog, input, &args, None)?;
    faired.report.check_finite()?;
    let grid = faired.plot.faired.clone().ok_or_else(|| Error::Internal {
        message: "no faired grid".into(),
    })?;
    Ok(SurfaceResult {
        grid,
        report: faired.report,
    })
}

/// Measures a curve as `fair inspect` does: the report (method `inspect`) and the measurement
/// the drawing is made from. O(n).
pub fn inspect_curve(
    catalog: &Catalog,
    input: &CurveInput,
    kind: KindArg,
) -> Result<(CurveKind, Report, measure::CurveMeasurement)> {
    input.require_at_least(curve::MIN_CURVE_POINTS, "a curve")?;
    let kind = kind::resolve(kind, input)?;
    let measured = measure::curve(kind, &input.points).map_err(|e| measure::in_file(e, &input.source))?;
    let mut measures = measured.measures.clone();
    measures.criteria =
        crate::commands::inspect::curve_criteria(catalog, kind, input, measures.energies.as_ref())?;
    let report = Report::inspection(
        ReportKind::from(kind),
        input.len(),
        measures,
        measured.curve.clone(),
    );
    report.check_finite()?;
    Ok((kind, report, measured))
}

/// Measures a surface as `fair inspect` does. O(m·n).
pub fn inspect_surface(input: &SurfaceInput) -> Result<(Report, measure::SurfaceMeasurement)> {
    surface::require_grid(input)?;
    let measured = measure::surface(&input.grid).map_err(|e| measure::in_file(e, &input.source))?;
    let report = Report::inspection(
        ReportKind::Surface,
        input.grid.points.len(),
        measured.measures.clone(),
        measured.surface.clone(),
    );
    report.check_finite()?;
    Ok((report, measured))
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::Vec2;

    fn wave(n: usize) -> CurveInput {
        let points = (0..n)
            .map(|i| {
                let x = i as f64 * 0.25;
                Vec2::new(x, x.sin() + if i == n / 2 { 0.05 } else { 0.0 })
            })
            .collect();
        curve_input("wave", Points::Planar(points))
    }

    #[test]
    fn a_job_is_the_command_line_it_stands_for() {
        let job = Job {
            method: Some("smoothing-spline".into()),
            params: BTreeMap::from([
                ("p".to_string(), serde_json::json!(0.999)),
                ("rule".to_string(), serde_json::json!("gcv")),
                ("unused".to_string(), serde_json::Value::Null),
            ]),
            constraints: JobConstraints {
                fixed: vec![3, 1],
                tolerance: Some(0.5),
                clamp_ends: Some(ClampEnds::G0),
                ..JobConstraints::default()
            },
        };
        let args = arguments(&job, KindArg::Function).unwrap();
        assert_eq!(
            args.settings,
            vec![
                Setting {
                    name: "p".into(),
                    value: "0.999".into()
                },
                Setting {
                    name: "rule".into(),
                    value: "gcv".into()
                }
            ]
        );
        assert_eq!(args.fixed, Some(IndexList(vec![3, 1])));
        assert_eq!(args.points, None);
        assert_eq!(args.tolerance, Some(0.5));
        assert_eq!(args.clamp_ends, Some(ClampEnds::G0));
        let twice = Job {
            constraints: JobConstraints {
                points: vec![4, 4],
                ..JobConstraints::default()
            },
            ..Job::default()
        };
        assert!(arguments(&twice, KindArg::Auto)
            .unwrap_err()
            .to_string()
            .contains("twice"));
        let nested = Job {
            params: BTreeMap::from([("p".to_string(), serde_json::json!([1]))]),
            ..Job::default()
        };
        assert_eq!(arguments(&nested, KindArg::Auto).unwrap_err().exit_code(), 2);
    }

    #[test]
    fn fairing_gives_the_command_report_and_exact_points() {
        let input = wave(24);
        let job = Job {
            method: Some("strain-energy".into()),
            constraints: JobConstraints {
                points: vec![12],
                ..JobConstraints::default()
            },
            ..Job::default()
        };
        let catalog = Catalog::builtin();
        let result = fair_curve(&catalog, &input, KindArg::Auto, &job).unwrap();
        let args = arguments(&job, KindArg::Auto).unwrap();
        let command = curve::process(&catalog, &input, &args, None).unwrap();
        let mut expected = command.report.clone();
        expected.elapsed_ms = result.report.elapsed_ms;
        assert_eq!(result.report, expected);
        assert_eq!(result.report.moved, vec![12]);
        let text = crate::output::format_curve(&input, &result.points).unwrap();
        assert_eq!(text, command.points_text);
        assert_eq!(result.points.len(), 24);
    }

    #[test]
    fn methods_list_every_registered_method_with_its_defaults() {
        let catalog = Catalog::builtin();
        let value = methods(&catalog);
        let list = value["methods"].as_array().unwrap();
        let registered =
            catalog.methods(MethodKind::Curve).count() + catalog.methods(MethodKind::Surface).count();
        assert_eq!(list.len(), registered);
        let strain = list.iter().find(|m| m["name"] == "strain-energy").unwrap();
        assert_eq!(strain["takes_points"], true);
        assert_eq!(
            strain["schema"]["properties"]["energy-tolerance"]["default"],
            1e-6
        );
        assert_eq!(strain["schema"]["properties"]["replacement"]["default"], "limit");
        let two_phase = list.iter().find(|m| m["name"] == "two-phase").unwrap();
        assert_eq!(two_phase["planar_only"], true);
        assert_eq!(two_phase["takes_points"], false);
        assert_eq!(value["defaults"]["surface"], "zhang-cheng");
    }
}
