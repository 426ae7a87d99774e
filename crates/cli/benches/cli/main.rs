//! The command at real sizes: `fair inspect`'s measuring path and `fair curve` end to end
//! (read, fair, measure, write) on a noisy function segment of 10⁴ … 10⁶ points, the file
//! `../shared/peers/speed.py N OUT.csv` makes (x increasing with random steps, y = sin(x/2) +
//! N(0, 0.01)), so that the csaps time printed by that script is of the same data.
//!
//! `cargo bench -p fair-cli --bench cli` runs every size; under `cargo test` only the
//! smallest runs, to check the code, not to time it. Time per point should be flat.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use fair_cli::input::{parse_curve, Source};
use fair_door::measure::Detail;
use fair_door::KindChoice;
use std::hint::black_box;

fn sizes() -> Vec<usize> {
    let all = [10_000, 100_000, 1_000_000];
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

/// A deterministic stand-in for speed.py's data: x with uniform steps in [0.5, 1.5]·(4π/n),
/// y = sin(x/2) + N(0, 0.01) (Box–Muller over a 64-bit LCG), as CSV `x,y`.
fn noisy_segment(n: usize) -> String {
    let mut state: u64 = 0x2026_1122;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    let mut text = String::with_capacity(40 * n);
    text.push_str("x,y\n");
    let mut x = 0.0;
    for _ in 0..n {
        x += (0.5 + uniform()) * (4.0 * std::f64::consts::PI / n as f64);
        let gauss = (-2.0 * uniform().ln()).sqrt() * (2.0 * std::f64::consts::PI * uniform()).cos();
        let y = (x / 2.0).sin() + 0.01 * gauss;
        text.push_str(&format!("{x:?},{y:?}\n"));
    }
    text
}

fn inspect_path(c: &mut Criterion) {
    let catalog = fairing::catalog::Catalog::builtin();
    let mut group = c.benchmark_group("inspect");
    group.sample_size(10);
    for n in sizes() {
        let source = Source::from_text("noisy.csv", &noisy_segment(n));
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("noisy-function", n), &source, |b, source| {
            b.iter(|| {
                let input = parse_curve(black_box(source)).unwrap();
                let detail = Detail {
                    plot: false,
                    record: true,
                };
                fair_door::inspect_curve(&catalog, &input.data(), KindChoice::Auto, detail).unwrap()
            })
        });
    }
    group.finish();
}

fn curve_end_to_end(c: &mut Criterion) {
    let mut group = c.benchmark_group("curve");
    group.sample_size(10);
    // Removed when dropped, at the end of this function or on a panic.
    let scratch = tempfile::Builder::new().prefix("fair-bench-").tempdir().unwrap();
    let dir = scratch.path();
    for n in sizes() {
        let input = dir.join(format!("noisy{n}.csv"));
        std::fs::write(&input, noisy_segment(n)).unwrap();
        let output = dir.join(format!("faired{n}.csv"));
        let report = dir.join(format!("report{n}.json"));
        group.throughput(Throughput::Elements(n as u64));
        // The default method (jump-lsq, λ chosen by its rule), as a user runs it; and the
        // smoothing spline at csaps' own p = 0.999 on csaps' convention: the same computation
        // speed.py times, plus reading, measuring before and after, writing.
        let methods: [(&str, &[&str]); 2] = [
            ("default-method", &[]),
            (
                "smoothing-spline-p0.999",
                &["--method", "smoothing-spline", "--set", "p=0.999"],
            ),
        ];
        for (name, method) in methods {
            let mut command = vec!["fair", "curve", input.to_str().unwrap()];
            command.extend_from_slice(method);
            command.extend([
                "-o",
                output.to_str().unwrap(),
                "--report",
                report.to_str().unwrap(),
                "-q",
            ]);
            group.bench_function(BenchmarkId::new(name, n), |b| {
                b.iter(|| {
                    assert_eq!(
                        fair_cli::run_from(command.clone()),
                        std::process::ExitCode::SUCCESS
                    )
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, inspect_path, curve_end_to_end);
criterion_main!(benches);
