//! Reading curves and surfaces from files or standard input.
//!
//! Formats (docs/CONTRACT.md, "Commands"):
//! - CSV `x,y` or `x,y,z`, header optional (a first row that is not all numbers is a header),
//!   blank lines and `#` comments skipped, spaces around fields allowed; a file without any
//!   comma is read as whitespace-separated columns;
//! - JSON `{"points": [[x, y], ...]}` (other keys are kept and written back), or a bare array
//!   `[[x, y], ...]`;
//! - airfoil `.dat`: Selig (a name line, then `x y` pairs around the contour) or Lednicer
//!   (a name line, a line with the two point counts, then the upper and the lower surface
//!   each from the leading edge), detected by that counts line; a Lednicer file is turned
//!   into one Selig-ordered contour and written back as Lednicer;
//! - surfaces: CSV `i,j,x,y,z` into a rectangular grid ([`grid`]).
//!
//! `-` reads standard input; its format is sniffed from the content. Every reader is linear
//! in the size of the input and names the file and line of the first error.

mod airfoil;
pub mod columns;
pub mod embedded;
pub mod grid;
mod json;
mod table;

use fair_door::error::{Error, Result};

pub use columns::{Layout, ReadOptions};
pub use grid::{Grid, SurfaceInput};
pub use json::JsonDocument;
pub use table::Delimiter;

/// The points of a curve: the library's type.
pub use fairing::catalog::CurvePoints;

/// How a curve file was written, remembered so that the output is written the same way.
#[derive(Debug, Clone, PartialEq)]
pub enum InputFormat {
    /// Delimited columns.
    Csv {
        /// The header line exactly as read, if the file had one.
        header: Option<String>,
        /// Comma or whitespace.
        delimiter: Delimiter,
        /// Which columns are the coordinates, and the label columns' text.
        layout: Layout,
    },
    /// JSON.
    Json {
        /// The original document: an object whose `points` is replaced on output, or `None`
        /// for a bare top-level array.
        document: Option<JsonDocument>,
    },
    /// Selig airfoil `.dat`: a name line, then the contour.
    Selig {
        /// The name line, trimmed.
        name: String,
    },
    /// Lednicer airfoil `.dat`, held in memory as one Selig-ordered contour.
    Lednicer {
        /// The name line, trimmed.
        name: String,
        /// Points on the upper surface in the file.
        upper: usize,
        /// Points on the lower surface in the file.
        lower: usize,
        /// Whether both surfaces start at the same leading-edge point, kept once in memory.
        shared_leading_edge: bool,
    },
}

/// A curve read from a file: its points, the format to write results in, and where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveInput {
    /// The data points, in file order (Lednicer: Selig order).
    pub points: CurvePoints,
    /// The format they were read in.
    pub format: InputFormat,
    /// The path as given, or `<stdin>`.
    pub source: String,
    /// The line of each point, from 1 (empty when the format does not track lines, as JSON).
    pub lines: Vec<usize>,
    /// What the reader wants the user to know (a file without a header read by position):
    /// printed on standard error unless `-q`.
    pub notes: Vec<String>,
}

impl CurveInput {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there are no points (never true for a successfully read input).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The points as the door takes them: with the file's name and each point's line.
    pub fn data(&self) -> fair_door::CurveData<'_> {
        fair_door::CurveData {
            points: &self.points,
            source: &self.source,
            lines: &self.lines,
        }
    }

    /// The names of the coordinates, abscissa first: the header's names of the columns read
    /// (`z`, `y` for `--columns z,y`), else `x`, `y`[, `z`].
    pub fn coordinate_names(&self) -> Vec<String> {
        match &self.format {
            InputFormat::Csv { layout, .. } => layout.names.clone(),
            _ => ["x", "y", "z"][..self.points.dimension()]
                .iter()
                .map(|s| s.to_string())
                .collect(),
        }
    }

    /// Prints the reader's [`notes`](Self::notes) on standard error (`fair: note: …`), unless
    /// `quiet`.
    pub fn print_notes(&self, quiet: bool) {
        if quiet {
            return;
        }
        for note in &self.notes {
            eprintln!("{}: note: {note}", crate::program_name());
        }
    }
}

