//! `jump-lsq`: least squares on the points with a penalty on the roughness of their
//! spline's third-derivative jumps ([`JumpLsq`]), λ chosen automatically. Both kinds, 2D and
//! 3D, every constraint. A closed curve (`closed = true`, or a parametric polygon given with
//! its first point repeated at the end) is faired with the periodic spline; the repeated
//! copy is written back equal to the faired first point, so the polygon stays closed.
//!
//! The report's extras: `lambda`, `sigma` (the noise estimate σ̂), `rule` (`discrepancy`,
//! `gcv`, `gml`, `target-sd` or `given`; under `rule = auto` the rule whose fit was kept), `target_sd`, `rms_displacement`, `lambda_limited`, `gcv`,
//! `trace` (tr A(λ), the fit's degrees of freedom, under the GCV rule), `solves`, `refits`, `pinned`, `reweighted`, `band_rounds`, `clipped`, `penalty_before`,
//! `penalty_after`, `closed`, `ends` (the spline's end conditions at the start and the end:
//! `runout`, `natural` or `periodic`; `function-ends` = `auto` reports its choice),
//! `difference_order` (the penalty's d; `difference-order` = `auto` reports its choice),
//! `exponent` (the penalty's spacing exponent a; `exponent` = `auto` reports its choice),
//! `knots` (beyond 10^4 points with λ chosen by a rule: the bins of the reduced basis the
//! fit was made on, its λ and `rule` theirs; `null` with one knot per point),
//! `warnings` (what kept the run from doing its job: λ at its precision limit, a degenerate
//! σ̂, no point moved; the command prints them on standard error).

use curve_repr::Vector;
use fairness::curvature::CurvatureForm;
use serde_json::json;

use super::smoothing_spline::domain;
use crate::catalog::{run_strategy, CurveJob, CurveKind, CurveMethod, CurvePoints, CurveRun, Settings};
use crate::strategies::jump_lsq::{JumpLsq, JumpLsqReport, JumpLsqSettings};
use crate::strategies::CurveDomain;
use crate::{Constraints, EndClamp, Error, Refusal, Result};

impl Settings for JumpLsqSettings {
    fn validate(&self) -> Result<()> {
        JumpLsqSettings::validate(self)
    }
}

/// The `jump-lsq` method.
#[derive(Clone, Copy, Debug, Default)]
pub struct JumpLsqMethod;

/// Whether the job's points are a closed polygon with its first point repeated at the end
/// (two-phase reads a closed curve the same way).
pub(in crate::catalog) fn repeats_first(points: &CurvePoints) -> bool {
    fn repeated<const D: usize>(p: &[Vector<D>]) -> bool {
        p.len() > 4 && p.first() == p.last()
    }
    match points {
        CurvePoints::Planar(p) => repeated(p),
        CurvePoints::Spatial(p) => repeated(p),
    }
}

/// Whether a parametric job's points are a closed polygon: the last point repeats the first,
/// unless both are fixed (a curve opened at a corner, [`crate::corners`], runs from the corner
/// round to the same point).
pub(super) fn closes(job: &CurveJob) -> bool {
    let n = job.points.len();
    let fixed = job.constraints.fixed();
    job.kind == CurveKind::Parametric
        && repeats_first(job.points)
        && !(fixed.contains(&0) && fixed.contains(&(n - 1)))
}

fn is_closed(settings: &JumpLsqSettings, job: &CurveJob) -> bool {
    settings.closed || closes(job)
}

impl CurveMethod for JumpLsqMethod {
    type Settings = JumpLsqSettings;

    /// A closed curve has no ends to clamp and cannot be a function y(x).
    fn check(&self, settings: &JumpLsqSettings, job: &CurveJob) -> Result<()> {
        if !is_closed(settings, job) {
            return Ok(());
        }
        if job.kind == CurveKind::Function {
            return Err(Error::Refused {
                method: job.method.to_owned(),
                what: Refusal::Kind,
                reason: "fairs a closed curve only as a parametric curve (x of a function increases)".into(),
            });
        }
        if job.constraints.end_clamp() != EndClamp::None {
            return Err(Error::Refused {
                method: job.method.to_owned(),
                what: Refusal::EndClamp,
                reason: format!(
                    "fairs a closed curve (periodic spline), which has no ends to clamp ({})",
                    job.constraints.end_clamp().name()
                ),
            });
        }
        Ok(())
    }

    fn run(&self, settings: &JumpLsqSettings, job: &CurveJob) -> Result<CurveRun> {
        match job.points {
            CurvePoints::Planar(p) => fit(settings, job, p),
            CurvePoints::Spatial(p) => fit(settings, job, p),
        }
    }
}

