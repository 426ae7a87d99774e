//! The one place where the bindings call into the framework.
//!
//! Everything here is plain Rust (no Python types), so that it runs with the GIL released and
//! so that switching the library path is a local change. Each call does exactly what the
//! command does for the same input: [`fair_curve`] is `fair curve FILE` on a file holding the
//! same points, [`fair_surface`] is `fair surface`, [`inspect_curve`]/[`inspect_surface`] are
//! `fair inspect`, and the reports are the command's reports, field for field.
//!
//! Points cross this boundary as [`Coordinates`]: a flat row-major `Vec<f64>` and a
//! dimension, the layout of a C-contiguous NumPy array, so that results become arrays
//! without a copy.

use std::collections::BTreeMap;

use std::sync::OnceLock;

use fair_door::curve::{default_method, CurveRequest, MIN_CURVE_POINTS};
use fair_door::measure::Detail;
use fair_door::surface::{SurfaceRequest, DEFAULT_METHOD};
use fair_door::{ConstraintRequest, CurveData, Error, GridData, KindChoice};
use fairing::catalog::{
    Catalog, ConfigFile, CurveKind, CurvePoints, GivenValue, Grid, MethodKind, ParameterMap,
};
use fairing::EndClamp;

/// The catalogue the module was built over, made once per process.
static CATALOG: OnceLock<Catalog> = OnceLock::new();

/// The methods, criteria and indicators the module's functions run and `Catalog()` starts
/// from: the library's built-in catalogue (the one `fair` runs), or a Rust user's own when
/// their module's init installed it first ([`install`]).
pub fn catalog() -> &'static Catalog {
    CATALOG.get_or_init(Catalog::builtin)
}

/// Makes `make()` the module's catalogue; the first call of a process wins (the module's
/// init calls it once, before any function runs).
pub fn install(make: fn() -> Catalog) {
    CATALOG.get_or_init(make);
}

/// What the points are called in messages (the command names the file instead).
pub const POINTS: &str = "points";
/// What a surface grid is called in messages.
pub const GRID: &str = "grid";

/// Points as a flat row-major array of `dimension` columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Coordinates {
    /// Columns per point: 2 or 3 for curves, 3 for grids.
    pub dimension: usize,
    /// `rows × dimension` values, row after row.
    pub values: Vec<f64>,
}

impl Coordinates {
    /// Number of points.
    pub fn rows(&self) -> usize {
        self.values.len() / self.dimension.max(1)
    }
}

/// Why a call failed: the command's one-line message, and whether it is the caller's to fix
/// (the command's exit status 2) or a failure of the framework (exit status 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// The message, one line.
    pub message: String,
    /// Bad input, arguments or parameters (exit status 2 in the command).
    pub bad_input: bool,
}

impl Failure {
    /// A failure of the caller's input.
    pub fn bad_input(message: impl Into<String>) -> Failure {
        Failure {
            message: message.into(),
            bad_input: true,
        }
    }
}

impl From<Error> for Failure {
    fn from(error: Error) -> Failure {
        let bad_input = error.exit_code() == 2;
        let error = match error {
            Error::Argument { option, message } => Error::Argument {
                option: argument_name(option),
                message,
            },
            Error::Parameter { origin, message } if origin == "--set" => Error::Parameter {
                origin: "params".into(),
                message,
            },
            other => other,
        };
        let message = error
            .one_line()
            .replace("`fair methods` lists them", "`fairspline.methods()` lists them");
        Failure { message, bad_input }
    }
}

