//! `two-phase`: Han et al.'s coarse-to-fine fairing (§4.1) of a function y(x), and for
//! parametric planar input the arbitrary-curve pipeline of §4.2 around it
//! ([`SegmentedFairing`]), open or closed.
//!
//! The report's extras: `stages`, `closed`, and `prepass`, what the noise pre-pass did
//! ([`PrepassReport`]; null with `denoise = off`): `fits`, the fits whose results it used,
//! each with its `role` ([`PrepassFit::role`](crate::two_phase::PrepassFit::role):
//! `function`, `open`, `periodic`, `corner` and `through-corner`, or `first-seam` and
//! `second-seam`), `smoother` (`jump-lsq` or `smoothing-spline`) and `jump_lsq`, jump-lsq's
//! report spelt as `jump-lsq`'s extras (without `closed`), with the `rule`, `lambda`,
//! `difference_order` and `ends` it chose from the data; and `bins`, the bins fitted beyond
//! the pre-pass's limit of points ([`MAX_PREPASS_POINTS`](crate::two_phase::MAX_PREPASS_POINTS)
//! for a function, [`MAX_CURVE_PREPASS_POINTS`](crate::two_phase::MAX_CURVE_PREPASS_POINTS) for
//! a curve), else null.

use std::f64::consts::PI;

use curve_repr::{EndCondition, SplineFunction, Vec2};
use serde::{Deserialize, Serialize};

use super::jump_lsq::{closes, without_repeat};
use crate::catalog::{CurveJob, CurveKind, CurveMethod, CurvePoints, CurveRun, Settings};
use crate::two_phase::{PrepassReport, TwoPhase, TwoPhaseSettings};
use crate::{CurveGuard, EndClamp, Error, PartitionSettings, Pipeline, Refusal, Result, SegmentedFairing};

/// The parameters of `two-phase`: Han's phases ([`TwoPhaseSettings`]) and the options of the
/// arbitrary-curve pipeline (§4.2) that parametric input runs through.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, rename_all = "kebab-case")]
pub struct TwoPhaseCurveSettings {
    /// The two phases' settings (their fields are parameters of the same list).
    #[serde(flatten)]
    pub phases: TwoPhaseSettings,
    /// Parametric input: partition-fair-blend passes (Han 4.2.4).
    #[schemars(range(min = 1))]
    pub segment_passes: usize,
    /// Parametric input: largest turning angle of a segment, degrees.
    ///
    /// In (0, 180]; 180 is Han §4.2.1 ([`PartitionSettings::limit`] in radians).
    #[schemars(range(max = 180), extend("exclusiveMinimum" = 0))]
    pub turning_limit: f64,
    /// Parametric input: points shared by adjacent segments.
    #[schemars(range(min = 1))]
    pub overlap: usize,
    /// Parametric input: true for a closed curve (last point joins the first).
    pub closed: bool,
    /// Parametric input: refuse moves (local), passes (pass) or none (off, the paper) that make the curve's inflections or vibrations worse.
    ///
    /// Not in the paper; [`CurveGuard`] says what is counted and what it measured.
    pub curve_guard: CurveGuard,
}

impl Default for TwoPhaseCurveSettings {
    fn default() -> Self {
        let partition = PartitionSettings::default();
        TwoPhaseCurveSettings {
            phases: TwoPhaseSettings::default(),
            segment_passes: SegmentedFairing::<TwoPhase>::DEFAULT_PASSES,
            turning_limit: PartitionSettings::DEFAULT_LIMIT_DEGREES,
            overlap: partition.overlap,
            closed: false,
            curve_guard: SegmentedFairing::<TwoPhase>::DEFAULT_CURVE_GUARD,
        }
    }
}

impl TwoPhaseCurveSettings {
    /// The partition settings (limit in radians).
    pub fn partition(&self) -> PartitionSettings {
        PartitionSettings::default()
            .with_limit(self.turning_limit * PI / 180.0)
            .with_overlap(self.overlap)
    }
}

impl Settings for TwoPhaseCurveSettings {
    /// The ranges declared on the fields (`turning-limit` in (0, 180], `segment-passes` ≥ 1,
    /// the phases' own), then the phases' and the partition's checks.
    fn validate(&self) -> Result<()> {
        crate::catalog::check_declared_ranges(self)?;
        self.phases.validate()?;
        self.partition().validate().map_err(|e| match e {
            Error::BadParameter {
                name: "limit",
                value,
                reason,
            } => Error::BadParameter {
                name: "turning-limit",
                value,
                reason,
            },
            other => other,
        })
    }
}

/// The `two-phase` method.
#[derive(Clone, Copy, Debug, Default)]
pub struct TwoPhaseMethod;

impl CurveMethod for TwoPhaseMethod {
    type Settings = TwoPhaseCurveSettings;

    /// Han's spline function and its parametric pair are planar: spatial points are refused
    /// by the catalogue.
    fn planar_only(&self) -> bool {
        true
    }

    /// `g0` at most (the spline function has the parabolic-runout end
    /// condition and cannot hold end tangents or curvatures), no clamp on a closed curve;
    /// `closed` needs parametric input.
    fn check(&self, settings: &TwoPhaseCurveSettings, job: &CurveJob) -> Result<()> {
        let refuse = |what, reason: &str| Error::Refused {
            method: job.method.to_owned(),
            what,
            reason: reason.to_owned(),
        };
        match job.constraints.end_clamp() {
            EndClamp::G1 | EndClamp::G2 => {
                return Err(refuse(
                    Refusal::EndClamp,
                    "supports only g0: its spline function has the parabolic-runout end condition \
                     and cannot hold end tangents or curvatures",
                ))
            }
            EndClamp::G0 if is_closed(settings, job) => {
                return Err(refuse(
                    Refusal::EndClamp,
                    "was given an end clamp, but a closed curve has no ends",
                ))
            }
            _ => {}
        }
        if settings.closed && job.kind == CurveKind::Function {
            return Err(Error::BadValue {
                name: "closed".into(),
                message: "`true` needs parametric input (--kind parametric)".into(),
            });
        }
        Ok(())
    }

