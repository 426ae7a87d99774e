//! Zhang–Cheng automatic fairing in release:
//! - `strain_energy_10_steps/n`: ten automatic steps after `init` (the setup, not timed). The
//!   time should not grow with n: a step updates the spline, the indicator, the energy and
//!   the heap only inside a window of knots (O(window · log n) for the heap).
//! - `strain_energy_full_run/n`: a whole automatic run (init + steps until the energy
//!   tolerance stops it) through the [`Pipeline`], the "10^5 points under 2 s".

use criterion::{criterion_group, BatchSize, BenchmarkId, Criterion};
use curve_repr::Vec2;
use fairing::strategies::{StrainEnergy, StrainEnergySettings};
use fairing::{Constraints, FairingState, FairingStrategy, Pipeline};

/// Under `cargo test` (no `--bench` flag) only the smallest size runs: the bench code is
/// checked there, not timed, and the suite stays fast.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

/// n points on a circle of radius 100 with pseudo-random radial noise of up to 0.02.
fn noisy_arc(n: usize) -> Vec<Vec2> {
    (0..n)
        .map(|i| {
            let a = i as f64 * 0.01;
            let e = 0.02 * ((i as f64) * 12.9898).sin().fract();
            Vec2::new((100.0 + e) * a.cos(), (100.0 + e) * a.sin())
        })
        .collect()
}

fn steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("strain_energy_10_steps");
    group.sample_size(10);
    for n in sizes(&[1_000usize, 10_000, 100_000, 1_000_000]) {
        let points = noisy_arc(n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &points, |b, points| {
            b.iter_batched(
                || {
                    let mut state = FairingState::new(points.clone(), Constraints::default(), false).unwrap();
                    let mut s = StrainEnergy::new(StrainEnergySettings::poliakoff());
                    s.init(&mut state).unwrap();
                    (state, s)
                },
                |(mut state, mut s)| {
                    for _ in 0..10 {
                        s.step(&mut state).unwrap();
                    }
                    (state, s)
                },
                BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

fn full_run(c: &mut Criterion) {
    let mut group = c.benchmark_group("strain_energy_full_run");
    group.sample_size(10);
    for n in sizes(&[1_000usize, 10_000, 100_000, 1_000_000]) {
        let points = noisy_arc(n);
        // Steps taken, printed once for the report (not timed).
        let once = Pipeline::new(StrainEnergy::<2>::new(StrainEnergySettings::poliakoff()))
            .with_trace(false)
            .with_max_iterations(usize::MAX)
            .run(points.clone())
            .unwrap();
        eprintln!(
            "n = {n}: {} steps, {} points moved, {:?}",
            once.iterations,
            once.moved.len(),
            once.termination
        );
        group.bench_with_input(BenchmarkId::from_parameter(n), &points, |b, points| {
            b.iter_batched(
                || points.clone(),
                |points| {
                    Pipeline::new(StrainEnergy::<2>::new(StrainEnergySettings::poliakoff()))
                        .with_trace(false)
                        .with_max_iterations(usize::MAX)
                        .run(points)
                        .unwrap()
                },
                BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

criterion_group!(benches, steps, full_run);
