//! Method parameters from `--config FILE` (TOML) and `--set NAME=VALUE`, checked against the
//! method's list in the [`registry`](crate::registry).
//!
//! A config file ([`config`](crate::config), TOML or JSON) holds `name = value` pairs at the
//! top level (for whatever method runs) and optionally tables named after a method
//! (`[smoothing-spline]`) that apply only to it.
//! `--set` overrides the file. Every name must be a parameter of the method.

use crate::args::Setting;
use crate::config::ConfigFile;
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
        let mut values = Vec::new();
        if let Some(path) = config {
            values = ConfigFile::read(path)?.method_values(method.name)?;
        }
        Parameters::from_values(method, values, settings)
    }

    /// Parameters for `method` from values already read (a config file's, a pipeline
    /// stage's), then the `--set`s, which win; every name is checked against the method.
    pub fn from_values(
        method: &MethodInfo,
        given: Vec<(String, Given)>,
        settings: &[Setting],
    ) -> Result<Parameters> {
        let mut values: BTreeMap<String, Given> = given.into_iter().collect();
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

    /// The given values as (name, text) pairs, for `--print-config`.
    pub fn given_values(&self) -> Vec<(String, String)> {
        self.values
            .iter()
            .map(|(k, g)| (k.clone(), g.value.clone()))
            .collect()
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
