//! Running a plan piece by piece between a curve's corners ([`crate::corners`]): every method
//! keeps a corner as a G0 break because it never sees across it.
//!
//! An open curve (or a function) with corners c_1 < … < c_k is split into the pieces
//! [0, c_1], [c_1, c_2], …, [c_k, n − 1]; a closed one into the pieces between consecutive
//! corners round the loop (one corner: one piece from the corner round to itself). Each piece
//! runs the whole plan as an open curve with its corner ends fixed, the run's fixed points and
//! tolerance, and the end clamp at the curve's own ends; a piece of fewer than
//! [`MIN_PIECE_POINTS`] points (a straight trailing edge, a short chine segment) is kept as
//! read. The pieces' points are joined, a closed input's repeated first point kept equal to
//! the first. Cost: the plan's on each piece, so about its cost on the whole curve.

use serde_json::{json, Value};

use super::builtin::repeats_first;
use super::job::{CurveKind, CurvePoints, CurveRun};
use super::plan::{Plan, PlanConstraints};
use super::Catalog;
use crate::corners::{detect, Corners};
use crate::{EndClamp, Error, Result};

/// The fewest points a piece between corners must have to be faired.
pub(super) const MIN_PIECE_POINTS: usize = 6;

/// Whether the plan fairs the curve as closed: a repeated first point, or `closed = true` in
/// a stage's settings.
fn closed(plan: &Plan, points: &CurvePoints, kind: CurveKind) -> bool {
    kind == CurveKind::Parametric
        && (repeats_first(points)
            || plan
                .stages
                .iter()
                .any(|s| s.settings.get("closed") == Some(&Value::Bool(true))))
}

/// The corners `constraints.corners` names for these points (indices of the input; a closed
/// input's repeated last point is its first), or none where the run cannot split: bad points
/// (`--points`) or a G1/G2 end clamp with `auto` (declared corners are then refused).
pub(super) fn corners_of(
    plan: &Plan,
    points: &CurvePoints,
    kind: CurveKind,
    constraints: &PlanConstraints,
) -> Result<(Vec<usize>, bool)> {
    let n = points.len();
    let closed = closed(plan, points, kind);
    let unique = if closed && repeats_first(points) { n - 1 } else { n };
    let blocked = if !constraints.bad_points.is_empty() {
        Some("bad points (--points) are given")
    } else if matches!(constraints.clamp, EndClamp::G1 | EndClamp::G2) {
        Some("the ends are clamped g1 or g2")
    } else {
        None
    };
    let corners = match &constraints.corners {
        Corners::None => Vec::new(),
        Corners::Auto if blocked.is_some() => Vec::new(),
        Corners::Auto => match points {
            CurvePoints::Planar(p) => detect(&p[..unique], closed),
            CurvePoints::Spatial(p) => detect(&p[..unique], closed),
        },
        Corners::At(at) => {
            if let Some(why) = blocked {
                return Err(Error::Config {
                    origin: "--corners".into(),
                    message: format!("corners cannot be kept when {why}"),
                });
            }
            if let Some(&bad) = at.iter().find(|&&i| i >= n) {
                return Err(Error::Config {
                    origin: "--corners".into(),
                    message: format!(
                        "index {bad} is past the last point ({n} points, indices 0 to {})",
                        n.saturating_sub(1)
                    ),
                });
            }
            let mut at: Vec<usize> = at.iter().map(|&i| if i == unique { 0 } else { i }).collect();
            if !closed {
                // A curve's own ends are no corners.
                at.retain(|&i| i > 0 && i + 1 < n);
            }
            at.sort_unstable();
            at.dedup();
            at
        }
    };
    Ok((corners, closed))
}

