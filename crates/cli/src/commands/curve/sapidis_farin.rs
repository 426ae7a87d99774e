//! `--method sapidis-farin`: Sapidis & Farin's knot removal and reinsertion on the cubic
//! interpolating B-spline, via [`fairing::strategies::SapidisFarin`]. The data points are
//! mapped to the faired curve at their parameters; knots whose fairing would move a fixed
//! point or leave the tolerance band are skipped.
//!
//! Parameters (registry): `jump-reduction` (stop when the largest curvature-slope jump is at
//! most this fraction of the initial one; default 1e-3), `max-iterations` (knots faired at
//! most; default 1000) and `max-move` (data | off | a distance: how far a point may move
//! without `--tolerance`; default data, the bound the data imply). A function y(x) is faired as the graph of a B-spline parametrised by its
//! abscissa, x kept; a parametric curve over chord length.

use std::collections::BTreeMap;

use curve_repr::Vector;
use fairing::strategies::{CurveDomain, MoveBound, MoveRule, SapidisFarin, SapidisFarinSettings, SapidisFarinStop};
use fairness::curvature::CurvatureForm;

use super::strategy_run::{by_dimension, fairing_constraints, run, Described};
use super::{CurveJob, CurveOutcome};
use crate::error::{Error, Result};
use crate::kind::CurveKind;

/// Reads the parameters, runs the fairing, describes it.
pub fn fair(job: &CurveJob) -> Result<CurveOutcome> {
    let parameters = job.parameters;
    let defaults = SapidisFarinSettings::default();
    let origin = |name: &str| {
        parameters
            .get(name)
            .map(|g| g.origin.clone())
            .unwrap_or_default()
    };
    let jump_reduction = parameters.number("jump-reduction", defaults.jump_reduction)?;
    if jump_reduction < 0.0 {
        return Err(Error::Parameter {
            origin: origin("jump-reduction"),
            message: format!("`jump-reduction` = {jump_reduction} must not be negative"),
        });
    }
    let max_move = match parameters.get("max-move").map(|g| g.value.as_str()) {
        None => defaults.max_move,
        Some("data") => MoveBound::Rule(MoveRule::Data),
        Some("off") => MoveBound::Rule(MoveRule::Off),
        Some(text) => match text.parse::<f64>() {
            Ok(d) if d.is_finite() && d >= 0.0 => MoveBound::Distance(d),
            _ => {
                return Err(Error::Parameter {
                    origin: origin("max-move"),
                    message: format!("`max-move` = `{text}` is not data, off or a distance ≥ 0"),
                })
            }
        },
    };
    let max_iterations = parameters.count("max-iterations", defaults.max_iterations)?;
    let settings = SapidisFarinSettings::default()
        .with_jump_reduction(jump_reduction)
        .with_max_move(max_move)
        .with_max_iterations(max_iterations)
        .with_domain(match job.kind {
            CurveKind::Function => CurveDomain::Function,
            CurveKind::Parametric => CurveDomain::Parametric,
        });
    let constraints = fairing_constraints(job.constraints);
    let planar_constraints = constraints.clone();
    by_dimension(
        job,
        move |points| fair_points(points, settings, planar_constraints),
        move |points| fair_points(points, settings, constraints),
    )
}

fn fair_points<const D: usize>(
    points: &[Vector<D>],
    settings: SapidisFarinSettings,
    constraints: fairing::Constraints,
) -> fairing::Result<(Vec<Vector<D>>, Described)>
where
    Vector<D>: CurvatureForm,
{
    let mut strategy = SapidisFarin::<D>::new(settings);
    // One more step than knots to fair: the last one reports done.
    let result = run(
        &mut strategy,
        points.to_vec(),
        constraints,
        settings.max_iterations.saturating_add(1),
    )?;
    let mut curve = match strategy.curve() {
        Some(curve) => serde_json::to_value(curve).unwrap_or(serde_json::Value::Null),
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
    let stop = match strategy.stop() {
        Some(SapidisFarinStop::JumpReduction) => "jump-reduction",
        Some(SapidisFarinStop::MaxIterations) => "max-iterations",
        Some(SapidisFarinStop::NoCandidate) => "no-candidate",
        None => "max-iterations",
    };
    let steps: Vec<serde_json::Value> = strategy
        .history()
        .iter()
        .map(|s| serde_json::json!({"knot": s.knot, "jump_before": s.jump_before, "max_jump_after": s.max_jump_after}))
        .collect();
    let mut extras = BTreeMap::new();
    extras.insert("jump_reduction".into(), serde_json::json!(settings.jump_reduction));
    extras.insert("move_bound".into(), serde_json::json!(strategy.move_bound()));
    extras.insert(
        "max_jump_before".into(),
        serde_json::json!(strategy.initial_max_jump()),
    );
    extras.insert("max_jump_after".into(), serde_json::json!(strategy.max_jump()));
    extras.insert("knots_faired".into(), serde_json::json!(strategy.history().len()));
    extras.insert("stop".into(), serde_json::json!(stop));
    extras.insert("steps".into(), serde_json::Value::Array(steps));
    Ok((
        result.points,
        Described {
            curve,
            extras,
            moved: result.moved,
            iterations: strategy.history().len(),
            elapsed_ms: result.elapsed_ms,
        },
    ))
}
