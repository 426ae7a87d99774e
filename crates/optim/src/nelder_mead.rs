//! Nelder–Mead downhill simplex minimisation: a small adapter over argmin's
//! `NelderMead`.
//!
//! Nowacki et al. (1996, §3) find the NURBS weight-law parameters k0..k3 with "the well known
//! simplex method of downhill search by Nelder and Mead": an unconstrained, derivative-free
//! minimiser. This module exposes it with plain `Vec<f64>` parameter vectors, an objective that
//! may fail, a settings struct, an observer hook and a termination reason that is an enum, not
//! an error.
//!
//! # Failures inside the search
//!
//! An objective that returns an error, NaN or ±∞ at some trial point is treated as if it had
//! returned **+∞** there: that vertex ranks worst, so the simplex contracts away from it. Trial
//! points whose coordinates overflow to non-finite values are also given +∞ without calling the
//! objective. Only a failure at the start point is a hard error ([`Error::StartFailed`]),
//! because then there is no finite value to improve on. [`Minimum::failed_evaluations`] counts
//! the failures so that a caller can tell a clean run from one that brushed against them.
//!
//! # Cost
//!
//! Each iteration evaluates the objective once or twice (reflection, expansion or contraction),
//! or `n + 1` times on a shrink, plus O(n²) arithmetic on the simplex (argmin computes the
//! centroid afresh) and an O(n log n) sort.
//!
//! # Example
//!
//! ```
//! use optim::nelder_mead::{minimize, NelderMeadSettings, Termination};
//!
//! // (x − 1)² + 10 (y + 2)², minimum 0 at (1, −2).
//! let objective = |p: &[f64]| Ok((p[0] - 1.0).powi(2) + 10.0 * (p[1] + 2.0).powi(2));
//! let minimum = minimize(&objective, &[0.0, 0.0], NelderMeadSettings::default())?;
//! assert_eq!(minimum.termination, Termination::Converged);
//! assert!((minimum.params[0] - 1.0).abs() < 1e-4 && (minimum.params[1] + 2.0).abs() < 1e-4);
//! # Ok::<(), optim::Error>(())
//! ```

use std::cell::Cell;
use std::fmt;

use argmin::core::{CostFunction, IterState, Problem, Solver, State, TerminationReason, TerminationStatus};
use argmin::solver::neldermead::NelderMead;

use crate::error::{Error, Result};

/// A function to minimise over a parameter vector.
///
/// Implemented for every closure `Fn(&[f64]) -> Result<f64>`. Returning an error or a
/// non-finite value at a trial point is allowed (it counts as +∞, see the module docs).
pub trait Objective {
    /// The cost at `params`.
    fn cost(&self, params: &[f64]) -> Result<f64>;
}

impl<F> Objective for F
where
    F: Fn(&[f64]) -> Result<f64>,
{
    fn cost(&self, params: &[f64]) -> Result<f64> {
        self(params)
    }
}

/// What an [`Observer`] sees: the state after an iteration.
#[derive(Debug, Clone, Copy)]
pub struct Progress<'p> {
    /// Iterations completed so far: 0 right after the initial simplex was evaluated.
    pub iteration: u64,
    /// The lowest cost found so far (the best vertex).
    pub best_cost: f64,
    /// The parameters of the best vertex.
    pub best_params: &'p [f64],
    /// Objective evaluations so far, including the failed ones.
    pub evaluations: u64,
}

