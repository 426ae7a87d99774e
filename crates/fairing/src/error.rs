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
    /// An error of a fairness indicator or criterion (so that a strategy that evaluates one
    /// can use `?`).
    #[error(transparent)]
    Fairness(#[from] fairness::Error),
    /// An error of the optimisation crate (the NURBS weight search); its cancellation
    /// becomes [`Error::Cancelled`].
    #[error(transparent)]
    Optim(optim::Error),
    /// The run was cancelled ([`optim::cancel`]): the token of the scope it ran in was
    /// cancelled or its deadline passed. Not a failure of the data or the method: there is no
    /// result because the caller stopped waiting for it.
    #[error("{}", optim::cancel::Cancelled)]
    Cancelled,
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
    /// A parameter's value that a method refuses, said where only the parameter's name is
    /// known (a method's check); the catalogue adds where it was given ([`Error::Parameter`]).
    #[error("`{name}`: {message}")]
    BadValue {
        /// The parameter's name (kebab-case).
        name: String,
        /// What is wrong with its value.
        message: String,
    },
    /// A method name the catalogue does not know for this kind of input.
    #[error("unknown {kind} method `{name}` (known: {known})")]
    UnknownMethod {
        /// The name given.
        name: String,
        /// `curve` or `surface`.
        kind: &'static str,
        /// The known names, comma-separated.
        known: String,
    },
    /// A method the catalogue has for the other kind of input: a surface method asked to
    /// fair a curve, or a curve method a surface.
    #[error("`{name}` is a {fairs} method and the input is a {kind} (the {kind} methods: {known})")]
    WrongKind {
        /// The name given.
        name: String,
        /// The input's kind: `curve` or `surface`.
        kind: &'static str,
        /// What the method fairs: `surface` or `curve`.
        fairs: &'static str,
        /// The methods of the input's kind, comma-separated.
        known: String,
    },
    /// A name (a parameter of a method, a criterion, an indicator) the catalogue does not know.
    #[error("{origin}: `{name}` is not {what} (known: {known})")]
    UnknownName {
        /// Where the name was given: `--set`, `config.toml:3`, `config.toml:9 (stage 2)`.
        origin: String,
        /// What kind of name was expected, with its owner: "a parameter of `batten`",
        /// "a registered criterion".
        what: String,
        /// The name given.
        name: String,
        /// The known names, comma-separated (or a sentence when there are none).
        known: String,
    },
    /// A parameter value that cannot be read or is out of range, with where it was given.
    #[error("{origin}: {message}")]
    Parameter {
        /// `--set`, `config.toml:3`, ...
        origin: String,
        /// What is wrong.
        message: String,
    },
    /// A parameter's value outside the range its settings declare (the schema's `minimum`,
    /// `maximum` and exclusive bounds), with where it was given.
    #[error("{origin}: `{method}`: {setting} = {value} is out of range: {allowed}")]
    OutOfRange {
        /// `--set`, `config.toml:3`, ...
        origin: String,
        /// The method whose parameter it is.
        method: String,
        /// The parameter's name (kebab-case).
        setting: String,
        /// The value as given (at most a few dozen characters of it).
        value: String,
        /// The range in words: `an integer ≥ 1`, `a number in (0, 1]`.
        allowed: String,
    },
    /// A config file (TOML or JSON) that is malformed, with the file and line.
    #[error("{origin}: {message}")]
    Config {
        /// `config.toml:LINE`, or the file name when the line is unknown.
        origin: String,
        /// What is wrong.
        message: String,
    },
    /// A coordinate too large for the arithmetic of fairing (see
    /// [`LARGEST_COORDINATE`](crate::catalog::LARGEST_COORDINATE)), or not finite. Said before
    /// any method runs.
    #[error(
        "{what} {index} has the coordinate {value:e}, beyond ±1e150: the squares fairing forms would overflow; give the coordinates in a larger unit"
    )]
    CoordinateRange {
        /// `point` or `grid point`.
        what: &'static str,
        /// The point's index, from 0.
        index: usize,
        /// The coordinate.
        value: f64,
    },
    /// A method refuses what it was asked to do (an end clamp it cannot hold, bad points it
    /// does not take, a kind or dimension of curve it does not fair). Said before it runs.
    #[error("`{method}` {reason}")]
    Refused {
        /// The method's name.
        method: String,
        /// What is refused (the command names the option from it).
        what: Refusal,
        /// Why, as the rest of the sentence after the method's name.
        reason: String,
    },
}

impl Error {
    /// `method` refuses `what`, the rest of the sentence after its name being `reason`
    /// ([`Error::Refused`]): the typed form of a refusal, which a caller matches on `what`.
    pub fn refused(method: &str, what: Refusal, reason: impl Into<String>) -> Self {
        Error::Refused {
            method: method.to_owned(),
            what,
            reason: reason.into(),
        }
    }
}

impl From<optim::Error> for Error {
    fn from(error: optim::Error) -> Self {
        match error {
            optim::Error::Cancelled(_) => Error::Cancelled,
            other => Error::Optim(other),
        }
    }
}

impl From<optim::cancel::Cancelled> for Error {
    fn from(_: optim::cancel::Cancelled) -> Self {
        Error::Cancelled
    }
}

/// What a method refuses ([`Error::Refused`]); the command names the option from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Refusal {
    /// An end clamp (`--clamp-ends`).
    EndClamp,
    /// Bad points (`--points`).
    BadPoints,
    /// Fixed points (`--fixed`).
    Fixed,
    /// A tolerance band (`--tolerance`).
    Tolerance,
    /// Restraining radii (a program's [`Constraints::with_restraining_radii`](crate::Constraints::with_restraining_radii)).
    Radii,
    /// A kind of curve (function or parametric, `--kind`).
    Kind,
    /// A dimension of the points (planar or spatial).
    Dimension,
    /// A closed curve.
    Closed,
    /// A combination of parameters.
    Parameters,
    /// A surface edge held to a neighbour (`--join`).
    Join,
}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, Error>;
