//! Config files: method parameters, constraints and pipelines of stages, in TOML or JSON,
//! read into [`ParameterMap`]s whose every value knows its file and line.
//!
//! A config file holds
//! - top-level `name = value` pairs: parameters of whatever method runs;
//! - tables named after a method (`[smoothing-spline]`): parameters of that method only
//!   (they win over the top level);
//! - a `[constraints]` table: `fixed = [2, 5]`, `points = [4]`, `tolerance = 0.01`,
//!   `clamp-ends = "g0"`, `corners = "none"` (or `"auto"`, or `[0, 57]`);
//! - an array of `[[stage]]` tables, each with a `method` and that method's parameters: a
//!   pipeline; the stages run in order, each on the points the previous one produced.
//!
//! ```toml
//! [constraints]
//! fixed = [0, 64]
//! tolerance = 0.05
//!
//! [[stage]]
//! method = "smoothing-spline"
//! p = 0.9999
//!
//! [[stage]]
//! method = "two-phase"
//! ```
//!
//! JSON (a file ending in `.json` or starting with `{`) has the same structure:
//! `{"constraints": {...}, "stage": [{"method": ...}, ...]}`.

use serde_json::Value;

use super::parameters::ParameterMap;
use crate::{EndClamp, Error, Result};

/// The key of the pipeline's stage tables.
pub const STAGE_KEY: &str = "stage";
/// The key of the constraints table.
pub const CONSTRAINTS_KEY: &str = "constraints";

/// A config file, read and parsed into a TOML table (JSON is converted).
#[derive(Debug, Clone)]
pub struct ConfigFile {
    /// The path as given.
    pub name: String,
    /// The text, for line numbers.
    pub text: String,
    /// The parsed content.
    pub table: toml::Table,
}

/// Constraints set in a config file's `[constraints]`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ConfigConstraints {
    /// `fixed = [...]`.
    pub fixed: Option<Vec<usize>>,
    /// `points = [...]`.
    pub points: Option<Vec<usize>>,
    /// `tolerance = D`.
    pub tolerance: Option<f64>,
    /// `clamp-ends = "g0" | "g1" | "g2"`.
    pub clamp_ends: Option<EndClamp>,
    /// `corners = "auto" | "none" | [i, j, ...]`.
    pub corners: Option<crate::corners::Corners>,
}

/// One stage of a pipeline as the file gives it.
#[derive(Debug, Clone)]
pub struct StageConfig {
    /// The method's name.
    pub method: String,
    /// Where `method = ...` is (`file:LINE`).
    pub origin: String,
    /// Its parameters, each with its line.
    pub parameters: ParameterMap,
}

/// The line (from 1) of a byte offset.
fn line_at(text: &str, offset: usize) -> usize {
    1 + text
        .as_bytes()
        .iter()
        .take(offset)
        .filter(|b| **b == b'\n')
        .count()
}

