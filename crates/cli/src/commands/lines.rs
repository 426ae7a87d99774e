//! `fair lines`: fair a ship's table of offsets as one hull (the `fair-lines` crate) and
//! write what was asked: the faired table, one CSV per line, the report, the three views and
//! the hull surface. The numerics are all in `fair_lines`; this maps its errors to the
//! command's exit statuses (bad table or setting: 2; a failed fit or CAD export: 1).

use fair_door::error::{Error, Result};

use crate::args::LinesArgs;
use crate::commands::say;

/// The command's error for a `fair_lines` error: the table's file and line are kept.
fn error(e: fair_lines::Error) -> Error {
    match e {
        fair_lines::Error::Table {
            path,
            line: 0,
            message,
        } => Error::Invalid { path, message },
        fair_lines::Error::Table { path, line, message } => Error::Parse { path, line, message },
        fair_lines::Error::Setting { name, message } => Error::Parameter {
            origin: format!("--{name}"),
            message,
        },
        fair_lines::Error::Io { path, message } => Error::Invalid { path, message },
        e @ (fair_lines::Error::Fit(_) | fair_lines::Error::Cad(_)) => Error::Internal {
            message: e.to_string(),
        },
    }
}

/// Runs `fair lines`.
pub(crate) fn run(args: &LinesArgs) -> Result<()> {
    let table = fair_lines::read_table(&args.table).map_err(error)?;
    let settings = fair_lines::Settings {
        step: args.step,
        tolerance: args.tolerance,
        knuckles: args.knuckles.clone(),
    };
    let faired = fair_lines::fair(&table, &settings).map_err(error)?;
    if let Some(path) = &args.output {
        fair_lines::write::write_table(&faired, path).map_err(error)?;
    }
    if let Some(dir) = &args.lines_dir {
        fair_lines::write::write_lines(&faired, dir).map_err(error)?;
    }
    if let Some(path) = &args.report {
        write_text(path, &fair_lines::write::report_json(&faired))?;
    }
    if let Some(path) = &args.plot {
        write_text(path, &fair_lines::write::svg(&faired))?;
    }
    if let Some(path) = &args.hull {
        fair_lines::write::write_hull(&faired, path).map_err(error)?;
    }
    let r = &faired.report;
    say(
        args.quiet,
        false,
        &format!(
            "{}: {} offsets, {} moved more than one step, {} flagged; consistency rms {:.3e} -> {:.3e}",
            args.table.display(),
            r.offsets.len(),
            r.moved_above_one_step,
            r.flagged,
            r.consistency_before.rms,
            r.consistency_after.rms
        ),
    );
    Ok(())
}

fn write_text(path: &std::path::Path, text: &str) -> Result<()> {
    std::fs::write(path, text).map_err(|e| Error::Write {
        path: path.display().to_string(),
        reason: e.to_string(),
    })
}
