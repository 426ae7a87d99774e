//! Writing faired points back in the format they were read in.
//!
//! Numbers are written in Rust's shortest round-trip form, so reading the output back gives
//! the same `f64`s. Nothing NaN or infinite is ever written: [`Error::NonFiniteOutput`] instead.

use curve_repr::number::Compact;

use crate::input::{CurveInput, CurvePoints, Delimiter, Grid, InputFormat, Layout, SurfaceInput};
use fair_door::error::{Error, Result};

/// Formats `points` in the format of `input` (header, JSON document, airfoil name).
///
/// `points` must have the dimension of the input; a Lednicer input needs the same count.
pub(crate) fn format_curve(input: &CurveInput, points: &CurvePoints) -> Result<String> {
    if let Some(index) = points.first_non_finite() {
        return Err(Error::NonFiniteOutput {
            what: "output point".into(),
            index,
        });
    }
    if points.dimension() != input.points.dimension() {
        return Err(Error::Internal {
            message: format!(
                "output has dimension {}, input {}",
                points.dimension(),
                input.points.dimension()
            ),
        });
    }
    let rows = points.rows();
    let mut text = String::new();
    match &input.format {
        InputFormat::Csv {
            header,
            delimiter,
            layout,
        } => {
            if let Some(header) = header {
                text.push_str(header);
                text.push('\n');
            }
            push_layout_rows(&mut text, &rows, layout, *delimiter)?;
        }
        InputFormat::Json { document } => {
            let written = match document {
                Some(document) => document.to_pretty(&rows),
                None => serde_json::to_string_pretty(&rows),
            };
            text = written.map_err(|e| Error::Internal {
                message: e.to_string(),
            })?;
            text.push('\n');
        }
        InputFormat::Selig { name } => {
            text.push_str(name);
            text.push('\n');
            push_rows(&mut text, rows.iter().map(Vec::as_slice), Delimiter::Whitespace);
        }
        InputFormat::Lednicer {
            name,
            upper,
            lower,
            shared_leading_edge,
        } => {
            let expected = (upper + lower).saturating_sub(usize::from(*shared_leading_edge));
            if rows.len() != expected || *upper == 0 {
                return Err(Error::Internal {
                    message: format!("Lednicer output needs {expected} points, got {}", rows.len()),
                });
            }
            let (upper_rows, rest) = rows.split_at(*upper);
            let mut lower_rows: Vec<&[f64]> = Vec::with_capacity(*lower);
            if *shared_leading_edge {
                lower_rows.extend(upper_rows.last().map(Vec::as_slice));
            }
            lower_rows.extend(rest.iter().map(Vec::as_slice));
            text.push_str(&format!("{name}\n{upper}. {lower}.\n\n"));
            push_rows(
                &mut text,
                upper_rows.iter().rev().map(Vec::as_slice),
                Delimiter::Whitespace,
            );
            text.push('\n');
            push_rows(&mut text, lower_rows.into_iter(), Delimiter::Whitespace);
        }
    }
    Ok(text)
}

/// Formats a surface grid in the row order and header of `input`, indices as in the file.
pub(crate) fn format_surface(input: &SurfaceInput, grid: &Grid) -> Result<String> {
    if let Some(index) = grid.points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(Error::NonFiniteOutput {
            what: "output grid point".into(),
            index,
        });
    }
    let mut text = String::new();
    if let Some(header) = &input.header {
        text.push_str(header);
        text.push('\n');
    }
    let separator = input.delimiter.as_str();
    for &(i, j) in &input.order {
        let p = grid.get(i, j).ok_or_else(|| Error::Internal {
            message: format!("output grid has no cell ({i}, {j})"),
        })?;
        let (fi, fj) = (i as i64 + input.offset.0, j as i64 + input.offset.1);
        let fields = [
            fi.to_string(),
            fj.to_string(),
            number(p.x),
            number(p.y),
            number(p.z),
        ];
        // Each field in its file column (input.columns is a permutation of 0..5).
        let mut row: [&str; 5] = [""; 5];
        for (field, &column) in fields.iter().zip(&input.columns) {
            if let Some(slot) = row.get_mut(column) {
                *slot = field;
            }
        }
        text.push_str(&row.join(separator));
        text.push('\n');
    }
    Ok(text)
}

