//! The [`FairingStrategy`] trait: how the shape is changed, one step at a time.

use crate::{Constraints, EndClamp, Error, FairingState, Result};

/// What a strategy reports after one step. The moves themselves are recorded by
/// [`FairingState::move_point`]; the pipeline puts them in the [`StepRecord`](crate::StepRecord).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepOutcome {
    /// The strategy has nothing left to do (no case of its rules applies, every pass made).
    pub done: bool,
    /// The strategy's energy or criterion value after the step, if it has one.
    pub criterion: Option<f64>,
}

impl StepOutcome {
    /// A step after which the strategy wants to go on.
    pub fn running(criterion: Option<f64>) -> Self {
        Self {
            done: false,
            criterion,
        }
    }

    /// The strategy's last step: nothing left to do.
    pub fn done(criterion: Option<f64>) -> Self {
        Self {
            done: true,
            criterion,
        }
    }
}

/// A fairing method: the solver in argmin's terms. The [`Pipeline`](crate::Pipeline) owns the
/// loop, the limits and the observers; a strategy only says how to take one step.
///
/// Contract:
/// - [`supports`](Self::supports) returns [`Error::ConstraintUnsupported`] for every
///   constraint the strategy cannot honour; the pipeline calls it before any stage runs.
/// - [`init`](Self::init) is called once before the first step of the stage (build the
///   spline, the indicator, restraining radii). It may set `state.criterion`.
/// - [`step`](Self::step) moves points only through [`FairingState::move_point`] and reads the
///   actual position it returns (the constraints may have shortened the move).
pub trait FairingStrategy<const D: usize> {
    /// The method's name, as `fair methods` lists it (e.g. `"two-phase"`).
    fn name(&self) -> &str;

    /// Whether the strategy can honour `constraints`. The default accepts fixed points,
    /// radii, the tolerance band (all enforced by `move_point`) and [`EndClamp::None`] /
    /// [`EndClamp::G0`], and rejects G1 and G2, which need the representation's help.
    fn supports(&self, constraints: &Constraints) -> Result<()> {
        reject_derivative_clamps(self.name(), constraints)
    }

    /// Prepares the stage. Default: nothing.
    fn init(&mut self, state: &mut FairingState<D>) -> Result<()> {
        let _ = state;
        Ok(())
    }

    /// Takes one step.
    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome>;
}

impl<const D: usize, S: FairingStrategy<D> + ?Sized> FairingStrategy<D> for Box<S> {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn supports(&self, constraints: &Constraints) -> Result<()> {
        (**self).supports(constraints)
    }
    fn init(&mut self, state: &mut FairingState<D>) -> Result<()> {
        (**self).init(state)
    }
    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        (**self).step(state)
    }
}

/// A borrowed strategy runs like the strategy itself, so that a caller can read its state
/// (a fit, a history) after a [`Pipeline`](crate::Pipeline) has run it.
impl<const D: usize, S: FairingStrategy<D> + ?Sized> FairingStrategy<D> for &mut S {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn supports(&self, constraints: &Constraints) -> Result<()> {
        (**self).supports(constraints)
    }
    fn init(&mut self, state: &mut FairingState<D>) -> Result<()> {
        (**self).init(state)
    }
    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        (**self).step(state)
    }
}

/// The default of [`FairingStrategy::supports`]: G1 and G2 end clamps are rejected with
/// [`Error::ConstraintUnsupported`], everything else accepted.
pub fn reject_derivative_clamps(strategy: &str, constraints: &Constraints) -> Result<()> {
    match constraints.end_clamp() {
        EndClamp::G1 | EndClamp::G2 => Err(Error::ConstraintUnsupported {
            strategy: strategy.to_owned(),
            constraint: format!("end clamp {}", constraints.end_clamp().name()),
        }),
        EndClamp::None | EndClamp::G0 => Ok(()),
    }
}
