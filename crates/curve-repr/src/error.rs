//! The crate's one error type.

use crate::number::Compact;

/// Everything that can go wrong while building or evaluating a representation.
///
/// Indices count from 0, the first data point (or control point, or knot).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Fewer data or control points than the representation needs.
    #[error("too few points: {what} needs at least {needed}, got {got}")]
    TooFewPoints {
        /// What needs them.
        what: &'static str,
        /// The minimum.
        needed: usize,
        /// What was given.
        got: usize,
    },
    /// A sequence that must increase strictly does not (x of a spline function, parameters, knots).
    #[error(
        "{what} must increase strictly: value {} at index {index} follows {}",
        Compact(*value),
        Compact(*previous)
    )]
    NotIncreasing {
        /// Which sequence.
        what: &'static str,
        /// Index of the offending value.
        index: usize,
        /// The value before it.
        previous: f64,
        /// The offending value.
        value: f64,
    },
    /// Two consecutive data points coincide, so a chord-length parameter step would be zero.
    #[error("points {index} and {} coincide", index + 1)]
    RepeatedPoint {
        /// Index of the first of the two points.
        index: usize,
    },
    /// A closed curve given with its first point repeated at the end: the closing segment
    /// P_{n−1} → P_0 would have zero length.
    #[error(
        "the last point (index {last}) repeats the first; a closed curve closes by itself, drop the repeat"
    )]
    ClosingRepeat {
        /// Index of the last point.
        last: usize,
    },
    /// A distance between consecutive points that double precision cannot hold (the
    /// coordinates are too large: their difference overflows).
    #[error("the distance from point {index} to point {} overflows; rescale the coordinates", index + 1)]
    DistanceOverflow {
        /// Index of the first of the two points.
        index: usize,
    },
    /// A coordinate, parameter, weight or knot is NaN or infinite.
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
    /// A knot vector is not a valid clamped, non-decreasing vector for the degree and count.
    #[error("bad knot vector: {reason}")]
    BadKnots {
        /// What is wrong with it.
        reason: String,
    },
    /// A degree the representation does not support.
    #[error("bad degree {degree}: {reason}")]
    BadDegree {
        /// The degree given.
        degree: usize,
        /// Why it is not allowed.
        reason: &'static str,
    },
    /// A weight of a rational curve or surface is not strictly positive.
    #[error("weight {index} is {}, weights must be positive", Compact(*value))]
    BadWeight {
        /// Its index.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// An index (of a data point, a control point) is out of range.
    #[error("index {index} out of range for {len} {what}")]
    IndexOutOfRange {
        /// What is indexed.
        what: &'static str,
        /// The index given.
        index: usize,
        /// How many there are.
        len: usize,
    },
    /// A move that a representation cannot make (e.g. changing x of a spline function's point).
    #[error("invalid move of point {index}: {reason}")]
    InvalidMove {
        /// The point.
        index: usize,
        /// Why.
        reason: &'static str,
    },
    /// A linear system that must be solved is singular or numerically so.
    #[error("singular system while {what}")]
    Singular {
        /// What was being solved.
        what: &'static str,
    },
    /// A grid of surface points is not rectangular.
    #[error("grid row {row} has {got} points, expected {expected}")]
    RaggedGrid {
        /// The row.
        row: usize,
        /// Expected length.
        expected: usize,
        /// Actual length.
        got: usize,
    },
    /// A scalar argument outside its allowed range (a radius, an angle sweep, a knot to insert).
    #[error("{what} is {}: {reason}", Compact(*value))]
    OutOfRange {
        /// Which argument.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The allowed range.
        reason: &'static str,
    },
    /// Two pieces of a piecewise curve do not meet at their common break point (a gap larger
    /// than the continuity tolerance).
    #[error("the pieces before and after break point {index} do not meet: gap {}", Compact(*gap))]
    Discontinuous {
        /// Index of the break point.
        index: usize,
        /// The distance between the end of one piece and the start of the next.
        gap: f64,
    },
    /// Two consecutive grid lines of a surface coincide on average, so the averaged
    /// chord-length knot step between them would be zero.
    #[error("grid lines {index} and {} in the {direction} direction coincide", index + 1)]
    RepeatedGridLine {
        /// `"u"` (lines i and i + 1 of P_ij) or `"v"` (lines j and j + 1).
        direction: &'static str,
        /// Index of the first of the two lines.
        index: usize,
    },
}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, Error>;
