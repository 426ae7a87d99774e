//! One full two-phase fairing (Han §4.1: coarse and fine passes alternating until no case
//! applies or `max_passes`) of a noisy function segment against n: time per point should be
//! flat (every move is a windowed O(1) update, never a rebuild; one rebuild per pass).

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, Throughput};
use curve_repr::{EndCondition, SplineFunction};
use fairing::two_phase::{fair_function, TwoPhaseSettings};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

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

/// Prints the counts the long-run option is measured by (once, not timed): a 10^5-point
/// noisy segment faired with the paper's rules and with `max_run` = 64.
fn print_counts() {
    use fairness::xc::XcPolyline;
    let n = 100_000;
    let (x, y) = noisy_segment(n);
    let clean: Vec<f64> = x.iter().map(|t| (t / 2.0).sin()).collect();
    let count = |y: &[f64]| XcPolyline::of_points(&x, y).map(|p| (p.inflections(), p.vibrations()));
    eprintln!(
        "n = {n}: clean (inflections, vibrations) {:?}, noisy {:?}",
        count(&clean),
        count(&y)
    );
    for (name, settings) in [
        ("paper", TwoPhaseSettings::default()),
        ("max_run 64", TwoPhaseSettings::default().with_max_run(64)),
        (
            "max_run 64, guard off",
            TwoPhaseSettings::default()
                .with_max_run(64)
                .with_count_guard(fairing::two_phase::CountGuard::Off),
        ),
    ] {
        let mut spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).expect("spline");
        let passes = fair_function(&mut spline, &settings, &|_| true).expect("fairing");
        eprintln!("  {name}: {passes} passes, faired {:?}", count(spline.y()));
    }
}

fn bench(c: &mut Criterion) {
    print_counts();
    let mut group = c.benchmark_group("two_phase_full_fairing");
    group.sample_size(10);
    let settings = TwoPhaseSettings::default();
    for n in [1_000usize, 10_000, 100_000, 1_000_000] {
        let (x, y) = noisy_segment(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter_batched(
                || SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).expect("spline"),
                |mut spline| {
                    fair_function(&mut spline, &settings, &|_| true).expect("fairing");
                    spline
                },
                BatchSize::PerIteration,
            )
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
