//! Delimited numeric tables: the common reader behind curve CSV and surface grids.
//!
//! Rows are lines; blank lines and lines starting with `#` are skipped; fields are trimmed.
//! The first row is a header when any of its fields is not a number. Every data field must
//! be a finite number and every row must have as many fields as the first one. (Curve tables,
//! whose label columns are text, have their own reader: [`super::columns`].)

use super::Source;
use fair_door::error::{Error, Result};

/// How fields are separated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Delimiter {
    /// `,`
    Comma,
    /// Runs of spaces or tabs (a file with no comma at all).
    Whitespace,
}

impl Delimiter {
    /// The separator written on output.
    pub fn as_str(self) -> &'static str {
        match self {
            Delimiter::Comma => ",",
            Delimiter::Whitespace => " ",
        }
    }

    pub(crate) fn split(self, line: &str) -> Vec<&str> {
        match self {
            Delimiter::Comma => line.split(',').map(str::trim).collect(),
            Delimiter::Whitespace => line.split_whitespace().collect(),
        }
    }
}

/// A header row as read.
#[derive(Debug, Clone)]
pub(super) struct Header {
    /// The line number, from 1.
    pub line: usize,
    /// The line, trimmed.
    pub text: String,
    /// Its fields, trimmed and unquoted.
    pub names: Vec<String>,
}

/// One data row.
#[derive(Debug, Clone)]
pub(super) struct Row {
    /// The line number, from 1.
    pub line: usize,
    /// Its values, all finite, in file order.
    pub values: Vec<f64>,
}

/// A parsed table: an optional header and at least one row of equal length.
#[derive(Debug, Clone)]
pub(super) struct Table {
    /// The header, if the first row was not numeric.
    pub header: Option<Header>,
    /// The data rows.
    pub rows: Vec<Row>,
    /// Fields per row.
    pub columns: usize,
    /// The separator found.
    pub delimiter: Delimiter,
}

impl Table {
    /// Parses a table; fails on the first bad field or row with its line, and with
    /// [`Error::Empty`] when there is no data row.
    pub(super) fn parse(source: &Source) -> Result<Table> {
        let delimiter = if source.text.contains(',') {
            Delimiter::Comma
        } else {
            Delimiter::Whitespace
        };
        let mut header = None;
        let mut rows: Vec<Row> = Vec::new();
        let mut columns = 0;
        for (line, raw) in super::numbered_lines(&source.text) {
            let text = raw.trim().trim_start_matches('\u{feff}');
            if text.is_empty() || text.starts_with('#') {
                continue;
            }
            let fields = delimiter.split(text);
            if header.is_none() && rows.is_empty() && !all_numeric(text, delimiter) {
                columns = fields.len();
                let names: Vec<String> = fields.iter().map(|f| f.trim_matches('"').to_string()).collect();
                header = Some(Header {
                    line,
                    text: text.to_string(),
                    names,
                });
                continue;
            }
            if columns == 0 {
                columns = fields.len();
            }
            if fields.len() != columns {
                let (what, first) = match (&header, rows.first()) {
                    (_, Some(row)) => ("the first row", row.line),
                    (Some(h), None) => ("the header", h.line),
                    (None, None) => ("the first row", line),
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
            let mut values = Vec::with_capacity(columns);
            for (column, field) in fields.iter().enumerate() {
                values.push(number(field).map_err(|problem| Error::Parse {
                    path: source.name.clone(),
                    line,
                    message: format!(
                        "column {} ({}): {problem}",
                        column + 1,
                        column_name(&header, column)
                    ),
                })?);
            }
            rows.push(Row { line, values });
        }
        if rows.is_empty() {
            let reason = match &header {
                Some(h) => format!("only a header (line {})", h.line),
                None => "the file is empty".to_string(),
            };
            return Err(Error::Empty {
                path: source.name.clone(),
                reason,
            });
        }
        Ok(Table {
            header,
            rows,
            columns,
            delimiter,
        })
    }

    /// The line of the header, or of the first row.
    pub(super) fn first_line(&self) -> usize {
        match (&self.header, self.rows.first()) {
            (Some(h), _) => h.line,
            (None, Some(r)) => r.line,
            (None, None) => 1,
        }
    }
}

fn column_name(header: &Option<Header>, column: usize) -> String {
    match header.as_ref().and_then(|h| h.names.get(column)) {
        Some(name) => name.clone(),
        None => ["x", "y", "z"]
            .get(column)
            .map_or_else(|| format!("#{}", column + 1), |s| s.to_string()),
    }
}

/// Parses one field as a finite number, or says why it is not one.
pub(crate) fn number(field: &str) -> std::result::Result<f64, String> {
    if field.is_empty() {
        return Err("empty field, expected a number".into());
    }
    match field.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("`{}` is not finite", super::echo(field))),
        Err(_) => Err(format!("`{}` is not a number", super::echo(field))),
    }
}

/// Whether every field of a line parses as a number (NaN and infinities count as numbers here,
/// so that a first row `nan,1` is reported as a bad value rather than taken for a header).
pub(crate) fn all_numeric(line: &str, delimiter: Delimiter) -> bool {
    let fields = delimiter.split(line.trim());
    !fields.is_empty() && fields.iter().all(|f| f.parse::<f64>().is_ok())
}
