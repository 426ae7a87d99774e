//! The IGES reader.

use curve_repr::{NurbsCurve, NurbsSurface, Vec3};

use crate::model::{CadCurve, CadModel, CadSurface};
use crate::number::parse_real;
use crate::{Error, Result, Units};

const FORMAT: &str = "IGES";

/// One line of the file: its 1-based number, section letter and data columns (1–72).
struct Line<'a> {
    number: usize,
    section: char,
    data: &'a str,
}

/// A parameter of an entity or of the Global section: `None` when defaulted (empty).
type Parameter = Option<String>;

/// Splits parameter text at `delimiter`, stopping at `end`, with Hollerith strings (`nH…`)
/// taken whole, so that a delimiter inside a string does not split it.
fn split(text: &str, delimiter: char, end: char) -> Vec<Parameter> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    loop {
        while i < chars.len() && chars[i] == ' ' {
            i += 1;
        }
        // A Hollerith string: digits, then H.
        let digits = chars[i..].iter().take_while(|c| c.is_ascii_digit()).count();
        let mut token = String::new();
        if digits > 0 && chars.get(i + digits).is_some_and(|&c| c == 'H' || c == 'h') {
            let n: usize = chars[i..i + digits]
                .iter()
                .collect::<String>()
                .parse()
                .unwrap_or(0);
            let start = i + digits + 1;
            let stop = (start + n).min(chars.len());
            token = chars[start..stop].iter().collect();
            i = stop;
            while i < chars.len() && chars[i] != delimiter && chars[i] != end {
                i += 1;
            }
        } else {
            while i < chars.len() && chars[i] != delimiter && chars[i] != end {
                token.push(chars[i]);
                i += 1;
            }
            token = token.trim().to_string();
        }
        out.push((!token.is_empty()).then_some(token));
        if i >= chars.len() || chars[i] == end {
            break;
        }
        i += 1;
    }
    out
}

/// The Global section's delimiters: parameter 1 and 2, each `1Hc` or defaulted (`,`, `;`).
fn delimiters(text: &str) -> (char, char) {
    let hollerith = |rest: &str| -> Option<(char, usize)> {
        let c = rest.strip_prefix("1H")?.chars().next()?;
        Some((c, 2 + c.len_utf8()))
    };
    let mut rest = text.trim_start();
    let parameter = match hollerith(rest) {
        Some((c, length)) => {
            rest = &rest[length..];
            c
        }
        None => ',',
    };
    rest = rest.trim_start();
    rest = rest.strip_prefix(parameter).unwrap_or(rest).trim_start();
    let record = hollerith(rest).map_or(';', |(c, _)| c);
    (parameter, record)
}

/// A directory entry: the fields the reader uses.
struct Directory {
    kind: i64,
    parameter_start: usize,
    transform: usize,
    status: String,
    parameter_count: usize,
    label: String,
    line: usize,
}

fn field(line: &str, index: usize) -> &str {
    line.get(index * 8..(index + 1) * 8).unwrap_or("").trim()
}

fn integer(text: &str, what: &str, line: usize) -> Result<i64> {
    if text.is_empty() {
        return Ok(0);
    }
    if let Ok(v) = text.parse::<i64>() {
        return Ok(v);
    }
    match parse_real(text) {
        Some(v) if v.fract() == 0.0 && v.abs() < 1e15 => Ok(v as i64),
        _ => Err(Error::parse(
            FORMAT,
            line,
            format!("{what}: `{text}` is not an integer"),
        )),
    }
}

/// The parameters of one entity, with the line where they start for messages.
struct Parameters {
    values: Vec<Parameter>,
    line: usize,
    next: usize,
}

impl Parameters {
    fn take(&mut self) -> Parameter {
        let value = self.values.get(self.next).cloned().flatten();
        self.next += 1;
        value
    }

    fn integer(&mut self, what: &str) -> Result<i64> {
        let text = self.take().unwrap_or_default();
        integer(&text, what, self.line)
    }