/// A coordinate as text: the shortest digits that read back as the same f64, scientific
/// outside 1e-5 ≤ |v| < 1e16 ([`Compact`]): `1e-200`, not 200 digits of zeros. O(1).
pub(crate) fn number(v: f64) -> String {
    Compact(v).to_string()
}

fn push_rows<'a>(text: &mut String, rows: impl Iterator<Item = &'a [f64]>, delimiter: Delimiter) {
    for row in rows {
        let fields: Vec<String> = row.iter().map(|&v| number(v)).collect();
        text.push_str(&fields.join(delimiter.as_str()));
        text.push('\n');
    }
}

/// Rows with every coordinate back in its own column and the label columns' text in place,
/// in the file's column order.
fn push_layout_rows(
    text: &mut String,
    rows: &[Vec<f64>],
    layout: &Layout,
    delimiter: Delimiter,
) -> Result<()> {
    let has_labels = !layout.labels.is_empty();
    if has_labels && layout.labels.len() != rows.len() {
        return Err(Error::Internal {
            message: format!(
                "{} rows for {} labelled input rows",
                rows.len(),
                layout.labels.len()
            ),
        });
    }
    // Which coordinate (or, for None, the next label) goes in each file column.
    let slots: Vec<Option<usize>> = (0..layout.columns)
        .map(|column| layout.coordinates.iter().position(|&c| c == column))
        .collect();
    let separator = delimiter.as_str();
    for (index, row) in rows.iter().enumerate() {
        let mut words = layout.labels.get(index).into_iter().flatten();
        for (column, slot) in slots.iter().enumerate() {
            if column > 0 {
                text.push_str(separator);
            }
            match slot {
                Some(k) => text.push_str(&row.get(*k).map(|&v| number(v)).unwrap_or_default()),
                None => text.push_str(words.next().map(String::as_str).unwrap_or_default()),
            }
        }
        text.push('\n');
    }
    Ok(())
}

/// The format `-o` asks for, by its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum OutputFormat {
    /// The input's own format (`-o -`, standard output).
    SameAsInput,
    /// `.csv`: comma-separated, a header naming the columns.
    Csv,
    /// `.json`: `{"points": [...]}`.
    Json,
    /// `.dat`: a Selig airfoil file (a name line, then `x y` pairs).
    Dat,
}

impl OutputFormat {
    /// The format of `path` by its extension: `.csv`, `.json`, `.dat` (and `.txt`, written as
    /// a table like `.csv`); `-` keeps the input's. Any other extension, or none, is refused
    /// naming the ones known, before anything runs. O(1).
    pub(crate) fn of_path(path: &str) -> Result<OutputFormat> {
        if path == "-" {
            return Ok(OutputFormat::SameAsInput);
        }
        if std::path::Path::new(path).is_dir() {
            return Err(Error::Write {
                path: path.into(),
                reason: "it is a directory".into(),
            });
        }
        let extension = std::path::Path::new(path)
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase());
        match extension.as_deref() {
            Some("csv") | Some("txt") => Ok(OutputFormat::Csv),
            Some("json") => Ok(OutputFormat::Json),
            Some("dat") => Ok(OutputFormat::Dat),
            other => Err(Error::Argument {
                option: "-o",
                message: format!(
                    "`{path}`: {}; the points are written as .csv, .json or .dat (chosen by the extension), or to - in the input's format",
                    match other {
                        Some(e) => format!("unknown extension `.{e}`"),
                        None => "no extension".to_string(),
                    }
                ),
            }),
        }
    }
}

