//! `--method smoothing-spline`: the smoothing spline baseline (the papers' MST) via
//! [`fairing::strategies::SmoothingSplineFairing`]. Every free point moves onto the spline;
//! fixed points and clamped ends are interpolation constraints (weight +∞); the tolerance band
//! is met by reweighting.
//!
//! Parameters (registry): `p` (a number in [0, 1] or `auto`, default auto) and `rule`
//! (`gcv` or `trace`, default gcv: it looks at the data's noise, while csaps's trace rule
//! depends on the parameters alone and is known to smooth little on dense data). The report's
//! extras say which p was used (`p`) and how it was chosen (`rule`: given, gcv or trace).
//!
//! A function y(x) is smoothed as y over x (x kept); a parametric curve coordinate by
//! coordinate over its chord-length parameters. A closed polygon given with its first point
//! repeated at the end (a Selig airfoil with a sharp trailing edge, say) keeps both ends where
//! they are, so that it stays closed: the fit is not periodic, and would otherwise move the
//! two copies of that point apart.

use std::collections::BTreeMap;

use curve_repr::Vector;
use fairing::strategies::{CurveDomain, SmoothingRule, SmoothingSettings, SmoothingSplineFairing};

use super::strategy_run::{by_dimension, fairing_constraints, run, Described};
use super::{CurveJob, CurveOutcome};
use crate::error::{Error, Result};
use crate::kind::CurveKind;

/// Reads the parameters, runs the fit, describes it.
pub fn fair(job: &CurveJob) -> Result<CurveOutcome> {
    let parameters = job.parameters;
    let rule = match parameters.choice("rule", &["gcv", "trace"], "gcv")?.as_str() {
        "trace" => SmoothingRule::Trace,
        _ => SmoothingRule::Gcv,
    };
    let mut settings = SmoothingSettings::default().with_rule(rule);
    if let Some(given) = parameters.get("p") {
        if given.value != "auto" {
            let p = parameters.number("p", 1.0)?;
            if !(0.0..=1.0).contains(&p) {
                return Err(Error::Parameter {
                    origin: given.origin.clone(),
                    message: format!("`p` = `{}` must lie in [0, 1] (or be `auto`)", given.value),
                });
            }
            settings = settings.with_p(p);
        }
    }
    let domain = match job.kind {
        CurveKind::Function => CurveDomain::Function,
        CurveKind::Parametric => CurveDomain::Parametric,
    };
    let constraints = fairing_constraints(job.constraints);
    let planar_settings = settings.clone();
    let planar_constraints = constraints.clone();
    by_dimension(
        job,
        move |points| fit(points, planar_settings, domain, planar_constraints),
        move |points| fit(points, settings, domain, constraints),
    )
}

fn fit<const D: usize>(
    points: &[Vector<D>],
    settings: SmoothingSettings,
    domain: CurveDomain,
    constraints: fairing::Constraints,
) -> fairing::Result<(Vec<Vector<D>>, Described)> {
    let closed = points.len() > 2 && points.first() == points.last();
    let constraints = if closed {
        constraints.with_fixed([0, points.len() - 1])
    } else {
        constraints
    };
    let mut strategy = SmoothingSplineFairing::<D>::new(settings, domain);
    let result = run(&mut strategy, points.to_vec(), constraints, 1)?;
    let Some(spline) = strategy.fit() else {
        return Err(fairing::Error::Strategy {
            strategy: "smoothing-spline".into(),
            reason: "no fit was made".into(),
        });
    };
    let coordinates =
        |v: &[Vector<D>]| -> Vec<Vec<f64>> { v.iter().map(|p| p.iter().copied().collect()).collect() };
    let curve = serde_json::json!({
        "type": "natural-cubic-spline",
        "parametrization": match domain {
            CurveDomain::Function => "x",
            CurveDomain::Parametric => "chord-length",
        },
        "knots": spline.knots(),
        "values": coordinates(spline.values()),
        "second_derivatives": coordinates(spline.second_derivatives()),
    });
    let mut extras = BTreeMap::new();
    extras.insert("p".into(), serde_json::json!(spline.p()));
    extras.insert("rule".into(), serde_json::json!(spline.rule().name()));
    extras.insert("gcv".into(), serde_json::json!(spline.gcv()));
    extras.insert(
        "bending_energy".into(),
        serde_json::json!(spline.bending_energy()),
    );
    extras.insert("reweights".into(), serde_json::json!(strategy.reweights()));
    extras.insert("clipped".into(), serde_json::json!(strategy.clipped()));
    extras.insert("termination".into(), serde_json::json!(result.termination));
    Ok((
        result.points,
        Described {
            curve,
            extras,
            moved: result.moved,
            iterations: result.iterations,
            elapsed_ms: result.elapsed_ms,
        },
    ))
}
