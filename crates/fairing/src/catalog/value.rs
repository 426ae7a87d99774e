//! Parameter values that text, TOML and JSON all carry: "a number or `auto`" and "a number or
//! `inf`". JSON has no spelling for `None` or infinity, so a settings field of those shapes
//! is written with one of these serde modules and its schema type:
//!
//! ```
//! # use serde::{Deserialize, Serialize};
//! #[derive(Serialize, Deserialize, schemars::JsonSchema)]
//! #[serde(rename_all = "kebab-case")]
//! struct Example {
//!     /// Smoothing weight: `auto` or a number.
//!     #[serde(with = "fairing::catalog::value::auto")]
//!     #[schemars(with = "fairing::catalog::value::AutoNumber")]
//!     lambda: Option<f64>,
//!     /// Largest move: `inf` or a number.
//!     #[serde(with = "fairing::catalog::value::unbounded")]
//!     #[schemars(with = "fairing::catalog::value::BoundNumber")]
//!     range: f64,
//! }
//! let text = serde_json::to_string(&Example { lambda: None, range: f64::INFINITY }).unwrap();
//! assert_eq!(text, r#"{"lambda":"auto","range":"inf"}"#);
//! ```

use std::borrow::Cow;

use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::de::{self, Deserializer, Visitor};
use serde::Serializer;

/// The schema of "a number or `auto`" (for `#[schemars(with = ...)]`).
pub struct AutoNumber;

impl JsonSchema for AutoNumber {
    fn schema_name() -> Cow<'static, str> {
        "AutoNumber".into()
    }
    fn inline_schema() -> bool {
        true
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({ "anyOf": [ { "type": "string", "enum": ["auto"] }, { "type": "number" } ] })
    }
}

/// The schema of "an integer ≥ 0 or `auto`" (for `#[schemars(with = ...)]`).
pub struct AutoCount;

impl JsonSchema for AutoCount {
    fn schema_name() -> Cow<'static, str> {
        "AutoCount".into()
    }
    fn inline_schema() -> bool {
        true
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({ "anyOf": [ { "type": "string", "enum": ["auto"] }, { "type": "integer", "minimum": 0 } ] })
    }
}

/// The schema of "a number or `inf`" (for `#[schemars(with = ...)]`).
pub struct BoundNumber;

impl JsonSchema for BoundNumber {
    fn schema_name() -> Cow<'static, str> {
        "BoundNumber".into()
    }
    fn inline_schema() -> bool {
        true
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({ "anyOf": [ { "type": "string", "enum": ["inf"] }, { "type": "number" } ] })
    }
}

/// A number, or one word standing for a value JSON cannot hold.
struct NumberOr {
    word: &'static str,
}

impl Visitor<'_> for NumberOr {
    type Value = Option<f64>;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "a number or `{}`", self.word)
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
        Ok(Some(v))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
        Ok(Some(v as f64))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
        Ok(Some(v as f64))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
        let word = v.trim();
        if word.eq_ignore_ascii_case(self.word) {
            return Ok(None);
        }
        match word.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(Some(x)),
            _ => Err(E::custom(format!("`{v}` is not a number or `{}`", self.word))),
        }
    }
}

/// Serde for `Option<f64>` written as the number or `auto` (`None`).
pub mod auto {
    use super::*;

    /// Writes `None` as `"auto"`.
    pub fn serialize<S: Serializer>(value: &Option<f64>, serializer: S) -> Result<S::Ok, S::Error> {
        match value {
            Some(v) => serializer.serialize_f64(*v),
            None => serializer.serialize_str("auto"),
        }
    }

    /// Reads a number or `"auto"`.
    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<f64>, D::Error> {
        deserializer.deserialize_any(NumberOr { word: "auto" })
    }
}

/// Serde for `Option<usize>` written as the integer or `auto` (`None`).
pub mod auto_count {
    use super::*;

    /// Writes `None` as `"auto"`.
    pub fn serialize<S: Serializer>(value: &Option<usize>, serializer: S) -> Result<S::Ok, S::Error> {
        match value {
            Some(v) => serializer.serialize_u64(*v as u64),
            None => serializer.serialize_str("auto"),
        }
    }

    /// Reads an integer ≥ 0 or `"auto"`.
    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<usize>, D::Error> {
        match deserializer.deserialize_any(NumberOr { word: "auto" })? {
            None => Ok(None),
            Some(x) if x >= 0.0 && x.fract() == 0.0 && x <= usize::MAX as f64 => Ok(Some(x as usize)),
            Some(x) => Err(de::Error::custom(format!(
                "`{x}` is not an integer ≥ 0 or `auto`"
            ))),
        }
    }
}

/// Serde for `f64` written as the number or `inf` (`f64::INFINITY`).
pub mod unbounded {
    use super::*;

    /// Writes infinity as `"inf"`.
    pub fn serialize<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
        if *value == f64::INFINITY {
            serializer.serialize_str("inf")
        } else {
            serializer.serialize_f64(*value)
        }
    }

    /// Reads a number or `"inf"`.
    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
        Ok(deserializer
            .deserialize_any(NumberOr { word: "inf" })?
            .unwrap_or(f64::INFINITY))
    }
}
