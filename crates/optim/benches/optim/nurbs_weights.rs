//! Nowacki's NURBS weight fairing: one Ek evaluation of a 100-point interpolating NURBS (the
//! cost of one Nelder–Mead trial, re-solve included) and a whole Bernstein-law optimisation.

use std::hint::black_box;

use criterion::{criterion_group, Criterion as Bench};
use curve_repr::{Interpolation, InterpolationSettings, Parametrization, Vec2};
use fairness::Criterion;
use optim::{CriterionName, CubicBernstein, NurbsWeightFairing};

/// 100 points on a gently wavy arc (a section-like curve with mild unfairness).
fn points() -> Vec<Vec2> {
    (0..100)
        .map(|i| {
            let t = i as f64 / 99.0 * 2.5;
            let wobble = 1e-3 * (37.0 * t).sin();
            Vec2::new((1.0 + wobble) * t.cos(), (1.0 + wobble) * t.sin())
        })
        .collect()
}

fn nurbs_weights(c: &mut Bench) {
    let points = points();
    let interpolation = Interpolation::with_parametrization(
        &points,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )
    .unwrap();
    let weights: Vec<f64> = (0..interpolation.control_count())
        .map(|i| 1.0 + 0.01 * (i % 7) as f64)
        .collect();
    let ek = CriterionName::Ek.criterion::<2>();
    let mut group = c.benchmark_group("nurbs_weights");
    group.sample_size(10);
    group.bench_function("ek_evaluation_100_points", |b| {
        b.iter(|| {
            let curve = interpolation.solve(black_box(&weights)).unwrap();
            ek.evaluate(&curve).unwrap()
        })
    });
    group.bench_function("optimise_ek_bernstein_100_points", |b| {
        b.iter(|| {
            NurbsWeightFairing::new(CubicBernstein, CriterionName::Ek.criterion::<2>())
                .run(black_box(&points))
                .unwrap()
                .criterion_after
        })
    });
    group.finish();
}

criterion_group!(benches, nurbs_weights);
