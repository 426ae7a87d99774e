//! The crate's benchmark: fairing each real table of offsets in `data/` as one hull
//! ([`fair_lines::fair`], the read excluded), issue 47's "the largest table faired in under a
//! second". `cargo bench -p fair-lines --bench lines` runs it; under `cargo test` (no `--bench`
//! flag) only the smallest table runs, once.
//!
//! Cost: about a hundred banded solves per hull region (the λ search of each robust outer
//! iteration), each O(n·bw²) with n the region's coefficients and bw its band.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use fair_lines::{fair, read_table, Settings};
use std::hint::black_box;
use std::path::Path;

/// (name, file, step): the steps of the grids as `examples/lines_plan.rs` gives them (PX121 in
/// 1/1140 of the half-beam, Gunnerus read at 1 cm); the others from their decimals. Smallest
/// first.
const HULLS: [(&str, &str, Option<f64>); 5] = [
    (
        "sharpie",
        "data/hull_chesapeake_bay_sharpie/offsets_table.csv",
        None,
    ),
    ("gokstad", "data/hull_gokstad_ship/offsets_table.csv", None),
    ("px121", "data/hull_px121/offsets_nondim.csv", Some(1.0 / 1140.0)),
    (
        "block_island",
        "data/hull_block_island_boat/offsets_table_inches.csv",
        None,
    ),
    ("gunnerus", "data/hull_gunnerus/offsets_m.csv", Some(0.01)),
];

fn hulls(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let all = std::env::args().any(|a| a == "--bench");
    let mut group = c.benchmark_group("lines_fair");
    group.sample_size(10);
    for (name, file, step) in HULLS.iter().take(if all { HULLS.len() } else { 1 }) {
        let table = read_table(root.join(file)).expect("a table of data/ reads");
        let settings = Settings {
            step: *step,
            ..Settings::default()
        };
        group.throughput(Throughput::Elements(table.cells.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(name), &table, |b, table| {
            b.iter(|| fair(black_box(table), &settings).expect("the table fairs"));
        });
    }
    group.finish();
}

criterion_group!(benches, hulls);
criterion_main!(benches);
