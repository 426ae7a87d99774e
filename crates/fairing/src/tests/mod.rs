//! Tests of the crate (one test binary, to keep build times down).

mod constraints;
mod partition;
mod pipeline;
