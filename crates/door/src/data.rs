//! What the door is given: points with the name of where they came from and the line of each
//! point, so that every error names the file and line a front end read them from.

use fairing::catalog::{CurvePoints, Grid};

use crate::error::{Error, Result};

/// A curve's points and where they came from (a borrowed view: a front end keeps its own
/// reader's type and lends the door this).
#[derive(Debug, Clone, Copy)]
pub struct CurveData<'a> {
    /// The points.
    pub points: &'a CurvePoints,
    /// The name messages give them: a path, `<stdin>`, or a front end's word (`points`).
    pub source: &'a str,
    /// The line of each point, from 1; empty when not known.
    pub lines: &'a [usize],
}

impl<'a> CurveData<'a> {
    /// Points named `source`, lines unknown.
    pub fn new(points: &'a CurvePoints, source: &'a str) -> CurveData<'a> {
        CurveData {
            points,
            source,
            lines: &[],
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The line point `index` was read from, when known.
    pub fn line_of(&self, index: usize) -> Option<usize> {
        self.lines.get(index).copied()
    }

    /// Fails with [`Error::TooFewPoints`] when there are fewer than `needed` points; `what`
    /// names who needs them (`"a curve"`, a method name).
    pub fn require_at_least(&self, needed: usize, what: &str) -> Result<()> {
        if self.len() < needed {
            return Err(Error::TooFewPoints {
                path: self.source.to_string(),
                found: self.len(),
                needed,
                what: what.to_string(),
            });
        }
        Ok(())
    }

    /// An error about point `index`, naming its line when known.
    pub fn point_error(&self, index: usize, message: impl Into<String>) -> Error {
        match self.line_of(index) {
            Some(line) => Error::Parse {
                path: self.source.to_string(),
                line,
                message: message.into(),
            },
            None => Error::Invalid {
                path: self.source.to_string(),
                message: format!("point {index}: {}", message.into()),
            },
        }
    }
}

/// A surface grid and where it came from.
#[derive(Debug, Clone, Copy)]
pub struct GridData<'a> {
    /// The grid (row by row).
    pub grid: &'a Grid,
    /// The name messages give it.
    pub source: &'a str,
}

/// The smallest grid with an interior point (z_ij is defined at interior points).
pub const MIN_GRID: (usize, usize) = (3, 3);

impl GridData<'_> {
    /// Checks that the grid has an interior point.
    pub fn require_grid(&self) -> Result<()> {
        let (rows, columns) = (self.grid.rows, self.grid.columns);
        if rows < MIN_GRID.0 || columns < MIN_GRID.1 {
            return Err(Error::Invalid {
                path: self.source.to_string(),
                message: format!(
                    "a {rows} × {columns} grid has no interior point; a surface needs at least 3 × 3"
                ),
            });
        }
        Ok(())
    }
}
