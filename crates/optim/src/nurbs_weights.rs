//! Nowacki et al.'s NURBS weight fairing (FAIRSHAPE 1996, §3 "Fairing by NURBS weights").
//!
//! The cubic NUBS through the data points ([`Interpolation`], The NURBS Book A9.1) is
//! rewritten as a NURBS with unit weights; a [`WeightLaw`] (the paper's cubic Bernstein law
//! w_i = Σ_j k_j B_j(i/n), or one weight per control point) maps a few parameters to weights;
//! the curve is re-solved through the *same* points at the *same* parameters with those weights
//! ([`Interpolation::solve`], the factorisation reused, O(n) per trial) and a fairness
//! [`Criterion`] (E1, E2, E3, Ek, Ek′, or your own) of the result is minimised by Nelder–Mead
//! ([`WeightProblem`]). The data points never move: only the curve between them changes.
//!
//! ```
//! use curve_repr::Vec2;
//! use fairness::Ek;
//! use optim::{CubicBernstein, NurbsWeightFairing};
//!
//! let points: Vec<Vec2> = (0..12)
//!     .map(|i| {
//!         let x = i as f64 / 11.0;
//!         Vec2::new(x, (3.0 * x).sin() + if i == 5 { 0.02 } else { 0.0 })
//!     })
//!     .collect();
//! let result = NurbsWeightFairing::new(CubicBernstein, Ek::<2>::new()).run(&points)?;
//! assert!(result.criterion_after <= result.criterion_before);
//! assert!(result.weights.iter().all(|w| *w > 0.0));
//! assert!(result.max_residual < 1e-9);
//! # Ok::<(), optim::Error>(())
//! ```
//!
//! Cost: one banded factorisation (O(n)), then per Nelder–Mead trial one O(n) solve plus one
//! evaluation of the criterion (O(pieces) quadrature).

use std::fmt;
use std::str::FromStr;

use curve_repr::{Interpolation, InterpolationSettings, NurbsCurve, Parametrization, Vector};
use fairness::curvature::CurvatureForm;
use fairness::{Adaptive, Criterion, Ek, EkPrime, Energies, EnergyAccuracy, E1, E2, E3};

use crate::error::{Error, Result};
use crate::gradient::{InterpolantCriterion, SmoothCriterion};
use crate::lbfgs::LbfgsSettings;
use crate::nelder_mead::{NelderMeadSettings, Termination};
use crate::problem::WeightProblem;
use crate::weight_law::{LawDescription, WeightLaw};
use fairness::fixed_rule::FixedRule;

/// The built-in criteria by name, for a command line (`--set criterion=ek`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum CriterionName {
    /// [`E1`] = ∫ |C′|² dt.
    E1,
    /// [`E2`] = ∫ |C″|² dt.
    E2,
    /// [`E3`] = ∫ |C‴|² dt.
    E3,
    /// [`Ek`] = ∫ κ² ds (the default).
    #[default]
    Ek,
    /// [`EkPrime`] = ∫ (dκ/ds)² ds.
    EkPrime,
}

impl CriterionName {
    /// All five, in the paper's order.
    pub const ALL: [CriterionName; 5] = [
        CriterionName::E1,
        CriterionName::E2,
        CriterionName::E3,
        CriterionName::Ek,
        CriterionName::EkPrime,
    ];

    /// The kebab-case name ("e1", "e2", "e3", "ek", "ek-prime").
    pub fn as_str(self) -> &'static str {
        match self {
            CriterionName::E1 => "e1",
            CriterionName::E2 => "e2",
            CriterionName::E3 => "e3",
            CriterionName::Ek => "ek",
            CriterionName::EkPrime => "ek-prime",
        }
    }

    /// The criterion itself, boxed, with its default (adaptive) quadrature.
    pub fn criterion<const D: usize>(self) -> Box<dyn Criterion<NurbsCurve<D>>>
    where
        Vector<D>: CurvatureForm,
    {
        match self {
            CriterionName::E1 => Box::new(E1::<D>::new()),
            CriterionName::E2 => Box::new(E2::<D>::new()),
            CriterionName::E3 => Box::new(E3::<D>::new()),
            CriterionName::Ek => Box::new(Ek::<D>::new()),
            CriterionName::EkPrime => Box::new(EkPrime::<D>::new()),
        }
    }

    /// This criterion's value among `energies`.
    pub fn of(self, energies: &Energies) -> f64 {
        match self {
            CriterionName::E1 => energies.e1,
            CriterionName::E2 => energies.e2,
            CriterionName::E3 => energies.e3,
            CriterionName::Ek => energies.ek,
            CriterionName::EkPrime => energies.ek_prime,
        }
    }
}