/// Whether a source is a surface grid: five comma-separated columns on its first row.
pub fn looks_like_surface(source: &Source) -> bool {
    let first = numbered_lines(&source.text)
        .map(|(_, l)| l.trim())
        .find(|l| !l.is_empty() && !l.starts_with('#'));
    first.is_some_and(|l| l.split(',').count() == 5)
}

/// The lines of a text, numbered from 1. A line ends at `\n`, `\r\n` or a lone `\r` (old Mac
/// files): a file with CR line ends is read line by line, not as one line. O(size).
pub(crate) fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.split('\n')
        .flat_map(|l| l.strip_suffix('\r').unwrap_or(l).split('\r'))
        .enumerate()
        .map(|(i, l)| (i + 1, l))
}

/// The most characters of input a message echoes ([`echo`]).
const ECHO: usize = 120;

/// The longest message a reader gives (characters after `FILE:LINE: `): whatever the input,
/// a refusal is one line that a terminal shows whole.
pub const LONGEST_MESSAGE: usize = 400;

/// A piece of the input as a message quotes it: control characters (line ends, tabs, NUL) as
/// spaces, cut at [`ECHO`] characters with `…`. O(ECHO).
pub(crate) fn echo(text: &str) -> String {
    shorten(text, ECHO)
}

fn shorten(text: &str, limit: usize) -> String {
    let mut out: String = text
        .chars()
        .take(limit)
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    if text.chars().nth(limit).is_some() {
        out.push('…');
    }
    out
}

/// A reader's error made one line of at most [`LONGEST_MESSAGE`] characters: the net under
/// every reader, whatever a message quotes.
pub(crate) fn bounded(error: Error) -> Error {
    match error {
        Error::Parse { path, line, message } => Error::Parse {
            path,
            line,
            message: shorten(&message, LONGEST_MESSAGE),
        },
        Error::Invalid { path, message } => Error::Invalid {
            path,
            message: shorten(&message, LONGEST_MESSAGE),
        },
        Error::Empty { path, reason } => Error::Empty {
            path,
            reason: shorten(&reason, LONGEST_MESSAGE),
        },
        Error::Argument { option, message } => Error::Argument {
            option,
            message: shorten(&message, LONGEST_MESSAGE),
        },
        other => other,
    }
}

/// The text of an input and where it came from.
#[derive(Debug, Clone)]
pub struct Source {
    /// The path as given, or `<stdin>` for `-`.
    pub name: String,
    /// The whole content.
    pub text: String,
    /// The lower-case file extension, if any.
    pub extension: Option<String>,
}

impl Source {
    /// Wraps text already in memory (tests, embedded demo data).
    pub fn from_text(name: &str, text: &str) -> Source {
        Source {
            name: name.to_string(),
            text: text.to_string(),
            extension: extension_of(name),
        }
    }

    /// Reads a file, or standard input for `-`.
    pub fn read(path: &str) -> Result<Source> {
        let (name, bytes) = if path == "-" {
            let mut bytes = Vec::new();
            std::io::Read::read_to_end(&mut std::io::stdin(), &mut bytes).map_err(|e| Error::Read {
                path: "<stdin>".into(),
                reason: e.to_string(),
            })?;
            ("<stdin>".to_string(), bytes)
        } else {
            let bytes = std::fs::read(path).map_err(|e| Error::Read {
                path: path.into(),
                reason: io_reason(&e),
            })?;
            (path.to_string(), bytes)
        };
        let text = match String::from_utf8(bytes) {
            Ok(text) => text,
            Err(e) => {
                let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
                // Lines as the readers count them: `\n`, `\r\n` or a lone `\r` ends one.
                let ends = valid
                    .iter()
                    .enumerate()
                    .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && valid.get(i + 1) != Some(&b'\n')))
                    .count();
                let line = 1 + ends;
                return Err(Error::Parse {
                    path: name,
                    line,
                    message: "not UTF-8 text".into(),
                });
            }
        };
        let extension = if path == "-" { None } else { extension_of(path) };
        Ok(Source {
            name,
            text,
            extension,
        })
    }
}

/// The operating system's reason for an I/O failure, without the "(os error 2)" suffix.
pub(crate) use fair_door::error::io_reason;

