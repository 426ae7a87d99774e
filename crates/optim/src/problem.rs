//! The weight problem: choose a weight law's parameters to minimise a criterion of the weights.
//!
//! Nowacki et al. (1996, §3) fair an interpolating cubic NURBS by re-solving it with the
//! weights a cubic Bernstein law gives and minimising a fairness criterion (E1, E2, E3, Ek)
//! of the result by Nelder–Mead, starting from unit weights (the NUBS curve). Here that is
//! [`WeightProblem`] with the law [`CubicBernstein`](crate::CubicBernstein) and, as the
//! criterion, "interpolate the data with these weights, then measure": the NURBS version is an
//! instance, with no NURBS code in this module.
//!
//! ```
//! use optim::{CubicBernstein, NelderMeadSettings, WeightProblem};
//!
//! // A stand-in criterion with its minimum where the weights rise linearly from 1 to 2.
//! let criterion = |w: &[f64]| {
//!     let n = (w.len() - 1) as f64;
//!     Ok(w.iter().enumerate().map(|(i, w)| (w - 1.0 - i as f64 / n).powi(2)).sum::<f64>())
//! };
//! let problem = WeightProblem::new(CubicBernstein, 8, criterion);
//! let solution = problem.solve(NelderMeadSettings::default())?;
//! assert!(solution.after <= solution.before);
//! assert!(solution.after < 1e-8 * solution.before);
//! assert!(solution.weights.iter().all(|w| *w > 0.0));
//! # Ok::<(), optim::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::lbfgs::{minimize_lbfgs, LbfgsSettings};
use crate::nelder_mead::{minimize, NelderMeadSettings, Termination};
use crate::weight_law::{LawDescription, WeightLaw};

/// A criterion of the weights: for NURBS fairing, the fairness measure of the curve re-solved
/// with these weights. Implemented for every closure `Fn(&[f64]) -> Result<f64>`.
///
/// A failure or non-finite value at a trial point counts as +∞ during the search (see
/// [`nelder_mead`](crate::nelder_mead)); at unit weights it is a hard error.
pub trait WeightCriterion {
    /// The criterion for one weight per control point.
    fn evaluate(&self, weights: &[f64]) -> Result<f64>;
}

impl<F> WeightCriterion for F
where
    F: Fn(&[f64]) -> Result<f64>,
{
    fn evaluate(&self, weights: &[f64]) -> Result<f64> {
        self(weights)
    }
}

/// A weight law over `control_points` control points coupled with a criterion of the weights.
///
/// The search minimises `criterion(law.weights(params)) / |criterion(unit weights)|` (the raw
/// criterion when that is zero): scaled so, the settings' standard-deviation tolerance is
/// relative to the starting criterion, whatever its units (the paper's Table 1 spans E1 ≈ 2e2
/// to E3 ≈ 1e8). The reported `before` and `after` are the unscaled criterion.
#[derive(Debug, Clone)]
pub struct WeightProblem<L, C> {
    law: L,
    control_points: usize,
    criterion: C,
}

/// The result of [`WeightProblem::solve`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct WeightSolution {
    /// The best weights found, one per control point.
    pub weights: Vec<f64>,
    /// The law's parameters that give them.
    pub params: Vec<f64>,
    /// The criterion at unit weights.
    pub before: f64,
    /// The criterion at `weights` (never above `before`).
    pub after: f64,
    /// The law, for the report.
    pub law: LawDescription,
    /// Solver iterations (Nelder–Mead's or L-BFGS's).
    pub iterations: u64,
    /// Why the search stopped.
    pub termination: Termination,
    /// Criterion evaluations, including failed ones and the final re-evaluation.
    pub evaluations: u64,
    /// Evaluations that failed or were not finite.
    pub failed_evaluations: u64,
    /// Gradient evaluations (0 for Nelder–Mead; included in `evaluations`).
    pub gradient_evaluations: u64,
}

impl<L: WeightLaw, C: WeightCriterion> WeightProblem<L, C> {
    /// Couples `law` over `control_points` control points with `criterion`.
    pub fn new(law: L, control_points: usize, criterion: C) -> Self {
        WeightProblem {
            law,
            control_points,
            criterion,
        }
    }

    /// The weight law.
    pub fn law(&self) -> &L {
        &self.law
    }

    /// The number of control points (of weights).
    pub fn control_points(&self) -> usize {
        self.control_points
    }

    /// The criterion itself.
    pub fn criterion(&self) -> &C {
        &self.criterion
    }

    /// The criterion at the weights of the law's parameters `params`.
    pub fn criterion_at(&self, params: &[f64]) -> Result<f64> {
        let weights = self.law.weights(params, self.control_points)?;
        self.criterion.evaluate(&weights)
    }

