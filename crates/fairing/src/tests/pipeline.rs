use curve_repr::Vec2;

use crate::{
    Constraints, EndClamp, Error, FairingState, FairingStrategy, Pipeline, Result, StepOutcome, StepRecord,
    TerminationReason, Trace,
};

/// Toy strategy: one Jacobi step of Laplacian smoothing, P_i += λ ((P_{i−1} + P_{i+1})/2 − P_i)
/// for interior points; criterion Σ |P_{i−1} − 2P_i + P_{i+1}|².
struct Laplacian {
    lambda: f64,
}

fn second_difference_energy(points: &[Vec2]) -> f64 {
    points
        .windows(3)
        .map(|w| (w[0] - 2.0 * w[1] + w[2]).norm_squared())
        .sum()
}

impl FairingStrategy<2> for Laplacian {
    fn name(&self) -> &str {
        "laplacian"
    }
    fn init(&mut self, state: &mut FairingState<2>) -> Result<()> {
        state.criterion = Some(second_difference_energy(state.points()));
        Ok(())
    }
    fn step(&mut self, state: &mut FairingState<2>) -> Result<StepOutcome> {
        let p = state.points().to_vec();
        for i in 1..p.len() - 1 {
            let target = p[i] + self.lambda * ((p[i - 1] + p[i + 1]) * 0.5 - p[i]);
            state.move_point(i, target)?;
        }
        Ok(StepOutcome::running(Some(second_difference_energy(
            state.points(),
        ))))
    }
}

/// Done after `steps` steps, moving point 1 up by 1 each time.
struct Counted {
    steps: usize,
    taken: usize,
}

impl FairingStrategy<2> for Counted {
    fn name(&self) -> &str {
        "counted"
    }
    fn step(&mut self, state: &mut FairingState<2>) -> Result<StepOutcome> {
        self.taken += 1;
        let p = state.points()[1];
        state.move_point(1, p + Vec2::new(0.0, 1.0))?;
        Ok(if self.taken >= self.steps {
            StepOutcome::done(None)
        } else {
            StepOutcome::running(None)
        })
    }
}

fn noisy(n: usize) -> Vec<Vec2> {
    (0..n)
        .map(|i| {
            Vec2::new(
                i as f64,
                if i % 2 == 0 { 0.5 } else { -0.5 } + (i as f64 * 0.37).sin(),
            )
        })
        .collect()
}

/// Replays a trace from the original points.
fn replay(original: &[Vec2], trace: &Trace<2>) -> Vec<Vec2> {
    let mut points = original.to_vec();
    for m in trace.moves() {
        assert_eq!(points[m.index], m.from, "trace out of order at point {}", m.index);
        points[m.index] = m.to;
    }
    points
}

#[test]
fn stops_at_max_iterations_and_observers_see_every_step() {
    let mut seen: Vec<(usize, usize, f64)> = Vec::new();
    let result = {
        let mut pipeline = Pipeline::new(Laplacian { lambda: 0.5 })
            .with_max_iterations(7)
            .with_observer(|state: &FairingState<2>, step: &StepRecord<2>| {
                assert_eq!(state.iteration, step.iteration);
                seen.push((
                    step.iteration,
                    step.moves.len(),
                    step.criterion.unwrap_or(f64::NAN),
                ));
            });
        pipeline.run(noisy(20)).unwrap()
    };
    assert_eq!(result.termination, TerminationReason::MaxIterations);
    assert_eq!(result.iterations, 7);
    assert_eq!(
        seen.iter().map(|s| s.0).collect::<Vec<_>>(),
        (1..=7).collect::<Vec<_>>()
    );
    assert_eq!(result.trace.steps.len(), 7);
    for (record, s) in result.trace.steps.iter().zip(&seen) {
        assert_eq!(record.moves.len(), s.1);
    }
    // Smoothing lowers the energy at every step.
    assert!(seen.windows(2).all(|w| w[1].2 < w[0].2));
    // The trace holds every move: replaying it reproduces the result exactly.
    assert_eq!(replay(&result.original, &result.trace), result.points);
    assert_eq!(result.moved, (1..19).collect::<Vec<_>>());
}