/// The Python argument that stands for a command-line option, for messages.
fn argument_name(option: &'static str) -> &'static str {
    match option {
        "--fixed" => "fixed",
        "--points" => "points_to_fix",
        "--tolerance" => "tolerance",
        "--clamp-ends" => "clamp_ends",
        "--kind" => "kind",
        "--method" => "method",
        "--set" => "params",
        "INPUT" => POINTS,
        "-o" => "path",
        "--cad" => "format",
        "--control-points" => "control_points",
        "--fit-tolerance" => "fit_tolerance",
        other => other,
    }
}

/// The result of a backend call.
pub type Result<T> = std::result::Result<T, Failure>;

/// `kind=` of a curve: `None`/`"auto"`, `"function"` or `"parametric"`.
pub fn kind_argument(kind: Option<&str>) -> Result<KindChoice> {
    match kind {
        None | Some("auto") => Ok(KindChoice::Auto),
        Some("function") => Ok(KindChoice::Function),
        Some("parametric") => Ok(KindChoice::Parametric),
        Some(other) => Err(Failure::bad_input(format!(
            "kind: `{other}` is not a kind of curve (auto, function or parametric)"
        ))),
    }
}

/// `clamp_ends=`: `None`, `"g0"`, `"g1"` or `"g2"`.
pub fn clamp_argument(clamp: Option<&str>) -> Result<Option<EndClamp>> {
    match clamp {
        None => Ok(None),
        Some("g0") => Ok(Some(EndClamp::G0)),
        Some("g1") => Ok(Some(EndClamp::G1)),
        Some("g2") => Ok(Some(EndClamp::G2)),
        Some(other) => Err(Failure::bad_input(format!(
            "clamp_ends: `{other}` is not an end condition (g0, g1 or g2)"
        ))),
    }
}

/// A parsed config file (TOML or JSON), as `--config` takes it.
#[derive(Debug, Clone)]
pub struct Config(ConfigFile);

impl Config {
    /// Parses config text; `name` appears in messages (`name:LINE: ...`), and a name ending in
    /// `.json` (or text starting with `{`) is read as JSON, anything else as TOML.
    pub fn parse(name: &str, text: &str) -> Result<Config> {
        ConfigFile::parse(name, text)
            .map(Config)
            .map_err(|e| Error::from_fairing(e, name).into())
    }

    /// Reads a config file, as `--config PATH` does.
    pub fn read(path: &str) -> Result<Config> {
        ConfigFile::read(std::path::Path::new(path))
            .map(Config)
            .map_err(|e| Error::from_fairing(e, path).into())
    }

    /// The name messages use.
    pub fn name(&self) -> &str {
        &self.0.name
    }
}

/// Everything a fairing call takes besides the points: the command's options.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// `--method`; `None` for the default of the kind.
    pub method: Option<String>,
    /// `--kind` (curves only).
    pub kind: Option<String>,
    /// `--set NAME=VALUE`, in order: numbers and booleans as JSON values, strings as text.
    pub params: Vec<(String, GivenValue)>,
    /// `--fixed`.
    pub fixed: Option<Vec<usize>>,
    /// `--points`.
    pub bad_points: Option<Vec<usize>>,
    /// `--tolerance`.
    pub tolerance: Option<f64>,
    /// `--clamp-ends`.
    pub clamp_ends: Option<String>,
    /// `--config`.
    pub config: Option<Config>,
    /// The curve is a closed loop (its last point joins its first).
    pub closed: bool,
    /// `--corners` (`None`: detected).
    pub corners: Option<fairing::corners::Corners>,
}

impl Options {
    /// The parameters as the catalogue's map (given at `--set`, as on the command line),
    /// each name checked as the command checks `--set NAME=VALUE`.
    fn parameters(&self) -> Result<ParameterMap> {
        let mut map = ParameterMap::new();
        for (name, value) in &self.params {
            if name.is_empty()
                || !name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
            {
                return Err(Failure::bad_input(format!(
                    "params: parameter name `{name}` must be letters, digits, `_` or `-`"
                )));
            }
            let value = match value {
                GivenValue::Text(text) | GivenValue::Json(serde_json::Value::String(text)) => {
                    let text = text.trim();
                    if text.is_empty() {
                        return Err(Failure::bad_input(format!(
                            "params: parameter `{name}` has an empty value"
                        )));
                    }
                    GivenValue::Text(text.to_string())
                }
                other => other.clone(),
            };
            map.insert(name, value, "--set");
        }
        Ok(map)
    }

    /// Refuses a tolerance that is not a finite positive number.
    fn check_tolerance(&self) -> Result<()> {
        match self.tolerance {
            Some(t) if !(t.is_finite() && t > 0.0) => Err(Failure::bad_input(format!(
                "tolerance: {t} must be a finite number greater than 0"
            ))),
            _ => Ok(()),
        }
    }

