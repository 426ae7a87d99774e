//! Export (exact conversion of the natural spline + writing) and read per format, and the
//! rebuild within a tolerance, against the number of faired points: all linear in n
//! (the rebuild O(n log n): O(log n) fits).

use cad::{rebuild, CadCurve, CadSettings, Format, RebuildTarget, Shape, WriteOptions};
use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use curve_repr::{HermiteSpline, Vec2};
use std::hint::black_box;

/// Under `cargo test` (no `--bench` flag) only the smallest size runs.
fn sizes(all: &[usize]) -> Vec<usize> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

fn curve(n: usize) -> CadCurve {
    let points: Vec<Vec2> = (0..n)
        .map(|i| {
            let t = i as f64 / n as f64 * 20.0;
            Vec2::new(t * 50.0, 30.0 * t.sin() + 0.5 * (7.3 * t).cos())
        })
        .collect();
    CadCurve::from_hermite(&HermiteSpline::natural(&points).unwrap()).unwrap()
}

fn export(c: &mut Criterion) {
    let mut group = c.benchmark_group("export");
    group.sample_size(10);
    for n in sizes(&[1_000, 10_000, 100_000, 1_000_000]) {
        let shape = Shape::Curve(curve(n));
        group.throughput(Throughput::Elements(n as u64));
        for format in Format::ALL {
            group.bench_with_input(
                BenchmarkId::new(format!("write_{format}"), n),
                &shape,
                |b, shape| {
                    b.iter(|| {
                        cad::export(
                            black_box(shape),
                            format,
                            &CadSettings::default(),
                            &WriteOptions::default(),
                        )
                        .unwrap()
                    });
                },
            );
            let text = cad::export(&shape, format, &CadSettings::default(), &WriteOptions::default())
                .unwrap()
                .text;
            group.bench_with_input(BenchmarkId::new(format!("read_{format}"), n), &text, |b, text| {
                b.iter(|| cad::read(black_box(text), format).unwrap());
            });
        }
    }
    group.finish();
}

fn rebuild_within(c: &mut Criterion) {
    let mut group = c.benchmark_group("rebuild");
    group.sample_size(10);
    for n in sizes(&[1_000, 10_000, 100_000]) {
        let faired = curve(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("tolerance_1e-3", n), &faired, |b, faired| {
            b.iter(|| rebuild(black_box(faired), RebuildTarget::Tolerance(1e-3), 3).unwrap());
        });
    }
    group.finish();
}

criterion_group!(benches, export, rebuild_within);
