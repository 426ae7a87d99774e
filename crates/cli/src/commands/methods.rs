//! `fair methods`: the table of every method and its parameters, criteria and indicators,
//! derived from the catalogue (each method's settings type).

use fairing::catalog::Catalog;

use fair_door::error::Result;

/// Prints [`Catalog::table`] to standard output.
pub(crate) fn run(catalog: &Catalog) -> Result<()> {
    crate::output::write_text("-", &catalog.table())
}
