//! JSON curves: `{"points": [[x, y], ...]}` (other keys kept) or a bare `[[x, y], ...]`.
//!
//! One pass of a small serde visitor: serde_json reports the line of a wrong value (a string,
//! a point of the wrong length, a number out of range, a key given twice). The other keys are
//! kept in file order with their values' text exactly as written ([`JsonDocument`]): a
//! 23-digit id comes back digit for digit. Nesting is bounded by serde_json's recursion limit
//! (128); a deeper document is refused with its line.

use super::{CurveInput, CurvePoints, InputFormat, Source};
use fair_door::error::{Error, Result};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;
use std::fmt;

/// A list of points of one dimension (2 or 3).
struct PointList {
    dimension: usize,
    rows: Vec<Vec<f64>>,
}

/// A JSON object as read: its keys in file order, the `points` entry's place, and every other
/// value's text exactly as written (numbers of any size, spacing, nested objects).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct JsonDocument {
    entries: Vec<(String, Entry)>,
}

#[derive(Debug, Clone, PartialEq)]
enum Entry {
    /// Where the points go.
    Points,
    /// A value's JSON text.
    Raw(String),
}

impl JsonDocument {
    /// An empty document (the points alone).
    pub fn new() -> JsonDocument {
        JsonDocument::default()
    }

    /// Whether the document has `key` (`points` included once the points were read).
    pub fn contains_key(&self, key: &str) -> bool {
        self.entries.iter().any(|(k, _)| k == key)
    }

    /// The text of `key`'s value as read, or `None` (and for `points`).
    pub fn raw(&self, key: &str) -> Option<&str> {
        self.entries.iter().find_map(|(k, e)| match e {
            Entry::Raw(text) if k == key => Some(text.as_str()),
            _ => None,
        })
    }

    /// Appends `key` with `value` written as serde_json writes it.
    pub fn push(&mut self, key: &str, value: &serde_json::Value) {
        self.entries
            .push((key.to_string(), Entry::Raw(value.to_string())));
    }

    /// The document with `rows` as its points (at the `points` key's place, else last),
    /// pretty-printed; the other values' text as read. O(size).
    pub fn to_pretty(&self, rows: &[Vec<f64>]) -> serde_json::Result<String> {
        let mut entries: Vec<(&str, Value<'_>)> = Vec::with_capacity(self.entries.len() + 1);
        for (key, entry) in &self.entries {
            entries.push(match entry {
                Entry::Points => (key.as_str(), Value::Points(rows)),
                Entry::Raw(text) => (
                    key.as_str(),
                    Value::Raw(serde_json::value::RawValue::from_string(text.clone())?),
                ),
            });
        }
        if !self.contains_key("points") {
            entries.push(("points", Value::Points(rows)));
        }
        serde_json::to_string_pretty(&Ordered(entries))
    }
}

enum Value<'a> {
    Points(&'a [Vec<f64>]),
    Raw(Box<serde_json::value::RawValue>),
}

/// Entries serialised as an object in their order.
struct Ordered<'a>(Vec<(&'a str, Value<'a>)>);

impl serde::Serialize for Ordered<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (key, value) in &self.0 {
            match value {
                Value::Points(rows) => map.serialize_entry(key, rows)?,
                Value::Raw(raw) => map.serialize_entry(key, raw)?,
            }
        }
        map.end()
    }
}

/// What the top level holds: an object (its document and its points, if any) or an array.
enum Top {
    Object(JsonDocument, Option<PointList>),
    Array(PointList),
}

struct TopVisitor;

impl<'de> Visitor<'de> for TopVisitor {
    type Value = Top;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("{\"points\": [[x, y], ...]} or an array of points")
    }

    fn visit_map<A: de::MapAccess<'de>>(self, mut map: A) -> std::result::Result<Top, A::Error> {
        let mut document = JsonDocument::new();
        let mut seen = std::collections::HashSet::new();
        let mut points = None;
        while let Some(key) = map.next_key::<String>()? {
            if !seen.insert(key.clone()) {
                return Err(de::Error::custom(format!(
                    "the key `{}` is given twice: an object's keys must be distinct (which one is meant?)",
                    super::echo(&key)
                )));
            }
            if key == "points" {
                points = Some(map.next_value::<PointList>()?);
                document.entries.push((key, Entry::Points));
            } else {
                let raw = map.next_value::<Box<serde_json::value::RawValue>>()?;
                document.entries.push((key, Entry::Raw(raw.get().to_string())));
            }
        }
        Ok(Top::Object(document, points))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> std::result::Result<Top, A::Error> {
        PointListVisitor.visit_seq(seq).map(Top::Array)
    }
}

