//! Build and one-point move of a planar chord-length natural Hermite spline at n = 10³..10⁶.
//! Building should cost the same per point at every n; a move should not grow with n.

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use curve_repr::{HermiteSpline, Interpolant, Vec2};
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
            let t = i as f64 * 0.01;
            Vec2::new(
                t + 0.003 * (t * 37.0).sin(),
                (t * 3.0).sin() + 0.002 * (t * 91.0).cos(),
            )
        })
        .collect()
}

fn hermite(c: &mut Criterion) {
    let sizes = sizes(&[1_000usize, 10_000, 100_000, 1_000_000]);
    let mut build = c.benchmark_group("hermite_build");
    for &n in &sizes {
        let data = points(n);
        build.throughput(Throughput::Elements(n as u64));
        build.bench_with_input(BenchmarkId::from_parameter(n), &data, |b, data| {
            b.iter(|| HermiteSpline::natural(black_box(data)).map(|s| s.segment_count()))
        });
    }
    build.finish();
    let mut moves = c.benchmark_group("hermite_move_one_point");
    for &n in &sizes {
        let data = points(n);
        let mut spline = match HermiteSpline::natural(&data) {
            Ok(spline) => spline,
            Err(error) => panic!("bench data: {error}"),
        };
        let index = n / 2;
        let mut flip = false;
        moves.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| {
                flip = !flip;
                let offset = if flip { 1e-3 } else { 0.0 };
                let target = data[index] + Vec2::new(0.0, offset);
                spline.move_points(black_box(&[(index, target)])).is_ok()
            })
        });
    }
    moves.finish();
}

criterion_group!(benches, hermite);
