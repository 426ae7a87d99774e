//! Automatic Zhang–Cheng fairing of whole noisy nets from 50 × 50 to 400 × 400 (boundary
//! curves, restraining regions, every interior point each step, the refusal rules, the knot
//! refresh; default settings), reported per point (criterion's throughput in elements): the
//! time per point should stay flat. Issue 19's target: the 200 × 200 run under 1 s in
//! release. The surface baseline (tensor-product smoothing spline matched to a displacement)
//! at the same sizes.

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use curve_repr::Vec3;
use fairing::strategies::{
    SurfaceFairing, SurfaceFairingSettings, SurfaceSmoothing, SurfaceSmoothingSettings,
};

/// Under `cargo test` (no `--bench` flag) only the smallest size runs: the bench code is
/// checked there, not timed, and the suite stays fast.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

/// A smooth surface over a square with deterministic pseudo-random bumps on every point.
fn noisy_net(size: usize) -> Vec<Vec<Vec3>> {
    (0..size)
        .map(|i| {
            (0..size)
                .map(|j| {
                    let (x, y) = (i as f64 / 10.0, j as f64 / 10.0);
                    let noise = 0.01 * ((i * 7919 + j * 104_729) as f64 * 12.9898).sin().fract();
                    Vec3::new(x, y, (0.3 * x).sin() * (0.2 * y).cos() + noise)
                })
                .collect()
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("surface_automatic");
    group.sample_size(10);
    for size in sizes(&[50usize, 100, 200, 400]) {
        let net = noisy_net(size);
        group.throughput(Throughput::Elements((size * size) as u64));
        group.bench_with_input(BenchmarkId::from_parameter(size), &net, |b, net| {
            b.iter(|| {
                SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng())
                    .run(net)
                    .unwrap()
            })
        });
    }
    group.finish();
    let mut group = c.benchmark_group("surface_smoothing_baseline");
    group.sample_size(10);
    for size in sizes(&[50usize, 100, 200, 400]) {
        let net = noisy_net(size);
        // S_d of 0.0025 per point: about the noise's mean size.
        let target = 0.0025 * (size * size) as f64;
        group.throughput(Throughput::Elements((size * size) as u64));
        group.bench_with_input(BenchmarkId::from_parameter(size), &net, |b, net| {
            b.iter(|| {
                SurfaceSmoothing::new(SurfaceSmoothingSettings::default().with_displacement(target))
                    .run(net)
                    .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
