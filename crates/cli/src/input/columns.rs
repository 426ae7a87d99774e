//! Curve tables: which columns are the coordinates, decided by name, never by guess.
//!
//! - With a header (a first row that is not all numbers), the coordinates are the columns
//!   named `x`, `y` and (optionally) `z`, compared without case, wherever they stand; every
//!   other column is a label, carried through to the output as text, numeric or not, byte
//!   for byte in a comma table (spaces included). A whitespace table's header is read the
//!   same way ([`super`]'s sniffing takes it for a header, not an airfoil's name line).
//!   `--columns z,y` names the coordinates instead (a hull section faired as y(z)): the first
//!   named column is the abscissa, and the faired values are written back into the same
//!   columns.
//! - Without a header the columns are read by position (x, y[, z]) only when there are two
//!   or three of them and every field is a number; the reader says so in a note (the command
//!   prints it on standard error unless `-q`). `--columns` then names positions by the same
//!   letters (`z,y` = columns 3 and 2).
//!
//! Every error names the file and the line. One pass over the text, O(size) time; the points
//! are stored without a row allocation unless there are label columns.

use super::table::{number, Delimiter};
use super::{CurveInput, CurvePoints, InputFormat, Source};
use curve_repr::{Vec2, Vec3};
use fair_door::error::{Error, Result};

/// How a curve table's columns become points, remembered to write the result back in place.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Fields per row.
    pub columns: usize,
    /// The file column (from 0) of each coordinate of a point, in point order: `[0, 1]` for
    /// `x,y`; `[2, 1]` for `--columns z,y` on `x,y,z`.
    pub coordinates: Vec<usize>,
    /// The names of those columns as the header writes them (`x`, `y`, `z` by position in a
    /// file without a header): the axes of plots.
    pub names: Vec<String>,
    /// Each row's label fields (every column that is not a coordinate), in file order; empty
    /// when there is no label column.
    pub labels: Vec<Vec<String>>,
}

impl Layout {
    /// The file columns (from 0) that are labels, in file order.
    pub fn label_columns(&self) -> Vec<usize> {
        (0..self.columns)
            .filter(|c| !self.coordinates.contains(c))
            .collect()
    }
}

/// What the reader is told: the coordinate columns by name (`--columns`).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct ReadOptions {
    /// The coordinate columns by name, abscissa first (2 or 3 names), or `None` for `x,y[,z]`.
    pub columns: Option<Vec<String>>,
}

impl ReadOptions {
    /// Options with `--columns` as given (`None` for the default x, y[, z]).
    pub fn with_columns(columns: Option<Vec<String>>) -> ReadOptions {
        ReadOptions { columns }
    }
}

fn unquote(field: &str) -> &str {
    let field = field.trim();
    field
        .strip_prefix('"')
        .and_then(|f| f.strip_suffix('"'))
        .unwrap_or(field)
        .trim()
}

/// The header's columns that are coordinates: by `--columns`, else x, y[, z].
fn coordinates_from_header(
    source: &Source,
    line: usize,
    text: &str,
    names: &[&str],
    chosen: Option<&[String]>,
) -> Result<Vec<usize>> {
    let find = |wanted: &str| -> Result<Option<usize>> {
        let matches: Vec<usize> = (0..names.len())
            .filter(|&c| names[c].eq_ignore_ascii_case(wanted.trim()))
            .collect();
        match matches.as_slice() {
            [] => Ok(None),
            [one] => Ok(Some(*one)),
            [first, second, ..] => Err(Error::Parse {
                path: source.name.clone(),
                line,
                message: format!(
                    "the header names column `{wanted}` twice (columns {} and {}): rename one",
                    first + 1,
                    second + 1
                ),
            }),
        }
    };
    match chosen {
        Some(wanted) => wanted
            .iter()
            .map(|name| {
                find(name)?.ok_or_else(|| Error::Argument {
                    option: "--columns",
                    message: format!(
                        "{}: no column `{name}` in the header `{}` (line {line})",
                        source.name,
                        super::echo(text)
                    ),
                })
            })
            .collect(),
        None => {
            let (x, y, z) = (find("x")?, find("y")?, find("z")?);
            match (x, y) {
                (Some(x), Some(y)) => Ok([Some(x), Some(y), z].into_iter().flatten().collect()),
                _ => {
                    let missing = if x.is_none() { "x" } else { "y" };
                    Err(Error::Parse {
                        path: source.name.clone(),
                        line,
                        message: format!(
                            "the header `{}` has no `{missing}` column: name the coordinate columns \
                             x, y (and z), or choose them with --columns (e.g. --columns z,y)",
                            super::echo(text)
                        ),
                    })
                }
            }
        }
    }
}

