//! Method parameters from `--config FILE` (TOML) and `--set NAME=VALUE`, checked against the
//! method's list in the [`registry`](crate::registry).
//!
//! A config file holds `name = value` pairs at the top level (for whatever method runs) and
//! optionally tables named after a method (`[smoothing-spline]`) that apply only to it.
//! `--set` overrides the file. Every name must be a parameter of the method.

use crate::args::Setting;
use crate::error::{Error, Result};
use crate::registry::MethodInfo;
use std::collections::BTreeMap;

/// A parameter value as given, and where it came from (for messages).
#[derive(Debug, Clone, PartialEq)]
pub struct Given {
    /// The value as text (TOML strings without quotes).
    pub value: String,
    /// `--set` or `file.toml:LINE`.
    pub origin: String,
}

/// The parameters given for one method run, by name.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Parameters {
    values: BTreeMap<String, Given>,
}

impl Parameters {
    /// Collects parameters for `method` from an optional config file and `--set`s, and checks
    /// every name against the method.
    pub fn collect(
        method: &MethodInfo,
        config: Option<&std::path::Path>,
        settings: &[Setting],
    ) -> Result<Parameters> {
        let mut values = BTreeMap::new();
        if let Some(path) = config {
            let name = path.display().to_string();
            let text = std::fs::read_to_string(path).map_err(|e| Error::Read {
                path: name.clone(),
                reason: crate::input::io_reason(&e),
            })?;
            for (key, given) in parse_config(&name, &text, method.name)? {
                values.insert(key, given);
            }
        }
        for setting in settings {
            values.insert(
                setting.name.clone(),
                Given {
                    value: setting.value.clone(),
                    origin: "--set".into(),
                },
            );
        }
        for (name, given) in &values {
            if method.parameter(name).is_none() {
                let known: Vec<&str> = method.parameters.iter().map(|p| p.name).collect();
                let known = if known.is_empty() {
                    "it has none yet".to_string()
                } else {
                    format!("known: {}", known.join(", "))
                };
                return Err(Error::Parameter {
                    origin: given.origin.clone(),
                    message: format!("`{}` is not a parameter of `{}` ({known})", name, method.name),
                });
            }
        }
        Ok(Parameters { values })
    }

    /// The raw value of `name`, if given.
    pub fn get(&self, name: &str) -> Option<&Given> {
        self.values.get(name)
    }

    /// `name` as a finite number, or `default` when not given.
    pub fn number(&self, name: &str, default: f64) -> Result<f64> {
        match self.values.get(name) {
            None => Ok(default),
            Some(given) => match given.value.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(Error::Parameter {
                    origin: given.origin.clone(),
                    message: format!("`{name}` = `{}` is not a finite number", given.value),
                }),
            },
        }
    }

    /// `name` as a whole number, or `default` when not given.
    pub fn count(&self, name: &str, default: usize) -> Result<usize> {
        match self.values.get(name) {
            None => Ok(default),
            Some(given) => given.value.parse::<usize>().map_err(|_| Error::Parameter {
                origin: given.origin.clone(),
                message: format!("`{name}` = `{}` is not a whole number", given.value),
            }),
        }
    }

    /// `name` as one of `choices`, or `default` when not given.
    pub fn choice(&self, name: &str, choices: &[&str], default: &str) -> Result<String> {
        match self.values.get(name) {
            None => Ok(default.to_string()),
            Some(given) if choices.contains(&given.value.as_str()) => Ok(given.value.clone()),
            Some(given) => Err(Error::Parameter {
                origin: given.origin.clone(),
                message: format!(
                    "`{name}` = `{}` is not one of {}",
                    given.value,
                    choices.join(", ")
                ),
            }),
        }
    }

    /// The given values as JSON for the report's `params`.
    pub fn to_json(&self) -> BTreeMap<String, serde_json::Value> {
        self.values
            .iter()
            .map(|(k, g)| {
                let value = match g.value.parse::<f64>() {
                    Ok(v) if v.is_finite() => serde_json::json!(v),
                    _ => serde_json::json!(g.value),
                };
                (k.clone(), value)
            })
            .collect()
    }
}

fn line_at(text: &str, offset: usize) -> usize {
    1 + text
        .as_bytes()
        .iter()
        .take(offset)
        .filter(|b| **b == b'\n')
        .count()
}

