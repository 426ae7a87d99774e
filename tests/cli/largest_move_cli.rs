//! Every curve method's report says how far its farthest point moved and whether that exceeds
//! the bound the user did not ask to exceed (the data's noise and decimal step, or a wider
//! `--tolerance`), with a warning on standard error unless `-q` (issue 18).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A straight line typed with one decimal (y = k/2) and one point pushed 3 units off it:
/// no noise, a decimal step of 0.1, so the data's bound is 0.1; written in `dir`.
fn bumped_line(dir: &Path) -> PathBuf {
    let mut text = String::from("x,y\n");
    for k in 0..41 {
        let y = 0.5 * k as f64 + if k == 20 { 3.0 } else { 0.0 };
        text.push_str(&format!("{k},{y}\n"));
    }
    let path = dir.join("bumped.csv");
    std::fs::write(&path, text).unwrap();
    path
}

fn fair(method: &str, args: &[&str], tag: &str) -> (Output, serde_json::Value) {
    let scratch = crate::scratch_dir("fair-largest-move-");
    let dir = scratch.path();
    let report = dir.join(format!("{tag}.json"));
    let output = Command::new(env!("CARGO_BIN_EXE_fair"))
        .arg("curve")
        .arg(bumped_line(dir))
        .args(["--method", method, "-o"])
        .arg(dir.join(format!("{tag}.csv")))
        .arg("--report")
        .arg(&report)
        .args(args)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let report = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    (output, report)
}

#[test]
fn a_move_beyond_the_datas_bound_is_reported_and_warned() {
    let (output, report) = fair("smoothing-spline", &[], "warned");
    let largest = &report["largest_move"];
    assert_eq!(largest["index"], 20, "{largest}");
    assert_eq!(largest["bound"].as_f64(), Some(0.1), "{largest}");
    assert_eq!(largest["bound_from"], "data");
    assert_eq!(largest["quantum"].as_f64(), Some(0.1));
    let distance = largest["distance"].as_f64().unwrap();
    assert!(distance > 0.1, "{largest}");
    assert_eq!(largest["exceeds"], true);
    // The report's M_d is the same move.
    assert_eq!(report["m_d"].as_f64(), Some(distance));
    // The warning numbers the point as the report and `--fixed` do, from 0.
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("fair: warning:") && stderr.contains("moved point 20 by"),
        "{stderr}"
    );

    let (quiet, report) = fair("smoothing-spline", &["-q"], "quiet");
    assert_eq!(report["largest_move"]["exceeds"], true);
    assert!(!String::from_utf8_lossy(&quiet.stderr).contains("warning"));
}

#[test]
fn a_move_within_the_users_tolerance_is_not_warned() {
    let (output, report) = fair("smoothing-spline", &["--tolerance", "5"], "tolerance");
    let largest = &report["largest_move"];
    assert_eq!(largest["bound"].as_f64(), Some(5.0), "{largest}");
    assert_eq!(largest["bound_from"], "tolerance");
    assert_eq!(largest["exceeds"], false);
    assert!(!String::from_utf8_lossy(&output.stderr).contains("warning"));
}
