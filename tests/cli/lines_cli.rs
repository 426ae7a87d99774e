//! `fair lines`: a table of offsets faired as one hull, through the command.

use std::process::{Command, Output};

const TABLE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/data/hull_block_island_boat/offsets_table_inches.csv"
);

fn fair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .output()
        .expect("run fair")
}

/// The rows of a CSV table as cells, header included.
fn rows(path: &std::path::Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .expect("read table")
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[test]
fn lines_fairs_the_block_island_table() {
    let dir = super::scratch_dir("fair-lines-");
    let out = dir.path().join("faired.csv");
    let report = dir.path().join("report.json");
    let r = fair(&[
        "lines",
        TABLE,
        "-o",
        out.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(r.status.code(), Some(0), "{}", String::from_utf8_lossy(&r.stderr));
    let stdout = String::from_utf8_lossy(&r.stdout);
    assert!(
        stdout.contains("offsets") && stdout.contains("flagged"),
        "{stdout}"
    );

    // The faired table has the input's layout: the same header, rows and columns, and the
    // same labels; only the values may change.
    let input = rows(std::path::Path::new(TABLE));
    let faired = rows(&out);
    assert_eq!(faired.len(), input.len());
    assert_eq!(faired[0], input[0]);
    for (a, b) in input.iter().zip(&faired) {
        assert_eq!(a.len(), b.len());
        assert_eq!(a[..a.len() - 1], b[..b.len() - 1]);
    }

    // Every flagged offset is one the hull would move by more than three steps.
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let offsets = report["offsets"].as_array().unwrap();
    assert!(!offsets.is_empty());
    let flagged: Vec<_> = offsets.iter().filter(|o| o["flagged"] == true).collect();
    assert_eq!(flagged.len() as u64, report["flagged"].as_u64().unwrap());
    for o in flagged {
        assert!(o["move_steps"].as_f64().unwrap() > 3.0, "{o}");
    }
}

#[test]
fn lines_names_the_file_and_line_of_a_bad_value() {
    let dir = super::scratch_dir("fair-lines-bad-");
    let bad = dir.path().join("bad.csv");
    let mut text: Vec<String> = std::fs::read_to_string(TABLE)
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect();
    let cells: Vec<&str> = text[4].split(',').collect();
    text[4] = format!("{},abc", cells[..cells.len() - 1].join(","));
    std::fs::write(&bad, text.join("\n") + "\n").unwrap();
    let r = fair(&["lines", bad.to_str().unwrap()]);
    assert_eq!(r.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&r.stderr);
    assert!(
        stderr.starts_with(&format!("fair: {}:5: ", bad.display())),
        "{stderr}"
    );
}
