//! Han et al.'s coarse-to-fine fairing of a function segment (Han et al. §4.1).
//!
//! - [`TwoPhaseSettings`]: λ of both phases, the α rule, passes, the long-run option, the
//!   pre-pass, the move cap and the count guards.
//! - [`phase1`]: Phase 1, coarse fairing of curvature vibrations (small, medium, large;
//!   interior and end cases), [`coarse_pass`].
//! - [`phase2`]: Phase 2, fine fairing of inflections (small and large curve vibrations,
//!   interior and end cases, the α rule, a well-posed Case 2), [`fine_pass`]; as an option
//!   beyond the paper, wrong-sign runs of more than two points.
//! - [`full_pass`] / [`fair_function`]: the phases alternating (coarse, then fine) until a
//!   full pass applies no case or `max_passes` is reached.
//! - [`TwoPhase`]: a [`FairingStrategy<2>`] for function segments (one full pass per step),
//!   and a [`SegmentFairer`] so that
//!   [`SegmentedFairing`](crate::SegmentedFairing)`::new(TwoPhase::default())` fairs arbitrary
//!   open or closed planar curves (Han §4.2).
//! - [`bins`]: the noise pre-pass of dense data (beyond 10^5 points) on the means of bins of
//!   consecutive points (not in the paper).

pub mod bins;
mod denoise;
pub mod foot_point;
pub mod phase1;
pub mod phase2;
mod quintic;
mod settings;

pub use bins::{BINS_PER_DOF, FIRST_BINS, MAX_BINS, MAX_CURVE_PREPASS_POINTS, MAX_PREPASS_POINTS};
pub use denoise::{
    denoise, denoise_by, denoise_curve, denoise_curve_by, denoise_curve_reported, denoise_reported,
    CurvePrepass, Denoise, Limits, Prepass, PrepassFit, PrepassReport, PrepassRule, CORRECTION_ROUNDS,
};
pub use foot_point::{foot_points, FootPoint, Projection};
pub use phase1::{coarse_pass, counts, detect, displacement, e_at, Case, CaseKind, PassReport};
pub use phase2::{detect_fine, end_y_change, fine_displacement, fine_pass, zero_level};
pub use settings::{
    CountGuard, MoveCap, TwoPhaseSettings, END_RUN_MAX_DEVIANCE, GUARD_WINDOW, MAX_MOVE_FACTOR, PAIR_MIN_SINE,
};
pub(crate) use settings::{Rules, RunData};

use curve_repr::{EndCondition, SplineFunction, Vec2};

use crate::partition::SegmentFairer;
use crate::state::strategy_error;
use crate::{
    reject_derivative_clamps, Constraints, Error, FairingState, FairingStrategy, Refusal, Result, StepOutcome,
};

/// One full pass: a [`coarse_pass`] then a [`fine_pass`] (Han §4.1: "the two primary phases
/// are performed in an alternative way iteratively"). Returns both reports.
///
/// With the long-run option (`max_run` > 2) and a count guard on, the coarse pass works for
/// the fine pass that follows: its moves are not count-guarded one by one (it runs with
/// [`CountGuard::Off`]); if the full pass then ends with more inflections than it started
/// with, it is undone and redone with the coarse moves guarded (the coarse report is then
/// marked `reverted`), so a full pass never raises Infl_num. On noise, Phase 1 turns short
/// wrong-sign runs of c into runs that the absorption can take, adding inflections on the way
/// that Phase 2 then removes; guarding every coarse move stops that (see
/// [`phase2`]). O(n · guard window), twice for a redone pass.
pub fn full_pass(
    spline: &mut SplineFunction,
    settings: &TwoPhaseSettings,
    movable: &dyn Fn(usize) -> bool,
) -> Result<(PassReport, PassReport)> {
    full_pass_from(spline, &Rules::direct(settings), movable, None)
}

/// [`full_pass`] given the spline's [`counts`] if the caller knows them (the last pass's fine
/// [`PassReport::counts`]).
fn full_pass_from(
    spline: &mut SplineFunction,
    settings: &Rules,
    movable: &dyn Fn(usize) -> bool,
    known: Option<(usize, usize)>,
) -> Result<(PassReport, PassReport)> {
    if settings.max_run <= 2 || settings.count_guard == CountGuard::Off {
        let coarse = phase1::coarse_pass_from(spline, settings, movable, known)?;
        let fine = phase2::fine_pass_from(spline, settings, movable, Some(coarse.counts))?;
        return Ok((coarse, fine));
    }
    let start = known.unwrap_or_else(|| counts(spline));
    let saved = spline.y().to_vec();
    let open = Rules {
        settings: settings.settings.clone().with_count_guard(CountGuard::Off),
        run: settings.run.clone(),
    };
    let coarse = phase1::coarse_pass_from(spline, &open, movable, Some(start))?;
    let fine = phase2::fine_pass_from(spline, settings, movable, Some(coarse.counts))?;
    if fine.counts.1 <= start.1 {
        return Ok((coarse, fine));
    }
    // More inflections: undo, and redo the pass with each coarse move guarded.
    let restore: Vec<(usize, f64)> = coarse
        .moves
        .iter()
        .chain(&fine.moves)
        .map(|&(k, _)| (k, saved[k]))
        .collect();
    spline
        .set_y(&restore)
        .map_err(|e| strategy_error("two-phase", format!("restoring a pass failed: {e}")))?;
    spline.rebuild()?;
    let mut coarse = phase1::coarse_pass_from(spline, settings, movable, None)?;
    let fine = phase2::fine_pass_from(spline, settings, movable, Some(coarse.counts))?;
    coarse.reverted = true;
    Ok((coarse, fine))
}

