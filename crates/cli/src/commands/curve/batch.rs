//! `fair curve` over many curves: a directory of curve files, or a JSON-lines stream.
//!
//! - INPUT is a directory: every regular file in it with a curve file's extension (`.csv`,
//!   `.json`, `.dat`, `.txt`; [`CURVE_EXTENSIONS`]) and a name not starting with `.` is a
//!   curve, taken in name order; the other files (a `PROVENANCE.md`) are skipped and listed in
//!   a note on standard error (unless `-q`).
//! - INPUT ends in `.jsonl` or `.ndjson`, or `--batch` is given (`-` reads standard input):
//!   every non-blank line is one JSON curve, `{"points": [[x, y], ...]}` (other keys kept), and
//!   errors name the file and that line.
//!
//! Curves are faired in parallel on all cores (rayon), each exactly as `fair curve` would fair
//! it alone. The report is one JSON line per curve, in input order: the report of
//! `docs/CONTRACT.md` with a `source` field added, or `{"source": ..., "error": ..., "exit_status": 2}`
//! for a curve that failed; the others go on. The lines go to standard output, or to
//! `--report FILE`. `-o` names a directory for a directory batch (each faired file under its
//! own name) and a JSON-lines file for a stream (one line per input line, `{"error": ...}`
//! for failures); `--plot` names a directory (`<file stem>.svg`, `line-<N>.svg` for streams).
//! The command exits 0 when every curve succeeded, else with [`Error::Batch`] (2 when every
//! failure was bad input, 1 otherwise) after writing everything.

use fairing::catalog::{Catalog, ConfigFile};

use super::{process, Faired};
use crate::args::FairArgs;
use crate::commands::say;
use crate::input::{self, CurveInput, Source};
use crate::progress;
use fair_door::error::{Error, Result};
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// The extensions of the files a directory batch takes (compared without case).
pub(crate) const CURVE_EXTENSIONS: [&str; 4] = ["csv", "json", "dat", "txt"];

fn is_curve_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| CURVE_EXTENSIONS.iter().any(|c| c.eq_ignore_ascii_case(e)))
}

/// Whether `fair curve` should treat its INPUT as a batch.
pub(crate) fn is_batch(args: &FairArgs) -> bool {
    args.is_batch()
}

/// One curve of a batch, read when it is faired (in parallel).
#[derive(Debug, Clone)]
pub(crate) struct Item {
    /// The file, or `file:LINE` for a stream.
    pub name: String,
    /// The file name (directory batch) or `line-N` (stream), for output files.
    pub stem: String,
    /// Where its points are.
    pub source: ItemSource,
}

/// Where the points of one batch item are.
#[derive(Debug, Clone)]
pub(crate) enum ItemSource {
    /// A file of a directory batch.
    File(String),
    /// One line of a JSON-lines stream.
    Line {
        /// The stream's name.
        stream: String,
        /// The line, from 1.
        number: usize,
        /// Its text.
        text: String,
    },
}

impl Item {
    /// Reads the item's points (a file with `options`' `--columns`); errors name the file, or
    /// the stream and line.
    pub(crate) fn read(&self, options: &input::ReadOptions) -> Result<CurveInput> {
        match &self.source {
            ItemSource::File(path) => input::read_curve_with(path, options),
            ItemSource::Line { stream, number, text } => {
                input::parse_curve(&Source::from_text(&format!("{stream}.json"), text))
                    .map(|mut curve| {
                        curve.source = self.name.clone();
                        curve
                    })
                    .map_err(|e| relocate(e, stream, *number))
            }
        }
    }
}

/// Reads the items of a batch.
pub(crate) fn items(args: &FairArgs) -> Result<Vec<Item>> {
    let path = Path::new(&args.input);
    if path.is_dir() && !args.batch {
        let entries = std::fs::read_dir(path).map_err(|e| Error::Read {
            path: args.input.clone(),
            reason: input::io_reason(&e),
        })?;
        let candidates: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file())
            .filter(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| !n.starts_with('.'))
            })
            .collect();
        let (mut files, mut skipped): (Vec<PathBuf>, Vec<PathBuf>) =
            candidates.into_iter().partition(|p| is_curve_file(p));
        files.sort();
        skipped.sort();
        if !skipped.is_empty() && !args.quiet {
            let names: Vec<String> = skipped.iter().map(|p| p.display().to_string()).collect();
            eprintln!(
                "{}: note: skipped {} file{} without a curve extension (.{}): {}",
                crate::program_name(),
                names.len(),
                if names.len() == 1 { "" } else { "s" },
                CURVE_EXTENSIONS.join(", ."),
                names.join(", ")
            );
        }
        if files.is_empty() {
            return Err(Error::Empty {
                path: args.input.clone(),
                reason: format!(
                    "the directory holds no curve files (.{})",
                    CURVE_EXTENSIONS.join(", .")
                ),
            });
        }
        return Ok(files
            .into_iter()
            .map(|file| {
                let name = file.display().to_string();
                let stem = file
                    .file_name()
                    .and_then(|n| n.to_str())
                    .unwrap_or("curve")
                    .to_string();
                Item {
                    source: ItemSource::File(name.clone()),
                    name,
                    stem,
                }
            })
            .collect());
    }
    let source = Source::read(&args.input)?;
    let mut out = Vec::new();
    for (index, line) in source.text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let number = index + 1;
        out.push(Item {
            name: format!("{}:{number}", source.name),
            stem: format!("line-{number}"),
            source: ItemSource::Line {
                stream: source.name.clone(),
                number,
                text: line.to_string(),
            },
        });
    }
    if out.is_empty() {
        return Err(Error::Empty {
            path: source.name,
            reason: "no JSON lines".into(),
        });
    }
    Ok(out)
}

