//! The crate's integration tests, one binary (it links once): one module per subject.

mod atomic_outputs_cli;
mod baselines_cli;
mod basics;
mod batten_cli;
mod cad_cli;
mod columns_cli;
mod formats_cli;
mod fuzz_readers;
mod inspect;
mod jump_lsq_cli;
mod largest_move_cli;
mod lines_cli;
#[path = "../../crates/cad/tests/cad/mutate.rs"]
mod mutate;
// A file of fairing's benches, shared: its item is `pub` for the benches' crate.
#[allow(unreachable_pub)]
#[path = "../../crates/fairing/benches/fairing/noisy_segment.rs"]
mod noisy_segment;
mod nurbs_weights_cli;
mod nurbs_weights_solver_cli;
mod pipeline_batch_cli;
mod serve;
mod strain_energy_cli;
mod surface_cli;
mod surface_join_cli;
mod two_phase_cli;

/// A fresh directory `$TMPDIR/<prefix>XXXXXX` for a test's files, removed with everything in it
/// when the returned guard is dropped: keep it in a variable for as long as the test uses the
/// directory, and it goes when the test ends, passed or failed (a panic unwinds through it).
fn scratch_dir(prefix: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(prefix)
        .tempdir()
        .expect("scratch directory")
}