/// The top-level scalars of a config, then those of the table named `method` (which win).
fn parse_config(name: &str, text: &str, method: &str) -> Result<Vec<(String, Given)>> {
    let table: toml::Table = toml::from_str(text).map_err(|e| {
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
    })?;
    let locate = |key: &str| -> String {
        // The first line that starts with the key: good enough for a flat file of parameters.
        let line = text
            .lines()
            .position(|l| {
                let l = l.trim_start();
                l.strip_prefix(key)
                    .is_some_and(|rest| rest.trim_start().starts_with('='))
            })
            .map_or(0, |i| i + 1);
        if line > 0 {
            format!("{name}:{line}")
        } else {
            name.to_string()
        }
    };
    let scalar = |key: &str, value: &toml::Value| -> Result<Given> {
        let text = match value {
            toml::Value::String(s) => s.clone(),
            toml::Value::Integer(i) => i.to_string(),
            toml::Value::Float(f) => f.to_string(),
            toml::Value::Boolean(b) => b.to_string(),
            _ => {
                return Err(Error::Parameter {
                    origin: locate(key),
                    message: format!("`{key}` must be a number, string or boolean"),
                })
            }
        };
        Ok(Given {
            value: text,
            origin: locate(key),
        })
    };
    let mut out = Vec::new();
    for (key, value) in &table {
        if !value.is_table() {
            out.push((key.clone(), scalar(key, value)?));
        }
    }
    if let Some(toml::Value::Table(section)) = table.get(method) {
        for (key, value) in section {
            out.push((key.clone(), scalar(key, value)?));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::registry::{MethodKind, ParameterInfo};

    const METHOD: MethodInfo = MethodInfo {
        name: "smoothing-spline",
        kind: MethodKind::Curve,
        paper: "",
        summary: "",
        parameters: &[
            ParameterInfo {
                name: "p",
                default: "0.99",
                meaning: "",
            },
            ParameterInfo {
                name: "criterion",
                default: "ek",
                meaning: "",
            },
        ],
    };

    fn temp(name: &str, text: &str) -> std::path::PathBuf {
        let path = std::env::temp_dir().join(format!("fair-cli-params-{}-{name}", std::process::id()));
        std::fs::write(&path, text).unwrap();
        path
    }

    #[test]
    fn set_overrides_config_and_method_table_overrides_top() {
        let path = temp(
            "a.toml",
            "p = 0.5\ncriterion = \"e2\"\n[smoothing-spline]\np = 0.7\n[batten]\np = 3\n",
        );
        let params = Parameters::collect(&METHOD, Some(&path), &[]).unwrap();
        assert_eq!(params.number("p", 0.0).unwrap(), 0.7);
        assert_eq!(params.choice("criterion", &["e2", "ek"], "ek").unwrap(), "e2");
        let set = [Setting {
            name: "p".into(),
            value: "0.9".into(),
        }];
        let params = Parameters::collect(&METHOD, Some(&path), &set).unwrap();
        assert_eq!(params.number("p", 0.0).unwrap(), 0.9);
        std::fs::remove_file(path).ok();
    }

    #[test]
    fn unknown_and_bad_values() {
        let set = [Setting {
            name: "q".into(),
            value: "1".into(),
        }];
        let e = Parameters::collect(&METHOD, None, &set).unwrap_err();
        assert!(
            e.to_string()
                .contains("`q` is not a parameter of `smoothing-spline` (known: p, criterion)"),
            "{e}"
        );
        let set = [Setting {
            name: "p".into(),
            value: "x".into(),
        }];
        let params = Parameters::collect(&METHOD, None, &set).unwrap();
        assert!(params.number("p", 1.0).is_err());
        assert!(params.count("p", 1).is_err());
        assert_eq!(params.number("criterion", 2.0).unwrap(), 2.0);
    }

    #[test]
    fn config_errors_name_line() {
        let path = temp("bad.toml", "p = 0.5\nq = = 1\n");
        let e = Parameters::collect(&METHOD, Some(&path), &[]).unwrap_err();
        assert!(e.to_string().contains(".toml:2: "), "{e}");
        std::fs::remove_file(path).ok();
        let path = temp("unknown.toml", "p = 0.5\n\nzz = 1\n");
        let e = Parameters::collect(&METHOD, Some(&path), &[]).unwrap_err();
        assert!(e.to_string().contains("unknown.toml:3: `zz`"), "{e}");
        std::fs::remove_file(path).ok();
    }
}