/// An error found in the text of one stream line, named by the stream and that line.
fn relocate(error: Error, stream: &str, line: usize) -> Error {
    match error {
        Error::Parse { message, .. } => Error::Parse {
            path: stream.into(),
            line,
            message,
        },
        Error::Empty { reason, .. } => Error::Parse {
            path: stream.into(),
            line,
            message: format!("no points: {reason}"),
        },
        Error::Invalid { message, .. } => Error::Parse {
            path: stream.into(),
            line,
            message,
        },
        other => other,
    }
}

/// Runs a batch.
pub(crate) fn run(catalog: &Catalog, args: &FairArgs, file: Option<&ConfigFile>) -> Result<()> {
    if args.print_config {
        return Err(Error::Argument {
            option: "--print-config",
            message: "give one curve, not a batch, to print the config it implies".into(),
        });
    }
    if args.output.as_deref() == Some("-") {
        return Err(Error::Argument {
            option: "-o",
            message: "a batch writes its report lines to standard output; give -o a directory or file".into(),
        });
    }
    let items = items(args)?;
    let directory_batch = Path::new(&args.input).is_dir() && !args.batch;
    for (option, dir) in [
        ("--plot", args.plot.as_deref()),
        (
            "-o",
            args.output.as_deref().map(Path::new).filter(|_| directory_batch),
        ),
    ] {
        if let Some(dir) = dir {
            std::fs::create_dir_all(dir).map_err(|e| Error::Argument {
                option,
                message: format!(
                    "{}: cannot create the directory: {}",
                    dir.display(),
                    input::io_reason(&e)
                ),
            })?;
        }
    }
    let bar = progress::bar(items.len() as u64, args.quiet, "fairing");
    let results: Vec<Result<Faired>> = items
        .par_iter()
        .map(|item| {
            // A report with a non-finite number is that curve's failure, never a `null` line.
            let result = item
                .read(&args.read_options())
                .and_then(|input| process(catalog, &input, args, file))
                .and_then(|faired| faired.report.check_finite().map(|()| faired));
            bar.inc(1);
            result
        })
        .collect();
    bar.finish_and_clear();

    let mut report_lines = String::new();
    let mut output_lines = String::new();
    // Every file of the batch written all or none, after every curve was faired.
    let mut outputs = cad::atomic::Outputs::new();
    let (mut failed, mut status) = (0usize, 2u8);
    for (item, result) in items.iter().zip(&results) {
        match result {
            Ok(faired) => {
                super::warn_largest_move(&item.name, &faired.report, args.quiet);
                let mut value = serde_json::to_value(&faired.report).map_err(|e| Error::Internal {
                    message: e.to_string(),
                })?;
                if let serde_json::Value::Object(map) = &mut value {
                    map.insert("source".into(), serde_json::json!(item.name));
                }
                report_lines.push_str(&compact(&value)?);
                if let Some(out) = &args.output {
                    if directory_batch {
                        let path = Path::new(out).join(&item.stem);
                        outputs.add_text(cad::atomic::Target::File(path), &faired.points_text);
                    } else {
                        let value: serde_json::Value =
                            serde_json::from_str(&faired.points_text).map_err(|e| Error::Internal {
                                message: format!("re-reading the JSON output of {}: {e}", item.name),
                            })?;
                        output_lines.push_str(&compact(&value)?);
                    }
                }
                if let Some(dir) = &args.plot {
                    let stem = Path::new(&item.stem)
                        .file_stem()
                        .and_then(|s| s.to_str())
                        .unwrap_or("curve");
                    let path = dir.join(format!("{stem}.svg"));
                    outputs.add(cad::atomic::Target::File(path), |w| {
                        w.write_all(faired.plot.figure().to_svg().as_bytes())
                    });
                }
            }
            Err(e) => {
                failed += 1;
                if e.exit_code() != 2 {
                    status = 1;
                }
                let line = serde_json::json!({
                    "source": item.name,
                    "error": e.one_line(),
                    "exit_status": e.exit_code(),
                });
                report_lines.push_str(&compact(&line)?);
                output_lines.push_str(&compact(&serde_json::json!({ "error": e.one_line() }))?);
            }
        }
    }
    if let (Some(out), false) = (&args.output, directory_batch) {
        outputs.add_text(crate::commands::target(out), output_lines);
    }
    let report_target = match &args.report {
        Some(path) => crate::commands::target(path),
        None => cad::atomic::Target::Stdout,
    };
    outputs.add_text(report_target, report_lines);
    outputs.commit().map_err(|e| Error::from_write(&e))?;
    if args.report.is_some() {
        say(
            args.quiet,
            false,
            &format!("{}: {} curves, {} failed", args.input, items.len(), failed),
        );
    }
    if failed > 0 {
        return Err(Error::Batch {
            failed,
            total: items.len(),
            status,
        });
    }
    Ok(())
}

/// One JSON line.
fn compact(value: &serde_json::Value) -> Result<String> {
    let mut text = serde_json::to_string(value).map_err(|e| Error::Internal {
        message: e.to_string(),
    })?;
    text.push('\n');
    Ok(text)
}
