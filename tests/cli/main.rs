//! The crate's integration tests, one binary (it links once): one module per subject.

mod baselines_cli;
mod basics;
mod batten_cli;
mod cad_cli;
mod columns_cli;
mod formats_cli;
mod inspect;
mod nurbs_weights_cli;
mod pipeline_batch_cli;
mod serve;
mod strain_energy_cli;
mod surface_cli;
mod two_phase_cli;