    /// Minimises from the law's identity parameters (unit weights), as the paper does.
    pub fn solve(&self, settings: NelderMeadSettings<'_>) -> Result<WeightSolution> {
        let start = self.law.identity_params(self.control_points);
        self.solve_from(&start, settings)
    }

    /// Minimises from the law's parameters `start`; `before` is still the criterion at unit
    /// weights. The observer in `settings` sees the scaled criterion (see the type's docs).
    pub fn solve_from(&self, start: &[f64], settings: NelderMeadSettings<'_>) -> Result<WeightSolution> {
        let unit = self.law.identity_params(self.control_points);
        let before = self.criterion_at(&unit).map_err(|error| Error::StartFailed {
            reason: format!("at unit weights: {error}"),
        })?;
        if !before.is_finite() {
            return Err(Error::StartFailed {
                reason: format!("the criterion at unit weights is {before}"),
            });
        }
        let scale = if before == 0.0 { 1.0 } else { before.abs() };
        let objective = |params: &[f64]| Ok(self.criterion_at(params)? / scale);
        let minimum = minimize(&objective, start, settings)?;
        let weights = self.law.weights(&minimum.params, self.control_points)?;
        let after = self.criterion.evaluate(&weights)?;
        let (params, after, weights) = if after <= before {
            (minimum.params, after, weights)
        } else {
            // Only when started away from unit weights and the search ended above them.
            (
                unit.clone(),
                before,
                self.law.weights(&unit, self.control_points)?,
            )
        };
        Ok(WeightSolution {
            weights,
            params,
            before,
            after,
            law: self.law.describe(self.control_points),
            iterations: minimum.iterations,
            termination: minimum.termination,
            evaluations: minimum.evaluations + 2,
            failed_evaluations: minimum.failed_evaluations,
            gradient_evaluations: 0,
        })
    }

