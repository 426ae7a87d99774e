//! The state a strategy works on: current and original points, the constraints, what moved.

use std::collections::BTreeSet;

use curve_repr::Vector;
use serde::{Deserialize, Serialize};

use crate::{Constraints, Error, Result};

/// One point moved from `from` to `to` (after the constraints were applied).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Move<const D: usize> {
    /// The point's index, counting from 0.
    pub index: usize,
    /// Its position before the move.
    pub from: Vector<D>,
    /// Its position after the move.
    pub to: Vector<D>,
}

/// What a strategy sees and changes: a small concrete state (argmin's `IterState` without the
/// generics).
///
/// The points are private: a strategy reads them with [`points`](Self::points) and moves them
/// only through [`move_point`](Self::move_point), which applies the constraints and records
/// the move. Thus no strategy can bypass a constraint or move a point unseen by the trace.
#[derive(Clone, Debug)]
pub struct FairingState<const D: usize> {
    points: Vec<Vector<D>>,
    original: Vec<Vector<D>>,
    constraints: Constraints,
    closed: bool,
    moved: BTreeSet<usize>,
    pending: Vec<Move<D>>,
    /// The stage being run, counting from 0 (set by the pipeline).
    pub stage: usize,
    /// Steps completed in the current stage (set by the pipeline).
    pub iteration: usize,
    /// The strategy's energy or criterion value after its last step, if it has one. The
    /// pipeline's tolerance test compares consecutive values.
    pub criterion: Option<f64>,
}

impl<const D: usize> FairingState<D> {
    /// A state at the start: the points are their own originals, nothing moved. `closed`
    /// says the last point joins the first.
    ///
    /// Errors: non-finite coordinates, constraints that do not fit `points.len()`, an end
    /// clamp on a closed curve (it has no ends).
    pub fn new(points: Vec<Vector<D>>, constraints: Constraints, closed: bool) -> Result<Self> {
        curve_repr::vector::check_finite(&points)?;
        constraints.validate(points.len())?;
        if closed && constraints.end_clamp() != crate::EndClamp::None {
            return Err(Error::BadConstraint {
                reason: format!(
                    "end clamp {} on a closed curve, which has no ends",
                    constraints.end_clamp().name()
                ),
            });
        }
        Ok(Self {
            original: points.clone(),
            points,
            constraints,
            closed,
            moved: BTreeSet::new(),
            pending: Vec::new(),
            stage: 0,
            iteration: 0,
            criterion: None,
        })
    }

    /// Whether the points form a closed curve.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The current points.
    pub fn points(&self) -> &[Vector<D>] {
        &self.points
    }

    /// The original points, the input of the whole pipeline (not of the current stage).
    pub fn original(&self) -> &[Vector<D>] {
        &self.original
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there is no point.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The constraints in force.
    pub fn constraints(&self) -> &Constraints {
        &self.constraints
    }

    /// Indices of every point moved so far (by any stage), increasing. A point moved and moved
    /// back stays in this set; [`FairingResult::moved`](crate::FairingResult::moved) lists the
    /// points whose final position differs from the original.
    pub fn moved(&self) -> &BTreeSet<usize> {
        &self.moved
    }

    /// Whether point `index` may move at all (see [`Constraints::is_movable`]).
    pub fn is_movable(&self, index: usize) -> bool {
        self.constraints.is_movable(index, self.points.len())
    }

    /// Moves point `index` towards `proposed`, projected by
    /// [`Constraints::constrain_move_from`] (the coordinates the proposal does not change are
    /// kept), and returns where it actually went. A move that changes nothing is not recorded. O(D).
    ///
    /// Errors: an index out of range, a non-finite proposal.
    pub fn move_point(&mut self, index: usize, proposed: Vector<D>) -> Result<Vector<D>> {
        let n = self.points.len();
        let (Some(original), Some(current)) = (self.original.get(index), self.points.get(index).copied())
        else {
            return Err(curve_repr::Error::IndexOutOfRange {
                what: "points",
                index,
                len: n,
            }
            .into());
        };
        // Coordinates the proposal leaves as they are stay as they are (a y-only move of a
        // function strategy never changes x, whatever an earlier stage did to x).
        let to = self
            .constraints
            .constrain_move_from(index, n, original, &current, &proposed)?;
        if to != current {
            if let Some(slot) = self.points.get_mut(index) {
                *slot = to;
            }
            self.moved.insert(index);
            self.pending.push(Move {
                index,
                from: current,
                to,
            });
        }
        Ok(to)
    }

    /// The moves made since the last call (the pipeline collects them after every step).
    pub fn take_moves(&mut self) -> Vec<Move<D>> {
        std::mem::take(&mut self.pending)
    }

    /// Gives back the storage of moves taken by [`take_moves`](Self::take_moves) and no
    /// longer needed (the pipeline's, when no trace keeps them), so that the next step's
    /// moves do not allocate.
    pub(crate) fn recycle_moves(&mut self, mut moves: Vec<Move<D>>) {
        if self.pending.capacity() == 0 {
            moves.clear();
            self.pending = moves;
        }
    }

    /// Takes the points out of the state at the end of a run.
    pub(crate) fn into_points(self) -> (Vec<Vector<D>>, Vec<Vector<D>>) {
        (self.points, self.original)
    }
}

impl<const D: usize> FairingState<D> {
    /// Checks the current points against the constraints (see [`Constraints::check`]).
    pub fn check(&self) -> Result<()> {
        self.constraints.check(&self.original, &self.points)
    }
}

/// Returns an error naming the strategy: a helper for strategy authors.
pub fn strategy_error(strategy: &str, reason: impl Into<String>) -> Error {
    Error::Strategy {
        strategy: strategy.to_owned(),
        reason: reason.into(),
    }
}