/// The constraints of the first n − 1 points of a polygon whose point n − 1 repeats point 0:
/// what held either copy holds point 0.
pub(super) fn without_repeat(constraints: &Constraints, n: usize) -> Constraints {
    let last = n - 1;
    let mut fixed: Vec<usize> = constraints
        .fixed()
        .iter()
        .copied()
        .filter(|&i| i < last)
        .collect();
    if constraints.fixed().contains(&last) {
        fixed.push(0);
    }
    let mut reduced = Constraints::default()
        .with_fixed(fixed)
        .with_end_clamp(constraints.end_clamp());
    if let Some(d) = constraints.tolerance() {
        reduced = reduced.with_tolerance(d);
    }
    if let Some(radii) = constraints.restraining_radii() {
        let mut r = radii[..last].to_vec();
        r[0] = r[0].min(radii[last]);
        reduced = reduced.with_restraining_radii(r);
    }
    reduced
}

fn fit<const D: usize>(settings: &JumpLsqSettings, job: &CurveJob, points: &[Vector<D>]) -> Result<CurveRun>
where
    Vector<D>: CurvatureForm,
{
    let closed = is_closed(settings, job);
    let repeated = closed && repeats_first(job.points);
    let n = points.len();
    let reduced;
    let (input, job_used) = if repeated {
        reduced = without_repeat(job.constraints, n);
        (
            &points[..n - 1],
            CurveJob {
                constraints: &reduced,
                ..*job
            },
        )
    } else {
        (points, *job)
    };
    let domain = domain(job.kind);
    let mut strategy = JumpLsq::<D>::new(settings.clone().with_closed(closed), domain);
    let mut run = run_strategy(Box::new(&mut strategy), input, &job_used, 1)?;
    let Some(report) = strategy.report().cloned() else {
        return Err(crate::strategy_error(job.method, "no solve was made"));
    };
    if repeated {
        let mut faired: Vec<Vector<D>> = run
            .points
            .as_dimension::<D>()
            .map(<[_]>::to_vec)
            .unwrap_or_default();
        let first = faired[0];
        faired.push(first);
        if first != points[n - 1] {
            run.moved.push(n - 1);
        }
        run.points = CurvePoints::from_vectors(faired).unwrap_or(CurvePoints::Planar(Vec::new()));
    }
    run.curve = json!({
        "type": "interpolating-cubic-spline",
        "end_condition": if closed {
            "periodic"
        } else if domain == CurveDomain::Function {
            "parabolic-runout"
        } else {
            "natural"
        },
        "parametrization": match domain {
            CurveDomain::Function => "x",
            CurveDomain::Parametric => "chord-length",
        },
        "closed": closed,
    });
    for (name, value) in report_fields(&report) {
        run.extras.insert(name.into(), value);
    }
    run.extras.insert("closed".into(), json!(closed));
    run.extras.insert("warnings".into(), json!(warnings(&report)));
    Ok(run)
}

/// What kept the run from doing its job, in words for the report's `warnings` (the command
/// prints them on standard error): λ stopped at its precision limit, a noise estimate σ̂ that
/// is 0 or not finite where the rule used it, no point moved although λ was not given as 0.
pub(crate) fn warnings(report: &JumpLsqReport) -> Vec<String> {
    let mut out = Vec::new();
    if report.lambda_limited {
        out.push(format!(
            "λ stopped at its precision limit ({:e}) before the `{}` rule was satisfied: the \
             fit may keep noise the rule wanted removed",
            report.lambda, report.rule
        ));
    }
    let uses_sigma = matches!(report.rule.as_str(), "discrepancy" | "gml" | "gcv");
    if uses_sigma && !(report.sigma_hat.is_finite() && report.sigma_hat > 0.0) {
        out.push(format!(
            "the noise estimate σ̂ is {} (the points' third differences are mostly equal, as on \
             a zigzag or an exactly tabulated polynomial): λ was chosen without it",
            report.sigma_hat
        ));
    }
    if report.rule != "given" && report.rms_displacement == 0.0 && report.clipped == 0 {
        out.push(format!(
            "moved no point (rule `{}`, λ = {:e})",
            report.rule, report.lambda
        ));
    }
    out
}

/// jump-lsq's report as the catalogue spells it (the extras of its runs but `closed`, in the
/// module doc's order); two-phase's `prepass` report field reuses it.
pub(super) fn report_fields(report: &JumpLsqReport) -> Vec<(&'static str, serde_json::Value)> {
    vec![
        ("lambda", json!(report.lambda)),
        ("sigma", json!(report.sigma_hat)),
        ("rule", json!(report.rule)),
        ("target_sd", json!(report.target_sd)),
        ("rms_displacement", json!(report.rms_displacement)),
        ("lambda_limited", json!(report.lambda_limited)),
        ("gcv", json!(report.gcv)),
        ("trace", json!(report.trace)),
        ("solves", json!(report.solves)),
        ("refits", json!(report.refits)),
        ("pinned", json!(report.pinned)),
        ("reweighted", json!(report.reweighted)),
        ("band_rounds", json!(report.band_rounds)),
        ("clipped", json!(report.clipped)),
        ("penalty_before", json!(report.penalty_before)),
        ("penalty_after", json!(report.penalty_after)),
        ("ends", json!(report.ends)),
        ("difference_order", json!(report.difference_order)),
        ("exponent", json!(report.exponent)),
        ("knots", json!(report.knots)),
    ]
}
