//! `fair methods`: the table of every method and its parameters.

use crate::error::Result;

/// Prints [`crate::registry::table`] to standard output.
pub fn run() -> Result<()> {
    crate::output::write_text("-", &crate::registry::table())
}
