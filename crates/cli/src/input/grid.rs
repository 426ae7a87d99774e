//! Surface grids: CSV rows `i,j,x,y,z` (header optional) into a rectangular grid P_ij.
//!
//! With a header the columns are taken by name, in any order (`j,i,x,y,z` is read as the
//! header says, and written back in the same order); a header naming a column that is not
//! one of `i, j, x, y, z`, or missing one, is refused with its line. Without a header the five
//! columns are `i, j, x, y, z` by position.
//!
//! Indices are integers and may start anywhere (a table of offsets starting at station 20);
//! the grid spans i_min..=i_max by j_min..=j_max and every cell must be given exactly once.
//! The row order of the file is remembered so that the output is written in the same order.

use super::table::Table;
use super::{Delimiter, Source};
use curve_repr::Vec3;
use fair_door::error::{Error, Result};

pub use fairing::catalog::Grid;

impl SurfaceInput {
    /// The grid as the door takes it, with the file's name.
    pub fn data(&self) -> fair_door::GridData<'_> {
        fair_door::GridData {
            grid: &self.grid,
            source: &self.source,
        }
    }
}

/// A surface read from a file.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceInput {
    /// The grid, indices shifted to start at 0.
    pub grid: Grid,
    /// The smallest i and j of the file (added back on output).
    pub offset: (i64, i64),
    /// For each file row in order, its cell (i, j) in the grid (from 0).
    pub order: Vec<(usize, usize)>,
    /// The header line as read, if any.
    pub header: Option<String>,
    /// The separator found.
    pub delimiter: Delimiter,
    /// The file column (from 0) of `i`, `j`, `x`, `y`, `z`: `[0, 1, 2, 3, 4]` without a
    /// header; the output writes its fields back in this order.
    pub columns: [usize; 5],
    /// The path as given, or `<stdin>`.
    pub source: String,
    /// The line of each file row, from 1.
    pub lines: Vec<usize>,
}

fn index(value: f64) -> Option<i64> {
    (value.fract() == 0.0 && value.abs() < 1e9).then_some(value as i64)
}

/// The names of a grid's columns, in the order of [`SurfaceInput::columns`].
const NAMES: [&str; 5] = ["i", "j", "x", "y", "z"];

/// The file column of each of `i, j, x, y, z` by the header's names, or why they are not a
/// grid's: an unknown name, a name given twice, a name missing.
fn columns_by_name(path: &str, line: usize, names: &[String]) -> Result<[usize; 5]> {
    let refuse = |message: String| Error::Parse {
        path: path.into(),
        line,
        message,
    };
    let mut columns = [usize::MAX; 5];
    for (c, name) in names.iter().enumerate() {
        let name = name.trim();
        let Some(k) = NAMES.iter().position(|n| n.eq_ignore_ascii_case(name)) else {
            return Err(refuse(format!(
                "the header's column {} `{}` is not one of i, j, x, y, z (a surface grid has \
                 exactly these five columns, in any order)",
                c + 1,
                super::echo(name)
            )));
        };
        if columns[k] != usize::MAX {
            return Err(refuse(format!(
                "the header names `{}` twice (columns {} and {})",
                NAMES[k],
                columns[k] + 1,
                c + 1
            )));
        }
        columns[k] = c;
    }
    if let Some(k) = columns.iter().position(|&c| c == usize::MAX) {
        return Err(refuse(format!(
            "the header has no `{}` column (a surface grid has the columns i, j, x, y, z, in any order)",
            NAMES[k]
        )));
    }
    Ok(columns)
}

/// Parses an `i,j,x,y,z` grid; every message is one line of bounded length.
pub fn parse(source: &Source) -> Result<SurfaceInput> {
    parse_grid(source).map_err(super::bounded)
}

