//! Cost of every curve indicator on a piecewise cubic with n pieces: linear in n.
//!
//! The curve is a C2 piecewise cubic graph (t, y(t)) on uniform breaks 0, 1, …, n with O(1)
//! piece lookup, so the timings show the indicators' own cost.

use criterion::{criterion_group, BenchmarkId, Criterion as Bench, Throughput};
use curve_repr::{Curve, Side, Vec2};
use fairness::curvature::curvature_at_breaks;
use fairness::jumps::{curvature_slope_jumps, curvature_vibrations, third_derivative_jumps};
use fairness::{sign_changes, Energies};
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

/// y on piece i is a_i0 + a_i1 τ + a_i2 τ² + a_i3 τ³, τ = t − i.
struct Wiggle {
    pieces: Vec<[f64; 4]>,
}

impl Wiggle {
    fn new(n: usize) -> Self {
        let (mut y, mut d1, mut d2) = (0.0_f64, 0.0_f64, 0.0_f64);
        let pieces = (0..n)
            .map(|i| {
                // A bounded, irregular third derivative with feedback that keeps y′, y″ small.
                let d3 = (1.3 * i as f64).sin() - 0.5 * d2 - 0.1 * d1;
                let a = [y, d1, 0.5 * d2, d3 / 6.0];
                y = a[0] + a[1] + a[2] + a[3];
                d1 = a[1] + 2.0 * a[2] + 3.0 * a[3];
                d2 = 2.0 * a[2] + 6.0 * a[3];
                a
            })
            .collect();
        Wiggle { pieces }
    }
}

impl Curve<2> for Wiggle {
    fn domain(&self) -> (f64, f64) {
        (0.0, self.pieces.len() as f64)
    }
    fn jet(&self, t: f64, side: Side) -> [Vec2; 4] {
        let last = self.pieces.len() - 1;
        let floor = t.floor();
        let mut i = floor.max(0.0) as usize;
        if side == Side::Left && t == floor && i > 0 {
            i -= 1;
        }
        let i = i.min(last);
        let a = self.pieces[i];
        let s = t - i as f64;
        [
            Vec2::new(t, a[0] + (a[1] + (a[2] + a[3] * s) * s) * s),
            Vec2::new(1.0, a[1] + (2.0 * a[2] + 3.0 * a[3] * s) * s),
            Vec2::new(0.0, 2.0 * a[2] + 6.0 * a[3] * s),
            Vec2::new(0.0, 6.0 * a[3]),
        ]
    }
    fn breaks(&self) -> Vec<f64> {
        (0..=self.pieces.len()).map(|i| i as f64).collect()
    }
}

fn indicators(c: &mut Bench) {
    let mut group = c.benchmark_group("indicators");
    group.sample_size(10);
    for n in sizes(&[10_000, 100_000, 1_000_000]) {
        let curve = Wiggle::new(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("jumps", n), &curve, |b, curve| {
            b.iter(|| {
                let z = third_derivative_jumps(black_box(curve)).unwrap();
                let slope = curvature_slope_jumps(black_box(curve)).unwrap();
                (z.len(), slope.len())
            })
        });
        group.bench_with_input(BenchmarkId::new("curvature-counts", n), &curve, |b, curve| {
            b.iter(|| {
                let kappa = curvature_at_breaks(black_box(curve)).unwrap();
                let e = curvature_vibrations(&curve.breaks(), &kappa).unwrap();
                (sign_changes(&kappa), sign_changes(&e))
            })
        });
        group.bench_with_input(BenchmarkId::new("energies", n), &curve, |b, curve| {
            b.iter(|| Energies::of_polynomial(black_box(curve), 3).unwrap())
        });
    }
    group.finish();
}

/// The command's whole measuring path (`fair inspect`): build the spline through n points and
/// compute every indicator and energy of docs/CONTRACT.md's summary. A noisy sine, so that the curve
/// has many inflections and vibrations, like measured data; the noise is a fixed fraction of
/// the spacing h, so that every n sees pieces of the same shape (noise of fixed amplitude
/// would make the curve rougher per piece as n grows, and the quadrature's work per piece
/// with it).
fn summaries(c: &mut Bench) {
    let mut group = c.benchmark_group("summary");
    group.sample_size(10);
    for n in sizes(&[10_000, 100_000, 1_000_000]) {
        let h = 10.0 / n as f64;
        let x: Vec<f64> = (0..n).map(|i| i as f64 * h).collect();
        // A deterministic, irregular perturbation (no RNG dependency).
        let y: Vec<f64> = x
            .iter()
            .enumerate()
            .map(|(i, &x)| x.sin() + 0.1 * h * ((i as f64 * 12.9898).sin() * 43_758.545).fract())
            .collect();
        let points: Vec<Vec2> = x.iter().zip(&y).map(|(&x, &y)| Vec2::new(x, y)).collect();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("function", n), &(&x, &y), |b, (x, y)| {
            b.iter(|| fairness::summary::function(black_box(x), black_box(y)).unwrap())
        });
        group.bench_with_input(BenchmarkId::new("parametric", n), &points, |b, points| {
            b.iter(|| fairness::summary::parametric(black_box(points)).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, indicators, summaries);
