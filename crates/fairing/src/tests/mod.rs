//! Tests of the crate (one test binary, to keep build times down).

mod constraints;
mod limited_prepass;
mod partition;
mod pipeline;
