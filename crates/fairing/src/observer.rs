//! Observers: code the pipeline calls after every step (progress bars, logs, plots).

use crate::{FairingState, StepRecord};

/// Something that watches a run. Called after every step with the state after the step and
/// the step's record; it cannot change the state.
pub trait Observer<const D: usize> {
    /// Sees one step.
    fn observe(&mut self, state: &FairingState<D>, step: &StepRecord<D>);
}

impl<const D: usize, F: FnMut(&FairingState<D>, &StepRecord<D>)> Observer<D> for F {
    fn observe(&mut self, state: &FairingState<D>, step: &StepRecord<D>) {
        self(state, step)
    }
}