fn parse_grid(source: &Source) -> Result<SurfaceInput> {
    let path = source.name.as_str();
    let first = source.text.trim_start();
    if first.starts_with('{') || first.starts_with('[') {
        return Err(Error::Invalid {
            path: path.into(),
            message: "surfaces are read from CSV rows i,j,x,y,z".into(),
        });
    }
    let table = Table::parse(source)?;
    let layout = match &table.header {
        Some(header) => columns_by_name(path, header.line, &header.names)?,
        None if table.columns == 5 => [0, 1, 2, 3, 4],
        None => {
            return Err(Error::Parse {
                path: path.into(),
                line: table.first_line(),
                message: format!("{} columns, expected 5 (i,j,x,y,z)", table.columns),
            })
        }
    };
    let mut cells = Vec::with_capacity(table.rows.len());
    for row in &table.rows {
        let [i, j, x, y, z] = layout.map(|c| row.values.get(c).copied().unwrap_or(f64::NAN));
        if !(x.is_finite() && y.is_finite() && z.is_finite()) {
            return Err(Error::Internal {
                message: "grid row without 5 values".into(),
            });
        }
        let (Some(i), Some(j)) = (index(i), index(j)) else {
            return Err(Error::Parse {
                path: path.into(),
                line: row.line,
                message: format!(
                    "indices i={}, j={} must be integers below 1e9 in magnitude",
                    curve_repr::number::Compact(i),
                    curve_repr::number::Compact(j)
                ),
            });
        };
        cells.push((row.line, i, j, Vec3::new(x, y, z)));
    }
    let i_min = cells.iter().map(|c| c.1).min().unwrap_or(0);
    let i_max = cells.iter().map(|c| c.1).max().unwrap_or(0);
    let j_min = cells.iter().map(|c| c.2).min().unwrap_or(0);
    let j_max = cells.iter().map(|c| c.2).max().unwrap_or(0);
    let rows = (i_max - i_min + 1) as usize;
    let columns = (j_max - j_min + 1) as usize;
    let size = rows.checked_mul(columns).filter(|s| *s <= 4 * cells.len() + 16).ok_or_else(|| Error::Invalid {
        path: path.into(),
        message: format!(
            "indices i in {i_min}..={i_max}, j in {j_min}..={j_max} span far more cells than the {} rows given",
            cells.len()
        ),
    })?;
    let mut seen: Vec<Option<usize>> = vec![None; size];
    let mut points = vec![Vec3::zeros(); size];
    let mut order = Vec::with_capacity(cells.len());
    for &(line, i, j, p) in &cells {
        let (gi, gj) = ((i - i_min) as usize, (j - j_min) as usize);
        let k = gi * columns + gj;
        if let Some(first) = seen[k] {
            return Err(Error::Parse {
                path: path.into(),
                line,
                message: format!("cell i={i}, j={j} given twice (first at line {first})"),
            });
        }
        seen[k] = Some(line);
        points[k] = p;
        order.push((gi, gj));
    }
    if let Some(k) = seen.iter().position(Option::is_none) {
        let missing = seen.iter().filter(|s| s.is_none()).count();
        return Err(Error::Invalid {
            path: path.into(),
            message: format!(
                "grid is not rectangular: {missing} of {size} cells missing, the first i={}, j={} \
                 (i in {i_min}..={i_max}, j in {j_min}..={j_max})",
                i_min + (k / columns) as i64,
                j_min + (k % columns) as i64
            ),
        });
    }
    Ok(SurfaceInput {
        grid: Grid {
            rows,
            columns,
            points,
        },
        offset: (i_min, j_min),
        order,
        header: table.header.map(|h| h.text),
        delimiter: table.delimiter,
        columns: layout,
        source: path.into(),
        lines: table.rows.iter().map(|r| r.line).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_text(text: &str) -> Result<SurfaceInput> {
        parse(&Source::from_text("s.csv", text))
    }

    #[test]
    fn reads_grid_with_offset_and_any_order() {
        let s = parse_text("i,j,x,y,z\n1,21,1,1,5\n0,20,0,0,1\n0,21,0,1,2\n1,20,1,0,3\n").unwrap();
        assert_eq!((s.grid.rows, s.grid.columns), (2, 2));
        assert_eq!(s.offset, (0, 20));
        assert_eq!(s.grid.get(1, 1), Some(&Vec3::new(1., 1., 5.)));
        assert_eq!(s.grid.get(0, 1), Some(&Vec3::new(0., 1., 2.)));
        assert_eq!(s.order, vec![(1, 1), (0, 0), (0, 1), (1, 0)]);
        assert_eq!(s.grid.get(2, 0), None);
    }

    #[test]
    fn missing_cell_is_named() {
        let e = parse_text("0,0,0,0,0\n0,1,0,1,0\n1,0,1,0,0\n").unwrap_err();
        assert!(
            e.to_string().contains("1 of 4 cells missing, the first i=1, j=1"),
            "{e}"
        );
        assert_eq!(e.exit_code(), 2);
    }

    #[test]
    fn duplicate_names_both_lines() {
        let e = parse_text("i,j,x,y,z\n0,0,0,0,0\n0,1,0,1,0\n0,0,1,0,0\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "s.csv:4: cell i=0, j=0 given twice (first at line 2)"
        );
    }

    #[test]
    fn bad_rows() {
        let e = parse_text("i,j,x,y,z\n0,0,0,0\n").unwrap_err();
        assert!(e.to_string().starts_with("s.csv:2: "), "{e}");
        let e = parse_text("0,0.5,0,0,0\n").unwrap_err();
        assert!(e.to_string().starts_with("s.csv:1: indices"), "{e}");
        let e = parse_text("0,0\n0,1\n").unwrap_err();
        assert!(e.to_string().contains("expected 5"), "{e}");
        let e = parse_text("0,0,0,0,0\n1000000,1000000,0,0,0\n").unwrap_err();
        assert!(e.to_string().contains("span far more cells"), "{e}");
        let e = parse_text("i,j,x,y,z\n0,0,0,nan,0\n").unwrap_err();
        assert!(e.to_string().starts_with("s.csv:2: "), "{e}");
    }

    /// Columns by the header's names in any order, written back in the same order; a header
    /// naming an unknown column, one twice or missing one is refused with its line.
    #[test]
    fn columns_are_taken_by_name() {
        let by_name = |text: &str| parse_text(text).unwrap();
        let plain = by_name("i,j,x,y,z\n0,0,0,0,1\n0,1,0,1,2\n1,0,1,0,3\n1,1,1,1,5\n");
        let swapped = by_name("j,i,x,y,z\n0,0,0,0,1\n1,0,0,1,2\n0,1,1,0,3\n1,1,1,1,5\n");
        let moved = by_name("x,y,z,i,j\n0,0,1,0,0\n0,1,2,0,1\n1,0,3,1,0\n1,1,5,1,1\n");
        assert_eq!(swapped.grid, plain.grid);
        assert_eq!(moved.grid, plain.grid);
        assert_eq!(swapped.columns, [1, 0, 2, 3, 4]);
        assert_eq!(
            crate::output::format_surface(&swapped, &swapped.grid).unwrap(),
            "j,i,x,y,z\n0,0,0,0,1\n1,0,0,1,2\n0,1,1,0,3\n1,1,1,1,5\n"
        );
        assert_eq!(
            crate::output::format_surface(&moved, &moved.grid).unwrap(),
            "x,y,z,i,j\n0,0,1,0,0\n0,1,2,0,1\n1,0,3,1,0\n1,1,5,1,1\n"
        );
        for (text, needle) in [
            (
                "i,j,x,y,w\n0,0,0,0,0\n",
                "column 5 `w` is not one of i, j, x, y, z",
            ),
            ("i,j,x,y\n0,0,0,0\n", "no `z` column"),
            ("i,j,x,y,z,t\n0,0,0,0,0,0\n", "`t` is not one of"),
            ("i,i,x,y,z\n0,0,0,0,0\n", "names `i` twice"),
        ] {
            let e = parse_text(&format!("# grid\n{text}")).unwrap_err().to_string();
            assert!(e.starts_with("s.csv:2: "), "{e}");
            assert!(e.contains(needle), "{e}");
        }
    }

    #[test]
    fn teapot_net_reads() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../data/surface_utah_teapot/teapot_body_control_net.csv"
        );
        let s = crate::input::read_surface(path).unwrap();
        assert_eq!((s.grid.rows, s.grid.columns), (13, 13));
    }
}
