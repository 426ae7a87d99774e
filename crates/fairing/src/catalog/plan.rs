//! Plans: what runs for one input — one method, or a pipeline of stages from a config file —
//! with complete, checked settings; and running a plan on a curve.
//!
//! Constraints hold for the whole pipeline, measured from the input:
//! - fixed points and the end clamp are passed to every stage, so no stage moves them;
//! - the tolerance band D is shared out: stage k gets D minus the largest distance any point
//!   has already moved (by the triangle inequality no point ends farther than D from where it
//!   started); when nothing is left the remaining stages are skipped and the report says so;
//! - bad points go to every stage that takes them.
//!
//! A pipeline's run: `iterations` and `elapsed_ms` summed, `moved` = the points that differ
//! from the input at the end, `curve` the last stage's, `termination` the last stage's, and
//! the extra `stages` with each stage's method, parameters, iterations, moved count, S_d and
//! M_d against the stage's own input, termination and extras.

use std::collections::BTreeMap;

use serde_json::Value;

use super::config::{toml_text, ConfigConstraints, ConfigFile};
use super::job::{CurveJob, CurveKind, CurvePoints, CurveRun, Represented, SurfaceJob, SurfaceRun};
use super::parameters::ParameterMap;
use super::{Catalog, MethodKind};
use crate::corners::Corners;
use crate::displacement::{unasked_move_as, NoiseModel};
use crate::{Constraints, EndClamp, Error, Result};

/// One stage of a plan: a method of the catalogue and its complete settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Stage {
    /// The method's name.
    pub method: String,
    /// The values as given (for messages and the printed config).
    pub given: ParameterMap,
    /// The complete settings (defaults filled in, checked and validated).
    pub settings: Value,
}

/// What runs: one stage for `--method`, several for a config with `[[stage]]`s, and the
/// config's `[constraints]` (which the command line overrides).
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Curves or surfaces.
    pub kind: MethodKind,
    /// The stages, in order.
    pub stages: Vec<Stage>,
    /// The config file's constraints.
    pub constraints: ConfigConstraints,
}

impl Plan {
    /// The report's `method`: the method, or the stages' names joined by `+`.
    pub fn name(&self) -> String {
        let names: Vec<&str> = self.stages.iter().map(|s| s.method.as_str()).collect();
        names.join("+")
    }

    /// The single stage's parameters without the pinned ones (for a report's `params`);
    /// empty for a pipeline (each stage's are in its record).
    pub fn params(&self, catalog: &Catalog) -> BTreeMap<String, Value> {
        match self.stages.as_slice() {
            [stage] => catalog
                .method(self.kind, &stage.method)
                .map(|entry| entry.visible(&stage.settings).into_iter().collect())
                .unwrap_or_default(),
            _ => BTreeMap::new(),
        }
    }

    /// Whether some stage takes bad points (`--points`).
    pub fn takes_bad_points(&self, catalog: &Catalog) -> bool {
        self.stages.iter().any(|s| {
            catalog
                .method(self.kind, &s.method)
                .is_ok_and(|m| m.takes_bad_points())
        })
    }

    /// The TOML config that reproduces the plan: its constraints and its stages with every
    /// parameter (given values, else the defaults) and its meaning as a comment; for a
    /// surface, the one method's table. What `--print-config` prints; reading it back gives
    /// the same plan.
    pub fn render(&self, catalog: &Catalog, constraints: &PlanConstraints) -> String {
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
            lines.push(format!("tolerance = {}", toml_text(&Value::from(d))));
        }
        if constraints.clamp != EndClamp::None {
            lines.push(format!("clamp-ends = \"{}\"", constraints.clamp.name()));
        }
        if !lines.is_empty() {
            text.push_str("[constraints]\n");
            for line in lines {
                text.push_str(&line);
                text.push('\n');
            }
        }
        for stage in &self.stages {
            if !text.is_empty() {
                text.push('\n');
            }
            match self.kind {
                // A pipeline of stages (curves), each naming its method.
                MethodKind::Curve => text.push_str(&format!("[[stage]]\nmethod = \"{}\"\n", stage.method)),
                // A surface config sets one method's parameters, in a table named after it
                // (the method itself is chosen by `--method`).
                MethodKind::Surface => {
                    text.push_str(&format!("# run with --method {0}\n[{0}]\n", stage.method))
                }
            }
            let Ok(entry) = catalog.method(self.kind, &stage.method) else {
                continue;
            };
            for parameter in entry.parameters() {
                let value = stage
                    .settings
                    .get(&parameter.name)
                    .unwrap_or(&parameter.default_value);
                text.push_str(&format!(
                    "{} = {}  # {}\n",
                    parameter.name,
                    toml_text(value),
                    parameter.meaning
                ));
            }
        }
        text
    }
}

