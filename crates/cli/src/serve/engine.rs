//! The server's one door to the fairing code: the methods and their parameters, fairing a
//! curve or a surface, inspecting one.
//!
//! Everything runs through the library's door ([`fair_door`]), as the command does, so that a
//! report from the page is the report `fair curve` writes for the same points, method,
//! parameters and constraints (`elapsed_ms` aside). A request's parameters go to the
//! catalogue as the JSON values they are.
//!
//! The methods, their parameters and defaults come from the library's catalogue (the one the
//! command was started with), so a method registered by a program is on the page too.

use std::collections::BTreeMap;

use fair_door::curve::{default_method, CurveRequest};
use fair_door::error::{Error, Result};
use fair_door::kind::{CurveKind, KindChoice};
use fair_door::measure::{CurveMeasurement, Detail, SurfaceMeasurement};
use fair_door::report::Report;
use fair_door::surface::{SurfaceRequest, DEFAULT_METHOD};
use fair_door::ConstraintRequest;
use fairing::catalog::{Catalog, CurvePoints, MethodEntry, MethodKind, ParameterMap};
use fairing::EndClamp;

use crate::input::{CurveInput, Grid, InputFormat, SurfaceInput};

/// What to run: a method, its parameters and the constraints.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Job {
    /// The method; `None` for the default for the kind of input.
    pub(crate) method: Option<String>,
    /// Parameter values by name (numbers, strings or booleans; `null` = the default).
    pub(crate) params: BTreeMap<String, serde_json::Value>,
    /// Fixed points, bad points, tolerance, ends.
    pub(crate) constraints: JobConstraints,
}

/// The constraints of a [`Job`], as `--fixed`, `--points`, `--tolerance`, `--clamp-ends`.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct JobConstraints {
    /// Points that must not move (from 0; grid points counted row by row).
    pub(crate) fixed: Vec<usize>,
    /// The bad points for the interactive methods.
    pub(crate) points: Vec<usize>,
    /// No point moves farther than this.
    pub(crate) tolerance: Option<f64>,
    /// What is kept at the ends.
    pub(crate) clamp_ends: Option<EndClamp>,
    /// The corners kept (`None`: detected).
    pub(crate) corners: Option<fairing::corners::Corners>,
}

/// A faired curve.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CurveResult {
    /// The faired points, same count and order.
    pub(crate) points: CurvePoints,
    /// The command's report.
    pub(crate) report: Report,
    /// The kind the measures were taken for.
    pub(crate) kind: CurveKind,
}

/// A faired surface.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SurfaceResult {
    /// The faired grid, same size.
    pub(crate) grid: Grid,
    /// The command's report.
    pub(crate) report: Report,
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
pub(crate) fn methods(catalog: &Catalog) -> serde_json::Value {
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
                "planar_only": m.planar_only(),
                "schema": schema(m),
            })
        })
        .collect();
    serde_json::json!({
        "methods": list,
        "defaults": {
            "function": default_method(CurveKind::Function),
            "parametric": default_method(CurveKind::Parametric),
            "surface": DEFAULT_METHOD,
        },
    })
}

/// A job's parameters as the catalogue's map (given at `--set`, as on the command line);
/// `null` means "the default" and is left out. Refused: an empty string, an array or an
/// object.
fn parameters(job: &Job) -> Result<ParameterMap> {
    let mut map = ParameterMap::new();
    for (name, value) in &job.params {
        match value {
            serde_json::Value::Null => continue,
            serde_json::Value::Number(_) | serde_json::Value::Bool(_) => {
                map.insert_json(name, value.clone(), "--set");
            }
            serde_json::Value::String(s) if !s.trim().is_empty() => {
                map.insert_text(name, s.trim(), "--set");
            }
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
        }
    }
    Ok(map)
}

/// A job's constraints as the door takes them: indices checked for repeats, the tolerance
/// for being a finite positive number.
fn constraints(job: &Job) -> Result<ConstraintRequest> {
    let list = |option: &'static str, indices: &[usize]| -> Result<Option<Vec<usize>>> {
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
        Ok(Some(indices.to_vec()))
    };
    if let Some(tolerance) = job.constraints.tolerance {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::Argument {
                option: "--tolerance",
                message: format!("{tolerance} must be a finite number greater than 0"),
            });
        }
    }
    Ok(ConstraintRequest {
        fixed: list("--fixed", &job.constraints.fixed)?,
        bad_points: list("--points", &job.constraints.points)?,
        tolerance: job.constraints.tolerance,
        clamp_ends: job.constraints.clamp_ends,
        corners: job.constraints.corners.clone(),
    })
}

