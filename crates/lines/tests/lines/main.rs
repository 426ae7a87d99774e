//! The fair-lines integration tests.

mod read;
