//! Tables of offsets as they come: the long form (`line,station_index,station_name,x,
//! half_breadth,height[,kind]`), the block form of Chapelle's tables (`block,line,
//! station_index,station_name,value…` with blocks FORE-AFT POSITION, HEIGHT, BREADTH) and the
//! vessel.js grid (`i,j,x,y,z`). Axes: x fore-aft, y half-breadth, z height.
//!
//! A cell is one offset: a point of one line at one station. Waterlines fix z, buttocks fix y,
//! stations fix x; the cell's *free* coordinates are the measured ones (y of a waterline, z of a
//! buttock, y and z of an edge line such as the sheer). The table keeps its file's rows so that
//! the faired values can be written back in the same layout.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use serde::Serialize;

use crate::error::{io, Error, Result};

/// What a line of the plan is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// A plane cut at fixed height z: half-breadths y(x).
    Waterline,
    /// A plane cut at fixed half-breadth y: heights z(x).
    Buttock,
    /// An edge line with both y and z (sheer, chine, rabbet, keel, girth lines).
    Edge,
    /// An edge line seen in profile only (heights, no half-breadths).
    Profile,
    /// An edge line seen in plan only (half-breadths, no heights).
    Plan,
}

/// A coordinate of a cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Coord {
    /// Fore-aft position.
    X,
    /// Half-breadth.
    Y,
    /// Height.
    Z,
}

/// The file layout a table came in (and is written back in).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Layout {
    /// `line,station_index,station_name,x,half_breadth,height[,kind]`.
    Long,
    /// `block,line,station_index,station_name,value…`.
    Block,
    /// `i,j,x,y,z`: waterline i, station j.
    Grid,
}

/// One line of the plan.
#[derive(Clone, Debug, Serialize)]
pub struct Line {
    /// The label as in the file.
    pub label: String,
    /// Its family.
    pub kind: Kind,
    /// The plane coordinate: a waterline's z, a buttock's y.
    pub plane: Option<f64>,
    /// Whether it is a knuckle (a G0 break of the hull: chine, declared knuckle).
    pub knuckle: bool,
}

/// One offset: line `line` (index into [`Table::lines`]) at station `station_index`.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// Index of its line in [`Table::lines`].
    pub line: usize,
    /// The station index as in the file.
    pub station_index: i64,
    /// The station name as in the file.
    pub station_name: String,
    /// Fore-aft position.
    pub x: f64,
    /// Half-breadth (NaN for a profile-only line).
    pub y: f64,
    /// Height (NaN for a plan-only line).
    pub z: f64,
    /// Whether the cell lies in its station's plane (the x most cells of that index share);
    /// a waterline's end at the stem does not.
    pub on_station: bool,
}

impl Cell {
    /// The coordinate of index k (0 = x, 1 = y, 2 = z).
    pub(crate) fn get_index(&self, k: usize) -> f64 {
        [self.x, self.y, self.z][k]
    }

    /// The coordinate of index k: 0 = x, 1 = y, 2 = z (panics for another k).
    pub fn get_coord(&self, k: usize) -> f64 {
        self.get_index(k)
    }

    /// The coordinate `c`.
    pub fn get(&self, c: Coord) -> f64 {
        match c {
            Coord::X => self.x,
            Coord::Y => self.y,
            Coord::Z => self.z,
        }
    }
}

#[derive(Clone, Debug)]
pub(crate) struct Record {
    pub fields: Vec<String>,
    /// (cell, coordinate, column) the row holds.
    pub refs: Vec<(usize, Coord, usize)>,
}

/// A table of offsets.
#[derive(Clone, Debug)]
pub struct Table {
    /// The file it was read from.
    pub path: String,
    /// Its layout.
    pub layout: Layout,
    /// The length unit, where the file says it (a value column `value_in`, a file name ending
    /// `_m`, `_mm`, `_in`/`_inches`, `_ft`).
    pub units: Option<String>,
    /// The lines, in file order.
    pub lines: Vec<Line>,
    /// The offsets.
    pub cells: Vec<Cell>,
    /// Station index → (name, x) of every station plane.
    pub stations: BTreeMap<i64, (String, f64)>,
    /// The rounding step inferred from the values (the largest of 1, 1/2 … 1/32, 0.1, 0.01 …
    /// 10⁻⁶ that every value is a multiple of; else 10^−decimals).
    pub step: f64,
    /// Rows of the file, with the cells each holds (to write the table back).
    pub(crate) header: Vec<String>,
    pub(crate) records: Vec<Record>,
    /// Cells dropped as read (no x): (line label, station index).
    pub dropped: Vec<(String, i64)>,
}

