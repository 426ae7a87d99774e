//! The command line of `fair` (`docs/CONTRACT.md`), as clap derive types.
//!
//! Values that need more than clap's own parsing (`--set NAME=VALUE`, index lists `2,5,7`,
//! a positive tolerance) have value parsers here whose messages say what was expected.

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// The whole command line.
#[derive(Debug, Clone, Parser)]
#[command(
    name = "fair",
    version,
    about = "Fair measured curves and surfaces: splines, fairness indicators, fairing strategies",
    propagate_version = true
)]
pub(crate) struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Clone, Subcommand)]
pub(crate) enum Command {
    /// Fair a curve (CSV x,y or x,y,z; JSON {"points": ...}; Selig .dat; - for stdin).
    Curve(FairArgs),
    /// Fair a surface grid (CSV i,j,x,y,z).
    Surface(FairArgs),
    /// Measure a curve or surface without changing it.
    Inspect(InspectArgs),
    /// Fair a ship's table of offsets (stations, waterlines, buttocks) as one hull.
    Lines(LinesArgs),
    /// List every method and its parameters.
    Methods,
    /// Run every method on the embedded data sets.
    Demo(DemoArgs),
    /// Fair interactively in the browser: a local web page over a JSON API.
    Serve(ServeArgs),
}

/// How to read a curve's points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum KindArg {
    /// A function y(x): x must increase strictly.
    Function,
    /// A parametric curve in 2D or 3D.
    Parametric,
    /// Function when x increases strictly (2D), else parametric.
    #[default]
    Auto,
}

/// What to keep at the ends of a curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ClampEnds {
    /// The end points.
    G0,
    /// The end points and end tangents.
    G1,
    /// The end points, tangents and curvatures.
    G2,
}

impl ClampEnds {
    /// The name `--clamp-ends` and config files take: `g0`, `g1` or `g2`.
    pub fn name(self) -> &'static str {
        match self {
            ClampEnds::G0 => "g0",
            ClampEnds::G1 => "g1",
            ClampEnds::G2 => "g2",
        }
    }
}

impl From<KindArg> for fair_door::KindChoice {
    fn from(kind: KindArg) -> Self {
        match kind {
            KindArg::Auto => fair_door::KindChoice::Auto,
            KindArg::Function => fair_door::KindChoice::Function,
            KindArg::Parametric => fair_door::KindChoice::Parametric,
        }
    }
}

impl From<ClampEnds> for fairing::EndClamp {
    fn from(clamp: ClampEnds) -> Self {
        match clamp {
            ClampEnds::G0 => fairing::EndClamp::G0,
            ClampEnds::G1 => fairing::EndClamp::G1,
            ClampEnds::G2 => fairing::EndClamp::G2,
        }
    }
}

/// Whether a path names a JSON-lines stream (`.jsonl`, `.ndjson`).
pub(crate) fn is_stream_name(path: &str) -> bool {
    let lower = path.to_ascii_lowercase();
    lower.ends_with(".jsonl") || lower.ends_with(".ndjson")
}

