//! `fair curve`: read, check, fair, write the points, the report and the plot.
//!
//! Order of checks (so that the user's mistakes are reported before anything runs): the
//! input file, the number of points, `--kind`, `--method`, the parameters, the constraints.
//! Then [`fair`] (the SEAM to the strategies), then the outputs.

use crate::args::FairArgs;
use crate::commands::{measure, say};
use crate::constraints::Constraints;
use crate::error::{Error, Result};
use crate::input::{self, CurveInput, Points};
use crate::kind::{self, CurveKind};
use crate::parameters::Parameters;
use crate::plots::{planar_view, CurvePlot};
use crate::registry::{self, MethodInfo, MethodKind};
use crate::report::{Energies, Report};
use std::collections::BTreeMap;

mod nurbs_weights;
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

/// Runs `fair curve`.
pub fn run(args: &FairArgs) -> Result<()> {
    let input = input::read_curve(&args.input)?;
    input.require_at_least(MIN_CURVE_POINTS, "a curve")?;
    let kind = kind::resolve(args.kind, &input)?;
    let method = registry::find(
        args.method.as_deref().unwrap_or(default_method(kind)),
        MethodKind::Curve,
    )?;
    let parameters = Parameters::collect(method, args.config.as_deref(), &args.settings)?;
    let constraints = Constraints::from_args(args, input.len())?;

    let job = CurveJob {
        input: &input,
        kind,
        method,
        parameters: &parameters,
        constraints: &constraints,
    };
    let outcome = fair(&job)?;
    if outcome.points.len() != input.len() || outcome.points.dimension() != input.points.dimension() {
        return Err(Error::Internal {
            message: format!(
                "method `{}` returned {} points for {}",
                method.name,
                outcome.points.len(),
                input.len()
            ),
        });
    }
    let mut before = measure::curve(kind, &input.points)?;
    let mut after = measure::curve(kind, &outcome.points)?;
    if let Some((energies_before, energies_after)) = outcome.represented_energies {
        before.measures.energies = Some(energies_before);
        after.measures.energies = Some(energies_after);
    }
    let (s_d, m_d) = displacement(&input.points, &outcome.points);
    let report = Report {
        method: method.name.into(),
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
        params: parameters.to_json(),
        extras: outcome.extras.clone(),
    };
    // Everything is checked before anything is written.
    let points_text = crate::output::format_curve(&input, &outcome.points)?;
    let report_text = report.to_json()?;
    if let Some(out) = &args.output {
        crate::output::write_text(out, &points_text)?;
    }
    if let Some(path) = &args.report {
        crate::output::write_text(&path.display().to_string(), &report_text)?;
    }
    if let Some(path) = &args.plot {
        let plot = CurvePlot {
            title: format!("{} — {}", input.source, method.name),
            input: planar_view(&input.points),
            faired: Some(planar_view(&outcome.points)),
            input_curve: before.samples,
            faired_curve: after.samples,
            comb: after.comb,
            z_before: before.z,
            z_after: after.z,
            function: kind == CurveKind::Function,
        };
        plot.figure().write(path)?;
    }
    say(
        args.quiet,
        args.output.as_deref() == Some("-"),
        &format!(
            "{}: {} ({} points, {:?}): {} iterations, {} moved, S_d = {s_d:.6e}, M_d = {m_d:.6e}",
            input.source,
            method.name,
            input.len(),
            kind,
            report.iterations,
            report.moved.len()
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
