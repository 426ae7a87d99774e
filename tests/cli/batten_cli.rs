//! `fair curve --method batten` end to end through the binary, on Okada's Table 1 data
//! (11 points in 3D, points 3, 6 and 8 of the paper fixed, i.e. indices 2, 5 and 7).

use std::process::{Command, Output};

/// Okada (1969) Table 1, DATA-X, DATA-Y, DATA-Z.
const OKADA: [[f64; 3]; 11] = [
    [10.0, 100.0, 21.0],
    [10.0, 102.0, 21.0],
    [20.0, 104.0, 40.0],
    [30.0, 110.0, 60.0],
    [50.0, 111.0, 90.0],
    [70.0, 119.0, 111.5],
    [90.0, 127.0, 130.0],
    [110.0, 130.3, 151.6],
    [130.0, 135.3, 166.0],
    [140.0, 138.0, 174.0],
    [150.0, 140.0, 180.0],
];

fn run(args: &[&str]) -> (Output, Vec<Vec<f64>>, serde_json::Value) {
    let scratch = crate::scratch_dir("fair-batten-");
    let dir = scratch.path();
    let input = dir.join("okada.csv");
    let text: String = std::iter::once("x,y,z\n".to_string())
        .chain(OKADA.iter().map(|r| format!("{},{},{}\n", r[0], r[1], r[2])))
        .collect();
    std::fs::write(&input, text).unwrap();
    let (out, report) = (dir.join("out.csv"), dir.join("report.json"));
    let output = Command::new(env!("CARGO_BIN_EXE_fair"))
        .arg("curve")
        .arg(&input)
        .args(["--method", "batten", "--quiet"])
        .args(args)
        .arg("-o")
        .arg(&out)
        .arg("--report")
        .arg(&report)
        .output()
        .unwrap();
    if !output.status.success() {
        return (output, Vec::new(), serde_json::Value::Null);
    }
    let rows = std::fs::read_to_string(&out)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse::<f64>().unwrap()).collect())
        .collect();
    let report = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    (output, rows, report)
}

fn assert_ok(output: &Output) {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

fn assert_bad(output: &Output, words: &[&str]) {
    assert_eq!(
        output.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let err = String::from_utf8_lossy(&output.stderr);
    for w in words {
        assert!(err.contains(w), "`{w}` not in {err}");
    }
}

/// Table 1's setting: fixed points and ends bit for bit, the others adjusted, the run stops by
/// the curvature-sign rule, and the report's curve is the Ferguson chain through the output
/// points (each segment's R_0 and R_0 + R_1 + R_2 + R_3 are its end points).
#[test]
fn okada_table_1_setting() {
    let (output, rows, report) = run(&["--fixed", "2,5,7"]);
    assert_ok(&output);
    assert_eq!(report["method"], "batten");
    // Issue 15: termination reasons in one kebab-case spelling for every method.
    assert_eq!(report["termination"], "strategy-done");
    assert!(report["iterations"].as_u64().unwrap() >= 2);
    for i in [0, 2, 5, 7, 10] {
        assert_eq!(rows[i], OKADA[i].to_vec(), "point {i}");
    }
    let moved: Vec<u64> = report["moved"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert_eq!(moved, vec![1, 3, 4, 6, 8, 9]);
    let segments = report["curve"]["segments"].as_array().unwrap();
    assert_eq!(segments.len(), 10);
    for (i, s) in segments.iter().enumerate() {
        let r: Vec<Vec<f64>> = serde_json::from_value(s.clone()).unwrap();
        for c in 0..3 {
            assert!((r[0][c] - rows[i][c]).abs() < 1e-9);
            let end = r[0][c] + r[1][c] + r[2][c] + r[3][c];
            assert!((end - rows[i + 1][c]).abs() < 1e-9 * (1.0 + end.abs()));
        }
    }
}

/// `--set range=R` bounds every move by R (Okada's adjustable ranges), as does `--tolerance`;
/// a prescribed tangent direction is accepted; bad values and options are refused.
#[test]
fn ranges_tangents_and_errors() {
    for args in [
        &["--set", "range=0.5"][..],
        &["--tolerance", "0.5"][..],
        &["--set", "range=0.5", "--set", "update=solve"][..],
        &["--set", "range=0.5", "--set", "update=jacobi"][..],
    ] {
        let (output, rows, report) = run(args);
        assert_ok(&output);
        assert!(report["m_d"].as_f64().unwrap() <= 0.5);
        let worst = rows
            .iter()
            .zip(OKADA.iter())
            .map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        assert!(worst <= 0.5 && worst > 0.0, "{worst}");
    }
    let (output, _, _) = run(&["--set", "tangent-directions=5:1,0.4,1"]);
    assert_ok(&output);
    assert_bad(
        &run(&["--set", "tangent-directions=5:1,0"]).0,
        &["tangent-directions", "components"],
    );
    assert_bad(
        &run(&["--set", "tangent-directions=50:1,0,0"]).0,
        &["tangent-directions", "past"],
    );
    assert_bad(
        &run(&["--set", "tangent-directions=5:1,0,0;5:0,1,0"]).0,
        &["tangent-directions", "twice"],
    );
    assert_bad(&run(&["--set", "range=-1"]).0, &["range"]);
    assert_bad(&run(&["--set", "update=newton"]).0, &["update"]);
    assert_bad(&run(&["--points", "3"]).0, &["--points"]);
    assert_bad(&run(&["--clamp-ends", "g1"]).0, &["--clamp-ends"]);
}