/// Runs `plan` piece by piece between `corners` (module docs); `run` runs the plan on one
/// piece. `None` when a piece's result is the method's own representation of points it does
/// not move (nurbs-weights): such a method runs on the whole curve.
///
/// The run's `curve` is the measured spline of each piece between its corners, as Ferguson
/// segments (null where that cannot be written: a closed curve given without its repeated
/// point, whose closing span has no segment). The extras: `corners`; `pieces`, each piece's
/// first and last input index and its run's termination, iterations and extras (or `kept` for
/// a piece too short to fair); and `warnings`, the pieces' own, each naming its piece.
#[allow(clippy::too_many_arguments)]
pub(super) fn run_pieces(
    catalog: &Catalog,
    plan: &Plan,
    points: &CurvePoints,
    kind: CurveKind,
    constraints: &PlanConstraints,
    corners: &[usize],
    closed: bool,
    run: &dyn Fn(&Catalog, &Plan, &CurvePoints, &PlanConstraints) -> Result<CurveRun>,
) -> Result<Option<CurveRun>> {
    let rows = points.rows();
    let dimension = points.dimension();
    let n = rows.len();
    let unique = if closed && repeats_first(points) { n - 1 } else { n };
    // Each piece as a run of input indices (a closed curve's wrap past its last point).
    let mut ranges: Vec<Vec<usize>> = Vec::new();
    if closed {
        for (j, &start) in corners.iter().enumerate() {
            let end = corners.get(j + 1).copied().unwrap_or(corners[0] + unique);
            ranges.push((start..=end).map(|i| i % unique).collect());
        }
    } else {
        let mut cuts = vec![0];
        cuts.extend_from_slice(corners);
        cuts.push(n - 1);
        for w in cuts.windows(2) {
            ranges.push((w[0]..=w[1]).collect());
        }
    }
    // Pieces of open curves open: a stage's `closed = true` does not hold for a piece.
    let mut open_plan = plan.clone();
    for stage in &mut open_plan.stages {
        if let Some(closed) = stage.settings.get_mut("closed") {
            *closed = Value::Bool(false);
        }
    }
    let mut out = rows.clone();
    let (mut iterations, mut elapsed_ms) = (0usize, 0.0);
    let mut termination = String::from("strategy-done");
    let mut records = Vec::with_capacity(ranges.len());
    let mut warnings: Vec<String> = Vec::new();
    for range in &ranges {
        let (first, last) = (range[0], *range.last().unwrap_or(&range[0]));
        if range.len() < MIN_PIECE_POINTS {
            records.push(json!({ "first": first, "last": last, "kept": "too few points to fair" }));
            continue;
        }
        let piece_rows: Vec<Vec<f64>> = range.iter().map(|&i| rows[i].clone()).collect();
        let piece = CurvePoints::from_rows(dimension, &piece_rows).ok_or_else(|| Error::Strategy {
            strategy: plan.name(),
            reason: "a piece between corners has points of another dimension".into(),
        })?;
        let is_corner = |i: usize| corners.contains(&i);
        // A closed input's repeated last point is its first: fixing either fixes both.
        let is_fixed = |i: usize| {
            constraints.fixed.contains(&i) || (i == 0 && unique < n && constraints.fixed.contains(&(n - 1)))
        };
        let mut fixed: Vec<usize> = range
            .iter()
            .enumerate()
            .filter(|&(k, &i)| is_fixed(i) || ((k == 0 || k + 1 == range.len()) && is_corner(i)))
            .map(|(k, _)| k)
            .collect();
        fixed.dedup();
        // The end clamp holds at the curve's own ends; at a corner the end is fixed anyway.
        let piece_constraints = PlanConstraints {
            fixed,
            bad_points: Vec::new(),
            tolerance: constraints.tolerance,
            clamp: constraints.clamp,
            corners: Corners::None,
        };
        let piece_run = run(catalog, &open_plan, &piece, &piece_constraints)?;
        if piece_run.represented.is_some() {
            // The result is the method's own curve over points it does not move (nurbs-weights'
            // weights): pieces of it are no result of the whole; the caller runs the curve whole.
            return Ok(None);
        }
        let rows = piece_run.points.rows();
        if rows.len() != range.len() {
            return Err(Error::Strategy {
                strategy: plan.name(),
                reason: format!(
                    "returned {} points for the {} of the piece from point {first} to {last}",
                    rows.len(),
                    range.len()
                ),
            });
        }
        for (&i, row) in range.iter().zip(rows) {
            out[i] = row;
        }
        iterations = iterations.max(piece_run.iterations);
        elapsed_ms += piece_run.elapsed_ms;
        termination = piece_run.termination.clone();
        if let Some(said) = piece_run.extras.get("warnings").and_then(Value::as_array) {
            warnings.extend(
                said.iter()
                    .filter_map(Value::as_str)
                    .map(|w| format!("the piece from point {first} to {last}: {w}")),
            );
        }
        records.push(json!({
            "first": first,
            "last": last,
            "iterations": piece_run.iterations,
            "termination": piece_run.termination,
            "extras": piece_run.extras,
        }));
    }
    if unique < n {
        out[n - 1] = out[0].clone();
    }
    let faired = CurvePoints::from_rows(dimension, &out).ok_or_else(|| Error::Strategy {
        strategy: plan.name(),
        reason: "the pieces between corners joined into points of another dimension".into(),
    })?;
    let curve = pieces_record(&faired, kind, &ranges, n).unwrap_or(Value::Null);
    let mut extras = std::collections::BTreeMap::new();
    extras.insert("corners".to_owned(), json!(corners));
    extras.insert("pieces".to_owned(), Value::Array(records));
    if !warnings.is_empty() {
        extras.insert("warnings".to_owned(), json!(warnings));
    }
    Ok(Some(CurveRun {
        moved: points.differences(&faired),
        points: faired,
        iterations,
        elapsed_ms,
        termination,
        curve,
        extras,
        represented: None,
    }))
}

