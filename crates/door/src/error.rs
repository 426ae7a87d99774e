//! The one error type of the door and its front ends, and the exit status each error maps to.
//!
//! Every message is one line in the style `<file>:<line>: <what is wrong>` (the line when it is
//! known); the command prefixes it with `fair: `. Options are named as the command spells
//! them (`--fixed`); other front ends rename them for their own users.

/// Everything fairing, measuring or exporting through the door (and the front ends' reading
/// and writing) can fail on.
///
/// Point indices count from 0, the first data point; line numbers count from 1.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A command-line usage error (unknown subcommand, bad option value), already one line.
    #[error("{message}")]
    Usage {
        /// clap's first message line, without its `error: ` prefix.
        message: String,
    },
    /// An input file cannot be opened or read (missing file, a directory, no permission).
    #[error("{path}: cannot read: {reason}")]
    Read {
        /// The path as the user gave it.
        path: String,
        /// The operating system's reason.
        reason: String,
    },
    /// The input holds no points at all.
    #[error("{path}: no points: {reason}")]
    Empty {
        /// The input file.
        path: String,
        /// Why nothing was found (empty file, header only, ...).
        reason: String,
    },
    /// A syntax or value error at a known line of an input file.
    #[error("{path}:{line}: {message}")]
    Parse {
        /// The input file.
        path: String,
        /// The line, from 1.
        line: usize,
        /// What is wrong there.
        message: String,
    },
    /// An input error that belongs to the whole file rather than to one line (a ragged grid).
    #[error("{path}: {message}")]
    Invalid {
        /// The input file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// Fewer points than the method or indicator needs.
    #[error("{path}: {found} point{}, {what} needs at least {needed}", plural(*.found))]
    TooFewPoints {
        /// The input file.
        path: String,
        /// How many points were read.
        found: usize,
        /// The minimum.
        needed: usize,
        /// What needs them (a method, an indicator, "a curve").
        what: String,
    },
    /// A method name that the catalogue does not know for this kind of input.
    #[error("unknown {kind} method `{name}` (known: {known}; `fair methods` lists them)")]
    UnknownMethod {
        /// The name given.
        name: String,
        /// `curve` or `surface`.
        kind: &'static str,
        /// The known names, comma-separated.
        known: String,
    },
    /// A `--set NAME=VALUE` or config-file parameter that the method does not have or cannot parse.
    #[error("{origin}: {message}")]
    Parameter {
        /// Where the parameter came from: `--set`, or `config.toml:3`.
        origin: String,
        /// What is wrong.
        message: String,
    },
    /// An option whose value does not fit the input (an index past the last point, say).
    #[error("{option}: {message}")]
    Argument {
        /// The option, e.g. `--fixed`.
        option: &'static str,
        /// What is wrong.
        message: String,
    },
    /// A method that does not apply to this input (a planar-only method on 3D points).
    #[error("{path}: {message}")]
    NotApplicable {
        /// The input file.
        path: String,
        /// Why.
        message: String,
    },
    /// A known method (or indicator) whose numerical code is not wired into the command yet.
    #[error("{what} is not available yet")]
    NotAvailable {
        /// The method or piece, e.g. "method `batten`".
        what: String,
    },
    /// A representation cannot be built from the points (repeated points, x not increasing).
    #[error("{path}: {source}")]
    Representation {
        /// The input file.
        path: String,
        /// The representation crate's error.
        source: curve_repr::Error,
    },
    /// An output, report or plot file cannot be written.
    #[error("{path}: cannot write: {reason}")]
    Write {
        /// The output path.
        path: String,
        /// The operating system's reason.
        reason: String,
    },
    /// A value about to be written is NaN or infinite: the computation failed.
    #[error("{what}: value {index} is not finite; nothing written")]
    NonFiniteOutput {
        /// What was being written (`output`, `report`).
        what: String,
        /// Index of the first offending value.
        index: usize,
    },
    /// Some curves of a batch failed; each has its own report line with its error.
    #[error("{failed} of {total} inputs failed (each has an `error` line in the batch report)")]
    Batch {
        /// How many inputs failed.
        failed: usize,
        /// How many inputs the batch had.
        total: usize,
        /// The exit status the failures call for: 2 when every failure was the user's to fix,
        /// else 1.
        status: u8,
    },
    /// A failure of the command itself (a bug, a caught panic, a failed computation).
    #[error("internal error: {message}")]
    Internal {
        /// What failed.
        message: String,
    },
    /// The work was cancelled by its caller ([`optim::cancel`]): its deadline passed or its
    /// client left. Only a front end that cancels (the server) sees it.
    #[error("{}", optim::cancel::Cancelled)]
    Cancelled,
}

