//! Running a [`Plan`]: one stage, or a pipeline of stages each fairing the previous result.
//!
//! Constraints hold for the whole pipeline, measured from the input as read:
//! - fixed points are passed to every stage, so they are never moved by any;
//! - the tolerance band D is shared out: stage k gets D minus the largest distance any point
//!   has already moved (by the triangle inequality no point ends farther than D from where it
//!   started); when nothing is left the remaining stages are skipped and the report says so;
//! - bad points (`--points`) and end clamps are passed to every stage.
//!
//! The report of a pipeline: `iterations` and `elapsed_ms` are summed, `moved` lists the
//! points that differ from the input at the end, `curve` is the last stage's, and `stages`
//! holds each stage's method, parameters, iterations, moved count, S_d and M_d (against the
//! stage's own input) and extras.

use super::{displacement, fair, CurveJob, CurveOutcome, Plan};
use crate::constraints::Constraints;
use crate::error::{Error, Result};
use crate::input::CurveInput;
use crate::kind::CurveKind;
use std::collections::BTreeMap;

/// Runs the stages of `plan` on `input`. O(sum of the stages' costs) plus O(n) per stage.
pub fn run(
    input: &CurveInput,
    kind: CurveKind,
    plan: &Plan,
    constraints: &Constraints,
) -> Result<CurveOutcome> {
    if let [(method, parameters)] = plan.stages.as_slice() {
        let job = CurveJob {
            input,
            kind,
            method,
            parameters,
            constraints,
        };
        let outcome = fair(&job)?;
        check_shape(input, &outcome, method.name)?;
        return Ok(outcome);
    }
    let mut current = input.clone();
    let (mut iterations, mut elapsed_ms) = (0usize, 0.0);
    let mut records = Vec::with_capacity(plan.stages.len());
    let mut curve = serde_json::Value::Null;
    let mut energies = Vec::with_capacity(plan.stages.len());
    for (number, (method, parameters)) in plan.stages.iter().enumerate() {
        let mut stage_constraints = constraints.clone();
        if let Some(band) = constraints.tolerance {
            let (_, used) = displacement(&input.points, &current.points);
            let left = band - used;
            if left.is_nan() || left <= 0.0 {
                records.push(serde_json::json!({
                    "stage": number + 1,
                    "method": method.name,
                    "skipped": "the tolerance band is used up by the earlier stages",
                }));
                energies.push(None);
                continue;
            }
            stage_constraints.tolerance = Some(left);
        }
        let job = CurveJob {
            input: &current,
            kind,
            method,
            parameters,
            constraints: &stage_constraints,
        };
        let outcome = fair(&job).map_err(|e| match e {
            Error::Internal { message } => Error::Internal {
                message: format!("stage {} ({}): {message}", number + 1, method.name),
            },
            other => other,
        })?;
        check_shape(&current, &outcome, method.name)?;
        let (s_d, m_d) = displacement(&current.points, &outcome.points);
        iterations += outcome.iterations;
        elapsed_ms += outcome.elapsed_ms;
        records.push(serde_json::json!({
            "stage": number + 1,
            "method": method.name,
            "params": parameters.to_json(),
            "iterations": outcome.iterations,
            "moved": outcome.moved.len(),
            "s_d": s_d,
            "m_d": m_d,
            "elapsed_ms": outcome.elapsed_ms,
            "extras": outcome.extras,
        }));
        energies.push(outcome.represented_energies);
        curve = outcome.curve;
        current.points = outcome.points;
    }
    let before = input.points.rows();
    let after = current.points.rows();
    let moved = before
        .iter()
        .zip(&after)
        .enumerate()
        .filter(|(_, (a, b))| a != b)
        .map(|(i, _)| i)
        .collect();
    // Energies of the curve as represented are only reported when the first and the last
    // stage both represent it their own way (else before and after would measure different
    // curves).
    let represented_energies = match (energies.first(), energies.last()) {
        (Some(Some((first, _))), Some(Some((_, last)))) => Some((*first, *last)),
        _ => None,
    };
    let mut extras = BTreeMap::new();
    extras.insert("stages".to_string(), serde_json::Value::Array(records));
    Ok(CurveOutcome {
        points: current.points,
        iterations,
        moved,
        elapsed_ms,
        curve,
        extras,
        represented_energies,
    })
}

fn check_shape(input: &CurveInput, outcome: &CurveOutcome, method: &str) -> Result<()> {
    if outcome.points.len() != input.len() || outcome.points.dimension() != input.points.dimension() {
        return Err(Error::Internal {
            message: format!(
                "method `{method}` returned {} points for {}",
                outcome.points.len(),
                input.len()
            ),
        });
    }
    Ok(())
}