/// Called once after the initial simplex is evaluated and once after every iteration, e.g.
/// to drive a progress bar or a log. Implemented for every closure `FnMut(&Progress)`.
pub trait Observer {
    /// Receives the state after an iteration.
    fn observe(&mut self, progress: &Progress<'_>);
}

impl<F> Observer for F
where
    F: FnMut(&Progress<'_>),
{
    fn observe(&mut self, progress: &Progress<'_>) {
        self(progress)
    }
}

/// How the initial simplex of `n + 1` vertices is built around the start point `x0`.
///
/// The start point is always vertex 0; the variants give the other `n`.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum InitialSimplex {
    /// Vertex `i + 1` is `x0 + h e_i` with the same step `h` for every coordinate.
    Step(f64),
    /// Vertex `i + 1` is `x0 + h_i e_i` with one step per coordinate (length `n`).
    Steps(Vec<f64>),
    /// The `n` other vertices, each of length `n`, given explicitly.
    Vertices(Vec<Vec<f64>>),
}

/// Settings of [`minimize`]: `Default` plus chained `with_*` setters.
///
/// Defaults: a simplex of step 0.1 along each axis ([`InitialSimplex::Step`]), at most 1000
/// iterations, stop when the sample standard deviation of the vertices' costs falls below
/// 1e-10 (an absolute tolerance on the cost, as argmin defines it), no observer.
pub struct NelderMeadSettings<'a> {
    simplex: InitialSimplex,
    max_iterations: u64,
    sd_tolerance: f64,
    observer: Option<Box<dyn Observer + 'a>>,
}

impl Default for NelderMeadSettings<'_> {
    fn default() -> Self {
        NelderMeadSettings {
            simplex: InitialSimplex::Step(0.1),
            max_iterations: 1000,
            sd_tolerance: 1e-10,
            observer: None,
        }
    }
}

impl fmt::Debug for NelderMeadSettings<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("NelderMeadSettings")
            .field("simplex", &self.simplex)
            .field("max_iterations", &self.max_iterations)
            .field("sd_tolerance", &self.sd_tolerance)
            .field("observer", &self.observer.as_ref().map(|_| "<observer>"))
            .finish()
    }
}

impl<'a> NelderMeadSettings<'a> {
    /// The same step `h` (non-zero, finite) along every coordinate from the start point.
    #[must_use]
    pub fn with_step(mut self, step: f64) -> Self {
        self.simplex = InitialSimplex::Step(step);
        self
    }

    /// One step per coordinate (non-zero, finite; as many as parameters).
    #[must_use]
    pub fn with_steps(mut self, steps: Vec<f64>) -> Self {
        self.simplex = InitialSimplex::Steps(steps);
        self
    }

    /// The `n` vertices besides the start point, explicitly (they must span `n` dimensions).
    #[must_use]
    pub fn with_vertices(mut self, vertices: Vec<Vec<f64>>) -> Self {
        self.simplex = InitialSimplex::Vertices(vertices);
        self
    }

    /// Any [`InitialSimplex`].
    #[must_use]
    pub fn with_simplex(mut self, simplex: InitialSimplex) -> Self {
        self.simplex = simplex;
        self
    }

    /// The largest number of iterations; reaching it ends the search with
    /// [`Termination::MaxIterations`]. Zero returns the start point.
    #[must_use]
    pub fn with_max_iterations(mut self, max_iterations: u64) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Convergence: the sample standard deviation of the `n + 1` vertex costs below this
    /// (finite, ≥ 0) absolute value ends the search with [`Termination::Converged`].
    #[must_use]
    pub fn with_sd_tolerance(mut self, sd_tolerance: f64) -> Self {
        self.sd_tolerance = sd_tolerance;
        self
    }

    /// Calls `observer` after the initial simplex and after every iteration.
    #[must_use]
    pub fn with_observer(mut self, observer: impl Observer + 'a) -> Self {
        self.observer = Some(Box::new(observer));
        self
    }

    /// The initial simplex.
    pub fn simplex(&self) -> &InitialSimplex {
        &self.simplex
    }

    /// The iteration limit.
    pub fn max_iterations(&self) -> u64 {
        self.max_iterations
    }

    /// The standard-deviation tolerance on the vertex costs.
    pub fn sd_tolerance(&self) -> f64 {
        self.sd_tolerance
    }
}

/// Why the search stopped. None of these is an error: the best point found is returned.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub enum Termination {
    /// The vertex costs agree to within the standard-deviation tolerance.
    Converged,
    /// The iteration limit was reached first.
    MaxIterations,
    /// argmin stopped for another reason (its message).
    Other(String),
}