#[test]
fn stops_when_the_criterion_converges() {
    let tol = 1e-3;
    let result = Pipeline::new(Laplacian { lambda: 0.5 })
        .with_tolerance(tol)
        .run(noisy(12))
        .unwrap();
    assert_eq!(result.termination, TerminationReason::Converged);
    assert!(result.iterations < Pipeline::<2>::DEFAULT_MAX_ITERATIONS);
    let mut criteria: Vec<f64> = vec![second_difference_energy(&result.original)];
    criteria.extend(result.trace.steps.iter().map(|s| s.criterion.unwrap()));
    let converged = |w: &[f64]| (w[1] - w[0]).abs() <= tol * w[0].abs();
    // The first step whose relative change is within tol is the last one.
    assert!(converged(&criteria[criteria.len() - 2..]));
    assert!(criteria[..criteria.len() - 1].windows(2).all(|w| !converged(w)));
}

#[test]
fn stops_when_the_strategy_is_done() {
    let result = Pipeline::new(Counted { steps: 3, taken: 0 })
        .with_max_iterations(10)
        .run(noisy(4))
        .unwrap();
    assert_eq!(result.termination, TerminationReason::StrategyDone);
    assert_eq!(result.iterations, 3);
    assert_eq!(result.points[1], result.original[1] + Vec2::new(0.0, 3.0));
    assert_eq!(result.moved, vec![1]);
}

#[test]
fn stops_when_the_indicator_is_satisfied() {
    let points = noisy(20);
    let threshold = 0.1 * second_difference_energy(&points);
    let result = Pipeline::new(Laplacian { lambda: 0.5 })
        .then(Counted { steps: 1, taken: 0 })
        .with_satisfied(|s: &FairingState<2>| second_difference_energy(s.points()) < threshold)
        .run(points.clone())
        .unwrap();
    assert_eq!(result.termination, TerminationReason::IndicatorSatisfied);
    assert_eq!(result.stages.len(), 1, "later stages are skipped");
    let energies: Vec<f64> = result.trace.steps.iter().map(|s| s.criterion.unwrap()).collect();
    assert!(*energies.last().unwrap() < threshold);
    assert!(energies[..energies.len() - 1].iter().all(|&e| e >= threshold));

    // Satisfied before any step: nothing runs.
    let result = Pipeline::new(Laplacian { lambda: 0.5 })
        .with_satisfied(|_: &FairingState<2>| true)
        .run(points.clone())
        .unwrap();
    assert_eq!(
        (result.iterations, result.termination),
        (0, TerminationReason::IndicatorSatisfied)
    );
    assert_eq!(result.points, points);
}

#[test]
fn stages_run_one_after_another_on_the_same_points() {
    let points = noisy(10);
    let result = Pipeline::new(Laplacian { lambda: 0.5 })
        .with_max_iterations(4)
        .then(Counted { steps: 2, taken: 0 })
        .run(points.clone())
        .unwrap();
    assert_eq!(result.stages.len(), 2);
    assert_eq!(result.stages[0].name, "laplacian");
    assert_eq!(result.stages[0].termination, TerminationReason::MaxIterations);
    assert_eq!(
        (result.stages[1].iterations, result.stages[1].termination),
        (2, TerminationReason::StrategyDone)
    );
    assert_eq!(result.termination, TerminationReason::StrategyDone);
    assert_eq!(result.iterations, 6);
    assert_eq!(result.original, points);
    assert!(result.trace.steps[4..].iter().all(|s| s.stage == 1));
    assert_eq!(replay(&points, &result.trace), result.points);
}

#[test]
fn constraints_hold_through_the_run() {
    let points = noisy(15);
    let constraints = Constraints::default()
        .with_fixed([5])
        .with_tolerance(0.2)
        .with_end_clamp(EndClamp::G0);
    let result = Pipeline::new(Laplacian { lambda: 0.9 })
        .with_constraints(constraints.clone())
        .with_max_iterations(50)
        .run(points.clone())
        .unwrap();
    assert!(constraints.check(&points, &result.points).is_ok());
    assert_eq!(result.points[5], points[5]);
    assert_eq!(result.points[0], points[0]);
    assert_eq!(result.points[14], points[14]);
    // The band is active: some point sits on it.
    let max = result
        .points
        .iter()
        .zip(&points)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(max > 0.19 && max <= 0.2, "max displacement {max}");
    assert!(!result.moved.contains(&5) && !result.moved.contains(&0));
}