    /// The constraints, checked as the command's option parser checks them.
    fn constraints(&self) -> Result<ConstraintRequest> {
        let index_list = |what: &str, list: &Option<Vec<usize>>| -> Result<Option<Vec<usize>>> {
            let Some(list) = list else { return Ok(None) };
            for (k, i) in list.iter().enumerate() {
                if list[..k].contains(i) {
                    return Err(Failure::bad_input(format!("{what}: index {i} appears twice")));
                }
            }
            Ok(Some(list.clone()))
        };
        Ok(ConstraintRequest {
            fixed: index_list("fixed", &self.fixed)?,
            bad_points: index_list("points_to_fix", &self.bad_points)?,
            tolerance: self.tolerance,
            clamp_ends: clamp_argument(self.clamp_ends.as_deref())?,
            corners: self.corners.clone(),
        })
    }

    /// The door's request for a curve (checked in the order the command's option parser
    /// checks: tolerance, parameters, kind, indices, ends).
    fn curve_request(&self) -> Result<CurveRequest> {
        self.check_tolerance()?;
        let settings = self.parameters()?;
        let kind = kind_argument(self.kind.as_deref())?;
        let constraints = self.constraints()?;
        Ok(CurveRequest {
            method: self.method.clone(),
            kind,
            settings,
            config: self.config.as_ref().map(|c| c.0.clone()),
            constraints,
            samples: false,
        })
    }

    /// The door's request for a surface.
    fn surface_request(&self) -> Result<SurfaceRequest> {
        self.check_tolerance()?;
        let settings = self.parameters()?;
        let constraints = self.constraints()?;
        Ok(SurfaceRequest {
            method: self.method.clone(),
            settings,
            config: self.config.as_ref().map(|c| c.0.clone()),
            constraints,
            ..Default::default()
        })
    }
}

/// A faired curve or grid: the points (same layout as given) and the command's report.
#[derive(Debug, Clone, PartialEq)]
pub struct Faired {
    /// The faired points.
    pub points: Coordinates,
    /// The command's JSON report, as a value.
    pub report: serde_json::Value,
}

/// Checks the shape and values of curve points and makes the library's points of them.
fn curve_points(points: &Coordinates) -> Result<CurvePoints> {
    let planar = |v: &[f64]| curve_repr::Vec2::new(v[0], v[1]);
    let spatial = |v: &[f64]| curve_repr::Vec3::new(v[0], v[1], v[2]);
    let chunks = points.values.chunks_exact(points.dimension.max(1));
    let library = match points.dimension {
        2 => CurvePoints::Planar(chunks.map(planar).collect()),
        3 => CurvePoints::Spatial(chunks.map(spatial).collect()),
        d => {
            return Err(Failure::bad_input(format!(
                "{POINTS}: a curve's points have 2 or 3 coordinates, got {d} columns"
            )))
        }
    };
    if let Some(i) = library.first_non_finite() {
        return Err(Failure::bad_input(format!(
            "{POINTS}: point {i} has a coordinate that is not finite: {:?}",
            &points.values[i * points.dimension..(i + 1) * points.dimension]
        )));
    }
    Ok(library)
}

/// The points' coordinates, row after row.
fn flat(points: &CurvePoints) -> Vec<f64> {
    match points {
        CurvePoints::Planar(p) => p.iter().flat_map(|v| [v.x, v.y]).collect(),
        CurvePoints::Spatial(p) => p.iter().flat_map(|v| [v.x, v.y, v.z]).collect(),
    }
}

fn internal(message: String) -> Failure {
    Failure {
        message: format!("internal error: {message}"),
        bad_input: false,
    }
}

fn report_value(report: &fair_door::Report) -> Result<serde_json::Value> {
    report.check_finite()?;
    serde_json::to_value(report).map_err(|e| internal(e.to_string()))
}

/// The catalogue's name of a parameter that says a curve is closed.
const CLOSED: &str = "closed";

