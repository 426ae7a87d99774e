//! One handler per subcommand; [`dispatch`] picks it.
//!
//! Where the numerical crates plug in: [`measure`] (indicators and criteria: `fair inspect`
//! and the report's `before`/`after`) and [`curve::fair`] / [`surface::fair`] (strategies).
//! Until they are wired they return [`Error::NotAvailable`](crate::Error::NotAvailable).

pub mod curve;
pub mod demo;
pub mod inspect;
pub mod measure;
pub mod methods;
pub mod surface;

use crate::args::{Cli, Command};
use crate::error::Result;

/// Runs the parsed command.
pub fn dispatch(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Curve(args) => curve::run(&args),
        Command::Surface(args) => surface::run(&args),
        Command::Inspect(args) => inspect::run(&args),
        Command::Methods => methods::run(),
        Command::Demo(args) => demo::run(&args),
    }
}

/// Prints a summary line to standard output, or to standard error when standard output
/// carries the points (`-o -`); nothing with `--quiet`.
pub(crate) fn say(quiet: bool, points_on_stdout: bool, text: &str) {
    use std::io::Write;
    if quiet {
        return;
    }
    // A closed pipe is not worth failing for.
    if points_on_stdout {
        let _ = writeln!(std::io::stderr(), "{text}");
    } else {
        let _ = writeln!(std::io::stdout(), "{text}");
    }
}

/// Writes what `-o`, `--report` and `--plot` ask for: the faired points (or grid) as text,
/// the report and the picture. The report text is made (and checked finite) before anything
/// is written, so a failing report leaves no half-written outputs.
pub(crate) fn write_results(
    args: &crate::args::FairArgs,
    report: &crate::report::Report,
    points_text: &str,
    figure: impl FnOnce() -> crate::svg::Figure,
) -> Result<()> {
    let report_text = report.to_json()?;
    if let Some(out) = &args.output {
        crate::output::write_text(out, points_text)?;
    }
    if let Some(path) = &args.report {
        crate::output::write_text(&path.display().to_string(), &report_text)?;
    }
    if let Some(path) = &args.plot {
        figure().write(path)?;
    }
    Ok(())
}