/// Options of `fair curve` and `fair surface`.
#[derive(Debug, Clone, Args)]
pub(crate) struct FairArgs {
    /// Input file, or - for standard input.
    #[arg(value_name = "INPUT")]
    pub input: String,
    /// Fairing method (`fair methods` lists the catalogue's and names the default for each
    /// kind of input).
    #[arg(long, short = 'm', value_name = "M")]
    pub method: Option<String>,
    /// How to read the points (curves only).
    #[arg(long, value_enum, default_value_t = KindArg::Auto)]
    pub kind: KindArg,
    /// The coordinate columns of a CSV curve by header name, abscissa first, e.g. z,y to fair
    /// a hull section as y(z) (written back in place; other columns are carried through).
    /// Default: the columns named x, y and z.
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    pub columns: Option<Vec<String>>,
    /// A TOML or JSON config: method parameters (the names `--set` takes), [constraints] and
    /// [[stage]] pipelines.
    // The comment is the command's help text, not rustdoc: its TOML table names are not links.
    #[allow(rustdoc::broken_intra_doc_links)]
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Set one method parameter, e.g. --set p=0.999 (repeatable; overrides --config).
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = parse_setting)]
    pub settings: Vec<Setting>,
    /// Indices (from 0) of points that must not move, e.g. 2,5,7.
    #[arg(long, value_name = "LIST", value_parser = parse_index_list)]
    pub fixed: Option<IndexList>,
    /// Indices (from 0) of the bad points, for the interactive methods, e.g. 4,5.
    #[arg(long, value_name = "LIST", value_parser = parse_index_list)]
    pub points: Option<IndexList>,
    /// No point moves farther than D.
    #[arg(long, value_name = "D", value_parser = parse_tolerance, allow_negative_numbers = true)]
    pub tolerance: Option<f64>,
    /// Keep the end points (g0), also the end tangents (g1), also the end curvatures (g2).
    #[arg(long, value_enum, value_name = "G")]
    pub clamp_ends: Option<ClampEnds>,
    /// Curves: points kept as corners (G0 breaks, each piece between them faired alone):
    /// auto (detected: a turn of 45° or more at every reach; the default), none, or indices
    /// from 0, e.g. 0,57.
    #[arg(long, value_name = "auto|none|LIST", value_parser = parse_corners)]
    pub corners: Option<fairing::corners::Corners>,
    /// Surfaces: hold an edge (u0, u1, v0, v1) of the faired net to a neighbour, e.g.
    /// --join u0=bow.csv:g1 — FILE a grid in any format `fair surface` reads, or an IGES/STEP
    /// surface; g0 positions, g1 (default) also the tangent plane, g2 also the curvature.
    /// Repeatable, one per edge; the surface jump-lsq holds it (the method by default).
    #[arg(long = "join", value_name = "EDGE=FILE[:G]", value_parser = parse_join)]
    pub joins: Vec<JoinArg>,
    /// Write the faired points here (same format as INPUT; - for standard output).
    #[arg(short = 'o', long = "output", value_name = "OUT")]
    pub output: Option<String>,
    /// Write the JSON report here.
    #[arg(long, value_name = "REPORT.json")]
    pub report: Option<PathBuf>,
    /// Write an SVG plot here.
    #[arg(long, value_name = "PLOT.svg")]
    pub plot: Option<PathBuf>,
    /// Print nothing on success, and no progress bar.
    #[arg(long, short = 'q')]
    pub quiet: bool,
    /// Print the config file (TOML) that this command line implies, every parameter with its
    /// value, and write nothing else. The input is faired first (its result discarded), so that
    /// a value the method refuses (out of range, say) exits 2 here too.
    #[arg(long)]
    pub print_config: bool,
    /// Read INPUT as a batch: a JSON-lines stream (one `{"points": ...}` object per line; `-`
    /// for standard input). A directory, or a file ending in `.jsonl`/`.ndjson`, is a batch
    /// without this flag. One report line per curve, to standard output or to the file
    /// --report names; -o names a directory for a directory batch (a JSON-lines file for a
    /// stream), --plot a directory.
    #[arg(long)]
    pub batch: bool,
    /// The faired result as a CAD file (`--cad`, `--control-points`, `--fit-tolerance`).
    #[command(flatten)]
    pub cad: CadArgs,
}

