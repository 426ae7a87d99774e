//! Nelder–Mead on the Rosenbrock function in 4 and 20 dimensions.

use criterion::{criterion_group, BenchmarkId, Criterion};
use optim::{minimize, NelderMeadSettings};
use std::hint::black_box;

/// Σ_i 100 (x_{i+1} − x_i²)² + (1 − x_i)²; minimum 0 at (1, ..., 1).
fn rosenbrock(x: &[f64]) -> f64 {
    x.windows(2)
        .map(|w| 100.0 * (w[1] - w[0] * w[0]).powi(2) + (1.0 - w[0]).powi(2))
        .sum()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("nelder_mead_rosenbrock");
    for (dimension, max_iterations) in [(4usize, 5_000u64), (20, 20_000)] {
        let start: Vec<f64> = (0..dimension)
            .map(|i| if i % 2 == 0 { -1.2 } else { 1.0 })
            .collect();
        let objective = |p: &[f64]| Ok(rosenbrock(p));
        // Report once what the timed runs do.
        if let Ok(m) = minimize(
            &objective,
            &start,
            NelderMeadSettings::default()
                .with_max_iterations(max_iterations)
                .with_sd_tolerance(1e-12),
        ) {
            eprintln!(
                "n = {dimension}: cost {:.3e}, {} iterations, {} evaluations, {:?}",
                m.cost, m.iterations, m.evaluations, m.termination
            );
        }
        group.bench_with_input(BenchmarkId::from_parameter(dimension), &start, |b, start| {
            b.iter(|| {
                minimize(
                    &objective,
                    black_box(start),
                    NelderMeadSettings::default()
                        .with_max_iterations(max_iterations)
                        .with_sd_tolerance(1e-12),
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