/// Columns chosen by letter in a file without a header: x, y, z are columns 1, 2, 3.
fn coordinates_by_position(source: &Source, columns: usize, chosen: Option<&[String]>) -> Result<Vec<usize>> {
    match chosen {
        None => Ok((0..columns).collect()),
        Some(wanted) => wanted
            .iter()
            .map(|name| {
                let position = ["x", "y", "z"]
                    .iter()
                    .position(|letter| letter.eq_ignore_ascii_case(name.trim()));
                match position {
                    Some(p) if p < columns => Ok(p),
                    _ => Err(Error::Argument {
                        option: "--columns",
                        message: format!(
                            "{}: the file has no header, so its {columns} columns are x, y{}; `{name}` is none of them",
                            source.name,
                            if columns == 3 { ", z" } else { "" }
                        ),
                    }),
                }
            })
            .collect(),
    }
}

/// Checks `--columns` itself: 2 or 3 distinct names.
pub fn check_columns(columns: &[String]) -> Result<()> {
    if columns.len() != 2 && columns.len() != 3 {
        return Err(Error::Argument {
            option: "--columns",
            message: format!(
                "`{}` names {} columns; give 2 (abscissa first, e.g. z,y) or 3",
                columns.join(","),
                columns.len()
            ),
        });
    }
    for (i, name) in columns.iter().enumerate() {
        if name.trim().is_empty() {
            return Err(Error::Argument {
                option: "--columns",
                message: format!("`{}` has an empty name", columns.join(",")),
            });
        }
        if columns[..i]
            .iter()
            .any(|n| n.trim().eq_ignore_ascii_case(name.trim()))
        {
            return Err(Error::Argument {
                option: "--columns",
                message: format!("`{name}` appears twice in `{}`", columns.join(",")),
            });
        }
    }
    Ok(())
}