/// Options that write the faired result as an exact B-spline into a CAD file (IGES, STEP,
/// DXF). The settings themselves are `fair-cad`'s [`cad::CadSettings`].
#[derive(Debug, Clone, Default, PartialEq, Args)]
pub(crate) struct CadArgs {
    /// Write the faired curve or surface as an exact B-spline in this CAD format (iges, step,
    /// dxf) to the file -o names, instead of the points. Without it, -o's extension chooses
    /// (.igs/.iges, .step/.stp, .dxf). DXF holds curves only.
    #[arg(long, value_name = "FORMAT", value_parser = parse_cad_format)]
    pub cad: Option<cad::Format>,
    /// Rebuild the CAD curve with N control points: a least-squares fit of the faired points
    /// (The NURBS Book Eq. 9.63–9.69; end points kept).
    #[arg(long, value_name = "N")]
    pub control_points: Option<usize>,
    /// Rebuild the CAD curve with the fewest control points within D of every faired point
    /// (|Δy| for a function); the exact curve when no fit with at most half as many control
    /// points as points does.
    #[arg(long, value_name = "D", value_parser = parse_tolerance, allow_negative_numbers = true)]
    pub fit_tolerance: Option<f64>,
    /// The length unit the CAD file declares: mm (default), cm, m, um, in or ft. The
    /// coordinates are written as they are: give the unit the points are in (a ship's lines
    /// in metres: m).
    #[arg(long, value_name = "UNIT", value_parser = parse_units)]
    pub cad_units: Option<cad::Units>,
    /// The STEP application protocol: ap214 (default, read by every importer) or ap242.
    #[arg(long, value_name = "SCHEMA", value_parser = parse_step_schema)]
    pub step_schema: Option<cad::StepSchema>,
}

/// Parses `--cad-units`: a unit's short name.
fn parse_units(text: &str) -> Result<cad::Units, String> {
    cad::Units::ALL
        .into_iter()
        .find(|u| u.name().eq_ignore_ascii_case(text.trim()))
        .ok_or_else(|| format!("`{text}` is not a length unit (mm, cm, m, um, in or ft)"))
}

/// Parses `--step-schema`: ap214 or ap242.
fn parse_step_schema(text: &str) -> Result<cad::StepSchema, String> {
    match text.trim().to_ascii_lowercase().as_str() {
        "ap214" => Ok(cad::StepSchema::Ap214),
        "ap242" => Ok(cad::StepSchema::Ap242),
        _ => Err(format!("`{text}` is not a STEP schema (ap214 or ap242)")),
    }
}

/// Parses `--cad`: iges/igs, step/stp or dxf, any case.
pub(crate) fn parse_cad_format(text: &str) -> Result<cad::Format, String> {
    text.parse::<cad::Format>()
        .map_err(|_| format!("`{text}` is not a CAD format (iges, step or dxf)"))
}

impl FairArgs {
    /// Whether the input is a batch: `--batch`, a directory, or a JSON-lines stream
    /// (`.jsonl`, `.ndjson`).
    pub(crate) fn is_batch(&self) -> bool {
        self.batch || std::path::Path::new(&self.input).is_dir() || is_stream_name(&self.input)
    }

    /// The `--set`s as the catalogue's parameter map.
    pub(crate) fn parameters(&self) -> fairing::catalog::ParameterMap {
        fairing::catalog::ParameterMap::from_sets(
            self.settings.iter().map(|s| (s.name.as_str(), s.value.as_str())),
        )
    }

    /// `--fixed`, `--points`, `--tolerance`, `--clamp-ends`, `--corners` as the door takes them.
    pub(crate) fn constraints(&self) -> fair_door::ConstraintRequest {
        fair_door::ConstraintRequest {
            fixed: self.fixed.as_ref().map(|l| l.0.clone()),
            bad_points: self.points.as_ref().map(|l| l.0.clone()),
            tolerance: self.tolerance,
            clamp_ends: self.clamp_ends.map(Into::into),
            corners: self.corners.clone(),
        }
    }

    /// `-o`, `--cad`, `--control-points`, `--fit-tolerance` as the door's CAD request.
    pub(crate) fn cad_request(&self) -> fair_door::cad::CadRequest {
        fair_door::cad::CadRequest {
            output: self.output.clone(),
            format: self.cad.cad,
            control_points: self.cad.control_points,
            fit_tolerance: self.cad.fit_tolerance,
            units: self.cad.cad_units,
            step_schema: self.cad.step_schema,
            batch: self.is_batch(),
        }
    }

    /// How to read the input: `--columns`.
    pub(crate) fn read_options(&self) -> crate::input::ReadOptions {
        crate::input::ReadOptions::with_columns(self.columns.clone())
    }
}