/// `fair curve` on these points: the faired points and the report.
///
/// `closed`: a method with a `closed` parameter (two-phase) gets `closed=true`; any other
/// method gets the loop the way the command takes a closed curve, its first point repeated
/// at the end, and the repeat is dropped from the returned points (the report is the
/// command's for that input, so its `n` counts the repeat).
pub fn fair_curve(catalog: &Catalog, points: &Coordinates, options: &Options) -> Result<Faired> {
    let mut options = options.clone();
    let mut library = curve_points(points)?;
    let mut repeated = false;
    if options.closed {
        let has_closed = options.config.is_none()
            && options
                .method
                .as_deref()
                .and_then(|m| catalog.method(MethodKind::Curve, m).ok())
                .is_some_and(|m| m.parameter(CLOSED).is_some());
        if has_closed {
            if let Some((_, value)) = options.params.iter().find(|(n, _)| n == CLOSED) {
                let value = value.text();
                if value.trim() != "true" {
                    return Err(Failure::bad_input(format!(
                        "params: `closed` = `{value}` contradicts closed=True"
                    )));
                }
            } else {
                options
                    .params
                    .push((CLOSED.into(), GivenValue::Json(serde_json::Value::Bool(true))));
            }
        } else if library.len() > 1 {
            let first = library.coordinates(0).unwrap_or_default();
            let last = library.coordinates(library.len() - 1).unwrap_or_default();
            if first != last {
                match &mut library {
                    CurvePoints::Planar(p) => p.push(p[0]),
                    CurvePoints::Spatial(p) => p.push(p[0]),
                }
                repeated = true;
            }
        }
    }
    let request = options.curve_request()?;
    let faired = fair_door::curve(catalog, &CurveData::new(&library, POINTS), &request)?;
    let mut values = flat(&faired.points);
    if repeated {
        values.truncate(values.len() - points.dimension);
    }
    if values.len() != points.values.len() {
        return Err(internal(format!(
            "{} values back for {} given",
            values.len(),
            points.values.len()
        )));
    }
    Ok(Faired {
        points: Coordinates {
            dimension: points.dimension,
            values,
        },
        report: report_value(&faired.report)?,
    })
}

/// Checks a grid's values and makes the library's grid of it (`rows × columns` points).
fn grid_of(grid: &Coordinates, rows: usize, columns: usize) -> Result<Grid> {
    if grid.dimension != 3 || grid.values.len() != rows * columns * 3 {
        return Err(internal(format!(
            "grid of {} values is not {rows} × {columns} × 3",
            grid.values.len()
        )));
    }
    let points: Vec<curve_repr::Vec3> = grid
        .values
        .chunks_exact(3)
        .map(|v| curve_repr::Vec3::new(v[0], v[1], v[2]))
        .collect();
    if let Some(k) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(Failure::bad_input(format!(
            "{GRID}: point ({}, {}) has a coordinate that is not finite: {:?}",
            k / columns,
            k % columns,
            &grid.values[3 * k..3 * k + 3]
        )));
    }
    Ok(Grid {
        rows,
        columns,
        points,
    })
}

/// `fair surface` on a `rows × columns` grid of 3D points (row-major): the faired grid and
/// the report. Indices in `fixed`/`bad_points` count row by row (k = i · columns + j).
pub fn fair_surface(
    catalog: &Catalog,
    grid: &Coordinates,
    rows: usize,
    columns: usize,
    options: &Options,
) -> Result<Faired> {
    if options.kind.is_some() || options.closed {
        return Err(Failure::bad_input(
            "kind and closed apply to curves only; a surface grid has neither",
        ));
    }
    let library = grid_of(grid, rows, columns)?;
    let request = options.surface_request()?;
    let data = GridData {
        grid: &library,
        source: GRID,
    };
    let faired = fair_door::surface(catalog, &data, &request)?;
    let values: Vec<f64> = faired.grid.points.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    if values.len() != grid.values.len() {
        return Err(internal("the faired grid has another size".into()));
    }
    Ok(Faired {
        points: Coordinates { dimension: 3, values },
        report: report_value(&faired.report)?,
    })
}

