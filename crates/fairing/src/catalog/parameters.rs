//! Parameter values as given — text from `--set NAME=VALUE`, typed values from a TOML or
//! JSON config file — with where each was given, so that every message about a value names
//! its origin (`--set`, `config.toml:3`, `config.toml:9 (stage 2)`).

use std::collections::BTreeMap;

use serde_json::Value;

/// A value as given.
#[derive(Clone, Debug, PartialEq)]
pub enum GivenValue {
    /// Text (`--set`): converted to the parameter's type by its schema.
    Text(String),
    /// A typed value (config files). A string here is converted like text, so that
    /// `pairs = "on"` and `pairs = true` both work.
    Json(Value),
}

impl GivenValue {
    /// The value as text, for messages.
    pub fn text(&self) -> String {
        match self {
            GivenValue::Text(t) => t.clone(),
            GivenValue::Json(Value::String(s)) => s.clone(),
            GivenValue::Json(v) => v.to_string(),
        }
    }
}

/// A parameter value and where it was given.
#[derive(Clone, Debug, PartialEq)]
pub struct Given {
    /// The value.
    pub value: GivenValue,
    /// `--set`, `file.toml:LINE`, `file.toml:LINE (stage N)`.
    pub origin: String,
}

/// The parameters given for one method run, by name; a later value for a name replaces an
/// earlier one (so `--set` given after a config file wins).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParameterMap {
    values: BTreeMap<String, Given>,
}

impl ParameterMap {
    /// No parameters.
    pub fn new() -> Self {
        Self::default()
    }

    /// Parameters from `--set NAME=VALUE` pairs.
    pub fn from_sets<'a>(sets: impl IntoIterator<Item = (&'a str, &'a str)>) -> Self {
        let mut map = Self::new();
        for (name, value) in sets {
            map.insert_text(name, value, "--set");
        }
        map
    }

    /// Sets `name` to text given at `origin`.
    pub fn insert_text(&mut self, name: &str, text: &str, origin: &str) -> &mut Self {
        self.insert(name, GivenValue::Text(text.to_owned()), origin)
    }

    /// Sets `name` to a typed value given at `origin`.
    pub fn insert_json(&mut self, name: &str, value: Value, origin: &str) -> &mut Self {
        self.insert(name, GivenValue::Json(value), origin)
    }

    /// Sets `name`.
    pub fn insert(&mut self, name: &str, value: GivenValue, origin: &str) -> &mut Self {
        self.values.insert(
            name.to_owned(),
            Given {
                value,
                origin: origin.to_owned(),
            },
        );
        self
    }

    /// Adds every value of `other`, which win over these.
    pub fn extend(&mut self, other: &ParameterMap) -> &mut Self {
        for (name, given) in &other.values {
            self.values.insert(name.clone(), given.clone());
        }
        self
    }

    /// The value given for `name`.
    pub fn get(&self, name: &str) -> Option<&Given> {
        self.values.get(name)
    }

    /// Every value, by name.
    pub fn iter(&self) -> impl Iterator<Item = (&String, &Given)> {
        self.values.iter()
    }

    /// Whether nothing was given.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// How many values were given.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Where `name` was given, or `--set` when it was not (a value the method refuses
    /// after defaults were filled in).
    pub fn origin_of(&self, name: &str) -> String {
        self.values
            .get(name)
            .map_or_else(|| "--set".to_owned(), |g| g.origin.clone())
    }
}
