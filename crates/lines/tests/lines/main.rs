//! The fair-lines integration tests.

mod known_hull;
mod read;
mod write;