impl<'de> Deserialize<'de> for PointList {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        deserializer.deserialize_seq(PointListVisitor)
    }
}

struct PointListVisitor;

impl<'de> Visitor<'de> for PointListVisitor {
    type Value = PointList;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an array of points [x, y] or [x, y, z]")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> std::result::Result<PointList, A::Error> {
        let mut rows: Vec<Vec<f64>> = Vec::with_capacity(seq.size_hint().unwrap_or(0));
        let mut dimension = 0;
        while let Some(Coordinates(row)) = seq.next_element_seed(CoordinatesSeed {
            index: rows.len(),
            dimension,
        })? {
            dimension = row.len();
            rows.push(row);
        }
        Ok(PointList { dimension, rows })
    }
}

/// One point's coordinates, each finite.
struct Coordinates(Vec<f64>);

/// Reads one point, checking its length (against the first point's once known) before
/// serde_json moves past its closing bracket, so that the error names the point's line.
struct CoordinatesSeed {
    index: usize,
    dimension: usize,
}

impl<'de> de::DeserializeSeed<'de> for CoordinatesSeed {
    type Value = Coordinates;
    fn deserialize<D: Deserializer<'de>>(
        self,
        deserializer: D,
    ) -> std::result::Result<Coordinates, D::Error> {
        deserializer.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for CoordinatesSeed {
    type Value = Coordinates;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a point [x, y] or [x, y, z] of numbers")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> std::result::Result<Coordinates, A::Error> {
        let mut values = Vec::with_capacity(3);
        while let Some(v) = seq.next_element::<f64>()? {
            if !v.is_finite() {
                return Err(de::Error::custom("coordinate is not finite"));
            }
            values.push(v);
        }
        let index = self.index;
        if values.len() != 2 && values.len() != 3 {
            return Err(de::Error::custom(format!(
                "point {index} has {} coordinates, expected 2 or 3",
                values.len()
            )));
        }
        if self.dimension != 0 && values.len() != self.dimension {
            return Err(de::Error::custom(format!(
                "point {index} has {} coordinates, the first point has {}",
                values.len(),
                self.dimension
            )));
        }
        Ok(Coordinates(values))
    }
}

/// Turns serde_json's error into ours, with the line and without serde_json's position suffix.
fn json_error(path: &str, e: serde_json::Error) -> Error {
    let line = e.line();
    let text = e.to_string();
    let suffix = format!(" at line {} column {}", e.line(), e.column());
    let message = text.strip_suffix(&suffix).unwrap_or(&text).to_string();
    if line == 0 {
        Error::Invalid {
            path: path.into(),
            message,
        }
    } else {
        Error::Parse {
            path: path.into(),
            line,
            message,
        }
    }
}

/// Parses a JSON curve.
pub(super) fn parse(source: &Source) -> Result<CurveInput> {
    let path = source.name.as_str();
    let mut deserializer = serde_json::Deserializer::from_str(&source.text);
    let top = deserializer
        .deserialize_any(TopVisitor)
        .and_then(|top| deserializer.end().map(|()| top))
        .map_err(|e| json_error(path, e))?;
    let (list, document) = match top {
        Top::Object(document, Some(list)) => (list, Some(document)),
        Top::Object(_, None) => {
            return Err(Error::Invalid {
                path: path.into(),
                message: "expected an object with a `points` array of [x, y] or [x, y, z]".into(),
            })
        }
        Top::Array(list) => (list, None),
    };
    if list.rows.is_empty() {
        return Err(Error::Empty {
            path: path.into(),
            reason: "the `points` array is empty".into(),
        });
    }
    let points = CurvePoints::from_rows(list.dimension, &list.rows).ok_or_else(|| Error::Internal {
        message: "JSON points of unequal dimension".into(),
    })?;
    Ok(CurveInput {
        points,
        format: InputFormat::Json { document },
        source: path.into(),
        lines: Vec::new(),
        notes: Vec::new(),
    })
}
