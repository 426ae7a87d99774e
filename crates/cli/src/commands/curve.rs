//! `fair curve`: read, check, fair, write the points, the report and the plot.
//!
//! Order of checks (so that the user's mistakes are reported before anything runs): the
//! input file, the number of points, `--kind`, `--method` and the parameters (the
//! catalogue's [`Catalog::plan`]), the constraints; then the plan runs
//! ([`Catalog::run_curve_plan`]: one method or a pipeline of stages), then the outputs.
//! Everything about methods — names, parameters, what each refuses — is the catalogue's.
//! A directory or a JSON-lines stream is a [`batch`].

use std::collections::BTreeMap;

use fairing::catalog::{
    AnyCurve, Catalog, ConfigFile, CurvePoints, MethodKind, ParameterMap, Plan, PlanConstraints,
};

use crate::args::FairArgs;
use crate::commands::{measure, say, write_results};
use crate::error::{Error, Result};
use crate::input::{self, CurveInput, Points};
use crate::kind::{self, CurveKind};
use crate::plots::{planar_view, CurvePlot};
use crate::progress;
use crate::report::{Energies, Report, ReportKind};

pub mod batch;

/// The fewest points any curve method works on: curvature-slope jumps e_i need three.
pub const MIN_CURVE_POINTS: usize = 3;

/// The default method for a kind of curve: `jump-lsq` for both (issue 17: it met the goal
/// against csaps and OpenCASCADE on 4 of the 5 required test curves, README). The papers'
/// methods (`two-phase`, `strain-energy`, ...) stay selectable by name.
pub fn default_method(kind: CurveKind) -> &'static str {
    match kind {
        CurveKind::Function | CurveKind::Parametric => "jump-lsq",
    }
}

/// `s_d` and `m_d`: the sum and the largest of the distances moved. O(n).
pub fn displacement(before: &Points, after: &Points) -> (f64, f64) {
    let (a, b) = (before.rows(), after.rows());
    let distances = a
        .iter()
        .zip(&b)
        .map(|(p, q)| p.iter().zip(q).map(|(u, v)| (u - v).powi(2)).sum::<f64>().sqrt());
    distances.fold((0.0, 0.0), |(sum, max), d| (sum + d, f64::max(max, d)))
}

/// The command's points as the catalogue's.
pub fn to_catalog(points: &Points) -> CurvePoints {
    match points {
        Points::Planar(p) => CurvePoints::Planar(p.clone()),
        Points::Spatial(p) => CurvePoints::Spatial(p.clone()),
    }
}

/// The catalogue's points as the command's.
pub fn from_catalog(points: CurvePoints) -> Points {
    match points {
        CurvePoints::Planar(p) => Points::Planar(p),
        CurvePoints::Spatial(p) => Points::Spatial(p),
    }
}

/// The `--set`s of a command line.
pub fn sets(args: &FairArgs) -> ParameterMap {
    ParameterMap::from_sets(args.settings.iter().map(|s| (s.name.as_str(), s.value.as_str())))
}

/// Every criterion of the catalogue that applies to a curve of `dimension` whose energies are
/// `energies`, by name: the criteria that are energies are read from them (no second
/// integration), the others evaluated on the curve `curve()` builds, only if one needs it. A
/// criterion that cannot be evaluated is left out (its reason goes to `failed`); errors name
/// `source`.
pub fn criteria<C: std::borrow::Borrow<AnyCurve>>(
    catalog: &Catalog,
    dimension: usize,
    energies: Option<&Energies>,
    curve: impl FnOnce() -> fairing::Result<C>,
    source: &str,
    failed: &mut BTreeMap<String, String>,
) -> Result<BTreeMap<String, f64>> {
    let values = catalog
        .criteria_with(dimension, energies, curve)
        .map_err(|e| Error::from_fairing(e, source))?;
    let mut out = BTreeMap::new();
    for (name, value) in values {
        match value {
            Ok(v) if v.is_finite() => {
                out.insert(name, v);
            }
            Ok(v) => {
                failed.insert(name, format!("not finite ({v})"));
            }
            Err(e) => {
                failed.insert(name, e.to_string());
            }
        }
    }
    Ok(out)
}

/// The spline the report measures for `points` read as `kind`, for the criteria that are not
/// energies.
fn measured_spline(kind: CurveKind, points: &Points) -> fairing::Result<AnyCurve> {
    fairing::catalog::measured_curve(kind, &to_catalog(points))
}

/// A faired curve, ready to be written: what one input of `fair curve` produces.
#[derive(Debug, Clone)]
pub struct Faired {
    /// The JSON report.
    pub report: Report,
    /// The faired points in the input's format.
    pub points_text: String,
    /// The before/after picture.
    pub plot: CurvePlot,
    /// The faired points.
    pub points: Points,
    /// How they were measured.
    pub kind: CurveKind,
}

