//! The crate's benchmarks, one binary (it links once): one module per subject; filter with
//! `cargo bench -p <crate> --bench representations -- <group name>`.

mod bicubic_surface;
mod hermite;
mod nurbs;
mod spline_function;

criterion::criterion_main!(
    bicubic_surface::benches,
    hermite::benches,
    nurbs::benches,
    spline_function::benches,
);