fn parse_num(s: &str) -> Option<f64> {
    let t = s.trim();
    if t.is_empty()
        || matches!(
            t.to_ascii_lowercase().as_str(),
            "nan" | "null" | "none" | "x" | "-"
        )
    {
        return None;
    }
    t.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// The number of a label ending in `(<number><unit>)`, e.g. `0-54-0 (54in)` → 54.
pub fn label_number(label: &str) -> Option<f64> {
    let t = label.trim_end();
    let inner = t.strip_suffix(')')?;
    let open = inner.rfind('(')?;
    let body = inner[open + 1..].trim();
    let end = body
        .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')))
        .unwrap_or(body.len());
    let (num, unit) = body.split_at(end);
    if !unit
        .trim()
        .chars()
        .all(|c| c.is_ascii_alphabetic() || c == '"' || c == '\'')
    {
        return None;
    }
    num.parse().ok()
}

fn starts_word(label: &str, words: &[&str]) -> bool {
    let l = label.to_ascii_lowercase();
    words.iter().any(|w| {
        l.starts_with(w)
            && !l[w.len()..]
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphabetic())
    })
}

fn is_knuckle_name(label: &str) -> bool {
    let l = label.to_ascii_lowercase();
    l.contains("chine") || l.contains("knuckle")
}

struct Rows {
    path: String,
    header: Vec<String>,
    header_line: usize,
    rows: Vec<(usize, Vec<String>)>,
}

fn read_rows(path: &Path) -> Result<Rows> {
    let text = std::fs::read_to_string(path).map_err(|e| io(path, e))?;
    let p = path.display().to_string();
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(text.as_bytes());
    let mut all = Vec::new();
    for rec in reader.records() {
        let rec = rec.map_err(|e| Error::Table {
            path: p.clone(),
            line: e.position().map_or(0, |q| q.line() as usize),
            message: format!("not CSV: {e}"),
        })?;
        let line = rec.position().map_or(0, |q| q.line() as usize);
        let fields: Vec<String> = rec.iter().map(|s| s.trim().to_string()).collect();
        if fields.iter().all(String::is_empty) || fields[0].starts_with('#') {
            continue;
        }
        all.push((line, fields));
    }
    let Some((header_line, header)) = (!all.is_empty()).then(|| all.remove(0)) else {
        return Err(Error::Table {
            path: p,
            line: 0,
            message: "empty file: no header".into(),
        });
    };
    Ok(Rows {
        path: p,
        header,
        header_line,
        rows: all,
    })
}

fn units_of(path: &Path, header: &[String]) -> Option<String> {
    for h in header {
        let h = h.to_ascii_lowercase();
        if let Some(u) = h.strip_prefix("value_") {
            return Some(u.to_string());
        }
    }
    let stem = path.file_stem()?.to_str()?.to_ascii_lowercase();
    for (suffix, unit) in [
        ("_inches", "in"),
        ("_in", "in"),
        ("_mm", "mm"),
        ("_m", "m"),
        ("_ft", "ft"),
    ] {
        if stem.ends_with(suffix) {
            return Some(unit.to_string());
        }
    }
    None
}

