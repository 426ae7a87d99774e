//! `fair inspect`: measure a curve or a surface, change nothing.
//!
//! A CSV whose header or rows have five columns `i,j,x,y,z` is a surface (or `--surface`);
//! anything else is a curve. The report has the shape of `fair curve`'s with `method`
//! `inspect`, `after` equal to `before`, nothing moved.

use std::path::Path;

use fair_door::error::Result;
use fair_door::kind::CurveKind;
use fair_door::measure::Detail;
use fair_door::report::Report;
use fairing::catalog::Catalog;

use crate::args::{InspectArgs, KindArg};
use crate::commands::say;
use crate::input::{self, looks_like_surface, ReadOptions, Source};
use crate::plots::{planar_view, CurvePlot, SurfacePlot};
use crate::progress;

fn format_measures(report: &Report) -> String {
    let m = &report.before;
    let count = |c: Option<usize>| c.map_or("-".to_string(), |c| c.to_string());
    format!(
        "{} points, {:?}: inflections {}, vibrations {}, e_s = {:.6e}, max_z = {:.6e}",
        report.n,
        report.kind,
        count(m.inflections),
        count(m.vibrations),
        m.e_s,
        m.max_z
    )
}

/// Runs `fair inspect`.
pub(crate) fn run(catalog: &Catalog, args: &InspectArgs) -> Result<()> {
    super::check_outputs(&[
        ("--report", args.report.as_ref().map(super::target)),
        ("--plot", args.plot.as_ref().map(super::file)),
    ])?;
    let source = {
        let _activity = progress::Activity::start(&format!("reading {}", args.input), args.quiet);
        Source::read(&args.input)?
    };
    let (report, figure) = measure(
        catalog,
        &source,
        args.kind,
        args.surface,
        args.plot.is_some(),
        args.report.is_some(),
        &args.read_options(),
        args.quiet,
    )?;
    // The report and the plot written all or none (cad::atomic).
    let mut outputs = cad::atomic::Outputs::new();
    if let Some(path) = &args.report {
        outputs.add(super::target(path), |w| report.write_json_to(w));
    }
    if let (Some(path), Some(figure)) = (&args.plot, &figure) {
        outputs.add(super::file(path), move |w| {
            w.write_all(figure.to_svg().as_bytes())
        });
    }
    outputs.commit().map_err(|e| fair_door::Error::from_write(&e))?;
    say(
        args.quiet,
        false,
        &format!("{}: {}", source.name, format_measures(&report)),
    );
    Ok(())
}

/// Measures `source` (a surface when `surface` is set or it has five columns, else a curve
/// of kind `kind`), draws the plot to `plot` if given, and returns the report (checked
/// finite). The work of `fair inspect` and `fair demo`.
pub(crate) fn inspect(
    catalog: &Catalog,
    source: &Source,
    kind_arg: KindArg,
    surface: bool,
    plot: Option<&Path>,
) -> Result<Report> {
    inspect_with(
        catalog,
        source,
        kind_arg,
        surface,
        Outputs { plot, record: true },
        &ReadOptions::default(),
        true,
    )
}

/// What `fair inspect` writes besides the measures: the plot (to this path), and whether the
/// report's `curve` record is wanted (a curve's record is O(n) JSON values: at 10⁶ points a
/// few hundred MB that a run without `--report` need not build; it is then `null`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Outputs<'a> {
    /// Draw the plot here.
    pub(crate) plot: Option<&'a Path>,
    /// Build the report's `curve` record.
    pub(crate) record: bool,
}

/// [`inspect`] with `--columns` ([`ReadOptions`]) and a choice of [`Outputs`]; the reader's
/// notes and a progress spinner on standard error unless `quiet`.
pub(crate) fn inspect_with(
    catalog: &Catalog,
    source: &Source,
    kind_arg: KindArg,
    surface: bool,
    outputs: Outputs<'_>,
    options: &ReadOptions,
    quiet: bool,
) -> Result<Report> {
    let (report, figure) = measure(
        catalog,
        source,
        kind_arg,
        surface,
        outputs.plot.is_some(),
        outputs.record,
        options,
        quiet,
    )?;
    if let (Some(path), Some(figure)) = (outputs.plot, figure) {
        figure.write(path)?;
    }
    Ok(report)
}

/// Measures `source` as [`inspect_with`] does and draws the plot if `draw`, without writing
/// it. The report is checked finite.
#[allow(clippy::too_many_arguments)]
fn measure(
    catalog: &Catalog,
    source: &Source,
    kind_arg: KindArg,
    surface: bool,
    draw: bool,
    record: bool,
    options: &ReadOptions,
    quiet: bool,
) -> Result<(Report, Option<crate::svg::Figure>)> {
    let mut figure = None;
    let report = if surface || looks_like_surface(source) {
        if options.columns.is_some() {
            return Err(fair_door::Error::Argument {
                option: "--columns",
                message: format!(
                    "{}: the input is a surface grid i,j,x,y,z; --columns is for curves",
                    source.name
                ),
            });
        }
        if kind_arg != KindArg::Auto {
            return Err(fair_door::Error::Argument {
                option: "--kind",
                message: format!(
                    "{}: the input is a surface grid; --kind is for curves",
                    source.name
                ),
            });
        }
        let input = input::grid::parse(source)?;
        let inspected = fair_door::inspect_surface(&input.data())?;
        if draw {
            let plot = SurfacePlot {
                title: format!("{} — inspect", input.source),
                input: Some(input.grid.clone()),
                faired: None,
                z: inspected.measured.z.clone(),
                z_before: None,
                highlights: true,
            };
            figure = Some(plot.figure());
        }
        inspected.report
    } else {
        let input = {
            let _activity = progress::Activity::start(&format!("parsing {}", source.name), quiet);
            input::parse_curve_with(source, options)?
        };
        input.print_notes(quiet);
        let inspected = {
            let _activity = progress::Activity::start(
                &format!("measuring {} ({} points)", source.name, input.len()),
                quiet,
            );
            let detail = Detail { plot: draw, record };
            fair_door::inspect_curve(catalog, &input.data(), kind_arg.into(), detail)?
        };
        if draw {
            let measured = &inspected.measured;
            let names = input.coordinate_names();
            let plot = CurvePlot {
                title: format!("{} — inspect", input.source),
                input: planar_view(&input.points),
                input_curve: measured.samples.clone(),
                comb: measured.comb.clone(),
                z_before: measured.z.clone(),
                function: inspected.kind == CurveKind::Function,
                curvature_before: measured.curvature.clone(),
                axes: Some(crate::plots::axis_names(&names)),
                projections: crate::plots::other_projections(&names, &input.points, None),
                ..CurvePlot::default()
            };
            figure = Some(plot.figure());
        }
        inspected.report
    };
    report.check_finite()?;
    Ok((report, figure))
}
