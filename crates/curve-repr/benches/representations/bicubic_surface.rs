//! Building a bicubic spline surface (Zhang–Cheng §4) and rebuilding it after one point moves.

use criterion::{criterion_group, BenchmarkId, Criterion};
use curve_repr::{BicubicSplineSurface, Vec3};
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

fn grid(count: usize) -> Vec<Vec<Vec3>> {
    (0..count)
        .map(|i| {
            (0..count)
                .map(|j| {
                    let (x, y) = (i as f64 * 0.1, j as f64 * 0.1);
                    Vec3::new(
                        x,
                        y,
                        (x * 0.7).sin() * (y * 0.4).cos() + 0.01 * ((i * 31 + j * 17) as f64).sin(),
                    )
                })
                .collect()
        })
        .collect()
}

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("bicubic_surface_build");
    for count in sizes(&[50, 100, 200, 400]) {
        let points = grid(count);
        group.bench_with_input(
            BenchmarkId::from_parameter(format!("{count}x{count}")),
            &points,
            |b, points| b.iter(|| BicubicSplineSurface::new(black_box(points))),
        );
    }
    group.finish();
}

fn move_one_point(c: &mut Criterion) {
    let mut surface = BicubicSplineSurface::new(&grid(200)).unwrap_or_else(|error| panic!("{error}"));
    let mut group = c.benchmark_group("bicubic_surface_move");
    let mut toggle = false;
    group.bench_function("one point 200x200", |b| {
        b.iter(|| {
            toggle = !toggle;
            let z = if toggle { 0.5 } else { -0.5 };
            surface.move_points(black_box(&[((100, 77), Vec3::new(10.0, 7.7, z))]))
        })
    });
    group.finish();
}

criterion_group!(benches, build, move_one_point);
