//! The `fair` command: read measured points, fair them, write points, a report and a plot.
//!
//! The command surface is the contract of `docs/CONTRACT.md`; [`main_with`] parses it and
//! dispatches to one handler per subcommand with a [`Catalog`] of methods. The command is a
//! thin adapter over the library's door ([`fair_door`]: fair a curve, fair a surface,
//! measure), which the local server (`fair serve`) and the Python package use too. A program
//! with its own methods is a few lines:
//!
//! ```no_run
//! use fairing::catalog::Catalog;
//! fn main() -> std::process::ExitCode {
//!     let catalog = Catalog::builtin(); // then catalog.register_strategy::<S>(...), ...
//!     fair_cli::main_with(catalog)
//! }
//! ```
//!
//! Split by job, each part importing one way (`.ci/import_cycles.py` checks it): [`input`]
//! reads curves (CSV, JSON, Selig/Lednicer `.dat`, `-` for stdin) and surface grids (CSV
//! `i,j,x,y,z`), naming file and line on every error, and the output module writes results
//! back in the input's format; [`svg`] is a small plotting toolkit and [`plots`] the pictures
//! built with it; the server and its page, the argument parsing and the handlers are private
//! modules.
//!
//! Exit status: 0 on success, 2 on bad input or arguments, 1 on internal failure; every
//! error is one line on standard error, `fair: <file>:<line>: <what is wrong>`. No input
//! makes the command panic, and a panic in a library would still end as one line and exit 1.

pub(crate) mod args;
pub(crate) mod commands;
pub mod input;
pub(crate) mod output;
pub mod plots;
pub(crate) mod progress;
pub(crate) mod serve;
pub mod svg;

pub use fair_door::{Error, Result};

use clap::Parser;
use fairing::catalog::Catalog;
use std::ffi::OsString;
use std::io::Write;
use std::process::ExitCode;

/// Runs the command with the built-in methods ([`Catalog::builtin`]) and the process
/// arguments; see [`main_with`].
pub fn run() -> ExitCode {
    main_with(Catalog::builtin())
}

/// Runs the command with the methods of `catalog` and the process arguments, and returns its
/// exit status: `fair_cli::main_with(catalog)` is the whole `main` of a binary that adds
/// methods, criteria or indicators to the built-in ones.
///
/// Installs a quiet panic hook first, so that a panic anywhere below ends as one line on
/// standard error (`fair: internal error: ...`) and exit status 1, never a backtrace.
pub fn main_with(catalog: Catalog) -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        let message = panic_message(info.payload());
        let place = info
            .location()
            .map(|l| format!(" ({}:{})", l.file(), l.line()))
            .unwrap_or_default();
        if let Ok(mut last) = LAST_PANIC.lock() {
            *last = Some(format!("{message}{place}"));
        }
    }));
    run_from_with(&catalog, std::env::args_os())
}

/// The running binary's name (its first argument's file stem, `fair` when there is none):
/// a user's binary built on [`main_with`] speaks in its own name.
static PROGRAM: std::sync::OnceLock<String> = std::sync::OnceLock::new();

/// The name messages start with and point at for help: the running binary's file stem,
/// `fair` by default.
pub fn program_name() -> &'static str {
    PROGRAM.get_or_init(|| stem_of(std::env::args_os().next()))
}

fn stem_of(first: Option<OsString>) -> String {
    first
        .as_deref()
        .map(std::path::Path::new)
        .and_then(|p| p.file_stem())
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .unwrap_or("fair")
        .to_owned()
}

static LAST_PANIC: std::sync::Mutex<Option<String>> = std::sync::Mutex::new(None);

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown failure".to_string()
    }
}

/// Runs the command with the built-in methods and the given arguments (the first is the
/// program name).
pub fn run_from<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    run_from_with(&Catalog::builtin(), args)
}

/// Runs the command with the methods of `catalog` and the given arguments (the first is the
/// program name).
pub fn run_from_with<I, T>(catalog: &Catalog, args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let args: Vec<OsString> = args.into_iter().map(Into::into).collect();
    let _ = PROGRAM.set(stem_of(args.first().cloned()));
    let cli = match args::Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => return usage(e),
    };
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| commands::dispatch(catalog, cli)))
        .unwrap_or_else(|payload| {
            let recorded = LAST_PANIC.lock().ok().and_then(|mut last| last.take());
            Err(Error::Internal {
                message: recorded.unwrap_or_else(|| panic_message(payload.as_ref())),
            })
        });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "{}: {}", program_name(), e.one_line());
            ExitCode::from(e.exit_code())
        }
    }
}

/// Help and version go to standard output with status 0; every other clap error becomes one
/// line on standard error with status 2.
fn usage(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = write!(std::io::stdout(), "{}", e.render());
            ExitCode::SUCCESS
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand | ErrorKind::MissingSubcommand => {
            let _ = writeln!(
                std::io::stderr(),
                "{0}: a subcommand is required: curve, surface, inspect, methods, demo or serve (see `{0} --help`)",
                program_name()
            );
            ExitCode::from(2)
        }
        _ => {
            let error = Error::Usage {
                message: usage_line(&e.render().to_string()),
            };
            let _ = writeln!(std::io::stderr(), "{}: {}", program_name(), error.one_line());
            ExitCode::from(error.exit_code())
        }
    }
}

/// clap's message without its `error: ` prefix on one line, plus where to look for help. A
/// message that ends in `:` continues on the next lines (the arguments not provided): they
/// are joined, so that the line names what is missing.
fn usage_line(rendered: &str) -> String {
    let mut lines = rendered.lines().map(str::trim).skip_while(|l| l.is_empty());
    let first = lines.next().unwrap_or("invalid arguments");
    let mut message = first
        .strip_prefix("error:")
        .map(str::trim)
        .unwrap_or(first)
        .to_string();
    if message.ends_with(':') {
        let rest: Vec<&str> = lines
            .take_while(|l| !l.is_empty() && !l.starts_with("Usage:"))
            .collect();
        if !rest.is_empty() {
            message = format!("{} {}", message, rest.join(", "));
        }
    }
    format!("{message} (see `{} --help`)", program_name())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Messages speak in the running binary's name: its first argument's file stem.
    #[test]
    fn the_program_name_is_the_binary_stem() {
        assert_eq!(stem_of(Some("/usr/local/bin/my-fair.exe".into())), "my-fair");
        assert_eq!(stem_of(Some("laplacian-fair".into())), "laplacian-fair");
        assert_eq!(stem_of(Some("".into())), "fair");
        assert_eq!(stem_of(None), "fair");
    }

    #[test]
    fn usage_line_is_one_line() {
        let e = args::Cli::try_parse_from(["fair", "frobnicate"]).unwrap_err();
        let line = usage_line(&e.render().to_string());
        assert!(!line.contains('\n'));
        assert!(line.starts_with("unrecognized subcommand 'frobnicate'"), "{line}");
    }

    #[test]
    fn a_missing_argument_is_named() {
        let e = args::Cli::try_parse_from(["fair", "curve"]).unwrap_err();
        let line = usage_line(&e.render().to_string());
        assert!(!line.contains('\n'));
        assert!(line.contains("<INPUT>"), "{line}");
    }

    #[test]
    fn a_negative_tolerance_is_a_clear_message() {
        let e = args::Cli::try_parse_from(["fair", "curve", "a.csv", "--tolerance", "-1"]).unwrap_err();
        let line = usage_line(&e.render().to_string());
        assert!(line.contains("greater than 0"), "{line}");
        assert!(!line.contains("unexpected argument"), "{line}");
    }
}
