//! `--method strain-energy | kjellander | poliakoff`: Zhang–Cheng strain-energy point
//! replacement ([`fairing::strategies::StrainEnergy`]; Zhang, Zhang & Cheng, CAD 2001, §2–3).
//!
//! The mode follows `--points`: without it the automatic algorithm (§3.3 algorithm 2: the
//! worst z_i first, each point kept in its restraining circle/sphere); with it the interactive
//! one on the named bad points (algorithm 1: adjacent worst two replaced together, Eq. 15).
//! `kjellander` fixes uniform knots, `poliakoff` chord-length knots; `strain-energy` takes
//! `parametrization`.
//!
//! Parameters (registry): `energy-tolerance` (stop when |ΔE| ≤ tol·E, default 1e-6),
//! `radius-scale` (scale of the restraining radii, default 1 = the paper), `pairs` (on/off:
//! automatic mode may replace the two worst adjacent points together, default off),
//! `replacement` (limit = Eq. 11/15, iterated = one application of Eq. 8/13 per step),
//! `max-iterations` (default 100000), and for `strain-energy` `parametrization`
//! (chord-length, uniform, centripetal).
//!
//! Constraints: `--fixed` and `--tolerance` are honoured by the library's constraints;
//! `--clamp-ends g0` keeps the end points (which this method never moves anyway); `g1` and
//! `g2` are refused (the natural spline's end tangent follows the interior points).

use std::collections::BTreeMap;

use curve_repr::{HermiteSettings, HermiteSpline, Parametrization, Vector};
use fairing::strategies::{Mode, Replacement, StrainEnergy, StrainEnergySettings};
use fairing::FairingResult;

use super::strategy_run::{fairing_constraints, run_strategy};
use super::{CurveJob, CurveOutcome};
use crate::error::{Error, Result};
use crate::input::Points;
use crate::parameters::Parameters;

/// Runs the strain-energy family on `job`'s points.
pub fn fair(job: &CurveJob) -> Result<CurveOutcome> {
    let parameters = job.parameters;
    let parametrization = match job.method.name {
        "kjellander" => Parametrization::Uniform,
        "poliakoff" => Parametrization::ChordLength,
        _ => match parameters
            .choice(
                "parametrization",
                &["chord-length", "uniform", "centripetal"],
                "chord-length",
            )?
            .as_str()
        {
            "uniform" => Parametrization::Uniform,
            "centripetal" => Parametrization::Centripetal,
            _ => Parametrization::ChordLength,
        },
    };
    let replacement = match parameters
        .choice("replacement", &["limit", "iterated"], "limit")?
        .as_str()
    {
        "iterated" => Replacement::Iterated,
        _ => Replacement::Limit,
    };
    let mut settings = StrainEnergySettings::default()
        .with_parametrization(parametrization)
        .with_tolerance(non_negative(parameters, "energy-tolerance", 1e-6)?)
        .with_radius_scale(non_negative(parameters, "radius-scale", 1.0)?)
        .with_pairs(parameters.choice("pairs", &["on", "off"], "off")? == "on")
        .with_replacement(replacement);
    let n = job.input.len();
    let bad = &job.constraints.bad_points;
    if let Some(k) = bad.iter().find(|&&k| k == 0 || k + 1 >= n) {
        return Err(Error::Argument {
            option: "--points",
            message: format!(
                "point {k} is an end point; {} replaces interior points only (1 to {})",
                job.method.name,
                n.saturating_sub(2)
            ),
        });
    }
    if !bad.is_empty() {
        settings = settings.with_mode(Mode::Interactive(bad.clone()));
    }
    let max_iterations = parameters.count("max-iterations", 100_000)?;
    match &job.input.points {
        Points::Planar(points) => {
            let run = run_strategy(
                job,
                StrainEnergy::new(settings.clone()),
                points,
                max_iterations,
                fairing_constraints(job.constraints),
            )?;
            Ok(outcome(points, run, &settings))
        }
        Points::Spatial(points) => {
            let run = run_strategy(
                job,
                StrainEnergy::new(settings.clone()),
                points,
                max_iterations,
                fairing_constraints(job.constraints),
            )?;
            Ok(outcome(points, run, &settings))
        }
    }
}