/// The constraints a plan runs under, resolved from the command line and the config.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlanConstraints {
    /// Points that never move (sorted, from 0).
    pub fixed: Vec<usize>,
    /// The bad points (`--points`), in the order given.
    pub bad_points: Vec<usize>,
    /// No point moves farther than this.
    pub tolerance: Option<f64>,
    /// What the ends keep.
    pub clamp: EndClamp,
    /// Where the curve has corners, kept as G0 breaks ([`crate::corners`]; detected by
    /// default).
    pub corners: Corners,
}

impl PlanConstraints {
    /// The fairing crate's constraints for the whole run (or a stage, with `tolerance`).
    pub fn constraints(&self, tolerance: Option<f64>) -> Constraints {
        let mut out = Constraints::default()
            .with_fixed(self.fixed.iter().copied())
            .with_end_clamp(self.clamp);
        if let Some(d) = tolerance {
            out = out.with_tolerance(d);
        }
        out
    }
}

impl Catalog {
    /// The plan a command line and an optional config file imply for input of `kind`:
    /// the config's `[[stage]]` list, or else the one method (`method`, or `default_method`)
    /// with the config's top-level and `[method]` parameters and then `sets` (which win).
    /// Every name and value is checked here, each error naming where it was given.
    ///
    /// A pipeline and `method` or `sets` together are refused as ambiguous; a pipeline is
    /// for curves.
    pub fn plan(
        &self,
        kind: MethodKind,
        method: Option<&str>,
        default_method: &str,
        config: Option<&ConfigFile>,
        sets: &ParameterMap,
    ) -> Result<Plan> {
        let constraints = config
            .map(ConfigFile::constraints)
            .transpose()?
            .unwrap_or_default();
        if let Some(file) = config {
            file.check_tables(|name| self.has_method(name), || self.method_names())?;
        }
        if let Some(stages) = config.map(ConfigFile::stages).transpose()?.flatten() {
            if kind == MethodKind::Surface {
                return Err(Error::Config {
                    origin: config.map(|c| c.name.clone()).unwrap_or_default(),
                    message: "pipelines of [[stage]]s are for curves; a surface config sets one method's parameters".into(),
                });
            }
            if method.is_some() {
                return Err(Error::Parameter {
                    origin: "--method".into(),
                    message:
                        "the config file defines a pipeline of [[stage]]s; give either --method or the stages"
                            .into(),
                });
            }
            if !sets.is_empty() {
                return Err(Error::Parameter {
                    origin: "--set".into(),
                    message: "the config file defines a pipeline; set parameters in its [[stage]] tables"
                        .into(),
                });
            }
            let stages = stages
                .into_iter()
                .map(|stage| {
                    // At the stage's `method =` line, as everything else the file gives.
                    let entry = self.method(kind, &stage.method).map_err(|e| Error::Config {
                        origin: stage.origin.clone(),
                        message: e.to_string(),
                    })?;
                    Ok(Stage {
                        settings: entry.settings(&stage.parameters)?,
                        method: stage.method,
                        given: stage.parameters,
                    })
                })
                .collect::<Result<Vec<_>>>()?;
            return Ok(Plan {
                kind,
                stages,
                constraints,
            });
        }
        let entry = self.method(kind, method.unwrap_or(default_method))?;
        let mut given = match config {
            Some(file) => file.method_values(entry.name())?,
            None => ParameterMap::new(),
        };
        given.extend(sets);
        Ok(Plan {
            kind,
            stages: vec![Stage {
                method: entry.name().to_owned(),
                settings: entry.settings(&given)?,
                given,
            }],
            constraints,
        })
    }

