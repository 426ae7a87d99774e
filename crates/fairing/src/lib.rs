//! Fairing strategies, the constraints they honour and the pipeline that runs them.
//!
//! The third and fourth axes of the framework (see the README): *how the shape is changed*
//! ([`FairingStrategy`]) and *what must hold* ([`Constraints`]). The pieces are separate as
//! in argmin: a strategy says how to take one step on a [`FairingState`]; the [`Pipeline`]
//! owns the loop, termination ([`TerminationReason`]), [`Observer`]s, the [`Trace`] of every
//! move, timing, composition of stages and the final [`Constraints::check`].
//!
//! [`catalog`] names every method, criterion and indicator, reads each method's parameters
//! from its settings type, parses and runs config pipelines: the one path the `fair`
//! command, bindings and programs share (a method added there is a method of the command).
//!
//! [`mod@partition`] holds the arbitrary-curve machinery of Han et al. §4.2: split a planar
//! curve into overlapping function segments by turning angle, transform each into the frame of
//! its angular bisector, fair it as a function y(x), transform back and blend the overlaps
//! ([`SegmentedFairing`]).

// `fairing::serde` and `fairing::schemars`, the paths `settings!` derives through, resolve
// inside this crate too.
extern crate self as fairing;

mod bins;
pub mod catalog;
pub mod constraints;
pub mod corners;
pub mod displacement;
pub mod error;
pub mod observer;
pub mod partition;
pub mod pipeline;
mod settings_macro;
pub mod smoothing;
pub mod state;
pub mod strategies;
pub mod strategy;
pub mod trace;
pub mod two_phase;

pub use constraints::{project_into_ball, Constraints, EndClamp};
pub use error::{Error, Refusal, Result};
pub use observer::Observer;
pub use partition::{
    curve_counts, partition, CurveGuard, PartitionSettings, Segment, SegmentFairer, SegmentedFairing,
};
pub use pipeline::{FairingResult, Pipeline, StageReport, TerminationReason};
/// What a settings struct derives with, at the framework's versions: a user crate needs no
/// direct dependency (`#[serde(crate = "fairing::serde")]`,
/// `#[schemars(crate = "fairing::schemars")]`).
pub use schemars;
pub use serde;
pub use serde_json;
pub use state::{strategy_error, FairingState, Move};
pub use strategy::{reject_derivative_clamps, FairingStrategy, StepOutcome};
pub use trace::{StepRecord, Trace};

#[cfg(test)]
mod tests;