/// Reads a table of offsets, the layout detected from its header (`#` lines are comments).
///
/// Fails with [`Error::Io`] when the file cannot be read and [`Error::Table`] (file and line)
/// when it is not a table of offsets: an unknown header, a missing or non-numeric value, a
/// station index that is not an integer, an unknown block, a grid row whose z varies, a
/// duplicate cell, or no cell at all.
pub fn read_table(path: impl AsRef<Path>) -> Result<Table> {
    let path = path.as_ref();
    let rows = read_rows(path)?;
    let lower: Vec<String> = rows.header.iter().map(|h| h.to_ascii_lowercase()).collect();
    let has = |n: &str| lower.iter().any(|h| h == n);
    let layout = if has("block") && has("line") {
        Layout::Block
    } else if ["line", "station_index", "x", "half_breadth", "height"]
        .iter()
        .all(|n| has(n))
    {
        Layout::Long
    } else if ["i", "j", "x", "y", "z"].iter().all(|n| has(n)) {
        Layout::Grid
    } else {
        return Err(Error::Table {
            path: rows.path,
            line: rows.header_line,
            message: format!(
                "not a table of offsets: header {:?} is none of line,station_index,station_name,x,half_breadth,height / block,line,station_index,station_name,value / i,j,x,y,z",
                rows.header
            ),
        });
    };
    let mut t = Table {
        path: rows.path.clone(),
        layout,
        units: units_of(path, &rows.header),
        lines: Vec::new(),
        cells: Vec::new(),
        stations: BTreeMap::new(),
        step: 0.0,
        header: rows.header.clone(),
        records: Vec::new(),
        dropped: Vec::new(),
    };
    match layout {
        Layout::Long => read_long(&mut t, &rows, &lower)?,
        Layout::Block => read_block(&mut t, &rows, &lower)?,
        Layout::Grid => read_grid(&mut t, &rows, &lower)?,
    }
    if t.cells.is_empty() {
        return Err(Error::Table {
            path: t.path,
            line: 0,
            message: "no offset in the table".into(),
        });
    }
    t.finish();
    Ok(t)
}

struct Ctx<'a> {
    path: &'a str,
}

impl Ctx<'_> {
    fn err(&self, line: usize, message: String) -> Error {
        Error::Table {
            path: self.path.to_string(),
            line,
            message,
        }
    }
    fn field<'r>(&self, line: usize, row: &'r [String], col: usize, name: &str) -> Result<&'r str> {
        row.get(col)
            .map(String::as_str)
            .ok_or_else(|| self.err(line, format!("row has no `{name}` column")))
    }
    fn index(&self, line: usize, s: &str) -> Result<i64> {
        let v = s
            .trim()
            .parse::<f64>()
            .map_err(|_| self.err(line, format!("station index `{s}` is not a number")))?;
        if v.fract() != 0.0 || !v.is_finite() {
            return Err(self.err(line, format!("station index `{s}` is not an integer")));
        }
        Ok(v as i64)
    }
    fn number(&self, line: usize, s: &str, name: &str) -> Result<Option<f64>> {
        let t = s.trim();
        match parse_num(t) {
            Some(v) => Ok(Some(v)),
            None if t.is_empty()
                || matches!(
                    t.to_ascii_lowercase().as_str(),
                    "nan" | "null" | "none" | "x" | "-"
                ) =>
            {
                Ok(None)
            }
            None => Err(self.err(line, format!("{name} `{s}` is not a number"))),
        }
    }
}

fn col(lower: &[String], name: &str) -> Option<usize> {
    lower.iter().position(|h| h == name)
}

