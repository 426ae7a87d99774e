//! `zhang-cheng` (surfaces), and its preset `kjellander`: Zhang–Cheng §4 bicubic surface
//! fairing and Kjellander's one-point baseline, via [`SurfaceFairing`]. Without bad points
//! the automatic algorithm runs (boundary curves first, restraining spheres, every interior
//! point each step); with them (grid indices k = i·columns + j) the interactive one fairs
//! those points, grouped as the paper's step 1.3 says. Fixed nodes never move; the tolerance
//! bounds every move; `g0` keeps the grid's boundary (its first and last rows and columns).

use crate::catalog::{Settings, SurfaceJob, SurfaceMethod, SurfaceRun};
use crate::strategies::{SurfaceFairing, SurfaceFairingSettings, SurfaceMode};
use crate::{EndClamp, Error, Refusal, Result};

impl Settings for SurfaceFairingSettings {
    fn validate(&self) -> Result<()> {
        SurfaceFairingSettings::validate(self)
    }
}

/// The `zhang-cheng` surface method (and its presets).
#[derive(Clone, Copy, Debug, Default)]
pub struct SurfaceFairingMethod;

impl SurfaceMethod for SurfaceFairingMethod {
    type Settings = SurfaceFairingSettings;

    fn takes_bad_points(&self) -> bool {
        true
    }

    /// `g1`/`g2` are refused (no surface method here holds cross-boundary tangents or
    /// curvatures); with `g0` a bad point on the boundary is refused; given restraining radii
    /// are refused (the method derives its own spheres; the tolerance band bounds every move).
    fn check(&self, _: &SurfaceFairingSettings, job: &SurfaceJob) -> Result<()> {
        let refuse = |what, reason: String| Error::Refused {
            method: job.method.to_owned(),
            what,
            reason,
        };
        if job.constraints.restraining_radii().is_some() {
            return Err(refuse(
                Refusal::Radii,
                "keeps points in its own restraining spheres (Zhang–Cheng §4.4); it takes no given radii                  (use the tolerance band)"
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
        let columns = job.grid.columns.max(1);
        if clamp == EndClamp::G0 {
            let boundary = job.grid.boundary();
            if let Some(k) = job.bad_points.iter().find(|k| boundary.contains(k)) {
                return Err(refuse(
                    Refusal::BadPoints,
                    format!(
                        "cannot move point {k} (i = {}, j = {}): it is on the boundary, which g0 keeps",
                        k / columns,
                        k % columns
                    ),
                ));
            }
        }
        Ok(())
    }

    fn run(&self, settings: &SurfaceFairingSettings, job: &SurfaceJob) -> Result<SurfaceRun> {
        let grid = job.grid;
        let columns = grid.columns.max(1);
        let node = |k: usize| (k / columns, k % columns);
        let mut settings = settings.clone();
        settings.fixed = job.fixed_nodes();
        settings.max_distance = job.constraints.tolerance();
        if !job.bad_points.is_empty() {
            settings.mode = SurfaceMode::Interactive(job.bad_points.iter().map(|&k| node(k)).collect());
        }
        let result = SurfaceFairing::new(settings.clone()).run(&grid.to_rows())?;
        let surface = &result.surface;
        let record = bicubic_record(surface, settings.parametrization, &result.topology);
        let mut extras = std::collections::BTreeMap::new();
        extras.insert(
            "refusal".into(),
            serde_json::json!(result.refusal.map(|r| r.name())),
        );
        extras.insert("refused_steps".into(), serde_json::json!(result.refused_steps));
        extras.insert("refused_moves".into(), serde_json::json!(result.refused_moves));
        extras.insert("quantum".into(), serde_json::json!(result.quantum));
        extras.insert("steps_tried".into(), serde_json::json!(result.steps));
        extras.insert("boundary_steps".into(), serde_json::json!(result.boundary_steps));
        let mode = if matches!(settings.mode, SurfaceMode::Automatic) {
            "automatic"
        } else {
            "interactive"
        };
        extras.insert("mode".into(), serde_json::json!(mode));
        extras.insert(
            "network_energy_start".into(),
            serde_json::json!(result.start.energy),
        );
        extras.insert(
            "energy_per_step".into(),
            serde_json::json!(result.history.iter().map(|s| s.energy).collect::<Vec<_>>()),
        );
        extras.insert(
            "max_z_per_step".into(),
            serde_json::json!(result.history.iter().map(|s| s.max_z).collect::<Vec<_>>()),
        );
        Ok(SurfaceRun {
            grid: crate::catalog::Grid {
                rows: grid.rows,
                columns: grid.columns,
                points: surface.points().to_vec(),
            },
            // Kjellander: point moves; otherwise the accepted steps, one per entry of
            // `energy_per_step` (the boundary fairing, when kept, is the first).
            iterations: if settings.one_point_per_step {
                result.steps
            } else {
                result.history.len()
            },
            moved: result.moved.iter().map(|&(i, j)| i * columns + j).collect(),
            elapsed_ms: result.elapsed.as_secs_f64() * 1e3,
            termination: result.termination.name().to_owned(),
            surface: record,
            extras,
        })
    }
}

/// The report's `surface` record of a bicubic spline surface: its knots, points, and the
/// closures and poles it was built with.
pub(crate) fn bicubic_record(
    surface: &curve_repr::BicubicSplineSurface,
    parametrization: curve_repr::Parametrization,
    topology: &curve_repr::GridTopology,
) -> serde_json::Value {
    let points: Vec<[f64; 3]> = surface.points().iter().map(|p| [p.x, p.y, p.z]).collect();
    let parametrization = match parametrization {
        curve_repr::Parametrization::Uniform => "uniform-averaged",
        _ => "chord-length-averaged",
    };
    let (rows, columns) = surface.shape();
    let poles = topology.poles;
    serde_json::json!({
        "type": "bicubic",
        "parametrization": parametrization,
        "rows": rows,
        "columns": columns,
        "closed_u": topology.closed_u,
        "closed_v": topology.closed_v,
        "poles": {
            "u_start": poles.u_start,
            "u_end": poles.u_end,
            "v_start": poles.v_start,
            "v_end": poles.v_end,
        },
        "u_knots": surface.u_knots(),
        "v_knots": surface.v_knots(),
        "points": points,
    })
}
