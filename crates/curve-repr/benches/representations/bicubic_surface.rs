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

/// One point moved and the surface rebuilt locally (tangents and twists in a window round the
/// point): the time should not grow with the grid (O(m + n) for the two unit responses, a
/// small part, and O(window²) for the twists).
fn move_one_point(c: &mut Criterion) {
    let mut group = c.benchmark_group("bicubic_surface_move");
    for count in sizes(&[50usize, 100, 200, 400]) {
        let mut surface = BicubicSplineSurface::new(&grid(count)).unwrap_or_else(|error| panic!("{error}"));
        let (i, j) = (count / 2, count * 3 / 8);
        let (x, y) = (i as f64 * 0.1, j as f64 * 0.1);
        let mut toggle = false;
        group.bench_function(format!("one point {count}x{count}"), |b| {
            b.iter(|| {
                toggle = !toggle;
                let z = if toggle { 0.5 } else { -0.5 };
                surface.move_points(black_box(&[((i, j), Vec3::new(x, y, z))]))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, build, move_one_point);
