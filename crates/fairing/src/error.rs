//! The crate's one error type.

/// Everything that can go wrong while fairing.
///
/// Point indices count from 0, the first data point. Errors of the representations are
/// wrapped as [`Error::Repr`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// An error of a curve or surface representation (bad input points, a singular system).
    #[error(transparent)]
    Repr(#[from] curve_repr::Error),
    // Errors of the `fairness` crate go here as `Fairness(#[from] fairness::Error)` once that
    // crate has its error enum.
    /// A strategy cannot honour a constraint it was given. Strategies say so before they run,
    /// never ignore a constraint silently.
    #[error("strategy {strategy} cannot honour the constraint: {constraint}")]
    ConstraintUnsupported {
        /// The strategy's name.
        strategy: String,
        /// The constraint it cannot honour.
        constraint: String,
    },
    /// A constraint is malformed for the data it is applied to (an index out of range, a
    /// negative radius, a radius list of the wrong length).
    #[error("bad constraint: {reason}")]
    BadConstraint {
        /// What is wrong.
        reason: String,
    },
    /// A faired result breaks a constraint: a strategy has a bug. Found by
    /// [`Constraints::check`](crate::Constraints::check), which the pipeline runs at the end.
    #[error("point {index} violates the {constraint} constraint: {detail}")]
    ConstraintViolated {
        /// The point.
        index: usize,
        /// Which constraint ("fixed point", "restraining radius", "tolerance", "end clamp").
        constraint: &'static str,
        /// Numbers that show the violation.
        detail: String,
    },
    /// A parameter of a strategy, pipeline or partition is out of its range.
    #[error("bad parameter {name} = {value}: {reason}")]
    BadParameter {
        /// The parameter's name.
        name: &'static str,
        /// Its value, printed.
        value: String,
        /// Why it is not allowed.
        reason: &'static str,
    },
    /// A strategy proposed a move to a point that is NaN or infinite.
    #[error("strategy proposed a non-finite position for point {index}")]
    NonFiniteMove {
        /// The point.
        index: usize,
    },
    /// A pipeline without any stage was run.
    #[error("the pipeline has no stage")]
    NoStages,
    /// The points cannot be split into function segments (e.g. a closed loop whose turning
    /// never exceeds the limit, which no closed polygon has).
    #[error("cannot partition the points: {reason}")]
    Partition {
        /// Why.
        reason: String,
    },
    /// A strategy (or a segment fairer) failed for its own reasons.
    #[error("strategy {strategy} failed: {reason}")]
    Strategy {
        /// The strategy's name.
        strategy: String,
        /// Why.
        reason: String,
    },
}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, Error>;
