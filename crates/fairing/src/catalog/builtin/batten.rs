//! `batten`: Okada's numerical batten ([`Batten`]; Okada 1969). Every movable point is
//! adjusted within its adjustable range (`range`, and the tolerance band); the two end
//! points never move.

use curve_repr::Vector;
use fairness::curvature::CurvatureForm;

use crate::catalog::{run_strategy, CurveJob, CurveMethod, CurvePoints, CurveRun, Settings};
use crate::strategies::{batten, Batten, BattenSettings};
use crate::{FairingStrategy, Result};

impl Settings for BattenSettings {
    fn validate(&self) -> Result<()> {
        BattenSettings::validate(self)
    }
}

/// The `batten` method.
#[derive(Clone, Copy, Debug, Default)]
pub struct BattenMethod;

impl CurveMethod for BattenMethod {
    type Settings = BattenSettings;

    /// End clamps above g0 are refused (the end tangents follow the circle through the
    /// moving end points).
    fn check(&self, settings: &BattenSettings, job: &CurveJob) -> Result<()> {
        match job.points {
            CurvePoints::Planar(_) => Batten::<2>::new(settings.clone()).supports(job.constraints),
            CurvePoints::Spatial(_) => Batten::<3>::new(settings.clone()).supports(job.constraints),
        }
    }

    fn run(&self, settings: &BattenSettings, job: &CurveJob) -> Result<CurveRun> {
        match job.points {
            CurvePoints::Planar(p) => run_points(settings.clone(), job, p),
            CurvePoints::Spatial(p) => run_points(settings.clone(), job, p),
        }
    }
}

fn run_points<const D: usize>(
    settings: BattenSettings,
    job: &CurveJob,
    points: &[Vector<D>],
) -> Result<CurveRun>
where
    Vector<D>: CurvatureForm,
{
    let max_iterations = settings.max_iterations;
    let given = settings.tangent_directions.clone();
    let mut run = run_strategy(Box::new(Batten::<D>::new(settings)), points, job, max_iterations)?;
    // The run checked the directions' dimension.
    let directions: Vec<(usize, Vector<D>)> = given
        .iter()
        .filter(|(_, d)| d.len() == D)
        .map(|(i, d)| (*i, Vector::<D>::from_iterator(d.iter().copied())))
        .collect();
    // Okada Step 7: the Ferguson coefficient vectors of the faired chain (each segment on
    // t ∈ [0, 1]), tangents recomputed on the final points.
    let faired: &[Vector<D>] = run.points.as_dimension::<D>().unwrap_or(&[]);
    if let Ok(tangents) = batten::okada_tangents(faired, &directions) {
        let segments: Vec<Vec<Vec<f64>>> = (0..tangents.x.len())
            .filter_map(|i| {
                let r = batten::ferguson(faired[i], faired[i + 1], tangents.x[i], tangents.y(i)?);
                Some(r.iter().map(|v| v.iter().copied().collect()).collect())
            })
            .collect();
        run.extras
            .insert("batten_energy".into(), batten::energy(faired, &tangents).into());
        run.curve = serde_json::json!({
            "type": "ferguson",
            "degree": 3,
            "segments": segments,
        });
    }
    Ok(run)
}
