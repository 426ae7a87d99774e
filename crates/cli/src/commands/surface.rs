//! `fair surface`: read a grid `i,j,x,y,z`, fair it, write the grid, the report and the plot.
//!
//! Same order of checks as `fair curve`; `--kind` does not apply to surfaces and is ignored.

use crate::args::FairArgs;
use crate::commands::{measure, say};
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

/// Runs `fair surface`.
pub fn run(args: &FairArgs) -> Result<()> {
    let input = input::read_surface(&args.input)?;
    require_grid(&input)?;
    let method = registry::find(
        args.method.as_deref().unwrap_or(DEFAULT_METHOD),
        MethodKind::Surface,
    )?;
    let parameters = Parameters::collect(method, args.config.as_deref(), &args.settings)?;
    let constraints = Constraints::from_args(args, input.grid.points.len())?;

    let job = SurfaceJob {
        input: &input,
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
    let grid_text = crate::output::format_surface(&input, &outcome.grid)?;
    let report_text = report.to_json()?;
    if let Some(out) = &args.output {
        crate::output::write_text(out, &grid_text)?;
    }
    if let Some(path) = &args.report {
        crate::output::write_text(&path.display().to_string(), &report_text)?;
    }
    if let Some(path) = &args.plot {
        let plot = SurfacePlot {
            title: format!("{} — {}", input.source, method.name),
            input: Some(input.grid.clone()),
            faired: Some(outcome.grid.clone()),
            z: after.z,
            z_before: before.z.clone(),
            highlights: true,
        };
        plot.figure().write(path)?;
    }
    say(
        args.quiet,
        args.output.as_deref() == Some("-"),
        &format!(
            "{}: {} ({} × {} grid): {} iterations, {} moved, S_d = {s_d:.6e}, M_d = {m_d:.6e}",
            input.source,
            method.name,
            input.grid.rows,
            input.grid.columns,
            report.iterations,
            report.moved.len()
        ),
    );
    Ok(())
}
