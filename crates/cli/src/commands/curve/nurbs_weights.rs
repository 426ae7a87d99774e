//! `--method nurbs-weights`: Nowacki et al.'s NURBS weight fairing (FAIRSHAPE 1996, §3) via
//! [`optim::NurbsWeightFairing`]. The points are returned unchanged; the faired curve is the
//! cubic NURBS through them whose weights minimise the chosen criterion.
//!
//! Parameters (registry): `criterion` (e1, e2, e3, ek, ek-prime; default ek), `law`
//! (bernstein, per-point; default bernstein), `max-iterations` (default 1000).

use std::collections::BTreeMap;
use std::time::Instant;

use curve_repr::Vector;
use fairness::curvature::CurvatureForm;
use optim::{
    CriterionName, CubicBernstein, NelderMeadSettings, NurbsWeightFairing, NurbsWeightResult, PerPoint,
};

use super::{CurveJob, CurveOutcome};
use crate::args::ClampEnds;
use crate::commands::measure::{in_file, POINTS};
use crate::error::{Error, Result};
use crate::input::Points;
use crate::report::Energies;

/// The criterion names `--set criterion=` takes.
const CRITERIA: [&str; 5] = ["e1", "e2", "e3", "ek", "ek-prime"];

/// Runs the weight fairing on `job`'s points. Errors of the interpolation or the search exit
/// with status 2 and name the input file.
///
/// Constraints: no point moves, so `--fixed`, `--tolerance` and `--clamp-ends g0` hold by
/// construction; `g1` and `g2` are refused (the weights change the end tangent directions and
/// curvatures of the interpolant, which this method does not hold). `--points` is refused by
/// [`Plan::check_bad_points`](super::Plan::check_bad_points).
pub fn fair(job: &CurveJob) -> Result<CurveOutcome> {
    let parameters = job.parameters;
    if let Some(clamp @ (ClampEnds::G1 | ClampEnds::G2)) = job.constraints.clamp_ends {
        return Err(Error::Argument {
            option: "--clamp-ends",
            message: format!(
                "{}: nurbs-weights keeps the points (g0) but its weights turn the end tangents and \
                 change the end curvatures; it cannot hold them",
                clamp.name()
            ),
        });
    }
    let criterion: CriterionName =
        parameters
            .choice("criterion", &CRITERIA, "ek")?
            .parse()
            .map_err(|e: optim::Error| Error::Internal {
                message: e.to_string(),
            })?;
    let law = parameters.choice("law", &["bernstein", "per-point"], "bernstein")?;
    let max_iterations = parameters.count("max-iterations", 1000)? as u64;
    let start = Instant::now();
    let outcome = match &job.input.points {
        Points::Planar(points) => run(points, criterion, &law, max_iterations),
        Points::Spatial(points) => run(points, criterion, &law, max_iterations),
    };
    let (curve, extras, iterations, represented_energies) =
        outcome.map_err(|e| in_file(e, &job.input.source))?;
    Ok(CurveOutcome {
        points: job.input.points.clone(),
        iterations,
        moved: Vec::new(),
        elapsed_ms: start.elapsed().as_secs_f64() * 1e3,
        curve,
        extras,
        represented_energies: Some(represented_energies),
    })
}

type Run = (
    serde_json::Value,
    BTreeMap<String, serde_json::Value>,
    usize,
    (Energies, Energies),
);

fn run<const D: usize>(
    points: &[Vector<D>],
    criterion: CriterionName,
    law: &str,
    max_iterations: u64,
) -> Result<Run>
where
    Vector<D>: CurvatureForm,
{
    let settings = NelderMeadSettings::default().with_max_iterations(max_iterations);
    let result = if law == "per-point" {
        NurbsWeightFairing::new(PerPoint, criterion.criterion::<D>())
            .with_nelder_mead(settings)
            .run(points)
    } else {
        NurbsWeightFairing::new(CubicBernstein, criterion.criterion::<D>())
            .with_nelder_mead(settings)
            .run(points)
    }
    .map_err(from_optim)?;
    Ok(describe(result))
}

fn describe<const D: usize>(result: NurbsWeightResult<D>) -> Run {
    let mut curve = serde_json::to_value(&result.curve).unwrap_or(serde_json::Value::Null);
    if let Some(object) = curve.as_object_mut() {
        object.insert("params".into(), serde_json::json!(result.params));
        object.insert("parametrization".into(), serde_json::json!("chord-length"));
    }
    let mut extras = BTreeMap::new();
    extras.insert("criterion".into(), serde_json::json!(result.criterion));
    extras.insert(
        "criterion_before".into(),
        serde_json::json!(result.criterion_before),
    );
    extras.insert(
        "criterion_after".into(),
        serde_json::json!(result.criterion_after),
    );
    extras.insert("law".into(), serde_json::json!(result.law));
    extras.insert("law_params".into(), serde_json::json!(result.law_params));
    extras.insert("energies_unit_weights".into(), serde_json::json!(result.before));
    extras.insert("energies_faired".into(), serde_json::json!(result.after));
    extras.insert("termination".into(), serde_json::json!(result.termination));
    extras.insert("evaluations".into(), serde_json::json!(result.evaluations));
    extras.insert("max_residual".into(), serde_json::json!(result.max_residual));
    let iterations = usize::try_from(result.iterations).unwrap_or(usize::MAX);
    let represented = (result.before, result.after);
    (curve, extras, iterations, represented)
}

/// The search's errors, with the path [`POINTS`] that [`in_file`] replaces by the file name.
fn from_optim(error: optim::Error) -> Error {
    match error {
        optim::Error::Curve(source) => Error::Representation {
            path: POINTS.into(),
            source,
        },
        other => Error::Invalid {
            path: POINTS.into(),
            message: other.to_string(),
        },
    }
}
