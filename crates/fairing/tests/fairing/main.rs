//! The crate's integration tests, one binary (it links once): one module per subject.

mod batten;
mod catalog;
mod composition;
mod contract;
mod curve_guard;
mod displacement;
mod equivariance;
mod extending;
mod jump_lsq;
mod pages;
mod runtime_schema;
mod sapidis_farin_data;
mod strain_energy;
mod surface;
mod surface_join;
mod surface_jump_lsq;
mod two_phase;
mod two_phase_curves;
mod two_phase_denoise;
mod two_phase_ends;
mod two_phase_fine;
mod two_phase_foot_point;