/// Options of `fair lines`; the settings' meanings and defaults are `fair_lines::Settings`'s.
#[derive(Debug, Clone, Args)]
pub(crate) struct LinesArgs {
    /// The table of offsets (CSV).
    #[arg(value_name = "TABLE")]
    pub table: PathBuf,
    /// Write the faired table here, in the input's layout.
    #[arg(short = 'o', long = "output", value_name = "FAIRED_TABLE")]
    pub output: Option<PathBuf>,
    /// Write every faired line as its own CSV into this directory.
    #[arg(long, value_name = "DIR")]
    pub lines_dir: Option<PathBuf>,
    /// Write the JSON report here.
    #[arg(long, value_name = "REPORT.json")]
    pub report: Option<PathBuf>,
    /// Write the three views (body plan, half-breadth, profile) as SVG here.
    #[arg(long, value_name = "PLOT.svg")]
    pub plot: Option<PathBuf>,
    /// Write the hull surface here (.igs or .step).
    #[arg(long, value_name = "HULL.igs|.step")]
    pub hull: Option<PathBuf>,
    /// The table's rounding step (default: read from the table's digits).
    #[arg(long, value_name = "S")]
    pub step: Option<f64>,
    /// How far an offset may move before it is flagged.
    #[arg(long, value_name = "T")]
    pub tolerance: Option<f64>,
    /// The edge lines the hull is split along (knuckles), comma-separated.
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    pub knuckles: Option<Vec<String>>,
    /// Print nothing on success.
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

/// Options of `fair inspect`.
#[derive(Debug, Clone, Args)]
pub(crate) struct InspectArgs {
    /// Input file, or - for standard input.
    #[arg(value_name = "INPUT")]
    pub input: String,
    /// How to read the points.
    #[arg(long, value_enum, default_value_t = KindArg::Auto)]
    pub kind: KindArg,
    /// The coordinate columns of a CSV curve by header name, abscissa first, e.g. z,y.
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    pub columns: Option<Vec<String>>,
    /// Read INPUT as a surface grid i,j,x,y,z (also chosen when the CSV header is i,j,x,y,z).
    #[arg(long)]
    pub surface: bool,
    /// Write the JSON report here.
    #[arg(long, value_name = "REPORT.json")]
    pub report: Option<PathBuf>,
    /// Write an SVG plot here.
    #[arg(long, value_name = "PLOT.svg")]
    pub plot: Option<PathBuf>,
    /// Print nothing on success.
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

impl InspectArgs {
    /// How to read the input: `--columns`.
    pub(crate) fn read_options(&self) -> crate::input::ReadOptions {
        crate::input::ReadOptions::with_columns(self.columns.clone())
    }
}

/// Options of `fair demo`.
#[derive(Debug, Clone, Args)]
pub(crate) struct DemoArgs {
    /// Directory for the outputs, reports and plots (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out/demo")]
    pub out: PathBuf,
    /// Print nothing but errors.
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

/// One `--set NAME=VALUE`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Setting {
    /// The parameter name.
    pub name: String,
    /// Its value, as text (the method parses it).
    pub value: String,
}

/// A comma-separated list of point indices, in the order given, without duplicates.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub(crate) struct IndexList(pub Vec<usize>);

/// Parses `NAME=VALUE`: a name of letters, digits, `_` or `-`, and a non-empty value.
pub(crate) fn parse_setting(text: &str) -> Result<Setting, String> {
    let Some((name, value)) = text.split_once('=') else {
        return Err(format!("expected NAME=VALUE, got `{text}`"));
    };
    let (name, value) = (name.trim(), value.trim());
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        return Err(format!(
            "parameter name `{name}` must be letters, digits, `_` or `-`"
        ));
    }
    if value.is_empty() {
        return Err(format!("parameter `{name}` has an empty value"));
    }
    Ok(Setting {
        name: name.to_string(),
        value: value.to_string(),
    })
}

/// Parses `2,5,7` (spaces allowed) into point indices counted from 0.
pub(crate) fn parse_index_list(text: &str) -> Result<IndexList, String> {
    let mut indices = Vec::new();
    for field in text.split(',') {
        let field = field.trim();
        let index: usize = field
            .parse()
            .map_err(|_| format!("`{field}` in `{text}` is not a point index (a whole number from 0)"))?;
        if indices.contains(&index) {
            return Err(format!("index {index} appears twice in `{text}`"));
        }
        indices.push(index);
    }
    Ok(IndexList(indices))
}

/// One `--join`: the edge, the neighbour's file and the continuity.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct JoinArg {
    /// The faired net's edge.
    pub edge: fairing::strategies::JoinEdge,
    /// The neighbour's file.
    pub file: String,
    /// What is held (g1 unless given).
    pub continuity: fairing::strategies::Continuity,
}

