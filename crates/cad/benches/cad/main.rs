//! The crate's benchmarks, one binary: export (convert + write) and read of a faired curve in
//! each format at 10³ … 10⁶ points, and the least-squares rebuild within a tolerance.
//! `cargo bench -p fair-cad --bench cad -- export` runs one group.

mod export;

criterion::criterion_main!(export::benches);
