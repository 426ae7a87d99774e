//! The routes of `fair serve`: the page, and the JSON API under it.
//!
//! | route | body | answer |
//! |---|---|---|
//! | `GET /` (`/app.js`, `/style.css`) | | the page |
//! | `GET /api/methods` | | `{"methods": [{name, kind, paper, summary, takes_points, planar_only, schema}], "defaults"}` |
//! | `GET /api/datasets` | | `{"datasets": [{name, about, origin}]}` |
//! | `GET /api/datasets/{name}` | | a [loaded](#loaded) data set, plus `about` |
//! | `POST /api/inspect` | `{"text", "name"?, "kind"?, "surface"?}` (a file's content) or `{"points", "kind"?}` or `{"rows", "columns", "points"}` | [loaded](#loaded) |
//! | `POST /api/curve` | `{"points", "kind"?, "method"?, "params"?, "constraints"?, "name"?}` | `{"points", "report", "drawing": {"before", "after"}}` |
//! | `POST /api/surface` | `{"rows", "columns", "points", "method"?, "params"?, "constraints"?, "name"?}` | `{"rows", "columns", "points", "report", "drawing": {"before", "after"}}` |
//! | `POST /api/cad` | the body of `/api/curve` or `/api/surface`, plus `"format": "iges" \| "step" \| "dxf"`, `"control-points"?`, `"fit-tolerance"?`, `"fair"?` | the CAD file (attachment), its report's `cad` object in the `X-Fair-Cad` header |
//!
//! <a id="loaded"></a>A loaded curve or surface is `{"name", "type": "curve" | "surface",
//! "points", ("rows", "columns" for a surface), "report", "drawing"}`, the report being
//! `fair inspect`'s. `constraints` is `{"fixed", "points", "tolerance", "clamp-ends", "corners"}`, the
//! names of a config file's `[constraints]`; `params` maps parameter names to values (`fair
//! methods` lists them). Point indices count from 0; a grid's row by row (k = i · columns + j).
//! The `drawing`s are described in [`super::drawing`].
//!
//! Every failure is `{"error": "one line"}` with a 4xx status for what the request got wrong
//! (400 bad input, 404 unknown route or data set, 405 wrong method, 413 too large or too
//! many points, 415 not JSON, 422 an iteration setting over the server's limit, see
//! [`super::limits`]) and 5xx for the server's own failures (503 when the request's deadline
//! passed and its work was cancelled).

use std::collections::BTreeMap;

use serde::Deserialize;
use serde_json::{json, Value};

use super::datasets::{Datasets, Unavailable};
use super::drawing;
use super::engine::{self, Job, JobConstraints};
use super::http::{Request, Response};
use super::limits::{self, Rows};
use super::page;
use crate::input::{self, looks_like_surface, CurvePoints, Grid, Source};
use curve_repr::Vec3;
use fair_door::error::Error;
use fair_door::KindChoice;
use fairing::corners::Corners;
use fairing::EndClamp;

/// What every request may use: the methods, the data sets and the body limit.
#[derive(Debug, Clone)]
pub(crate) struct Context {
    /// The methods, criteria and indicators (the command's own catalogue).
    pub catalog: fairing::catalog::Catalog,
    /// The data sets offered.
    pub datasets: Datasets,
    /// The largest body (and data file) in bytes.
    pub max_upload: usize,
}

impl Default for Context {
    /// The built-in catalogue, no data sets, no body limit.
    fn default() -> Self {
        Context {
            catalog: fairing::catalog::Catalog::builtin(),
            datasets: Datasets::default(),
            max_upload: 0,
        }
    }
}

