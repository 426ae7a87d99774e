use fair_lines::{read_table, Error, Kind};

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
    // the wale has no x at the stem and post: those two cells are dropped, as the judge does
    assert_eq!(t.dropped.len(), 2);
    assert_eq!(t.cells.len(), 204);
    // WL 54's end at the stem is off its station's plane
    let wl54 = t
        .lines
        .iter()
        .position(|l| l.label.starts_with("0-54-0") && l.kind == Kind::Waterline)
        .unwrap();
    let stem = t
        .cells
        .iter()
        .find(|c| c.line == wl54 && c.station_index == 0)
        .unwrap();
    assert_eq!((stem.x, stem.on_station), (4.25, false));
}

#[test]
fn the_other_layouts_read() {
    let s = read_table(data("hull_chesapeake_bay_sharpie/offsets_table.csv")).unwrap();
    assert!(s.lines.iter().any(|l| l.label == "chine" && l.knuckle));
    assert!(!s.has_redundant_views());
    let g = read_table(data("hull_gunnerus/offsets_m.csv")).unwrap();
    assert_eq!((g.lines.len(), g.cells.len()), (16, 764));
    assert_eq!(g.units.as_deref(), Some("m"));
}

fn refused(text: &str) -> (usize, String) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("t.csv");
    std::fs::write(&p, text).unwrap();
    match read_table(&p) {
        Err(Error::Table { line, message, path }) => {
            assert!(path.ends_with("t.csv"));
            (line, message)
        }
        other => panic!("not refused: {other:?}"),
    }
}

#[test]
fn a_table_that_is_not_one_is_refused_with_its_line() {
    let (line, m) = refused("a,b\n1,2\n");
    assert_eq!(line, 1, "{m}");
    let (line, m) =
        refused("line,station_index,station_name,x,half_breadth,height\nWL1,0,0,0,1,2\nWL1,1,1,10,abc,2\n");
    assert_eq!(line, 3);
    assert!(m.contains("abc"), "{m}");
    let (line, m) = refused("line,station_index,station_name,x,half_breadth,height\nWL1,0.5,0,0,1,2\n");
    assert_eq!(line, 2);
    assert!(m.contains("integer"), "{m}");
    let (line, m) = refused("i,j,x,y,z\n0,0,0,1,0\n0,1,1,1,0.5\n");
    assert_eq!(line, 3);
    assert!(m.contains("waterline grid"), "{m}");
    let (line, m) = refused("block,line,station_index,station_name,value\nWIDTH,Sheer,0,0,1\n");
    assert_eq!(line, 2);
    assert!(m.contains("unknown block"), "{m}");
}