impl Error {
    /// The process exit status for this error: 2 for bad input, arguments, unknown methods and
    /// missing or unwritable files (the user can fix them), 1 for internal failures (including
    /// methods not available yet and non-finite results).
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Usage { .. }
            | Error::Read { .. }
            | Error::Empty { .. }
            | Error::Parse { .. }
            | Error::Invalid { .. }
            | Error::TooFewPoints { .. }
            | Error::UnknownMethod { .. }
            | Error::Parameter { .. }
            | Error::Argument { .. }
            | Error::Representation { .. }
            | Error::NotApplicable { .. }
            | Error::Write { .. } => 2,
            Error::Batch { status, .. } => *status,
            Error::NotAvailable { .. }
            | Error::NonFiniteOutput { .. }
            | Error::Internal { .. }
            | Error::Cancelled => 1,
        }
    }

    /// The message on one line: any newline inside a wrapped message becomes `; `.
    pub fn one_line(&self) -> String {
        let text = self.to_string();
        let parts: Vec<&str> = text.lines().map(str::trim).filter(|l| !l.is_empty()).collect();
        parts.join("; ")
    }
}

impl Error {
    /// The library's error as the command's, naming `file` where the points are at fault:
    /// unknown names and bad values at their origin (`--set`, `file.toml:LINE`); a method's
    /// refusal as the option it refuses (`--clamp-ends`, `--points`, `--kind`); errors of the
    /// representations and strategies on the data name the file (exit status 2); a result
    /// that breaks a constraint is a bug (exit status 1).
    pub fn from_fairing(error: fairing::Error, file: &str) -> Error {
        use fairing::{Error as F, Refusal};
        match error {
            F::Repr(source)
            | F::Fairness(fairness::Error::Curve(source))
            | F::Optim(optim::Error::Curve(source)) => Error::Representation {
                path: file.to_string(),
                source,
            },
            F::Cancelled | F::Optim(optim::Error::Cancelled(_)) => Error::Cancelled,
            F::UnknownMethod { name, kind, known } => Error::UnknownMethod { name, kind, known },
            F::WrongKind { .. } => Error::Argument {
                option: "--method",
                message: error.to_string(),
            },
            F::UnknownName {
                origin,
                what,
                name,
                known,
            } => Error::Parameter {
                origin,
                message: format!("`{name}` is not {what} (known: {known})"),
            },
            F::Parameter { origin, message } | F::Config { origin, message } => {
                Error::Parameter { origin, message }
            }
            F::OutOfRange {
                origin,
                method,
                setting,
                value,
                allowed,
            } => Error::Parameter {
                origin,
                message: format!("`{method}`: {setting} = {value} is out of range: {allowed}"),
            },
            F::Refused {
                what: Refusal::Dimension | Refusal::Closed,
                ..
            } => Error::NotApplicable {
                path: file.to_string(),
                message: error.to_string(),
            },
            F::Refused { what, .. } => {
                let option = match what {
                    Refusal::EndClamp => "--clamp-ends",
                    Refusal::BadPoints => "--points",
                    Refusal::Fixed => "--fixed",
                    Refusal::Tolerance => "--tolerance",
                    Refusal::Kind => "--kind",
                    Refusal::Join => "--join",
                    _ => "--set",
                };
                Error::Argument {
                    option,
                    message: error.to_string(),
                }
            }
            F::ConstraintUnsupported { .. } => Error::Argument {
                option: "--clamp-ends",
                message: error.to_string(),
            },
            F::BadParameter { .. } | F::BadValue { .. } | F::BadConstraint { .. } => Error::Parameter {
                origin: "--set".into(),
                message: error.to_string(),
            },
            F::ConstraintViolated { .. } => Error::Internal {
                message: error.to_string(),
            },
            other => Error::Invalid {
                path: file.to_string(),
                message: other.to_string(),
            },
        }
    }
}

impl Error {
    /// The error of an output that could not be written ([`cad::atomic`]): the path as given
    /// (`<stdout>` for standard output) and the system's reason. Exit status 2.
    pub fn from_write(e: &cad::atomic::WriteError) -> Self {
        Error::Write {
            path: e.target.name(),
            reason: io_reason(&e.error),
        }
    }
}

/// The operating system's reason for an I/O error, without the `(os error N)` suffix.
pub fn io_reason(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file or directory".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        _ => {
            let text = e.to_string();
            match text.find(" (os error") {
                Some(cut) => text[..cut].to_string(),
                None => text,
            }
        }
    }
}

/// `""` for one, `"s"` otherwise.
fn plural(count: usize) -> &'static str {
    if count == 1 {
        ""
    } else {
        "s"
    }
}

/// The crate's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_error_names_file_and_line() {
        let e = Error::Parse {
            path: "a.csv".into(),
            line: 3,
            message: "bad".into(),
        };
        assert_eq!(e.to_string(), "a.csv:3: bad");
        assert_eq!(e.exit_code(), 2);
    }

    #[test]
    fn internal_failures_exit_one() {
        assert_eq!(
            Error::NotAvailable {
                what: "method `batten`".into()
            }
            .exit_code(),
            1
        );
        assert_eq!(Error::Internal { message: "x".into() }.exit_code(), 1);
    }

    #[test]
    fn too_few_points_singular() {
        let e = Error::TooFewPoints {
            path: "p.csv".into(),
            found: 1,
            needed: 3,
            what: "a curve".into(),
        };
        assert_eq!(e.to_string(), "p.csv: 1 point, a curve needs at least 3");
    }

    #[test]
    fn one_line_joins_lines() {
        let e = Error::Internal {
            message: "a\nb\n".into(),
        };
        assert_eq!(e.one_line(), "internal error: a; b");
    }
}