#[test]
fn unsupported_constraints_fail_before_anything_runs() {
    let mut steps = 0;
    let err = Pipeline::new(Laplacian { lambda: 0.5 })
        .with_constraints(Constraints::default().with_end_clamp(EndClamp::G1))
        .with_observer(|_: &FairingState<2>, _: &StepRecord<2>| steps += 1)
        .run(noisy(6))
        .unwrap_err();
    assert!(matches!(err, Error::ConstraintUnsupported { ref strategy, .. } if strategy == "laplacian"));
    assert_eq!(steps, 0);
}

#[test]
fn bad_input_is_an_error() {
    let mut pipeline = Pipeline::new(Laplacian { lambda: 0.5 });
    let mut points = noisy(6);
    points[3].x = f64::NAN;
    assert!(matches!(
        pipeline.run(points),
        Err(Error::Repr(curve_repr::Error::NonFinite { index: 3, .. }))
    ));
    let err = Pipeline::new(Laplacian { lambda: 0.5 })
        .with_constraints(Constraints::default().with_fixed([6]))
        .run(noisy(6))
        .unwrap_err();
    assert!(matches!(err, Error::BadConstraint { .. }));
    let err = Pipeline::new(Laplacian { lambda: 0.5 })
        .with_constraints(Constraints::default().with_end_clamp(EndClamp::G0))
        .with_closed(true)
        .run(noisy(6))
        .unwrap_err();
    assert!(matches!(err, Error::BadConstraint { .. }));
    // A strategy that proposes NaN.
    struct Broken;
    impl FairingStrategy<2> for Broken {
        fn name(&self) -> &str {
            "broken"
        }
        fn step(&mut self, state: &mut FairingState<2>) -> Result<StepOutcome> {
            state.move_point(1, Vec2::new(f64::NAN, 0.0))?;
            Ok(StepOutcome::done(None))
        }
    }
    assert_eq!(
        Pipeline::new(Broken).run(noisy(3)).unwrap_err(),
        Error::NonFiniteMove { index: 1 }
    );
    struct NanCriterion;
    impl FairingStrategy<2> for NanCriterion {
        fn name(&self) -> &str {
            "nan"
        }
        fn step(&mut self, _: &mut FairingState<2>) -> Result<StepOutcome> {
            Ok(StepOutcome::running(Some(f64::NAN)))
        }
    }
    assert!(matches!(
        Pipeline::new(NanCriterion).run(noisy(3)),
        Err(Error::Strategy { .. })
    ));
    assert!(matches!(
        Pipeline::new(NanCriterion).with_tolerance(-1.0).run(noisy(3)),
        Err(Error::BadParameter {
            name: "tolerance",
            ..
        })
    ));
}

#[test]
fn trace_serialises() {
    let result = Pipeline::new(Counted { steps: 2, taken: 0 })
        .run(noisy(3))
        .unwrap();
    let json = serde_json::to_string(&result.trace).unwrap();
    let back: Trace<2> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, result.trace);
    assert_eq!(back.move_count(), 2);
}

#[test]
fn a_cancelled_run_stops_between_steps_with_its_typed_error() {
    // Cancelled from inside the run (as the server's watchdog would from its thread) after
    // five steps: the sixth is never taken and the run is an error, not a result.
    let token = optim::Cancel::new();
    let steps = std::cell::Cell::new(0usize);
    let result = token.scope(|| {
        Pipeline::new(Laplacian { lambda: 0.5 })
            .with_max_iterations(1000)
            .with_observer(|state: &FairingState<2>, _: &StepRecord<2>| {
                steps.set(state.iteration);
                if state.iteration == 5 {
                    token.cancel();
                }
            })
            .run(noisy(20))
    });
    assert!(matches!(result, Err(Error::Cancelled)), "{result:?}");
    assert_eq!(steps.get(), 5);
    // Outside the scope the same run goes to its end.
    let result = Pipeline::new(Laplacian { lambda: 0.5 })
        .with_max_iterations(10)
        .run(noisy(20))
        .unwrap();
    assert_eq!(result.iterations, 10);
}
