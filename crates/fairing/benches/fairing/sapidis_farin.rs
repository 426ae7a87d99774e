//! Cost of a whole default Sapidis–Farin run against n (10^4, 10^5, 10^6 points): at most
//! 1000 knots faired, each chosen off a tournament tree and faired on a window of the
//! B-spline, so the run should cost the interpolation's O(n) plus O(log n) per step.
//!
//! Data as the CLI's slowest test (`columns_cli`'s noisy segment): a function y(x) with x in
//! random steps of [0.5, 1.5]·4π/n, y = sin(x/2) + noise of standard deviation 1; and the
//! same points as a parametric curve (chord length).

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use curve_repr::Vec2;
use fairing::strategies::{CurveDomain, SapidisFarin, SapidisFarinSettings};
use fairing::Pipeline;

/// Under `cargo test` (no `--bench` flag) only the smallest size runs: the bench code is
/// checked there, not timed, and the suite stays fast.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

/// The CLI test's noisy segment: x in random steps, sin(x/2) plus Gaussian noise (σ = 1).
fn data(n: usize) -> Vec<Vec2> {
    crate::noisy_segment::noisy_segment(n, 1.0, 20_261_122)
        .into_iter()
        .map(|[x, y]| Vec2::new(x, y))
        .collect()
}

/// A default run (max-iterations 1000, moves bounded by the data) as the catalogue makes it.
fn run(points: &[Vec2], domain: CurveDomain) -> usize {
    let settings = SapidisFarinSettings::default().with_domain(domain);
    let steps = settings.max_iterations + 1;
    Pipeline::new(SapidisFarin::<2>::new(settings))
        .with_max_iterations(steps)
        .with_trace(false)
        .run(points.to_vec())
        .unwrap()
        .iterations
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("sapidis_farin");
    group.sample_size(10);
    for n in sizes(&[10_000usize, 100_000, 1_000_000]) {
        let points = data(n);
        group.throughput(Throughput::Elements(n as u64));
        for (label, domain) in [
            ("function", CurveDomain::Function),
            ("parametric", CurveDomain::Parametric),
        ] {
            group.bench_with_input(BenchmarkId::new(label, n), &(), |b, _| {
                b.iter(|| run(&points, domain))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