fn read_long(t: &mut Table, rows: &Rows, lower: &[String]) -> Result<()> {
    let cx = Ctx { path: &rows.path };
    let (cl, cs, cn, cxc, cy, cz, ck) = (
        col(lower, "line").unwrap_or(0),
        col(lower, "station_index").unwrap_or(0),
        col(lower, "station_name"),
        col(lower, "x").unwrap_or(0),
        col(lower, "half_breadth").unwrap_or(0),
        col(lower, "height").unwrap_or(0),
        col(lower, "kind"),
    );
    struct Item {
        line: usize,
        si: i64,
        name: String,
        x: Option<f64>,
        y: Option<f64>,
        z: Option<f64>,
        row: usize,
    }
    let mut order: Vec<String> = Vec::new();
    let mut per: HashMap<String, (Vec<Item>, Option<String>)> = HashMap::new();
    for (ri, (ln, row)) in rows.rows.iter().enumerate() {
        let label = cx.field(*ln, row, cl, "line")?.to_string();
        if label.is_empty() {
            return Err(cx.err(*ln, "empty line label".into()));
        }
        let si = cx.index(*ln, cx.field(*ln, row, cs, "station_index")?)?;
        let name = cn
            .and_then(|c| row.get(c))
            .cloned()
            .unwrap_or_else(|| si.to_string());
        let x = cx.number(*ln, row.get(cxc).map_or("", String::as_str), "x")?;
        let y = cx.number(*ln, row.get(cy).map_or("", String::as_str), "half_breadth")?;
        let z = cx.number(*ln, row.get(cz).map_or("", String::as_str), "height")?;
        if y.is_none() && z.is_none() {
            return Err(cx.err(
                *ln,
                format!("line `{label}` station {si}: neither half_breadth nor height"),
            ));
        }
        let kind = ck.and_then(|c| row.get(c)).filter(|k| !k.is_empty()).cloned();
        if !per.contains_key(&label) {
            order.push(label.clone());
        }
        let e = per.entry(label).or_insert_with(|| (Vec::new(), None));
        if kind.is_some() {
            e.1 = kind;
        }
        e.0.push(Item {
            line: *ln,
            si,
            name,
            x,
            y,
            z,
            row: ri,
        });
    }
    let mut records: Vec<Record> = rows
        .rows
        .iter()
        .map(|(_, f)| Record {
            fields: f.clone(),
            refs: Vec::new(),
        })
        .collect();
    for label in order {
        let (items, kind) = per.remove(&label).unwrap_or_default();
        let all_eq = |f: &dyn Fn(&Item) -> Option<f64>| {
            let v: Vec<Option<f64>> = items.iter().map(f).collect();
            v.iter().all(Option::is_some) && v.windows(2).all(|w| w[0] == w[1])
        };
        let kind = match kind.as_deref().map(str::to_ascii_lowercase).as_deref() {
            Some("waterline") => Kind::Waterline,
            Some("buttock") => Kind::Buttock,
            Some("edge") | None => {
                if starts_word(&label, &["dwl", "lwl", "wl", "waterline"]) && all_eq(&|i: &Item| i.z) {
                    Kind::Waterline
                } else if starts_word(&label, &["bt", "bl", "bk", "bttk", "buttock"])
                    && all_eq(&|i: &Item| i.y)
                {
                    Kind::Buttock
                } else if items.iter().all(|i| i.y.is_none()) {
                    Kind::Profile
                } else if items.iter().all(|i| i.z.is_none()) {
                    Kind::Plan
                } else {
                    Kind::Edge
                }
            }
            Some(other) => {
                return Err(cx.err(
                    items[0].line,
                    format!("kind `{other}` is none of waterline, buttock, edge"),
                ))
            }
        };
        if kind == Kind::Edge {
            if let Some(i) = items.iter().find(|i| i.y.is_none() || i.z.is_none()) {
                return Err(cx.err(
                    i.line,
                    format!(
                        "edge line `{label}` station {}: needs both half_breadth and height",
                        i.si
                    ),
                ));
            }
        }
        let plane = match kind {
            Kind::Waterline => items[0].z,
            Kind::Buttock => items[0].y,
            _ => None,
        };
        let li = t.lines.len();
        t.lines.push(Line {
            knuckle: kind == Kind::Edge && is_knuckle_name(&label),
            label: label.clone(),
            kind,
            plane,
        });
        let mut seen = std::collections::HashSet::new();
        for it in items {
            if !seen.insert(it.si) {
                return Err(cx.err(it.line, format!("line `{label}` has station {} twice", it.si)));
            }
            let Some(x) = it.x else {
                t.dropped.push((label.clone(), it.si));
                continue;
            };
            let ci = t.cells.len();
            t.cells.push(Cell {
                line: li,
                station_index: it.si,
                station_name: it.name,
                x,
                y: it.y.unwrap_or(f64::NAN),
                z: it.z.unwrap_or(f64::NAN),
                on_station: false,
            });
            let r = &mut records[it.row];
            if it.y.is_some() {
                r.refs.push((ci, Coord::Y, cy));
            }
            if it.z.is_some() {
                r.refs.push((ci, Coord::Z, cz));
            }
        }
    }
    t.records = records;
    Ok(())
}

