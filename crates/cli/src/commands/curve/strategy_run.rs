//! Running one `fairing` strategy from the command: the user's constraints in the fairing
//! crate's types, the step loop with its limit and final constraint check, and the fairing
//! crate's errors as the command's (exit status 2 for what the input or the options cause).
//!
//! Two ways to run: [`run_strategy`] through [`fairing::Pipeline`] (strain-energy, batten),
//! and [`run`], a plain loop for strategies whose own results (the smoothing spline's p,
//! Sapidis–Farin's knot history) the command reads after the run — the pipeline owns its
//! stages.

use std::collections::BTreeSet;
use std::time::Instant;

use curve_repr::{Vec2, Vec3, Vector};
use fairing::{EndClamp, FairingResult, FairingState, FairingStrategy, Pipeline};

use super::{CurveJob, CurveOutcome};
use crate::args::ClampEnds;
use crate::constraints::Constraints;
use crate::error::{Error, Result};
use crate::input::Points;

/// The user's constraints as the fairing crate's: fixed points, the tolerance band and the
/// end clamp (`--points` is for the interactive methods and ignored here).
pub fn fairing_constraints(constraints: &Constraints) -> fairing::Constraints {
    let mut out = fairing::Constraints::default().with_fixed(constraints.fixed.iter().copied());
    if let Some(d) = constraints.tolerance {
        out = out.with_tolerance(d);
    }
    let clamp = match constraints.clamp_ends {
        None => EndClamp::None,
        Some(ClampEnds::G0) => EndClamp::G0,
        Some(ClampEnds::G1) => EndClamp::G1,
        Some(ClampEnds::G2) => EndClamp::G2,
    };
    out.with_end_clamp(clamp)
}

/// The library's errors as the command's: representation errors and strategy failures on
/// the data name the file (exit 2), an unsupported end clamp names `--clamp-ends` and a bad
/// setting `--set` (exit 2); a constraint the result breaks is a bug (exit 1).
pub fn from_fairing(error: fairing::Error, file: &str) -> Error {
    match error {
        fairing::Error::Repr(source) => Error::Representation {
            path: file.to_string(),
            source,
        },
        fairing::Error::ConstraintUnsupported { .. } => Error::Argument {
            option: "--clamp-ends",
            message: error.to_string(),
        },
        fairing::Error::BadParameter { .. } | fairing::Error::BadConstraint { .. } => Error::Parameter {
            origin: "--set".into(),
            message: error.to_string(),
        },
        error @ fairing::Error::ConstraintViolated { .. } => Error::Internal {
            message: error.to_string(),
        },
        other => Error::Invalid {
            path: file.to_string(),
            message: other.to_string(),
        },
    }
}

/// What a run gives back.
#[derive(Debug, Clone)]
pub struct Run<const D: usize> {
    /// The faired points.
    pub points: Vec<Vector<D>>,
    /// Indices of the points whose final position differs from the original.
    pub moved: Vec<usize>,
    /// Steps made.
    pub iterations: usize,
    /// Time of init and steps, in milliseconds.
    pub elapsed_ms: f64,
    /// `strategy-done` or `max-iterations`.
    pub termination: &'static str,
}

/// Runs `strategy` on `points` (open curve) until it is done or has made `max_iterations`
/// steps, then checks the result against the constraints. O(steps × step cost).
pub fn run<const D: usize, S: FairingStrategy<D>>(
    strategy: &mut S,
    points: Vec<Vector<D>>,
    constraints: fairing::Constraints,
    max_iterations: usize,
) -> fairing::Result<Run<D>> {
    strategy.supports(&constraints)?;
    let mut state = FairingState::new(points, constraints, false)?;
    let start = Instant::now();
    strategy.init(&mut state)?;
    let mut termination = "max-iterations";
    let mut iterations = 0;
    while iterations < max_iterations {
        state.iteration = iterations;
        let outcome = strategy.step(&mut state)?;
        iterations += 1;
        if outcome.done {
            termination = "strategy-done";
            break;
        }
    }
    let elapsed_ms = start.elapsed().as_secs_f64() * 1e3;
    state.check()?;
    let moved: BTreeSet<usize> = state
        .points()
        .iter()
        .zip(state.original())
        .enumerate()
        .filter(|(_, (a, b))| a != b)
        .map(|(i, _)| i)
        .collect();
    Ok(Run {
        points: state.points().to_vec(),
        moved: moved.into_iter().collect(),
        iterations,
        elapsed_ms,
        termination,
    })
}

/// Runs one point-moving strategy through the [`Pipeline`] with the job's constraints,
/// mapping the library's errors to the command's (naming the input file or the option).
pub fn run_strategy<const D: usize>(
    job: &CurveJob,
    strategy: impl FairingStrategy<D>,
    points: &[Vector<D>],
    max_iterations: usize,
    constraints: fairing::Constraints,
) -> Result<FairingResult<D>> {
    if let Err(e) = strategy.supports(&constraints) {
        return Err(Error::Argument {
            option: "--clamp-ends",
            message: format!("not supported by `{}`: {e}", job.method.name),
        });
    }
    Pipeline::new(strategy)
        .with_constraints(constraints)
        .with_max_iterations(max_iterations)
        .with_trace(false)
        .run(points.to_vec())
        .map_err(|e| from_fairing(e, &job.input.source))
}

/// A strategy's run described for the report: everything of a [`CurveOutcome`] but the points.
#[derive(Debug, Clone)]
pub struct Described {
    /// The faired curve for the report's `curve`.
    pub curve: serde_json::Value,
    /// Method-specific extras.
    pub extras: std::collections::BTreeMap<String, serde_json::Value>,
    /// Indices of the points that moved.
    pub moved: Vec<usize>,
    /// Iterations (steps) made.
    pub iterations: usize,
    /// Time of the fairing itself, in milliseconds.
    pub elapsed_ms: f64,
}

/// Runs `planar` or `spatial` on the job's points, whichever they are, and makes the command's
/// outcome; the library's errors name the input file.
pub fn by_dimension(
    job: &CurveJob,
    planar: impl FnOnce(&[Vec2]) -> fairing::Result<(Vec<Vec2>, Described)>,
    spatial: impl FnOnce(&[Vec3]) -> fairing::Result<(Vec<Vec3>, Described)>,
) -> Result<CurveOutcome> {
    let result = match &job.input.points {
        Points::Planar(points) => planar(points).map(|(p, d)| (Points::Planar(p), d)),
        Points::Spatial(points) => spatial(points).map(|(p, d)| (Points::Spatial(p), d)),
    };
    let (points, described) = result.map_err(|e| from_fairing(e, &job.input.source))?;
    Ok(CurveOutcome {
        points,
        iterations: described.iterations,
        moved: described.moved,
        elapsed_ms: described.elapsed_ms,
        curve: described.curve,
        extras: described.extras,
        represented_energies: None,
    })
}