    fn count(&mut self, what: &str) -> Result<usize> {
        let value = self.integer(what)?;
        usize::try_from(value)
            .ok()
            .filter(|&v| v < 100_000_000)
            .ok_or_else(|| Error::parse(FORMAT, self.line, format!("{what} is {value}")))
    }

    fn real(&mut self, what: &str) -> Result<f64> {
        let index = self.next;
        match self.take() {
            None => Err(Error::parse(
                FORMAT,
                self.line,
                format!("{what} (parameter {}) is missing", index + 1),
            )),
            Some(text) => parse_real(&text).ok_or_else(|| {
                Error::parse(
                    FORMAT,
                    self.line,
                    format!("{what} (parameter {}): `{text}` is not a finite real", index + 1),
                )
            }),
        }
    }

    fn reals(&mut self, count: usize, what: &str) -> Result<Vec<f64>> {
        (0..count).map(|_| self.real(what)).collect()
    }

    fn points(&mut self, count: usize) -> Result<Vec<Vec3>> {
        (0..count)
            .map(|_| {
                Ok(Vec3::new(
                    self.real("control point")?,
                    self.real("control point")?,
                    self.real("control point")?,
                ))
            })
            .collect()
    }
}

/// An affine map x ↦ R x + T (entity 124).
#[derive(Clone, Copy)]
struct Transform {
    rotation: nalgebra::Matrix3<f64>,
    translation: Vec3,
}

impl Transform {
    fn apply(&self, p: &Vec3) -> Vec3 {
        self.rotation * p + self.translation
    }

    fn then(&self, outer: &Transform) -> Transform {
        Transform {
            rotation: outer.rotation * self.rotation,
            translation: outer.rotation * self.translation + outer.translation,
        }
    }
}

struct Reader<'a> {
    directory: Vec<Directory>,
    parameters: Vec<Line<'a>>,
    delimiter: char,
    end: char,
}