impl ConfigFile {
    /// Reads and parses `path`.
    pub fn read(path: &std::path::Path) -> Result<ConfigFile> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| Error::Config {
            origin: name.clone(),
            message: format!("cannot read: {}", io_reason(&e)),
        })?;
        ConfigFile::parse(&name, &text)
    }

    /// Parses config text; `name` is used in messages and decides JSON (`.json`, or text
    /// starting with `{`) or TOML.
    pub fn parse(name: &str, text: &str) -> Result<ConfigFile> {
        let json = name.to_ascii_lowercase().ends_with(".json") || text.trim_start().starts_with('{');
        let table = if json {
            let value: Value = serde_json::from_str(text).map_err(|e| Error::Config {
                origin: format!("{name}:{}", e.line().max(1)),
                message: format!("not valid JSON: {e}"),
            })?;
            match json_to_toml(&value) {
                Some(toml::Value::Table(table)) => table,
                _ => {
                    return Err(Error::Config {
                        origin: name.into(),
                        message: "a JSON config must be an object of names and values (no nulls)".into(),
                    })
                }
            }
        } else {
            toml::from_str(text).map_err(|e| Error::Config {
                origin: match e.span() {
                    Some(span) => format!("{name}:{}", line_at(text, span.start)),
                    None => name.to_owned(),
                },
                message: e.message().to_string(),
            })?
        };
        Ok(ConfigFile {
            name: name.into(),
            text: text.into(),
            table,
        })
    }

    /// `file:LINE` of the first line that sets `key` (`key =` in TOML, `"key":` in JSON), or
    /// the file name.
    pub fn locate(&self, key: &str) -> String {
        let quoted = format!("\"{key}\"");
        let line = self
            .text
            .lines()
            .position(|l| {
                let l = l.trim_start().trim_start_matches(['{', ',', ' ']);
                l.strip_prefix(key)
                    .is_some_and(|rest| rest.trim_start().starts_with('='))
                    || l.strip_prefix(&quoted)
                        .is_some_and(|rest| rest.trim_start().starts_with(':'))
            })
            .map_or(0, |i| i + 1);
        if line > 0 {
            format!("{}:{line}", self.name)
        } else {
            self.name.clone()
        }
    }

    /// The line of the `number`-th (from 0) `[[stage]]` header, if the file is TOML.
    fn stage_header(&self, number: usize) -> Option<usize> {
        self.text
            .lines()
            .enumerate()
            .filter(|(_, l)| l.trim().starts_with("[[stage]]"))
            .nth(number)
            .map(|(i, _)| i)
    }

    /// Like [`locate`](Self::locate), searching from the `number`-th `[[stage]]` header.
    fn locate_in_stage(&self, key: &str, number: usize) -> String {
        let Some(start) = self.stage_header(number) else {
            return self.locate(key);
        };
        self.text
            .lines()
            .enumerate()
            .skip(start + 1)
            .find(|(_, l)| {
                l.trim_start()
                    .strip_prefix(key)
                    .is_some_and(|rest| rest.trim_start().starts_with('='))
            })
            .map_or_else(|| self.locate(key), |(i, _)| format!("{}:{}", self.name, i + 1))
    }

    /// A parameter value as JSON (scalars and arrays; tables are refused).
    fn value(&self, key: &str, value: &toml::Value, origin: &str) -> Result<Value> {
        match value {
            toml::Value::Table(_) => Err(Error::Parameter {
                origin: origin.to_owned(),
                message: format!("`{key}` must be a number, string, boolean or list"),
            }),
            other => serde_json::to_value(other).map_err(|e| Error::Parameter {
                origin: origin.to_owned(),
                message: format!("`{key}`: {e}"),
            }),
        }
    }

    /// The parameters for `method`: the top-level values, then those of the table named
    /// after the method (which win).
    pub fn method_values(&self, method: &str) -> Result<ParameterMap> {
        let mut out = ParameterMap::new();
        for (key, value) in &self.table {
            if key == STAGE_KEY || key == CONSTRAINTS_KEY || value.is_table() {
                continue;
            }
            let origin = self.locate(key);
            out.insert_json(key, self.value(key, value, &origin)?, &origin);
        }
        if let Some(toml::Value::Table(section)) = self.table.get(method) {
            for (key, value) in section {
                let origin = self.locate(key);
                out.insert_json(key, self.value(key, value, &origin)?, &origin);
            }
        }
        Ok(out)
    }

    /// Refuses a table that is neither `[constraints]`, a `[[stage]]` nor named after a
    /// method (`is_method`), at its line, with the known names (`known`): its values would
    /// otherwise be ignored without a word. O(size of the file).
    pub fn check_tables(&self, is_method: impl Fn(&str) -> bool, known: impl Fn() -> String) -> Result<()> {
        for (key, value) in &self.table {
            if key == STAGE_KEY || key == CONSTRAINTS_KEY || !value.is_table() || is_method(key) {
                continue;
            }
            return Err(Error::Config {
                origin: self.locate_table(key),
                message: format!(
                    "`[{}]` names no method (a table is `[constraints]`, `[[stage]]` or a method's name: {})",
                    super::schema::clip(key, 80),
                    known()
                ),
            });
        }
        Ok(())
    }

    /// `file:LINE` of the table header `[key]` (TOML) or `"key":` (JSON), or the file name.
    fn locate_table(&self, key: &str) -> String {
        let header = format!("[{key}]");
        let quoted = format!("\"{key}\"");
        let line = self.text.lines().position(|l| {
            let l = l.trim();
            l.starts_with(&header)
                || l.trim_start_matches(['{', ',', ' '])
                    .strip_prefix(&quoted)
                    .is_some_and(|rest| rest.trim_start().starts_with(':'))
        });
        match line {
            Some(i) => format!("{}:{}", self.name, i + 1),
            None => self.name.clone(),
        }
    }

    /// Whether the file is a pipeline (has `[[stage]]`s).
    pub fn has_stages(&self) -> bool {
        self.table.contains_key(STAGE_KEY)
    }

    /// The stages, when the file is a pipeline (`[[stage]]`); `None` otherwise.
    pub fn stages(&self) -> Result<Option<Vec<StageConfig>>> {
        let Some(value) = self.table.get(STAGE_KEY) else {
            return Ok(None);
        };
        let origin = match self.stage_header(0) {
            Some(line) => format!("{}:{}", self.name, line + 1),
            None => self.locate(STAGE_KEY),
        };
        let toml::Value::Array(items) = value else {
            return Err(Error::Config {
                origin,
                message: "`stage` must be a list of tables, each with a `method`".into(),
            });
        };
        if items.is_empty() {
            return Err(Error::Config {
                origin,
                message: "the pipeline has no stages".into(),
            });
        }
        let mut stages = Vec::with_capacity(items.len());
        for (number, item) in items.iter().enumerate() {
            let header = self
                .stage_header(number)
                .map_or_else(|| origin.clone(), |line| format!("{}:{}", self.name, line + 1));
            let toml::Value::Table(table) = item else {
                return Err(Error::Config {
                    origin: header,
                    message: format!("stage {} is not a table", number + 1),
                });
            };
            let Some(toml::Value::String(name)) = table.get("method") else {
                return Err(Error::Config {
                    origin: header,
                    message: format!("stage {} has no `method = \"...\"`", number + 1),
                });
            };
            let mut parameters = ParameterMap::new();
            for (key, value) in table {
                if key != "method" {
                    let origin = format!("{} (stage {})", self.locate_in_stage(key, number), number + 1);
                    parameters.insert_json(key, self.value(key, value, &origin)?, &origin);
                }
            }
            stages.push(StageConfig {
                method: name.clone(),
                origin: format!(
                    "{} (stage {})",
                    self.locate_in_stage("method", number),
                    number + 1
                ),
                parameters,
            });
        }
        Ok(Some(stages))
    }

    /// The `[constraints]` table.
    pub fn constraints(&self) -> Result<ConfigConstraints> {
        let Some(value) = self.table.get(CONSTRAINTS_KEY) else {
            return Ok(ConfigConstraints::default());
        };
        let toml::Value::Table(table) = value else {
            return Err(Error::Config {
                origin: self.locate(CONSTRAINTS_KEY),
                message: "`constraints` must be a table".into(),
            });
        };
        let mut out = ConfigConstraints::default();
        for (key, value) in table {
            let origin = self.locate(key);
            let bad = |message: String| Error::Config {
                origin: origin.clone(),
                message,
            };
            match key.as_str() {
                "fixed" | "points" => {
                    let list = value
                        .as_array()
                        .and_then(|a| {
                            a.iter()
                                .map(|v| v.as_integer().and_then(|i| usize::try_from(i).ok()))
                                .collect::<Option<Vec<usize>>>()
                        })
                        .ok_or_else(|| bad(format!("`{key}` must be a list of point indices from 0")))?;
                    if key == "fixed" {
                        out.fixed = Some(list);
                    } else {
                        out.points = Some(list);
                    }
                }
                "tolerance" => {
                    let d = value
                        .as_float()
                        .or_else(|| value.as_integer().map(|i| i as f64))
                        .filter(|d| d.is_finite() && *d > 0.0)
                        .ok_or_else(|| bad("`tolerance` must be a positive number".into()))?;
                    out.tolerance = Some(d);
                }
                "clamp-ends" => {
                    out.clamp_ends = Some(match value.as_str() {
                        Some("g0") => EndClamp::G0,
                        Some("g1") => EndClamp::G1,
                        Some("g2") => EndClamp::G2,
                        _ => return Err(bad("`clamp-ends` must be \"g0\", \"g1\" or \"g2\"".into())),
                    });
                }
                "corners" => {
                    use crate::corners::Corners;
                    let list = || {
                        value.as_array().and_then(|a| {
                            a.iter()
                                .map(|v| v.as_integer().and_then(|i| usize::try_from(i).ok()))
                                .collect::<Option<Vec<usize>>>()
                        })
                    };
                    out.corners = Some(match (value.as_str().map(Corners::named), list()) {
                        (Some(Some(named)), _) => named,
                        (None, Some(at)) => Corners::At(at),
                        _ => {
                            return Err(bad(
                                "`corners` must be \"auto\", \"none\" or a list of point indices from 0"
                                    .into(),
                            ))
                        }
                    });
                }
                _ => {
                    return Err(bad(format!(
                        "`{key}` is not a constraint (known: fixed, points, tolerance, clamp-ends, corners)"
                    )))
                }
            }
        }
        Ok(out)
    }
}