    /// Minimises by L-BFGS with More–Thuente line search ([`minimize_lbfgs`]) from unit
    /// weights, following `smooth`, a smooth stand-in for the criterion with its gradient with
    /// respect to the weights (e.g. [`InterpolantCriterion`](crate::InterpolantCriterion):
    /// the fixed-rule Ek or E2), chained through the law's [`WeightLaw::pull_back`]. The
    /// search sees `smooth(w) / |smooth(unit)|`; `before` and `after` are this problem's own
    /// criterion, and the unit weights are returned if the found ones do not lower it.
    ///
    /// Fails with [`Error::InvalidSetting`] when the law has no derivative, and like
    /// [`WeightProblem::solve`] when the criterion fails at unit weights.
    pub fn solve_lbfgs<G>(&self, smooth: G, settings: LbfgsSettings) -> Result<WeightSolution>
    where
        G: Fn(&[f64]) -> Result<(f64, Vec<f64>)>,
    {
        let n = self.control_points;
        let unit = self.law.identity_params(n);
        let unit_weights = self.law.weights(&unit, n)?;
        let before = self.criterion_at(&unit).map_err(|error| Error::StartFailed {
            reason: format!("at unit weights: {error}"),
        })?;
        if !before.is_finite() {
            return Err(Error::StartFailed {
                reason: format!("the criterion at unit weights is {before}"),
            });
        }
        if self.law.pull_back(&unit, n, &vec![0.0; n]).is_none() {
            return Err(Error::InvalidSetting {
                name: "solver",
                reason: format!("the weight law {} has no derivative for L-BFGS", self.law.name()),
            });
        }
        let (start_value, _) = smooth(&unit_weights).map_err(|error| Error::StartFailed {
            reason: format!("the smooth criterion at unit weights: {error}"),
        })?;
        let scale = if start_value == 0.0 || !start_value.is_finite() {
            1.0
        } else {
            start_value.abs()
        };
        let objective = |params: &[f64]| -> Result<(f64, Vec<f64>)> {
            let weights = self.law.weights(params, n)?;
            let (value, gradient) = smooth(&weights)?;
            let pulled = self
                .law
                .pull_back(params, n, &gradient)
                .unwrap_or_else(|| Ok(vec![f64::NAN; params.len()]))?;
            Ok((value / scale, pulled.into_iter().map(|g| g / scale).collect()))
        };
        let result = minimize_lbfgs(&objective, &unit, settings)?;
        let minimum = result.minimum;
        let weights = self.law.weights(&minimum.params, n)?;
        let after = self.criterion.evaluate(&weights).ok().filter(|v| v.is_finite());
        let (params, after, weights) = match after {
            Some(after) if after <= before => (minimum.params, after, weights),
            _ => (unit, before, unit_weights),
        };
        Ok(WeightSolution {
            weights,
            params,
            before,
            after,
            law: self.law.describe(n),
            iterations: minimum.iterations,
            termination: minimum.termination,
            evaluations: minimum.evaluations + 2,
            failed_evaluations: minimum.failed_evaluations,
            gradient_evaluations: result.gradient_evaluations,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::weight_law::{CubicBernstein, PerPoint};

    /// A criterion with a known minimiser inside the cubic Bernstein family:
    /// target weights from k = (1, 3, 0.5, 2).
    fn target() -> Vec<f64> {
        CubicBernstein
            .weights(&[0.0, 3f64.ln(), 0.5f64.ln(), 2f64.ln()], 10)
            .unwrap()
    }

    #[test]
    fn recovers_a_law_that_is_the_minimiser() {
        let target = target();
        // A plain squared distance, whose unique minimiser is the target itself.
        let criterion =
            |w: &[f64]| -> Result<f64> { Ok(w.iter().zip(&target).map(|(a, b)| (a - b).powi(2)).sum()) };
        let problem = WeightProblem::new(CubicBernstein, 10, criterion);
        let solution = problem
            .solve(
                NelderMeadSettings::default()
                    .with_sd_tolerance(1e-16)
                    .with_max_iterations(5000),
            )
            .unwrap();
        assert_eq!(solution.termination, Termination::Converged);
        for (w, t) in solution.weights.iter().zip(&target) {
            assert!((w - t).abs() < 1e-5, "{w} vs {t}");
        }
        assert!(solution.after < solution.before);
        assert_eq!(solution.law.name, "cubic-bernstein");
        // `before` is the criterion at unit weights, by definition.
        let unit: f64 = target.iter().map(|t| (1.0 - t).powi(2)).sum();
        assert_eq!(solution.before, unit);
    }

    #[test]
    fn failing_criterion_at_unit_weights_is_an_error() {
        let criterion = |_: &[f64]| -> Result<f64> { Err(Error::objective("no curve")) };
        let problem = WeightProblem::new(PerPoint, 5, criterion);
        assert!(matches!(
            problem.solve(NelderMeadSettings::default()),
            Err(Error::StartFailed { .. })
        ));
        let nan = |_: &[f64]| -> Result<f64> { Ok(f64::NAN) };
        let problem = WeightProblem::new(PerPoint, 5, nan);
        assert!(matches!(
            problem.solve(NelderMeadSettings::default()),
            Err(Error::StartFailed { .. })
        ));
    }

    #[test]
    fn criterion_failing_away_from_unit_weights_is_avoided() {
        // Fails wherever any weight exceeds 1.5; the minimum of the rest is at w = 1.4.
        let criterion = |w: &[f64]| -> Result<f64> {
            if w.iter().any(|w| *w > 1.5) {
                return Err(Error::objective("curve could not be solved"));
            }
            Ok(w.iter().map(|w| (w - 1.4).powi(2)).sum())
        };
        let problem = WeightProblem::new(PerPoint, 4, criterion);
        let solution = problem
            .solve(NelderMeadSettings::default().with_step(0.5))
            .unwrap();
        assert!(solution.weights.iter().all(|w| *w <= 1.5));
        // w_0 is held at 1; the others reach 1.4.
        for w in &solution.weights[1..] {
            assert!((w - 1.4).abs() < 1e-3, "{w}");
        }
        assert!(solution.failed_evaluations > 0);
    }

    #[test]
    fn lbfgs_recovers_a_per_point_minimiser_from_the_gradient() {
        // Σ (w_i − t_i)², t_0 = 1 (w_0 is held), gradient 2 (w − t).
        let target: Vec<f64> = (0..12)
            .map(|i| if i == 0 { 1.0 } else { 0.5 + 0.1 * i as f64 })
            .collect();
        let criterion =
            |w: &[f64]| -> Result<f64> { Ok(w.iter().zip(&target).map(|(a, b)| (a - b).powi(2)).sum()) };
        let smooth = |w: &[f64]| -> Result<(f64, Vec<f64>)> {
            Ok((
                criterion(w)?,
                w.iter().zip(&target).map(|(a, b)| 2.0 * (a - b)).collect(),
            ))
        };
        let problem = WeightProblem::new(PerPoint, 12, criterion);
        let solution = problem.solve_lbfgs(smooth, LbfgsSettings::default()).unwrap();
        assert_eq!(solution.termination, Termination::Converged);
        for (w, t) in solution.weights.iter().zip(&target) {
            assert!((w - t).abs() < 1e-4, "{w} vs {t}");
        }
        assert!(solution.gradient_evaluations > 0 && solution.after < 1e-8);
    }

    #[test]
    fn single_control_point_has_nothing_to_optimise() {
        let criterion = |w: &[f64]| -> Result<f64> { Ok(w[0] + 1.0) };
        let problem = WeightProblem::new(PerPoint, 1, criterion);
        let solution = problem.solve(NelderMeadSettings::default()).unwrap();
        assert_eq!(solution.weights, vec![1.0]);
        assert_eq!(solution.before, 2.0);
        assert_eq!(solution.after, 2.0);
        assert_eq!(solution.iterations, 0);
    }
}