    /// A parametric polygon whose last point repeats its first is closed (as for jump-lsq):
    /// faired without the repeat, which is written back equal to the faired first point.
    fn run(&self, settings: &TwoPhaseCurveSettings, job: &CurveJob) -> Result<CurveRun> {
        if closes(job) {
            let Some(points) = job.points.as_dimension::<2>() else {
                return Err(Error::Refused {
                    method: job.method.to_owned(),
                    what: Refusal::Dimension,
                    reason: "fairs planar curves only".into(),
                });
            };
            let n = points.len();
            let reduced = without_repeat(job.constraints, n);
            let distinct = CurvePoints::Planar(points[..n - 1].to_vec());
            let inner = CurveJob {
                points: &distinct,
                constraints: &reduced,
                ..*job
            };
            let closed_settings = TwoPhaseCurveSettings {
                closed: true,
                ..settings.clone()
            };
            let mut run = self.run(&closed_settings, &inner)?;
            let mut faired = run.points.as_dimension::<2>().unwrap_or(&[]).to_vec();
            let first = faired[0];
            faired.push(first);
            if first != points[n - 1] {
                run.moved.push(n - 1);
            }
            run.points = CurvePoints::Planar(faired);
            run.curve = describe(&run.points, job.kind, true);
            return Ok(run);
        }
        let Some(points) = job.points.as_dimension::<2>() else {
            return Err(Error::Refused {
                method: job.method.to_owned(),
                what: Refusal::Dimension,
                reason: "fairs planar curves only".into(),
            });
        };
        let phases = settings.phases.clone();
        let (result, prepass) = match job.kind {
            CurveKind::Function => {
                let mut function = TwoPhase::new(phases.clone());
                let result = Pipeline::new(&mut function)
                    .with_constraints(job.constraints.clone())
                    .with_max_iterations(phases.max_passes.max(1))
                    .with_trace(false)
                    .run(points.to_vec())?;
                (result, prepass_json(function.prepass()))
            }
            CurveKind::Parametric => {
                let mut curve = SegmentedFairing::new(TwoPhase::new(phases))
                    .with_partition(settings.partition())
                    .with_passes(settings.segment_passes)
                    .with_curve_guard(settings.curve_guard);
                let result = Pipeline::new(&mut curve)
                    .with_closed(settings.closed)
                    .with_constraints(job.constraints.clone())
                    .with_max_iterations(settings.segment_passes)
                    .with_trace(false)
                    .run(points.to_vec())?;
                (result, prepass_json(curve.fairer().prepass()))
            }
        };
        let stages = serde_json::to_value(&result.stages).unwrap_or_default();
        let mut run = CurveRun::from_result(result);
        run.curve = describe(&run.points, job.kind, settings.closed);
        run.extras.insert("stages".into(), stages);
        run.extras.insert("closed".into(), settings.closed.into());
        run.extras.insert("prepass".into(), prepass);
        Ok(run)
    }
}

/// `closed = true`, or a parametric polygon whose last point repeats its first.
fn is_closed(settings: &TwoPhaseCurveSettings, job: &CurveJob) -> bool {
    settings.closed || closes(job)
}

/// The report's `prepass` (module doc): null where the pre-pass did nothing.
fn prepass_json(prepass: Option<&PrepassReport>) -> serde_json::Value {
    let Some(prepass) = prepass else {
        return serde_json::Value::Null;
    };
    let fits: Vec<serde_json::Value> = prepass
        .fits
        .iter()
        .map(|fit| {
            let jump_lsq = fit.jump_lsq.as_ref().map(|report| {
                super::jump_lsq::report_fields(report)
                    .into_iter()
                    .map(|(name, value)| (name.to_owned(), value))
                    .collect::<serde_json::Map<_, _>>()
            });
            serde_json::json!({
                "role": fit.role,
                "smoother": fit.smoother,
                "jump_lsq": jump_lsq,
            })
        })
        .collect();
    serde_json::json!({ "fits": fits, "bins": prepass.bins })
}

/// The report's `curve`: the spline function with its c_i (function), or the interpolating
/// cubic through the points (parametric).
fn describe(points: &CurvePoints, kind: CurveKind, closed: bool) -> serde_json::Value {
    let points: &[Vec2] = points.as_dimension::<2>().unwrap_or(&[]);
    match kind {
        CurveKind::Function => {
            let x: Vec<f64> = points.iter().map(|p| p.x).collect();
            let y: Vec<f64> = points.iter().map(|p| p.y).collect();
            let c = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout)
                .map(|s| s.c().to_vec())
                .unwrap_or_default();
            serde_json::json!({
                "type": "spline-function",
                "end_condition": "parabolic-runout",
                "x": x, "y": y, "c": c,
                "c_meaning": "y''(x_i)/6 (Han's convention)",
            })
        }
        CurveKind::Parametric => {
            let rows: Vec<[f64; 2]> = points.iter().map(|p| [p.x, p.y]).collect();
            serde_json::json!({
                "type": "interpolating-cubic",
                "end_condition": "natural",
                "parametrization": "chord-length",
                "closed": closed,
                "points": rows,
            })
        }
    }
}
