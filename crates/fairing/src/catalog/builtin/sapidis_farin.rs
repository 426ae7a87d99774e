//! `sapidis-farin`: Sapidis & Farin's knot removal and reinsertion on the cubic interpolating
//! B-spline ([`SapidisFarin`]). The data points are mapped to the faired curve at their
//! parameters; knots whose fairing would move a fixed point, leave the tolerance band or move
//! a point beyond `max-move` (by default the bound the data imply) are skipped. A function y(x) is faired as the graph of a B-spline parametrised by its
//! abscissa, x kept; a parametric curve over chord length.

use curve_repr::Vector;
use fairness::curvature::CurvatureForm;

use super::indicator_for;
use super::smoothing_spline::domain;
use crate::catalog::{run_strategy, CurveJob, CurveMethod, CurvePoints, CurveRun, Settings};
use crate::strategies::{CurveDomain, SapidisFarin, SapidisFarinSettings, SapidisFarinStop};
use crate::Result;

impl Settings for SapidisFarinSettings {
    fn validate(&self) -> Result<()> {
        SapidisFarinSettings::validate(self)
    }
}

/// The `sapidis-farin` method.
#[derive(Clone, Copy, Debug, Default)]
pub struct SapidisFarinMethod;

impl CurveMethod for SapidisFarinMethod {
    type Settings = SapidisFarinSettings;

    /// The indicator must be registered for the points' dimension; every end clamp is held.
    fn check(&self, settings: &SapidisFarinSettings, job: &CurveJob) -> Result<()> {
        if settings.indicator != SapidisFarinSettings::PAPER_INDICATOR {
            match job.points {
                CurvePoints::Planar(_) => indicator_for::<2>(job, &settings.indicator).map(|_| ())?,
                CurvePoints::Spatial(_) => indicator_for::<3>(job, &settings.indicator).map(|_| ())?,
            }
        }
        Ok(())
    }

    fn run(&self, settings: &SapidisFarinSettings, job: &CurveJob) -> Result<CurveRun> {
        let mut settings = settings.clone();
        settings.domain = domain(job.kind);
        match job.points {
            CurvePoints::Planar(p) => run_points(settings, job, p),
            CurvePoints::Spatial(p) => run_points(settings, job, p),
        }
    }
}

fn run_points<const D: usize>(
    settings: SapidisFarinSettings,
    job: &CurveJob,
    points: &[Vector<D>],
) -> Result<CurveRun>
where
    Vector<D>: CurvatureForm,
{
    let mut strategy = SapidisFarin::<D>::new(settings.clone());
    if settings.indicator != SapidisFarinSettings::PAPER_INDICATOR {
        strategy = strategy.with_indicator(indicator_for::<D>(job, &settings.indicator)?);
    }
    // One more step than knots to fair: the last one reports done.
    let steps = settings.max_iterations.saturating_add(1);
    let mut run = run_strategy(Box::new(&mut strategy), points, job, steps)?;
    let mut curve = match strategy.curve() {
        Some(curve) => serde_json::to_value(curve).unwrap_or_default(),
        None => serde_json::Value::Null,
    };
    if let Some(object) = curve.as_object_mut() {
        object.insert("params".into(), serde_json::json!(strategy.params()));
        let parametrization = match settings.domain {
            CurveDomain::Function => "x",
            CurveDomain::Parametric => "chord-length",
        };
        object.insert("parametrization".into(), serde_json::json!(parametrization));
    }
    run.curve = curve;
    run.termination = match strategy.stop() {
        Some(SapidisFarinStop::JumpReduction) => "jump-reduction",
        Some(SapidisFarinStop::NoCandidate) => "no-candidate",
        Some(SapidisFarinStop::MaxIterations) | None => "max-iterations",
    }
    .to_owned();
    let steps: Vec<serde_json::Value> = strategy
        .history()
        .iter()
        .map(|s| serde_json::json!({"knot": s.knot, "jump_before": s.jump_before, "max_jump_after": s.max_jump_after}))
        .collect();
    run.iterations = strategy.history().len();
    run.extras
        .insert("jump_reduction".into(), settings.jump_reduction.into());
    run.extras
        .insert("move_bound".into(), serde_json::json!(strategy.move_bound()));
    run.extras
        .insert("max_jump_before".into(), strategy.initial_max_jump().into());
    run.extras
        .insert("max_jump_after".into(), strategy.max_jump().into());
    run.extras
        .insert("knots_faired".into(), strategy.history().len().into());
    run.extras.insert("steps".into(), serde_json::Value::Array(steps));
    Ok(run)
}