    fn refuse_bad_points(&self, plan: &Plan, constraints: &PlanConstraints) -> Result<()> {
        if constraints.bad_points.is_empty() || plan.takes_bad_points(self) {
            return Ok(());
        }
        let takers: Vec<&str> = self
            .methods(plan.kind)
            .filter(|m| m.takes_bad_points())
            .map(|m| m.name())
            .collect();
        Err(Error::Refused {
            method: plan.name(),
            what: crate::Refusal::BadPoints,
            reason: format!(
                "takes no bad points (it finds what to change itself); the methods that do: {}",
                takers.join(", ")
            ),
        })
    }

    /// Runs `plan` on a curve: each stage on the previous stage's points; fixed points and the
    /// end clamp passed to every stage, the tolerance band D shared out (stage k gets D minus
    /// the largest distance any point has already moved; when nothing is left the remaining
    /// stages are skipped and the report says so). O(sum of the stages' costs) plus O(n) per
    /// stage.
    ///
    /// Every run's extras get `largest_move` ([`UnaskedMove::to_json`](crate::displacement::UnaskedMove::to_json)): the farthest move
    /// (index, distance) against the bound the user did not ask to exceed (the data's noise,
    /// read vertically for a function ([`NoiseModel::Vertical`]) and normal to the curve
    /// otherwise, and decimal step, or a wider `--tolerance`), and whether it `exceeds` it.
    /// O(n).
    ///
    /// A curve with corners ([`PlanConstraints::corners`]: detected by default) runs the plan
    /// piece by piece between them, each corner fixed, so that every method keeps it as a G0
    /// break; the extras then have `corners` and `pieces` (module `corner_split`). O(n log n)
    /// for the detection.
    pub fn run_curve_plan(
        &self,
        plan: &Plan,
        points: &CurvePoints,
        kind: CurveKind,
        constraints: &PlanConstraints,
    ) -> Result<CurveRun> {
        let (corners, closed) = super::corner_split::corners_of(plan, points, kind, constraints)?;
        let split = if corners.is_empty() {
            None
        } else {
            let stages =
                |catalog: &Catalog, plan: &Plan, piece: &CurvePoints, constraints: &PlanConstraints| {
                    catalog.run_curve_stages(plan, piece, kind, constraints)
                };
            super::corner_split::run_pieces(self, plan, points, kind, constraints, &corners, closed, &stages)?
        };
        let mut run = match split {
            Some(run) => run,
            None => self.run_curve_stages(plan, points, kind, constraints)?,
        };
        // A function's methods move y only, and its noise is read in y.
        let model = match kind {
            CurveKind::Function => NoiseModel::Vertical,
            CurveKind::Parametric => NoiseModel::Normal,
        };
        let tolerance = constraints.tolerance;
        let unasked = match (points, &run.points) {
            (CurvePoints::Planar(a), CurvePoints::Planar(b)) => unasked_move_as(a, b, tolerance, model),
            (CurvePoints::Spatial(a), CurvePoints::Spatial(b)) => unasked_move_as(a, b, tolerance, model),
            _ => {
                return Err(Error::Strategy {
                    strategy: plan.name(),
                    reason: "returned points of another dimension".into(),
                })
            }
        }?;
        run.extras.insert("largest_move".into(), unasked.to_json());
        Ok(run)
    }

