//! The crate's one error type.

/// What went wrong reading, fairing or writing a lines plan.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The system's message.
        message: String,
    },
    /// A file is not a table of offsets; `line` is the file's line (1 = the header).
    #[error("{path}:{line}: {message}")]
    Table {
        /// The file.
        path: String,
        /// The file's line number (1-based; 0 when the whole file is meant).
        line: usize,
        /// What is wrong there.
        message: String,
    },
    /// A setting is out of range.
    #[error("bad setting {name}: {message}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// Why it is refused.
        message: String,
    },
    /// The hull could not be fitted (too few offsets for a surface, a singular system).
    #[error("cannot fair: {0}")]
    Fit(String),
    /// Writing the CAD file failed.
    #[error("CAD: {0}")]
    Cad(#[from] cad::Error),
}

/// The crate's result.
pub type Result<T> = std::result::Result<T, Error>;

pub(crate) fn io(path: &std::path::Path, e: std::io::Error) -> Error {
    Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}