/// The result of [`minimize`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct Minimum {
    /// The best parameters found.
    pub params: Vec<f64>,
    /// The objective there (finite, never above the start point's cost).
    pub cost: f64,
    /// Iterations performed.
    pub iterations: u64,
    /// Why the search stopped.
    pub termination: Termination,
    /// Objective evaluations, including the start point and the failed ones.
    pub evaluations: u64,
    /// Evaluations that failed or were not finite (and so counted as +∞).
    pub failed_evaluations: u64,
}

/// Minimises `objective` by Nelder–Mead from `start`.
///
/// Errors: a non-finite start coordinate or simplex vertex, invalid settings, a degenerate
/// initial simplex, an objective that fails at the start point, or a cancellation
/// ([`Error::Cancelled`], checked once per iteration, see [`crate::cancel`]). With no parameters at all
/// the start (empty) point is returned as converged after one evaluation.
pub fn minimize<O>(objective: &O, start: &[f64], settings: NelderMeadSettings<'_>) -> Result<Minimum>
where
    O: Objective + ?Sized,
{
    let NelderMeadSettings {
        simplex,
        max_iterations,
        sd_tolerance,
        mut observer,
    } = settings;
    check_finite("start parameter", start)?;
    if !(sd_tolerance.is_finite() && sd_tolerance >= 0.0) {
        return Err(Error::InvalidSetting {
            name: "sd_tolerance",
            reason: format!("must be finite and non-negative, got {sd_tolerance}"),
        });
    }
    crate::cancel::checkpoint()?;
    let start_cost = match objective.cost(start) {
        Ok(cost) if cost.is_finite() => cost,
        Ok(cost) => {
            return Err(Error::StartFailed {
                reason: format!("the cost is {cost}"),
            })
        }
        Err(error) => {
            return Err(Error::StartFailed {
                reason: error.to_string(),
            })
        }
    };
    if start.is_empty() {
        if let Some(observer) = observer.as_mut() {
            observer.observe(&Progress {
                iteration: 0,
                best_cost: start_cost,
                best_params: start,
                evaluations: 1,
            });
        }
        return Ok(Minimum {
            params: Vec::new(),
            cost: start_cost,
            iterations: 0,
            termination: Termination::Converged,
            evaluations: 1,
            failed_evaluations: 0,
        });
    }
    let vertices = build_simplex(start, &simplex)?;

    let solver = NelderMead::new(vertices)
        .with_sd_tolerance(sd_tolerance)
        .map_err(Error::from_solver)?;
    let counts = Counts::default();
    let mut problem = Problem::new(CountedObjective {
        objective,
        counts: &counts,
    });
    let state = NmState::new().max_iters(max_iterations);
    let state = run(solver, &mut problem, state, &counts, observer.as_deref_mut())?;

    let termination = match state.get_termination_reason() {
        Some(TerminationReason::SolverConverged) => Termination::Converged,
        Some(TerminationReason::MaxItersReached) => Termination::MaxIterations,
        Some(other) => Termination::Other(other.text().to_string()),
        None => Termination::Other("not terminated".to_string()),
    };
    // The start point is a vertex with a finite cost, so argmin always holds a finite best;
    // the fallback keeps this panic-free regardless.
    let (params, cost) = match state.get_best_param() {
        Some(params) if state.get_best_cost() <= start_cost => (params.clone(), state.get_best_cost()),
        _ => (start.to_vec(), start_cost),
    };
    Ok(Minimum {
        params,
        cost,
        iterations: state.get_iter(),
        termination,
        evaluations: counts.evaluations(),
        failed_evaluations: counts.failures.get(),
    })
}

type NmState = IterState<Vec<f64>, (), (), (), (), f64>;

/// Evaluation counters shared between [`minimize`] and the objective argmin sees.
#[derive(Default)]
struct Counts {
    /// Evaluations made through argmin.
    through_solver: Cell<u64>,
    /// Of those, the failed or non-finite ones.
    failures: Cell<u64>,
}

impl Counts {
    /// All evaluations: argmin's plus the start point, evaluated by [`minimize`] first.
    fn evaluations(&self) -> u64 {
        self.through_solver.get() + 1
    }
}

/// The loop of argmin's `Executor::run` (init, then terminate-check / `next_iter` / update),
/// driven here so that the observer may borrow from the caller (argmin's observers must be
/// `'static`).
fn run<O: Objective + ?Sized>(
    mut solver: NelderMead<Vec<f64>, f64>,
    problem: &mut Problem<CountedObjective<'_, O>>,
    state: NmState,
    counts: &Counts,
    mut observer: Option<&mut (dyn Observer + '_)>,
) -> Result<NmState> {
    let mut notify = |state: &NmState| {
        if let (Some(observer), Some(best)) = (observer.as_mut(), state.get_best_param()) {
            observer.observe(&Progress {
                iteration: state.get_iter(),
                best_cost: state.get_best_cost(),
                best_params: best,
                evaluations: counts.evaluations(),
            });
        }
    };
    let (mut state, _) = solver.init(problem, state).map_err(Error::from_solver)?;
    state.update();
    notify(&state);
    loop {
        if !state.terminated() {
            if let TerminationStatus::Terminated(reason) =
                <NelderMead<Vec<f64>, f64> as Solver<CountedObjective<'_, O>, NmState>>::terminate_internal(
                    &mut solver,
                    &state,
                )
            {
                state = state.terminate_with(reason);
            }
        }
        if state.terminated() {
            return Ok(state);
        }
        crate::cancel::checkpoint()?;
        let (next, _) = solver.next_iter(problem, state).map_err(Error::from_solver)?;
        state = next;
        state.update();
        state.increment_iter();
        notify(&state);
    }
}

/// The objective as argmin sees it: never fails, counts evaluations and failures.
struct CountedObjective<'o, O: ?Sized> {
    objective: &'o O,
    counts: &'o Counts,
}

