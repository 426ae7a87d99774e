//! The crate's one error type.

/// Everything that can go wrong while converting, writing, reading or rebuilding.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A representation could not be built or converted (bad knots, too few points, …).
    #[error(transparent)]
    Representation(#[from] curve_repr::Error),
    /// A fairness measure of a rebuilt curve failed (a vanishing tangent, …).
    #[error(transparent)]
    Fairness(#[from] fairness::Error),
    /// A file that does not follow its format: the format, the 1-based line, and what is wrong.
    #[error("{format} line {line}: {message}")]
    Parse {
        /// "IGES", "STEP" or "DXF".
        format: &'static str,
        /// The line (1-based) where the problem was found.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// Something the format or this crate cannot express (a surface in DXF, a curve in more
    /// than three dimensions, a DXF spline given by fit points only, …).
    #[error("{0}")]
    Unsupported(String),
    /// A setting out of its range.
    #[error("{name} = {value}: {reason}")]
    BadParameter {
        /// The setting's name, as `--set` spells it.
        name: &'static str,
        /// Its value as given.
        value: String,
        /// The allowed range.
        reason: String,
    },
    /// A file name whose extension names no CAD format, or an unknown format name.
    #[error("unknown CAD format `{0}`: use iges (.igs, .iges), step (.step, .stp) or dxf (.dxf)")]
    UnknownFormat(String),
    /// A file that could not be read or written.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The system's message.
        message: String,
    },
}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// A parse error of `format` at `line`. The message is made one line of at most
    /// [`LONGEST_MESSAGE`] characters, since it may echo a stretch of a malformed file (a
    /// CR-only file is one "line").
    pub(crate) fn parse(format: &'static str, line: usize, message: impl Into<String>) -> Self {
        Error::Parse {
            format,
            line,
            message: one_line(&message.into()),
        }
    }
}

/// The most characters of a parse message; the echoed input is cut to fit.
pub(crate) const LONGEST_MESSAGE: usize = 400;

/// `message` with its line breaks and other control characters shown as `\u{..}` escapes and
/// cut to [`LONGEST_MESSAGE`] characters with an ellipsis.
fn one_line(message: &str) -> String {
    let mut out = String::new();
    let mut count = 0;
    for c in message.chars() {
        let shown: Vec<char> = if c.is_control() {
            c.escape_default().collect()
        } else {
            vec![c]
        };
        if count + shown.len() > LONGEST_MESSAGE {
            out.push('…');
            break;
        }
        count += shown.len();
        out.extend(shown);
    }
    out
}