fn extension_of(path: &str) -> Option<String> {
    std::path::Path::new(path)
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
}

/// The curve format of a source: JSON by extension or a first `{`/`[`; a table whose first
/// line is a header naming its columns ([`names_columns`]), whatever the extension; then an
/// airfoil by `.dat`, or by a name line (no comma, not all numbers) followed by a line of
/// whitespace-separated numbers; else a table.
fn sniff(source: &Source, options: &ReadOptions) -> Sniffed {
    match source.extension.as_deref() {
        Some("json") => return Sniffed::Json,
        Some("csv") => return Sniffed::Table,
        _ => {}
    }
    let first = source.text.trim_start();
    if source.extension.as_deref() != Some("dat") && (first.starts_with('{') || first.starts_with('[')) {
        return Sniffed::Json;
    }
    let mut lines = numbered_lines(&source.text)
        .map(|(_, l)| l.trim().trim_start_matches('\u{feff}'))
        .filter(|l| !l.is_empty() && !l.starts_with('#'));
    let (head, next) = (lines.next(), lines.next());
    if let (Some(head), Some(next)) = (head, next) {
        if names_columns(head, next, options) {
            return Sniffed::Table;
        }
    }
    if source.extension.as_deref() == Some("dat") {
        return Sniffed::Airfoil;
    }
    match (head, next) {
        // A name line with no comma and not all numbers, then whitespace-separated numbers.
        (Some(head), Some(next))
            if !head.contains(',')
                && !table::all_numeric(head, Delimiter::Whitespace)
                && !next.contains(',')
                && table::all_numeric(next, Delimiter::Whitespace) =>
        {
            Sniffed::Airfoil
        }
        _ => Sniffed::Table,
    }
}

/// Whether a whitespace-separated first line is a table's header rather than an airfoil's
/// name: it has as many words as the next line has fields, and among its words (compared
/// without case, quotes removed) are the coordinate columns (`x` and `y`, or the names
/// `--columns` gives). `y x` over `0 1` is a header; `NACA 0012` over `1 0` is a name.
fn names_columns(head: &str, next: &str, options: &ReadOptions) -> bool {
    if head.contains(',') || next.contains(',') {
        return false;
    }
    let words: Vec<&str> = head.split_whitespace().map(|w| w.trim_matches('"')).collect();
    if words.len() != next.split_whitespace().count() {
        return false;
    }
    let default = ["x".to_string(), "y".to_string()];
    let wanted = options.columns.as_deref().unwrap_or(&default);
    wanted
        .iter()
        .all(|name| words.iter().any(|w| w.eq_ignore_ascii_case(name.trim())))
}

enum Sniffed {
    Table,
    Json,
    Airfoil,
}

/// Reads a curve from `path` (`-` for standard input).
///
/// Fails with the file and line of the first problem; a file without any point is
/// [`Error::Empty`]. The minimum number of points is the caller's to check
/// ([`fair_door::CurveData::require_at_least`]).
pub fn read_curve(path: &str) -> Result<CurveInput> {
    parse_curve(&Source::read(path)?)
}

/// [`read_curve`] with `--columns` ([`ReadOptions`]).
pub fn read_curve_with(path: &str, options: &ReadOptions) -> Result<CurveInput> {
    parse_curve_with(&Source::read(path)?, options)
}

/// Parses a curve from text already read; see [`read_curve`].
pub fn parse_curve(source: &Source) -> Result<CurveInput> {
    parse_curve_with(source, &ReadOptions::default())
}

/// Parses a curve from text already read, with `--columns`: a table's coordinate columns by
/// name ([`columns`]). `--columns` is refused for JSON and airfoil files, whose coordinates
/// are not named columns.
pub fn parse_curve_with(source: &Source, options: &ReadOptions) -> Result<CurveInput> {
    let sniffed = sniff(source, options);
    if options.columns.is_some() && !matches!(sniffed, Sniffed::Table) {
        return Err(Error::Argument {
            option: "--columns",
            message: format!(
                "{}: only CSV and whitespace tables have named columns; this is {}",
                source.name,
                if matches!(sniffed, Sniffed::Json) {
                    "JSON"
                } else {
                    "an airfoil .dat"
                }
            ),
        });
    }
    match sniffed {
        Sniffed::Json => json::parse(source),
        Sniffed::Airfoil => airfoil::parse(source),
        Sniffed::Table => columns::parse(source, options),
    }
    .map_err(bounded)
}

