//! L-BFGS with a More–Thuente line search (argmin's `LBFGS` + `MoreThuenteLineSearch`) for
//! objectives that come with their exact gradient, e.g. a fixed-rule criterion of the NURBS
//! weights differentiated by [`Dual`](crate::Dual) numbers ([`crate::gradient`]).
//!
//! Like [`minimize`](crate::minimize) for Nelder–Mead, the loop of argmin's executor is driven
//! here so that a failed evaluation ends the search with the best point found so far instead
//! of losing it.

use std::cell::Cell;

use argmin::core::{
    CostFunction, Gradient, IterState, Problem, Solver, State, TerminationReason, TerminationStatus,
};
use argmin::solver::linesearch::MoreThuenteLineSearch;
use argmin::solver::quasinewton::LBFGS;

use crate::error::{Error, Result};
use crate::nelder_mead::{Minimum, Termination};

/// A function with its gradient: `(f(x), ∇f(x))`. Implemented for every closure
/// `Fn(&[f64]) -> Result<(f64, Vec<f64>)>`.
pub trait GradientObjective {
    /// Value and gradient at `params`.
    fn value_and_gradient(&self, params: &[f64]) -> Result<(f64, Vec<f64>)>;
}

impl<F> GradientObjective for F
where
    F: Fn(&[f64]) -> Result<(f64, Vec<f64>)>,
{
    fn value_and_gradient(&self, params: &[f64]) -> Result<(f64, Vec<f64>)> {
        self(params)
    }
}

/// Settings of [`minimize_lbfgs`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LbfgsSettings {
    /// Correction pairs kept (argmin's m). Default 7.
    pub memory: usize,
    /// Iterations at most. Default 1000.
    pub max_iterations: u64,
    /// Stop when |∇f| falls below this. Default 1e-8 (the weight problem scales f to 1 at the
    /// start).
    pub gradient_tolerance: f64,
    /// Stop when f changes by less than this in an iteration. Default 1e-6: the weight
    /// problem scales f to 1 at the start, and on per-point Ek (Gunnerus wl_03, NACA 2412)
    /// the iterations after that gain ~1e-4 of Ek in hundreds of gradients, towards extreme
    /// weights.
    pub cost_tolerance: f64,
}

impl Default for LbfgsSettings {
    fn default() -> Self {
        LbfgsSettings {
            memory: 7,
            max_iterations: 1000,
            gradient_tolerance: 1e-8,
            cost_tolerance: 1e-6,
        }
    }
}

/// Evaluation counters.
#[derive(Default)]
struct Counts {
    values: Cell<u64>,
    gradients: Cell<u64>,
    failures: Cell<u64>,
}

struct Adapter<'o, O: ?Sized> {
    objective: &'o O,
    counts: &'o Counts,
}

impl<O: GradientObjective + ?Sized> Adapter<'_, O> {
    fn evaluate(&self, params: &[f64]) -> std::result::Result<(f64, Vec<f64>), argmin::core::Error> {
        if crate::cancel::cancelled() {
            return Err(argmin::core::Error::msg("cancelled"));
        }
        match self.objective.value_and_gradient(params) {
            Ok((value, gradient)) if value.is_finite() && gradient.iter().all(|g| g.is_finite()) => {
                Ok((value, gradient))
            }
            Ok(_) => {
                self.counts.failures.set(self.counts.failures.get() + 1);
                Err(argmin::core::Error::msg(
                    "the objective or its gradient is not finite",
                ))
            }
            Err(error) => {
                self.counts.failures.set(self.counts.failures.get() + 1);
                Err(argmin::core::Error::msg(error.to_string()))
            }
        }
    }
}

impl<O: GradientObjective + ?Sized> CostFunction for Adapter<'_, O> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, params: &Vec<f64>) -> std::result::Result<f64, argmin::core::Error> {
        self.counts.values.set(self.counts.values.get() + 1);
        Ok(self.evaluate(params)?.0)
    }
}

impl<O: GradientObjective + ?Sized> Gradient for Adapter<'_, O> {
    type Param = Vec<f64>;
    type Gradient = Vec<f64>;

    fn gradient(&self, params: &Vec<f64>) -> std::result::Result<Vec<f64>, argmin::core::Error> {
        self.counts.gradients.set(self.counts.gradients.get() + 1);
        Ok(self.evaluate(params)?.1)
    }
}

type LbfgsState = IterState<Vec<f64>, Vec<f64>, (), (), (), f64>;
type Lbfgs = LBFGS<MoreThuenteLineSearch<Vec<f64>, Vec<f64>, f64>, Vec<f64>, Vec<f64>, f64>;

/// The result of [`minimize_lbfgs`]: the [`Minimum`] (its `evaluations` counts value and
/// gradient requests together) and the gradient requests alone.
#[derive(Debug, Clone, PartialEq)]
pub struct LbfgsMinimum {
    /// Best point, cost, iterations, termination, evaluations.
    pub minimum: Minimum,
    /// Gradient requests (each one costs what the objective's gradient costs).
    pub gradient_evaluations: u64,
}

