//! `fair surface`: read a grid `i,j,x,y,z`, fair it, write the grid, the report and the plot.
//!
//! Same order of checks as `fair curve`; `--kind` does not apply to surfaces and is refused
//! unless left at `auto`.

use crate::args::{ClampEnds, FairArgs};
use crate::commands::{measure, say, write_results};
use crate::config::ConfigFile;
use crate::constraints::Constraints;
use crate::error::{Error, Result};
use crate::input::{self, Grid, SurfaceInput};
use crate::parameters::Parameters;
use crate::plots::SurfacePlot;
use crate::registry::{self, MethodInfo, MethodKind};
use crate::report::{Report, ReportKind};
use std::collections::BTreeMap;

mod zhang_cheng;

/// The default surface method.
pub const DEFAULT_METHOD: &str = "zhang-cheng";

/// The smallest grid with an interior point (z_ij is defined at interior points).
pub const MIN_GRID: (usize, usize) = (3, 3);

/// Everything a surface strategy gets. Point indices in the constraints count the grid row by
/// row from 0 (k = i · columns + j).
#[derive(Debug, Clone)]
pub struct SurfaceJob<'a> {
    /// The grid as read.
    pub input: &'a SurfaceInput,
    /// The method.
    pub method: &'static MethodInfo,
    /// Its parameters as given.
    pub parameters: &'a Parameters,
    /// Fixed points, bad points, tolerance.
    pub constraints: &'a Constraints,
}

/// What a surface strategy gives back.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceOutcome {
    /// The faired grid, same size.
    pub grid: Grid,
    /// Iterations run.
    pub iterations: usize,
    /// Indices (row by row) of the grid points that moved.
    pub moved: Vec<usize>,
    /// Time of the fairing itself, in milliseconds.
    pub elapsed_ms: f64,
    /// The faired surface for the report's `curve`.
    pub surface: serde_json::Value,
    /// Method-specific extras for the report.
    pub extras: BTreeMap<String, serde_json::Value>,
}

/// SEAM: runs the surface strategy of `job.method` (crate `fairing`).
pub fn fair(job: &SurfaceJob) -> Result<SurfaceOutcome> {
    match job.method.name {
        "zhang-cheng" | "kjellander" => zhang_cheng::fair(job),
        _ => Err(Error::NotAvailable {
            what: format!("surface method `{}`", job.method.name),
        }),
    }
}

/// Checks that the grid has an interior point.
pub fn require_grid(input: &SurfaceInput) -> Result<()> {
    let (rows, columns) = (input.grid.rows, input.grid.columns);
    if rows < MIN_GRID.0 || columns < MIN_GRID.1 {
        return Err(Error::Invalid {
            path: input.source.clone(),
            message: format!(
                "a {rows} × {columns} grid has no interior point; a surface needs at least 3 × 3"
            ),
        });
    }
    Ok(())
}

/// A faired surface, ready to be written.
#[derive(Debug, Clone)]
pub struct FairedSurface {
    /// The JSON report.
    pub report: Report,
    /// The faired grid in the input's format.
    pub grid_text: String,
    /// The before/after picture (grid, highlight lines, z_ij maps).
    pub plot: SurfacePlot,
}

/// The method, its parameters and the constraints a command line and its config file give for
/// a grid of `count` points. A config may set the method's parameters and `[constraints]`;
/// pipelines of `[[stage]]`s are for curves and are refused.
///
/// `--clamp-ends g0` keeps the grid's boundary (its "end points": the first and last row and
/// column join the fixed points); `g1` and `g2` are refused, as no surface method here can
/// hold the cross-boundary tangents or curvatures.
fn plan(
    args: &FairArgs,
    file: Option<&ConfigFile>,
    grid: &Grid,
) -> Result<(&'static MethodInfo, Parameters, Constraints)> {
    let count = grid.points.len();
    let method = registry::find(
        args.method.as_deref().unwrap_or(DEFAULT_METHOD),
        MethodKind::Surface,
    )?;
    let (values, config_constraints) = match file {
        Some(file) => {
            if file.table.contains_key(crate::config::STAGE_KEY) {
                return Err(Error::Parameter {
                    origin: file.name.clone(),
                    message: "pipelines of [[stage]]s are for curves; a surface config sets one method's parameters".into(),
                });
            }
            (file.method_values(method.name)?, file.constraints()?)
        }
        None => (Vec::new(), Default::default()),
    };
    let parameters = Parameters::from_values(method, values, &args.settings)?;
    let mut constraints = Constraints::from_args_and_config(args, &config_constraints, count)?;
    match constraints.clamp_ends {
        None => {}
        Some(ClampEnds::G0) => {
            let (rows, columns) = (grid.rows, grid.columns);
            let on_boundary = |k: usize| {
                let (i, j) = (k / columns.max(1), k % columns.max(1));
                i == 0 || j == 0 || i + 1 == rows || j + 1 == columns
            };
            if let Some(k) = constraints.bad_points.iter().find(|&&k| on_boundary(k)) {
                return Err(Error::Argument {
                    option: "--points",
                    message: format!(
                        "point {k} (i = {}, j = {}) is on the boundary, which --clamp-ends g0 keeps",
                        k / columns.max(1),
                        k % columns.max(1)
                    ),
                });
            }
            constraints.fixed.extend((0..count).filter(|&k| on_boundary(k)));
            constraints.fixed.sort_unstable();
            constraints.fixed.dedup();
        }
        Some(clamp @ (ClampEnds::G1 | ClampEnds::G2)) => {
            return Err(Error::Argument {
                option: "--clamp-ends",
                message: format!(
                    "{}: the surface methods keep at most the boundary points (g0); they cannot hold \
                     tangents or curvatures across it",
                    clamp.name()
                ),
            });
        }
    }
    Ok((method, parameters, constraints))
}

