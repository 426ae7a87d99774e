//! The crate's integration tests, one binary (it links once): one module per subject.

mod gradient;
mod nurbs_weights;
mod user_extensions;