impl Reader<'_> {
    fn entity(&self, index: usize) -> Option<&Directory> {
        self.directory.get(index)
    }

    fn parameters(&self, entry: &Directory) -> Result<Parameters> {
        let first = entry
            .parameter_start
            .checked_sub(1)
            .ok_or_else(|| Error::parse(FORMAT, entry.line, "the parameter data pointer is 0"))?;
        let lines = self
            .parameters
            .get(first..first + entry.parameter_count.max(1))
            .ok_or_else(|| {
                Error::parse(
                    FORMAT,
                    entry.line,
                    format!(
                        "the parameter data of entity {} (lines {}…) lie past the parameter section",
                        entry.kind, entry.parameter_start
                    ),
                )
            })?;
        let line = lines.first().map_or(entry.line, |l| l.number);
        let text: String = lines.iter().map(|l| l.data.get(..64).unwrap_or(l.data)).collect();
        let values = split(&text, self.delimiter, self.end);
        let kind = integer(
            values.first().cloned().flatten().as_deref().unwrap_or(""),
            "entity type",
            line,
        )?;
        if kind != entry.kind {
            return Err(Error::parse(
                FORMAT,
                line,
                format!(
                    "the parameter data start with entity type {kind}, the directory says {}",
                    entry.kind
                ),
            ));
        }
        Ok(Parameters {
            values,
            line,
            next: 1,
        })
    }

    /// The transformation of an entity (DE field 7), composed with the transformations of
    /// the matrices themselves; depth-limited against cycles.
    fn transform(&self, entry: &Directory, depth: usize) -> Result<Option<Transform>> {
        if entry.transform == 0 {
            return Ok(None);
        }
        let index = (entry.transform - 1) / 2;
        let matrix = self
            .entity(index)
            .filter(|m| m.kind == 124 && depth < 16)
            .ok_or_else(|| {
                Error::parse(
                    FORMAT,
                    entry.line,
                    format!(
                        "the transformation matrix pointer {} names no entity 124",
                        entry.transform
                    ),
                )
            })?;
        let mut p = self.parameters(matrix)?;
        let v = p.reals(12, "transformation matrix")?;
        let own = Transform {
            rotation: nalgebra::Matrix3::new(v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10]),
            translation: Vec3::new(v[3], v[7], v[11]),
        };
        Ok(Some(match self.transform(matrix, depth + 1)? {
            Some(outer) => own.then(&outer),
            None => own,
        }))
    }

    fn curve(&self, entry: &Directory) -> Result<CadCurve> {
        let mut p = self.parameters(entry)?;
        let last = p.count("K (upper index of the control points)")?;
        let degree = p.count("M (degree)")?;
        let _planar = p.integer("PROP1")?;
        let _closed = p.integer("PROP2")?;
        let _polynomial = p.integer("PROP3")?;
        let _periodic = p.integer("PROP4")?;
        let knots = p.reals(last + degree + 2, "knot")?;
        let weights = p.reals(last + 1, "weight")?;
        let mut points = p.points(last + 1)?;
        if let Some(t) = self.transform(entry, 0)? {
            points.iter_mut().for_each(|q| *q = t.apply(q));
        }
        let line = p.line;
        let curve = NurbsCurve::new(degree, knots, points, weights)
            .map_err(|e| Error::parse(FORMAT, line, format!("entity 126: {e}")))?;
        // Planar in the xy plane when every z is 0 (PROP1 alone allows any plane).
        let mut cad = CadCurve::new(curve);
        cad.name = entry.label.clone();
        Ok(cad)
    }

    fn surface(&self, entry: &Directory) -> Result<CadSurface> {
        let mut p = self.parameters(entry)?;
        let last_u = p.count("K1 (upper index in u)")?;
        let last_v = p.count("K2 (upper index in v)")?;
        let degree_u = p.count("M1 (degree in u)")?;
        let degree_v = p.count("M2 (degree in v)")?;
        for what in ["PROP1", "PROP2", "PROP3", "PROP4", "PROP5"] {
            p.integer(what)?;
        }
        let knots_u = p.reals(last_u + degree_u + 2, "knot in u")?;
        let knots_v = p.reals(last_v + degree_v + 2, "knot in v")?;
        let (rows, columns) = (last_u + 1, last_v + 1);
        let flat_weights = p.reals(rows * columns, "weight")?;
        let mut flat_points = p.points(rows * columns)?;
        if let Some(t) = self.transform(entry, 0)? {
            flat_points.iter_mut().for_each(|q| *q = t.apply(q));
        }
        // The u index i varies fastest: element i + j·rows.
        let weights = (0..rows)
            .map(|i| (0..columns).map(|j| flat_weights[i + j * rows]).collect())
            .collect();
        let points = (0..rows)
            .map(|i| (0..columns).map(|j| flat_points[i + j * rows]).collect())
            .collect();
        let line = p.line;
        let surface = NurbsSurface::new(degree_u, degree_v, knots_u, knots_v, points, weights)
            .map_err(|e| Error::parse(FORMAT, line, format!("entity 128: {e}")))?;
        Ok(CadSurface::new(surface).with_name(entry.label.clone()))
    }
}

