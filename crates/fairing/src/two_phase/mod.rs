//! Han et al.'s coarse-to-fine fairing of a function segment (Han et al. §4.1).
//!
//! - [`TwoPhaseSettings`]: λ, α rule, passes, guards.
//! - [`phase1`]: Phase 1, coarse fairing of curvature vibrations (small, medium, large;
//!   interior and end cases), [`coarse_pass`].
//! - [`TwoPhase`]: a [`FairingStrategy<2>`] for function segments that runs coarse passes.
//!
//! **Not implemented yet:** Phase 2 (fine fairing of inflections, small and large curve
//! vibrations with the α rule), runs of more than two wrong-sign values, the arbitrary-curve
//! pipeline of §4.2 (use [`SegmentedFairing`](crate::SegmentedFairing) around this strategy
//! once Phase 2 exists). [`TwoPhase`] today is "Phase 1 only".

pub mod phase1;
mod settings;

pub use phase1::{coarse_pass, counts, detect, displacement, e_at, Case, CaseKind, PassReport};
pub use settings::{CountGuard, TwoPhaseSettings};

use curve_repr::{EndCondition, SplineFunction, Vec2};

use crate::state::strategy_error;
use crate::{reject_derivative_clamps, Constraints, FairingState, FairingStrategy, Result, StepOutcome};

/// Han's two-phase fairing of a function segment: points are (x, y) with x strictly
/// increasing, only y moves, the spline is [`SplineFunction`] with parabolic runout (Han's end
/// condition). Each [`step`](FairingStrategy::step) is one [`coarse_pass`]; the stage is done
/// when a pass applies no case or after `max_passes` passes.
///
/// With λ < 1 the small case shrinks |e| geometrically and keeps finding work, so on noisy
/// data the stage usually runs all `max_passes` (measured: 50 passes on a noisy sine); use
/// [`Pipeline::with_tolerance`](crate::Pipeline::with_tolerance)`(0.0)` to stop once a pass
/// leaves the vibration count (the reported criterion) unchanged.
///
/// Phase 2 is not implemented: the result has Phase 1's fewer curvature vibrations, and its
/// inflections are not reduced beyond what Phase 1 does.
///
/// Constraints: fixed points, radii and tolerance are honoured through
/// [`FairingState::move_point`] (a shortened move is read back into the spline); G1/G2 end
/// clamps are rejected with `ConstraintUnsupported`. The end points never move (Han §3.3).
#[derive(Clone, Debug, Default)]
pub struct TwoPhase {
    settings: TwoPhaseSettings,
    spline: Option<SplineFunction>,
    passes: usize,
}

impl TwoPhase {
    /// A strategy with the given settings.
    pub fn new(settings: TwoPhaseSettings) -> Self {
        TwoPhase {
            settings,
            spline: None,
            passes: 0,
        }
    }

    /// The settings.
    pub fn settings(&self) -> &TwoPhaseSettings {
        &self.settings
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
        reject_derivative_clamps(self.name(), constraints)
    }

    fn init(&mut self, state: &mut FairingState<2>) -> Result<()> {
        self.settings.validate()?;
        if state.is_closed() {
            return Err(strategy_error(self.name(), "a function segment cannot be closed"));
        }
        let spline = spline_of(state.points())?;
        state.criterion = Some(counts(&spline).0 as f64);
        self.spline = Some(spline);
        self.passes = 0;
        Ok(())
    }

    fn step(&mut self, state: &mut FairingState<2>) -> Result<StepOutcome> {
        let settings = self.settings.clone();
        let Some(spline) = self.spline.as_mut() else {
            return Err(strategy_error("two-phase", "step before init"));
        };
        let movable = |k: usize| state.is_movable(k);
        let report = coarse_pass(spline, &settings, &movable)?;
        // Write the moves into the state; read back what the constraints allowed.
        let mut corrections = Vec::new();
        let mut touched: Vec<usize> = report.moves.iter().map(|&(k, _)| k).collect();
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
        }
        self.passes += 1;
        let criterion = Some(counts(spline).0 as f64);
        state.criterion = criterion;
        if report.moves.is_empty() || self.passes >= settings.max_passes {
            Ok(StepOutcome::done(criterion))
        } else {
            Ok(StepOutcome::running(criterion))
        }
    }
}