/// Parses `--join EDGE=FILE[:g0|g1|g2]` (a trailing `:g0`/`:g1`/`:g2` is the continuity; any
/// other colon belongs to the file name).
pub(crate) fn parse_join(text: &str) -> Result<JoinArg, String> {
    use fairing::strategies::{Continuity, JoinEdge};
    let (edge, rest) = text
        .split_once('=')
        .ok_or_else(|| format!("`{text}` is not EDGE=FILE[:g0|g1|g2] (EDGE one of u0, u1, v0, v1)"))?;
    let edge = JoinEdge::parse(edge.trim()).ok_or_else(|| {
        format!("`{edge}` is not an edge: u0, u1 (first, last row), v0, v1 (first, last column)")
    })?;
    let (file, continuity) = match rest.rsplit_once(':') {
        Some((file, c)) if Continuity::parse(c).is_some() => (file, Continuity::parse(c).unwrap_or_default()),
        _ => (rest, Continuity::default()),
    };
    if file.is_empty() {
        return Err(format!("`{text}` names no neighbour file"));
    }
    Ok(JoinArg {
        edge,
        file: file.to_owned(),
        continuity,
    })
}

/// Parses a tolerance: a finite number greater than 0.
/// `--corners`: `auto`, `none`, or point indices (from 0) separated by commas.
pub(crate) fn parse_corners(text: &str) -> Result<fairing::corners::Corners, String> {
    match fairing::corners::Corners::named(text.trim()) {
        Some(corners) => Ok(corners),
        None => parse_index_list(text)
            .map(|list| fairing::corners::Corners::At(list.0))
            .map_err(|e| format!("{e}; or auto, or none")),
    }
}

pub(crate) fn parse_tolerance(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        Ok(_) => Err(format!("`{text}` must be a finite number greater than 0")),
        Err(_) => Err(format!("`{text}` is not a number")),
    }
}

/// The default port of `fair serve`.
pub(crate) const DEFAULT_PORT: u16 = 8765;

/// The default largest request body, in bytes (16 MiB: a scan of about 400 000 points as JSON).
pub(crate) const DEFAULT_MAX_UPLOAD: usize = 16 << 20;

/// `fair serve --deadline`: seconds a request has, reading, fairing and writing.
pub(crate) const DEFAULT_DEADLINE: u64 = 120;

/// Options of `fair serve`.
#[derive(Debug, Clone, clap::Args)]
pub(crate) struct ServeArgs {
    /// Curve or surface files to offer on the page, or folders of them (every .csv, .json,
    /// .dat and .txt file inside); nothing outside them is ever read.
    #[arg(value_name = "FILE")]
    pub files: Vec<std::path::PathBuf>,
    /// The port to listen on (0: any free port; the address is printed).
    #[arg(long, short = 'p', value_name = "P", default_value_t = DEFAULT_PORT)]
    pub port: u16,
    /// The address to listen on. The default serves this machine only; another address lets
    /// anyone who reaches it use the page and read the files given.
    #[arg(long, value_name = "ADDR", default_value = "127.0.0.1")]
    pub bind: std::net::IpAddr,
    /// The largest request body (an upload, a curve to fair), in bytes.
    #[arg(long, value_name = "BYTES", default_value_t = DEFAULT_MAX_UPLOAD)]
    pub max_upload: usize,
    /// The time a request has, from its first byte to the last byte of its answer (reading,
    /// fairing and writing); past it the work is stopped and the answer is 503.
    #[arg(long, value_name = "SECONDS", default_value_t = DEFAULT_DEADLINE, value_parser = clap::value_parser!(u64).range(1..=86_400))]
    pub deadline: u64,
    /// Print nothing but the address (no line per request).
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<Cli, clap::Error> {
        Cli::try_parse_from(std::iter::once("fair").chain(args.iter().copied()))
    }

