//! Adding a method and a criterion to the `fair` command, in a binary of your own.
//!
//! Registers a strategy `laplacian` (each pass moves every free interior point toward the
//! midpoint of its neighbours by `factor`, `passes` times) and a criterion `turning-angle`
//! (Σ over interior samples of the squared second difference of the turning angle, sampled
//! at 4 points per piece of the curve), then runs the standard command line with that
//! catalogue. Everything `fair` takes works, and the new names are everywhere a built-in one
//! is: `fair methods`, `--method`, `--set`, config pipelines, `--set criterion=` of
//! nurbs-weights, and every report's `criteria`.
//!
//! ```sh
//! cargo run --release --example custom_method -- methods
//! cargo run --release --example custom_method -- curve data/hull_gunnerus/waterlines/wl_03.csv \
//!     --method laplacian --set factor=0.3 --report r.json
//! cargo run --release --example custom_method -- curve data/airfoil_ua2-180/ua2-180_upper.csv \
//!     --method nurbs-weights --set criterion=turning-angle --report r.json
//! ```
//!
//! `cargo test` runs the checks at the end of this file.

use curve_repr::{Curve, Side, Vec2};
use fairing::catalog::{Catalog, CriterionEntry, CurveJob, MethodInfo, Settings, StrategySettings};
use fairing::{Error, FairingState, FairingStrategy, Result, StepOutcome};
use fairness::Criterion;

/// The parameters of `laplacian`: one settings struct, the one source of its parameter list.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct LaplacianSettings {
    /// Fraction of the way to the neighbours' midpoint each pass moves a point, in (0, 1].
    pub factor: f64,
    /// Passes over the points.
    pub passes: usize,
}

impl Default for LaplacianSettings {
    fn default() -> Self {
        LaplacianSettings {
            factor: 0.3,
            passes: 20,
        }
    }
}

impl Settings for LaplacianSettings {
    fn validate(&self) -> Result<()> {
        if !(self.factor > 0.0 && self.factor <= 1.0) {
            return Err(Error::BadParameter {
                name: "factor",
                value: self.factor.to_string(),
                reason: "must lie in (0, 1]",
            });
        }
        Ok(())
    }
}

/// Laplacian smoothing as a strategy: one pass per step.
pub struct Laplacian {
    settings: LaplacianSettings,
    passes: usize,
}

impl<const D: usize> FairingStrategy<D> for Laplacian {
    fn name(&self) -> &str {
        "laplacian"
    }

    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        if self.passes >= self.settings.passes {
            return Ok(StepOutcome::done(None));
        }
        // Every target from the points as they were at the start of the pass.
        let points = state.points().to_vec();
        for i in 1..points.len().saturating_sub(1) {
            if state.is_movable(i) {
                let midpoint = (points[i - 1] + points[i + 1]) / 2.0;
                // Through the state, which applies the constraints.
                state.move_point(i, points[i] + (midpoint - points[i]) * self.settings.factor)?;
            }
        }
        self.passes += 1;
        Ok(StepOutcome::running(None))
    }
}

impl StrategySettings for LaplacianSettings {
    fn strategy<const D: usize>(&self, _: &CurveJob) -> Result<Box<dyn FairingStrategy<D>>> {
        Ok(Box::new(Laplacian {
            settings: self.clone(),
            passes: 0,
        }))
    }

    fn max_iterations(&self) -> usize {
        self.passes + 1
    }
}

/// Σ over interior samples of (θ_{j+1} − 2θ_j + θ_{j−1})², θ_j the turning angle of the polyline
/// through the curve sampled at 4 points per piece.
pub struct TurningAngle;

impl Criterion<dyn Curve<2>> for TurningAngle {
    fn name(&self) -> &str {
        "turning-angle"
    }

    fn evaluate(&self, curve: &dyn Curve<2>) -> fairness::Result<f64> {
        let breaks = curve.breaks();
        let mut samples: Vec<Vec2> = Vec::with_capacity(4 * breaks.len());
        for w in breaks.windows(2) {
            for k in 0..4 {
                samples.push(curve.jet(w[0] + (w[1] - w[0]) * k as f64 / 4.0, Side::Right)[0]);
            }
        }
        if let Some(&last) = breaks.last() {
            samples.push(curve.jet(last, Side::Left)[0]);
        }
        let turning: Vec<f64> = samples
            .windows(3)
            .map(|w| {
                let (a, b) = (w[1] - w[0], w[2] - w[1]);
                (a.x * b.y - a.y * b.x).atan2(a.dot(&b))
            })
            .collect();
        let total: f64 = turning
            .windows(3)
            .map(|t| (t[2] - 2.0 * t[1] + t[0]).powi(2))
            .sum();
        if total.is_finite() {
            Ok(total)
        } else {
            Err(fairness::Error::NonFinite {
                what: "turning-angle criterion",
                parameter: f64::NAN,
            })
        }
    }
}

/// The built-in catalogue plus `laplacian` and `turning-angle`.
pub fn catalog() -> Catalog {
    let mut catalog = Catalog::builtin();
    catalog.register_strategy::<LaplacianSettings>(
        MethodInfo::new(
            "laplacian",
            "moves every free interior point toward its neighbours' midpoint, pass after pass",
        )
        .with_paper("Laplacian smoothing, a user's example"),
    );
    catalog.register_criterion(
        CriterionEntry::new(
            "turning-angle",
            "Σ squared second differences of the turning angle, 4 samples per piece",
        )
        .planar(TurningAngle),
    );
    catalog
}