impl<O: Objective + ?Sized> CostFunction for CountedObjective<'_, O> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, params: &Vec<f64>) -> std::result::Result<f64, argmin::core::Error> {
        let counts = self.counts;
        counts.through_solver.set(counts.through_solver.get() + 1);
        // Cancelled: no more evaluations (a shrink evaluates n of them); the loop's next
        // checkpoint ends the search.
        let cost = if params.iter().all(|x| x.is_finite()) && !crate::cancel::cancelled() {
            match self.objective.cost(params) {
                Ok(cost) if cost.is_finite() => Some(cost),
                _ => None,
            }
        } else {
            None
        };
        Ok(cost.unwrap_or_else(|| {
            counts.failures.set(counts.failures.get() + 1);
            f64::INFINITY
        }))
    }
}

fn check_finite(what: &'static str, values: &[f64]) -> Result<()> {
    match values.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(Error::NonFinite { what, index }),
        None => Ok(()),
    }
}

/// The `n + 1` vertices: the start point first, then the others from `simplex`. Checks that
/// they are finite and span `n` dimensions. O(n³) for the rank check (n is small here).
fn build_simplex(start: &[f64], simplex: &InitialSimplex) -> Result<Vec<Vec<f64>>> {
    let n = start.len();
    let steps_vertices = |steps: &[f64]| -> Result<Vec<Vec<f64>>> {
        if let Some(index) = steps.iter().position(|h| !h.is_finite() || *h == 0.0) {
            return Err(Error::InvalidSetting {
                name: "simplex step",
                reason: format!("step {index} must be finite and non-zero"),
            });
        }
        Ok(steps
            .iter()
            .enumerate()
            .map(|(i, h)| {
                let mut vertex = start.to_vec();
                if let Some(x) = vertex.get_mut(i) {
                    *x += h;
                }
                vertex
            })
            .collect())
    };
    let others = match simplex {
        InitialSimplex::Step(h) => steps_vertices(&vec![*h; n])?,
        InitialSimplex::Steps(steps) => {
            if steps.len() != n {
                return Err(Error::LengthMismatch {
                    what: "simplex steps",
                    expected: n,
                    got: steps.len(),
                });
            }
            steps_vertices(steps)?
        }
        InitialSimplex::Vertices(vertices) => {
            if vertices.len() != n {
                return Err(Error::LengthMismatch {
                    what: "simplex vertices besides the start",
                    expected: n,
                    got: vertices.len(),
                });
            }
            for vertex in vertices {
                if vertex.len() != n {
                    return Err(Error::LengthMismatch {
                        what: "simplex vertex",
                        expected: n,
                        got: vertex.len(),
                    });
                }
                check_finite("simplex vertex coordinate", vertex)?;
            }
            vertices.clone()
        }
    };
    for vertex in &others {
        check_finite("simplex vertex coordinate", vertex)?;
    }
    let edges: Vec<Vec<f64>> = others
        .iter()
        .map(|v| v.iter().zip(start).map(|(a, b)| a - b).collect())
        .collect();
    if rank_deficient(edges) {
        return Err(Error::DegenerateSimplex { dimension: n });
    }
    let mut vertices = Vec::with_capacity(n + 1);
    vertices.push(start.to_vec());
    vertices.extend(others);
    Ok(vertices)
}

