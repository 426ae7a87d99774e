//! The cost of the automatic Zhang–Cheng step per point, by order of work: four steps on a
//! noisy net (the surface table's: a smooth wave with ±0.01 hashed noise on every point) from
//! 50 × 50 to 400 × 400, reported per point moved (criterion's throughput: 4 · size²
//! elements). Flat time per element means each move costs O(window) whatever the grid's
//! size, and the step's O(m·n) parts (the knot refresh and judgement, the order) are
//! amortised over its m·n moves. Costs per grid line and per run (the boundary curves'
//! fairing, the unit responses of the knot vectors) are not amortised that way, and make the
//! smallest net the slowest per point (the surface module's docs, "cost of a step").
//! `queue`: largest current z first off an indexed heap;
//! `sort`: the paper's sort of the step's starting z;
//! `sort_steps`: `sort` without the boundary fairing (step 2.1, once per run), so the four
//! steps alone: their per-point cost, which the per-run cost does not blur at the small end
//! (a different run: the boundary curves stay as they are);
//! `tiles`: the paper's sort inside 64 × 64 tiles, the tiles by their largest z (the same
//! run as `sort` at 50 × 50; the default), `tiles_steps` the same without the boundary
//! fairing. Filter with
//! `cargo bench -p fairing --bench fairing -- surface_step` (`surface_step/sort` gives both
//! `sort` entries).

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use fairing::strategies::{SurfaceFairing, SurfaceFairingSettings, SweepOrder};

use crate::step_net::noisy_net;

/// Under `cargo test` (no `--bench` flag) only the smallest size runs.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

const STEPS: usize = 4;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("surface_step");
    group.sample_size(10);
    for size in sizes(&[50usize, 100, 200, 400]) {
        let net = noisy_net(size);
        group.throughput(Throughput::Elements((STEPS * size * size) as u64));
        for (name, order, boundary) in [
            ("queue", SweepOrder::Queue, true),
            ("sort", SweepOrder::Sort, true),
            ("sort_steps", SweepOrder::Sort, false),
            ("tiles", SweepOrder::Tiles, true),
            ("tiles_steps", SweepOrder::Tiles, false),
        ] {
            let settings = SurfaceFairingSettings::zhang_cheng()
                .with_order(order)
                .with_fair_boundary(boundary)
                .with_max_steps(STEPS);
            group.bench_with_input(BenchmarkId::new(name, size), &net, |b, net| {
                b.iter(|| SurfaceFairing::new(settings.clone()).run(net).unwrap())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
