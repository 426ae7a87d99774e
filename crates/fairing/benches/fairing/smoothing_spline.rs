//! Cost of the smoothing spline against n (10^4, 10^5, 10^6 points): it should grow linearly.
//! Given p (one banded solve), the trace rule (one solve), GCV (about 100 banded solves and
//! banded inverses) on a noisy function y(x), and a 3D parametric curve at the trace rule.

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use curve_repr::Vec3;
use fairing::strategies::{fit_parametric, SmoothingRule, SmoothingSettings, SmoothingSpline};

/// Under `cargo test` (no `--bench` flag) only the smallest size runs: the bench code is
/// checked there, not timed, and the suite stays fast.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

fn noise(k: usize) -> f64 {
    ((k as f64 * 12.9898).sin() * 43758.5453).rem_euclid(1.0) - 0.5
}

fn data(n: usize) -> (Vec<f64>, Vec<f64>) {
    let x: Vec<f64> = (0..n).map(|k| k as f64 * 1e-3 + 2e-4 * noise(3 * k)).collect();
    let y = x
        .iter()
        .enumerate()
        .map(|(k, x)| (3.0 * x).sin() + 0.05 * noise(k))
        .collect();
    (x, y)
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("smoothing_spline");
    group.sample_size(10);
    for n in sizes(&[10_000usize, 100_000, 1_000_000]) {
        let (x, y) = data(n);
        group.throughput(Throughput::Elements(n as u64));
        for (label, settings) in [
            ("given_p", SmoothingSettings::default().with_p(0.999)),
            (
                "trace",
                SmoothingSettings::default().with_rule(SmoothingRule::Trace),
            ),
            ("gcv", SmoothingSettings::default().with_rule(SmoothingRule::Gcv)),
        ] {
            group.bench_with_input(BenchmarkId::new(label, n), &(), |b, _| {
                b.iter(|| SmoothingSpline::fit_function(&x, &y, &settings).unwrap())
            });
        }
        let points: Vec<Vec3> = x
            .iter()
            .zip(&y)
            .map(|(x, y)| Vec3::new(*x, *y, 0.5 * x * x))
            .collect();
        let trace = SmoothingSettings::default().with_rule(SmoothingRule::Trace);
        group.bench_with_input(BenchmarkId::new("parametric_3d_trace", n), &(), |b, _| {
            b.iter(|| fit_parametric(&points, &trace).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