/// Formats `points` as `format` asks: in the input's own form when the families agree (its
/// header and label columns, its JSON document, its airfoil name), else converted — a CSV
/// with a header of the coordinates' names (label columns kept), a JSON object with the
/// points (and the label columns as `labels`), a Selig file named after the input. A 3D curve
/// cannot be an airfoil `.dat`. O(n).
pub(crate) fn format_curve_as(
    input: &CurveInput,
    points: &CurvePoints,
    format: OutputFormat,
) -> Result<String> {
    let same = matches!(
        (format, &input.format),
        (OutputFormat::SameAsInput, _)
            | (OutputFormat::Csv, InputFormat::Csv { .. })
            | (OutputFormat::Json, InputFormat::Json { .. })
            | (
                OutputFormat::Dat,
                InputFormat::Selig { .. } | InputFormat::Lednicer { .. }
            )
    );
    if same {
        return format_curve(input, points);
    }
    let stem = std::path::Path::new(&input.source)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("curve")
        .to_string();
    let converted = match format {
        OutputFormat::Csv => {
            let (header, layout) = match &input.format {
                InputFormat::Csv { header, layout, .. } => (header.clone(), layout.clone()),
                _ => {
                    let names = input.coordinate_names();
                    let layout = Layout {
                        columns: names.len(),
                        coordinates: (0..names.len()).collect(),
                        names: names.clone(),
                        labels: Vec::new(),
                    };
                    (Some(names.join(",")), layout)
                }
            };
            InputFormat::Csv {
                header,
                delimiter: Delimiter::Comma,
                layout,
            }
        }
        OutputFormat::Json => {
            let mut document = crate::input::JsonDocument::new();
            match &input.format {
                InputFormat::Selig { name } | InputFormat::Lednicer { name, .. } => {
                    document.push("name", &serde_json::json!(name));
                }
                InputFormat::Csv { header, layout, .. } if !layout.labels.is_empty() => {
                    let names: Vec<String> = header
                        .as_deref()
                        .map(|h| {
                            let delimiter = if h.contains(',') {
                                Delimiter::Comma
                            } else {
                                Delimiter::Whitespace
                            };
                            delimiter
                                .split(h)
                                .iter()
                                .map(|f| f.trim_matches('"').to_string())
                                .collect()
                        })
                        .unwrap_or_default();
                    let mut labels = serde_json::Map::new();
                    for (k, column) in layout.label_columns().into_iter().enumerate() {
                        let name = names
                            .get(column)
                            .cloned()
                            .unwrap_or_else(|| format!("column {}", column + 1));
                        let values: Vec<&str> = layout.labels.iter().map(|row| row[k].as_str()).collect();
                        labels.insert(name, serde_json::json!(values));
                    }
                    document.push("labels", &serde_json::Value::Object(labels));
                }
                _ => {}
            }
            InputFormat::Json {
                document: Some(document),
            }
        }
        OutputFormat::Dat => {
            if points.dimension() != 2 {
                return Err(Error::Argument {
                    option: "-o",
                    message: format!(
                        "an airfoil .dat file holds planar x y pairs; {} is a 3D curve (write .csv or .json)",
                        input.source
                    ),
                });
            }
            InputFormat::Selig { name: stem }
        }
        OutputFormat::SameAsInput => input.format.clone(),
    };
    let converted_input = CurveInput {
        format: converted,
        ..input.clone()
    };
    format_curve(&converted_input, points)
}