/// The plan and constraints a command line and its config imply for `input` of `kind`.
pub fn plan(
    catalog: &Catalog,
    input: &CurveInput,
    args: &FairArgs,
    file: Option<&ConfigFile>,
    kind: CurveKind,
) -> Result<(Plan, PlanConstraints)> {
    let plan = catalog
        .plan(
            MethodKind::Curve,
            args.method.as_deref(),
            default_method(kind),
            file,
            &sets(args),
        )
        .map_err(|e| Error::from_fairing(e, &input.source))?;
    let constraints = crate::constraints::resolve(args, &plan.constraints, input.len())?;
    Ok((plan, constraints))
}

/// Reads, checks and fairs one curve input: everything `fair curve` does but writing.
///
/// Every error about the points names the input file (not "the points").
pub fn process(
    catalog: &Catalog,
    input: &CurveInput,
    args: &FairArgs,
    file: Option<&ConfigFile>,
) -> Result<Faired> {
    process_points(catalog, input, args, file).map_err(|e| measure::in_file(e, &input.source))
}

/// [`process`], errors about the points not yet named after the file.
fn process_points(
    catalog: &Catalog,
    input: &CurveInput,
    args: &FairArgs,
    file: Option<&ConfigFile>,
) -> Result<Faired> {
    input.require_at_least(MIN_CURVE_POINTS, "a curve")?;
    let kind = kind::resolve(args.kind, input)?;
    let (plan, constraints) = plan(catalog, input, args, file, kind)?;
    let points = to_catalog(&input.points);
    let run = catalog
        .run_curve_plan(&plan, &points, kind, &constraints)
        .map_err(|e| Error::from_fairing(e, &input.source))?;
    let faired = from_catalog(run.points);
    if kind == CurveKind::Function {
        check_still_a_function(&faired, &plan)?;
    }
    // The plot's samples only when a plot is asked for (the figure is drawn only then).
    let detail = measure::Detail {
        plot: args.plot.is_some(),
        record: true,
    };
    let mut before = measure::curve_with(kind, &input.points, detail)?;
    let mut after = measure::curve_with(kind, &faired, detail)?;
    // Criteria on the curve as represented: the method's own curves when it has them, else
    // the spline the report measures (whose energies are already in the measures).
    let mut failed = BTreeMap::new();
    let dimension = input.points.dimension();
    match &run.represented {
        Some(represented) => {
            for (measures, curve) in [
                (&mut before.measures, &represented.before),
                (&mut after.measures, &represented.after),
            ] {
                // The method's own curve (rational pieces): every energy adaptive, each with
                // its accuracy; where an integrand is not finite, no energies.
                let measured = fairing::catalog::measure_energies(curve).ok();
                measures.energies = measured.map(|m| m.values);
                measures.energy_accuracy = measured.map(|m| m.accuracy);
                measures.criteria = criteria(
                    catalog,
                    dimension,
                    measures.energies.as_ref(),
                    || Ok(curve),
                    &input.source,
                    &mut failed,
                )?;
            }
        }
        None => {
            for (measures, points) in [
                (&mut before.measures, &input.points),
                (&mut after.measures, &faired),
            ] {
                measures.criteria = criteria(
                    catalog,
                    dimension,
                    measures.energies.as_ref(),
                    || measured_spline(kind, points),
                    &input.source,
                    &mut failed,
                )?;
            }
        }
    }
    let (s_d, m_d) = displacement(&input.points, &faired);
    let mut extras = run.extras;
    extras.insert("termination".into(), serde_json::json!(run.termination));
    if !failed.is_empty() {
        extras.insert("criteria_failed".into(), serde_json::json!(failed));
    }
    let report = Report {
        method: plan.name(),
        kind: ReportKind::from(kind),
        n: input.len(),
        iterations: run.iterations,
        before: before.measures.clone(),
        after: after.measures.clone(),
        s_d,
        m_d,
        moved: run.moved,
        elapsed_ms: run.elapsed_ms,
        curve: run.curve,
        params: plan.params(catalog),
        extras,
    };
    let points_text = crate::output::format_curve_as(input, &faired, output_format(args)?)?;
    let plot = CurvePlot {
        title: format!("{} — {}", input.source, report.method),
        input: planar_view(&input.points),
        faired: Some(planar_view(&faired)),
        input_curve: before.samples,
        faired_curve: after.samples,
        comb: after.comb,
        z_before: before.z,
        z_after: after.z,
        function: kind == CurveKind::Function,
        curvature_before: before.curvature,
        curvature_after: after.curvature,
        axes: Some(crate::plots::axis_names(&input.coordinate_names())),
        projections: crate::plots::other_projections(&input.coordinate_names(), &input.points, Some(&faired)),
    };
    Ok(Faired {
        report,
        points_text,
        plot,
        points: faired,
        kind,
    })
}

