//! `fair methods`: the table of every method and its parameters, criteria and indicators,
//! derived from the catalogue (each method's settings type).

use fairing::catalog::Catalog;

use fair_door::curve::default_method;
use fair_door::error::Result;
use fair_door::kind::CurveKind;

/// Prints [`Catalog::table`] to standard output, then the default method of each kind of
/// input (the door's, which `fair curve` and `fair surface` use without `--method`).
pub(crate) fn run(catalog: &Catalog) -> Result<()> {
    crate::output::write_text("-", &format!("{}{}", catalog.table(), defaults()))
}

/// The line naming the default methods.
fn defaults() -> String {
    format!(
        "defaults: {} for functions, {} for parametric curves, {} for surfaces\n",
        default_method(CurveKind::Function),
        default_method(CurveKind::Parametric),
        fair_door::surface::DEFAULT_METHOD,
    )
}
