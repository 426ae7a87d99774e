use fair_lines::{fair, read_table, write, Settings};

fn block_island() -> fair_lines::Faired {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/hull_block_island_boat/offsets_table_inches.csv");
    fair(&read_table(p).unwrap(), &Settings::default()).unwrap()
}

#[test]
fn the_faired_table_keeps_the_input_layout_and_reads_back_as_faired() {
    let f = block_island();
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("faired_inches.csv");
    write::write_table(&f, &p).unwrap();
    let text = std::fs::read_to_string(&p).unwrap();
    let input = std::fs::read_to_string(&f.table.path).unwrap();
    assert_eq!(text.lines().count(), input.lines().count());
    // FORE-AFT rows (the layout) are unchanged
    for (a, b) in text.lines().zip(input.lines()) {
        if b.starts_with("FORE-AFT") {
            assert_eq!(a, b);
        }
    }
    let back = read_table(&p).unwrap();
    assert_eq!(back.cells.len(), f.table.cells.len());
    for (c, v) in back.cells.iter().zip(&f.values) {
        for (k, w) in [c.x, c.y, c.z].iter().enumerate() {
            if w.is_finite() {
                assert!((w - v[k]).abs() < 1e-4, "{c:?} {v:?}");
            }
        }
    }
}

#[test]
fn the_hull_goes_to_cad_and_reads_back() {
    let f = block_island();
    let dir = tempfile::tempdir().unwrap();
    for name in ["hull.igs", "hull.stp"] {
        let p = dir.path().join(name);
        write::write_hull(&f, &p).unwrap();
        let m = cad::read_path(&p, None).unwrap();
        assert_eq!(m.surfaces.len(), 1);
        let h = f.hulls.first().unwrap();
        let ((x0, x1), (z0, z1)) = h.domain();
        let (x, z) = (0.3 * x0 + 0.7 * x1, 0.6 * z0 + 0.4 * z1);
        let p3 = m.surfaces[0].point_at(x, z);
        // a function surface on its Greville net: the parameters are x and z themselves
        assert!(
            (p3[0] - x).abs() < 1e-6 && (p3[2] - z).abs() < 1e-6 && (p3[1] - h.eval(x, z).0).abs() < 1e-6,
            "{p3:?}"
        );
    }
}

#[test]
fn lines_report_and_views_are_written() {
    let f = block_island();
    let dir = tempfile::tempdir().unwrap();
    let files = write::write_lines(&f, dir.path()).unwrap();
    assert!(files.iter().any(|n| n.starts_with("line_Sheer")));
    assert_eq!(
        files.iter().filter(|n| n.starts_with("station_")).count(),
        f.table.stations.len()
    );
    let r: serde_json::Value = serde_json::from_str(&write::report_json(&f)).unwrap();
    assert_eq!(r["offsets"].as_array().unwrap().len(), f.table.cells.len());
    let svg = write::svg(&f);
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<circle").count() > 0, f.report.flagged > 0);
}
