//! Config files: method parameters, constraints and pipelines of stages, in TOML or JSON.
//!
//! A config file is read by `--config FILE` (TOML, or JSON when the file ends in `.json` or
//! starts with `{`). It may hold:
//! - top-level `name = value` pairs: parameters of whatever method runs (see
//!   [`parameters`](crate::parameters));
//! - tables named after a method (`[smoothing-spline]`): parameters of that method only;
//! - a `[constraints]` table: `fixed = [2, 5]`, `points = [4]`, `tolerance = 0.01`,
//!   `clamp-ends = "g0"`; the command-line options of the same names win;
//! - an array of `[[stage]]` tables, each with a `method` and that method's parameters: a
//!   pipeline. The stages run in order, each on the points the previous one produced.
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
//! `fair curve INPUT ... --print-config` prints the config a command line implies, in this
//! form, with every parameter of every stage (defaults filled in), once a run of it (whose
//! result is discarded) has shown that the methods accept every value.

use crate::args::ClampEnds;
use crate::error::{Error, Result};
use crate::parameters::Given;
use crate::registry::{self, MethodInfo, MethodKind};

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

/// Constraints set in a config file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ConfigConstraints {
    /// `fixed = [...]`.
    pub fixed: Option<Vec<usize>>,
    /// `points = [...]`.
    pub points: Option<Vec<usize>>,
    /// `tolerance = D`.
    pub tolerance: Option<f64>,
    /// `clamp-ends = "g0" | "g1" | "g2"`.
    pub clamp_ends: Option<ClampEnds>,
}

/// One stage of a pipeline: a method and its parameters as given in the file.
#[derive(Debug, Clone)]
pub struct StageConfig {
    /// The method.
    pub method: &'static MethodInfo,
    /// Its parameters, with where each was given.
    pub values: Vec<(String, Given)>,
}