/// An I/O error's reason without the "(os error N)" tail.
fn io_reason(error: &std::io::Error) -> String {
    let text = error.to_string();
    match text.find(" (os error") {
        Some(i) => text[..i].to_owned(),
        None => text,
    }
}

/// Converts JSON to TOML values; `None` for a null anywhere (TOML has none).
fn json_to_toml(value: &Value) -> Option<toml::Value> {
    Some(match value {
        Value::Null => return None,
        Value::Bool(b) => toml::Value::Boolean(*b),
        Value::Number(n) => match n.as_i64() {
            Some(i) => toml::Value::Integer(i),
            None => toml::Value::Float(n.as_f64()?),
        },
        Value::String(s) => toml::Value::String(s.clone()),
        Value::Array(items) => {
            toml::Value::Array(items.iter().map(json_to_toml).collect::<Option<Vec<_>>>()?)
        }
        Value::Object(map) => toml::Value::Table(
            map.iter()
                .map(|(k, v)| Some((k.clone(), json_to_toml(v)?)))
                .collect::<Option<toml::Table>>()?,
        ),
    })
}

/// A JSON value as TOML text (for `--print-config`): numbers with a decimal point or
/// exponent stay floats, strings quoted.
pub(super) fn toml_text(value: &Value) -> String {
    match value {
        Value::Number(n) if n.is_f64() => {
            let v = n.as_f64().unwrap_or(0.0);
            let text = v.to_string();
            if text.contains(['.', 'e', 'E']) {
                text
            } else {
                format!("{text}.0")
            }
        }
        Value::Number(n) => n.to_string(),
        Value::Bool(b) => b.to_string(),
        Value::String(s) => toml::Value::String(s.clone()).to_string(),
        Value::Array(items) => format!("[{}]", items.iter().map(toml_text).collect::<Vec<_>>().join(", ")),
        Value::Null => "\"none\"".into(),
        Value::Object(map) => {
            let fields: Vec<String> = map
                .iter()
                .map(|(k, v)| format!("{k} = {}", toml_text(v)))
                .collect();
            format!("{{ {} }}", fields.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stages_constraints_and_parameters_from_toml() {
        let text = "p = 0.5\n[constraints]\nfixed = [0, 4]\ntolerance = 0.25\nclamp-ends = \"g0\"\n\n[[stage]]\nmethod = \"nurbs-weights\"\ncriterion = \"e2\"\n\n[[stage]]\nmethod = \"two-phase\"\n";
        let file = ConfigFile::parse("pipe.toml", text).unwrap();
        let stages = file.stages().unwrap().unwrap();
        assert_eq!(stages.len(), 2);
        assert_eq!(stages[0].method, "nurbs-weights");
        let criterion = stages[0].parameters.get("criterion").unwrap();
        assert_eq!(criterion.value.text(), "e2");
        assert_eq!(criterion.origin, "pipe.toml:9 (stage 1)");
        assert_eq!(stages[1].method, "two-phase");
        // A name set in two stages is located in each stage's own table.
        let text = "[[stage]]\nmethod = \"nurbs-weights\"\ncriterion = \"e2\"\n[[stage]]\nmethod = \"nurbs-weights\"\ncriterion = \"e3\"\n";
        let two = ConfigFile::parse("two.toml", text)
            .unwrap()
            .stages()
            .unwrap()
            .unwrap();
        assert_eq!(
            two[1].parameters.get("criterion").unwrap().origin,
            "two.toml:6 (stage 2)"
        );
        let constraints = file.constraints().unwrap();
        assert_eq!(constraints.fixed, Some(vec![0, 4]));
        assert_eq!(constraints.tolerance, Some(0.25));
        assert_eq!(constraints.clamp_ends, Some(EndClamp::G0));
        let corners = |text: &str| {
            ConfigFile::parse("c.toml", &format!("[constraints]\ncorners = {text}\n"))
                .and_then(|f| f.constraints())
                .map(|c| c.corners)
        };
        use crate::corners::Corners;
        assert_eq!(corners("\"none\"").unwrap(), Some(Corners::None));
        assert_eq!(corners("[0, 57]").unwrap(), Some(Corners::At(vec![0, 57])));
        let e = corners("\"often\"").unwrap_err().to_string();
        assert!(e.contains("c.toml:2") && e.contains("corners"), "{e}");
        // Top-level scalars stay parameters; stage and constraints tables are not.
        let values = file.method_values("two-phase").unwrap();
        assert_eq!(values.len(), 1);
        assert_eq!(values.get("p").unwrap().origin, "pipe.toml:1");
    }

    #[test]
    fn json_config_is_the_same_structure() {
        let text = "{\n  \"constraints\": {\"fixed\": [1]},\n  \"stage\": [\n    {\"method\": \"two-phase\"}\n  ],\n  \"criterion\": \"ek\"\n}\n";
        let file = ConfigFile::parse("pipe.json", text).unwrap();
        assert_eq!(file.stages().unwrap().unwrap()[0].method, "two-phase");
        assert_eq!(file.constraints().unwrap().fixed, Some(vec![1]));
        let values = file.method_values("x").unwrap();
        assert_eq!(values.get("criterion").unwrap().origin, "pipe.json:6");
    }

    #[test]
    fn bad_configs_name_the_file_and_line() {
        let e = ConfigFile::parse("a.toml", "p = 1\nq = = 2\n").unwrap_err();
        assert!(e.to_string().starts_with("a.toml:2:"), "{e}");
        let e = ConfigFile::parse("a.json", "{\"p\": 1,\n \"q\": }").unwrap_err();
        assert!(e.to_string().starts_with("a.json:2:"), "{e}");
        let file = ConfigFile::parse("a.toml", "[[stage]]\np = 1\n").unwrap();
        let e = file.stages().unwrap_err();
        assert!(
            e.to_string().contains("a.toml:1") && e.to_string().contains("no `method"),
            "{e}"
        );
        let file = ConfigFile::parse("a.toml", "[constraints]\ntolerance = -1\n").unwrap();
        let e = file.constraints().unwrap_err();
        assert!(e.to_string().starts_with("a.toml:2"), "{e}");
        let file = ConfigFile::parse("a.toml", "[constraints]\nfixd = [1]\n").unwrap();
        assert!(file.constraints().is_err());
    }

    #[test]
    fn toml_text_reads_back() {
        for value in [
            serde_json::json!(1.0),
            serde_json::json!(1e-300),
            serde_json::json!(7),
            serde_json::json!("a \"b\""),
            serde_json::json!(true),
            serde_json::json!([1, 2]),
        ] {
            let text = format!("x = {}\n", toml_text(&value));
            let table: toml::Table = toml::from_str(&text).unwrap();
            assert_eq!(serde_json::to_value(&table["x"]).unwrap(), value, "{text}");
        }
    }
}
