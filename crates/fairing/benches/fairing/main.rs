//! The crate's benchmarks, one binary (it links once): one module per subject; filter with
//! `cargo bench -p <crate> --bench fairing -- <group name>`.

mod jump_lsq;
mod noisy_segment;
mod sapidis_farin;
mod smoothing_spline;
mod step_net;
mod strain_energy;
mod surface_fairing;
mod surface_jump;
mod surface_order;
mod two_phase;

criterion::criterion_main!(
    jump_lsq::benches,
    sapidis_farin::benches,
    smoothing_spline::benches,
    strain_energy::benches,
    surface_fairing::benches,
    surface_jump::benches,
    surface_order::benches,
    two_phase::benches,
);
