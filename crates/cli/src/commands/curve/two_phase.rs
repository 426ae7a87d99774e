//! `--method two-phase`: Han et al.'s coarse-to-fine fairing (§4.1) via
//! [`fairing::two_phase::TwoPhase`]; for parametric input (planar only) the arbitrary-curve
//! pipeline of §4.2, [`fairing::SegmentedFairing`] around it, open or (`closed=true`) closed.
//!
//! Parameters (registry, defaults = the paper's values or the library's guards):
//! `coarse-lambda` 0.8, `fine-lambda` 0.75, `alpha-divisor` 5, `max-passes` 50,
//! `max-move-factor` 0.5, `guard-window` 16, `count-guard` local|pass|off, `pair-min-sine`
//! 0.05, `max-run` (> 2 turns on the long-run option), `denoise` gcv|off; parametric only:
//! `segment-passes`, `turning-limit` (degrees), `overlap`, `closed` false. Defaults are the
//! library's ([`TwoPhaseSettings::default`], [`PartitionSettings::default`]).
//!
//! Constraints: `--fixed` and `--tolerance` are honoured by the library's
//! [`fairing::Constraints`]; `--clamp-ends g0` keeps the end points (which two-phase never
//! moves anyway); `g1`/`g2` are refused with exit status 2 (the method's spline has the
//! parabolic-runout end condition and cannot hold end tangents or curvatures), as is any
//! clamp on a closed curve (it has no ends).

use std::collections::BTreeMap;
use std::f64::consts::PI;

use curve_repr::Vec2;
use fairing::two_phase::{CountGuard, Denoise, TwoPhase, TwoPhaseSettings};
use fairing::{EndClamp, FairingResult, PartitionSettings, Pipeline, SegmentedFairing};

use super::{CurveJob, CurveOutcome};
use crate::args::ClampEnds;
use crate::commands::measure::{in_file, POINTS};
use crate::error::{Error, Result};
use crate::input::Points;
use crate::kind::CurveKind;

/// Runs two-phase fairing on `job`'s points.
pub fn fair(job: &CurveJob) -> Result<CurveOutcome> {
    let p = job.parameters;
    let count_guard = match p
        .choice("count-guard", &["local", "pass", "off"], "local")?
        .as_str()
    {
        "pass" => CountGuard::Pass,
        "off" => CountGuard::Off,
        _ => CountGuard::Local,
    };
    let defaults = TwoPhaseSettings::default();
    let settings = TwoPhaseSettings {
        coarse_lambda: p.number("coarse-lambda", defaults.coarse_lambda)?,
        fine_lambda: p.number("fine-lambda", defaults.fine_lambda)?,
        alpha_divisor: p.number("alpha-divisor", defaults.alpha_divisor)?,
        max_passes: p.count("max-passes", defaults.max_passes)?,
        max_move_factor: p.number("max-move-factor", defaults.max_move_factor)?,
        guard_window: p.count("guard-window", defaults.guard_window)?,
        count_guard,
        pair_min_sine: p.number("pair-min-sine", defaults.pair_min_sine)?,
        max_run: p.count("max-run", defaults.max_run)?,
        stall_passes: p.count("stall-passes", defaults.stall_passes)?,
        min_gain: p.number("min-gain", defaults.min_gain)?,
        detection_floor: defaults.detection_floor,
        denoise: match p
            .choice("denoise", &["gcv", "off"], defaults.denoise.name())?
            .as_str()
        {
            "off" => Denoise::Off,
            _ => Denoise::Gcv,
        },
    };
    settings.validate().map_err(|e| Error::Parameter {
        origin: "--set".into(),
        message: e.to_string(),
    })?;
    let closed = p.choice("closed", &["false", "true"], "false")? == "true";
    let clamp = match job.constraints.clamp_ends {
        None => EndClamp::None,
        Some(ClampEnds::G0) if closed => return Err(clamp_error("a closed curve has no ends")),
        Some(ClampEnds::G0) => EndClamp::G0,
        Some(ClampEnds::G1 | ClampEnds::G2) => {
            return Err(clamp_error(
                "two-phase supports only g0: its spline function has the parabolic-runout end \
                 condition and cannot hold end tangents or curvatures",
            ))
        }
    };
    let mut constraints = fairing::Constraints::default()
        .with_fixed(job.constraints.fixed.iter().copied())
        .with_end_clamp(clamp);
    if let Some(distance) = job.constraints.tolerance {
        constraints = constraints.with_tolerance(distance);
    }
    // The arbitrary-curve settings are read (and checked) whatever the input's kind, so that a
    // bad value is refused even where it would not be used.
    let partition_defaults = PartitionSettings::default();
    let limit_degrees = p.number("turning-limit", partition_defaults.limit.to_degrees())?;
    if !(limit_degrees > 0.0 && limit_degrees <= 180.0) {
        return Err(Error::Parameter {
            origin: p
                .get("turning-limit")
                .map_or("--set".into(), |g| g.origin.clone()),
            message: format!("`turning-limit` = `{limit_degrees}` must lie in (0, 180] degrees"),
        });
    }
    let partition = PartitionSettings::default()
        .with_limit(limit_degrees * PI / 180.0)
        .with_overlap(p.count("overlap", partition_defaults.overlap)?);
    partition.validate().map_err(|e| Error::Parameter {
        origin: "--set".into(),
        message: e.to_string(),
    })?;
    let passes = p.count("segment-passes", SegmentedFairing::<TwoPhase>::DEFAULT_PASSES)?;
    if passes == 0 {
        return Err(Error::Parameter {
            origin: "--set".into(),
            message: "`segment-passes` must be at least 1".into(),
        });
    }
    let Points::Planar(points) = &job.input.points else {
        return Err(Error::Invalid {
            path: job.input.source.clone(),
            message: "two-phase fairs planar curves (x, y); the input has 3 coordinates".into(),
        });
    };
    let result = match job.kind {
        CurveKind::Function => {
            if closed {
                return Err(Error::Parameter {
                    origin: "--set".into(),
                    message: "`closed` = `true` needs parametric input (--kind parametric)".into(),
                });
            }
            Pipeline::new(TwoPhase::new(settings.clone()))
                .with_constraints(constraints)
                .with_max_iterations(settings.max_passes.max(1))
                .run(points.clone())
        }
        CurveKind::Parametric => Pipeline::new(
            SegmentedFairing::new(TwoPhase::new(settings.clone()))
                .with_partition(partition)
                .with_passes(passes),
        )
        .with_closed(closed)
        .with_constraints(constraints)
        .with_max_iterations(passes)
        .run(points.clone()),
    };
    let result = result.map_err(|e| in_file(from_fairing(e), &job.input.source))?;
    Ok(describe(result, job.kind, closed))
}

