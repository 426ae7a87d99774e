//! Cost of jump-lsq against n (10^3 … 10^6 points): time per point should stay flat.
//!
//! Data as the speed peer's (`speed.py`): a noisy function segment, x with uniform random
//! steps in [0.5, 1.5]·4π/n, y = sin(x/2) + noise of standard deviation 0.01. Cases: one
//! solve at a given λ (one knot per point at every size); λ by the default rule (`auto`; the
//! case keeps its old name `discrepancy`); by GCV (to 10^5); and a 3D parametric curve with the
//! default rule and refits. Beyond 10^4 points the rules' cases fit on jump-lsq's reduced basis
//! (bin means, read back at every point), so their time per point falls there. At 10^3 points also two-phase's
//! function pre-pass settings (`rule = auto`, `function-ends = auto`), with d = 1 and with
//! `difference-order = auto` (the order chosen by GCV, up to 2000 points only), and with
//! `exponent = auto` too (the six pairs (d, a) of the joint search: these steps are uneven).

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use curve_repr::{Vec2, Vec3};
use fairing::strategies::jump_lsq::{fair, JumpLsqSettings, LambdaRule, ORDER_AUTO_MAX};
use fairing::strategies::{CurveDomain, FunctionEnds};
use fairing::Constraints;

/// Under `cargo test` (no `--bench` flag) only the smallest size runs: the bench code is
/// checked there, not timed, and the suite stays fast.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

/// A uniform value in [0, 1) from an integer (a hash; no RNG state).
fn uniform(k: usize) -> f64 {
    ((k as f64 * 12.9898).sin() * 43758.5453).rem_euclid(1.0)
}

/// Approximately normal noise (sum of four uniforms, scaled to unit variance).
fn normal(k: usize) -> f64 {
    ((0..4).map(|j| uniform(4 * k + j + 7)).sum::<f64>() - 2.0) * 3f64.sqrt()
}

fn function_data(n: usize) -> Vec<Vec2> {
    let step = 4.0 * std::f64::consts::PI / n as f64;
    let mut x = 0.0;
    (0..n)
        .map(|k| {
            x += (0.5 + uniform(3 * k + 1)) * step;
            Vec2::new(x, (x / 2.0).sin() + 0.01 * normal(k))
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("jump_lsq");
    group.sample_size(10);
    let none = Constraints::default();
    for n in sizes(&[1_000usize, 10_000, 100_000, 1_000_000]) {
        let points = function_data(n);
        group.throughput(Throughput::Elements(n as u64));
        let cases = [
            ("given_lambda", JumpLsqSettings::default().with_lambda(1e3)),
            ("discrepancy", JumpLsqSettings::default()),
            ("gcv", JumpLsqSettings::default().with_rule(LambdaRule::Gcv)),
        ];
        for (label, settings) in cases {
            if label == "gcv" && n > 100_000 {
                continue;
            }
            group.bench_with_input(BenchmarkId::new(label, n), &(), |b, _| {
                b.iter(|| fair(&points, &points, &none, CurveDomain::Function, false, &settings).unwrap())
            });
        }
        if n <= ORDER_AUTO_MAX {
            let prepass = JumpLsqSettings::default()
                .with_rule(LambdaRule::Auto)
                .with_function_ends(FunctionEnds::Auto);
            let cases = [
                ("prepass_order_1", prepass.clone()),
                ("prepass_order_auto", prepass.clone().with_auto_difference_order()),
                (
                    "prepass_order_exponent_auto",
                    prepass.with_auto_difference_order().with_exponent_auto(),
                ),
            ];
            for (label, settings) in cases {
                group.bench_with_input(BenchmarkId::new(label, n), &(), |b, _| {
                    b.iter(|| fair(&points, &points, &none, CurveDomain::Function, false, &settings).unwrap())
                });
            }
        }
        let space: Vec<Vec3> = points
            .iter()
            .map(|p| Vec3::new(p.x, p.y, 0.1 * (3.0 * p.x).cos()))
            .collect();
        let settings = JumpLsqSettings::default();
        group.bench_with_input(BenchmarkId::new("parametric_3d", n), &(), |b, _| {
            b.iter(|| fair(&space, &space, &none, CurveDomain::Parametric, false, &settings).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
