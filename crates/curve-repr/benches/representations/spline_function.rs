//! Build and windowed-update costs of the cubic spline function, at n = 10^3 … 10^6.
//!
//! Throughput is set to the number of points for the build (so criterion reports time per
//! point, which should be flat in n) and to one element for the update (whose time should be
//! flat in n too: O(window), not O(n)).

use std::hint::black_box;

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use curve_repr::{EndCondition, SplineFunction};

/// Under `cargo test` (no `--bench` flag) only the smallest size runs: the bench code is
/// checked there, not timed, and the suite stays fast.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

fn data(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = Vec::with_capacity(n);
    let mut t = 0.0;
    for i in 0..n {
        t += 0.5 + ((i as f64) * 0.37).sin().abs();
        x.push(t);
    }
    let y = x
        .iter()
        .map(|t| (0.01 * t).sin() + 0.001 * (7.0 * t).cos())
        .collect();
    (x, y)
}

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("spline_function/build");
    for n in sizes(&[1_000, 10_000, 100_000, 1_000_000]) {
        let (x, y) = data(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| SplineFunction::new(black_box(&x), black_box(&y), EndCondition::ParabolicRunout))
        });
    }
    group.finish();
}

fn update(c: &mut Criterion) {
    let mut group = c.benchmark_group("spline_function/update_one_point");
    for n in sizes(&[1_000, 10_000, 100_000, 1_000_000]) {
        let (x, y) = data(n);
        let Ok(mut spline) = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout) else {
            return;
        };
        let j = n / 2;
        let mut step = 0u64;
        group.throughput(Throughput::Elements(1));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| {
                step += 1;
                let value = y[j] + if step.is_multiple_of(2) { 1e-3 } else { -1e-3 };
                spline.set_y(black_box(&[(j, value)]))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, build, update);
