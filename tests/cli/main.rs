//! The crate's integration tests, one binary (it links once): one module per subject.

mod baselines_cli;
mod basics;
mod batten_cli;
mod cad_cli;
mod columns_cli;
mod formats_cli;
mod inspect;
mod jump_lsq_cli;
mod largest_move_cli;
#[path = "../../crates/fairing/benches/fairing/noisy_segment.rs"]
mod noisy_segment;
mod nurbs_weights_cli;
mod nurbs_weights_solver_cli;
mod pipeline_batch_cli;
mod serve;
mod strain_energy_cli;
mod surface_cli;
mod two_phase_cli;
