//! The crate's integration tests, one binary: one module per subject.

mod common;
mod errors;
mod exact;
mod fuzz;
mod mutate;
mod occ_check;
mod occ_files;
mod rebuild;
mod round_trip;