/// `fair inspect` on curve points: the report (`method` = `inspect`, `after` = `before`).
/// Errors about a point name it as the command names the line of a file holding the points
/// one per line (`points:LINE: ...`).
pub fn inspect_curve(
    catalog: &Catalog,
    points: &Coordinates,
    kind: Option<&str>,
) -> Result<serde_json::Value> {
    let kind = kind_argument(kind)?;
    let library = curve_points(points)?;
    let lines: Vec<usize> = (1..=library.len()).collect();
    let data = CurveData {
        points: &library,
        source: POINTS,
        lines: &lines,
    };
    let detail = Detail {
        plot: false,
        record: true,
    };
    report_value(&fair_door::inspect_curve(catalog, &data, kind, detail)?.report)
}

/// `fair inspect --surface` on a `rows × columns` grid: the report.
pub fn inspect_surface(grid: &Coordinates, rows: usize, columns: usize) -> Result<serde_json::Value> {
    let library = grid_of(grid, rows, columns)?;
    let data = GridData {
        grid: &library,
        source: GRID,
    };
    report_value(&fair_door::inspect_surface(&data)?.report)
}

/// The methods, as `fair methods` lists them (from the catalogue, each method's settings
/// type): name, kind (`curve`/`surface`), paper, summary and the parameters (name, default as
/// text, default as a value, meaning, JSON Schema), in the catalogue's order.
pub fn methods(catalog: &Catalog) -> Vec<serde_json::Value> {
    [MethodKind::Curve, MethodKind::Surface]
        .into_iter()
        .flat_map(|kind| catalog.methods(kind))
        .map(|m| {
            let parameters: Vec<serde_json::Value> = m
                .parameters()
                .iter()
                .map(|p| {
                    serde_json::json!({
                        "name": p.name,
                        "default": p.default,
                        "value": p.default_value,
                        "meaning": p.meaning,
                        "schema": p.schema,
                    })
                })
                .collect();
            serde_json::json!({
                "name": m.name(),
                "kind": m.info().kind.name(),
                "paper": m.info().paper,
                "summary": m.info().summary,
                "parameters": parameters,
            })
        })
        .collect()
}

/// The default method for a curve of `kind` and for surfaces, as the command chooses them.
pub fn default_methods() -> BTreeMap<&'static str, &'static str> {
    BTreeMap::from([
        ("function", default_method(CurveKind::Function)),
        ("parametric", default_method(CurveKind::Parametric)),
        ("surface", DEFAULT_METHOD),
    ])
}

/// What `fairspline.export_cad` writes: the file, its format (`None`: by the extension) and an
/// optional rebuild — `fair curve -o PATH [--cad FORMAT] [--control-points N]
/// [--fit-tolerance D]`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CadRequest {
    /// The file to write.
    pub path: String,
    /// `iges`, `step` or `dxf`; `None` for the extension's.
    pub format: Option<String>,
    /// `--control-points`.
    pub control_points: Option<usize>,
    /// `--fit-tolerance`.
    pub fit_tolerance: Option<f64>,
}

/// Parses a CAD format's name: iges/igs, step/stp or dxf, any case.
fn cad_format(text: &str) -> Result<cad::Format> {
    text.parse::<cad::Format>().map_err(|_| {
        Failure::bad_input(format!(
            "format: `{text}` is not a CAD format (iges, step or dxf)"
        ))
    })
}

impl CadRequest {
    /// The door's CAD target for these options, checked as the command checks them.
    fn target(&self, surface: bool) -> Result<fair_door::cad::CadTarget> {
        let format = self.format.as_deref().map(cad_format).transpose()?;
        if let Some(d) = self.fit_tolerance {
            if !(d.is_finite() && d > 0.0) {
                return Err(Failure::bad_input(format!(
                    "fit_tolerance: {d} must be a finite number greater than 0"
                )));
            }
        }
        let request = fair_door::cad::CadRequest {
            output: Some(self.path.clone()),
            format,
            control_points: self.control_points,
            fit_tolerance: self.fit_tolerance,
            units: None,
            step_schema: None,
            batch: false,
        };
        fair_door::cad::target(&request, surface)?.ok_or_else(|| {
            Failure::bad_input(format!(
                "path: `{}` names no CAD format by its extension (.igs, .iges, .step, .stp, .dxf); give format=",
                self.path
            ))
        })
    }
}

