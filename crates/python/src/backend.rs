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

use fair_cli::args::{ClampEnds, FairArgs, IndexList, KindArg, Setting};
use fair_cli::commands::{curve, inspect, surface};
use fair_cli::input::{CurveInput, Delimiter, Grid, InputFormat, Points, SurfaceInput};
use fair_cli::Error;
use fairing::catalog::{Catalog, ConfigFile, MethodKind};

/// The methods, criteria and indicators the bindings run: the library's built-in catalogue,
/// the one `fair` runs, made once per process.
pub fn catalog() -> &'static Catalog {
    static CATALOG: OnceLock<Catalog> = OnceLock::new();
    CATALOG.get_or_init(Catalog::builtin)
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
            .replace("`fair methods` lists them", "`fair.methods()` lists them");
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
pub fn kind_argument(kind: Option<&str>) -> Result<KindArg> {
    match kind {
        None | Some("auto") => Ok(KindArg::Auto),
        Some("function") => Ok(KindArg::Function),
        Some("parametric") => Ok(KindArg::Parametric),
        Some(other) => Err(Failure::bad_input(format!(
            "kind: `{other}` is not a kind of curve (auto, function or parametric)"
        ))),
    }
}

/// `clamp_ends=`: `None`, `"g0"`, `"g1"` or `"g2"`.
pub fn clamp_argument(clamp: Option<&str>) -> Result<Option<ClampEnds>> {
    match clamp {
        None => Ok(None),
        Some("g0") => Ok(Some(ClampEnds::G0)),
        Some("g1") => Ok(Some(ClampEnds::G1)),
        Some("g2") => Ok(Some(ClampEnds::G2)),
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
    /// `--set NAME=VALUE`, in order.
    pub params: Vec<(String, String)>,
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
}

impl Options {
    /// The command line these options stand for (`input` is only a name for messages).
    fn args(&self, input: &str) -> Result<FairArgs> {
        let index_list = |what: &str, list: &Option<Vec<usize>>| -> Result<Option<IndexList>> {
            let Some(list) = list else { return Ok(None) };
            for (k, i) in list.iter().enumerate() {
                if list[..k].contains(i) {
                    return Err(Failure::bad_input(format!("{what}: index {i} appears twice")));
                }
            }
            Ok(Some(IndexList(list.clone())))
        };
        if let Some(t) = self.tolerance {
            if !(t.is_finite() && t > 0.0) {
                return Err(Failure::bad_input(format!(
                    "tolerance: {t} must be a finite number greater than 0"
                )));
            }
        }
        let mut settings = Vec::with_capacity(self.params.len());
        for (name, value) in &self.params {
            let setting = fair_cli::args::parse_setting(&format!("{name}={value}"))
                .map_err(|e| Failure::bad_input(format!("params: {e}")))?;
            settings.push(Setting {
                name: setting.name,
                value: setting.value,
            });
        }
        Ok(FairArgs {
            input: input.into(),
            method: self.method.clone(),
            kind: kind_argument(self.kind.as_deref())?,
            columns: None,
            config: None,
            settings,
            fixed: index_list("fixed", &self.fixed)?,
            points: index_list("points_to_fix", &self.bad_points)?,
            tolerance: self.tolerance,
            clamp_ends: clamp_argument(self.clamp_ends.as_deref())?,
            output: None,
            report: None,
            plot: None,
            quiet: true,
            print_config: false,
            batch: false,
            cad: Default::default(),
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

/// Checks the shape and values of curve points and makes the command's input of them.
fn curve_input(points: &Coordinates) -> Result<CurveInput> {
    let rows = points.rows();
    let planar = |v: &[f64]| curve_repr::Vec2::new(v[0], v[1]);
    let spatial = |v: &[f64]| curve_repr::Vec3::new(v[0], v[1], v[2]);
    let chunks = points.values.chunks_exact(points.dimension.max(1));
    let library = match points.dimension {
        2 => Points::Planar(chunks.map(planar).collect()),
        3 => Points::Spatial(chunks.map(spatial).collect()),
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
    debug_assert_eq!(library.len(), rows);
    Ok(CurveInput {
        points: library,
        format: InputFormat::Csv {
            header: None,
            delimiter: Delimiter::Comma,
            layout: fair_cli::input::columns::Layout {
                columns: points.dimension,
                coordinates: (0..points.dimension).collect(),
                names: ["x", "y", "z"][..points.dimension]
                    .iter()
                    .map(|s| s.to_string())
                    .collect(),
                labels: Vec::new(),
            },
        },
        source: POINTS.into(),
        lines: Vec::new(),
        notes: Vec::new(),
    })
}

/// Reads back the command's output text (comma-separated rows of shortest round-trip numbers,
/// so the values are bit for bit the library's). `skip` leading columns are dropped (a grid's
/// `i,j`).
fn parse_rows(text: &str, dimension: usize, skip: usize) -> Result<Vec<f64>> {
    let mut values = Vec::new();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != skip + dimension {
            return Err(internal(format!("unexpected output row `{line}`")));
        }
        for field in &fields[skip..] {
            values.push(
                field
                    .trim()
                    .parse::<f64>()
                    .map_err(|_| internal(format!("unexpected output number `{field}`")))?,
            );
        }
    }
    Ok(values)
}

fn internal(message: String) -> Failure {
    Failure {
        message: format!("internal error: {message}"),
        bad_input: false,
    }
}

fn report_value(report: &fair_cli::report::Report) -> Result<serde_json::Value> {
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
pub fn fair_curve(points: &Coordinates, options: &Options) -> Result<Faired> {
    let mut options = options.clone();
    let mut input = curve_input(points)?;
    let mut repeated = false;
    if options.closed {
        let has_closed = options.config.is_none()
            && options
                .method
                .as_deref()
                .and_then(|m| catalog().method(MethodKind::Curve, m).ok())
                .is_some_and(|m| m.parameter(CLOSED).is_some());
        if has_closed {
            if let Some((_, value)) = options.params.iter().find(|(n, _)| n == CLOSED) {
                if value != "true" {
                    return Err(Failure::bad_input(format!(
                        "params: `closed` = `{value}` contradicts closed=True"
                    )));
                }
            } else {
                options.params.push((CLOSED.into(), "true".into()));
            }
        } else if input.len() > 1 {
            let first = input.points.coordinates(0).unwrap_or_default();
            let last = input.points.coordinates(input.len() - 1).unwrap_or_default();
            if first != last {
                match &mut input.points {
                    Points::Planar(p) => p.push(p[0]),
                    Points::Spatial(p) => p.push(p[0]),
                }
                repeated = true;
            }
        }
    }
    let args = options.args(POINTS)?;
    let config = options.config.as_ref().map(|c| &c.0);
    let faired = curve::process(catalog(), &input, &args, config)?;
    let mut values = parse_rows(&faired.points_text, points.dimension, 0)?;
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

/// Checks a grid's values and makes the command's input of it (`rows × columns` points).
fn surface_input(grid: &Coordinates, rows: usize, columns: usize) -> Result<SurfaceInput> {
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
    Ok(SurfaceInput {
        grid: Grid {
            rows,
            columns,
            points,
        },
        offset: (0, 0),
        order: (0..rows)
            .flat_map(|i| (0..columns).map(move |j| (i, j)))
            .collect(),
        header: None,
        delimiter: Delimiter::Comma,
        source: GRID.into(),
        lines: Vec::new(),
    })
}

/// `fair surface` on a `rows × columns` grid of 3D points (row-major): the faired grid and
/// the report. Indices in `fixed`/`bad_points` count row by row (k = i · columns + j).
pub fn fair_surface(grid: &Coordinates, rows: usize, columns: usize, options: &Options) -> Result<Faired> {
    if options.kind.is_some() || options.closed {
        return Err(Failure::bad_input(
            "kind and closed apply to curves only; a surface grid has neither",
        ));
    }
    let input = surface_input(grid, rows, columns)?;
    let args = options.args(GRID)?;
    let config = options.config.as_ref().map(|c| &c.0);
    let faired = surface::process(catalog(), &input, &args, config)?;
    let values = parse_rows(&faired.grid_text, 3, 2)?;
    if values.len() != grid.values.len() {
        return Err(internal("the faired grid has another size".into()));
    }
    Ok(Faired {
        points: Coordinates { dimension: 3, values },
        report: report_value(&faired.report)?,
    })
}

/// `fair inspect` on curve points: the report (`method` = `inspect`, `after` = `before`).
pub fn inspect_curve(points: &Coordinates, kind: Option<&str>) -> Result<serde_json::Value> {
    let kind = kind_argument(kind)?;
    let input = curve_input(points)?;
    let text = fair_cli::output::format_curve(&input, &input.points)?;
    let source = fair_cli::input::Source::from_text(POINTS, &text);
    report_value(&inspect::inspect(catalog(), &source, kind, false, None)?)
}

/// `fair inspect --surface` on a `rows × columns` grid: the report.
pub fn inspect_surface(grid: &Coordinates, rows: usize, columns: usize) -> Result<serde_json::Value> {
    let input = surface_input(grid, rows, columns)?;
    let text = fair_cli::output::format_surface(&input, &input.grid)?;
    let source = fair_cli::input::Source::from_text(GRID, &text);
    report_value(&inspect::inspect(catalog(), &source, KindArg::Auto, true, None)?)
}

/// The methods, as `fair methods` lists them (from the catalogue, each method's settings
/// type): name, kind (`curve`/`surface`), paper, summary and the parameters (name, default as
/// text, default as a value, meaning, JSON Schema), in the catalogue's order.
pub fn methods() -> Vec<serde_json::Value> {
    [MethodKind::Curve, MethodKind::Surface]
        .into_iter()
        .flat_map(|kind| catalog().methods(kind))
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
        (
            "function",
            curve::default_method(fair_cli::kind::CurveKind::Function),
        ),
        (
            "parametric",
            curve::default_method(fair_cli::kind::CurveKind::Parametric),
        ),
        ("surface", surface::DEFAULT_METHOD),
    ])
}

/// What `fair.export_cad` writes: the file, its format (`None`: by the extension) and an
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

impl CadRequest {
    /// The command's CAD target for these options, checked as the command checks them.
    fn target(&self, surface: bool) -> Result<fair_cli::cad_file::CadTarget> {
        let mut args = Options::default().args(POINTS)?;
        args.output = Some(self.path.clone());
        args.cad.cad = self
            .format
            .as_deref()
            .map(fair_cli::args::parse_cad_format)
            .transpose()
            .map_err(|e| Failure::bad_input(format!("format: {e}")))?;
        args.cad.control_points = self.control_points;
        if let Some(d) = self.fit_tolerance {
            if !(d.is_finite() && d > 0.0) {
                return Err(Failure::bad_input(format!(
                    "fit_tolerance: {d} must be a finite number greater than 0"
                )));
            }
        }
        args.cad.fit_tolerance = self.fit_tolerance;
        fair_cli::cad_file::target(&args, surface)?.ok_or_else(|| {
            Failure::bad_input(format!(
                "path: `{}` names no CAD format by its extension (.igs, .iges, .step, .stp, .dxf); give format=",
                self.path
            ))
        })
    }
}

/// The file's stem, as the shape's name inside it.
fn shape_name(path: &str) -> String {
    fair_cli::commands::curve::stem(path)
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
    let input = curve_input(points)?;
    input.require_at_least(curve::MIN_CURVE_POINTS, "a curve")?;
    let kind = fair_cli::kind::resolve(kind_argument(kind)?, &input)?;
    let made =
        fair_cli::cad_file::export_curve(&target, record, &input.points, kind, &shape_name(&request.path))?;
    fair_cli::output::write_text(&request.path, &made.text)?;
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
    let input = surface_input(grid, rows, columns)?;
    surface::require_grid(&input)?;
    let made = fair_cli::cad_file::export_surface(&target, record, &input.grid, &shape_name(&request.path))?;
    fair_cli::output::write_text(&request.path, &made.text)?;
    Ok(made.summary)
}

/// Reads an IGES, STEP or DXF file (`format`: by the extension when `None`): `{"units",
/// "tolerance", "curves": [{"name", "degree", "knots", "control_points", "weights"}],
/// "surfaces": [{"name", "degrees", "u_knots", "v_knots", "control_points" (rows of rows),
/// "weights"}]}`, every number as read (the writers' round trip is exact).
pub fn read_cad(path: &str, format: Option<&str>) -> Result<serde_json::Value> {
    let format = format
        .map(fair_cli::args::parse_cad_format)
        .transpose()
        .map_err(|e| Failure::bad_input(format!("format: {e}")))?;
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
