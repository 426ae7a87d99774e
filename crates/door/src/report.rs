//! The JSON report of `fair curve`, `fair surface` and `fair inspect` (`docs/CONTRACT.md`:
//! the field names here are the contract). `before`/`after` carry `criteria`: every criterion
//! of the catalogue that applies to the curve, by name (the `energies` object stays).
//!
//! Counts that do not apply (inflections of a 3D curve, vibrations of a surface) are `null`,
//! never omitted. `fair inspect` writes the same shape with `after` equal to `before`,
//! `iterations` 0 and nothing moved. Non-finite numbers are refused ([`Report::check_finite`])
//! because serde_json would silently write them as `null`.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// What was faired: the kind of the input as the indicators see it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ReportKind {
    /// A spline function y(x).
    Function,
    /// A parametric curve in 2D or 3D.
    Parametric,
    /// A surface grid.
    Surface,
}

impl ReportKind {
    /// The name as the report writes it: `function`, `parametric` or `surface`.
    pub fn name(self) -> &'static str {
        match self {
            ReportKind::Function => "function",
            ReportKind::Parametric => "parametric",
            ReportKind::Surface => "surface",
        }
    }
}

impl From<fairing::catalog::CurveKind> for ReportKind {
    fn from(kind: fairing::catalog::CurveKind) -> Self {
        match kind {
            fairing::catalog::CurveKind::Function => ReportKind::Function,
            fairing::catalog::CurveKind::Parametric => ReportKind::Parametric,
        }
    }
}

/// The energies of a curve as represented (E1–E3 over its own parameter; Ek, Ek' over arc
/// length): the fairness crate's block, serialised as the report's `energies`.
pub use fairness::Energies;

/// How accurately each energy is known (the fairness crate's block, serialised as the
/// report's `energy_accuracy`): the relative tolerance asked, each energy's error estimate,
/// whether it met the tolerance, and whether it was integrated exactly.
pub use fairness::EnergyAccuracy;

/// The fairness measures of a curve or surface (see `docs/CONTRACT.md` for each definition).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Measures {
    /// Sign changes of curvature; `null` for 3D curves and surfaces.
    pub inflections: Option<usize>,
    /// Sign changes of the curvature slope jumps e_i; `null` for surfaces.
    pub vibrations: Option<usize>,
    /// Strain energy (function: ∫ y''² dx; parametric: ∫ |C''|² dt; surface: network energy).
    pub e_s: f64,
    /// Largest third-derivative jump (curves) or largest z_ij (surfaces, Eq. 26).
    pub max_z: f64,
    /// The energies of the curve; `null` for surfaces (and for a curve whose integrands are
    /// not finite somewhere, e.g. at a vanishing tangent).
    pub energies: Option<Energies>,
    /// Every registered criterion that applies to the curve (the measured spline, or the
    /// method's own representation when it has one), by name. Those that are one of the
    /// energies (`e1` … `ek-prime`) are the `energies` values, not integrated again.
    #[serde(default)]
    pub criteria: BTreeMap<String, f64>,
    /// The accuracy of `energies` (an addition to the contract's first fields): E1–E3 are exact up to
    /// round-off, Ek and Ek′ adaptive to a relative tolerance; an energy whose tolerance could
    /// not be met within the linear budget is its best estimate, with its error here. `null`
    /// where `energies` is. For a method's own representation (a NURBS) every energy is
    /// adaptive, to the criteria's own tolerance (1e-10).
    #[serde(default)]
    pub energy_accuracy: Option<EnergyAccuracy>,
}

/// The whole report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// The method name (`two-phase`, ...), or `inspect`.
    pub method: String,
    /// The kind of the input.
    pub kind: ReportKind,
    /// Number of data points (grid points for surfaces).
    pub n: usize,
    /// Iterations the method ran.
    pub iterations: usize,
    /// Measures of the input.
    pub before: Measures,
    /// Measures of the result.
    pub after: Measures,
    /// S_d = Σ |P̃_i − P_i|.
    pub s_d: f64,
    /// M_d = max |P̃_i − P_i|.
    pub m_d: f64,
    /// Indices (from 0) of the points that moved.
    pub moved: Vec<usize>,
    /// Time of the fairing itself, in milliseconds (no parsing or writing).
    pub elapsed_ms: f64,
    /// The faired curve or surface itself; its fields depend on the representation
    /// (see [`NurbsRecord`] for a NURBS).
    pub curve: serde_json::Value,
    /// The method's parameters as used (defaults filled in); omitted when empty.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub params: BTreeMap<String, serde_json::Value>,
    /// Method-specific extras (termination reason, per-iteration trace, ...), written at the top
    /// level next to the contract's fields.
    #[serde(flatten)]
    pub extras: BTreeMap<String, serde_json::Value>,
}

