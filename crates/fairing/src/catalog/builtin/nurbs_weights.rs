//! `nurbs-weights`: Nowacki et al.'s NURBS weight fairing (FAIRSHAPE 1996, §3) via
//! [`NurbsWeightFairing`]. The points are returned unchanged; the faired curve is the cubic
//! NURBS through them whose weights minimise the chosen criterion — any criterion of the
//! catalogue (`--set criterion=NAME`).

use std::time::Instant;

use curve_repr::{Interpolation, InterpolationSettings, Parametrization, Vector};
use fairness::curvature::CurvatureForm;
use optim::{
    CubicBernstein, LawName, LbfgsSettings, NelderMeadSettings, NurbsWeightFairing, NurbsWeightSettings,
    PerPoint, SmoothCriterion, SolverName, Termination,
};

use crate::catalog::{
    AnyCurve, CurveJob, CurveMethod, CurvePoints, CurveRun, OnCurve, Represented, Settings,
};
use crate::{EndClamp, Error, Refusal, Result};

impl Settings for NurbsWeightSettings {
    fn validate(&self) -> Result<()> {
        Ok(NurbsWeightSettings::validate(self)?)
    }
}

/// The `nurbs-weights` method.
#[derive(Clone, Copy, Debug, Default)]
pub struct NurbsWeightMethod;

/// Nelder–Mead's stop in the report's one spelling.
fn termination_name(termination: &Termination) -> &'static str {
    match termination {
        Termination::Converged => "converged",
        Termination::MaxIterations => "max-iterations",
        _ => "solver-stopped",
    }
}

impl CurveMethod for NurbsWeightMethod {
    type Settings = NurbsWeightSettings;

    /// No point moves, so fixed points, the tolerance band and `g0` hold by construction;
    /// `g1` and `g2` are refused (the weights turn the end tangents and change the end
    /// curvatures of the interpolant). The criterion must be registered for the points'
    /// dimension.
    fn check(&self, settings: &NurbsWeightSettings, job: &CurveJob) -> Result<()> {
        if matches!(job.constraints.end_clamp(), EndClamp::G1 | EndClamp::G2) {
            return Err(Error::Refused {
                method: job.method.to_owned(),
                what: Refusal::EndClamp,
                reason: format!(
                    "keeps the points (g0) but its weights turn the end tangents and change the end \
                     curvatures; it cannot hold {}",
                    job.constraints.end_clamp().name()
                ),
            });
        }
        criterion_entry(settings, job, job.points.dimension()).map(|_| ())
    }

    fn run(&self, settings: &NurbsWeightSettings, job: &CurveJob) -> Result<CurveRun> {
        match job.points {
            CurvePoints::Planar(p) => run_points(settings, job, p),
            CurvePoints::Spatial(p) => run_points(settings, job, p),
        }
    }
}

fn criterion_entry<'a>(
    settings: &NurbsWeightSettings,
    job: &CurveJob<'a>,
    dimension: usize,
) -> Result<&'a crate::catalog::CriterionEntry> {
    let entry = job
        .catalog
        .criterion(&settings.criterion, "criterion")
        .map_err(|e| match e {
            Error::UnknownName {
                what, name, known, ..
            } => Error::BadValue {
                name: "criterion".into(),
                message: format!("`{name}` is not {what} (known: {known})"),
            },
            other => other,
        })?;
    if !entry.applies_to(dimension) {
        return Err(Error::BadValue {
            name: "criterion".into(),
            message: format!("`{}` has no implementation for {dimension}D curves", entry.name()),
        });
    }
    Ok(entry)
}

fn run_points<const D: usize>(
    settings: &NurbsWeightSettings,
    job: &CurveJob,
    points: &[Vector<D>],
) -> Result<CurveRun>
where
    Vector<D>: CurvatureForm,
{
    let entry = criterion_entry(settings, job, D)?;
    let criterion = entry.for_dimension::<D>().ok_or_else(|| Error::BadValue {
        name: "criterion".into(),
        message: format!("`{}` has no implementation for {D}D curves", entry.name()),
    })?;
    let start = Instant::now();
    let nelder_mead = NelderMeadSettings::default().with_max_iterations(settings.max_iterations);
    let solver = settings.resolved_solver();
    let lbfgs = match solver {
        SolverName::Lbfgs => Some((
            SmoothCriterion::from_name(&settings.criterion).ok_or_else(|| Error::BadValue {
                name: "solver".into(),
                message: format!(
                    "lbfgs needs criterion ek or e2 (a differentiable fixed-rule form), not `{}`",
                    settings.criterion
                ),
            })?,
            LbfgsSettings {
                max_iterations: settings.max_iterations,
                ..LbfgsSettings::default()
            },
        )),
        _ => None,
    };
    let result = match settings.law {
        LawName::PerPoint => {
            let fairing = NurbsWeightFairing::new(PerPoint, OnCurve(criterion)).with_nelder_mead(nelder_mead);
            match lbfgs {
                Some((smooth, lbfgs)) => fairing.with_lbfgs(smooth, lbfgs),
                None => fairing,
            }
            .run(points)?
        }
        LawName::Bernstein => {
            let fairing =
                NurbsWeightFairing::new(CubicBernstein, OnCurve(criterion)).with_nelder_mead(nelder_mead);
            match lbfgs {
                Some((smooth, lbfgs)) => fairing.with_lbfgs(smooth, lbfgs),
                None => fairing,
            }
            .run(points)?
        }
    };
    let elapsed_ms = start.elapsed().as_secs_f64() * 1e3;
    // The unit-weight curve the search starts from: the interpolating NUBS.
    let unit = Interpolation::with_parametrization(
        points,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )?
    .nubs()?;
    let mut curve = serde_json::to_value(&result.curve).unwrap_or_default();
    if let Some(object) = curve.as_object_mut() {
        object.insert("params".into(), serde_json::json!(result.params));
        object.insert("parametrization".into(), serde_json::json!("chord-length"));
    }
    let mut extras = std::collections::BTreeMap::new();
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
    extras.insert("evaluations".into(), serde_json::json!(result.evaluations));
    extras.insert("solver".into(), serde_json::json!(solver.as_str()));
    extras.insert(
        "gradient_evaluations".into(),
        serde_json::json!(result.gradient_evaluations),
    );
    extras.insert("max_residual".into(), serde_json::json!(result.max_residual));
    let represented = match (AnyCurve::new::<D, _>(unit), AnyCurve::new::<D, _>(result.curve)) {
        (Some(before), Some(after)) => Some(Represented { before, after }),
        _ => None,
    };
    Ok(CurveRun {
        points: job.points.clone(),
        iterations: usize::try_from(result.iterations).unwrap_or(usize::MAX),
        moved: Vec::new(),
        elapsed_ms,
        termination: termination_name(&result.termination).to_owned(),
        curve,
        extras,
        represented,
    })
}
