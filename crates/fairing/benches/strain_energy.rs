//! Cost of one automatic Zhang–Cheng step against n: it should not grow with n (O(window)).

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion};
use curve_repr::Vec2;
use fairing::strategies::{StrainEnergy, StrainEnergySettings};
use fairing::{Constraints, FairingState, FairingStrategy};

fn noisy_arc(n: usize) -> Vec<Vec2> {
    (0..n)
        .map(|i| {
            let a = i as f64 * 0.01;
            let e = 0.02 * ((i as f64) * 12.9898).sin().fract();
            Vec2::new((100.0 + e) * a.cos(), (100.0 + e) * a.sin())
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("strain_energy_10_steps");
    for n in [1_000usize, 10_000, 100_000] {
        let points = noisy_arc(n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &points, |b, points| {
            b.iter_batched(
                || {
                    let mut state = FairingState::new(points.clone(), Constraints::default(), false).unwrap();
                    let mut s = StrainEnergy::new(StrainEnergySettings::poliakoff());
                    s.init(&mut state).unwrap();
                    (state, s)
                },
                |(mut state, mut s)| {
                    for _ in 0..10 {
                        s.step(&mut state).unwrap();
                    }
                    (state, s)
                },
                BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
