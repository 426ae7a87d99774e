//! The [`Pipeline`]: runs fairing strategies the way argmin's `Executor` runs a solver.
//!
//! The pipeline owns the loop: it validates the input and the constraints, asks every stage
//! whether it supports the constraints before anything runs, calls `init` and then `step`
//! until a termination rule fires, records every move in a [`Trace`], calls the observers,
//! times the run, and finally checks the result against the constraints (so a buggy strategy
//! cannot silently break a promise). Stages run one after another on the same points
//! ([`Pipeline::then`]), e.g. a smoothing spline, then Han's two-phase fairing.

use std::time::{Duration, Instant};

use curve_repr::Vector;
use serde::{Deserialize, Serialize};

use crate::{Constraints, Error, FairingState, FairingStrategy, Observer, Result, StepRecord, Trace};

/// Why a stage (and, for the last stage, the run) stopped. Not an error.
///
/// Serialised (and named by [`name`](Self::name)) in kebab-case, the one spelling every
/// report uses: `max-iterations`, `converged`, `strategy-done`, `indicator-satisfied`,
/// `refused`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TerminationReason {
    /// The stage made its maximum number of steps.
    MaxIterations,
    /// The criterion changed by at most `tolerance` × its previous magnitude in one step.
    Converged,
    /// The strategy declared itself done (no case of its rules applies).
    StrategyDone,
    /// The user's predicate (e.g. "no inflection left") holds; later stages are skipped.
    IndicatorSatisfied,
    /// The strategy's own rules refused every step it tried (a surface fairing whose every
    /// step would have raised its energy or its largest z_ij): nothing it proposed was kept.
    Refused,
}

impl TerminationReason {
    /// The kebab-case name reports use (the same as its serialisation).
    pub fn name(self) -> &'static str {
        match self {
            TerminationReason::MaxIterations => "max-iterations",
            TerminationReason::Converged => "converged",
            TerminationReason::StrategyDone => "strategy-done",
            TerminationReason::IndicatorSatisfied => "indicator-satisfied",
            TerminationReason::Refused => "refused",
        }
    }
}

impl std::fmt::Display for TerminationReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// How one stage ended.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StageReport {
    /// The strategy's name.
    pub name: String,
    /// Steps the stage made.
    pub iterations: usize,
    /// Why it stopped.
    pub termination: TerminationReason,
}

/// What a run returns.
#[derive(Clone, Debug)]
pub struct FairingResult<const D: usize> {
    /// The faired points, same count and order as the input.
    pub points: Vec<Vector<D>>,
    /// The input points.
    pub original: Vec<Vector<D>>,
    /// Steps made, over all stages.
    pub iterations: usize,
    /// Indices of the points whose final position differs from the original, increasing.
    pub moved: Vec<usize>,
    /// Why the last stage that ran stopped.
    pub termination: TerminationReason,
    /// One report per stage that ran.
    pub stages: Vec<StageReport>,
    /// Every step and move (empty if the trace was switched off).
    pub trace: Trace<D>,
    /// Wall-clock time of the fairing itself (init and steps, no I/O).
    pub elapsed: Duration,
}

type Predicate<'a, const D: usize> = Box<dyn FnMut(&FairingState<D>) -> bool + 'a>;

/// Runs one or more [`FairingStrategy`] stages on a set of points.
///
/// ```
/// use fairing::{Pipeline, FairingStrategy, FairingState, StepOutcome, TerminationReason, Result};
/// use curve_repr::Vec2;
/// struct Nothing;
/// impl FairingStrategy<2> for Nothing {
///     fn name(&self) -> &str { "nothing" }
///     fn step(&mut self, _: &mut FairingState<2>) -> Result<StepOutcome> { Ok(StepOutcome::done(None)) }
/// }
/// let result = Pipeline::new(Nothing).run(vec![Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)]).unwrap();
/// assert_eq!(result.termination, TerminationReason::StrategyDone);
/// ```
pub struct Pipeline<'a, const D: usize> {
    stages: Vec<Box<dyn FairingStrategy<D> + 'a>>,
    observers: Vec<Box<dyn Observer<D> + 'a>>,
    satisfied: Option<Predicate<'a, D>>,
    constraints: Constraints,
    max_iterations: usize,
    tolerance: Option<f64>,
    record_trace: bool,
    closed: bool,
}

impl<'a, const D: usize> Pipeline<'a, D> {
    /// The default step limit per stage.
    pub const DEFAULT_MAX_ITERATIONS: usize = 10_000;

    /// A pipeline of one stage, no constraint, [`DEFAULT_MAX_ITERATIONS`](Self::DEFAULT_MAX_ITERATIONS)
    /// steps per stage, no tolerance test, the trace on, an open curve.
    pub fn new(strategy: impl FairingStrategy<D> + 'a) -> Self {
        Self {
            stages: vec![Box::new(strategy)],
            observers: Vec::new(),
            satisfied: None,
            constraints: Constraints::default(),
            max_iterations: Self::DEFAULT_MAX_ITERATIONS,
            tolerance: None,
            record_trace: true,
            closed: false,
        }
    }

    /// Adds a stage that runs after the ones before it, on their result.
    pub fn then(mut self, strategy: impl FairingStrategy<D> + 'a) -> Self {
        self.stages.push(Box::new(strategy));
        self
    }