/// The faired curve as the pieces' measured splines (the report's definitions: a function's
/// spline with parabolic runout ends, a parametric curve's natural spline over chord lengths),
/// one Ferguson segment per span of the input, in order: each span's cubic in the power basis
/// over t ∈ [0, 1] from its Taylor coefficients at the span's start (exact for a cubic), so the
/// curve breaks at the corners (G0) and is C² within each piece. `None` when a piece's spline
/// cannot be built or a span has no place among the input's n − 1 (a closed curve given
/// without its repeated point). O(n).
fn pieces_record(faired: &CurvePoints, kind: CurveKind, ranges: &[Vec<usize>], n: usize) -> Option<Value> {
    let rows = faired.rows();
    let dimension = faired.dimension();
    let mut segments: Vec<Option<Value>> = vec![None; n.checked_sub(1)?];
    for range in ranges {
        let piece_rows: Vec<Vec<f64>> = range.iter().map(|&i| rows[i].clone()).collect();
        let piece = CurvePoints::from_rows(dimension, &piece_rows)?;
        let curve = super::measured_curve(kind, &piece).ok()?;
        let spans: Vec<Vec<Vec<f64>>> = match dimension {
            2 => taylor_spans::<2>(curve.as_dimension::<2>()?),
            3 => taylor_spans::<3>(curve.as_dimension::<3>()?),
            _ => return None,
        };
        if spans.len() + 1 != range.len() {
            return None;
        }
        for (k, span) in spans.into_iter().enumerate() {
            *segments.get_mut(range[k])? = Some(json!(span));
        }
    }
    let segments: Vec<Value> = segments.into_iter().collect::<Option<_>>()?;
    Some(json!({ "type": "ferguson", "degree": 3, "segments": segments }))
}

/// Each span of `curve` between consecutive breaks as power-basis coefficients over
/// t ∈ [0, 1]: P(b + t h) = a_0 + a_1 t + a_2 t² + a_3 t³, a_k = P^(k)(b⁺) h^k / k!.
fn taylor_spans<const D: usize>(curve: &(dyn curve_repr::Curve<D> + Send + Sync)) -> Vec<Vec<Vec<f64>>> {
    let breaks = curve.breaks();
    breaks
        .windows(2)
        .map(|w| {
            let (b, h) = (w[0], w[1] - w[0]);
            let jet = curve.jet(b, curve_repr::Side::Right);
            let scale = [1.0, h, h * h / 2.0, h * h * h / 6.0];
            jet.iter()
                .zip(scale)
                .map(|(v, f)| v.iter().map(|c| c * f).collect())
                .collect()
        })
        .collect()
}