fn clamp_error(message: &str) -> Error {
    Error::Argument {
        option: "--clamp-ends",
        message: message.into(),
    }
}

/// The library's errors: representation failures (x not increasing, repeated points) and
/// unsupported constraints are the user's (exit 2); the rest are internal.
fn from_fairing(error: fairing::Error) -> Error {
    match error {
        fairing::Error::Repr(source) => Error::Representation {
            path: POINTS.into(),
            source,
        },
        fairing::Error::ConstraintUnsupported { .. } => Error::Argument {
            option: "--clamp-ends",
            message: error.to_string(),
        },
        fairing::Error::BadParameter { .. } => Error::Parameter {
            origin: "--set".into(),
            message: error.to_string(),
        },
        fairing::Error::Partition { .. } => Error::Invalid {
            path: POINTS.into(),
            message: error.to_string(),
        },
        other => Error::Internal {
            message: other.to_string(),
        },
    }
}

fn describe(result: FairingResult<2>, kind: CurveKind, closed: bool) -> CurveOutcome {
    let points: Vec<Vec<f64>> = result.points.iter().map(|p| vec![p.x, p.y]).collect();
    let curve = match kind {
        CurveKind::Function => {
            let x: Vec<f64> = result.points.iter().map(|p| p.x).collect();
            let y: Vec<f64> = result.points.iter().map(|p| p.y).collect();
            let c = curve_repr::SplineFunction::new(&x, &y, curve_repr::EndCondition::ParabolicRunout)
                .map(|s| s.c().to_vec())
                .unwrap_or_default();
            serde_json::json!({
                "type": "spline-function",
                "end_condition": "parabolic-runout",
                "x": x, "y": y, "c": c,
                "c_meaning": "y''(x_i)/6 (Han's convention)",
            })
        }
        CurveKind::Parametric => serde_json::json!({
            "type": "interpolating-cubic",
            "end_condition": "natural",
            "parametrization": "chord-length",
            "closed": closed,
            "points": points,
        }),
    };
    let mut extras = BTreeMap::new();
    extras.insert(
        "termination".into(),
        serde_json::json!(format!("{:?}", result.termination)),
    );
    extras.insert("stages".into(), serde_json::json!(result.stages));
    extras.insert("closed".into(), serde_json::json!(closed));
    CurveOutcome {
        points: Points::Planar(result.points.iter().map(|p| Vec2::new(p.x, p.y)).collect()),
        iterations: result.iterations,
        moved: result.moved,
        elapsed_ms: result.elapsed.as_secs_f64() * 1e3,
        curve,
        extras,
        represented_energies: None,
    }
}