impl Report {
    /// The report of `fair inspect`: `after` equals `before`, nothing moved.
    pub fn inspection(kind: ReportKind, n: usize, measures: Measures, curve: serde_json::Value) -> Report {
        Report {
            method: "inspect".into(),
            kind,
            n,
            iterations: 0,
            before: measures.clone(),
            after: measures,
            s_d: 0.0,
            m_d: 0.0,
            moved: Vec::new(),
            elapsed_ms: 0.0,
            curve,
            params: BTreeMap::new(),
            extras: BTreeMap::new(),
        }
    }

    /// Fails with [`Error::NonFiniteOutput`] naming the first NaN or infinite number anywhere in
    /// the report (its path is given as `what`).
    pub fn check_finite(&self) -> Result<()> {
        // serde_json turns NaN into null, so look at the floats themselves.
        let fields = [
            ("s_d", self.s_d),
            ("m_d", self.m_d),
            ("elapsed_ms", self.elapsed_ms),
            ("before.e_s", self.before.e_s),
            ("before.max_z", self.before.max_z),
            ("after.e_s", self.after.e_s),
            ("after.max_z", self.after.max_z),
        ];
        let errors = |m: &Measures| m.energy_accuracy.map(|a| a.errors);
        let energies = [
            ("before", &self.before.energies),
            ("after", &self.after.energies),
            ("before.energy_accuracy", &errors(&self.before)),
            ("after.energy_accuracy", &errors(&self.after)),
        ];
        let mut bad: Option<String> = fields
            .iter()
            .find(|(_, v)| !v.is_finite())
            .map(|(n, _)| n.to_string());
        for (side, energies) in energies {
            if let (None, Some(e)) = (&bad, energies) {
                let named = [
                    ("e1", e.e1),
                    ("e2", e.e2),
                    ("e3", e.e3),
                    ("ek", e.ek),
                    ("ek_prime", e.ek_prime),
                ];
                bad = named.iter().find(|(_, v)| !v.is_finite()).map(|(n, _)| {
                    if side.contains('.') {
                        format!("{side}.errors.{n}")
                    } else {
                        format!("{side}.energies.{n}")
                    }
                });
            }
        }
        for (side, measures) in [("before", &self.before), ("after", &self.after)] {
            if bad.is_none() {
                bad = measures
                    .criteria
                    .iter()
                    .find(|(_, v)| !v.is_finite())
                    .map(|(name, _)| format!("{side}.criteria.{name}"));
            }
        }
        match bad {
            Some(what) => Err(Error::NonFiniteOutput {
                what: format!("report {what}"),
                index: 0,
            }),
            None => Ok(()),
        }
    }

    /// Writes the report as pretty JSON to `path` (`-`: standard output), after
    /// [`Report::check_finite`], completely or not at all ([`cad::atomic`]). The text is
    /// [`write_json_to`](Self::write_json_to)'s.
    pub fn write_json(&self, path: &str) -> Result<()> {
        self.check_finite()?;
        let mut outputs = cad::atomic::Outputs::new();
        outputs.add(cad::atomic::Target::from_arg(path), |w| self.write_json_to(w));
        outputs.commit().map_err(|e| crate::error::Error::from_write(&e))
    }

    /// Streams the report as pretty JSON and a newline into `writer`: the same text as
    /// [`to_json`](Self::to_json), through the writer rather than built in memory (at 10⁶
    /// points the text of a curve record is a few hundred MB). Call [`Report::check_finite`]
    /// first; a value that JSON cannot hold is an error of kind `InvalidData`.
    pub fn write_json_to(&self, writer: &mut dyn std::io::Write) -> std::io::Result<()> {
        serde_json::to_writer_pretty(&mut *writer, self).map_err(|e| match e.io_error_kind() {
            Some(kind) => std::io::Error::new(kind, e.to_string()),
            None => std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()),
        })?;
        writer.write_all(b"\n")
    }

    /// The report as pretty JSON, after [`Report::check_finite`].
    pub fn to_json(&self) -> Result<String> {
        self.check_finite()?;
        let mut text = serde_json::to_string_pretty(self).map_err(|e| Error::Internal {
            message: e.to_string(),
        })?;
        text.push('\n');
        Ok(text)
    }
}

/// The `curve` field for a NURBS curve (`docs/CONTRACT.md`): degree, knots, control points, weights and
/// the data points' parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NurbsRecord {
    /// The polynomial degree.
    pub degree: usize,
    /// The knot vector.
    pub knots: Vec<f64>,
    /// Control points as coordinate rows.
    pub control_points: Vec<Vec<f64>>,
    /// One weight per control point.
    pub weights: Vec<f64>,
    /// The parameter of each data point.
    pub params: Vec<f64>,
}