/// Checks and fairs one surface input: everything `fair surface` does but writing.
///
/// Every error about the points names the input file (not "the points").
pub fn process(input: &SurfaceInput, args: &FairArgs, file: Option<&ConfigFile>) -> Result<FairedSurface> {
    process_grid(input, args, file).map_err(|e| measure::in_file(e, &input.source))
}

/// [`process`], errors about the points not yet named after the file.
fn process_grid(input: &SurfaceInput, args: &FairArgs, file: Option<&ConfigFile>) -> Result<FairedSurface> {
    require_grid(input)?;
    let (method, parameters, constraints) = plan(args, file, &input.grid)?;
    let job = SurfaceJob {
        input,
        method,
        parameters: &parameters,
        constraints: &constraints,
    };
    let outcome = fair(&job)?;
    if (outcome.grid.rows, outcome.grid.columns) != (input.grid.rows, input.grid.columns) {
        return Err(Error::Internal {
            message: format!("method `{}` changed the grid size", method.name),
        });
    }
    let before = measure::surface(&input.grid)?;
    let after = measure::surface(&outcome.grid)?;
    let distances = input
        .grid
        .points
        .iter()
        .zip(&outcome.grid.points)
        .map(|(p, q)| (p - q).norm());
    let (s_d, m_d) = distances.fold((0.0, 0.0), |(sum, max), d| (sum + d, f64::max(max, d)));
    let report = Report {
        method: method.name.into(),
        kind: ReportKind::Surface,
        n: input.grid.points.len(),
        iterations: outcome.iterations,
        before: before.measures,
        after: after.measures,
        s_d,
        m_d,
        moved: outcome.moved.clone(),
        elapsed_ms: outcome.elapsed_ms,
        curve: outcome.surface.clone(),
        params: parameters.to_json(),
        extras: outcome.extras.clone(),
    };
    let grid_text = crate::output::format_surface(input, &outcome.grid)?;
    let plot = SurfacePlot {
        title: format!("{} — {}", input.source, method.name),
        input: Some(input.grid.clone()),
        faired: Some(outcome.grid.clone()),
        z: after.z,
        z_before: before.z.clone(),
        highlights: true,
    };
    Ok(FairedSurface {
        report,
        grid_text,
        plot,
    })
}

/// Runs `fair surface`.
pub fn run(args: &FairArgs) -> Result<()> {
    if args.batch || std::path::Path::new(&args.input).is_dir() {
        return Err(Error::Argument {
            option: "INPUT",
            message: "batches (a directory, --batch) are for `fair curve`; give one grid file".into(),
        });
    }
    if args.kind != crate::args::KindArg::Auto {
        return Err(Error::Argument {
            option: "--kind",
            message: "applies to curves only; a surface grid has no kind to choose".into(),
        });
    }
    let file = args.config.as_deref().map(ConfigFile::read).transpose()?;
    let input = input::read_surface(&args.input)?;
    if args.print_config {
        require_grid(&input)?;
        let (method, parameters, constraints) = plan(args, file.as_ref(), &input.grid)?;
        // The methods check their values when they run (see `fair curve --print-config`).
        process(&input, args, file.as_ref())?;
        let text = crate::config::render(&constraints, &[(method, parameters.given_values())]);
        say(false, false, text.trim_end());
        return Ok(());
    }
    let faired = {
        let _activity = crate::progress::Activity::start(&format!("fairing {}", input.source), args.quiet);
        process(&input, args, file.as_ref())?
    };
    write_results(args, &faired.report, &faired.grid_text, || faired.plot.figure())?;
    let report = &faired.report;
    say(
        args.quiet,
        args.output.as_deref() == Some("-"),
        &format!(
            "{}: {} ({} × {} grid): {} iterations, {} moved, S_d = {:.6e}, M_d = {:.6e}",
            input.source,
            report.method,
            input.grid.rows,
            input.grid.columns,
            report.iterations,
            report.moved.len(),
            report.s_d,
            report.m_d
        ),
    );
    Ok(())
}
