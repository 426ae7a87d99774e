//! `fair curve`: read, check, fair, write the points, the report and the plot.
//!
//! Order of checks (so that the user's mistakes are reported before anything runs): the
//! input file, the number of points, `--kind`, `--method`, the parameters, the constraints.
//! Then [`fair`] (the SEAM to the strategies; [`stages`] chains several), then the outputs.
//! A directory or a JSON-lines stream is a [`batch`].

use crate::args::FairArgs;
use crate::commands::{measure, say, write_results};
use crate::config::{self, ConfigConstraints, ConfigFile};
use crate::constraints::Constraints;
use crate::error::{Error, Result};
use crate::input::{self, CurveInput, Points};
use crate::kind::{self, CurveKind};
use crate::parameters::Parameters;
use crate::plots::{planar_view, CurvePlot};
use crate::progress;
use crate::registry::{self, MethodInfo, MethodKind};
use crate::report::{Energies, Report};
use std::collections::BTreeMap;

pub mod batch;
mod batten;
mod nurbs_weights;
mod sapidis_farin;
mod smoothing_spline;
pub mod stages;
mod strain_energy;
mod strategy_run;
mod two_phase;

/// The fewest points any curve method works on: curvature-slope jumps e_i need three.
pub const MIN_CURVE_POINTS: usize = 3;

/// The default method for a kind of curve.
pub fn default_method(kind: CurveKind) -> &'static str {
    match kind {
        CurveKind::Function => "two-phase",
        CurveKind::Parametric => "strain-energy",
    }
}

/// Everything a strategy gets.
#[derive(Debug, Clone)]
pub struct CurveJob<'a> {
    /// The points as read.
    pub input: &'a CurveInput,
    /// Function or parametric.
    pub kind: CurveKind,
    /// The method.
    pub method: &'static MethodInfo,
    /// Its parameters as given (defaults are the method's to apply).
    pub parameters: &'a Parameters,
    /// Fixed points, bad points, tolerance, ends.
    pub constraints: &'a Constraints,
}

/// What a strategy gives back.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveOutcome {
    /// The faired data points: same count and order as the input (unchanged for methods that
    /// change weights).
    pub points: Points,
    /// Iterations run.
    pub iterations: usize,
    /// Indices of the points that moved.
    pub moved: Vec<usize>,
    /// Time of the fairing itself, in milliseconds.
    pub elapsed_ms: f64,
    /// The faired curve for the report's `curve`.
    pub curve: serde_json::Value,
    /// Method-specific extras for the report (termination reason, trace, ...).
    pub extras: BTreeMap<String, serde_json::Value>,
    /// For methods whose curve is not the spline the measures are defined on (nurbs-weights
    /// changes weights, not points): the energies of the curve as represented before and
    /// after, which replace the report's `before.energies` and `after.energies` as DESIGN.md
    /// asks ("energies over the curve as represented").
    pub represented_energies: Option<(Energies, Energies)>,
}