/// Reads a surface grid `i,j,x,y,z` from `path` (`-` for standard input).
pub fn read_surface(path: &str) -> Result<SurfaceInput> {
    grid::parse(&Source::read(path)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::{Vec2, Vec3};

    fn parse(name: &str, text: &str) -> Result<CurveInput> {
        parse_curve(&Source::from_text(name, text))
    }

    #[test]
    fn csv_with_header() {
        let c = parse("a.csv", "x,y\n0,1\n1, 2\n 2 ,3\n").unwrap();
        assert_eq!(
            c.points,
            CurvePoints::Planar(vec![Vec2::new(0., 1.), Vec2::new(1., 2.), Vec2::new(2., 3.)])
        );
        assert_eq!(
            c.format,
            InputFormat::Csv {
                header: Some("x,y".into()),
                delimiter: Delimiter::Comma,
                layout: Layout {
                    columns: 2,
                    coordinates: vec![0, 1],
                    names: vec!["x".to_string(), "y".to_string()],
                    labels: Vec::new(),
                }
            }
        );
        assert_eq!(c.lines, vec![2, 3, 4]);
    }

    #[test]
    fn csv_without_header_spatial() {
        let c = parse("a.csv", "0,1,2\n\n# comment\n3,4,5e-1\n").unwrap();
        assert_eq!(
            c.points,
            CurvePoints::Spatial(vec![Vec3::new(0., 1., 2.), Vec3::new(3., 4., 0.5)])
        );
        assert_eq!(
            c.format,
            InputFormat::Csv {
                header: None,
                delimiter: Delimiter::Comma,
                layout: Layout {
                    columns: 3,
                    coordinates: vec![0, 1, 2],
                    names: vec!["x".to_string(), "y".to_string(), "z".to_string()],
                    labels: Vec::new(),
                }
            }
        );
        assert_eq!(c.lines, vec![1, 4]);
    }

    #[test]
    fn label_columns_are_carried_and_written_back() {
        let text = "x,y,z,source\n1,0.75,0,buttock\n1,9,4.125,waterline\n1,18,8.75,buttock\n";
        let c = parse("station.csv", text).unwrap();
        assert_eq!(c.len(), 3);
        assert_eq!(c.points.dimension(), 3);
        let CurvePoints::Spatial(points) = &c.points else {
            panic!("3D points expected")
        };
        assert_eq!(points[1], Vec3::new(1.0, 9.0, 4.125));
        // Written back with the labels in place, moved values where they were.
        let mut moved = points.clone();
        moved[1].y = 9.5;
        let written = crate::output::format_curve(&c, &CurvePoints::Spatial(moved)).unwrap();
        assert_eq!(
            written,
            "x,y,z,source\n1,0.75,0,buttock\n1,9.5,4.125,waterline\n1,18,8.75,buttock\n"
        );
        // A label in a coordinate column is still an error naming the line.
        let e = parse("station.csv", "x,y,z,source\n1,2,3,a\n1,oops,3,b\n").unwrap_err();
        assert!(
            e.one_line().starts_with("station.csv:3: column 2 (y)"),
            "{}",
            e.one_line()
        );
    }

    /// Columns by name in any order; every other column a label, numeric or not, written
    /// back as read; `--columns` picks the coordinates and the abscissa.
    #[test]
    fn columns_are_taken_by_name() {
        let c = parse("s.csv", "y,x,w\n5,0,1\n6,1,2\n7,3,3\n").unwrap();
        assert_eq!(
            c.points,
            CurvePoints::Planar(vec![Vec2::new(0., 5.), Vec2::new(1., 6.), Vec2::new(3., 7.)])
        );
        assert_eq!(c.coordinate_names(), ["x", "y"]);
        assert!(c.notes.is_empty());
        let moved = CurvePoints::Planar(vec![Vec2::new(0., 5.5), Vec2::new(1., 6.), Vec2::new(3., 7.)]);
        assert_eq!(
            crate::output::format_curve(&c, &moved).unwrap(),
            "y,x,w\n5.5,0,1\n6,1,2\n7,3,3\n"
        );
        let options = ReadOptions::with_columns(Some(vec!["z".into(), "Y".into()]));
        let c = parse_curve_with(
            &Source::from_text("h.csv", "x,y,z\n9,1,0\n9,2,1\n9,3,2\n"),
            &options,
        )
        .unwrap();
        assert_eq!(
            c.points,
            CurvePoints::Planar(vec![Vec2::new(0., 1.), Vec2::new(1., 2.), Vec2::new(2., 3.)])
        );
        assert_eq!(c.coordinate_names(), ["z", "y"]);
        let moved = CurvePoints::Planar(vec![Vec2::new(0., 1.), Vec2::new(1., 2.25), Vec2::new(2., 3.)]);
        assert_eq!(
            crate::output::format_curve(&c, &moved).unwrap(),
            "x,y,z\n9,1,0\n9,2.25,1\n9,3,2\n"
        );
        // Headerless: by position, with a note; --columns by the same letters.
        let c = parse_curve_with(&Source::from_text("p.csv", "0,1,2\n1,2,3\n"), &options).unwrap();
        assert_eq!(
            c.points,
            CurvePoints::Planar(vec![Vec2::new(2., 1.), Vec2::new(3., 2.)])
        );
        assert_eq!(c.notes.len(), 1);
        assert!(c.notes[0].contains("no header"), "{:?}", c.notes);
        for (text, columns, needle) in [
            ("a,b\n1,2\n", None, "no `x` column"),
            (
                "x,y\n1,2\n",
                Some(vec!["x".to_string(), "q".to_string()]),
                "no column `q`",
            ),
            ("x,y\n1,2\n", Some(vec!["x".to_string()]), "give 2"),
            (
                "x,y\n1,2\n",
                Some(vec!["x".to_string(), "X".to_string()]),
                "twice",
            ),
            ("x,X,y\n1,2,3\n", None, "twice"),
        ] {
            let e = parse_curve_with(
                &Source::from_text("e.csv", text),
                &ReadOptions::with_columns(columns),
            )
            .unwrap_err();
            assert!(e.to_string().contains(needle), "{e}");
        }
        let e = parse_curve_with(&Source::from_text("j.json", "[[0, 1], [1, 2]]"), &options).unwrap_err();
        assert!(e.to_string().contains("--columns"), "{e}");
    }

    /// A whitespace table with a header is read by the header's names, not taken for an
    /// airfoil's name line: `y x` puts the second column in x, from a file or standard input.
    #[test]
    fn whitespace_header_is_read_by_name() {
        for name in ["t.txt", "-", "t.dat"] {
            let c = parse(name, "y x\n0 1\n1 2\n4 3\n").unwrap();
            assert_eq!(
                c.points,
                CurvePoints::Planar(vec![Vec2::new(1., 0.), Vec2::new(2., 1.), Vec2::new(3., 4.)]),
                "{name}"
            );
            assert!(
                matches!(&c.format, InputFormat::Csv { header: Some(h), delimiter: Delimiter::Whitespace, .. } if h == "y x"),
                "{name}: {:?}",
                c.format
            );
            assert_eq!(c.lines, vec![2, 3, 4]);
        }
        // Labels and z by name too; a name line is still a name line.
        let c = parse("-", "station Z X Y\nA 0 1 2\nB 1 2 3\n").unwrap();
        assert_eq!(
            c.points,
            CurvePoints::Spatial(vec![Vec3::new(1., 2., 0.), Vec3::new(2., 3., 1.)])
        );
        let c = parse("-", "NACA 0012\n1 0\n0 0\n1 0.1\n").unwrap();
        assert!(matches!(c.format, InputFormat::Selig { .. }), "{:?}", c.format);
        // --columns names the coordinates of a whitespace header.
        let options = ReadOptions::with_columns(Some(vec!["z".into(), "y".into()]));
        let c = parse_curve_with(&Source::from_text("-", "y z\n5 0\n6 1\n"), &options).unwrap();
        assert_eq!(
            c.points,
            CurvePoints::Planar(vec![Vec2::new(0., 5.), Vec2::new(1., 6.)])
        );
    }

    /// Old Mac files (CR line ends) are read line by line, with the right line numbers.
    #[test]
    fn cr_line_ends_are_line_ends() {
        let c = parse("m.csv", "x,y\r0,1\r1,2\r2,3\r").unwrap();
        assert_eq!(c.len(), 3);
        assert_eq!(c.lines, vec![2, 3, 4]);
        let e = parse("m.csv", "x,y\r0,1\r1,oops\r").unwrap_err();
        assert!(e.to_string().starts_with("m.csv:3: "), "{e}");
        let c = parse("m.dat", "FOIL\r1 0\r0 0\r1 0.1\r").unwrap();
        assert_eq!(c.len(), 3);
    }

    /// Bytes that are not UTF-8 are named by their line, CR line ends counted like the readers'.
    #[test]
    fn invalid_utf8_names_its_line_with_cr_ends() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("mac.csv");
        std::fs::write(&path, b"x,y\r0,1\r\n1,2\r2,\xff\r").unwrap();
        let e = read_curve(path.to_str().unwrap()).unwrap_err().to_string();
        assert!(e.ends_with("mac.csv:4: not UTF-8 text"), "{e}");
    }

    /// However long the garbage, a message is one line quoting at most a few hundred
    /// characters of it.
    #[test]
    fn messages_are_one_short_line() {
        let long = "7".repeat(100_000);
        let huge_header = format!("a{}\r", "b\r".repeat(50_000));
        for (name, text) in [
            ("l.csv", format!("x,y\n0,{long}x\n")),
            ("l.csv", format!("q{long},w\n1,2\n")),
            ("l.txt", huge_header.clone()),
            ("l.dat", format!("NAME\n1 {long}z\n")),
            (
                "l.json",
                format!("{{\"points\": [[0, 1]], \"{long}\": 1, \"{long}\": 2}}"),
            ),
        ] {
            let e = parse(name, &text).unwrap_err().one_line();
            assert!(
                e.chars().count() <= 500 && !e.contains(['\n', '\r']),
                "{name}: {} chars",
                e.len()
            );
        }
        let e = grid::parse(&Source::from_text(
            "g.csv",
            &format!("i,j,x,y,{long}\n0,0,0,0,0\n"),
        ))
        .unwrap_err();
        assert!(
            e.to_string().chars().count() <= 500,
            "{} chars",
            e.to_string().len()
        );
    }

    /// A CSV label is written back exactly, spaces included.
    #[test]
    fn labels_keep_their_spaces() {
        let text = "x,y, note \n0,1,  left \n1,2,right  \n2,3, \n";
        let c = parse("s.csv", text).unwrap();
        assert_eq!(crate::output::format_curve(&c, &c.points).unwrap(), text);
    }

    #[test]
    fn whitespace_columns() {
        let c = parse("a.txt", "0 1\n1\t2\n").unwrap();
        assert_eq!(c.len(), 2);
        assert_eq!(
            c.format,
            InputFormat::Csv {
                header: None,
                delimiter: Delimiter::Whitespace,
                layout: Layout {
                    columns: 2,
                    coordinates: vec![0, 1],
                    names: vec!["x".to_string(), "y".to_string()],
                    labels: Vec::new(),
                }
            }
        );
    }

    #[test]
    fn empty_file() {
        let e = parse("e.csv", "").unwrap_err();
        assert!(matches!(e, Error::Empty { .. }), "{e}");
        assert!(e.to_string().starts_with("e.csv: "), "{e}");
        let e = parse("h.csv", "x,y\n\n").unwrap_err();
        assert!(matches!(e, Error::Empty { .. }), "{e}");
    }

    #[test]
    fn one_point_is_returned_and_caller_decides() {
        let c = parse("one.csv", "x,y\n1,2\n").unwrap();
        assert_eq!(c.len(), 1);
        let e = c.data().require_at_least(3, "a curve").unwrap_err();
        assert_eq!(e.to_string(), "one.csv: 1 point, a curve needs at least 3");
        assert_eq!(e.exit_code(), 2);
    }

    #[test]
    fn text_in_number_column_names_line() {
        let e = parse("t.csv", "x,y\n0,1\n1,abc\n").unwrap_err();
        assert!(e.to_string().starts_with("t.csv:3: "), "{e}");
        assert!(e.to_string().contains("abc"), "{e}");
    }

    #[test]
    fn nan_and_infinity_are_rejected() {
        for bad in ["NaN", "inf", "-infinity", "1e999"] {
            let e = parse("n.csv", &format!("0,1\n1,{bad}\n2,3\n")).unwrap_err();
            assert!(e.to_string().starts_with("n.csv:2: "), "{e}");
            assert!(e.to_string().contains("not finite"), "{e}");
        }
    }

    #[test]
    fn mismatched_columns_name_line() {
        let e = parse("m.csv", "x,y\n0,1\n1,2\n2,3,4\n").unwrap_err();
        assert!(e.to_string().starts_with("m.csv:4: "), "{e}");
        assert!(e.to_string().contains("3 fields"), "{e}");
        let e = parse("m.csv", "x,y,z\n0,1\n").unwrap_err();
        assert!(e.to_string().starts_with("m.csv:2: "), "{e}");
    }

    #[test]
    fn wrong_column_count() {
        let e = parse("w.csv", "1\n2\n").unwrap_err();
        assert!(
            e.to_string().starts_with("w.csv:1: 1 columns without a header"),
            "{e}"
        );
        let e = parse("g.csv", "i,j,x,y,z\n0,0,1,2,3\n").unwrap_err();
        assert!(e.to_string().contains("fair surface"), "{e}");
    }

    #[test]
    fn missing_file() {
        let e = read_curve("/nonexistent/surely/not/here.csv").unwrap_err();
        assert_eq!(
            e.to_string(),
            "/nonexistent/surely/not/here.csv: cannot read: no such file or directory"
        );
        assert_eq!(e.exit_code(), 2);
    }

    #[test]
    fn json_object_and_array() {
        let c = parse("a.json", "{\"name\": \"s\", \"points\": [[0, 1], [2.5, 3]]}").unwrap();
        assert_eq!(
            c.points,
            CurvePoints::Planar(vec![Vec2::new(0., 1.), Vec2::new(2.5, 3.)])
        );
        assert!(matches!(&c.format, InputFormat::Json { document: Some(d) } if d.contains_key("name")));
        let c = parse("-", "[[0, 1, 2], [2, 3, 4]]").unwrap();
        assert_eq!(c.points.dimension(), 3);
        assert!(matches!(c.format, InputFormat::Json { document: None }));
    }

    /// Other keys round-trip exactly: order, a 23-digit integer, nested values; a key given
    /// twice is refused with its line.
    #[test]
    fn json_other_keys_round_trip_exactly() {
        let text = "{\"zeta\": 1, \"id\": 12345678901234567890123, \"points\": [[0, 1], [1, 2]], \"alpha\": {\"b\": [1.50, 2e400]}}";
        let c = parse("k.json", text).unwrap();
        let written = crate::output::format_curve(&c, &c.points).unwrap();
        let (zeta, id, points, alpha) = (
            written.find("\"zeta\"").unwrap(),
            written.find("\"id\": 12345678901234567890123,").unwrap(),
            written.find("\"points\"").unwrap(),
            written.find("\"alpha\": {\"b\": [1.50, 2e400]}").unwrap(),
        );
        assert!(zeta < id && id < points && points < alpha, "{written}");
        let e = parse("k.json", "{\"points\": [[0, 1], [1, 2]],\n \"a\": 1,\n \"a\": 2}").unwrap_err();
        assert!(
            e.to_string().starts_with("k.json:3: the key `a` is given twice"),
            "{e}"
        );
        let e = parse("k.json", "{\"points\": [[0, 1]],\n\"points\": [[0, 1]]}").unwrap_err();
        assert!(e.to_string().starts_with("k.json:2: "), "{e}");
        // A kept value nested 100 000 deep is skipped without recursion and written back whole;
        // points nested deeper than a point are refused at once.
        let nest = |depth: usize| format!("{}{}", "[".repeat(depth), "]".repeat(depth));
        let deep = format!("{{\"points\": [[0, 1]], \"d\": {}}}", nest(100_000));
        let c = parse("k.json", &deep).map_err(|e| e.to_string()).unwrap();
        let written = crate::output::format_curve(&c, &c.points).unwrap();
        assert!(written.contains(&nest(100_000)));
        let e = parse("k.json", &nest(100_000)).unwrap_err().to_string();
        assert!(e.starts_with("k.json:1: invalid type: sequence"), "{e}");
    }

    #[test]
    fn json_errors_name_line() {
        let e = parse("j.json", "{\"points\": [\n[0, 1],\n[1, \"a\"]\n]}").unwrap_err();
        assert!(e.to_string().starts_with("j.json:3: "), "{e}");
        let e = parse("j.json", "{\"points\": [\n[0, 1],\n[1, 2, 3]\n]}").unwrap_err();
        assert!(e.to_string().starts_with("j.json:3: "), "{e}");
        assert!(e.to_string().contains("3 coordinates"), "{e}");
        let e = parse("j.json", "{\"points\": [\n[0, 1],\n[1]\n]}").unwrap_err();
        assert!(e.to_string().starts_with("j.json:3: "), "{e}");
        let e = parse("j.json", "{\"points\": [\n[0, 1],\n[1, 2],\n").unwrap_err();
        assert!(matches!(e, Error::Parse { .. }), "{e}");
        let e = parse("j.json", "{\"points\": []}").unwrap_err();
        assert!(matches!(e, Error::Empty { .. }), "{e}");
        let e = parse("j.json", "{\"pts\": []}").unwrap_err();
        assert!(e.to_string().contains("points"), "{e}");
        let e = parse("j.json", "{\"points\": [[0, 1e999]]}").unwrap_err();
        assert!(e.to_string().starts_with("j.json:1: "), "{e}");
    }

    #[test]
    fn selig() {
        let c = parse(
            "a.dat",
            "NACA 0012\n 1.0 0.0\n 0.5 0.05\n 0.0 0.0\n 0.5 -0.05\n 1.0 0.0\n",
        )
        .unwrap();
        assert_eq!(c.len(), 5);
        assert_eq!(
            c.format,
            InputFormat::Selig {
                name: "NACA 0012".into()
            }
        );
        assert_eq!(c.lines, vec![2, 3, 4, 5, 6]);
        // sniffed without extension
        let c = parse("-", "my foil\n1 0\n0 0\n1 0.1\n").unwrap();
        assert!(matches!(c.format, InputFormat::Selig { .. }));
        let e = parse("a.dat", "NACA\n1.0 0.0\n0.5 x\n").unwrap_err();
        assert!(e.to_string().starts_with("a.dat:3: "), "{e}");
        let e = parse("a.dat", "NACA\n1.0 0.0\n0.5 0.1 0.2\n").unwrap_err();
        assert!(e.to_string().starts_with("a.dat:3: "), "{e}");
        let e = parse("a.dat", "NACA\n").unwrap_err();
        assert!(matches!(e, Error::Empty { .. }), "{e}");
        // No name line: the first pair is a point, not a name to drop.
        let e = parse("a.dat", "\n1.0 0.0\n0.5 0.06\n0.0 0.0\n0.5 -0.05\n1.0 0.001\n").unwrap_err();
        assert!(e.to_string().starts_with("a.dat:2: "), "{e}");
        assert!(e.to_string().contains("name line"), "{e}");
    }

    #[test]
    fn lednicer_becomes_selig_order() {
        let text = "FOIL\n3. 3.\n\n0 0\n0.5 0.1\n1 0\n\n0 0\n0.5 -0.1\n1 0\n";
        let c = parse("l.dat", text).unwrap();
        let expected = vec![
            Vec2::new(1., 0.),
            Vec2::new(0.5, 0.1),
            Vec2::new(0., 0.),
            Vec2::new(0.5, -0.1),
            Vec2::new(1., 0.),
        ];
        assert_eq!(c.points, CurvePoints::Planar(expected));
        assert_eq!(
            c.format,
            InputFormat::Lednicer {
                name: "FOIL".into(),
                upper: 3,
                lower: 3,
                shared_leading_edge: true
            }
        );
        assert_eq!(c.lines, vec![6, 5, 4, 9, 10]);
        let e = parse("l.dat", "FOIL\n3. 3.\n0 0\n0.5 0.1\n1 0\n0 0\n").unwrap_err();
        assert!(e.to_string().contains("3 + 3"), "{e}");
    }
}