/// Minimises `objective` from `start` by L-BFGS with More–Thuente line search.
///
/// A failed or non-finite evaluation during the search stops it with the best point so far
/// (termination `Other` with the reason); one at the start is [`Error::StartFailed`]. A
/// cancellation ([`crate::cancel`], checked once per iteration and per evaluation) is
/// [`Error::Cancelled`].
/// Cost per iteration: a few value-and-gradient evaluations plus O(memory · parameters).
pub fn minimize_lbfgs<O>(objective: &O, start: &[f64], settings: LbfgsSettings) -> Result<LbfgsMinimum>
where
    O: GradientObjective + ?Sized,
{
    crate::cancel::checkpoint()?;
    let start_cost = match objective.value_and_gradient(start) {
        Ok((cost, gradient)) if cost.is_finite() && gradient.iter().all(|g| g.is_finite()) => cost,
        Ok(_) => {
            return Err(Error::StartFailed {
                reason: "the cost or its gradient is not finite".into(),
            })
        }
        Err(error) => {
            return Err(Error::StartFailed {
                reason: error.to_string(),
            })
        }
    };
    let done = |params: Vec<f64>, cost, iterations, termination, counts: &Counts| LbfgsMinimum {
        minimum: Minimum {
            params,
            cost,
            iterations,
            termination,
            evaluations: counts.values.get() + counts.gradients.get() + 1,
            failed_evaluations: counts.failures.get(),
        },
        gradient_evaluations: counts.gradients.get() + 1,
    };
    let counts = Counts::default();
    if start.is_empty() {
        return Ok(done(Vec::new(), start_cost, 0, Termination::Converged, &counts));
    }
    let solver: Lbfgs = LBFGS::new(MoreThuenteLineSearch::new(), settings.memory.max(1))
        .with_tolerance_grad(settings.gradient_tolerance)
        .and_then(|s| s.with_tolerance_cost(settings.cost_tolerance))
        .map_err(Error::from_solver)?;
    let mut problem = Problem::new(Adapter {
        objective,
        counts: &counts,
    });
    let state = LbfgsState::new()
        .param(start.to_vec())
        .max_iters(settings.max_iterations);
    let (state, stopped) = run(solver, &mut problem, state);
    // A cancellation stops the loop (or a line search) like a failure; it is an error here.
    crate::cancel::checkpoint()?;
    let termination = match (stopped, state.get_termination_reason()) {
        (Some(reason), _) => Termination::Other(reason),
        (None, Some(TerminationReason::SolverConverged)) => Termination::Converged,
        (None, Some(TerminationReason::MaxItersReached)) => Termination::MaxIterations,
        (None, Some(other)) => Termination::Other(other.text().to_string()),
        (None, None) => Termination::Other("not terminated".into()),
    };
    let (params, cost) = match state.get_best_param() {
        Some(params) if state.get_best_cost() <= start_cost => (params.clone(), state.get_best_cost()),
        _ => (start.to_vec(), start_cost),
    };
    Ok(done(params, cost, state.get_iter(), termination, &counts))
}

/// argmin's executor loop (init, then terminate-check / `next_iter` / update); an error ends
/// it with the last state and the error's text.
fn run<O: GradientObjective + ?Sized>(
    mut solver: Lbfgs,
    problem: &mut Problem<Adapter<'_, O>>,
    state: LbfgsState,
) -> (LbfgsState, Option<String>) {
    let fallback = state.clone();
    let mut state = match solver.init(problem, state) {
        Ok((state, _)) => state,
        Err(error) => return (fallback, Some(format!("{error:#}"))),
    };
    state.update();
    loop {
        if !state.terminated() {
            if let TerminationStatus::Terminated(reason) =
                <Lbfgs as Solver<Adapter<'_, O>, LbfgsState>>::terminate_internal(&mut solver, &state)
            {
                state = state.terminate_with(reason);
            }
        }
        if state.terminated() {
            return (state, None);
        }
        if crate::cancel::cancelled() {
            return (state, Some("cancelled".into()));
        }
        let previous = state.clone();
        match solver.next_iter(problem, state) {
            Ok((next, _)) => {
                state = next;
                state.update();
                state.increment_iter();
            }
            Err(error) => return (previous, Some(format!("{error:#}"))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock's function with its gradient: minimum 0 at (1, 1).
    fn rosenbrock(x: &[f64]) -> Result<(f64, Vec<f64>)> {
        let (a, b) = (x[0], x[1]);
        let value = (1.0 - a).powi(2) + 100.0 * (b - a * a).powi(2);
        let gradient = vec![-2.0 * (1.0 - a) - 400.0 * a * (b - a * a), 200.0 * (b - a * a)];
        Ok((value, gradient))
    }

    #[test]
    fn finds_rosenbrocks_minimum() {
        // The default cost tolerance (1e-6) is for objectives scaled to 1; ask for more here.
        let settings = LbfgsSettings {
            cost_tolerance: 1e-15,
            ..LbfgsSettings::default()
        };
        let result = minimize_lbfgs(&rosenbrock, &[-1.2, 1.0], settings).unwrap();
        let m = result.minimum;
        assert_eq!(m.termination, Termination::Converged);
        assert!(
            (m.params[0] - 1.0).abs() < 1e-6 && (m.params[1] - 1.0).abs() < 1e-6,
            "{:?}",
            m.params
        );
        assert!(m.cost < 1e-12);
        assert!(result.gradient_evaluations > 1 && m.evaluations > result.gradient_evaluations);
    }

    #[test]
    fn failure_keeps_the_best_point_and_a_failing_start_is_an_error() {
        // Fails beyond x = 0.5 on the way to the minimum at 1: stops below 0.5, lower than start.
        let objective = |x: &[f64]| -> Result<(f64, Vec<f64>)> {
            if x[0] > 0.5 {
                return Err(Error::objective("no curve"));
            }
            Ok(((x[0] - 1.0).powi(2), vec![2.0 * (x[0] - 1.0)]))
        };
        let result = minimize_lbfgs(&objective, &[-3.0], LbfgsSettings::default()).unwrap();
        assert!(result.minimum.cost <= 16.0 && result.minimum.params[0] <= 0.5);
        let failing = |_: &[f64]| -> Result<(f64, Vec<f64>)> { Err(Error::objective("no")) };
        assert!(matches!(
            minimize_lbfgs(&failing, &[0.0], LbfgsSettings::default()),
            Err(Error::StartFailed { .. })
        ));
    }
}
