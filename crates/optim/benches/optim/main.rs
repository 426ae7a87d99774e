//! The crate's benchmarks, one binary (it links once): one module per subject; filter with
//! `cargo bench -p <crate> --bench optim -- <group name>`.

mod nelder_mead;
mod nurbs_weights;

criterion::criterion_main!(nelder_mead::benches, nurbs_weights::benches,);