impl NurbsRecord {
    /// The record as a `curve` value, tagged `"type": "nurbs"`.
    pub fn to_value(&self) -> serde_json::Value {
        let mut value = serde_json::json!({ "type": "nurbs" });
        if let (Some(map), Ok(serde_json::Value::Object(fields))) =
            (value.as_object_mut(), serde_json::to_value(self))
        {
            map.extend(fields);
        }
        value
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_json_is_the_json_text() {
        let scratch = tempfile::Builder::new().prefix("fair-report-").tempdir().unwrap();
        let dir = scratch.path();
        let path = dir.join("report.json");
        let report = sample();
        report.write_json(path.to_str().unwrap()).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), report.to_json().unwrap());
        let missing = dir.join("no/such/dir/report.json");
        let e = report.write_json(missing.to_str().unwrap()).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.one_line().contains("report.json"), "{}", e.one_line());
    }

    fn sample() -> Report {
        let measures = Measures {
            inflections: Some(4),
            vibrations: Some(19),
            e_s: 1.5e9,
            max_z: 0.8,
            energies: Some(Energies::default()),
            criteria: [("ek".to_string(), 0.5)].into_iter().collect(),
            energy_accuracy: Some(EnergyAccuracy::default()),
        };
        let curve = NurbsRecord {
            degree: 3,
            knots: vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            control_points: vec![vec![0.0, 0.0]; 4],
            weights: vec![1.0; 4],
            params: vec![0.0, 1.0],
        };
        Report {
            method: "two-phase".into(),
            kind: ReportKind::Function,
            n: 65,
            iterations: 12,
            before: measures.clone(),
            after: Measures {
                inflections: None,
                ..measures
            },
            s_d: 141.9,
            m_d: 12.6,
            moved: vec![3, 4, 9],
            elapsed_ms: 1.2,
            curve: curve.to_value(),
            params: BTreeMap::new(),
            extras: BTreeMap::new(),
        }
    }

    fn keys(value: &serde_json::Value) -> Vec<String> {
        let mut keys: Vec<String> = value.as_object().unwrap().keys().cloned().collect();
        keys.sort();
        keys
    }

    #[test]
    fn field_names_match_the_contract() {
        let value: serde_json::Value = serde_json::from_str(&sample().to_json().unwrap()).unwrap();
        let mut top = vec![
            "method",
            "kind",
            "n",
            "iterations",
            "before",
            "after",
            "s_d",
            "m_d",
            "moved",
            "elapsed_ms",
            "curve",
        ];
        top.sort();
        assert_eq!(keys(&value), top);
        let mut measures = vec![
            "inflections",
            "vibrations",
            "e_s",
            "max_z",
            "energies",
            "criteria",
            "energy_accuracy",
        ];
        measures.sort();
        assert_eq!(keys(&value["before"]), measures);
        assert_eq!(keys(&value["after"]), measures);
        let mut energies = vec!["e1", "e2", "e3", "ek", "ek_prime"];
        energies.sort();
        assert_eq!(keys(&value["before"]["energies"]), energies);
        assert_eq!(value["before"]["criteria"]["ek"], 0.5);
        let mut curve = vec!["type", "degree", "knots", "control_points", "weights", "params"];
        curve.sort();
        assert_eq!(keys(&value["curve"]), curve);
        assert_eq!(value["kind"], "function");
        assert_eq!(value["curve"]["type"], "nurbs");
        assert_eq!(value["moved"], serde_json::json!([3, 4, 9]));
    }

    #[test]
    fn inapplicable_counts_are_null_not_missing() {
        let value: serde_json::Value = serde_json::from_str(&sample().to_json().unwrap()).unwrap();
        assert!(value["after"].as_object().unwrap().contains_key("inflections"));
        assert!(value["after"]["inflections"].is_null());
    }

    #[test]
    fn params_and_extras_appear_when_given() {
        let mut report = sample();
        report.params.insert("p".into(), serde_json::json!(0.999));
        report
            .extras
            .insert("termination".into(), serde_json::json!("converged"));
        let value: serde_json::Value = serde_json::from_str(&report.to_json().unwrap()).unwrap();
        assert_eq!(value["params"]["p"], 0.999);
        assert_eq!(value["termination"], "converged");
        let back: Report = serde_json::from_value(value).unwrap();
        assert_eq!(back, report);
    }

    #[test]
    fn nan_is_refused() {
        let mut report = sample();
        report.after.energies = Some(Energies {
            ek: f64::NAN,
            ..Energies::default()
        });
        let e = report.to_json().unwrap_err();
        assert!(e.to_string().contains("after.energies.ek"), "{e}");
        let mut report = sample();
        report.m_d = f64::INFINITY;
        assert!(report.to_json().is_err());
    }

    #[test]
    fn kinds_are_lowercase() {
        for (kind, name) in [
            (ReportKind::Function, "function"),
            (ReportKind::Parametric, "parametric"),
            (ReportKind::Surface, "surface"),
        ] {
            assert_eq!(serde_json::to_value(kind).unwrap(), name);
        }
    }
}