impl fmt::Display for CriterionName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for CriterionName {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "e1" => Ok(CriterionName::E1),
            "e2" => Ok(CriterionName::E2),
            "e3" => Ok(CriterionName::E3),
            "ek" => Ok(CriterionName::Ek),
            "ek-prime" | "ekprime" | "ek'" => Ok(CriterionName::EkPrime),
            other => Err(Error::InvalidSetting {
                name: "criterion",
                reason: format!("unknown criterion {other:?} (expected e1, e2, e3, ek or ek-prime)"),
            }),
        }
    }
}

/// A weight law by name, for the catalogue (`--set law=...`).
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Hash,
    Default,
    serde::Serialize,
    serde::Deserialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum LawName {
    /// [`CubicBernstein`](crate::CubicBernstein): the paper's four cubic coefficients.
    #[default]
    Bernstein,
    /// [`PerPoint`](crate::PerPoint): one weight per control point.
    PerPoint,
}

/// Which solver searches the weights (`--set solver=...`).
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Hash,
    Default,
    serde::Serialize,
    serde::Deserialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum SolverName {
    /// nelder-mead for the bernstein law; lbfgs for per-point with criterion ek or e2.
    #[default]
    Auto,
    /// Nelder–Mead on the law's parameters, as in the paper.
    NelderMead,
    /// L-BFGS (More–Thuente line search) on the log-weights, following the exact gradient of
    /// the fixed-rule ek or e2 (`fairness::fixed_rule`, dual numbers).
    Lbfgs,
}

impl SolverName {
    /// The kebab-case name.
    pub fn as_str(self) -> &'static str {
        match self {
            SolverName::Auto => "auto",
            SolverName::NelderMead => "nelder-mead",
            SolverName::Lbfgs => "lbfgs",
        }
    }
}

/// Settings of Nowacki et al.'s weight fairing as a method of the catalogue
/// (`nurbs-weights`): which criterion, which weight law, how long to search.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct NurbsWeightSettings {
    /// Criterion minimised: a registered criterion (e1, e2, e3, ek, ek-prime, ...).
    ///
    /// The name is looked up in the catalogue (`fair methods` lists the criteria); default
    /// `ek`, as in the paper's Table 1.
    pub criterion: String,
    /// Weight law: bernstein (the paper's 4 cubic coefficients) or per-point.
    pub law: LawName,
    /// Iterations at most (Nelder-Mead's or L-BFGS's).
    pub max_iterations: u64,
    /// Solver: auto, nelder-mead or lbfgs (gradient-based; criterion ek or e2 only).
    ///
    /// `auto` (the default) is Nelder–Mead for the paper's 4-parameter bernstein law (as in
    /// the paper) and L-BFGS for the per-point law when the criterion is ek or e2, because it
    /// ends lower on the per-point law (the Gunnerus waterline wl_03, NACA 2412 upper), though
    /// it is slower per iteration (one dual evaluation per weight for each gradient). L-BFGS
    /// follows the exact gradient of the fixed-rule criterion (20-point Gauss–Legendre per knot span) with
    /// respect to the log-weights, which keeps the weights positive and within the law's
    /// bounds. The reported criterion is always the catalogue's (adaptive) one.
    pub solver: SolverName,
}

impl Default for NurbsWeightSettings {
    fn default() -> Self {
        NurbsWeightSettings {
            criterion: CriterionName::Ek.as_str().to_owned(),
            law: LawName::Bernstein,
            max_iterations: 1000,
            solver: SolverName::Auto,
        }
    }
}

