//! `fair lines`: fair a ship's table of offsets as one hull (the `fair-lines` crate) and
//! write what was asked: the faired table, one CSV per line, the report, the three views and
//! the hull surface. The numerics are all in `fair_lines`; this maps its errors to the
//! command's exit statuses (bad table or setting: 2; a failed fit or CAD export: 1).

use fair_door::error::{Error, Result};

use crate::args::LinesArgs;
use crate::commands::{check_outputs, file, say};

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

/// Runs `fair lines`: every output made in memory, then written all or none
/// ([`cad::atomic::Outputs`]; a `--lines-dir` created for them is removed again when the
/// writing fails).
pub(crate) fn run(args: &LinesArgs) -> Result<()> {
    check_outputs(&[
        ("-o", args.output.as_ref().map(file)),
        ("--report", args.report.as_ref().map(file)),
        ("--plot", args.plot.as_ref().map(file)),
        ("--hull", args.hull.as_ref().map(file)),
    ])?;
    let table = fair_lines::read_table(&args.table).map_err(error)?;
    let settings = fair_lines::Settings {
        step: args.step,
        tolerance: args.tolerance,
        knuckles: args.knuckles.clone(),
    };
    let faired = fair_lines::fair(&table, &settings).map_err(error)?;
    let mut outputs = cad::atomic::Outputs::new();
    if let Some(path) = &args.output {
        outputs.add_text(file(path), fair_lines::write::table_text(&faired));
    }
    if let Some(path) = &args.report {
        outputs.add_text(file(path), fair_lines::write::report_json(&faired));
    }
    if let Some(path) = &args.plot {
        outputs.add_text(file(path), fair_lines::write::svg(&faired));
    }
    if let Some(path) = &args.hull {
        let text = fair_lines::write::hull_text(&faired, path).map_err(error)?;
        outputs.add_text(file(path), text);
    }
    let mut created = None;
    if let Some(dir) = &args.lines_dir {
        if !dir.is_dir() {
            std::fs::create_dir_all(dir).map_err(|e| Error::Write {
                path: dir.display().to_string(),
                reason: fair_door::error::io_reason(&e),
            })?;
            created = Some(dir);
        }
        for (name, text) in fair_lines::write::lines_files(&faired) {
            outputs.add_text(cad::atomic::Target::File(dir.join(name)), text);
        }
    }
    if let Err(e) = outputs.commit() {
        if let Some(dir) = created {
            // Empty again: every temporary file in it was removed.
            let _ = std::fs::remove_dir(dir);
        }
        return Err(Error::from_write(&e));
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