fn main() -> std::process::ExitCode {
    fair_cli::main_with(catalog())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;
    use std::process::ExitCode;

    fn data(path: &str) -> String {
        format!("{}/data/{path}", env!("CARGO_MANIFEST_DIR"))
    }

    /// A fresh directory for a test's files, removed when the returned guard is dropped.
    fn scratch_dir() -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix("fair-custom-method-")
            .tempdir()
            .unwrap()
    }

    /// Runs the command line with the example's catalogue.
    fn fair(args: &[&str]) -> ExitCode {
        fair_cli::run_from_with(&catalog(), std::iter::once("fair").chain(args.iter().copied()))
    }

    fn success(code: ExitCode) -> bool {
        format!("{code:?}") == format!("{:?}", ExitCode::SUCCESS)
    }

    fn report(path: &Path) -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
    }

    fn turning(report: &serde_json::Value, side: &str) -> f64 {
        report[side]["criteria"]["turning-angle"]
            .as_f64()
            .unwrap_or_else(|| panic!("no {side}.criteria.turning-angle in {report}"))
    }

    #[test]
    fn methods_lists_laplacian_with_its_parameters() {
        assert!(success(fair(&["methods"])));
        let table = catalog().table();
        let block: Vec<&str> = table
            .lines()
            .skip_while(|l| !l.trim_start().starts_with("laplacian"))
            .take(3)
            .collect();
        assert!(block[1].contains("factor=0.3"), "{table}");
        assert!(block[2].contains("passes=20"), "{table}");
        assert!(table.contains("turning-angle"), "{table}");
    }

    #[test]
    fn laplacian_fairs_a_waterline_and_the_report_has_the_new_criterion() {
        let scratch = scratch_dir();
        let out = scratch.path().join("laplacian.json");
        let code = fair(&[
            "curve",
            &data("hull_gunnerus/waterlines/wl_03.csv"),
            "--method",
            "laplacian",
            "--set",
            "factor=0.3",
            "--report",
            out.to_str().unwrap(),
            "-q",
        ]);
        assert!(success(code));
        let report = report(&out);
        assert_eq!(report["method"], "laplacian");
        assert_eq!(report["params"]["passes"], 20);
        assert!(report["moved"].as_array().unwrap().len() > 10);
        assert!(turning(&report, "after") < turning(&report, "before"));
        assert_eq!(report["termination"], "strategy-done");
    }

    #[test]
    fn nurbs_weights_lowers_the_new_criterion() {
        let scratch = scratch_dir();
        let out = scratch.path().join("weights.json");
        let code = fair(&[
            "curve",
            &data("airfoil_ua2-180/ua2-180_upper.csv"),
            "--method",
            "nurbs-weights",
            "--set",
            "criterion=turning-angle",
            "--report",
            out.to_str().unwrap(),
            "-q",
        ]);
        assert!(success(code));
        let report = report(&out);
        assert_eq!(report["criterion"], "turning-angle");
        let (before, after) = (turning(&report, "before"), turning(&report, "after"));
        assert!(after < before, "{after} >= {before}");
        assert_eq!(report["criterion_after"].as_f64().unwrap(), after);
    }

    #[test]
    fn a_laplacian_then_two_phase_pipeline_holds_the_band() {
        let scratch = scratch_dir();
        let config = scratch.path().join("pipeline.toml");
        std::fs::write(
            &config,
            "[[stage]]\nmethod = \"laplacian\"\npasses = 5\n\n[[stage]]\nmethod = \"two-phase\"\n",
        )
        .unwrap();
        let input = data("airfoil_ua2-180/ua2-180_upper.csv");
        for kind in ["parametric", "function"] {
            let (out, points) = (
                scratch.path().join(format!("{kind}.json")),
                scratch.path().join(format!("{kind}.csv")),
            );
            let code = fair(&[
                "curve",
                &input,
                "--kind",
                kind,
                "--config",
                config.to_str().unwrap(),
                "--tolerance",
                "5e-4",
                "-o",
                points.to_str().unwrap(),
                "--report",
                out.to_str().unwrap(),
                "-q",
            ]);
            assert!(success(code), "{kind}");
            let report = report(&out);
            assert_eq!(report["method"], "laplacian+two-phase");
            assert!(
                report["m_d"].as_f64().unwrap() <= 5e-4,
                "{kind}: {}",
                report["m_d"]
            );
            let read = |path: &str| -> Vec<Vec<f64>> {
                std::fs::read_to_string(path)
                    .unwrap()
                    .lines()
                    .skip(1)
                    .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
                    .collect()
            };
            let (before, after) = (read(&input), read(points.to_str().unwrap()));
            assert_eq!(before.len(), after.len());
            for (p, q) in before.iter().zip(&after) {
                let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
                assert!(d <= 5e-4, "{kind}: moved {d}");
            }
            let stages = report["stages"].as_array().unwrap();
            assert_eq!(stages.len(), 2);
            assert!(stages[0]["moved"].as_u64().unwrap() > 0, "{kind}");
        }
    }
}
