//! `fair curve`: read, fair through the door ([`fair_door::curve`]), write the points, the
//! report and the plot. A directory or a JSON-lines stream is a [`batch`].

use fair_door::curve::CurveRequest;
use fair_door::error::{Error, Result};
use fair_door::kind::CurveKind;
use fair_door::measure;
use fair_door::report::Report;
use fairing::catalog::{Catalog, ConfigFile};

use crate::args::FairArgs;
use crate::commands::{say, write_results};
use crate::input::{self, CurveInput, CurvePoints};
use crate::plots::{planar_view, CurvePlot};
use crate::progress;

pub(crate) mod batch;

/// A faired curve, ready to be written: what one input of `fair curve` produces.
#[derive(Debug, Clone)]
pub(crate) struct Faired {
    /// The JSON report.
    pub(crate) report: Report,
    /// The faired points in the input's format.
    pub(crate) points_text: String,
    /// The before/after picture.
    pub(crate) plot: CurvePlot,
    /// The faired points.
    pub(crate) points: CurvePoints,
    /// How they were measured.
    pub(crate) kind: CurveKind,
}

/// The door's request for a command line (and its config file).
fn request(args: &FairArgs, file: Option<&ConfigFile>) -> CurveRequest {
    CurveRequest {
        method: args.method.clone(),
        kind: args.kind.into(),
        settings: args.parameters(),
        config: file.cloned(),
        constraints: args.constraints(),
        // The plot's samples only when a plot is asked for (the figure is drawn only then).
        samples: args.plot.is_some(),
    }
}

/// Fairs one curve input through the door and formats what `fair curve` writes.
pub(crate) fn process(
    catalog: &Catalog,
    input: &CurveInput,
    args: &FairArgs,
    file: Option<&ConfigFile>,
) -> Result<Faired> {
    let faired = fair_door::curve(catalog, &input.data(), &request(args, file))?;
    let points_text = crate::output::format_curve_as(input, &faired.points, output_format(args)?)?;
    let names = input.coordinate_names();
    let plot = CurvePlot {
        title: format!("{} — {}", input.source, faired.report.method),
        input: planar_view(&input.points),
        faired: Some(planar_view(&faired.points)),
        input_curve: faired.before.samples,
        faired_curve: faired.after.samples,
        comb: faired.after.comb,
        z_before: faired.before.z,
        z_after: faired.after.z,
        function: faired.kind == CurveKind::Function,
        curvature_before: faired.before.curvature,
        curvature_after: faired.after.curvature,
        axes: Some(crate::plots::axis_names(&names)),
        projections: crate::plots::other_projections(&names, &input.points, Some(&faired.points)),
    };
    Ok(Faired {
        report: faired.report,
        points_text,
        plot,
        points: faired.points,
        kind: faired.kind,
    })
}

/// The format of the faired points: by `-o`'s extension for a single curve (a batch writes
/// each file in its own format).
fn output_format(args: &FairArgs) -> Result<crate::output::OutputFormat> {
    match &args.output {
        Some(path) if !args.is_batch() && args.cad_request().format_of().is_none() => {
            crate::output::OutputFormat::of_path(path)
        }
        _ => Ok(crate::output::OutputFormat::SameAsInput),
    }
}

