//! The user guide's method pages (`docs/methods/<kind>/<name>.md`) against what the catalogue
//! generates from each method's settings type: a page whose generated part differs, a
//! method without a page and a page without a method all fail. `FAIR_BLESS=1` rewrites the
//! generated parts (and creates missing pages), keeping the prose above the marker.

use std::fs;
use std::path::{Path, PathBuf};

use fairing::catalog::{Catalog, GENERATED_MARKER};

fn pages_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/methods")
}

/// The hand-written part of a page (through the marker's line), or a title for a new page.
fn prose(existing: Option<&str>, path: &str) -> String {
    match existing.and_then(|text| text.find(GENERATED_MARKER).map(|at| &text[..at])) {
        Some(above) => above.to_owned(),
        None => {
            let name = path.trim_end_matches(".md").replace('/', " method: ");
            format!("# {name}\n\n")
        }
    }
}

#[test]
fn method_pages() {
    let dir = pages_dir();
    let bless = std::env::var("FAIR_BLESS").is_ok_and(|v| v == "1");
    let pages = Catalog::builtin().pages();
    let mut stale = Vec::new();
    for (path, generated) in &pages {
        let file = dir.join(path);
        let existing = fs::read_to_string(&file).ok();
        let generated_part = existing
            .as_deref()
            .and_then(|text| text.split_once(GENERATED_MARKER).map(|(_, below)| below));
        if generated_part == Some(generated.as_str()) {
            continue;
        }
        if bless {
            let text = format!(
                "{}{GENERATED_MARKER}{generated}",
                prose(existing.as_deref(), path)
            );
            fs::create_dir_all(file.parent().expect("a page has a folder")).expect("create docs/methods");
            fs::write(&file, text).expect("write the page");
        } else {
            stale.push(path.clone());
        }
    }
    let known: Vec<&str> = pages.iter().map(|(p, _)| p.as_str()).collect();
    let mut orphans = Vec::new();
    for kind in ["curve", "surface"] {
        if let Ok(entries) = fs::read_dir(dir.join(kind)) {
            for entry in entries.flatten() {
                let path = format!("{kind}/{}", entry.file_name().to_string_lossy());
                if !known.contains(&path.as_str()) {
                    orphans.push(path);
                }
            }
        }
    }
    assert!(
        stale.is_empty(),
        "docs/methods/: these pages differ from what the catalogue generates (or are missing): \
         {stale:?}; rewrite their generated part with `FAIR_BLESS=1 cargo test -p fairing --test \
         fairing method_pages` and commit the pages"
    );
    assert!(
        orphans.is_empty(),
        "docs/methods/: pages of no method in Catalog::builtin(): {orphans:?}; remove them"
    );
}