/// SEAM: runs the strategy of `job.method` (crate `fairing`).
pub fn fair(job: &CurveJob) -> Result<CurveOutcome> {
    match job.method.name {
        "nurbs-weights" => nurbs_weights::fair(job),
        "strain-energy" | "kjellander" | "poliakoff" => strain_energy::fair(job),
        "batten" => batten::fair(job),
        "smoothing-spline" => smoothing_spline::fair(job),
        "sapidis-farin" => sapidis_farin::fair(job),
        "two-phase" => two_phase::fair(job),
        _ => Err(Error::NotAvailable {
            what: format!("method `{}`", job.method.name),
        }),
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

/// A faired curve, ready to be written: what one input of `fair curve` produces.
#[derive(Debug, Clone)]
pub struct Faired {
    /// The JSON report.
    pub report: Report,
    /// The faired points in the input's format.
    pub points_text: String,
    /// The before/after picture.
    pub plot: CurvePlot,
}

/// What runs: the stages (one for `--method`, several for a config with `[[stage]]`) and the
/// config file's constraints.
#[derive(Debug, Clone)]
pub struct Plan {
    /// Each stage's method and parameters, in order.
    pub stages: Vec<(&'static MethodInfo, Parameters)>,
    /// The config file's `[constraints]` (the command line wins).
    pub config_constraints: ConfigConstraints,
}

impl Plan {
    /// The plan a command line and its config file imply for a curve of `kind`.
    pub fn new(args: &FairArgs, file: Option<&ConfigFile>, kind: CurveKind) -> Result<Plan> {
        let config_constraints = file.map(ConfigFile::constraints).transpose()?.unwrap_or_default();
        if let Some(stages) = file.map(|f| f.stages(MethodKind::Curve)).transpose()?.flatten() {
            if args.method.is_some() {
                return Err(Error::Argument {
                    option: "--method",
                    message:
                        "the config file defines a pipeline of [[stage]]s; give either --method or the stages"
                            .into(),
                });
            }
            if !args.settings.is_empty() {
                return Err(Error::Argument {
                    option: "--set",
                    message: "the config file defines a pipeline; set parameters in its [[stage]] tables"
                        .into(),
                });
            }
            let stages = stages
                .into_iter()
                .map(|stage| {
                    Ok((
                        stage.method,
                        Parameters::from_values(stage.method, stage.values, &[])?,
                    ))
                })
                .collect::<Result<Vec<_>>>()?;
            return Ok(Plan {
                stages,
                config_constraints,
            });
        }
        let method = registry::find(
            args.method.as_deref().unwrap_or(default_method(kind)),
            MethodKind::Curve,
        )?;
        let values = match file {
            Some(file) => file.method_values(method.name)?,
            None => Vec::new(),
        };
        let parameters = Parameters::from_values(method, values, &args.settings)?;
        Ok(Plan {
            stages: vec![(method, parameters)],
            config_constraints,
        })
    }

    /// The methods that take bad points (`--points`): the interactive strain-energy family.
    pub const BAD_POINT_METHODS: [&'static str; 3] = ["strain-energy", "kjellander", "poliakoff"];

    /// Refuses `--points` when no stage takes bad points (the other methods find the unfair
    /// points themselves, or change weights), instead of ignoring it. O(stages).
    pub fn check_bad_points(&self, constraints: &Constraints) -> Result<()> {
        let takes = |name: &str| Self::BAD_POINT_METHODS.contains(&name);
        if constraints.bad_points.is_empty() || self.stages.iter().any(|(m, _)| takes(m.name)) {
            return Ok(());
        }
        Err(Error::Argument {
            option: "--points",
            message: format!(
                "`{}` takes no bad points (it finds what to change itself); the methods that do: {}",
                self.name(),
                Self::BAD_POINT_METHODS.join(", ")
            ),
        })
    }

    /// The report's `method`: the method, or the stages' names joined by `+`.
    pub fn name(&self) -> String {
        let names: Vec<&str> = self.stages.iter().map(|(m, _)| m.name).collect();
        names.join("+")
    }
}

/// Reads, checks and fairs one curve input: everything `fair curve` does but writing.
///
/// Order of checks: the number of points, `--kind`, the method(s) and parameters, the
/// constraints; then the stages; then the measures, the report and the output text (so that
/// nothing is written for a run that fails).
///
/// Every error about the points names the input file (not "the points").
pub fn process(input: &CurveInput, args: &FairArgs, file: Option<&ConfigFile>) -> Result<Faired> {
    process_points(input, args, file).map_err(|e| measure::in_file(e, &input.source))
}

/// [`process`], errors about the points not yet named after the file.
fn process_points(input: &CurveInput, args: &FairArgs, file: Option<&ConfigFile>) -> Result<Faired> {
    input.require_at_least(MIN_CURVE_POINTS, "a curve")?;
    let kind = kind::resolve(args.kind, input)?;
    let plan = Plan::new(args, file, kind)?;
    let constraints = Constraints::from_args_and_config(args, &plan.config_constraints, input.len())?;
    plan.check_bad_points(&constraints)?;
    let outcome = stages::run(input, kind, &plan, &constraints)?;
    if kind == CurveKind::Function {
        check_still_a_function(&outcome.points, &plan)?;
    }
    let mut before = measure::curve(kind, &input.points)?;
    let mut after = measure::curve(kind, &outcome.points)?;
    if let Some((energies_before, energies_after)) = outcome.represented_energies {
        before.measures.energies = Some(energies_before);
        after.measures.energies = Some(energies_after);
        // Integrated by the method's own criteria to their default tolerance (they fail
        // rather than return an unmet one): no error estimate to report.
        before.measures.energy_accuracy = None;
        after.measures.energy_accuracy = None;
    }
    let (s_d, m_d) = displacement(&input.points, &outcome.points);
    let params = match plan.stages.as_slice() {
        [(_, parameters)] => parameters.to_json(),
        _ => BTreeMap::new(),
    };
    let report = Report {
        method: plan.name(),
        kind: kind.report_kind(),
        n: input.len(),
        iterations: outcome.iterations,
        before: before.measures.clone(),
        after: after.measures.clone(),
        s_d,
        m_d,
        moved: outcome.moved.clone(),
        elapsed_ms: outcome.elapsed_ms,
        curve: outcome.curve.clone(),
        params,
        extras: outcome.extras.clone(),
    };
    let points_text = crate::output::format_curve_as(input, &outcome.points, output_format(args)?)?;
    let plot = CurvePlot {
        title: format!("{} — {}", input.source, report.method),
        input: planar_view(&input.points),
        faired: Some(planar_view(&outcome.points)),
        input_curve: before.samples,
        faired_curve: after.samples,
        comb: after.comb,
        z_before: before.z,
        z_after: after.z,
        function: kind == CurveKind::Function,
        curvature_before: before.curvature,
        curvature_after: after.curvature,
        axes: Some(crate::plots::axis_names(&input.coordinate_names())),
        projections: crate::plots::other_projections(
            &input.coordinate_names(),
            &input.points,
            Some(&outcome.points),
        ),
    };
    Ok(Faired {
        report,
        points_text,
        plot,
    })
}

/// The format of the faired points: by `-o`'s extension for a single curve (a batch writes
/// each file in its own format).
fn output_format(args: &FairArgs) -> Result<crate::output::OutputFormat> {
    match &args.output {
        Some(path) if !batch::is_batch(args) => crate::output::OutputFormat::of_path(path),
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
pub fn run(args: &FairArgs) -> Result<()> {
    let file = args.config.as_deref().map(ConfigFile::read).transpose()?;
    if batch::is_batch(args) {
        return batch::run(args, file.as_ref());
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
        let plan = Plan::new(args, file.as_ref(), kind)?;
        let constraints = Constraints::from_args_and_config(args, &plan.config_constraints, input.len())?;
        plan.check_bad_points(&constraints)?;
        // The methods check their values when they run: run it, so that a config that would
        // fail is not printed as if it were good.
        process(&input, args, file.as_ref())?;
        let stages: Vec<_> = plan.stages.iter().map(|(m, p)| (*m, p.given_values())).collect();
        say(false, false, config::render(&constraints, &stages).trim_end());
        return Ok(());
    }
    let faired = {
        let _activity = progress::Activity::start(
            &format!("fairing and measuring {} ({} points)", input.source, input.len()),
            args.quiet,
        );
        process(&input, args, file.as_ref())?
    };
    write_results(args, &faired.report, &faired.points_text, || faired.plot.figure())?;
    let report = &faired.report;
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