/// Writes a CAD file's text as the command writes `-o`: completely or not at all
/// ([`cad::atomic`]).
fn write_text(path: &str, text: &str) -> Result<()> {
    cad::atomic::write_text(path, text).map_err(|e| Error::from_write(&e).into())
}

/// Writes a curve as `fair curve -o FILE.igs` does: `record` is the report's `curve` of a
/// fairing (its method's own curve is written when the points lie on it), or `null` for
/// points taken as they are (the spline the report measures). Returns the report's `cad`
/// object. O(n) without a rebuild.
pub fn export_cad_curve(
    points: &Coordinates,
    record: &serde_json::Value,
    kind: Option<&str>,
    request: &CadRequest,
) -> Result<serde_json::Value> {
    let target = request.target(false)?;
    let library = curve_points(points)?;
    let data = CurveData::new(&library, POINTS);
    data.require_at_least(MIN_CURVE_POINTS, "a curve")?;
    let kind = fair_door::kind::resolve(kind_argument(kind)?, &data)?;
    let made = fair_door::cad::export_curve(
        &target,
        record,
        &library,
        kind,
        &fair_door::cad::stem(&request.path),
    )?;
    write_text(&request.path, &made.text)?;
    Ok(made.summary)
}

/// Writes a `rows × columns` grid as `fair surface -o FILE.step` does (see
/// [`export_cad_curve`]; IGES or STEP, no rebuild). Returns the report's `cad` object.
pub fn export_cad_surface(
    grid: &Coordinates,
    rows: usize,
    columns: usize,
    record: &serde_json::Value,
    request: &CadRequest,
) -> Result<serde_json::Value> {
    let target = request.target(true)?;
    let library = grid_of(grid, rows, columns)?;
    GridData {
        grid: &library,
        source: GRID,
    }
    .require_grid()?;
    let made =
        fair_door::cad::export_surface(&target, record, &library, &fair_door::cad::stem(&request.path))?;
    write_text(&request.path, &made.text)?;
    Ok(made.summary)
}

/// Reads an IGES, STEP or DXF file (`format`: by the extension when `None`): `{"units",
/// "tolerance", "curves": [{"name", "degree", "knots", "control_points", "weights"}],
/// "surfaces": [{"name", "degrees", "u_knots", "v_knots", "control_points" (rows of rows),
/// "weights"}]}`, every number as read (the writers' round trip is exact).
pub fn read_cad(path: &str, format: Option<&str>) -> Result<serde_json::Value> {
    let format = format.map(cad_format).transpose()?;
    let model = cad::read_path(path, format).map_err(|e| Failure::bad_input(e.to_string()))?;
    let curves: Vec<serde_json::Value> = model
        .curves
        .iter()
        .map(|c| {
            let points: Vec<[f64; 3]> = c.curve.control_points().iter().map(|p| [p.x, p.y, p.z]).collect();
            serde_json::json!({
                "name": c.name,
                "degree": c.curve.degree(),
                "knots": c.curve.knots(),
                "control_points": points,
                "weights": c.curve.weights(),
            })
        })
        .collect();
    let surfaces: Vec<serde_json::Value> = model
        .surfaces
        .iter()
        .map(|s| {
            let (u, v) = s.surface.knot_vectors();
            let points: Vec<Vec<[f64; 3]>> = s
                .control_rows()
                .iter()
                .map(|row| row.iter().map(|p| [p.x, p.y, p.z]).collect())
                .collect();
            serde_json::json!({
                "name": s.name,
                "degrees": [s.surface.degrees().0, s.surface.degrees().1],
                "u_knots": u.knots(),
                "v_knots": v.knots(),
                "control_points": points,
                "weights": s.weight_rows(),
            })
        })
        .collect();
    Ok(serde_json::json!({
        "units": model.units,
        "tolerance": model.tolerance,
        "curves": curves,
        "surfaces": surfaces,
    }))
}