/// Reads every B-spline curve (126) and surface (128) of an IGES file (see the
/// [module documentation](super)). Fails with [`Error::Parse`] naming the line on a file that
/// is not fixed-form IGES or an entity whose parameters are wrong; a file without a curve or
/// surface reads as an empty model. O(size of the file).
pub fn read(text: &str) -> Result<CadModel> {
    let mut lines = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let raw = raw.trim_end_matches('\r');
        if raw.trim().is_empty() {
            continue;
        }
        let section = raw.chars().nth(72).ok_or_else(|| {
            Error::parse(
                FORMAT,
                i + 1,
                format!(
                    "an IGES line has its section letter in column 73; this line has {} columns",
                    raw.chars().count()
                ),
            )
        })?;
        if !"SGDPTC".contains(section) {
            return Err(Error::parse(
                FORMAT,
                i + 1,
                format!("`{section}` in column 73 is no IGES section (S, G, D, P, T)"),
            ));
        }
        if section == 'C' {
            return Err(Error::parse(FORMAT, i + 1, "compressed IGES is not supported"));
        }
        let data = raw.get(..72).unwrap_or(raw);
        lines.push(Line {
            number: i + 1,
            section,
            data,
        });
    }
    if lines.is_empty() {
        return Err(Error::parse(FORMAT, 1, "the file is empty"));
    }
    let global: String = lines
        .iter()
        .filter(|l| l.section == 'G')
        .map(|l| l.data)
        .collect();
    let (delimiter, end) = delimiters(&global);
    let global_values = split(&global, delimiter, end);
    let global_line = lines.iter().find(|l| l.section == 'G').map_or(1, |l| l.number);
    let text_at = |i: usize| global_values.get(i).cloned().flatten().unwrap_or_default();
    let unit_flag = integer(&text_at(13), "the units flag (Global parameter 14)", global_line)?;
    let units = Units::from_iges(unit_flag, &text_at(14)).unwrap_or_default();
    let tolerance = parse_real(&text_at(18)).unwrap_or(0.0);

    let directory_lines: Vec<&Line> = lines.iter().filter(|l| l.section == 'D').collect();
    if !directory_lines.len().is_multiple_of(2) {
        return Err(Error::parse(
            FORMAT,
            directory_lines.last().map_or(1, |l| l.number),
            "the directory entry section has an odd number of lines",
        ));
    }
    let mut directory = Vec::with_capacity(directory_lines.len() / 2);
    for pair in directory_lines.chunks(2) {
        let (first, second) = (pair[0], pair[1]);
        let line = first.number;
        let count = |text: &str, what: &str| -> Result<usize> {
            usize::try_from(integer(text, what, line)?)
                .map_err(|_| Error::parse(FORMAT, line, format!("{what} is negative")))
        };
        directory.push(Directory {
            kind: integer(field(first.data, 0), "entity type", line)?,
            parameter_start: count(field(first.data, 1), "parameter data pointer")?,
            transform: count(field(first.data, 6), "transformation matrix pointer")?,
            status: format!("{:0>8}", field(first.data, 8)),
            parameter_count: count(field(second.data, 3), "parameter line count")?,
            label: field(second.data, 7).to_string(),
            line,
        });
    }
    let reader = Reader {
        directory,
        parameters: lines.into_iter().filter(|l| l.section == 'P').collect(),
        delimiter,
        end,
    };
    let mut model = CadModel {
        curves: Vec::new(),
        surfaces: Vec::new(),
        units,
        tolerance,
    };
    for entry in &reader.directory {
        // Entity use flag (status digits 5–6): 05 marks a 2D parameter-space curve.
        let parametric = entry.status.get(4..6) == Some("05");
        match entry.kind {
            126 if !parametric => model.curves.push(reader.curve(entry)?),
            128 => model.surfaces.push(reader.surface(entry)?),
            _ => {}
        }
    }
    Ok(model)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_split_around_hollerith_strings() {
        let values = split("1H,,1H;,4Ha,b;,,3.5,7;ignored", ',', ';');
        assert_eq!(
            values,
            vec![
                Some(",".to_string()),
                Some(";".to_string()),
                Some("a,b;".to_string()),
                None,
                Some("3.5".to_string()),
                Some("7".to_string()),
            ]
        );
        assert_eq!(delimiters("1H,,1H;,4Hfair"), (',', ';'));
        assert_eq!(delimiters(",,4Hfair"), (',', ';'));
        assert_eq!(delimiters("1H//1H#/4Hfair"), ('/', '#'));
    }
}