impl NurbsWeightSettings {
    /// Checks the settings: a criterion is named.
    pub fn validate(&self) -> Result<()> {
        if self.criterion.trim().is_empty() {
            return Err(Error::InvalidSetting {
                name: "criterion",
                reason: "names no criterion".into(),
            });
        }
        if self.solver == SolverName::Lbfgs && SmoothCriterion::from_name(&self.criterion).is_none() {
            return Err(Error::InvalidSetting {
                name: "solver",
                reason: format!(
                    "lbfgs needs a criterion with a differentiable fixed-rule form (ek or e2), not {:?}",
                    self.criterion
                ),
            });
        }
        Ok(())
    }

    /// The solver `auto` stands for with these settings (see [`NurbsWeightSettings::solver`]):
    /// never `Auto`.
    pub fn resolved_solver(&self) -> SolverName {
        match (self.solver, self.law, SmoothCriterion::from_name(&self.criterion)) {
            (SolverName::Auto, LawName::PerPoint, Some(_)) => SolverName::Lbfgs,
            (SolverName::Auto, _, _) => SolverName::NelderMead,
            (chosen, _, _) => chosen,
        }
    }
}

/// Nowacki et al.'s weight fairing of the cubic NURBS through a point sequence: a weight law
/// `L`, a criterion `C` of the re-solved curve, Nelder–Mead settings, the parametrisation
/// (default chord length) and optional end tangents (derivatives with respect to the
/// normalised parameter, see [`InterpolationSettings::with_end_tangents`]).
pub struct NurbsWeightFairing<'a, L, C, const D: usize> {
    law: L,
    criterion: C,
    nelder_mead: NelderMeadSettings<'a>,
    lbfgs: Option<(SmoothCriterion, LbfgsSettings)>,
    parametrization: Parametrization,
    end_tangents: Option<(Vector<D>, Vector<D>)>,
}

/// The result of [`NurbsWeightFairing::run`].
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct NurbsWeightResult<const D: usize> {
    /// The faired NURBS through the unchanged points.
    pub curve: NurbsCurve<D>,
    /// Its weights, one per control point (all > 0).
    pub weights: Vec<f64>,
    /// The law's parameters that give `weights`.
    pub law_params: Vec<f64>,
    /// The law's name and parameter names.
    pub law: LawDescription,
    /// The normalised parameters of the data points on `curve`.
    pub params: Vec<f64>,
    /// All five criteria of the NUBS (unit weights): best estimates, see `before_accuracy`.
    pub before: Energies,
    /// All five criteria of the faired curve: best estimates, see `after_accuracy`.
    pub after: Energies,
    /// How accurately `before` is known ([`Energies::measure`], default settings).
    pub before_accuracy: EnergyAccuracy,
    /// How accurately `after` is known.
    pub after_accuracy: EnergyAccuracy,
    /// The optimised criterion's name.
    pub criterion: String,
    /// The optimised criterion at unit weights.
    pub criterion_before: f64,
    /// The optimised criterion at the optimum (never above `criterion_before`).
    pub criterion_after: f64,
    /// Solver iterations (Nelder–Mead's or L-BFGS's).
    pub iterations: u64,
    /// Why the search stopped.
    pub termination: Termination,
    /// Criterion evaluations (value and gradient requests together for L-BFGS).
    pub evaluations: u64,
    /// Gradient evaluations (0 for Nelder–Mead), each one dual evaluation per weight.
    pub gradient_evaluations: u64,
    /// max_k |C(ū_k) − D_k| of the faired curve at the data points.
    pub max_residual: f64,
}