    /// [`Catalog::run_curve_plan`] without the `largest_move` extra.
    fn run_curve_stages(
        &self,
        plan: &Plan,
        points: &CurvePoints,
        kind: CurveKind,
        constraints: &PlanConstraints,
    ) -> Result<CurveRun> {
        self.refuse_bad_points(plan, constraints)?;
        let run_stage = |stage: &Stage, points: &CurvePoints, tolerance: Option<f64>| -> Result<CurveRun> {
            let entry = self.method(MethodKind::Curve, &stage.method)?;
            let stage_constraints = constraints.constraints(tolerance);
            let job = CurveJob {
                method: entry.name(),
                points,
                kind,
                constraints: &stage_constraints,
                bad_points: if entry.takes_bad_points() {
                    &constraints.bad_points
                } else {
                    &[]
                },
                catalog: self,
            };
            entry
                .fair_curve(&stage.settings, &job)
                .map_err(|e| super::method::parameter_error(e, &stage.given))
        };
        if let [stage] = plan.stages.as_slice() {
            return run_stage(stage, points, constraints.tolerance);
        }
        let mut current = points.clone();
        let (mut iterations, mut elapsed_ms) = (0usize, 0.0);
        let mut records = Vec::with_capacity(plan.stages.len());
        let mut curve = Value::Null;
        let mut termination = String::from("strategy-done");
        let mut first_represented = None;
        let mut last_represented = None;
        for (number, stage) in plan.stages.iter().enumerate() {
            let mut tolerance = constraints.tolerance;
            if let Some(band) = constraints.tolerance {
                let used = points.distances(&current).into_iter().fold(0.0, f64::max);
                let left = band - used;
                if left.is_nan() || left <= 0.0 {
                    records.push(serde_json::json!({
                        "stage": number + 1,
                        "method": stage.method,
                        "skipped": "the tolerance band is used up by the earlier stages",
                    }));
                    continue;
                }
                tolerance = Some(left);
            }
            let run = run_stage(stage, &current, tolerance).map_err(|e| match e {
                Error::ConstraintViolated { .. } | Error::Strategy { .. } => Error::Strategy {
                    strategy: format!("stage {} ({})", number + 1, stage.method),
                    reason: e.to_string(),
                },
                other => other,
            })?;
            let distances = current.distances(&run.points);
            let s_d: f64 = distances.iter().sum();
            let m_d = distances.iter().copied().fold(0.0, f64::max);
            iterations += run.iterations;
            elapsed_ms += run.elapsed_ms;
            let params: serde_json::Map<String, Value> = self
                .method(MethodKind::Curve, &stage.method)
                .map(|e| e.visible(&stage.settings))
                .unwrap_or_default();
            records.push(serde_json::json!({
                "stage": number + 1,
                "method": stage.method,
                "params": params,
                "iterations": run.iterations,
                "moved": run.moved.len(),
                "s_d": s_d,
                "m_d": m_d,
                "elapsed_ms": run.elapsed_ms,
                "termination": run.termination,
                "extras": run.extras,
            }));
            match run.represented {
                Some(Represented { before, after }) => {
                    if number == 0 {
                        first_represented = Some(before);
                    }
                    last_represented = Some((number, after));
                }
                None => last_represented = None,
            }
            curve = run.curve;
            termination = run.termination;
            current = run.points;
        }
        // The represented curves are only reported when the first and the last stage both
        // represent the curve their own way (else before and after would measure different
        // curves).
        let last_stage = plan.stages.len() - 1;
        let represented = match (first_represented, last_represented) {
            (Some(before), Some((number, after))) if number == last_stage => {
                Some(Represented { before, after })
            }
            _ => None,
        };
        let mut extras = BTreeMap::new();
        extras.insert("stages".to_owned(), Value::Array(records));
        Ok(CurveRun {
            moved: points.differences(&current),
            points: current,
            iterations,
            elapsed_ms,
            termination,
            curve,
            extras,
            represented,
        })
    }

    /// Runs a one-stage surface plan on a grid.
    pub fn run_surface_plan(&self, plan: &Plan, job: &SurfaceJob) -> Result<SurfaceRun> {
        let [stage] = plan.stages.as_slice() else {
            return Err(Error::Config {
                origin: plan.name(),
                message: "a surface runs one method".into(),
            });
        };
        let entry = self.method(MethodKind::Surface, &stage.method)?;
        entry
            .fair_surface(&stage.settings, job)
            .map_err(|e| super::method::parameter_error(e, &stage.given))
    }
}