impl ConfigFile {
    /// Reads and parses `path`.
    pub fn read(path: &std::path::Path) -> Result<ConfigFile> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| Error::Read {
            path: name.clone(),
            reason: crate::input::io_reason(&e),
        })?;
        ConfigFile::parse(&name, &text)
    }

    /// Parses config text; `name` is used in messages and decides JSON (`.json`) or TOML.
    pub fn parse(name: &str, text: &str) -> Result<ConfigFile> {
        let json = name.to_ascii_lowercase().ends_with(".json") || text.trim_start().starts_with('{');
        let table = if json {
            let value: serde_json::Value = serde_json::from_str(text).map_err(|e| Error::Parse {
                path: name.into(),
                line: e.line().max(1),
                message: format!("not valid JSON: {e}"),
            })?;
            match json_to_toml(&value) {
                Some(toml::Value::Table(table)) => table,
                _ => {
                    return Err(Error::Invalid {
                        path: name.into(),
                        message: "a JSON config must be an object of names and values (no nulls)".into(),
                    })
                }
            }
        } else {
            toml::from_str(text).map_err(|e| {
                let message = e.message().to_string();
                match e.span() {
                    Some(span) => Error::Parse {
                        path: name.into(),
                        line: line_at(text, span.start),
                        message,
                    },
                    None => Error::Invalid {
                        path: name.into(),
                        message,
                    },
                }
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

    /// Like [`locate`](Self::locate), but searching from the `number`-th (from 0) `[[stage]]`
    /// header of a TOML file.
    fn locate_in_stage(&self, key: &str, number: usize) -> String {
        let start = self
            .text
            .lines()
            .enumerate()
            .filter(|(_, l)| l.trim().starts_with("[[stage]]"))
            .nth(number)
            .map(|(i, _)| i);
        let Some(start) = start else {
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

    /// A scalar parameter value as text.
    fn scalar(&self, key: &str, value: &toml::Value) -> Result<Given> {
        let text = match value {
            toml::Value::String(s) => s.clone(),
            toml::Value::Integer(i) => i.to_string(),
            toml::Value::Float(f) => f.to_string(),
            toml::Value::Boolean(b) => b.to_string(),
            _ => {
                return Err(Error::Parameter {
                    origin: self.locate(key),
                    message: format!("`{key}` must be a number, string or boolean"),
                })
            }
        };
        Ok(Given {
            value: text,
            origin: self.locate(key),
        })
    }

    /// The parameters for `method`: the top-level scalars, then those of the table named
    /// after the method (which win).
    pub fn method_values(&self, method: &str) -> Result<Vec<(String, Given)>> {
        let mut out = Vec::new();
        for (key, value) in &self.table {
            if key == STAGE_KEY || key == CONSTRAINTS_KEY || value.is_table() {
                continue;
            }
            out.push((key.clone(), self.scalar(key, value)?));
        }
        if let Some(toml::Value::Table(section)) = self.table.get(method) {
            for (key, value) in section {
                out.push((key.clone(), self.scalar(key, value)?));
            }
        }
        Ok(out)
    }

    /// The stages, when the file is a pipeline (`[[stage]]`); `None` otherwise.
    pub fn stages(&self, kind: MethodKind) -> Result<Option<Vec<StageConfig>>> {
        let Some(value) = self.table.get(STAGE_KEY) else {
            return Ok(None);
        };
        let origin = self.locate(STAGE_KEY);
        let origin = if origin == self.name {
            // TOML's `[[stage]]` header, not a `stage =` line.
            self.text
                .lines()
                .position(|l| l.trim().starts_with("[[stage]]"))
                .map_or(self.name.clone(), |i| format!("{}:{}", self.name, i + 1))
        } else {
            origin
        };
        let toml::Value::Array(items) = value else {
            return Err(Error::Parameter {
                origin,
                message: "`stage` must be a list of tables, each with a `method`".into(),
            });
        };
        if items.is_empty() {
            return Err(Error::Parameter {
                origin,
                message: "the pipeline has no stages".into(),
            });
        }
        let mut stages = Vec::with_capacity(items.len());
        for (number, item) in items.iter().enumerate() {
            let toml::Value::Table(table) = item else {
                return Err(Error::Parameter {
                    origin,
                    message: format!("stage {} is not a table", number + 1),
                });
            };
            let Some(toml::Value::String(name)) = table.get("method") else {
                return Err(Error::Parameter {
                    origin,
                    message: format!("stage {} has no `method = \"...\"`", number + 1),
                });
            };
            let method = registry::find(name, kind)?;
            let mut values = Vec::new();
            for (key, value) in table {
                if key != "method" {
                    let mut given = self.scalar(key, value)?;
                    given.origin = format!("{} (stage {})", self.locate_in_stage(key, number), number + 1);
                    values.push((key.clone(), given));
                }
            }
            stages.push(StageConfig { method, values });
        }
        Ok(Some(stages))
    }

    /// The `[constraints]` table.
    pub fn constraints(&self) -> Result<ConfigConstraints> {
        let Some(value) = self.table.get(CONSTRAINTS_KEY) else {
            return Ok(ConfigConstraints::default());
        };
        let toml::Value::Table(table) = value else {
            return Err(Error::Parameter {
                origin: self.locate(CONSTRAINTS_KEY),
                message: "`constraints` must be a table".into(),
            });
        };
        let mut out = ConfigConstraints::default();
        for (key, value) in table {
            let origin = self.locate(key);
            let bad = |message: String| Error::Parameter {
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
                        Some("g0") => ClampEnds::G0,
                        Some("g1") => ClampEnds::G1,
                        Some("g2") => ClampEnds::G2,
                        _ => return Err(bad("`clamp-ends` must be \"g0\", \"g1\" or \"g2\"".into())),
                    });
                }
                _ => {
                    return Err(bad(format!(
                        "`{key}` is not a constraint (known: fixed, points, tolerance, clamp-ends)"
                    )))
                }
            }
        }
        Ok(out)
    }
}

/// Converts JSON to TOML values; `None` for a null anywhere (TOML has none).
fn json_to_toml(value: &serde_json::Value) -> Option<toml::Value> {
    Some(match value {
        serde_json::Value::Null => return None,
        serde_json::Value::Bool(b) => toml::Value::Boolean(*b),
        serde_json::Value::Number(n) => match n.as_i64() {
            Some(i) => toml::Value::Integer(i),
            None => toml::Value::Float(n.as_f64()?),
        },
        serde_json::Value::String(s) => toml::Value::String(s.clone()),
        serde_json::Value::Array(items) => {
            toml::Value::Array(items.iter().map(json_to_toml).collect::<Option<Vec<_>>>()?)
        }
        serde_json::Value::Object(map) => toml::Value::Table(
            map.iter()
                .map(|(k, v)| Some((k.clone(), json_to_toml(v)?)))
                .collect::<Option<toml::Table>>()?,
        ),
    })
}

/// The line (from 1) of a byte offset.
pub(crate) fn line_at(text: &str, offset: usize) -> usize {
    1 + text
        .as_bytes()
        .iter()
        .take(offset)
        .filter(|b| **b == b'\n')
        .count()
}

/// The TOML config that reproduces a run: its constraints and its stages with every parameter
/// (given values, else the method's defaults). What `--print-config` prints.
pub fn render(
    constraints: &crate::constraints::Constraints,
    stages: &[(&MethodInfo, Vec<(String, String)>)],
) -> String {
    let mut text = String::new();
    let list = |v: &[usize]| {
        format!(
            "[{}]",
            v.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")
        )
    };
    let mut lines = Vec::new();
    if !constraints.fixed.is_empty() {
        lines.push(format!("fixed = {}", list(&constraints.fixed)));
    }
    if !constraints.bad_points.is_empty() {
        lines.push(format!("points = {}", list(&constraints.bad_points)));
    }
    if let Some(d) = constraints.tolerance {
        lines.push(format!("tolerance = {}", toml_number(d)));
    }
    if let Some(c) = constraints.clamp_ends {
        lines.push(format!("clamp-ends = \"{}\"", c.name()));
    }
    if !lines.is_empty() {
        text.push_str("[constraints]\n");
        for line in lines {
            text.push_str(&line);
            text.push('\n');
        }
    }
    for (method, values) in stages {
        if !text.is_empty() {
            text.push('\n');
        }
        text.push_str(&format!("[[stage]]\nmethod = \"{}\"\n", method.name));
        for parameter in method.parameters {
            let value = values
                .iter()
                .find(|(k, _)| k == parameter.name)
                .map_or(parameter.default, |(_, v)| v.as_str());
            let key = if parameter
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
            {
                parameter.name.to_string()
            } else {
                format!("\"{}\"", parameter.name)
            };
            text.push_str(&format!(
                "{key} = {}  # {}\n",
                toml_value(value),
                parameter.meaning
            ));
        }
    }
    text
}

fn toml_number(v: f64) -> String {
    let text = v.to_string();
    if text.contains(['.', 'e', 'E']) || text.contains("inf") || text.contains("NaN") {
        text
    } else {
        format!("{text}.0")
    }
}

/// A parameter value as TOML: numbers and booleans bare, everything else quoted.
fn toml_value(value: &str) -> String {
    if value == "true" || value == "false" {
        return value.into();
    }
    if value.parse::<i64>().is_ok() {
        return value.into();
    }
    match value.parse::<f64>() {
        Ok(v) if v.is_finite() => toml_number(v),
        _ => format!("\"{}\"", value.replace('\\', "\\\\").replace('"', "\\\"")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stages_constraints_and_parameters_from_toml() {
        let text = "p = 0.5\n[constraints]\nfixed = [0, 4]\ntolerance = 0.25\nclamp-ends = \"g0\"\n\n[[stage]]\nmethod = \"nurbs-weights\"\ncriterion = \"e2\"\n\n[[stage]]\nmethod = \"two-phase\"\n";
        let file = ConfigFile::parse("pipe.toml", text).unwrap();
        let stages = file.stages(MethodKind::Curve).unwrap().unwrap();
        assert_eq!(stages.len(), 2);
        assert_eq!(stages[0].method.name, "nurbs-weights");
        assert_eq!(stages[0].values[0].0, "criterion");
        assert_eq!(stages[0].values[0].1.value, "e2");
        assert_eq!(stages[0].values[0].1.origin, "pipe.toml:9 (stage 1)");
        assert_eq!(stages[1].method.name, "two-phase");
        // A name set in two stages is located in each stage's own table.
        let text = "[[stage]]\nmethod = \"nurbs-weights\"\ncriterion = \"e2\"\n[[stage]]\nmethod = \"nurbs-weights\"\ncriterion = \"e3\"\n";
        let two = ConfigFile::parse("two.toml", text)
            .unwrap()
            .stages(MethodKind::Curve)
            .unwrap()
            .unwrap();
        assert_eq!(two[1].values[0].1.origin, "two.toml:6 (stage 2)");
        let constraints = file.constraints().unwrap();
        assert_eq!(constraints.fixed, Some(vec![0, 4]));
        assert_eq!(constraints.tolerance, Some(0.25));
        assert_eq!(constraints.clamp_ends, Some(ClampEnds::G0));
        // Top-level scalars stay parameters; stage and constraints tables are not.
        let values = file.method_values("two-phase").unwrap();
        assert_eq!(values.len(), 1);
        assert_eq!(values[0].0, "p");
        assert_eq!(values[0].1.origin, "pipe.toml:1");
    }

    #[test]
    fn json_config_is_the_same_structure() {
        let text = "{\n  \"constraints\": {\"fixed\": [1]},\n  \"stage\": [\n    {\"method\": \"two-phase\"}\n  ],\n  \"criterion\": \"ek\"\n}\n";
        let file = ConfigFile::parse("pipe.json", text).unwrap();
        assert_eq!(
            file.stages(MethodKind::Curve).unwrap().unwrap()[0].method.name,
            "two-phase"
        );
        assert_eq!(file.constraints().unwrap().fixed, Some(vec![1]));
        let values = file.method_values("x").unwrap();
        assert_eq!(values[0].1.origin, "pipe.json:6");
    }

    #[test]
    fn bad_configs_name_the_file_and_line() {
        let e = ConfigFile::parse("a.toml", "p = 1\nq = = 2\n").unwrap_err();
        assert!(e.one_line().starts_with("a.toml:2:"), "{}", e.one_line());
        let e = ConfigFile::parse("a.json", "{\"p\": 1,\n \"q\": }").unwrap_err();
        assert!(e.one_line().starts_with("a.json:2:"), "{}", e.one_line());
        let file = ConfigFile::parse("a.toml", "[[stage]]\nmethod = \"frobnicate\"\n").unwrap();
        assert!(file.stages(MethodKind::Curve).is_err());
        let file = ConfigFile::parse("a.toml", "[[stage]]\np = 1\n").unwrap();
        let e = file.stages(MethodKind::Curve).unwrap_err();
        assert!(
            e.one_line().contains("a.toml:1") && e.one_line().contains("no `method"),
            "{}",
            e.one_line()
        );
        let file = ConfigFile::parse("a.toml", "[constraints]\ntolerance = -1\n").unwrap();
        let e = file.constraints().unwrap_err();
        assert!(e.one_line().starts_with("a.toml:2"), "{}", e.one_line());
        let file = ConfigFile::parse("a.toml", "[constraints]\nfixd = [1]\n").unwrap();
        assert!(file.constraints().is_err());
    }

    #[test]
    fn rendered_config_reads_back_as_the_same_pipeline() {
        let constraints = crate::constraints::Constraints {
            fixed: vec![0, 3],
            bad_points: vec![],
            tolerance: Some(0.5),
            clamp_ends: Some(ClampEnds::G1),
        };
        let method = registry::find("nurbs-weights", MethodKind::Curve).unwrap();
        let text = render(&constraints, &[(method, vec![("criterion".into(), "e3".into())])]);
        let file = ConfigFile::parse("printed.toml", &text).unwrap();
        let stages = file.stages(MethodKind::Curve).unwrap().unwrap();
        assert_eq!(stages.len(), 1);
        let criterion = stages[0].values.iter().find(|(k, _)| k == "criterion").unwrap();
        assert_eq!(criterion.1.value, "e3");
        // Every parameter is written, defaults filled in.
        assert_eq!(stages[0].values.len(), method.parameters.len());
        let c = file.constraints().unwrap();
        assert_eq!(c.fixed, Some(vec![0, 3]));
        assert_eq!(c.tolerance, Some(0.5));
        assert_eq!(c.clamp_ends, Some(ClampEnds::G1));
    }
}
