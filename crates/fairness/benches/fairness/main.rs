//! The crate's benchmarks, one binary (it links once): one module per subject; filter with
//! `cargo bench -p <crate> --bench fairness -- <group name>`.

mod indicators;

criterion::criterion_main!(indicators::benches,);