/// Answers one request. Never panics on any input (the server catches a panic anyway).
pub(crate) fn handle(request: &Request, context: &Context) -> Response {
    let path = request.path.as_str();
    let get = |answer: fn(&Context) -> Response| match request.method.as_str() {
        "GET" | "HEAD" => answer(context),
        _ => not_allowed("GET"),
    };
    match path {
        "/" | "/index.html" => get(|_| page::index()),
        "/app.js" => get(|_| page::script()),
        "/style.css" => get(|_| page::style()),
        "/api/methods" => get(|context| Response::json(200, &engine::methods(&context.catalog))),
        "/api/datasets" => get(datasets),
        "/api/inspect" | "/api/curve" | "/api/surface" | "/api/cad" => {
            if request.method != "POST" {
                return not_allowed("POST");
            }
            if let Some(refusal) = not_json(request) {
                return refusal;
            }
            let result = match path {
                "/api/inspect" => inspect(&context.catalog, &request.body),
                "/api/curve" => fair_curve(&context.catalog, &request.body),
                "/api/cad" => cad_file(&context.catalog, &request.body),
                _ => fair_surface(&context.catalog, &request.body),
            };
            result.unwrap_or_else(|refusal| refusal)
        }
        _ => match path.strip_prefix("/api/datasets/") {
            Some(name) => match request.method.as_str() {
                "GET" | "HEAD" => dataset(name, context),
                _ => not_allowed("GET"),
            },
            None => Response::error(404, format!("no route {path} (the API is under /api/)")),
        },
    }
}

fn not_allowed(allowed: &'static str) -> Response {
    Response::error(405, format!("method not allowed here; use {allowed}")).with_header("Allow", allowed)
}

/// A POST body must be declared JSON: a page elsewhere cannot send that without the browser
/// asking this server first (which it does not answer), so it cannot make it work for it.
fn not_json(request: &Request) -> Option<Response> {
    let declared = request
        .content_type
        .as_deref()
        .and_then(|t| t.split(';').next())
        .map(|t| t.trim().eq_ignore_ascii_case("application/json"))
        .unwrap_or(false);
    (!declared).then(|| {
        Response::error(
            415,
            "the body must be JSON sent with Content-Type: application/json",
        )
    })
}

type Answer = std::result::Result<Response, Response>;

/// The status for a command error: 400 for what the user can fix, 501 for a method not wired
/// yet, 500 for internal failures.
fn status_of(error: &Error) -> u16 {
    match error {
        Error::NotAvailable { .. } => 501,
        // The server cancelled the work (its deadline passed); the server says which.
        Error::Cancelled => 503,
        e if e.exit_code() == 2 => 400,
        _ => 500,
    }
}

/// The command's option names, as the request's fields.
fn request_field(option: &str) -> &str {
    match option {
        "--fixed" => "constraints.fixed",
        "--points" => "constraints.points",
        "--tolerance" => "constraints.tolerance",
        "--clamp-ends" => "constraints.clamp-ends",
        "--kind" => "kind",
        "--method" => "method",
        "--set" => "params",
        "--control-points" => "control-points",
        "--fit-tolerance" => "fit-tolerance",
        "-o" | "--cad" => "format",
        other => other,
    }
}

/// A command error as a response, its option names changed to the request's field names.
fn failure(error: Error) -> Response {
    let status = status_of(&error);
    let message = match &error {
        Error::Argument { option, message } => format!("{}: {message}", request_field(option)),
        Error::Parameter { origin, message } => format!("{}: {message}", request_field(origin)),
        other => other.one_line(),
    };
    Response::error(status, message.replace('\n', "; "))
}

fn parse_body<'a, T: Deserialize<'a>>(body: &'a [u8]) -> std::result::Result<T, Response> {
    serde_json::from_slice(body).map_err(|e| {
        if let Some(refusal) = limits::too_many_rows(&e) {
            return refusal;
        }
        let hint = if e.is_syntax() {
            " (JSON has no NaN or Infinity: every number must be finite)"
        } else {
            ""
        };
        Response::error(400, format!("request body: {e}{hint}"))
    })
}

