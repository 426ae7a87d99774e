//! The `fair` command: read measured points, fair them, write points, a report and a plot.
//!
//! The command surface is DESIGN.md's "The `fair` command" ([`args`]); [`run`] parses it and
//! dispatches to one handler per subcommand ([`commands`]). Around them:
//! - [`input`] reads curves (CSV, JSON, Selig/Lednicer `.dat`, `-` for stdin) and surface
//!   grids (CSV `i,j,x,y,z`), naming file and line on every error; [`output`] writes results
//!   back in the input's format;
//! - [`report`] is the JSON report; [`svg`] a small plotting toolkit and [`plots`] the pictures
//!   built with it;
//! - [`registry`] lists the methods and their parameters, [`parameters`] reads `--set` and
//!   `--config`, [`config`] reads config files (parameters, constraints, pipelines of stages), [`constraints`] checks `--fixed`/`--points`/`--tolerance`/`--clamp-ends`,
//!   [`kind`] resolves `--kind`;
//! - [`serve`] is `fair serve`, the local web page and its JSON API over the same code.
//!
//! The numerical crates plug in at three seams: [`commands::measure`] (indicators),
//! [`commands::curve::fair`] and [`commands::surface::fair`] (strategies).
//!
//! Exit status: 0 on success, 2 on bad input or arguments, 1 on internal failure; every
//! error is one line on standard error, `fair: <file>:<line>: <what is wrong>`. No input
//! makes the command panic, and a panic in a library would still end as one line and exit 1.

pub mod args;
pub mod commands;
pub mod config;
pub mod constraints;
pub mod error;
pub mod highlight;
pub mod input;
pub mod kind;
pub mod output;
pub mod parameters;
pub mod plots;
pub mod progress;
pub mod registry;
pub mod report;
pub mod serve;
pub mod svg;

pub use error::{Error, Result};

use clap::Parser;
use std::ffi::OsString;
use std::io::Write;
use std::process::ExitCode;

/// Runs the command with the process arguments and returns its exit status.
///
/// Installs a quiet panic hook first, so that a panic anywhere below ends as one line on
/// standard error (`fair: internal error: ...`) and exit status 1, never a backtrace.
pub fn run() -> ExitCode {
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
    run_from(std::env::args_os())
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

/// Runs the command with the given arguments (the first is the program name).
pub fn run_from<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match args::Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => return usage(e),
    };
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| commands::dispatch(cli)))
        .unwrap_or_else(|payload| {
            let recorded = LAST_PANIC.lock().ok().and_then(|mut last| last.take());
            Err(Error::Internal {
                message: recorded.unwrap_or_else(|| panic_message(payload.as_ref())),
            })
        });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "fair: {}", e.one_line());
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
                "fair: a subcommand is required: curve, surface, inspect, methods, demo or serve (see `fair --help`)"
            );
            ExitCode::from(2)
        }
        _ => {
            let error = Error::Usage {
                message: usage_line(&e.render().to_string()),
            };
            let _ = writeln!(std::io::stderr(), "fair: {}", error.one_line());
            ExitCode::from(error.exit_code())
        }
    }
}

/// clap's first message line without its `error: ` prefix, plus where to look for help.
fn usage_line(rendered: &str) -> String {
    let first = rendered
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .unwrap_or("invalid arguments");
    let first = first.strip_prefix("error:").map(str::trim).unwrap_or(first);
    format!("{first} (see `fair --help`)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn usage_line_is_one_line() {
        let e = args::Cli::try_parse_from(["fair", "frobnicate"]).unwrap_err();
        let line = usage_line(&e.render().to_string());
        assert!(!line.contains('\n'));
        assert!(line.starts_with("unrecognized subcommand 'frobnicate'"), "{line}");
    }
}