/// The format of the faired points: by `-o`'s extension for a single curve (a batch writes
/// each file in its own format).
fn output_format(args: &FairArgs) -> Result<crate::output::OutputFormat> {
    match &args.output {
        Some(path) if !batch::is_batch(args) && crate::cad_file::format_of(args).is_none() => {
            crate::output::OutputFormat::of_path(path)
        }
        _ => Ok(crate::output::OutputFormat::SameAsInput),
    }
}

/// Methods for parametric curves (strain-energy, batten) move x as well as y; on function
/// input the result must still be a function for the function-kind measures. Says which point
/// broke it and how to ask for parametric measures instead.
fn check_still_a_function(points: &Points, plan: &Plan) -> Result<()> {
    let rows = points.rows();
    let broken = rows
        .windows(2)
        .position(|w| w[1][0].partial_cmp(&w[0][0]) != Some(std::cmp::Ordering::Greater));
    match broken {
        Some(i) => Err(Error::Argument {
            option: "--kind",
            message: format!(
                "`{}` moved x so that it no longer increases at point {} (x = {} then {}); fair this curve with --kind parametric",
                plan.name(),
                i + 1,
                rows[i][0],
                rows[i + 1][0]
            ),
        }),
        None => Ok(()),
    }
}

/// Runs `fair curve`: one input, or a batch ([`batch`]).
pub fn run(catalog: &Catalog, args: &FairArgs) -> Result<()> {
    let file = read_config(args)?;
    let cad = crate::cad_file::target(args, false)?;
    if batch::is_batch(args) {
        return batch::run(catalog, args, file.as_ref());
    }
    output_format(args)?;
    let input = {
        let _activity = progress::Activity::start(&format!("reading {}", args.input), args.quiet);
        input::read_curve_with(&args.input, &args.read_options())?
    };
    input.print_notes(args.quiet);
    if args.print_config {
        input.require_at_least(MIN_CURVE_POINTS, "a curve")?;
        let kind = kind::resolve(args.kind, &input)?;
        let (plan, constraints) = plan(catalog, &input, args, file.as_ref(), kind)?;
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
            let name = stem(&input.source);
            let made = crate::cad_file::export_curve(
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
            "{}: {} ({} points, {}): {} iterations, {} moved, S_d = {:.6e}, M_d = {:.6e}",
            input.source,
            report.method,
            input.len(),
            report.kind.name(),
            report.iterations,
            report.moved.len(),
            report.s_d,
            report.m_d
        ),
    );
    Ok(())
}

/// `fair: warning: …` on standard error (unless `quiet`) when the report's `largest_move`
/// says the method moved a point farther than the bound the user did not ask to exceed
/// ([`fairing::displacement::unasked_move`]).
pub(crate) fn warn_largest_move(source: &str, report: &Report, quiet: bool) {
    // The method's own `warnings` (jump-lsq: λ at its precision limit, a degenerate σ̂, no
    // point moved), one line each.
    if let (false, Some(warnings)) = (quiet, report.extras.get("warnings").and_then(|w| w.as_array())) {
        for warning in warnings.iter().filter_map(|w| w.as_str()) {
            eprintln!("fair: warning: {source}: {}: {warning}", report.method);
        }
    }
    let Some(largest) = report.extras.get("largest_move") else {
        return;
    };
    if quiet || largest["exceeds"].as_bool() != Some(true) {
        return;
    }
    let index = largest["index"].as_u64().unwrap_or(0);
    let from = match largest["bound_from"].as_str() {
        Some("tolerance") => "the --tolerance given",
        _ => "the data's noise and decimal step; give --tolerance to bound the moves",
    };
    eprintln!(
        "fair: warning: {source}: {} moved point {} by {:.6e}, farther than {:.6e} ({from})",
        report.method,
        index + 1,
        largest["distance"].as_f64().unwrap_or(f64::NAN),
        largest["bound"].as_f64().unwrap_or(f64::NAN),
    );
}

/// A name for the shape in a CAD file: the input file's stem (`curve` for standard input).
pub fn stem(source: &str) -> String {
    match std::path::Path::new(source).file_stem().and_then(|s| s.to_str()) {
        Some(s) if source != "-" && !s.is_empty() => s.to_string(),
        _ => "curve".to_string(),
    }
}

/// Reads `--config` if given (errors name the file and line).
pub fn read_config(args: &FairArgs) -> Result<Option<ConfigFile>> {
    args.config
        .as_deref()
        .map(ConfigFile::read)
        .transpose()
        .map_err(|e| Error::from_fairing(e, "--config"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::Vec2;

    #[test]
    fn displacement_sums_and_maxes_distances() {
        let a = Points::Planar(vec![Vec2::new(0., 0.), Vec2::new(1., 0.), Vec2::new(2., 0.)]);
        let b = Points::Planar(vec![Vec2::new(0., 0.), Vec2::new(1., 3.), Vec2::new(5., 4.)]);
        assert_eq!(displacement(&a, &b), (8.0, 5.0));
    }
}