/// Whether the square matrix (rows = edge vectors) is singular, by Gaussian elimination with
/// partial pivoting, each row scaled to unit max-norm first; pivots below 1e-12 count as zero.
fn rank_deficient(mut rows: Vec<Vec<f64>>) -> bool {
    for row in rows.iter_mut() {
        let scale = row.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        if scale == 0.0 || !scale.is_finite() {
            return true;
        }
        row.iter_mut().for_each(|x| *x /= scale);
    }
    let n = rows.len();
    for column in 0..n {
        let pivot = (column..n).max_by(|&a, &b| {
            let value = |r: usize| {
                rows.get(r)
                    .and_then(|row| row.get(column))
                    .map_or(0.0, |x| x.abs())
            };
            value(a).total_cmp(&value(b))
        });
        let Some(pivot) = pivot else { return true };
        rows.swap(column, pivot);
        let Some(pivot_row) = rows.get(column).cloned() else {
            return true;
        };
        let pivot_value = pivot_row.get(column).copied().unwrap_or(0.0);
        if pivot_value.abs() < 1e-12 {
            return true;
        }
        for row in rows.iter_mut().skip(column + 1) {
            let factor = row.get(column).copied().unwrap_or(0.0) / pivot_value;
            for (x, p) in row.iter_mut().zip(&pivot_row).skip(column) {
                *x -= factor * p;
            }
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rosenbrock(x: &[f64]) -> f64 {
        x.windows(2)
            .map(|w| 100.0 * (w[1] - w[0] * w[0]).powi(2) + (1.0 - w[0]).powi(2))
            .sum()
    }

    /// A convex quadratic ½ (x − c)ᵀ A (x − c) with A symmetric positive definite (diagonally
    /// dominant): its minimiser is c, where the gradient A (x − c) vanishes.
    fn quadratic(x: &[f64]) -> f64 {
        let c = [1.0, -2.0, 0.5];
        let a = [[4.0, 1.0, 0.5], [1.0, 3.0, -1.0], [0.5, -1.0, 2.0]];
        let d: Vec<f64> = x.iter().zip(c).map(|(x, c)| x - c).collect();
        let mut sum = 0.0;
        for i in 0..3 {
            for j in 0..3 {
                sum += 0.5 * d[i] * a[i][j] * d[j];
            }
        }
        sum
    }

    #[test]
    fn finds_the_minimum_of_a_convex_quadratic() {
        let objective = |p: &[f64]| Ok(quadratic(p));
        let settings = NelderMeadSettings::default().with_sd_tolerance(1e-14);
        let m = minimize(&objective, &[0.0, 0.0, 0.0], settings).unwrap();
        assert_eq!(m.termination, Termination::Converged);
        // sd of costs < 1e-14 with eigenvalues of A ≥ ~0.9 bounds |x − c| ~ 1e-6.
        for (x, c) in m.params.iter().zip([1.0, -2.0, 0.5]) {
            assert!((x - c).abs() < 1e-5, "{x} vs {c}");
        }
        assert!(m.cost < 1e-10);
        assert!(m.evaluations > m.iterations);
    }

    #[test]
    fn finds_the_minimum_of_rosenbrock() {
        let objective = |p: &[f64]| Ok(rosenbrock(p));
        let settings = NelderMeadSettings::default()
            .with_sd_tolerance(1e-16)
            .with_max_iterations(10_000);
        let m = minimize(&objective, &[-1.2, 1.0], settings).unwrap();
        assert_eq!(m.termination, Termination::Converged);
        for x in &m.params {
            assert!((x - 1.0).abs() < 1e-4, "{:?}", m.params);
        }
    }

    #[test]
    fn iteration_limit_is_honoured_and_reported() {
        let objective = |p: &[f64]| Ok(rosenbrock(p));
        let settings = NelderMeadSettings::default().with_max_iterations(7);
        let m = minimize(&objective, &[-1.2, 1.0, -1.2, 1.0], settings).unwrap();
        assert_eq!(m.iterations, 7);
        assert_eq!(m.termination, Termination::MaxIterations);
        assert!(m.cost <= rosenbrock(&[-1.2, 1.0, -1.2, 1.0]));

        let zero = NelderMeadSettings::default().with_max_iterations(0);
        let m = minimize(&objective, &[-1.2, 1.0], zero).unwrap();
        assert_eq!(m.iterations, 0);
        assert_eq!(m.termination, Termination::MaxIterations);
        // No iteration, but the initial simplex was evaluated: its best vertex is returned.
        let vertices = [vec![-1.2, 1.0], vec![-1.2 + 0.1, 1.0], vec![-1.2, 1.0 + 0.1]];
        let best = vertices
            .iter()
            .min_by(|a, b| rosenbrock(a).total_cmp(&rosenbrock(b)))
            .unwrap();
        assert_eq!(m.params, *best);
    }

    #[test]
    fn observer_sees_every_iteration_and_a_non_increasing_best() {
        let objective = |p: &[f64]| Ok(rosenbrock(p));
        let mut seen: Vec<(u64, f64, Vec<f64>, u64)> = Vec::new();
        let settings = NelderMeadSettings::default()
            .with_max_iterations(25)
            .with_observer(|p: &Progress<'_>| {
                seen.push((p.iteration, p.best_cost, p.best_params.to_vec(), p.evaluations))
            });
        let m = minimize(&objective, &[-1.2, 1.0], settings).unwrap();
        assert_eq!(seen.len() as u64, m.iterations + 1);
        for (k, (iteration, cost, params, _)) in seen.iter().enumerate() {
            assert_eq!(*iteration, k as u64);
            assert_eq!(*cost, rosenbrock(params));
        }
        for pair in seen.windows(2) {
            assert!(pair[1].1 <= pair[0].1);
            assert!(pair[1].3 > pair[0].3);
        }
        let last = seen.last().unwrap();
        assert_eq!((last.1, &last.2, last.3), (m.cost, &m.params, m.evaluations));
    }

    #[test]
    fn failures_and_non_finite_costs_are_avoided() {
        // Minimum of (x − 2)² + y² is at (2, 0), but the objective fails for x > 1.5 and is
        // NaN for y < −0.5: the constrained minimum is (1.5, 0).
        let objective = |p: &[f64]| {
            if p[0] > 1.5 {
                Err(Error::objective("outside"))
            } else if p[1] < -0.5 {
                Ok(f64::NAN)
            } else {
                Ok((p[0] - 2.0).powi(2) + p[1].powi(2))
            }
        };
        let settings = NelderMeadSettings::default()
            .with_step(1.0)
            .with_sd_tolerance(1e-14);
        let m = minimize(&objective, &[0.0, 0.0], settings).unwrap();
        assert!(m.failed_evaluations > 0);
        assert!(m.cost.is_finite());
        assert!(
            m.params[0] <= 1.5 && (m.params[0] - 1.5).abs() < 1e-3,
            "{:?}",
            m.params
        );
        assert!(m.params[1].abs() < 1e-3, "{:?}", m.params);
    }

    #[test]
    fn objective_unbounded_below_never_hands_it_non_finite_parameters() {
        // Expansion doubles the step each time; coordinates eventually overflow.
        let objective = |p: &[f64]| {
            assert!(p.iter().all(|x| x.is_finite()));
            Ok(-p[0] - p[1])
        };
        let settings = NelderMeadSettings::default().with_max_iterations(3000);
        let m = minimize(&objective, &[0.0, 0.0], settings).unwrap();
        assert!(m.cost.is_finite() && m.params.iter().all(|x| x.is_finite()));
    }

    #[test]
    fn start_failures_and_bad_settings_are_errors() {
        let failing = |_: &[f64]| -> Result<f64> { Err(Error::objective("nope")) };
        assert!(matches!(
            minimize(&failing, &[0.0], NelderMeadSettings::default()),
            Err(Error::StartFailed { .. })
        ));
        let infinite = |_: &[f64]| Ok(f64::INFINITY);
        assert!(matches!(
            minimize(&infinite, &[0.0], NelderMeadSettings::default()),
            Err(Error::StartFailed { .. })
        ));
        let fine = |p: &[f64]| Ok(p.iter().map(|x| x * x).sum::<f64>());
        assert!(matches!(
            minimize(&fine, &[0.0, f64::NAN], NelderMeadSettings::default()),
            Err(Error::NonFinite { index: 1, .. })
        ));
        assert!(matches!(
            minimize(&fine, &[0.0], NelderMeadSettings::default().with_step(0.0)),
            Err(Error::InvalidSetting { .. })
        ));
        assert!(matches!(
            minimize(
                &fine,
                &[0.0],
                NelderMeadSettings::default().with_sd_tolerance(-1.0)
            ),
            Err(Error::InvalidSetting { .. })
        ));
        assert!(matches!(
            minimize(
                &fine,
                &[0.0, 0.0],
                NelderMeadSettings::default().with_steps(vec![1.0])
            ),
            Err(Error::LengthMismatch { .. })
        ));
        // Two vertices on one line through the start: the simplex is flat.
        let flat = vec![vec![1.0, 1.0], vec![2.0, 2.0]];
        assert!(matches!(
            minimize(
                &fine,
                &[0.0, 0.0],
                NelderMeadSettings::default().with_vertices(flat)
            ),
            Err(Error::DegenerateSimplex { dimension: 2 })
        ));
        // A step too small to change a large start coordinate also makes a flat simplex.
        assert!(matches!(
            minimize(&fine, &[1e20, 0.0], NelderMeadSettings::default().with_step(0.1)),
            Err(Error::DegenerateSimplex { .. })
        ));
    }

    #[test]
    fn explicit_vertices_and_per_coordinate_steps_work() {
        let objective = |p: &[f64]| Ok(quadratic(p));
        for settings in [
            NelderMeadSettings::default().with_steps(vec![0.5, -0.3, 2.0]),
            NelderMeadSettings::default().with_vertices(vec![
                vec![1.0, 0.0, 0.0],
                vec![0.0, 1.0, 1.0],
                vec![0.0, 0.0, 1.0],
            ]),
        ] {
            let m = minimize(&objective, &[0.0; 3], settings.with_sd_tolerance(1e-14)).unwrap();
            for (x, c) in m.params.iter().zip([1.0, -2.0, 0.5]) {
                assert!((x - c).abs() < 1e-5, "{x} vs {c}");
            }
        }
    }

    #[test]
    fn no_parameters_returns_the_start() {
        let objective = |_: &[f64]| Ok(3.0);
        let m = minimize(&objective, &[], NelderMeadSettings::default()).unwrap();
        assert_eq!((m.cost, m.iterations, m.evaluations), (3.0, 0, 1));
        assert!(m.params.is_empty());
    }
}
