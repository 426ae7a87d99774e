//! Reading a settings type's JSON Schema: the parameter table (name, default, meaning) and
//! the conversion of `--set` text to a JSON value of the type the parameter takes.
//!
//! The schema is `schemars::schema_for!(S)`: an object whose `properties` are the
//! parameters (kebab-case names), each with its `description` (the field's doc comment; its
//! first line is the meaning) or `title` + `description` when the comment starts with a
//! one-line paragraph, and a type given by `type`, `enum`, `const`, `anyOf`/`oneOf` or a
//! `$ref` into `$defs`.

use std::collections::BTreeSet;

use serde::de::{Deserializer, IgnoredAny, MapAccess, Visitor};
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// One parameter of a method, as `fair methods` lists it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ParameterInfo {
    /// The name `--set` and config files take (kebab-case).
    pub name: String,
    /// The default, as text (as `--set` would write it).
    pub default: String,
    /// The default as JSON.
    pub default_value: Value,
    /// What it means, one line.
    pub meaning: String,
    /// The property's JSON Schema (with `$ref`s into the settings' `$defs`).
    pub schema: Value,
}

/// The top-level keys of a serialised value, in the order they were written (struct fields
/// in declaration order, flattened fields in place).
pub(super) fn key_order<T: Serialize>(value: &T) -> Vec<String> {
    struct Keys(Vec<String>);
    impl<'de> Deserialize<'de> for Keys {
        fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
            struct KeysVisitor;
            impl<'de> Visitor<'de> for KeysVisitor {
                type Value = Keys;
                fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                    f.write_str("an object")
                }
                fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Keys, A::Error> {
                    let mut keys = Vec::new();
                    while let Some(key) = map.next_key::<String>()? {
                        map.next_value::<IgnoredAny>()?;
                        keys.push(key);
                    }
                    Ok(Keys(keys))
                }
            }
            deserializer.deserialize_map(KeysVisitor)
        }
    }
    serde_json::to_string(value)
        .ok()
        .and_then(|text| serde_json::from_str::<Keys>(&text).ok())
        .map(|k| k.0)
        .unwrap_or_default()
}

/// The property schemas of a settings schema, by name.
pub(super) fn properties(schema: &Value) -> serde_json::Map<String, Value> {
    schema
        .get("properties")
        .and_then(Value::as_object)
        .cloned()
        .unwrap_or_default()
}

/// `schema` with a `$ref` into the root's `$defs` (or `definitions`) followed.
fn resolve<'a>(schema: &'a Value, root: &'a Value) -> &'a Value {
    let mut current = schema;
    for _ in 0..8 {
        let Some(reference) = current.get("$ref").and_then(Value::as_str) else {
            return current;
        };
        let name = reference.rsplit('/').next().unwrap_or_default();
        let target = root
            .get("$defs")
            .or_else(|| root.get("definitions"))
            .and_then(|d| d.get(name));
        match target {
            Some(t) => current = t,
            None => return current,
        }
    }
    current
}

/// The JSON types a property schema accepts: `integer`, `number`, `boolean`, `string`,
/// `array`, `object`, `null`.
pub(super) fn accepted_types(schema: &Value, root: &Value) -> BTreeSet<&'static str> {
    let mut out = BTreeSet::new();
    collect_types(schema, root, &mut out, 0);
    out
}

fn type_name(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "boolean",
        Value::Number(n) if n.is_i64() || n.is_u64() => "integer",
        Value::Number(_) => "number",
        Value::String(_) => "string",
        Value::Array(_) => "array",
        Value::Object(_) => "object",
    }
}

fn collect_types(schema: &Value, root: &Value, out: &mut BTreeSet<&'static str>, depth: usize) {
    if depth > 8 {
        return;
    }
    let schema = resolve(schema, root);
    const NAMES: [&str; 7] = [
        "integer", "number", "boolean", "string", "array", "object", "null",
    ];
    let mut add = |name: &str| {
        if let Some(known) = NAMES.iter().find(|n| **n == name) {
            out.insert(known);
        }
    };
    match schema.get("type") {
        Some(Value::String(t)) => add(t),
        Some(Value::Array(ts)) => ts.iter().filter_map(Value::as_str).for_each(&mut add),
        _ => {}
    }
    if let Some(Value::Array(values)) = schema.get("enum") {
        values.iter().for_each(|v| add(type_name(v)));
    }
    if let Some(value) = schema.get("const") {
        add(type_name(value));
    }
    for key in ["anyOf", "oneOf", "allOf"] {
        if let Some(Value::Array(branches)) = schema.get(key) {
            for branch in branches {
                collect_types(branch, root, out, depth + 1);
            }
        }
    }
}

/// Reads `--set` text as the JSON value the property takes: an integer, a number, a boolean
/// (`true`/`on`/`yes`, `false`/`off`/`no`), a JSON array, or else the text as a string;
/// tried in that order among the types the schema accepts. The settings' deserialisation
/// then says whether the value fits.
pub(super) fn text_to_value(text: &str, schema: &Value, root: &Value) -> Value {
    let types = accepted_types(schema, root);
    let trimmed = text.trim();
    if types.contains("integer") {
        if let Ok(i) = trimmed.parse::<i64>() {
            return Value::from(i);
        }
        if let Ok(u) = trimmed.parse::<u64>() {
            return Value::from(u);
        }
    }
    if types.contains("number") {
        if let Ok(x) = trimmed.parse::<f64>() {
            if x.is_finite() {
                return Value::from(x);
            }
        }
    }
    if types.contains("boolean") {
        match trimmed.to_ascii_lowercase().as_str() {
            "true" | "on" | "yes" => return Value::Bool(true),
            "false" | "off" | "no" => return Value::Bool(false),
            _ => {}
        }
    }
    if types.contains("array") && trimmed.starts_with('[') {
        if let Ok(value @ Value::Array(_)) = serde_json::from_str::<Value>(trimmed) {
            return value;
        }
    }
    Value::String(trimmed.to_owned())
}

/// A value as `--set` text: strings bare, numbers in their shortest form, arrays and
/// objects as JSON.
pub(super) fn value_to_text(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        Value::Null => "none".into(),
        Value::Number(n) => match n.as_f64() {
            // 5.0 reads as 5, as it would be typed.
            Some(x) if n.is_f64() && x.fract() == 0.0 && x.abs() < 1e15 => format!("{}", x as i64),
            _ => n.to_string(),
        },
        other => other.to_string(),
    }
}

/// The one-line meaning of a property: its title, or the first line of its description.
pub(super) fn meaning(schema: &Value, root: &Value) -> String {
    let direct = |s: &Value| {
        s.get("title")
            .and_then(Value::as_str)
            .or_else(|| s.get("description").and_then(Value::as_str))
            .map(|d| {
                d.lines()
                    .next()
                    .unwrap_or_default()
                    .trim()
                    .trim_end_matches('.')
                    .to_owned()
            })
    };
    direct(schema)
        .or_else(|| direct(resolve(schema, root)))
        .unwrap_or_default()
}