/// Parses a curve table (see the module doc). Notes for the user (a headerless file read by
/// position) are returned in [`CurveInput::notes`].
pub fn parse(source: &Source, options: &ReadOptions) -> Result<CurveInput> {
    if let Some(columns) = &options.columns {
        check_columns(columns)?;
    }
    let chosen = options.columns.as_deref();
    let delimiter = if source.text.contains(',') {
        Delimiter::Comma
    } else {
        Delimiter::Whitespace
    };
    let mut lines_iter = super::numbered_lines(&source.text)
        .map(|(line, raw)| {
            let raw = raw.trim_start_matches('\u{feff}');
            (line, raw.trim(), raw)
        })
        .filter(|(_, text, _)| !text.is_empty() && !text.starts_with('#'))
        .peekable();
    let Some(&(first_line, first_text, first_raw)) = lines_iter.peek() else {
        return Err(Error::Empty {
            path: source.name.clone(),
            reason: "the file is empty".into(),
        });
    };
    let first_fields: Vec<&str> = delimiter.split(first_text);
    let has_header = !first_fields.iter().all(|f| f.parse::<f64>().is_ok());
    let columns = first_fields.len();
    let mut notes = Vec::new();
    let (header, coordinates, names) = if has_header {
        lines_iter.next();
        let names: Vec<&str> = first_fields.iter().map(|f| unquote(f)).collect();
        let named = |wanted: &str| names.iter().any(|n| n.eq_ignore_ascii_case(wanted));
        if chosen.is_none() && ["i", "j", "x", "y", "z"].iter().all(|n| named(n)) {
            return Err(Error::Parse {
                path: source.name.clone(),
                line: first_line,
                message: "an i,j,x,y,z grid is a surface: use `fair surface` (or name the curve's columns with --columns)".into(),
            });
        }
        let coordinates = coordinates_from_header(source, first_line, first_text, &names, chosen)?;
        let chosen_names = coordinates.iter().map(|&c| names[c].to_string()).collect();
        (Some(first_raw.to_string()), coordinates, chosen_names)
    } else {
        if columns != 2 && columns != 3 {
            let hint = if columns == 5 {
                " (an i,j,x,y,z grid is a surface: use `fair surface`)"
            } else {
                " (add a header naming the coordinate columns x, y, z; the others are then labels)"
            };
            return Err(Error::Parse {
                path: source.name.clone(),
                line: first_line,
                message: format!("{columns} columns without a header, expected 2 (x,y) or 3 (x,y,z){hint}"),
            });
        }
        let coordinates = coordinates_by_position(source, columns, chosen)?;
        let names: Vec<String> = coordinates
            .iter()
            .map(|&c| ["x", "y", "z"][c].to_string())
            .collect();
        notes.push(format!(
            "{}: no header; columns read by position as {}",
            source.name,
            ["x", "y", "z"][..columns].join(",")
        ));
        (None, coordinates, names)
    };
    let dimension = coordinates.len();
    let has_labels = dimension < columns;
    let header_names: Vec<String> = if has_header {
        first_fields.iter().map(|f| unquote(f).to_string()).collect()
    } else {
        Vec::new()
    };
    let column_name = |c: usize| -> String {
        header_names
            .get(c)
            .cloned()
            .or_else(|| ["x", "y", "z"].get(c).map(|s| s.to_string()))
            .unwrap_or_else(|| format!("#{}", c + 1))
    };
    let mut planar: Vec<Vec2> = Vec::new();
    let mut spatial: Vec<Vec3> = Vec::new();
    let mut labels: Vec<Vec<String>> = Vec::new();
    let mut lines: Vec<usize> = Vec::new();
    let mut fields: Vec<&str> = Vec::with_capacity(columns);
    let mut values = [0.0_f64; 3];
    for (line, text, raw) in lines_iter {
        fields.clear();
        match delimiter {
            // Untrimmed: a label is written back exactly as read, spaces and all; a
            // coordinate is trimmed where it is parsed.
            Delimiter::Comma => fields.extend(raw.split(',')),
            Delimiter::Whitespace => fields.extend(text.split_whitespace()),
        }
        if fields.len() != columns {
            let (what, first) = match lines.first() {
                Some(&row) => ("the first row", row),
                None if has_header => ("the header", first_line),
                None => ("the first row", line),
            };
            return Err(Error::Parse {
                path: source.name.clone(),
                line,
                message: format!(
                    "{} fields, expected {columns} like {what} (line {first})",
                    fields.len()
                ),
            });
        }
        for (k, &c) in coordinates.iter().enumerate() {
            values[k] = number(fields[c].trim()).map_err(|problem| Error::Parse {
                path: source.name.clone(),
                line,
                message: format!("column {} ({}): {problem}", c + 1, column_name(c)),
            })?;
        }
        if dimension == 2 {
            planar.push(Vec2::new(values[0], values[1]));
        } else {
            spatial.push(Vec3::new(values[0], values[1], values[2]));
        }
        if has_labels {
            labels.push(
                (0..columns)
                    .filter(|c| !coordinates.contains(c))
                    .map(|c| fields[c].to_string())
                    .collect(),
            );
        }
        lines.push(line);
    }
    if lines.is_empty() {
        let reason = if has_header {
            format!("only a header (line {first_line})")
        } else {
            "the file is empty".to_string()
        };
        return Err(Error::Empty {
            path: source.name.clone(),
            reason,
        });
    }
    let points = if dimension == 2 {
        CurvePoints::Planar(planar)
    } else {
        CurvePoints::Spatial(spatial)
    };
    Ok(CurveInput {
        points,
        format: InputFormat::Csv {
            header,
            delimiter,
            layout: Layout {
                columns,
                coordinates,
                names,
                labels,
            },
        },
        source: source.name.clone(),
        lines,
        notes,
    })
}
