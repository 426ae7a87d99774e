//! The crate's one error type.
//!
//! argmin reports failures as its own `anyhow`-based error; those are converted here, at the
//! crate's edge, into [`Error::Solver`] holding the message, so no argmin type leaks out.

/// Everything that can go wrong while setting up or running an optimisation.
///
/// Indices count from 0 (the first parameter, vertex or control point).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter of the start point, of a simplex vertex or of a weight law is NaN or infinite.
    #[error("{what} {index} is not finite")]
    NonFinite {
        /// Which kind of value.
        what: &'static str,
        /// Its index.
        index: usize,
    },
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
    /// A setting is outside its allowed range (a zero simplex step, a negative tolerance, ...).
    #[error("invalid setting {name}: {reason}")]
    InvalidSetting {
        /// The setting's name.
        name: &'static str,
        /// Why it is invalid.
        reason: String,
    },
    /// The initial simplex spans fewer than `n` dimensions, so Nelder–Mead could never leave
    /// its affine hull.
    #[error("the initial simplex is degenerate: its {dimension} edge vectors are linearly dependent")]
    DegenerateSimplex {
        /// The number of parameters.
        dimension: usize,
    },
    /// The objective failed (or was not finite) at the start point, so there is nothing to
    /// improve on. Failures elsewhere are not errors: they count as cost +∞.
    #[error("the objective cannot be evaluated at the start point: {reason}")]
    StartFailed {
        /// The objective's own error message, or the non-finite value it returned.
        reason: String,
    },
    /// An objective or criterion failed; user code returns this to report its own failures.
    #[error("objective failed: {message}")]
    Objective {
        /// What went wrong.
        message: String,
    },
    /// argmin reported an error (converted from its `anyhow` error at the crate's edge).
    #[error("solver error: {message}")]
    Solver {
        /// argmin's message.
        message: String,
    },
    /// A curve representation failed (for criteria that re-solve a curve with new weights).
    #[error(transparent)]
    Curve(#[from] curve_repr::Error),
    /// The search was cancelled ([`crate::cancel`]): its token was cancelled or its deadline
    /// passed. No result: the best point so far is dropped.
    #[error(transparent)]
    Cancelled(#[from] crate::cancel::Cancelled),
}

impl Error {
    /// An [`Error::Objective`] carrying the message of any displayable error, for objectives
    /// and criteria written by users: `Err(Error::objective(e))`.
    pub fn objective(error: impl std::fmt::Display) -> Self {
        Error::Objective {
            message: error.to_string(),
        }
    }

    /// Converts argmin's error (an `anyhow::Error`) into ours, keeping only its message.
    pub(crate) fn from_solver(error: argmin::core::Error) -> Self {
        Error::Solver {
            message: format!("{error:#}"),
        }
    }
}

/// The crate's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