/// Points from a request, named `name` in messages, as if read from a JSON file.
pub(crate) fn curve_input(name: &str, points: CurvePoints) -> CurveInput {
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
pub(crate) fn surface_input(name: &str, grid: Grid) -> SurfaceInput {
    let order = (0..grid.rows)
        .flat_map(|i| (0..grid.columns).map(move |j| (i, j)))
        .collect();
    SurfaceInput {
        grid,
        offset: (0, 0),
        order,
        header: None,
        delimiter: crate::input::Delimiter::Comma,
        columns: [0, 1, 2, 3, 4],
        source: name.to_string(),
        lines: Vec::new(),
    }
}

/// Fairs a curve as `fair curve` does with the job's options. O(the method).
pub(crate) fn fair_curve(
    catalog: &Catalog,
    input: &CurveInput,
    kind: KindChoice,
    job: &Job,
) -> Result<CurveResult> {
    let request = CurveRequest {
        method: job.method.clone(),
        kind,
        settings: parameters(job)?,
        config: None,
        constraints: constraints(job)?,
        samples: false,
    };
    let faired = fair_door::curve(catalog, &input.data(), &request)?;
    faired.report.check_finite()?;
    Ok(CurveResult {
        points: faired.points,
        kind: faired.kind,
        report: faired.report,
    })
}

/// Fairs a surface as `fair surface` does with the job's options. O(the method).
pub(crate) fn fair_surface(catalog: &Catalog, input: &SurfaceInput, job: &Job) -> Result<SurfaceResult> {
    let request = SurfaceRequest {
        method: job.method.clone(),
        settings: parameters(job)?,
        config: None,
        constraints: constraints(job)?,
        ..Default::default()
    };
    let faired = fair_door::surface(catalog, &input.data(), &request)?;
    faired.report.check_finite()?;
    Ok(SurfaceResult {
        grid: faired.grid,
        report: faired.report,
    })
}

/// Measures a curve as `fair inspect` does: the report (method `inspect`) and the measurement
/// the drawing is made from. O(n).
pub(crate) fn inspect_curve(
    catalog: &Catalog,
    input: &CurveInput,
    kind: KindChoice,
) -> Result<(CurveKind, Report, CurveMeasurement)> {
    let inspected = fair_door::inspect_curve(catalog, &input.data(), kind, Detail::ALL)?;
    Ok((inspected.kind, inspected.report, inspected.measured))
}

/// Measures a surface as `fair inspect` does. O(m·n).
pub(crate) fn inspect_surface(input: &SurfaceInput) -> Result<(Report, SurfaceMeasurement)> {
    let inspected = fair_door::inspect_surface(&input.data())?;
    Ok((inspected.report, inspected.measured))
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use curve_repr::Vec2;

    fn wave(n: usize) -> CurveInput {
        let points = (0..n)
            .map(|i| {
                let x = i as f64 * 0.25;
                Vec2::new(x, x.sin() + if i == n / 2 { 0.05 } else { 0.0 })
            })
            .collect();
        curve_input("wave", CurvePoints::Planar(points))
    }

    #[test]
    fn a_job_gives_the_door_its_parameters_and_constraints() {
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
                clamp_ends: Some(EndClamp::G0),
                ..JobConstraints::default()
            },
        };
        let map = parameters(&job).unwrap();
        let names: Vec<&String> = map.iter().map(|(n, _)| n).collect();
        assert_eq!(names, ["p", "rule"]);
        assert_eq!(map.get("p").unwrap().value.text(), "0.999");
        let c = constraints(&job).unwrap();
        assert_eq!(c.fixed, Some(vec![3, 1]));
        assert_eq!(c.bad_points, None);
        assert_eq!(c.tolerance, Some(0.5));
        assert_eq!(c.clamp_ends, Some(EndClamp::G0));
        let twice = Job {
            constraints: JobConstraints {
                points: vec![4, 4],
                ..JobConstraints::default()
            },
            ..Job::default()
        };
        assert!(constraints(&twice).unwrap_err().to_string().contains("twice"));
        let nested = Job {
            params: BTreeMap::from([("p".to_string(), serde_json::json!([1]))]),
            ..Job::default()
        };
        assert_eq!(parameters(&nested).unwrap_err().exit_code(), 2);
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
        let result = fair_curve(&catalog, &input, KindChoice::Auto, &job).unwrap();
        let args = match crate::args::Cli::try_parse_from([
            "fair",
            "curve",
            "-",
            "--method",
            "strain-energy",
            "--points",
            "12",
        ])
        .unwrap()
        .command
        {
            crate::args::Command::Curve(args) => args,
            _ => unreachable!(),
        };
        let command = crate::commands::curve::process(&catalog, &input, &args, None).unwrap();
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
        assert_eq!(value["defaults"]["surface"], "jump-lsq");
    }
}
