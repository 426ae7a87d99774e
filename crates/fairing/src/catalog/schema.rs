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

/// The numbers a property takes, as its schema declares them: integers only or any number,
/// and the bounds (`minimum`, `maximum`, `exclusiveMinimum`, `exclusiveMaximum`, on the
/// property or on its number branch, `$ref`s followed). Declared once on the settings' fields
/// (`#[schemars(range(min = 1))]`, or `#[schemars(extend("exclusiveMinimum" = 0))]`), read
/// here to check every value given and to print the range.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NumberRange {
    /// Integers only (the schema takes `integer` and not `number`).
    pub integer: bool,
    /// The lower bound and whether it is excluded.
    pub min: Option<(f64, bool)>,
    /// The upper bound and whether it is excluded.
    pub max: Option<(f64, bool)>,
}

impl NumberRange {
    /// The range of a property, `None` when it takes no numbers.
    pub fn of(schema: &Value, root: &Value) -> Option<NumberRange> {
        let types = accepted_types(schema, root);
        if !types.contains("integer") && !types.contains("number") {
            return None;
        }
        let mut range = NumberRange {
            integer: !types.contains("number"),
            ..NumberRange::default()
        };
        collect_bounds(schema, root, &mut range, 0);
        Some(range)
    }

    /// Whether `x` lies in the range (and is an integer where one is asked).
    pub fn contains(&self, x: f64) -> bool {
        let above = match self.min {
            Some((m, true)) => x > m,
            Some((m, false)) => x >= m,
            None => true,
        };
        let below = match self.max {
            Some((m, true)) => x < m,
            Some((m, false)) => x <= m,
            None => true,
        };
        x.is_finite() && above && below && (!self.integer || x.fract() == 0.0)
    }

    /// Whether a bound is declared.
    pub fn is_bounded(&self) -> bool {
        self.min.is_some() || self.max.is_some()
    }

    /// The range in words: `an integer ≥ 1`, `a number in (0, 1]`, `a number > 0`.
    pub fn describe(&self) -> String {
        let what = if self.integer { "an integer" } else { "a number" };
        match self.bounds() {
            Some(bounds) => format!("{what} {bounds}"),
            None => what.to_owned(),
        }
    }

    /// The bounds alone: `≥ 1`, `in (0, 1]`, `< 1`; `None` when unbounded.
    pub fn bounds(&self) -> Option<String> {
        let number = |x: f64| shortest(x);
        match (self.min, self.max) {
            (None, None) => None,
            (Some((lo, lo_open)), None) => {
                Some(format!("{} {}", if lo_open { ">" } else { "≥" }, number(lo)))
            }
            (None, Some((hi, hi_open))) => {
                Some(format!("{} {}", if hi_open { "<" } else { "≤" }, number(hi)))
            }
            (Some((lo, lo_open)), Some((hi, hi_open))) => Some(format!(
                "in {}{}, {}{}",
                if lo_open { "(" } else { "[" },
                number(lo),
                number(hi),
                if hi_open { ")" } else { "]" }
            )),
        }
    }
}

fn collect_bounds(schema: &Value, root: &Value, range: &mut NumberRange, depth: usize) {
    if depth > 8 {
        return;
    }
    let schema = resolve(schema, root);
    let bound = |key: &str| schema.get(key).and_then(Value::as_f64);
    if let Some(m) = bound("minimum") {
        range.min = Some((m, false));
    }
    if let Some(m) = bound("exclusiveMinimum") {
        range.min = Some((m, true));
    }
    if let Some(m) = bound("maximum") {
        range.max = Some((m, false));
    }
    if let Some(m) = bound("exclusiveMaximum") {
        range.max = Some((m, true));
    }
    for key in ["anyOf", "oneOf", "allOf"] {
        if let Some(Value::Array(branches)) = schema.get(key) {
            for branch in branches {
                collect_bounds(branch, root, range, depth + 1);
            }
        }
    }
}

/// A number as the shortest text that reads back to it (`120`, `0.5`, `1e-12`).
pub(super) fn shortest(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        // Rust's `Display` for f64 is the shortest round-trip form; `{:e}` is too, and
        // shorter for very small or large numbers.
        let plain = format!("{x}");
        let exp = format!("{x:e}");
        if exp.len() < plain.len() {
            exp
        } else {
            plain
        }
    }
}

/// At most `limit` characters of `text` (an echoed value in a one-line message), with `…`
/// where it was cut.
pub(super) fn clip(text: &str, limit: usize) -> String {
    let one_line: String = text
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    match one_line.char_indices().nth(limit) {
        Some((at, _)) => format!("{}…", &one_line[..at]),
        None => one_line,
    }
}

/// Refuses a field of `settings` outside the range its schema declares, or NaN where a
/// number is asked ([`Error::BadValue`](crate::Error::BadValue) naming the field): the
/// settings' own `validate` calls it, so that a range is written once, on the field, and
/// holds for a program that builds the settings directly as for `--set`. The schema is
/// derived once per type. O(fields).
pub fn check_declared_ranges<S: Serialize + schemars::JsonSchema + 'static>(
    settings: &S,
) -> crate::Result<()> {
    let root = schema_of_type::<S>();
    let value = serde_json::to_value(settings).unwrap_or_default();
    for (name, property) in properties(&root) {
        let Some(range) = NumberRange::of(&property, &root) else {
            continue;
        };
        let bad = |message: String| crate::Error::BadValue {
            name: name.clone(),
            message,
        };
        match value.get(&name) {
            // serde_json writes NaN as null.
            Some(Value::Null) if !accepted_types(&property, &root).contains("null") => {
                return Err(bad(format!("NaN is out of range: {}", range.describe())))
            }
            Some(Value::Number(n)) => {
                let x = n.as_f64().unwrap_or(f64::NAN);
                if !range.contains(x) {
                    return Err(bad(format!(
                        "{} is out of range: {}",
                        shortest(x),
                        range.describe()
                    )));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// The JSON Schema of `S`, derived once per type and kept.
fn schema_of_type<S: schemars::JsonSchema + 'static>() -> std::sync::Arc<Value> {
    use std::any::TypeId;
    use std::collections::HashMap;
    use std::sync::{Arc, Mutex, OnceLock};
    static SCHEMAS: OnceLock<Mutex<HashMap<TypeId, Arc<Value>>>> = OnceLock::new();
    let schemas = SCHEMAS.get_or_init(Default::default);
    if let Some(found) = schemas
        .lock()
        .ok()
        .and_then(|m| m.get(&TypeId::of::<S>()).cloned())
    {
        return found;
    }
    let schema = Arc::new(serde_json::to_value(schemars::schema_for!(S)).unwrap_or_default());
    if let Ok(mut map) = schemas.lock() {
        map.insert(TypeId::of::<S>(), schema.clone());
    }
    schema
}