    #[test]
    fn clap_definition_is_consistent() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }

    #[test]
    fn full_curve_command() {
        let cli = parse(&[
            "curve",
            "in.csv",
            "--method",
            "batten",
            "--kind",
            "function",
            "--config",
            "c.toml",
            "--set",
            "p=0.9",
            "--set",
            "criterion=ek",
            "--fixed",
            "2,5,7",
            "--points",
            "4, 5",
            "--tolerance",
            "0.01",
            "--clamp-ends",
            "g1",
            "-o",
            "out.csv",
            "--report",
            "r.json",
            "--plot",
            "p.svg",
            "--quiet",
        ])
        .unwrap();
        let Command::Curve(a) = cli.command else {
            panic!("not curve")
        };
        assert_eq!(a.input, "in.csv");
        assert_eq!(a.method.as_deref(), Some("batten"));
        assert_eq!(a.kind, KindArg::Function);
        assert_eq!(a.settings.len(), 2);
        assert_eq!(
            a.settings[1],
            Setting {
                name: "criterion".into(),
                value: "ek".into()
            }
        );
        assert_eq!(a.fixed, Some(IndexList(vec![2, 5, 7])));
        assert_eq!(a.points, Some(IndexList(vec![4, 5])));
        assert_eq!(a.tolerance, Some(0.01));
        assert_eq!(a.clamp_ends, Some(ClampEnds::G1));
        assert_eq!(a.output.as_deref(), Some("out.csv"));
        assert!(a.quiet);
    }

    #[test]
    fn other_subcommands() {
        assert!(matches!(parse(&["methods"]).unwrap().command, Command::Methods));
        let Command::Demo(d) = parse(&["demo", "--out", "d"]).unwrap().command else {
            panic!()
        };
        assert_eq!(d.out, PathBuf::from("d"));
        let Command::Inspect(i) = parse(&["inspect", "-", "--kind", "parametric"]).unwrap().command else {
            panic!()
        };
        assert_eq!(i.input, "-");
        let Command::Surface(s) = parse(&["surface", "s.csv", "--method", "kjellander"])
            .unwrap()
            .command
        else {
            panic!()
        };
        assert_eq!(s.method.as_deref(), Some("kjellander"));
    }

    #[test]
    fn bad_values_are_usage_errors() {
        for args in [
            &["curve", "a.csv", "--fixed", "1,x"][..],
            &["curve", "a.csv", "--fixed", "-1"],
            &["curve", "a.csv", "--fixed", "1,1"],
            &["curve", "a.csv", "--set", "p"],
            &["curve", "a.csv", "--set", "=3"],
            &["curve", "a.csv", "--tolerance", "-1"],
            &["curve", "a.csv", "--tolerance", "nan"],
            &["curve", "a.csv", "--clamp-ends", "g3"],
            &["curve", "a.csv", "--kind", "spline"],
            &["frobnicate"],
            &["curve"],
        ] {
            let e = parse(args).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{args:?}");
        }
    }

    #[test]
    fn setting_parser() {
        assert_eq!(
            parse_setting("a=b=c").unwrap(),
            Setting {
                name: "a".into(),
                value: "b=c".into()
            }
        );
        assert!(parse_setting("a b=1").is_err());
        assert!(parse_setting("a=").unwrap_err().contains("empty value"));
    }
}