impl<'a, L: WeightLaw, C, const D: usize> NurbsWeightFairing<'a, L, C, D>
where
    C: Criterion<NurbsCurve<D>>,
    Vector<D>: CurvatureForm,
{
    /// The fairing with `law` and `criterion`, default Nelder–Mead settings, chord-length
    /// parameters and free ends.
    pub fn new(law: L, criterion: C) -> Self {
        NurbsWeightFairing {
            law,
            criterion,
            nelder_mead: NelderMeadSettings::default(),
            lbfgs: None,
            parametrization: Parametrization::ChordLength,
            end_tangents: None,
        }
    }

    /// Sets the Nelder–Mead settings.
    pub fn with_nelder_mead(mut self, settings: NelderMeadSettings<'a>) -> Self {
        self.nelder_mead = settings;
        self
    }

    /// Searches by L-BFGS instead of Nelder–Mead, following the exact gradient of `smooth`
    /// (the fixed-rule form of the criterion, [`InterpolantCriterion`]); the criterion `C`
    /// still measures the result ([`WeightProblem::solve_lbfgs`]). The law must have a
    /// derivative ([`WeightLaw::pull_back`]).
    pub fn with_lbfgs(mut self, smooth: SmoothCriterion, settings: LbfgsSettings) -> Self {
        self.lbfgs = Some((smooth, settings));
        self
    }

    /// Sets the parametrisation of the data points.
    pub fn with_parametrization(mut self, parametrization: Parametrization) -> Self {
        self.parametrization = parametrization;
        self
    }

    /// Prescribes the end derivatives (with respect to the normalised parameter u ∈ [0, 1]).
    pub fn with_end_tangents(mut self, start: Vector<D>, end: Vector<D>) -> Self {
        self.end_tangents = Some((start, end));
        self
    }

    /// The weight law.
    pub fn law(&self) -> &L {
        &self.law
    }

    /// The criterion.
    pub fn criterion(&self) -> &C {
        &self.criterion
    }

    /// Fairs the cubic NURBS through `points`. Fails on the interpolation's errors (too few
    /// or repeated points, non-finite values) as [`Error::Curve`], when the criterion cannot
    /// be evaluated at unit weights ([`Error::StartFailed`]), and on invalid settings.
    pub fn run(self, points: &[Vector<D>]) -> Result<NurbsWeightResult<D>> {
        let mut settings = InterpolationSettings::<D>::default();
        if let Some((start, end)) = self.end_tangents {
            settings = settings.with_end_tangents(start, end);
        }
        let interpolation = Interpolation::with_parametrization(points, self.parametrization, settings)?;
        let criterion = &self.criterion;
        let interp = &interpolation;
        let objective = move |weights: &[f64]| -> Result<f64> {
            let curve = interp.solve(weights)?;
            criterion.evaluate(&curve).map_err(Error::objective)
        };
        let problem = WeightProblem::new(&self.law, interpolation.control_count(), objective);
        let solution = match self.lbfgs {
            None => problem.solve(self.nelder_mead)?,
            Some((smooth, settings)) => {
                let smooth = InterpolantCriterion::new(interp, smooth, FixedRule::default())?;
                problem.solve_lbfgs(|w: &[f64]| smooth.value_and_gradient(w), settings)?
            }
        };
        let nubs = interpolation.nubs()?;
        let curve = interpolation.solve(&solution.weights)?;
        // Diagnostics: best estimates with their accuracy, never a lost result for a
        // tolerance that a rational curve's integrands cannot meet.
        let before = Energies::measure(&nubs, &Adaptive::default()).map_err(Error::objective)?;
        let after = Energies::measure(&curve, &Adaptive::default()).map_err(Error::objective)?;
        let max_residual = interpolation
            .params()
            .iter()
            .zip(interpolation.points())
            .map(|(u, p)| (curve.point(*u) - p).norm())
            .fold(0.0, f64::max);
        if !max_residual.is_finite() {
            return Err(Error::objective("the faired curve is not finite at a data point"));
        }
        Ok(NurbsWeightResult {
            weights: solution.weights,
            law_params: solution.params,
            law: solution.law,
            params: interpolation.params().to_vec(),
            before: before.values,
            after: after.values,
            before_accuracy: before.accuracy,
            after_accuracy: after.accuracy,
            criterion: self.criterion.name().to_string(),
            criterion_before: solution.before,
            criterion_after: solution.after,
            iterations: solution.iterations,
            termination: solution.termination,
            evaluations: solution.evaluations,
            gradient_evaluations: solution.gradient_evaluations,
            max_residual,
            curve,
        })
    }
}
