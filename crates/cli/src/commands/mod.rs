//! One handler per subcommand; [`dispatch`] picks it.
//!
//! Where the numerical crates plug in: [`measure`] (indicators: `fair inspect` and the
//! report's `before`/`after`) and the catalogue (methods and criteria), which every handler
//! is given.

pub(crate) mod curve;
pub(crate) mod demo;
pub(crate) mod inspect;
pub(crate) mod lines;
pub(crate) mod methods;
pub(crate) mod surface;

use fairing::catalog::Catalog;

use crate::args::{Cli, Command};
use fair_door::error::{Error, Result};

/// Runs the parsed command with the methods of `catalog`.
pub(crate) fn dispatch(catalog: &Catalog, cli: Cli) -> Result<()> {
    match cli.command {
        Command::Curve(args) => curve::run(catalog, &args),
        Command::Surface(args) => surface::run(catalog, &args),
        Command::Inspect(args) => inspect::run(catalog, &args),
        Command::Lines(args) => lines::run(&args),
        Command::Methods => methods::run(catalog),
        Command::Demo(args) => demo::run(catalog, &args),
        Command::Serve(args) => crate::serve::run(catalog, &args),
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
/// Whether `path` (not `-`) can be a file: not a directory, in a directory that exists.
/// The write itself can still fail (permissions, a full disk) and says so then. O(1).
fn check_writable(path: &str) -> Result<()> {
    if path == "-" {
        return Ok(());
    }
    let target = std::path::Path::new(path);
    let problem = if target.is_dir() {
        Some("it is a directory".to_string())
    } else {
        match target.parent().filter(|p| !p.as_os_str().is_empty()) {
            Some(dir) if !dir.is_dir() => Some(format!("no directory {}", dir.display())),
            _ => None,
        }
    };
    match problem {
        Some(reason) => Err(Error::Write {
            path: path.into(),
            reason,
        }),
        None => Ok(()),
    }
}

pub(crate) fn write_results(
    args: &crate::args::FairArgs,
    report: &fair_door::report::Report,
    points_text: &str,
    figure: impl FnOnce() -> crate::svg::Figure,
) -> Result<()> {
    // The report is checked even when not written: a non-finite measure is an error either way.
    report.check_finite()?;
    // Every target checked before the first is written, so that a bad --report or --plot path
    // does not leave a fresh output file behind an exit status of 2.
    let targets = [
        args.output.clone(),
        args.report.as_ref().map(|p| p.display().to_string()),
        args.plot.as_ref().map(|p| p.display().to_string()),
    ];
    for path in targets.iter().flatten() {
        check_writable(path)?;
    }
    if let Some(out) = &args.output {
        crate::output::write_text(out, points_text)?;
    }
    if let Some(path) = &args.report {
        report.write_json(&path.display().to_string())?;
    }
    if let Some(path) = &args.plot {
        figure().write(path)?;
    }
    Ok(())
}
