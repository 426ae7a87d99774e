//! `--method batten`: Okada's numerical batten ([`fairing::strategies::Batten`]; Okada 1969).
//!
//! Parameters (registry): `range` (the adjustable range of every point: it stays within this
//! distance of its data point; default `inf`, unrestricted as in Okada's Table 1),
//! `tangent-directions` (prescribed tangent directions, `INDEX:DX,DY[,DZ]` separated by `;`,
//! default none), `update` (how Eq. 13 moves the points each iteration: gauss-seidel, one
//! sweep of its rows, the default; solve, the whole system; jacobi, one simultaneous sweep),
//! `max-iterations` (default 1000), `max-sweeps` (projected Gauss–Seidel sweeps when a range
//! binds under `update=solve`, default 10000).
//!
//! Constraints: `--fixed` and `--tolerance` through the library's constraints; the two end
//! points never move (g0 holds anyway); `--clamp-ends g1|g2` are refused. `--points` has no
//! meaning for this method and is refused.

use std::collections::BTreeMap;

use curve_repr::Vector;
use fairing::strategies::{batten, Batten, BattenSettings, PositionUpdate};
use fairing::FairingResult;

use super::strain_energy::points_of;
use super::strategy_run::{fairing_constraints, run_strategy};
use super::{CurveJob, CurveOutcome};
use crate::error::{Error, Result};
use crate::input::Points;

/// Runs the batten on `job`'s points.
pub fn fair(job: &CurveJob) -> Result<CurveOutcome> {
    let parameters = job.parameters;
    if !job.constraints.bad_points.is_empty() {
        return Err(Error::Argument {
            option: "--points",
            message: "`batten` adjusts every movable point; it takes no bad points (use --fixed)".into(),
        });
    }
    let range = match parameters.get("range") {
        None => f64::INFINITY,
        Some(given) => match given.value.parse::<f64>() {
            Ok(v) if v >= 0.0 => v,
            _ => {
                return Err(Error::Parameter {
                    origin: given.origin.clone(),
                    message: format!(
                        "`range` = `{}` is not a non-negative number (or inf)",
                        given.value
                    ),
                })
            }
        },
    };
    let directions = match parameters.get("tangent-directions") {
        None => Vec::new(),
        Some(given) => parse_directions(&given.value, job.input.points.dimension(), job.input.len())
            .map_err(|message| Error::Parameter {
                origin: given.origin.clone(),
                message: format!("`tangent-directions` = `{}`: {message}", given.value),
            })?,
    };
    let max_iterations = parameters.count("max-iterations", 1000)?;
    let max_sweeps = parameters.count("max-sweeps", 10_000)?;
    let update = match parameters
        .choice("update", &["gauss-seidel", "solve", "jacobi"], "gauss-seidel")?
        .as_str()
    {
        "solve" => PositionUpdate::Solve,
        "jacobi" => PositionUpdate::Jacobi,
        _ => PositionUpdate::GaussSeidel,
    };
    let mut constraints = fairing_constraints(job.constraints);
    if range.is_finite() {
        constraints = constraints.with_restraining_radii(vec![range; job.input.len()]);
    }
    match &job.input.points {
        Points::Planar(points) => {
            let settings = settings::<2>(&directions, max_sweeps, update);
            let run = run_strategy(
                job,
                Batten::new(settings.clone()),
                points,
                max_iterations,
                constraints,
            )?;
            Ok(outcome(run, &settings))
        }
        Points::Spatial(points) => {
            let settings = settings::<3>(&directions, max_sweeps, update);
            let run = run_strategy(
                job,
                Batten::new(settings.clone()),
                points,
                max_iterations,
                constraints,
            )?;
            Ok(outcome(run, &settings))
        }
    }
}

fn settings<const D: usize>(
    directions: &[(usize, Vec<f64>)],
    max_sweeps: usize,
    update: PositionUpdate,
) -> BattenSettings<D> {
    let mut settings = BattenSettings::default()
        .with_max_sweeps(max_sweeps)
        .with_position_update(update);
    for (i, d) in directions {
        let mut v = Vector::<D>::zeros();
        for (slot, value) in v.iter_mut().zip(d) {
            *slot = *value;
        }
        settings = settings.with_tangent_direction(*i, v);
    }
    settings
}

/// Parses `INDEX:DX,DY[,DZ];...` for points of `dimension` coordinates, `count` points.
fn parse_directions(
    text: &str,
    dimension: usize,
    count: usize,
) -> std::result::Result<Vec<(usize, Vec<f64>)>, String> {
    let mut out = Vec::new();
    for item in text.split(';').map(str::trim).filter(|s| !s.is_empty()) {
        let (index, direction) = item.split_once(':').ok_or_else(|| {
            format!(
                "`{item}` is not INDEX:DX,DY{}",
                if dimension == 3 { ",DZ" } else { "" }
            )
        })?;
        let index: usize = index
            .trim()
            .parse()
            .map_err(|_| format!("`{index}` is not a point index"))?;
        if index >= count {
            return Err(format!("point {index} is past the last point ({count} points)"));
        }
        let values: Vec<f64> = direction
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| format!("`{direction}` is not a list of numbers"))?;
        if values.len() != dimension {
            return Err(format!(
                "the direction at point {index} has {} components, the points {dimension}",
                values.len()
            ));
        }
        if !values.iter().all(|v| v.is_finite()) || values.iter().all(|v| *v == 0.0) {
            return Err(format!("the direction at point {index} is zero or not finite"));
        }
        if out.iter().any(|(k, _)| *k == index) {
            return Err(format!("point {index} is given a direction twice"));
        }
        out.push((index, values));
    }
    Ok(out)
}

fn outcome<const D: usize>(run: FairingResult<D>, settings: &BattenSettings<D>) -> CurveOutcome {
    let mut extras = BTreeMap::new();
    extras.insert("termination".into(), serde_json::json!(run.termination));
    // Okada Step 7: the Ferguson coefficient vectors of the faired chain (each segment on
    // t ∈ [0, 1]), tangents recomputed on the final points.
    let mut curve = serde_json::Value::Null;
    if let Ok(tangents) = batten::okada_tangents(&run.points, &settings.tangent_directions) {
        let segments: Vec<Vec<Vec<f64>>> = (0..tangents.x.len())
            .filter_map(|i| {
                let r = batten::ferguson(run.points[i], run.points[i + 1], tangents.x[i], tangents.y(i)?);
                Some(r.iter().map(|v| v.iter().copied().collect()).collect())
            })
            .collect();
        extras.insert(
            "batten_energy".into(),
            serde_json::json!(batten::energy(&run.points, &tangents)),
        );
        curve = serde_json::json!({
            "type": "ferguson",
            "degree": 3,
            "segments": segments,
        });
    }
    CurveOutcome {
        points: points_of(&run.points),
        iterations: run.iterations,
        moved: run.moved,
        elapsed_ms: run.elapsed.as_secs_f64() * 1e3,
        curve,
        extras,
        represented_energies: None,
    }
}
