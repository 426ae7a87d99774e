//! `--method zhang-cheng | kjellander` for surfaces: Zhang–Cheng §4 bicubic surface fairing
//! and Kjellander's one-point baseline, via [`fairing::strategies::SurfaceFairing`].
//!
//! Without `--points` the automatic algorithm runs (boundary curves first, restraining
//! spheres, every interior point each step); with `--points` (grid indices k = i·columns + j)
//! the interactive one fairs those points, grouped as the paper's step 1.3 says. `--fixed`
//! nodes never move; `--tolerance D` bounds every move.
//!
//! Parameters (registry): `replacement` (limit, iterated), `objective` (network,
//! thin-plate; thin-plate needs iterated), `boundary` (on, off), `energy-tolerance`,
//! `max-steps`, `parametrization` (chord-length, uniform).

use std::collections::BTreeMap;

use curve_repr::{Parametrization, Vec3};
use fairing::strategies::{Objective, Replacement, SurfaceFairing, SurfaceFairingSettings, SurfaceMode};

use super::{SurfaceJob, SurfaceOutcome};
use crate::error::{Error, Result};
use crate::input::Grid;

/// Runs the method of `job` on its grid.
pub fn fair(job: &SurfaceJob) -> Result<SurfaceOutcome> {
    let kjellander = job.method.name == "kjellander";
    let p = job.parameters;
    let mut settings = if kjellander {
        SurfaceFairingSettings::kjellander()
    } else {
        SurfaceFairingSettings::zhang_cheng()
    };
    let default_parametrization = if kjellander { "uniform" } else { "chord-length" };
    settings.parametrization = match p
        .choice(
            "parametrization",
            &["chord-length", "uniform"],
            default_parametrization,
        )?
        .as_str()
    {
        "uniform" => Parametrization::Uniform,
        _ => Parametrization::ChordLength,
    };
    settings.replacement = match p.choice("replacement", &["limit", "iterated"], "limit")?.as_str() {
        "iterated" => Replacement::Iterated,
        _ => Replacement::Limit,
    };
    settings.objective = match p
        .choice("objective", &["network", "thin-plate"], "network")?
        .as_str()
    {
        "thin-plate" => Objective::ThinPlate,
        _ => Objective::Network,
    };
    let boundary_default = if kjellander { "off" } else { "on" };
    settings.fair_boundary = p.choice("boundary", &["on", "off"], boundary_default)? == "on";
    settings.tolerance = p.number("energy-tolerance", settings.tolerance)?;
    settings.max_steps = p.count("max-steps", settings.max_steps)?;

    let grid = &job.input.grid;
    let columns = grid.columns;
    let node = |k: usize| (k / columns, k % columns);
    settings.fixed = job.constraints.fixed.iter().map(|&k| node(k)).collect();
    settings.max_distance = job.constraints.tolerance;
    if !job.constraints.bad_points.is_empty() {
        settings.mode =
            SurfaceMode::Interactive(job.constraints.bad_points.iter().map(|&k| node(k)).collect());
    }
    let rows: Vec<Vec<Vec3>> = grid.points.chunks(columns).map(<[Vec3]>::to_vec).collect();
    let result = SurfaceFairing::new(settings.clone())
        .run(&rows)
        .map_err(|e| from_fairing(e, &job.input.source))?;

    let surface = &result.surface;
    let points: Vec<[f64; 3]> = surface.points().iter().map(|p| [p.x, p.y, p.z]).collect();
    let record = serde_json::json!({
        "type": "bicubic",
        "parametrization": if settings.parametrization == Parametrization::Uniform { "uniform-averaged" } else { "chord-length-averaged" },
        "rows": grid.rows,
        "columns": grid.columns,
        "u_knots": surface.u_knots(),
        "v_knots": surface.v_knots(),
        "points": points,
    });
    let mut extras = BTreeMap::new();
    extras.insert("termination".into(), serde_json::json!(result.termination));
    extras.insert("boundary_steps".into(), serde_json::json!(result.boundary_steps));
    extras.insert(
        "mode".into(),
        serde_json::json!(if matches!(settings.mode, SurfaceMode::Automatic) {
            "automatic"
        } else {
            "interactive"
        }),
    );
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
    Ok(SurfaceOutcome {
        grid: Grid {
            rows: grid.rows,
            columns: grid.columns,
            points: surface.points().to_vec(),
        },
        iterations: result.steps,
        moved: result.moved.iter().map(|&(i, j)| i * columns + j).collect(),
        elapsed_ms: result.elapsed.as_secs_f64() * 1e3,
        surface: record,
        extras,
    })
}

/// The strategy's errors, naming the input file (exit status 2: they come from the input or
/// the options).
fn from_fairing(error: fairing::Error, file: &str) -> Error {
    match error {
        fairing::Error::Repr(source) => Error::Representation {
            path: file.to_string(),
            source,
        },
        other => Error::Invalid {
            path: file.to_string(),
            message: other.to_string(),
        },
    }
}