/// Writes text to a file, completely or not at all ([`cad::atomic`]), or to standard output
/// for `-`.
///
/// A closed standard output (`fair ... -o - | head`) is not an error.
pub(crate) fn write_text(path: &str, text: &str) -> Result<()> {
    let mut outputs = cad::atomic::Outputs::new();
    outputs.add_text(cad::atomic::Target::from_arg(path), text);
    outputs.commit().map_err(|e| Error::from_write(&e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::{grid, parse_curve, Source};
    use curve_repr::Vec2;

    fn round_trip(name: &str, text: &str) -> (CurveInput, CurveInput, String) {
        let input = parse_curve(&Source::from_text(name, text)).unwrap();
        let written = format_curve(&input, &input.points).unwrap();
        let again = parse_curve(&Source::from_text(name, &written)).unwrap();
        (input, again, written)
    }

    #[test]
    fn csv_round_trips_with_and_without_header() {
        let (a, b, w) = round_trip("a.csv", "x,y\n0.1,0.2\n1e-17,3\n");
        assert_eq!(a, b);
        assert!(w.starts_with("x,y\n"));
        let (a, b, w) = round_trip("a.csv", "0.1,0.2,0.3\n1,2,3\n");
        assert_eq!(a, b);
        assert!(w.starts_with("0.1,0.2,0.3\n"));
        let (a, b, _) = round_trip("a.txt", "0.1 0.2\n1 2\n");
        assert_eq!(a, b);
    }

    #[test]
    fn json_round_trips_keeping_other_keys() {
        let (a, b, w) = round_trip(
            "a.json",
            "{\"name\": \"w\", \"points\": [[0.1, 0.2], [0.3, 0.7]]}",
        );
        assert_eq!(a.points, b.points);
        assert_eq!(a.format, b.format);
        assert!(w.contains("\"name\": \"w\""));
        let (a, b, _) = round_trip("b.json", "[[0.1, 0.2, 0.3], [1, 2, 3]]");
        assert_eq!(a, b);
    }

    #[test]
    fn selig_and_lednicer_round_trip() {
        let (a, b, w) = round_trip("a.dat", "NACA 0012\n1 0\n0.5 0.06\n0 0\n0.5 -0.06\n1 0\n");
        assert_eq!(a.points, b.points);
        assert_eq!(a.format, b.format);
        assert!(w.starts_with("NACA 0012\n1 0\n"));
        let (a, b, w) = round_trip(
            "l.dat",
            "FOIL\n3. 3.\n\n0 0\n0.5 0.1\n1 0\n\n0 0\n0.5 -0.1\n1 0\n",
        );
        assert_eq!(a.points, b.points);
        assert_eq!(a.format, b.format);
        assert!(w.starts_with("FOIL\n3. 3.\n\n0 0\n"), "{w}");
    }

    #[test]
    fn moved_points_are_written() {
        let input = parse_curve(&Source::from_text("a.csv", "x,y\n0,0\n1,1\n")).unwrap();
        let moved = CurvePoints::Planar(vec![Vec2::new(0., 0.5), Vec2::new(1., 1.)]);
        assert_eq!(format_curve(&input, &moved).unwrap(), "x,y\n0,0.5\n1,1\n");
    }

    #[test]
    fn never_writes_nan() {
        let input = parse_curve(&Source::from_text("a.csv", "0,0\n1,1\n")).unwrap();
        let bad = CurvePoints::Planar(vec![Vec2::new(0., f64::NAN), Vec2::new(1., 1.)]);
        let e = format_curve(&input, &bad).unwrap_err();
        assert!(matches!(e, Error::NonFiniteOutput { index: 0, .. }), "{e}");
    }

    #[test]
    fn surface_round_trips_in_file_order() {
        let text = "i,j,x,y,z\n1,21,1,1,5\n0,20,0,0,1\n0,21,0,1,2\n1,20,1,0,3.5\n";
        let s = grid::parse(&Source::from_text("s.csv", text)).unwrap();
        assert_eq!(format_surface(&s, &s.grid).unwrap(), text);
    }

    #[test]
    fn write_to_missing_directory_fails_cleanly() {
        let e = write_text("/nonexistent/dir/out.csv", "x").unwrap_err();
        assert_eq!(
            e.to_string(),
            "/nonexistent/dir/out.csv: cannot write: no such file or directory"
        );
    }
}
