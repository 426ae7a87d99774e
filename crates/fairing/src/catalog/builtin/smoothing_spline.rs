//! `smoothing-spline`: the smoothing spline baseline (the papers' MST) via
//! [`SmoothingSplineFairing`]. Every free point moves onto the spline; fixed points and
//! clamped ends are interpolation constraints (weight +∞); the tolerance band is met by
//! reweighting. A function y(x) is smoothed as y over x (x kept); a parametric curve
//! coordinate by coordinate over its chord-length parameters. A closed polygon given with
//! its first point repeated at the end keeps both copies where they are, so that it stays
//! closed (the fit is not periodic).
//!
//! The report's `p` is the smoothing parameter used and `rule` the rule that chose it: under
//! the default `rule = auto` the criterion whose fit was kept (`gml` or `gcv`), with the
//! noise estimate σ̂ that refereed as `sigma` (jump-lsq's name); `gcv` is GCV's score when GCV chose p.

use curve_repr::Vector;
use fairness::curvature::CurvatureForm;

use crate::catalog::{run_strategy, CurveJob, CurveKind, CurveMethod, CurvePoints, CurveRun, Settings};
use crate::strategies::{CurveDomain, SmoothingSettings, SmoothingSplineFairing};
use crate::{FairingStrategy, Result};

impl Settings for SmoothingSettings {
    fn validate(&self) -> Result<()> {
        SmoothingSettings::validate(self)
    }
}

/// The `smoothing-spline` method.
#[derive(Clone, Copy, Debug, Default)]
pub struct SmoothingSplineMethod;

pub(super) fn domain(kind: CurveKind) -> CurveDomain {
    match kind {
        CurveKind::Function => CurveDomain::Function,
        CurveKind::Parametric => CurveDomain::Parametric,
    }
}

impl CurveMethod for SmoothingSplineMethod {
    type Settings = SmoothingSettings;

    /// End clamps above g0 are refused.
    fn check(&self, settings: &SmoothingSettings, job: &CurveJob) -> Result<()> {
        let domain = domain(job.kind);
        match job.points {
            CurvePoints::Planar(_) => {
                SmoothingSplineFairing::<2>::new(settings.clone(), domain).supports(job.constraints)
            }
            CurvePoints::Spatial(_) => {
                SmoothingSplineFairing::<3>::new(settings.clone(), domain).supports(job.constraints)
            }
        }
    }

    fn run(&self, settings: &SmoothingSettings, job: &CurveJob) -> Result<CurveRun> {
        match job.points {
            CurvePoints::Planar(p) => fit(settings, job, p),
            CurvePoints::Spatial(p) => fit(settings, job, p),
        }
    }
}

fn fit<const D: usize>(settings: &SmoothingSettings, job: &CurveJob, points: &[Vector<D>]) -> Result<CurveRun>
where
    Vector<D>: CurvatureForm,
{
    let closed = points.len() > 2 && points.first() == points.last();
    let constraints = if closed {
        job.constraints.clone().with_fixed([0, points.len() - 1])
    } else {
        job.constraints.clone()
    };
    let job = CurveJob {
        constraints: &constraints,
        ..*job
    };
    let domain = domain(job.kind);
    let mut strategy = SmoothingSplineFairing::<D>::new(settings.clone(), domain);
    let mut run = run_strategy(Box::new(&mut strategy), points, &job, 1)?;
    let Some(spline) = strategy.fit() else {
        return Err(crate::strategy_error(job.method, "no fit was made"));
    };
    let coordinates =
        |v: &[Vector<D>]| -> Vec<Vec<f64>> { v.iter().map(|p| p.iter().copied().collect()).collect() };
    run.curve = serde_json::json!({
        "type": "natural-cubic-spline",
        "parametrization": match domain {
            CurveDomain::Function => "x",
            CurveDomain::Parametric => "chord-length",
        },
        "knots": spline.knots(),
        "values": coordinates(spline.values()),
        "second_derivatives": coordinates(spline.second_derivatives()),
    });
    run.extras.insert("p".into(), spline.p().into());
    run.extras.insert("rule".into(), spline.rule().name().into());
    run.extras.insert("gcv".into(), serde_json::json!(spline.gcv()));
    run.extras
        .insert("sigma".into(), serde_json::json!(spline.sigma_hat()));
    run.extras
        .insert("bending_energy".into(), spline.bending_energy().into());
    run.extras.insert("reweights".into(), strategy.reweights().into());
    run.extras.insert("clipped".into(), strategy.clipped().into());
    Ok(run)
}