/// Fairs a function segment in place: [`full_pass`]es until one applies no case or after
/// `max_passes`; returns the number of passes made. O(max_passes · n · guard window).
pub fn fair_function(
    spline: &mut SplineFunction,
    settings: &TwoPhaseSettings,
    movable: &dyn Fn(usize) -> bool,
) -> Result<usize> {
    fair_spline(spline, &Rules::direct(settings), movable)
}

/// [`fair_function`] with the run's data.
fn fair_spline(spline: &mut SplineFunction, rules: &Rules, movable: &dyn Fn(usize) -> bool) -> Result<usize> {
    rules.validate()?;
    let mut now = counts(spline);
    for pass in 1..=rules.max_passes {
        optim::cancel::checkpoint()?;
        let (coarse, fine) = full_pass_from(spline, rules, movable, Some(now))?;
        now = fine.counts;
        if coarse.moves.is_empty() && fine.moves.is_empty() {
            return Ok(pass);
        }
    }
    Ok(rules.max_passes)
}

/// Han's two-phase fairing of a function segment: points are (x, y) with x strictly
/// increasing, only y moves, the spline is [`SplineFunction`] with parabolic runout (Han's end
/// condition). Each [`step`](FairingStrategy::step) is one [`full_pass`] (coarse, then fine);
/// the stage is done when a pass applies no case or after `max_passes` passes.
///
/// With λ < 1 the small case shrinks |e| geometrically and keeps finding work, so on noisy
/// data the stage usually runs all `max_passes`; use
/// [`Pipeline::with_tolerance`](crate::Pipeline::with_tolerance)`(0.0)` to stop once a pass
/// leaves the vibration count (the reported criterion) unchanged.
///
/// As a [`SegmentFairer`] it runs [`fair_function`] on each segment of a
/// [`SegmentedFairing`](crate::SegmentedFairing) (the `fixed` flags are honoured; the
/// segment's end points never move).
///
/// Constraints: fixed points, radii and tolerance are honoured through
/// [`FairingState::move_point`] (a shortened move is read back into the spline); G1/G2 end
/// clamps are rejected with `ConstraintUnsupported`. The phases never move the end points
/// (Han §3.3); the noise pre-pass ([`TwoPhaseSettings::denoise`]) fits them unless they are
/// fixed or clamped (`G0`).
#[derive(Clone, Debug, Default)]
pub struct TwoPhase {
    rules: Rules,
    spline: Option<SplineFunction>,
    passes: usize,
    /// The spline's (vibrations, inflections) after the last pass.
    counts: Option<(usize, usize)>,
    /// What the noise pre-pass of the last run did (a function's, or the whole curve's).
    prepass: Option<PrepassReport>,
}

impl TwoPhase {
    /// A strategy with the given settings.
    pub fn new(settings: TwoPhaseSettings) -> Self {
        TwoPhase {
            rules: Rules::direct(&settings),
            spline: None,
            passes: 0,
            counts: None,
            prepass: None,
        }
    }

    /// What the noise pre-pass of the last run did ([`PrepassReport`]: the fits used, each
    /// with its smoother and jump-lsq's rule, λ, difference order and ends as chosen from the
    /// data, and the bins): of a function run, or of the whole curve where the strategy fairs
    /// an arbitrary curve's segments ([`SegmentedFairing`](crate::SegmentedFairing), through
    /// its `fairer`); `None` before a run and with `denoise = off`.
    pub fn prepass(&self) -> Option<&PrepassReport> {
        self.prepass.as_ref()
    }

    /// The settings.
    pub fn settings(&self) -> &TwoPhaseSettings {
        &self.rules.settings
    }
}

fn spline_of(points: &[Vec2]) -> Result<SplineFunction> {
    let x: Vec<f64> = points.iter().map(|p| p.x).collect();
    let y: Vec<f64> = points.iter().map(|p| p.y).collect();
    Ok(SplineFunction::new(&x, &y, EndCondition::ParabolicRunout)?)
}

impl FairingStrategy<2> for TwoPhase {
    fn name(&self) -> &str {
        "two-phase"
    }

    fn supports(&self, constraints: &Constraints) -> Result<()> {
        reject_derivative_clamps("two-phase", constraints)
    }