fn read_block(t: &mut Table, rows: &Rows, lower: &[String]) -> Result<()> {
    let cx = Ctx { path: &rows.path };
    let cb = col(lower, "block").unwrap_or(0);
    let cl = col(lower, "line").unwrap_or(0);
    let Some(cs) = col(lower, "station_index") else {
        return Err(cx.err(rows.header_line, "block form needs a station_index column".into()));
    };
    let cn = col(lower, "station_name");
    let Some(cv) = lower.iter().position(|h| h.starts_with("value")) else {
        return Err(cx.err(
            rows.header_line,
            "block form needs a value column (value, value_in …)".into(),
        ));
    };
    // (block coord, label, si, name, value, row)
    let mut recs = Vec::new();
    let mut order: Vec<String> = Vec::new();
    for (ri, (ln, row)) in rows.rows.iter().enumerate() {
        let b = cx.field(*ln, row, cb, "block")?.to_ascii_lowercase();
        let c = if b.contains("fore") || b.contains("aft") || b.contains("position") {
            Coord::X
        } else if b.contains("height") {
            Coord::Z
        } else if b.contains("breadth") || b.contains("half") {
            Coord::Y
        } else {
            return Err(cx.err(
                *ln,
                format!("unknown block `{b}` (FORE-AFT POSITION, HEIGHT or BREADTH)"),
            ));
        };
        let label = cx.field(*ln, row, cl, "line")?.to_string();
        let si = cx.index(*ln, cx.field(*ln, row, cs, "station_index")?)?;
        let name = cn
            .and_then(|c| row.get(c))
            .cloned()
            .unwrap_or_else(|| si.to_string());
        let v = cx
            .number(*ln, cx.field(*ln, row, cv, "value")?, "value")?
            .ok_or_else(|| cx.err(*ln, "empty value".into()))?;
        if c != Coord::X && !order.contains(&label) {
            order.push(label.clone());
        }
        recs.push((c, label, si, name, v, ri, *ln));
    }
    let mut xrow: HashMap<(String, i64), (f64, usize)> = HashMap::new();
    let mut by_si: BTreeMap<i64, Vec<f64>> = BTreeMap::new();
    let mut names: HashMap<i64, String> = HashMap::new();
    let mut hz: HashMap<(String, i64), (f64, usize, usize)> = HashMap::new();
    let mut by: HashMap<(String, i64), (f64, usize, usize)> = HashMap::new();
    for (c, label, si, name, v, ri, ln) in &recs {
        names.entry(*si).or_insert_with(|| name.clone());
        let key = (label.clone(), *si);
        let dup = match c {
            Coord::X => {
                by_si.entry(*si).or_default().push(*v);
                xrow.insert(key, (*v, *ri)).is_some()
            }
            Coord::Z => hz.insert(key, (*v, *ri, *ln)).is_some(),
            Coord::Y => by.insert(key, (*v, *ri, *ln)).is_some(),
        };
        if dup {
            return Err(cx.err(
                *ln,
                format!("line `{label}` station {si} appears twice in its block"),
            ));
        }
    }
    // a station's x: the value most FORE-AFT cells at that index share (at least two)
    let mut station_x: HashMap<i64, f64> = HashMap::new();
    for (si, vs) in &by_si {
        let mut best = (0usize, 0.0);
        for v in vs {
            let n = vs.iter().filter(|w| *w == v).count();
            if n > best.0 {
                best = (n, *v);
            }
        }
        if best.0 >= 2 {
            station_x.insert(*si, best.1);
        }
    }
    let mut records: Vec<Record> = rows
        .rows
        .iter()
        .map(|(_, f)| Record {
            fields: f.clone(),
            refs: Vec::new(),
        })
        .collect();
    let cell_x = |label: &str, si: i64| -> Option<f64> {
        xrow.get(&(label.to_string(), si))
            .map(|p| p.0)
            .or_else(|| station_x.get(&si).copied())
    };
    let sorted = |m: &HashMap<(String, i64), (f64, usize, usize)>, label: &str| {
        let mut v: Vec<(i64, f64, usize)> = m
            .iter()
            .filter(|(k, _)| k.0 == label)
            .map(|(k, v)| (k.1, v.0, v.1))
            .collect();
        v.sort_by_key(|a| (a.2, a.0));
        v
    };
    for label in order {
        let in_h = hz.keys().any(|k| k.0 == label);
        let in_b = by.keys().any(|k| k.0 == label);
        if let Some(num) = label_number(&label) {
            for (c, m, kind) in [(Coord::Y, &by, Kind::Waterline), (Coord::Z, &hz, Kind::Buttock)] {
                if !(if c == Coord::Y { in_b } else { in_h }) {
                    continue;
                }
                let li = t.lines.len();
                t.lines.push(Line {
                    label: label.clone(),
                    kind,
                    plane: Some(num),
                    knuckle: false,
                });
                for (si, v, ri) in sorted(m, &label) {
                    let Some(x) = cell_x(&label, si) else {
                        t.dropped.push((label.clone(), si));
                        continue;
                    };
                    let ci = t.cells.len();
                    let (y, z) = if kind == Kind::Waterline {
                        (v, num)
                    } else {
                        (num, v)
                    };
                    t.cells.push(Cell {
                        line: li,
                        station_index: si,
                        station_name: names.get(&si).cloned().unwrap_or_default(),
                        x,
                        y,
                        z,
                        on_station: false,
                    });
                    records[ri].refs.push((ci, c, cv));
                }
            }
        } else {
            let kind = match (in_b, in_h) {
                (true, true) => Kind::Edge,
                (false, true) => Kind::Profile,
                _ => Kind::Plan,
            };
            let li = t.lines.len();
            t.lines.push(Line {
                label: label.clone(),
                kind,
                plane: None,
                knuckle: kind == Kind::Edge && is_knuckle_name(&label),
            });
            let mut sis: Vec<i64> = hz
                .keys()
                .chain(by.keys())
                .filter(|k| k.0 == label)
                .map(|k| k.1)
                .collect();
            sis.sort_unstable();
            sis.dedup();
            for si in sis {
                let b = by.get(&(label.clone(), si));
                let h = hz.get(&(label.clone(), si));
                if kind == Kind::Edge && (b.is_none() || h.is_none()) {
                    let ln = b.or(h).map_or(0, |p| p.2);
                    return Err(cx.err(
                        ln,
                        format!("edge line `{label}` station {si}: has only one of BREADTH and HEIGHT"),
                    ));
                }
                let Some(x) = cell_x(&label, si) else {
                    t.dropped.push((label.clone(), si));
                    continue;
                };
                let ci = t.cells.len();
                t.cells.push(Cell {
                    line: li,
                    station_index: si,
                    station_name: names.get(&si).cloned().unwrap_or_default(),
                    x,
                    y: b.map_or(f64::NAN, |p| p.0),
                    z: h.map_or(f64::NAN, |p| p.0),
                    on_station: false,
                });
                if let Some(p) = b {
                    records[p.1].refs.push((ci, Coord::Y, cv));
                }
                if let Some(p) = h {
                    records[p.1].refs.push((ci, Coord::Z, cv));
                }
            }
        }
    }
    t.records = records;
    Ok(())
}

