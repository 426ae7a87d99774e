//! Records of the steps a pipeline ran: what observers see, and the trace of every move.

use serde::{Deserialize, Serialize};

use crate::Move;

/// One step as the pipeline saw it; handed to every [`Observer`](crate::Observer).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StepRecord<const D: usize> {
    /// The stage, counting from 0.
    pub stage: usize,
    /// The step within the stage, counting from 1.
    pub iteration: usize,
    /// Every point moved in this step, in the order the strategy moved them.
    pub moves: Vec<Move<D>>,
    /// The strategy's criterion value after the step, if it has one.
    pub criterion: Option<f64>,
    /// Whether the strategy declared itself done.
    pub done: bool,
}

/// Every step of a run, serialisable (serde) for plots.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Trace<const D: usize> {
    /// The steps, in order.
    pub steps: Vec<StepRecord<D>>,
}

impl<const D: usize> Trace<D> {
    /// Total number of moves recorded.
    pub fn move_count(&self) -> usize {
        self.steps.iter().map(|s| s.moves.len()).sum()
    }

    /// Every move, in order.
    pub fn moves(&self) -> impl Iterator<Item = &Move<D>> {
        self.steps.iter().flat_map(|s| s.moves.iter())
    }
}
