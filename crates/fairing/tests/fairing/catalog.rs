//! The catalogue: parameter tables from the settings, `--set` text and config values, presets,
//! plans and pipelines, criteria in reports.

use fairing::catalog::{Catalog, MethodKind, ParameterMap};

#[test]
fn table_prints() {
    let catalog = Catalog::builtin();
    println!("{}", catalog.table());
    for m in catalog.methods(MethodKind::Curve) {
        println!("{} {}", m.name(), m.schema());
    }
    let _ = ParameterMap::new();
}
