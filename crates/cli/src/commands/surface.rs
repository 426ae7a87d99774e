//! `fair surface`: read a grid `i,j,x,y,z`, fair it, write the grid, the report and the plot.
//!
//! Same order of checks as `fair curve`; `--kind` does not apply to surfaces and is refused
//! unless left at `auto`. Point indices (`--fixed`, `--points`, the report's `moved`) count
//! the grid row by row from 0 (k = i · columns + j); `--clamp-ends g0` keeps the grid's
//! boundary. The method and what it refuses are the catalogue's.

use fairing::catalog::{Catalog, ConfigFile, MethodKind, Plan, PlanConstraints, SurfaceJob};

use crate::args::FairArgs;
use crate::commands::{measure, say, write_results};
use crate::error::{Error, Result};
use crate::input::{self, Grid, SurfaceInput};
use crate::plots::SurfacePlot;
use crate::report::{Report, ReportKind};

/// The default surface method.
pub const DEFAULT_METHOD: &str = "zhang-cheng";

/// The smallest grid with an interior point (z_ij is defined at interior points).
pub const MIN_GRID: (usize, usize) = (3, 3);

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
    /// The faired grid.
    pub grid: Grid,
}

/// The plan and constraints a command line and its config give for a grid of `count`
/// points. A config may set the method's parameters and `[constraints]`; pipelines of
/// `[[stage]]`s are for curves and are refused.
fn plan(
    catalog: &Catalog,
    input: &SurfaceInput,
    args: &FairArgs,
    file: Option<&ConfigFile>,
) -> Result<(Plan, PlanConstraints)> {
    let plan = catalog
        .plan(
            MethodKind::Surface,
            args.method.as_deref(),
            DEFAULT_METHOD,
            file,
            &super::curve::sets(args),
        )
        .map_err(|e| Error::from_fairing(e, &input.source))?;
    let constraints = crate::constraints::resolve(args, &plan.constraints, input.grid.points.len())?;
    Ok((plan, constraints))
}

fn to_catalog(grid: &Grid) -> fairing::catalog::Grid {
    fairing::catalog::Grid {
        rows: grid.rows,
        columns: grid.columns,
        points: grid.points.clone(),
    }
}

/// Checks and fairs one surface input: everything `fair surface` does but writing.
///
/// Every error about the points names the input file (not "the points").
pub fn process(
    catalog: &Catalog,
    input: &SurfaceInput,
    args: &FairArgs,
    file: Option<&ConfigFile>,
) -> Result<FairedSurface> {
    process_grid(catalog, input, args, file).map_err(|e| measure::in_file(e, &input.source))
}

/// [`process`], errors about the points not yet named after the file.
fn process_grid(
    catalog: &Catalog,
    input: &SurfaceInput,
    args: &FairArgs,
    file: Option<&ConfigFile>,
) -> Result<FairedSurface> {
    require_grid(input)?;
    let (plan, constraints) = plan(catalog, input, args, file)?;
    let grid = to_catalog(&input.grid);
    let whole = constraints.constraints(constraints.tolerance);
    let job = SurfaceJob {
        method: &plan.name(),
        grid: &grid,
        constraints: &whole,
        bad_points: &constraints.bad_points,
        catalog,
    };
    let run = catalog
        .run_surface_plan(&plan, &job)
        .map_err(|e| Error::from_fairing(e, &input.source))?;
    let faired = Grid {
        rows: run.grid.rows,
        columns: run.grid.columns,
        points: run.grid.points,
    };
    let before = measure::surface(&input.grid)?;
    let after = measure::surface(&faired)?;
    let distances = input
        .grid
        .points
        .iter()
        .zip(&faired.points)
        .map(|(p, q)| (p - q).norm());
    let (s_d, m_d) = distances.fold((0.0, 0.0), |(sum, max), d| (sum + d, f64::max(max, d)));
    let mut extras = run.extras;
    extras.insert("termination".into(), serde_json::json!(run.termination));
    let report = Report {
        method: plan.name(),
        kind: ReportKind::Surface,
        n: input.grid.points.len(),
        iterations: run.iterations,
        before: before.measures,
        after: after.measures,
        s_d,
        m_d,
        moved: run.moved,
        elapsed_ms: run.elapsed_ms,
        curve: run.surface,
        params: plan.params(catalog),
        extras,
    };
    let grid_text = crate::output::format_surface(input, &faired)?;
    let plot = SurfacePlot {
        title: format!("{} — {}", input.source, report.method),
        input: Some(input.grid.clone()),
        faired: Some(faired.clone()),
        z: after.z,
        z_before: before.z.clone(),
        highlights: true,
    };
    Ok(FairedSurface {
        report,
        grid_text,
        plot,
        grid: faired,
    })
}

/// Runs `fair surface`.
pub fn run(catalog: &Catalog, args: &FairArgs) -> Result<()> {
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
    let file = super::curve::read_config(args)?;
    let cad = crate::cad_file::target(args, true)?;
    let input = input::read_surface(&args.input)?;
    if args.print_config {
        require_grid(&input)?;
        let (plan, constraints) = plan(catalog, &input, args, file.as_ref())?;
        // The methods check their values when they run (see `fair curve --print-config`).
        process(catalog, &input, args, file.as_ref())?;
        say(false, false, plan.render(catalog, &constraints).trim_end());
        return Ok(());
    }
    let mut faired = {
        let _activity = crate::progress::Activity::start(&format!("fairing {}", input.source), args.quiet);
        process(catalog, &input, args, file.as_ref())?
    };
    let output_text = match &cad {
        Some(target) => {
            let name = super::curve::stem(&input.source);
            let made = crate::cad_file::export_surface(target, &faired.report.curve, &faired.grid, &name)
                .map_err(|e| measure::in_file(e, &input.source))?;
            faired.report.extras.insert("cad".into(), made.summary);
            made.text
        }
        None => std::mem::take(&mut faired.grid_text),
    };
    write_results(args, &faired.report, &output_text, || faired.plot.figure())?;
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