    fn init(&mut self, state: &mut FairingState<2>) -> Result<()> {
        self.rules.validate()?;
        if state.is_closed() {
            return Err(Error::refused(
                "two-phase",
                Refusal::Closed,
                "cannot fair a closed function segment",
            ));
        }
        // σ̂ and the data bound B from one noise estimate.
        let bound =
            crate::displacement::data_bound_as(state.points(), crate::displacement::NoiseModel::Vertical);
        let (x, y): (Vec<f64>, Vec<f64>) = state.points().iter().map(|p| (p.x, p.y)).unzip();
        self.rules.run = RunData {
            noise: bound.noise,
            bound: bound.bound,
            data: std::sync::Arc::from(y.clone()),
        };
        let keep = |k: usize| !state.is_movable(k);
        let allowed = |k: usize| state.constraints().allowed_distance(k);
        let limits = Limits {
            keep: &keep,
            allowed: &allowed,
        };
        let (smooth, prepass) = denoise_reported(
            self.rules.denoise,
            TwoPhaseSettings::function_prepass(),
            &x,
            &y,
            &limits,
        )?;
        self.prepass = prepass;
        for (k, (&new, &old)) in smooth.iter().zip(&y).enumerate() {
            if new != old {
                state.move_point(k, Vec2::new(x[k], new))?;
            }
        }
        let spline = spline_of(state.points())?;
        let now = counts(&spline);
        state.criterion = Some(now.0 as f64);
        self.counts = Some(now);
        self.spline = Some(spline);
        self.passes = 0;
        Ok(())
    }

    fn step(&mut self, state: &mut FairingState<2>) -> Result<StepOutcome> {
        let rules = &self.rules;
        let Some(spline) = self.spline.as_mut() else {
            return Err(strategy_error("two-phase", "step before init"));
        };
        let movable = |k: usize| state.is_movable(k);
        let (coarse, fine) = full_pass_from(spline, rules, &movable, self.counts)?;
        let mut now = fine.counts;
        // Write the moves into the state; read back what the constraints allowed.
        let mut corrections = Vec::new();
        let mut touched: Vec<usize> = coarse.moves.iter().chain(&fine.moves).map(|&(k, _)| k).collect();
        touched.sort_unstable();
        touched.dedup();
        for k in touched {
            let (Some(&x), Some(&y)) = (spline.x().get(k), spline.y().get(k)) else {
                continue;
            };
            let actual = state.move_point(k, Vec2::new(x, y))?;
            if actual.x != x {
                return Err(strategy_error(
                    "two-phase",
                    format!("a constraint moved x of point {k}"),
                ));
            }
            if actual.y != y {
                corrections.push((k, actual.y));
            }
        }
        if !corrections.is_empty() {
            spline.set_y(&corrections)?;
            spline.rebuild()?;
            now = counts(spline);
        }
        self.counts = Some(now);
        self.passes += 1;
        let criterion = Some(now.0 as f64);
        state.criterion = criterion;
        if (coarse.moves.is_empty() && fine.moves.is_empty()) || self.passes >= self.rules.max_passes {
            Ok(StepOutcome::done(criterion))
        } else {
            Ok(StepOutcome::running(criterion))
        }
    }
}

impl SegmentFairer for TwoPhase {
    fn name(&self) -> &str {
        "two-phase"
    }

    fn min_points(&self) -> usize {
        5
    }

    /// With a noise pre-pass an open curve's end points are fitted too.
    fn prepares_ends(&self) -> bool {
        self.rules.denoise != Denoise::Off
    }

    /// The noise pre-pass ([`TwoPhaseSettings::denoise`], the points projected to their
    /// foot points) on the whole curve ([`denoise_curve`]), the `kept` points interpolated,
    /// the `allowed` distances honoured.
    fn prepare(
        &mut self,
        points: &[Vec2],
        closed: bool,
        kept: &[bool],
        allowed: &[f64],
    ) -> Result<Option<Vec<Vec2>>> {
        let bound = crate::displacement::data_bound(points);
        self.rules.run = RunData {
            noise: bound.noise,
            bound: bound.bound,
            data: std::sync::Arc::from(Vec::new()),
        };
        self.prepass = None;
        if self.rules.denoise == Denoise::Off {
            return Ok(None);
        }
        let keep = |k: usize| kept.get(k).copied().unwrap_or(true);
        let allowed = |k: usize| allowed.get(k).copied().unwrap_or(0.0);
        let limits = Limits {
            keep: &keep,
            allowed: &allowed,
        };
        let rules = self.rules.curve_prepass();
        let (values, prepass) = denoise_curve_reported(&rules, points, closed, &limits)?;
        self.prepass = prepass;
        Ok(Some(values))
    }

    /// Runs Han's passes on the segment as [`fair_function`] does, with the curve's σ̂ and
    /// data bound; points with `fixed[j]` never move.
    fn fair(&mut self, x: &[f64], y: &mut [f64], fixed: &[bool]) -> Result<()> {
        let mut spline = SplineFunction::new(x, y, EndCondition::ParabolicRunout)?;
        let movable = |k: usize| !fixed.get(k).copied().unwrap_or(true);
        fair_spline(&mut spline, &self.rules, &movable)?;
        for (out, &v) in y.iter_mut().zip(spline.y()) {
            *out = v;
        }
        Ok(())
    }
}
