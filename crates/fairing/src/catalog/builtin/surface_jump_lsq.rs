//! `jump-lsq` (surfaces): least squares on the nodes with a penalty on the third-derivative
//! jumps of the net's bicubic surface in both directions ([`SurfaceJumpLsq`]), λ_u and λ_v by GCV.
//! Seams closed, poles and fixed nodes held bit for bit, the tolerance band held; `g0`
//! keeps the boundary; joins (`--join`) hold edges to neighbours g0/g1/g2, reported under
//! `joins`. It takes no bad points (it fairs every node) and no restraining radii.

use crate::catalog::{Settings, SurfaceJob, SurfaceMethod, SurfaceRun};
use crate::strategies::{SurfaceJumpLsq, SurfaceJumpLsqSettings};
use crate::{EndClamp, Error, Refusal, Result};

use super::surface::bicubic_record;

impl Settings for SurfaceJumpLsqSettings {
    fn validate(&self) -> Result<()> {
        SurfaceJumpLsqSettings::validate(self)
    }
}

/// The surface `jump-lsq` method.
#[derive(Clone, Copy, Debug, Default)]
pub struct SurfaceJumpLsqMethod;

impl SurfaceMethod for SurfaceJumpLsqMethod {
    type Settings = SurfaceJumpLsqSettings;

    /// Refuses `g1`/`g2` and restraining radii.
    fn check(&self, _: &SurfaceJumpLsqSettings, job: &SurfaceJob) -> Result<()> {
        let refuse = |what, reason: String| Error::Refused {
            method: job.method.to_owned(),
            what,
            reason,
        };
        if job.constraints.restraining_radii().is_some() {
            return Err(refuse(
                Refusal::Radii,
                "fairs every node against the data; it takes no restraining radii (use the tolerance band)"
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

    fn run(&self, settings: &SurfaceJumpLsqSettings, job: &SurfaceJob) -> Result<SurfaceRun> {
        let grid = job.grid;
        let columns = grid.columns.max(1);
        let mut settings = settings.clone();
        settings.fixed = job.fixed_nodes();
        settings.max_distance = job.constraints.tolerance();
        settings.joins = job.constraints.joins().to_vec();
        let result = SurfaceJumpLsq::new(settings.clone()).run(&grid.to_rows())?;
        let record = bicubic_record(&result.surface, settings.parametrization, &result.topology);
        let mut extras = std::collections::BTreeMap::new();
        extras.insert("lambda_u".into(), serde_json::json!(result.lambda_u));
        extras.insert("lambda_v".into(), serde_json::json!(result.lambda_v));
        extras.insert("gcv".into(), serde_json::json!(result.gcv));
        extras.insert("dof".into(), serde_json::json!(result.dof));
        extras.insert("band_pins".into(), serde_json::json!(result.band_pins));
        extras.insert("band_projected".into(), serde_json::json!(result.band_projected));
        extras.insert("fixed_spread".into(), serde_json::json!(result.fixed_spread));
        extras.insert("cg_iterations".into(), serde_json::json!(result.cg_iterations));
        extras.insert("displacement_sum".into(), serde_json::json!(result.displacement));
        extras.insert("basis_u".into(), serde_json::json!(result.basis.0));
        extras.insert("basis_v".into(), serde_json::json!(result.basis.1));
        // Fits the refusal rule turned down (each raised the largest z_ij or the network
        // energy); all of them when the weights end at 0 without a join to hold (the input
        // comes back unchanged).
        extras.insert("refused".into(), serde_json::json!(result.refused));
        let every_fit_refused =
            result.refused > 0 && result.lambda_u == 0.0 && result.lambda_v == 0.0 && result.joins.is_empty();
        if !result.joins.is_empty() {
            extras.insert("joins".into(), serde_json::json!(result.joins));
        }
        extras.insert("warnings".into(), serde_json::json!(warnings(&result)));
        Ok(SurfaceRun {
            grid: crate::catalog::Grid {
                rows: grid.rows,
                columns: grid.columns,
                points: result.surface.points().to_vec(),
            },
            iterations: 1,
            moved: result.moved.iter().map(|&(i, j)| i * columns + j).collect(),
            elapsed_ms: result.elapsed.as_secs_f64() * 1e3,
            termination: if every_fit_refused {
                "refused"
            } else {
                "strategy-done"
            }
            .to_owned(),
            surface: record,
            extras,
        })
    }
}

/// What kept the run from doing its job, in words for the report's `warnings` (the command
/// prints them on standard error): fixed nodes whose values the fit can pass through only by
/// swinging far from the data beside them ([`SurfaceJumpLsqResult::fixed_spread`]).
///
/// [`SurfaceJumpLsqResult::fixed_spread`]: crate::strategies::SurfaceJumpLsqResult::fixed_spread
fn warnings(result: &crate::strategies::SurfaceJumpLsqResult) -> Vec<String> {
    let mut out = Vec::new();
    if result.fixed_spread > crate::strategies::surface_jump_lsq::FIXED_SPREAD_WARNING {
        out.push(format!(
            "the fixed nodes inside the net bend the fit {:.1} times farther from the data than \
             it moves without them: their values are not smooth together (adjacent noisy \
             nodes?); fix fewer adjacent nodes, or fair them first",
            result.fixed_spread
        ));
    }
    out
}
