//! Two-phase fairing (Han §4.1) of a noisy function segment against n: time per point should
//! be flat (every move is a windowed O(1) update, never a rebuild; one rebuild per pass).
//!
//! - `two_phase_full_fairing`: one full fairing, [`fair_function`] with the default settings
//!   (coarse and fine passes alternating until no case applies or 50 passes), n = 10^3 … 10^6
//!   (10^6 takes ~17 s per iteration: the 10 samples take about three minutes);
//! - `two_phase_one_full_pass`: one coarse and one fine pass on the raw noisy data (the
//!   busiest pass), n = 10^3 … 10^6;
//! - `two_phase_binned_prepass`: the noise pre-pass of a function with two-phase's default
//!   settings beyond its limit of 10^5 points (bin means, module `two_phase::bins`), on
//!   y = sin(x/2) + N(0, 0.01²) over [0, 20], n = 1.25·10^5 … 10^6: O(n) for the bins and
//!   the read-back, the fits on 2 000 bins at every size.

use criterion::{criterion_group, BatchSize, BenchmarkId, Criterion, SamplingMode, Throughput};
use curve_repr::{EndCondition, SplineFunction};
use fairing::two_phase::{denoise_by, fair_function, full_pass, Limits, TwoPhaseSettings};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

/// Under `cargo test` (no `--bench` flag) only the smallest size runs: the bench code is
/// checked there, not timed, and the suite stays fast.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

/// y = sin(x/2) + N(0, 0.01²) at x = 0.1 k.
fn noisy_segment(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    let normal = Normal::new(0.0, 0.01).expect("valid normal");
    let x: Vec<f64> = (0..n).map(|k| 0.1 * k as f64).collect();
    let y = x
        .iter()
        .map(|t| (t / 2.0).sin() + normal.sample(&mut rng))
        .collect();
    (x, y)
}

/// One group: `run` on a fresh noisy segment at every size.
fn group(c: &mut Criterion, name: &str, run: &dyn Fn(&mut SplineFunction)) {
    let mut group = c.benchmark_group(name);
    group.sample_size(10);
    // One iteration per sample (a full fairing at 10^6 takes seconds; linear sampling would
    // run 55 of them).
    group.sampling_mode(SamplingMode::Flat);
    for n in sizes(&[1_000usize, 10_000, 100_000, 1_000_000]) {
        let (x, y) = noisy_segment(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter_batched(
                || SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).expect("spline"),
                |mut spline| {
                    run(&mut spline);
                    spline
                },
                BatchSize::PerIteration,
            )
        });
    }
    group.finish();
}

fn bench(c: &mut Criterion) {
    let paper = TwoPhaseSettings::default();
    group(c, "two_phase_full_fairing", &|spline| {
        fair_function(spline, &paper, &|_| true).expect("fairing");
    });
    group(c, "two_phase_one_full_pass", &|spline| {
        full_pass(spline, &paper, &|_| true).expect("pass");
    });
}

/// y = sin(x/2) + N(0, 0.01²) at n evenly spaced x over [0, 20] (denser with n, the same
/// curve).
fn dense_segment(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut rng = rand::rngs::StdRng::seed_from_u64(12);
    let normal = Normal::new(0.0, 0.01).expect("valid normal");
    let x: Vec<f64> = (0..n).map(|k| 20.0 * k as f64 / (n - 1) as f64).collect();
    let y = x
        .iter()
        .map(|t| (t / 2.0).sin() + normal.sample(&mut rng))
        .collect();
    (x, y)
}

fn bench_prepass(c: &mut Criterion) {
    let settings = TwoPhaseSettings::default();
    let prepass = TwoPhaseSettings::function_prepass();
    let none = |_: usize| false;
    let free = |_: usize| f64::INFINITY;
    let limits = Limits {
        keep: &none,
        allowed: &free,
    };
    let mut group = c.benchmark_group("two_phase_binned_prepass");
    group.sample_size(10);
    group.sampling_mode(SamplingMode::Flat);
    for n in sizes(&[125_000usize, 250_000, 500_000, 1_000_000]) {
        let (x, y) = dense_segment(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| denoise_by(settings.denoise, prepass, &x, &y, &limits).expect("pre-pass"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench, bench_prepass);
