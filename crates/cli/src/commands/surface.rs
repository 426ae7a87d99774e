//! `fair surface`: read a grid `i,j,x,y,z`, fair it through the door ([`fair_door::surface`]),
//! write the grid, the report and the plot.
//!
//! Same order of checks as `fair curve`; `--kind` does not apply to surfaces and is refused
//! unless left at `auto`. Point indices (`--fixed`, `--points`, the report's `moved`) count
//! the grid row by row from 0 (k = i · columns + j); `--clamp-ends g0` keeps the grid's
//! boundary. The method and what it refuses are the catalogue's.

use fair_door::error::{Error, Result};
use fair_door::measure;
use fair_door::report::Report;
use fair_door::surface::SurfaceRequest;
use fairing::catalog::{Catalog, ConfigFile};
use fairing::strategies::Join;

use crate::args::FairArgs;
use crate::commands::{say, write_results};
use crate::input::{self, Grid, SurfaceInput};
use crate::plots::SurfacePlot;

/// A faired surface, ready to be written.
#[derive(Debug, Clone)]
pub(crate) struct FairedSurface {
    /// The JSON report.
    pub(crate) report: Report,
    /// The faired grid in the input's format.
    pub(crate) grid_text: String,
    /// The before/after picture (grid, highlight lines, z_ij maps).
    pub(crate) plot: SurfacePlot,
    /// The faired grid.
    pub(crate) grid: Grid,
}

/// The door's request for a command line (and its config file), with the neighbours the
/// joins name already read. With a join and neither --method nor --config, the method is the
/// surface jump-lsq (the one that holds joins).
fn request(args: &FairArgs, file: Option<&ConfigFile>, joins: &[Join]) -> SurfaceRequest {
    let method = match (&args.method, file, joins.is_empty()) {
        (None, None, false) => Some(fairing::strategies::surface_jump_lsq::NAME.to_owned()),
        (method, _, _) => method.clone(),
    };
    SurfaceRequest {
        method,
        settings: args.parameters(),
        config: file.cloned(),
        constraints: args.constraints(),
        joins: joins.to_vec(),
    }
}

/// Reads the neighbours `--join` names: a grid file, or the first surface of an IGES/STEP
/// file sampled into a net ([`fair_door::cad::neighbour_net`]) meeting `input`'s edge.
pub(crate) fn read_joins(args: &FairArgs, input: &SurfaceInput) -> Result<Vec<Join>> {
    let grid = input.grid.to_rows();
    args.joins
        .iter()
        .map(|j| {
            let lower = j.file.to_ascii_lowercase();
            let cad = [".igs", ".iges", ".step", ".stp"]
                .iter()
                .any(|e| lower.ends_with(e));
            let neighbour = if cad {
                fair_door::cad::neighbour_net(&j.file, &grid, j.edge)?
            } else {
                input::read_surface(&j.file)?.grid.to_rows()
            };
            Ok(Join {
                edge: j.edge,
                continuity: j.continuity,
                neighbour,
                source: j.file.clone(),
            })
        })
        .collect()
}

/// Fairs one surface input through the door and formats what `fair surface` writes.
pub(crate) fn process(
    catalog: &Catalog,
    input: &SurfaceInput,
    args: &FairArgs,
    file: Option<&ConfigFile>,
) -> Result<FairedSurface> {
    let joins = read_joins(args, input)?;
    let faired = fair_door::surface(catalog, &input.data(), &request(args, file, &joins))?;
    let grid_text = crate::output::format_surface(input, &faired.grid)?;
    let plot = SurfacePlot {
        title: format!("{} — {}", input.source, faired.report.method),
        input: Some(input.grid.clone()),
        faired: Some(faired.grid.clone()),
        z: faired.after.z,
        z_before: faired.before.z,
        highlights: true,
    };
    Ok(FairedSurface {
        report: faired.report,
        grid_text,
        plot,
        grid: faired.grid,
    })
}

/// Runs `fair surface`.
pub(crate) fn run(catalog: &Catalog, args: &FairArgs) -> Result<()> {
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
    super::check_outputs(&[
        ("-o", args.output.as_ref().map(super::target)),
        ("--report", args.report.as_ref().map(super::target)),
        ("--plot", args.plot.as_ref().map(super::file)),
    ])?;
    let file = super::curve::read_config(args)?;
    let cad = fair_door::cad::target(&args.cad_request(), true)?;
    let input = input::read_surface(&args.input)?;
    if args.print_config {
        let joins = read_joins(args, &input)?;
        let (plan, constraints) =
            fair_door::surface::plan(catalog, &input.data(), &request(args, file.as_ref(), &joins))?;
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
            let name = fair_door::cad::stem(&input.source);
            let made = fair_door::cad::export_surface(target, &faired.report.curve, &faired.grid, &name)
                .map_err(|e| measure::in_file(e, &input.source))?;
            faired.report.extras.insert("cad".into(), made.summary);
            made.text
        }
        None => std::mem::take(&mut faired.grid_text),
    };
    write_results(args, &faired.report, &output_text, || faired.plot.figure())?;
    let report = &faired.report;
    super::curve::print_warnings(&input.source, report, args.quiet);
    // A run whose every step the method's refusal rule turned down says so: "0 moved" alone
    // reads as a net with nothing to fair.
    let refused = report.extras.get("termination").and_then(|t| t.as_str()) == Some("refused");
    say(
        args.quiet,
        args.output.as_deref() == Some("-"),
        &format!(
            "{}: {} ({} × {} grid): {} iterations, {} moved, S_d = {:.6e}, M_d = {:.6e}{}",
            input.source,
            report.method,
            input.grid.rows,
            input.grid.columns,
            report.iterations,
            report.moved.len(),
            report.s_d,
            report.m_d,
            if refused {
                "; refused: every step tried made the net less fair by the method's own measure \
                 (its largest z_ij or an energy), so the input is kept"
            } else {
                ""
            }
        ),
    );
    Ok(())
}
