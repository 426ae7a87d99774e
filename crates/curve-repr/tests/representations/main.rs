//! The crate's integration tests, one binary (it links once): one module per subject.

mod bicubic_surface;
mod convert;
mod generic;
mod hermite;
mod nurbs;
mod spline_function;