fn read_grid(t: &mut Table, rows: &Rows, lower: &[String]) -> Result<()> {
    let cx = Ctx { path: &rows.path };
    let [ci_, cj, cxx, cy, cz] = ["i", "j", "x", "y", "z"].map(|n| col(lower, n).unwrap_or(0));
    type GridRow = (i64, f64, f64, f64, usize, usize);
    let mut per_i: BTreeMap<i64, Vec<GridRow>> = BTreeMap::new();
    for (ri, (ln, row)) in rows.rows.iter().enumerate() {
        let i = cx.index(*ln, cx.field(*ln, row, ci_, "i")?)?;
        let j = cx.index(*ln, cx.field(*ln, row, cj, "j")?)?;
        let mut v = [0.0; 3];
        for (k, (c, n)) in [(cxx, "x"), (cy, "y"), (cz, "z")].into_iter().enumerate() {
            v[k] = cx
                .number(*ln, cx.field(*ln, row, c, n)?, n)?
                .ok_or_else(|| cx.err(*ln, format!("empty {n}")))?;
        }
        per_i.entry(i).or_default().push((j, v[0], v[1], v[2], ri, *ln));
    }
    let mut records: Vec<Record> = rows
        .rows
        .iter()
        .map(|(_, f)| Record {
            fields: f.clone(),
            refs: Vec::new(),
        })
        .collect();
    for (i, items) in per_i {
        let z0 = items[0].3;
        if let Some(bad) = items
            .iter()
            .find(|it| (it.3 - z0).abs() > 1e-9 * z0.abs().max(1.0))
        {
            return Err(cx.err(
                bad.5,
                format!("grid row i={i} has z {} and {}: not a waterline grid", z0, bad.3),
            ));
        }
        let li = t.lines.len();
        t.lines.push(Line {
            label: format!("WL{i:02}"),
            kind: Kind::Waterline,
            plane: Some(z0),
            knuckle: false,
        });
        let mut seen = std::collections::HashSet::new();
        for (j, x, y, z, ri, ln) in items {
            if !seen.insert(j) {
                return Err(cx.err(ln, format!("cell i={i} j={j} twice")));
            }
            let c = t.cells.len();
            t.cells.push(Cell {
                line: li,
                station_index: j,
                station_name: j.to_string(),
                x,
                y,
                z,
                on_station: false,
            });
            records[ri].refs.push((c, Coord::Y, cy));
        }
    }
    t.records = records;
    Ok(())
}