/// `constraints` of a request (the names of a config file's `[constraints]`).
#[derive(Debug, Default, Deserialize)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
struct ConstraintsBody {
    fixed: Vec<usize>,
    points: Vec<usize>,
    tolerance: Option<f64>,
    #[serde(alias = "clamp_ends")]
    clamp_ends: Option<String>,
    /// `"auto"`, `"none"` or point indices, as `--corners`.
    corners: Option<serde_json::Value>,
}

impl ConstraintsBody {
    fn into_job(self) -> std::result::Result<JobConstraints, Response> {
        let clamp_ends = match self.clamp_ends.as_deref() {
            None | Some("none") => None,
            Some("g0") => Some(EndClamp::G0),
            Some("g1") => Some(EndClamp::G1),
            Some("g2") => Some(EndClamp::G2),
            Some(other) => {
                return Err(Response::error(
                    400,
                    format!("constraints.clamp-ends: `{other}` is not one of g0, g1, g2"),
                ))
            }
        };
        let corners = match &self.corners {
            None => None,
            Some(value) => Some(
                value
                    .as_str()
                    .and_then(Corners::named)
                    .or_else(|| {
                        serde_json::from_value::<Vec<usize>>(value.clone())
                            .ok()
                            .map(Corners::At)
                    })
                    .ok_or_else(|| {
                        Response::error(
                            400,
                            "constraints.corners: not auto, none or a list of point indices from 0",
                        )
                    })?,
            ),
        };
        Ok(JobConstraints {
            fixed: self.fixed,
            points: self.points,
            tolerance: self.tolerance,
            clamp_ends,
            corners,
        })
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CurveBody {
    points: Rows,
    #[serde(default)]
    kind: Option<String>,
    #[serde(default)]
    method: Option<String>,
    #[serde(default)]
    params: BTreeMap<String, Value>,
    #[serde(default)]
    constraints: ConstraintsBody,
    #[serde(default)]
    name: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SurfaceBody {
    rows: usize,
    columns: usize,
    points: Rows,
    #[serde(default)]
    method: Option<String>,
    #[serde(default)]
    params: BTreeMap<String, Value>,
    #[serde(default)]
    constraints: ConstraintsBody,
    #[serde(default)]
    name: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct InspectBody {
    #[serde(default)]
    text: Option<String>,
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    kind: Option<String>,
    #[serde(default)]
    surface: bool,
    #[serde(default)]
    points: Option<Rows>,
    #[serde(default)]
    rows: Option<usize>,
    #[serde(default)]
    columns: Option<usize>,
}

fn kind_of(kind: Option<&str>) -> std::result::Result<KindChoice, Response> {
    match kind {
        None | Some("auto") => Ok(KindChoice::Auto),
        Some("function") => Ok(KindChoice::Function),
        Some("parametric") => Ok(KindChoice::Parametric),
        Some(other) => Err(Response::error(
            400,
            format!("kind: `{other}` is not one of function, parametric, auto"),
        )),
    }
}

/// The first non-finite coordinate, as a 400.
fn check_finite(rows: &[Vec<f64>]) -> std::result::Result<(), Response> {
    match rows.iter().position(|r| !r.iter().all(|c| c.is_finite())) {
        Some(i) => Err(Response::error(400, format!("points: point {i} is not finite"))),
        None => Ok(()),
    }
}

fn curve_points(rows: &[Vec<f64>]) -> std::result::Result<CurvePoints, Response> {
    check_finite(rows)?;
    let dimension = rows.first().map_or(2, Vec::len);
    if dimension != 2 && dimension != 3 {
        return Err(Response::error(
            400,
            format!("points: point 0 has {dimension} coordinates; a curve's have 2 (x, y) or 3 (x, y, z)"),
        ));
    }
    CurvePoints::from_rows(dimension, rows).ok_or_else(|| {
        let i = rows.iter().position(|r| r.len() != dimension).unwrap_or(0);
        Response::error(
            400,
            format!(
                "points: point {i} has {} coordinates, point 0 has {dimension}",
                rows.get(i).map_or(0, Vec::len)
            ),
        )
    })
}

fn grid_points(rows: usize, columns: usize, points: &[Vec<f64>]) -> std::result::Result<Grid, Response> {
    check_finite(points)?;
    if rows.checked_mul(columns) != Some(points.len()) {
        return Err(Response::error(
            400,
            format!(
                "points: {} points, but rows × columns = {rows} × {columns}",
                points.len()
            ),
        ));
    }
    let points = points
        .iter()
        .enumerate()
        .map(|(k, p)| match p.as_slice() {
            [x, y, z] => Ok(Vec3::new(*x, *y, *z)),
            _ => Err(Response::error(
                400,
                format!(
                    "points: point {k} has {} coordinates; a grid's have 3 (x, y, z)",
                    p.len()
                ),
            )),
        })
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok(Grid {
        rows,
        columns,
        points,
    })
}

fn datasets(context: &Context) -> Response {
    let list: Vec<Value> = context
        .datasets
        .list()
        .iter()
        .map(|d| json!({ "name": d.name, "about": d.about, "origin": d.origin_name() }))
        .collect();
    Response::json(200, &json!({ "datasets": list }))
}

/// Percent-decodes a path segment; `None` for a broken escape or bytes that are not UTF-8.
pub(crate) fn percent_decode(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

fn dataset(encoded: &str, context: &Context) -> Response {
    let Some(name) = percent_decode(encoded) else {
        return Response::error(
            400,
            format!("data set name `{encoded}` is not valid percent-encoded UTF-8"),
        );
    };
    let (entry, source) = match context.datasets.read(&name, context.max_upload) {
        Ok(found) => found,
        Err(Unavailable::Outside(name)) => {
            return Response::error(
                400,
                format!("`{name}` is outside the data folders; GET /api/datasets lists what can be read"),
            )
        }
        Err(Unavailable::Unknown(name)) => {
            return Response::error(
                404,
                format!("no data set `{name}` (GET /api/datasets lists them)"),
            )
        }
        Err(Unavailable::TooLarge(message)) => return Response::error(413, message),
        Err(Unavailable::Unreadable(error)) => return failure(error),
    };
    match load_text(&context.catalog, &source, KindChoice::Auto, false) {
        Ok(mut value) => {
            value["about"] = json!(entry.about);
            Response::json(200, &value)
        }
        Err(refusal) => refusal,
    }
}

/// A file's text measured as `fair inspect` reads it: a surface when `surface` is set or the
/// first row has five columns, else a curve.
fn load_text(
    catalog: &fairing::catalog::Catalog,
    source: &Source,
    kind: KindChoice,
    surface: bool,
) -> std::result::Result<Value, Response> {
    if surface || looks_like_surface(source) {
        if kind != KindChoice::Auto {
            return Err(Response::error(
                400,
                "kind: the input is a surface grid; kind is for curves",
            ));
        }
        let grid = input::grid::parse(source).map_err(failure)?;
        limits::surface_nodes(grid.grid.rows, grid.grid.columns)?;
        load_surface(&grid.source.clone(), grid)
    } else {
        let curve = input::parse_curve(source).map_err(failure)?;
        limits::curve_points(curve.points.len())?;
        load_curve(catalog, &curve, kind)
    }
}

fn load_curve(
    catalog: &fairing::catalog::Catalog,
    curve: &input::CurveInput,
    kind: KindChoice,
) -> std::result::Result<Value, Response> {
    let (kind, report, measured) = engine::inspect_curve(catalog, curve, kind).map_err(failure)?;
    Ok(json!({
        "name": curve.source,
        "type": "curve",
        "points": curve.points.rows(),
        "report": report,
        "drawing": drawing::curve(&curve.points, kind, &measured),
    }))
}

fn load_surface(name: &str, input: input::SurfaceInput) -> std::result::Result<Value, Response> {
    let (report, measured) = engine::inspect_surface(&input).map_err(failure)?;
    let grid = &input.grid;
    let light = drawing::light_for(grid);
    let points: Vec<[f64; 3]> = grid.points.iter().map(|p| [p.x, p.y, p.z]).collect();
    Ok(json!({
        "name": name,
        "type": "surface",
        "rows": grid.rows,
        "columns": grid.columns,
        "points": points,
        "report": report,
        "drawing": drawing::surface(grid, &measured, light.as_ref()),
    }))
}

fn inspect(catalog: &fairing::catalog::Catalog, body: &[u8]) -> Answer {
    let body: InspectBody = parse_body(body)?;
    let kind = kind_of(body.kind.as_deref())?;
    let name = body.name.unwrap_or_else(|| "upload".into());
    let value = match (body.text, body.points, body.rows, body.columns) {
        (Some(text), None, None, None) => load_text(catalog, &Source::from_text(&name, &text), kind, body.surface)?,
        (None, Some(Rows(points)), None, None) if !body.surface => {
            limits::curve_points(points.len())?;
            let curve = engine::curve_input(&name, curve_points(&points)?);
            load_curve(catalog, &curve, kind)?
        }
        (None, Some(Rows(points)), Some(rows), Some(columns)) => {
            if kind != KindChoice::Auto {
                return Err(Response::error(400, "kind: the input is a surface grid; kind is for curves"));
            }
            let grid = grid_points(rows, columns, &points)?;
            limits::surface_nodes(rows, columns)?;
            load_surface(&name, engine::surface_input(&name, grid))?
        }
        _ => {
            return Err(Response::error(
                400,
                "request body: give `text` (a file's content), or `points` (a curve), or `rows`, `columns` and `points` (a surface)",
            ))
        }
    };
    Ok(Response::json(200, &value))
}

fn fair_curve(catalog: &fairing::catalog::Catalog, body: &[u8]) -> Answer {
    let body: CurveBody = parse_body(body)?;
    let kind = kind_of(body.kind.as_deref())?;
    limits::curve_work(catalog, body.points.0.len(), body.method.as_deref(), &body.params)?;
    limits::iterations(&body.params)?;
    let name = body.name.unwrap_or_else(|| "points".into());
    let input = engine::curve_input(&name, curve_points(&body.points.0)?);
    let job = Job {
        method: body.method,
        params: body.params,
        constraints: body.constraints.into_job()?,
    };
    let result = engine::fair_curve(catalog, &input, kind, &job).map_err(failure)?;
    let before = drawing::measure_curve(&input.points, result.kind)
        .map_err(|e| failure(fair_door::measure::in_file(e, &name)))?;
    let after = drawing::measure_curve(&result.points, result.kind)
        .map_err(|e| failure(fair_door::measure::in_file(e, &name)))?;
    Ok(Response::json(
        200,
        &json!({
            "points": result.points.rows(),
            "report": result.report,
            "drawing": { "before": before, "after": after },
        }),
    ))
}

fn fair_surface(catalog: &fairing::catalog::Catalog, body: &[u8]) -> Answer {
    let body: SurfaceBody = parse_body(body)?;
    let grid = grid_points(body.rows, body.columns, &body.points.0)?;
    limits::surface_nodes(body.rows, body.columns)?;
    limits::iterations(&body.params)?;
    let name = body.name.unwrap_or_else(|| "points".into());
    let input = engine::surface_input(&name, grid);
    let job = Job {
        method: body.method,
        params: body.params,
        constraints: body.constraints.into_job()?,
    };
    let result = engine::fair_surface(catalog, &input, &job).map_err(failure)?;
    let light = drawing::light_for(&input.grid);
    let in_file = |e| failure(fair_door::measure::in_file(e, &name));
    let before = drawing::measure_surface(&input.grid, light.as_ref()).map_err(in_file)?;
    let after = drawing::measure_surface(&result.grid, light.as_ref()).map_err(in_file)?;
    let points: Vec<[f64; 3]> = result.grid.points.iter().map(|p| [p.x, p.y, p.z]).collect();
    Ok(Response::json(
        200,
        &json!({
            "rows": result.grid.rows,
            "columns": result.grid.columns,
            "points": points,
            "report": result.report,
            "drawing": { "before": before, "after": after },
        }),
    ))
}

/// A `/api/cad` body: the body of `/api/curve` (or of `/api/surface`, with `rows` and
/// `columns`) plus the format, a rebuild, and whether to fair first. Read in one pass, so that
/// its points are counted ([`Rows`]) as they are read.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
struct CadBody {
    format: String,
    #[serde(default)]
    control_points: Option<usize>,
    #[serde(default)]
    fit_tolerance: Option<f64>,
    #[serde(default = "yes")]
    fair: bool,
    #[serde(default)]
    rows: Option<usize>,
    #[serde(default)]
    columns: Option<usize>,
    points: Rows,
    #[serde(default)]
    kind: Option<String>,
    #[serde(default)]
    method: Option<String>,
    #[serde(default)]
    params: BTreeMap<String, Value>,
    #[serde(default)]
    constraints: ConstraintsBody,
    #[serde(default)]
    name: Option<String>,
}

fn yes() -> bool {
    true
}

/// A file name made of the request's name: letters, digits, `.`, `-` and `_` kept, the rest `_`.
fn file_stem(name: &str) -> String {
    let stem = fair_door::cad::stem(name);
    stem.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "._-".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// `POST /api/cad`: fairs the body as `/api/curve` (or `/api/surface` when it has `rows`)
/// does — or, with `"fair": false`, takes its points as already faired — and answers the CAD
/// file `fair curve -o NAME.EXT` would write, as an attachment; the report's `cad` object is
/// in the `X-Fair-Cad` header. The page sends the request of the step that made the current
/// result, so that the file holds that step's own curve.
fn cad_file(catalog: &fairing::catalog::Catalog, body: &[u8]) -> Answer {
    let body: CadBody = parse_body(body)?;
    let format: cad::Format = body.format.parse().map_err(|_| {
        Response::error(
            400,
            format!(
                "format: `{}` is not a CAD format (iges, step or dxf)",
                body.format
            ),
        )
    })?;
    let grid_size = match (body.rows, body.columns) {
        (Some(rows), Some(columns)) => Some((rows, columns)),
        (None, None) => None,
        _ => {
            return Err(Response::error(
                400,
                "request body: a grid needs both `rows` and `columns`",
            ))
        }
    };
    limits::iterations(&body.params)?;
    let request = fair_door::cad::CadRequest {
        output: Some(format!("points.{}", format.extension())),
        format: None,
        control_points: body.control_points,
        fit_tolerance: body.fit_tolerance,
        units: None,
        step_schema: None,
        batch: false,
    };
    let mut target = fair_door::cad::target(&request, grid_size.is_some())
        .map_err(failure)?
        .ok_or_else(|| Response::error(500, "no CAD target"))?;
    let name = body.name.unwrap_or_else(|| "points".into());
    let (name, made) = if let Some((rows, columns)) = grid_size {
        if body.kind.is_some() {
            return Err(Response::error(
                400,
                "kind: the input is a surface grid; kind is for curves",
            ));
        }
        let grid = grid_points(rows, columns, &body.points.0)?;
        limits::surface_nodes(rows, columns)?;
        let (grid, record, method) = if body.fair {
            let input = engine::surface_input(&name, grid);
            let job = Job {
                method: body.method,
                params: body.params,
                constraints: body.constraints.into_job()?,
            };
            let result = engine::fair_surface(catalog, &input, &job).map_err(failure)?;
            (result.grid, result.report.curve, result.report.method)
        } else {
            (grid, Value::Null, "points".to_string())
        };
        let stem = format!("{}-{method}", file_stem(&name));
        target.path = format!("{stem}.{}", format.extension());
        let made = fair_door::cad::export_surface(&target, &record, &grid, &stem).map_err(failure)?;
        (stem, made)
    } else {
        let kind = kind_of(body.kind.as_deref())?;
        limits::curve_work(catalog, body.points.0.len(), body.method.as_deref(), &body.params)?;
        let input = engine::curve_input(&name, curve_points(&body.points.0)?);
        let (points, record, kind, method) = if body.fair {
            let job = Job {
                method: body.method,
                params: body.params,
                constraints: body.constraints.into_job()?,
            };
            let result = engine::fair_curve(catalog, &input, kind, &job).map_err(failure)?;
            (
                result.points,
                result.report.curve,
                result.kind,
                result.report.method,
            )
        } else {
            let data = input.data();
            data.require_at_least(fair_door::curve::MIN_CURVE_POINTS, "a curve")
                .map_err(failure)?;
            let kind = fair_door::kind::resolve(kind, &data).map_err(failure)?;
            (input.points, Value::Null, kind, "points".to_string())
        };
        let stem = format!("{}-{method}", file_stem(&name));
        target.path = format!("{stem}.{}", format.extension());
        let made = fair_door::cad::export_curve(&target, &record, &points, kind, &stem)
            .map_err(|e| failure(fair_door::measure::in_file(e, &name)))?;
        (stem, made)
    };
    let content_type = match format {
        cad::Format::Iges => "model/iges",
        cad::Format::Step => "model/step",
        cad::Format::Dxf => "image/vnd.dxf",
    };
    Ok(Response {
        status: 200,
        content_type,
        headers: vec![
            (
                "Content-Disposition",
                format!("attachment; filename=\"{name}.{}\"", format.extension()),
            ),
            ("X-Fair-Cad", made.summary.to_string()),
        ],
        body: made.text.into_bytes(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn post(path: &str, body: &str) -> Response {
        let request = Request {
            method: "POST".into(),
            path: path.into(),
            content_type: Some("application/json".into()),
            body: body.as_bytes().to_vec(),
        };
        handle(&request, &Context::default())
    }

    fn message(response: &Response) -> String {
        let value: Value = serde_json::from_slice(&response.body).unwrap();
        value["error"].as_str().unwrap().to_string()
    }

    #[test]
    fn percent_decoding() {
        assert_eq!(percent_decode("a%20b%2Fc").as_deref(), Some("a b/c"));
        assert_eq!(percent_decode("%2e%2e/x").as_deref(), Some("../x"));
        assert_eq!(percent_decode("%zz"), None);
        assert_eq!(percent_decode("%2"), None);
        assert_eq!(percent_decode("%ff"), None);
    }

    #[test]
    fn request_errors_name_the_request_fields() {
        let points = "[[0,0],[1,1],[2,0],[3,1],[4,0]]";
        let r = post(
            "/api/curve",
            &format!(r#"{{"points": {points}, "constraints": {{"fixed": [9]}}}}"#),
        );
        assert_eq!(r.status, 400);
        assert!(
            message(&r).starts_with("constraints.fixed: index 9 is past the last point"),
            "{}",
            message(&r)
        );
        let r = post(
            "/api/curve",
            &format!(r#"{{"points": {points}, "method": "zz"}}"#),
        );
        assert_eq!(r.status, 400);
        assert!(
            message(&r).contains("unknown curve method `zz`"),
            "{}",
            message(&r)
        );
        let r = post(
            "/api/curve",
            &format!(r#"{{"points": {points}, "params": {{"zz": 1}}}}"#),
        );
        assert!(
            message(&r).starts_with("params: `zz` is not a parameter of `jump-lsq`"),
            "{}",
            message(&r)
        );
        let r = post("/api/curve", r#"{"points": [[0, NaN]]}"#);
        assert_eq!(r.status, 400);
        assert!(message(&r).contains("NaN"), "{}", message(&r));
        let r = post(
            "/api/surface",
            r#"{"rows": 2, "columns": 2, "points": [[0,0,0]]}"#,
        );
        assert_eq!(r.status, 400);
        assert!(message(&r).contains("rows × columns"), "{}", message(&r));
    }
}
