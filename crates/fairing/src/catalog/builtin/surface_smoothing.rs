//! `smoothing-spline` (surfaces): the surface baseline, a tensor-product cubic smoothing
//! spline over the grid's parameters ([`SurfaceSmoothing`]), periodic across seams, poles
//! and fixed nodes held; with `displacement` its smoothing matches a given S_d, which is how
//! a fairing is compared against it. It takes no bad points (it smooths every node) and no
//! tolerance band (it is matched by its displacement instead); `g0` holds the boundary.

use crate::catalog::{Settings, SurfaceJob, SurfaceMethod, SurfaceRun};
use crate::strategies::{SurfaceSmoothing, SurfaceSmoothingSettings};
use crate::{EndClamp, Error, Refusal, Result};

use super::surface::bicubic_record;

impl Settings for SurfaceSmoothingSettings {
    fn validate(&self) -> Result<()> {
        SurfaceSmoothingSettings::validate(self)
    }
}

/// The surface `smoothing-spline` method.
#[derive(Clone, Copy, Debug, Default)]
pub struct SurfaceSmoothingMethod;

impl SurfaceMethod for SurfaceSmoothingMethod {
    type Settings = SurfaceSmoothingSettings;

    /// Refuses `g1`/`g2`, a tolerance band and restraining radii.
    fn check(&self, _: &SurfaceSmoothingSettings, job: &SurfaceJob) -> Result<()> {
        let refuse = |what, reason: String| Error::Refused {
            method: job.method.to_owned(),
            what,
            reason,
        };
        if job.constraints.restraining_radii().is_some() {
            return Err(refuse(
                Refusal::Radii,
                "smooths every node; it takes no restraining radii".into(),
            ));
        }
        if job.constraints.tolerance().is_some() {
            return Err(refuse(
                Refusal::Tolerance,
                "is matched by its total displacement, not bounded point by point: use \
                 --set displacement=S_d instead of --tolerance"
                    .into(),
            ));
        }
        let clamp = job.constraints.end_clamp();
        if matches!(clamp, EndClamp::G1 | EndClamp::G2) {
            return Err(refuse(
                Refusal::EndClamp,
                format!(
                    "keeps at most the boundary points (g0); it cannot hold tangents or curvatures \
                     across it ({})",
                    clamp.name()
                ),
            ));
        }
        Ok(())
    }

    fn run(&self, settings: &SurfaceSmoothingSettings, job: &SurfaceJob) -> Result<SurfaceRun> {
        let grid = job.grid;
        let columns = grid.columns.max(1);
        let mut settings = settings.clone();
        settings.fixed = job.fixed_nodes();
        let result = SurfaceSmoothing::new(settings.clone()).run(&grid.to_rows())?;
        let record = bicubic_record(&result.surface, settings.parametrization, &result.topology);
        let mut extras = std::collections::BTreeMap::new();
        extras.insert("p_u".into(), serde_json::json!(result.p.0));
        extras.insert("p_v".into(), serde_json::json!(result.p.1));
        extras.insert("displacement_sum".into(), serde_json::json!(result.displacement));
        Ok(SurfaceRun {
            grid: crate::catalog::Grid {
                rows: grid.rows,
                columns: grid.columns,
                points: result.surface.points().to_vec(),
            },
            iterations: 1,
            moved: result.moved.iter().map(|&(i, j)| i * columns + j).collect(),
            elapsed_ms: result.elapsed.as_secs_f64() * 1e3,
            termination: if result.unreachable {
                "displacement-unreachable".to_owned()
            } else {
                "strategy-done".to_owned()
            },
            surface: record,
            extras,
        })
    }
}