/// Runs `fair curve`: one input, or a batch ([`batch`]).
pub(crate) fn run(catalog: &Catalog, args: &FairArgs) -> Result<()> {
    if !args.joins.is_empty() {
        return Err(Error::Argument {
            option: "--join",
            message: "holds a surface's edge to a neighbour; a curve has none (use --clamp-ends)".into(),
        });
    }
    let batch = batch::is_batch(args);
    // A batch's --plot (and a directory batch's -o) is a directory of files named per curve;
    // the files that can clash are a stream's -o and --report.
    let directory_batch = batch && std::path::Path::new(&args.input).is_dir() && !args.batch;
    super::check_outputs(&[
        (
            "-o",
            args.output
                .as_ref()
                .filter(|_| !directory_batch)
                .map(super::target),
        ),
        ("--report", args.report.as_ref().map(super::target)),
        ("--plot", args.plot.as_ref().filter(|_| !batch).map(super::file)),
    ])?;
    let file = read_config(args)?;
    let cad = fair_door::cad::target(&args.cad_request(), false)?;
    if batch {
        return batch::run(catalog, args, file.as_ref());
    }
    output_format(args)?;
    let input = {
        let _activity = progress::Activity::start(&format!("reading {}", args.input), args.quiet);
        input::read_curve_with(&args.input, &args.read_options())?
    };
    let mut input = input;
    input
        .notes
        .extend(fair_door::kind::auto_note(args.kind.into(), &input.data()));
    input.print_notes(args.quiet);
    if args.print_config {
        let (_, plan, constraints) =
            fair_door::curve::plan(catalog, &input.data(), &request(args, file.as_ref()))?;
        // The methods check their values when they run: run it, so that a config that would
        // fail is not printed as if it were good.
        process(catalog, &input, args, file.as_ref())?;
        say(false, false, plan.render(catalog, &constraints).trim_end());
        return Ok(());
    }
    let mut faired = {
        let _activity = progress::Activity::start(
            &format!("fairing and measuring {} ({} points)", input.source, input.len()),
            args.quiet,
        );
        process(catalog, &input, args, file.as_ref())?
    };
    let output_text = match &cad {
        Some(target) => {
            let name = fair_door::cad::stem(&input.source);
            let made = fair_door::cad::export_curve(
                target,
                &faired.report.curve,
                &faired.points,
                faired.kind,
                &name,
            )
            .map_err(|e| measure::in_file(e, &input.source))?;
            faired.report.extras.insert("cad".into(), made.summary);
            made.text
        }
        None => std::mem::take(&mut faired.points_text),
    };
    write_results(args, &faired.report, &output_text, || faired.plot.figure())?;
    let report = &faired.report;
    warn_largest_move(&input.source, report, args.quiet);
    say(
        args.quiet,
        args.output.as_deref() == Some("-"),
        &format!(
            "{}: {} ({} points, {}): {} iterations, {} moved, S_d = {:.6e}, M_d = {:.6e}, inflections {}, vibrations {}",
            input.source,
            report.method,
            input.len(),
            report.kind.name(),
            report.iterations,
            report.moved.len(),
            report.s_d,
            report.m_d,
            change(report.before.inflections, report.after.inflections),
            change(report.before.vibrations, report.after.vibrations)
        ),
    );
    Ok(())
}

/// The method's own `warnings` (curve jump-lsq: λ at its precision limit, a degenerate σ̂, no
/// point moved; surface jump-lsq: fixed nodes that swing the fit), one `fair: warning: …` line
/// each on standard error, unless `quiet`.
pub(crate) fn print_warnings(source: &str, report: &Report, quiet: bool) {
    if let (false, Some(warnings)) = (quiet, report.extras.get("warnings").and_then(|w| w.as_array())) {
        for warning in warnings.iter().filter_map(|w| w.as_str()) {
            eprintln!(
                "{}: warning: {source}: {}: {warning}",
                crate::program_name(),
                report.method
            );
        }
    }
}

/// `fair: warning: …` on standard error (unless `quiet`) when the report's `largest_move`
/// says the method moved a point farther than the bound the user did not ask to exceed
/// ([`fairing::displacement::unasked_move`]).
pub(crate) fn warn_largest_move(source: &str, report: &Report, quiet: bool) {
    print_warnings(source, report, quiet);
    let Some(largest) = report.extras.get("largest_move") else {
        return;
    };
    if quiet || largest["exceeds"].as_bool() != Some(true) {
        return;
    }
    // From 0, as `--fixed`, `--points` and the report count: a user who pastes the number
    // into `--fixed` pins the point that moved.
    let index = largest["index"].as_u64().unwrap_or(0);
    let from = match largest["bound_from"].as_str() {
        Some("tolerance") => "the --tolerance given",
        _ => "the data's noise and decimal step; give --tolerance to bound the moves",
    };
    eprintln!(
        "{}: warning: {source}: {} moved point {} by {:.6e}, farther than {:.6e} ({from})",
        crate::program_name(),
        report.method,
        index,
        largest["distance"].as_f64().unwrap_or(f64::NAN),
        largest["bound"].as_f64().unwrap_or(f64::NAN),
    );
}

/// Reads `--config` if given (errors name the file and line).
pub(crate) fn read_config(args: &FairArgs) -> Result<Option<ConfigFile>> {
    args.config
        .as_deref()
        .map(ConfigFile::read)
        .transpose()
        .map_err(|e| Error::from_fairing(e, "--config"))
}

/// A count before → after (`-` where it does not apply: inflections of a 3D curve).
fn change(before: Option<usize>, after: Option<usize>) -> String {
    let count = |c: Option<usize>| c.map_or("-".to_string(), |c| c.to_string());
    format!("{} → {}", count(before), count(after))
}
