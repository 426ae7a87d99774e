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

/// Whether `path` (not `-`) can be a file: not a directory, in a directory that exists.
/// The write itself can still fail (permissions, a full disk) and says so then. O(1).
fn check_writable(path: &std::path::Path) -> Result<()> {
    if path.as_os_str() == "-" {
        return Ok(());
    }
    let problem = if path.is_dir() {
        Some("it is a directory".to_string())
    } else {
        match path.parent().filter(|p| !p.as_os_str().is_empty()) {
            Some(dir) if !dir.is_dir() => Some(format!("no directory {}", dir.display())),
            _ => None,
        }
    };
    match problem {
        Some(reason) => Err(Error::Write {
            path: path.display().to_string(),
            reason,
        }),
        None => Ok(()),
    }
}

/// Checks a command line's outputs before anything runs: each can be a file
/// ([`check_writable`]), and no two name one file (`-o x.csv --report ./x.csv`, or a
/// symbolic link to it; `-` twice is standard output twice). `outputs` are (flag, target)
/// pairs, `None` for an output not asked for. Writing over the input is allowed (the output
/// replaces it only when complete). Exit status 2.
pub(crate) fn check_outputs(outputs: &[(&str, Option<cad::atomic::Target>)]) -> Result<()> {
    for target in outputs.iter().filter_map(|(_, target)| target.as_ref()) {
        if let cad::atomic::Target::File(path) = target {
            check_writable(path)?;
        }
    }
    let given = outputs
        .iter()
        .filter_map(|(flag, target)| target.clone().map(|t| (*flag, t)));
    match cad::atomic::find_clash(given) {
        Some(clash) => Err(Error::Write {
            path: clash.path,
            reason: format!(
                "{} and {} both name it (one would overwrite the other); give them different files",
                clash.first, clash.second
            ),
        }),
        None => Ok(()),
    }
}

/// The output of `path` for [`cad::atomic`] (`-`: standard output), for the flags that
/// take `-` (`-o` and `--report` of `fair curve`, `fair surface`, `fair inspect`).
pub(crate) fn target(path: impl AsRef<std::path::Path>) -> cad::atomic::Target {
    cad::atomic::Target::from_arg(path)
}

/// The output of `path` for [`cad::atomic`], a file even when named `-` (`--plot`, `fair
/// lines`' outputs).
pub(crate) fn file(path: impl AsRef<std::path::Path>) -> cad::atomic::Target {
    cad::atomic::Target::File(path.as_ref().to_path_buf())
}

/// Writes what `-o`, `--report` and `--plot` ask for: the faired points (or grid, or CAD
/// file) as text, the report and the picture, all or none ([`cad::atomic::Outputs`]): each to
/// a temporary file beside its target, renamed over the targets only when every one was
/// written. The report is checked finite before anything is written.
pub(crate) fn write_results(
    args: &crate::args::FairArgs,
    report: &fair_door::report::Report,
    points_text: &str,
    figure: impl FnOnce() -> crate::svg::Figure,
) -> Result<()> {
    // The report is checked even when not written: a non-finite measure is an error either way.
    report.check_finite()?;
    let mut outputs = cad::atomic::Outputs::new();
    if let Some(out) = &args.output {
        outputs.add_text(target(out), points_text);
    }
    if let Some(path) = &args.report {
        outputs.add(target(path), |w| report.write_json_to(w));
    }
    if let Some(path) = &args.plot {
        outputs.add(file(path), move |w| w.write_all(figure().to_svg().as_bytes()));
    }
    outputs.commit().map_err(|e| Error::from_write(&e))
}