/// `name` as a number ≥ 0 (a finite one, as [`Parameters::number`] reads it).
pub(super) fn non_negative(parameters: &Parameters, name: &str, default: f64) -> Result<f64> {
    let value = parameters.number(name, default)?;
    if value < 0.0 {
        return Err(Error::Parameter {
            origin: parameters
                .get(name)
                .map(|g| g.origin.clone())
                .unwrap_or_else(|| "--set".into()),
            message: format!("`{name}` = `{value}` must not be negative"),
        });
    }
    Ok(value)
}

/// The report's `curve` for a parametric cubic Hermite spline: knots, points and tangents.
pub(super) fn hermite_json<const D: usize>(
    spline: &HermiteSpline<D>,
    parametrization: &str,
) -> serde_json::Value {
    let rows = |v: &[Vector<D>]| {
        v.iter()
            .map(|p| p.iter().copied().collect::<Vec<f64>>())
            .collect::<Vec<_>>()
    };
    serde_json::json!({
        "type": "hermite",
        "degree": 3,
        "end_condition": "natural",
        "parametrization": parametrization,
        "knots": spline.knots(),
        "points": rows(spline.points()),
        "tangents": rows(spline.tangents()),
    })
}

fn parametrization_name(p: Parametrization) -> &'static str {
    match p {
        Parametrization::Uniform => "uniform",
        Parametrization::ChordLength => "chord-length",
        Parametrization::Centripetal => "centripetal",
    }
}

fn outcome<const D: usize>(
    original: &[Vector<D>],
    run: FairingResult<D>,
    settings: &StrainEnergySettings,
) -> CurveOutcome {
    let mut extras = BTreeMap::new();
    extras.insert("termination".into(), serde_json::json!(run.termination));
    extras.insert(
        "mode".into(),
        serde_json::json!(match settings.mode {
            Mode::Automatic => "automatic",
            Mode::Interactive(_) => "interactive",
        }),
    );
    let par = parametrization_name(settings.parametrization);
    extras.insert("parametrization".into(), serde_json::json!(par));
    // The strain energy ∫|C''|² of the natural spline at the ORIGINAL points' knots (the
    // knots are fixed while fairing), before and after: the quantity the method lowers.
    let knots = settings.parametrization.parameters(original).ok();
    let spline_at = |p: &[Vector<D>]| {
        knots
            .as_ref()
            .and_then(|t| HermiteSpline::new(p, &HermiteSettings::new().with_parameters(t.clone())).ok())
    };
    let mut curve = serde_json::Value::Null;
    if let (Some(before), Some(after)) = (spline_at(original), spline_at(&run.points)) {
        extras.insert(
            "strain_energy_before".into(),
            serde_json::json!(before.strain_energy()),
        );
        extras.insert(
            "strain_energy_after".into(),
            serde_json::json!(after.strain_energy()),
        );
        curve = hermite_json(&after, par);
    }
    let points = points_of(&run.points);
    CurveOutcome {
        points,
        iterations: run.iterations,
        moved: run.moved,
        elapsed_ms: run.elapsed.as_secs_f64() * 1e3,
        curve,
        extras,
        represented_energies: None,
    }
}

/// Library points back into the command's [`Points`] (D is 2 or 3 here).
pub(super) fn points_of<const D: usize>(points: &[Vector<D>]) -> Points {
    let rows: Vec<Vec<f64>> = points.iter().map(|p| p.iter().copied().collect()).collect();
    Points::from_rows(D, &rows).unwrap_or(Points::Planar(Vec::new()))
}
