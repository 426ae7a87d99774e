use fair_lines::{read_table, Kind};

fn data(p: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(p)
}

#[test]
fn block_island_reads_with_its_families() {
    let t = read_table(data("hull_block_island_boat/offsets_table_inches.csv")).unwrap();
    assert_eq!(t.step, 0.125);
    assert_eq!(t.units.as_deref(), Some("in"));
    let n = |k: Kind| t.lines.iter().filter(|l| l.kind == k).count();
    assert_eq!(
        (
            n(Kind::Waterline),
            n(Kind::Buttock),
            n(Kind::Edge),
            n(Kind::Profile)
        ),
        (8, 5, 1, 1)
    );
    for c in &t.cells {
        assert!(c.x.is_finite(), "{c:?}");
    }
    let f = fair_lines::fair(&t, &fair_lines::Settings::default());
    assert!(f.is_ok(), "{:?}", f.err());
}
