//! The crate's one error type.

use curve_repr::number::Compact;

/// Everything that can go wrong while measuring fairness.
///
/// Indices count from 0, the first data point (or knot). Errors of the representation being
/// measured are wrapped as [`Error::Curve`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// An error of the representation (construction or evaluation).
    #[error(transparent)]
    Curve(#[from] curve_repr::Error),
    /// Two inputs that must have related lengths do not.
    #[error("length mismatch: {what} expected {expected}, got {got}")]
    LengthMismatch {
        /// Which input.
        what: &'static str,
        /// The length it must have.
        expected: usize,
        /// The length it has.
        got: usize,
    },
    /// Fewer points (or knots) than the indicator needs.
    #[error("too few points: {what} needs at least {needed}, got {got}")]
    TooFewPoints {
        /// What needs them.
        what: &'static str,
        /// The minimum.
        needed: usize,
        /// What was given.
        got: usize,
    },
    /// An input value is NaN or infinite.
    #[error("{what} {index} is not finite")]
    NonFiniteInput {
        /// Which kind of value.
        what: &'static str,
        /// Its index.
        index: usize,
    },
    /// A computed quantity is NaN or infinite (e.g. curvature where the tangent vanishes).
    #[error("{what} is not finite at parameter {}", Compact(*parameter))]
    NonFinite {
        /// The quantity.
        what: &'static str,
        /// Where it was evaluated.
        parameter: f64,
    },
    /// Adaptive quadrature stopped before reaching its tolerance.
    #[error(
        "quadrature of {what} did not converge: estimate {}, error {} above tolerance {} ({reason})",
        Compact(*estimate),
        Compact(*error_estimate),
        Compact(*tolerance)
    )]
    NoConvergence {
        /// The integral.
        what: &'static str,
        /// The last estimate of the integral.
        estimate: f64,
        /// Its estimated absolute error.
        error_estimate: f64,
        /// The absolute tolerance it had to meet.
        tolerance: f64,
        /// Which limit stopped it.
        reason: &'static str,
    },
    /// A setting out of its allowed range (a quadrature order, a tolerance).
    #[error("invalid setting {what}: {reason}")]
    InvalidSetting {
        /// The setting.
        what: &'static str,
        /// Why it is not allowed.
        reason: &'static str,
    },
}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, Error>;
