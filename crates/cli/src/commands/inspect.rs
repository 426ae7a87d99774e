//! `fair inspect`: measure a curve or a surface, change nothing.
//!
//! A CSV whose header or rows have five columns `i,j,x,y,z` is a surface (or `--surface`);
//! anything else is a curve. The report has the shape of `fair curve`'s with `method`
//! `inspect`, `after` equal to `before`, nothing moved.

use std::path::Path;

use fairing::catalog::Catalog;

use crate::args::{InspectArgs, KindArg};
use crate::commands::{curve::MIN_CURVE_POINTS, measure, say, surface};
use crate::error::Result;
use crate::input::{self, ReadOptions, Source};
use crate::kind::{self, CurveKind};
use crate::plots::{planar_view, CurvePlot, SurfacePlot};
use crate::progress;
use crate::report::{Report, ReportKind};

/// Whether a source is a surface grid: five comma-separated columns on its first row.
pub fn looks_like_surface(source: &Source) -> bool {
    let first = source
        .text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'));
    first.is_some_and(|l| l.split(',').count() == 5)
}

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
pub fn run(catalog: &Catalog, args: &InspectArgs) -> Result<()> {
    let source = {
        let _activity = progress::Activity::start(&format!("reading {}", args.input), args.quiet);
        Source::read(&args.input)?
    };
    let report = inspect_with(
        catalog,
        &source,
        args.kind,
        args.surface,
        Outputs {
            plot: args.plot.as_deref(),
            record: args.report.is_some(),
        },
        &args.read_options(),
        args.quiet,
    )?;
    if let Some(path) = &args.report {
        report.write_json(&path.display().to_string())?;
    }
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
pub fn inspect(
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
pub struct Outputs<'a> {
    /// Draw the plot here.
    pub plot: Option<&'a Path>,
    /// Build the report's `curve` record.
    pub record: bool,
}

/// [`inspect`] with `--columns` ([`ReadOptions`]) and a choice of [`Outputs`]; the reader's
/// notes and a progress spinner on standard error unless `quiet`.
pub fn inspect_with(
    catalog: &Catalog,
    source: &Source,
    kind_arg: KindArg,
    surface: bool,
    outputs: Outputs<'_>,
    options: &ReadOptions,
    quiet: bool,
) -> Result<Report> {
    let plot = outputs.plot;
    let report = if surface || looks_like_surface(source) {
        if options.columns.is_some() {
            return Err(crate::error::Error::Argument {
                option: "--columns",
                message: format!(
                    "{}: the input is a surface grid i,j,x,y,z; --columns is for curves",
                    source.name
                ),
            });
        }
        if kind_arg != KindArg::Auto {
            return Err(crate::error::Error::Argument {
                option: "--kind",
                message: format!(
                    "{}: the input is a surface grid; --kind is for curves",
                    source.name
                ),
            });
        }
        let input = input::grid::parse(source)?;
        surface::require_grid(&input)?;
        let measured = measure::surface(&input.grid).map_err(|e| measure::in_file(e, &input.source))?;
        if let Some(path) = plot {
            let plot = SurfacePlot {
                title: format!("{} — inspect", input.source),
                input: Some(input.grid.clone()),
                faired: None,
                z: measured.z.clone(),
                z_before: None,
                highlights: true,
            };
            plot.figure().write(path)?;
        }
        Report::inspection(
            ReportKind::Surface,
            input.grid.points.len(),
            measured.measures,
            measured.surface,
        )
    } else {
        let input = {
            let _activity = progress::Activity::start(&format!("parsing {}", source.name), quiet);
            input::parse_curve_with(source, options)?
        };
        input.print_notes(quiet);
        input.require_at_least(MIN_CURVE_POINTS, "a curve")?;
        let kind = kind::resolve(kind_arg, &input)?;
        let measured = {
            let _activity = progress::Activity::start(
                &format!("measuring {} ({} points)", source.name, input.len()),
                quiet,
            );
            let detail = measure::Detail {
                plot: plot.is_some(),
                record: outputs.record,
            };
            measure::curve_with(kind, &input.points, detail)
                .map_err(|e| measure::in_file(e, &input.source))?
        };
        if let Some(path) = plot {
            let plot = CurvePlot {
                title: format!("{} — inspect", input.source),
                input: planar_view(&input.points),
                input_curve: measured.samples.clone(),
                comb: measured.comb.clone(),
                z_before: measured.z.clone(),
                function: kind == CurveKind::Function,
                curvature_before: measured.curvature.clone(),
                axes: Some(crate::plots::axis_names(&input.coordinate_names())),
                projections: crate::plots::other_projections(&input.coordinate_names(), &input.points, None),
                ..CurvePlot::default()
            };
            plot.figure().write(path)?;
        }
        let mut measures = measured.measures;
        measures.criteria = curve_criteria(catalog, kind, &input, measures.energies.as_ref())?;
        Report::inspection(ReportKind::from(kind), input.len(), measures, measured.curve)
    };
    report.check_finite()?;
    Ok(report)
}

/// Every registered criterion that applies, on the spline `fair inspect` measures for `input`
/// read as `kind`, whose energies are `energies` (the report's `criteria`; those that are
/// energies are read from `energies`, the spline is built again only for the others; a
/// criterion that fails is left out). O(n) per criterion that is not an energy.
pub fn curve_criteria(
    catalog: &Catalog,
    kind: CurveKind,
    input: &crate::input::CurveInput,
    energies: Option<&fairness::Energies>,
) -> Result<std::collections::BTreeMap<String, f64>> {
    let mut failed = std::collections::BTreeMap::new();
    crate::commands::curve::criteria(
        catalog,
        input.points.dimension(),
        energies,
        || fairing::catalog::measured_curve(kind, &crate::commands::curve::to_catalog(&input.points)),
        &input.source,
        &mut failed,
    )
}
