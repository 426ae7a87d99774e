//! JSON curves: `{"points": [[x, y], ...]}` (other keys kept) or a bare `[[x, y], ...]`.
//!
//! The points are read by a small serde visitor so that serde_json reports the line of a
//! wrong value (a string, a point of the wrong length, a number out of range).

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

/// The object form; unknown keys are ignored here and kept from the untyped parse.
#[derive(Deserialize)]
struct PointsObject {
    points: PointList,
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
    let value: serde_json::Value = serde_json::from_str(&source.text).map_err(|e| json_error(path, e))?;
    let (list, document) = match value {
        serde_json::Value::Object(map) => {
            if !map.contains_key("points") {
                return Err(Error::Invalid {
                    path: path.into(),
                    message: "expected an object with a `points` array of [x, y] or [x, y, z]".into(),
                });
            }
            let object: PointsObject = serde_json::from_str(&source.text).map_err(|e| json_error(path, e))?;
            (object.points, Some(map))
        }
        serde_json::Value::Array(_) => {
            let list: PointList = serde_json::from_str(&source.text).map_err(|e| json_error(path, e))?;
            (list, None)
        }
        _ => {
            return Err(Error::Invalid {
                path: path.into(),
                message: "expected {\"points\": [[x, y], ...]} or an array of points".into(),
            })
        }
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