impl Table {
    fn finish(&mut self) {
        // station planes: the x most cells of an index share (at least two, at least half)
        let mut by_si: BTreeMap<i64, Vec<usize>> = BTreeMap::new();
        for (i, c) in self.cells.iter().enumerate() {
            by_si.entry(c.station_index).or_default().push(i);
        }
        for (si, idx) in by_si {
            let mut best = (0usize, 0.0);
            for &i in &idx {
                let x = self.cells[i].x;
                let n = idx
                    .iter()
                    .filter(|&&k| (self.cells[k].x - x).abs() <= 1e-9 * x.abs().max(1.0))
                    .count();
                if n > best.0 {
                    best = (n, x);
                }
            }
            if best.0 >= 2 && 2 * best.0 >= idx.len() {
                for &i in &idx {
                    let c = &mut self.cells[i];
                    c.on_station = (c.x - best.1).abs() <= 1e-9 * best.1.abs().max(1.0);
                }
                self.stations
                    .insert(si, (self.cells[idx[0]].station_name.clone(), best.1));
            }
        }
        self.step = infer_step(
            self.cells
                .iter()
                .flat_map(|c| [c.x, c.y, c.z])
                .filter(|v| v.is_finite()),
        );
    }

    /// The cells of line `li`, sorted by x.
    pub fn line_cells(&self, li: usize) -> Vec<usize> {
        let mut v: Vec<usize> = (0..self.cells.len())
            .filter(|&i| self.cells[i].line == li)
            .collect();
        v.sort_by(|&a, &b| self.cells[a].x.total_cmp(&self.cells[b].x));
        v
    }

    /// Whether the table has both a waterline and a buttock family, or a waterline grid: views
    /// that share points, so that their agreement can be measured.
    pub fn has_redundant_views(&self) -> bool {
        self.lines
            .iter()
            .any(|l| matches!(l.kind, Kind::Waterline | Kind::Buttock))
    }
}

/// The rounding step of a set of values: the largest of 1, 1/2 … 1/32, 0.1, 0.01 … 10⁻⁶ that
/// every value is a multiple of (within 10⁻⁶ of it); else 10⁻⁶.
pub fn infer_step(values: impl Iterator<Item = f64> + Clone) -> f64 {
    for q in [
        1.0, 0.5, 0.25, 0.125, 0.0625, 0.03125, 0.1, 0.01, 0.001, 1e-4, 1e-5, 1e-6,
    ] {
        if values.clone().all(|v| {
            let r = v / q;
            (r - r.round()).abs() < 1e-6
        }) {
            return q;
        }
    }
    1e-6
}
