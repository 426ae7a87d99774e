//! NURBS interpolation: building (knots, matrix, sparse LU, solve) for 10², 10³, 10⁴ points,
//! and re-solving for new weights with the stored factors (the inner step of the weight
//! optimisation of Nowacki et al.).

use criterion::{criterion_group, BenchmarkId, Criterion};
use curve_repr::{Interpolation, InterpolationSettings, Parametrization, Vec2};
use std::hint::black_box;

/// Under `cargo test` (no `--bench` flag) only the smallest size runs: the bench code is
/// checked there, not timed, and the suite stays fast.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

fn points(n: usize) -> Vec<Vec2> {
    (0..n)
        .map(|i| {
            let t = i as f64 / n as f64 * 20.0;
            Vec2::new(t + 0.2 * (3.1 * t).sin(), t.sin() + 0.01 * (17.0 * t).cos())
        })
        .collect()
}

fn interpolation(c: &mut Criterion) {
    let mut group = c.benchmark_group("nurbs_interpolation");
    for n in sizes(&[100, 1_000, 10_000]) {
        let data = points(n);
        group.bench_with_input(BenchmarkId::new("build_and_solve", n), &data, |b, data| {
            b.iter(|| {
                let problem = Interpolation::with_parametrization(
                    black_box(data),
                    Parametrization::ChordLength,
                    InterpolationSettings::default(),
                )
                .unwrap();
                problem.nubs().unwrap()
            })
        });
    }
    let data = points(100);
    let settings =
        InterpolationSettings::default().with_end_tangents(Vec2::new(1.0, 1.0), Vec2::new(1.0, 0.0));
    let problem = Interpolation::with_parametrization(&data, Parametrization::ChordLength, settings).unwrap();
    let weights: Vec<f64> = (0..problem.control_count())
        .map(|i| 1.0 + 0.3 * (i as f64 * 0.1).sin())
        .collect();
    group.bench_function("weighted_resolve/100", |b| {
        b.iter(|| problem.solve(black_box(&weights)).unwrap())
    });
    group.finish();
}

criterion_group!(benches, interpolation);