    /// Sets the constraints every stage honours.
    pub fn with_constraints(mut self, constraints: Constraints) -> Self {
        self.constraints = constraints;
        self
    }

    /// Sets the step limit of each stage.
    pub fn with_max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Stops a stage when its criterion changes by at most `tolerance` × |previous value| in
    /// one step (relative change; equal values count as converged, also at 0). Only strategies
    /// that report a criterion are affected.
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = Some(tolerance);
        self
    }

    /// Adds an observer, called after every step.
    pub fn with_observer(mut self, observer: impl Observer<D> + 'a) -> Self {
        self.observers.push(Box::new(observer));
        self
    }

    /// Stops the whole run as soon as `predicate` holds for the state (checked after each
    /// stage's `init` and after every step; its cost adds to every step).
    pub fn with_satisfied(mut self, predicate: impl FnMut(&FairingState<D>) -> bool + 'a) -> Self {
        self.satisfied = Some(Box::new(predicate));
        self
    }

    /// Switches the trace of moves on (default) or off (saves memory on long runs).
    pub fn with_trace(mut self, record: bool) -> Self {
        self.record_trace = record;
        self
    }

    /// Marks the points as a closed curve (see [`FairingState::is_closed`]).
    pub fn with_closed(mut self, closed: bool) -> Self {
        self.closed = closed;
        self
    }

    /// Runs every stage on `points`.
    ///
    /// Errors: no stage; non-finite points; constraints that do not fit the points or that a
    /// stage does not support (before anything runs); a strategy's own error; a NaN
    /// criterion; a final result that breaks a constraint ([`Error::ConstraintViolated`]);
    /// a cancellation ([`Error::Cancelled`], checked before every step, see [`optim::cancel`]).
    pub fn run(&mut self, points: Vec<Vector<D>>) -> Result<FairingResult<D>> {
        if self.stages.is_empty() {
            return Err(Error::NoStages);
        }
        if let Some(t) = self.tolerance {
            if t.is_nan() || t < 0.0 {
                return Err(Error::BadParameter {
                    name: "tolerance",
                    value: t.to_string(),
                    reason: "must be a non-negative number",
                });
            }
        }
        let mut state = FairingState::new(points, self.constraints.clone(), self.closed)?;
        for stage in &self.stages {
            stage.supports(&self.constraints)?;
        }
        let start = Instant::now();
        let mut trace = Trace::default();
        let mut reports = Vec::with_capacity(self.stages.len());
        let mut total = 0;
        let mut termination = TerminationReason::MaxIterations;
        'stages: for (index, strategy) in self.stages.iter_mut().enumerate() {
            state.stage = index;
            state.iteration = 0;
            state.criterion = None;
            optim::cancel::checkpoint()?;
            strategy.init(&mut state)?;
            let init_moves = state.take_moves();
            if !init_moves.is_empty() && self.record_trace {
                trace.steps.push(StepRecord {
                    stage: index,
                    iteration: 0,
                    moves: init_moves,
                    criterion: state.criterion,
                    done: false,
                });
            }
            let name = strategy.name().to_owned();
            let report = |termination, iterations| StageReport {
                name: name.clone(),
                iterations,
                termination,
            };
            if self.satisfied.as_mut().is_some_and(|p| p(&state)) {
                termination = TerminationReason::IndicatorSatisfied;
                reports.push(report(termination, 0));
                break 'stages;
            }
            let mut previous = state.criterion;
            termination = loop {
                if state.iteration >= self.max_iterations {
                    break TerminationReason::MaxIterations;
                }
                optim::cancel::checkpoint()?;
                let outcome = strategy.step(&mut state)?;
                state.iteration += 1;
                total += 1;
                if let Some(c) = outcome.criterion {
                    if !c.is_finite() {
                        return Err(Error::Strategy {
                            strategy: strategy.name().to_owned(),
                            reason: format!("criterion {c} after step {}", state.iteration),
                        });
                    }
                }
                state.criterion = outcome.criterion;
                let record = StepRecord {
                    stage: index,
                    iteration: state.iteration,
                    moves: state.take_moves(),
                    criterion: outcome.criterion,
                    done: outcome.done,
                };
                for observer in &mut self.observers {
                    observer.observe(&state, &record);
                }
                if self.record_trace {
                    trace.steps.push(record);
                } else {
                    state.recycle_moves(record.moves);
                }
                if self.satisfied.as_mut().is_some_and(|p| p(&state)) {
                    reports.push(report(TerminationReason::IndicatorSatisfied, state.iteration));
                    termination = TerminationReason::IndicatorSatisfied;
                    break 'stages;
                }
                if outcome.done {
                    break TerminationReason::StrategyDone;
                }
                if let (Some(tol), Some(p), Some(c)) = (self.tolerance, previous, outcome.criterion) {
                    if c == p || (c - p).abs() <= tol * p.abs() {
                        break TerminationReason::Converged;
                    }
                }
                previous = outcome.criterion;
            };
            reports.push(report(termination, state.iteration));
        }
        let elapsed = start.elapsed();
        state.check()?;
        let (points, original) = state.into_points();
        let moved = (0..points.len())
            .filter(|&i| points.get(i) != original.get(i))
            .collect();
        Ok(FairingResult {
            points,
            original,
            iterations: total,
            moved,
            termination,
            stages: reports,
            trace,
            elapsed,
        })
    }
}
