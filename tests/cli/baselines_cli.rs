//! `fair curve --method smoothing-spline | sapidis-farin` end to end: exit status, the
//! report's fields (p and the rule that chose it; the knot history), fixed points unchanged,
//! the tolerance band kept, bad parameters refused with status 2.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn data(relative: &str) -> String {
    format!("{}/data/{relative}", env!("CARGO_MANIFEST_DIR"))
}

fn read_rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with(|c: char| c.is_alphabetic()))
        .map(|l| l.split(',').map(|x| x.trim().parse::<f64>().unwrap()).collect())
        .collect()
}

/// Runs `fair curve INPUT --method M ARGS -o OUT --report REPORT`; returns the output, the
/// faired rows and the report (when it succeeded).
fn fair(input: &Path, method: &str, args: &[&str], tag: &str) -> (Output, Vec<Vec<f64>>, serde_json::Value) {
    let scratch = crate::scratch_dir("fair-baselines-");
    let dir = scratch.path();
    let output = dir.join(format!("{tag}.csv"));
    let report = dir.join(format!("{tag}.json"));
    let result = Command::new(env!("CARGO_BIN_EXE_fair"))
        .arg("curve")
        .arg(input)
        .args(["--method", method, "--quiet"])
        .args(args)
        .arg("-o")
        .arg(&output)
        .arg("--report")
        .arg(&report)
        .output()
        .unwrap();
    if !result.status.success() {
        return (result, Vec::new(), serde_json::Value::Null);
    }
    let rows = read_rows(&output);
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    (result, rows, report)
}

fn airfoil() -> PathBuf {
    PathBuf::from(data("airfoil_naca2412/naca2412_upper.csv"))
}

fn assert_ok(output: &Output) {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// A noisy helix written as x,y,z CSV in `dir`.
fn helix(dir: &Path, tag: &str) -> PathBuf {
    let path = dir.join(format!("helix-{tag}.csv"));
    let mut text = String::from("x,y,z\n");
    for k in 0..60 {
        let s = k as f64 * 0.2;
        let e = ((k as f64 * 12.9898).sin() * 43758.5453).rem_euclid(1.0) - 0.5;
        text.push_str(&format!(
            "{},{},{}\n",
            2.0 * s.cos() + 0.02 * e,
            2.0 * s.sin() - 0.02 * e,
            0.3 * s
        ));
    }
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn smoothing_spline_gcv_keeps_fixed_points_and_reports_p() {
    let input = airfoil();
    let (out, rows, report) = fair(
        &input,
        "smoothing-spline",
        &["--fixed", "3,9", "--set", "rule=gcv"],
        "ss-gcv",
    );
    assert_ok(&out);
    let original = read_rows(&input);
    assert_eq!(rows.len(), original.len());
    for k in [3, 9] {
        assert_eq!(rows[k], original[k], "fixed point {k}");
    }
    assert_eq!(report["method"], "smoothing-spline");
    assert_eq!(report["kind"], "function");
    assert_eq!(report["rule"], "gcv");
    let p = report["p"].as_f64().unwrap();
    assert!(p > 0.0 && p < 1.0, "{p}");
    assert!(report["gcv"].as_f64().unwrap() > 0.0);
    let moved: Vec<u64> = report["moved"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert!(!moved.contains(&3) && !moved.contains(&9) && !moved.is_empty());
    // x is kept for a function.
    for (a, b) in rows.iter().zip(&original) {
        assert_eq!(a[0], b[0]);
    }
    assert_eq!(report["curve"]["type"], "natural-cubic-spline");
}

#[test]
fn smoothing_spline_trace_rule_is_csaps_formula() {
    let input = airfoil();
    let (out, _, report) = fair(&input, "smoothing-spline", &["--set", "rule=trace"], "ss-trace");
    assert_ok(&out);
    assert_eq!(report["rule"], "trace");
    // p = 1/(1 + tr R / tr QᵀQ) from the x values, computed here from the definitions.
    let x: Vec<f64> = read_rows(&input).iter().map(|r| r[0]).collect();
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let tr_r: f64 = h.windows(2).map(|w| (w[0] + w[1]) / 3.0).sum();
    let tr_b: f64 = h
        .windows(2)
        .map(|w| (1.0 / w[0]).powi(2) + (1.0 / w[0] + 1.0 / w[1]).powi(2) + (1.0 / w[1]).powi(2))
        .sum();
    let expected = 1.0 / (1.0 + tr_r / tr_b);
    let p = report["p"].as_f64().unwrap();
    assert!((p - expected).abs() < 1e-12, "{p} vs {expected}");
}

#[test]
fn smoothing_spline_p_one_interpolates_and_bad_p_exits_2() {
    let input = airfoil();
    let (out, rows, report) = fair(&input, "smoothing-spline", &["--set", "p=1"], "ss-one");
    assert_ok(&out);
    assert_eq!(rows, read_rows(&input));
    assert_eq!(report["rule"], "given");
    assert_eq!(report["p"].as_f64(), Some(1.0));
    assert!(report["moved"].as_array().unwrap().is_empty());
    let (out, _, _) = fair(&input, "smoothing-spline", &["--set", "p=1.5"], "ss-bad");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("[0, 1]"));
}

#[test]
fn smoothing_spline_parametric_3d_with_tolerance() {
    let scratch = crate::scratch_dir("fair-baselines-");
    let input = helix(scratch.path(), "tolerance");
    let tolerance = 0.004;
    let (out, rows, report) = fair(
        &input,
        "smoothing-spline",
        &[
            "--tolerance",
            &tolerance.to_string(),
            "--clamp-ends",
            "g0",
            "--set",
            "p=0.5",
        ],
        "ss-helix",
    );
    assert_ok(&out);
    assert_eq!(report["kind"], "parametric");
    let original = read_rows(&input);
    assert_eq!(rows[0], original[0]);
    assert_eq!(rows[59], original[59]);
    for (a, b) in rows.iter().zip(&original) {
        let d: f64 = a.iter().zip(b).map(|(u, v)| (u - v).powi(2)).sum::<f64>().sqrt();
        // The CSV round trip prints round-trip decimals: the band holds as written.
        assert!(d <= tolerance * (1.0 + 1e-12), "{d}");
    }
    assert!(report["reweights"].as_u64().unwrap() > 0, "the band was active");
}

#[test]
fn sapidis_farin_keeps_fixed_points_and_lowers_the_largest_jump() {
    let scratch = crate::scratch_dir("fair-baselines-");
    let input = helix(scratch.path(), "fixed");
    let (out, rows, report) = fair(
        &input,
        "sapidis-farin",
        &["--fixed", "10,30", "--set", "max-iterations=150"],
        "sf-helix",
    );
    assert_ok(&out);
    let original = read_rows(&input);
    for k in [10, 30] {
        assert_eq!(rows[k], original[k]);
    }
    assert_eq!(report["method"], "sapidis-farin");
    let before = report["max_jump_before"].as_f64().unwrap();
    let after = report["max_jump_after"].as_f64().unwrap();
    assert!(after < before, "{after} >= {before}");
    let faired = report["knots_faired"].as_u64().unwrap();
    assert!(faired > 0 && faired <= 150);
    assert_eq!(report["iterations"].as_u64(), Some(faired));
    assert_eq!(report["steps"].as_array().unwrap().len() as u64, faired);
    // Issue 15: one `termination` field for every method (Sapidis–Farin wrote `stop`).
    assert!(["jump-reduction", "max-iterations", "no-candidate"]
        .contains(&report["termination"].as_str().unwrap()));
    assert!(report.get("stop").is_none());
    assert_eq!(report["curve"]["type"], "nurbs");
}

#[test]
fn sapidis_farin_bad_parameter_exits_2() {
    let scratch = crate::scratch_dir("fair-baselines-");
    let (out, _, _) = fair(
        &helix(scratch.path(), "bad"),
        "sapidis-farin",
        &["--set", "jump-reduction=-1"],
        "sf-bad",
    );
    assert_eq!(out.status.code(), Some(2));
    let (out, _, _) = fair(
        &helix(scratch.path(), "bad2"),
        "sapidis-farin",
        &["--set", "max-iterations=many"],
        "sf-bad2",
    );
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn sapidis_farin_on_a_function_keeps_x() {
    let input = airfoil();
    let (out, rows, report) = fair(
        &input,
        "sapidis-farin",
        &["--fixed", "4", "--set", "max-iterations=40"],
        "sf-airfoil",
    );
    assert_ok(&out);
    assert_eq!(report["kind"], "function");
    assert_eq!(report["curve"]["parametrization"], "x");
    let original = read_rows(&input);
    assert_eq!(rows[4], original[4]);
    for (a, b) in rows.iter().zip(&original) {
        assert_eq!(a[0], b[0]);
    }
    assert!(!report["moved"].as_array().unwrap().is_empty());
}

#[test]
fn end_clamps_the_methods_cannot_honour_exit_2_and_those_they_can_are_kept() {
    let input = airfoil();
    let (out, _, _) = fair(&input, "smoothing-spline", &["--clamp-ends", "g1"], "ss-g1");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--clamp-ends") && stderr.contains("g1"),
        "{stderr}"
    );
    // Sapidis-Farin keeps G2 ends: end points unchanged, first and last knots never faired.
    let scratch = crate::scratch_dir("fair-baselines-");
    let spiral = helix(scratch.path(), "g2");
    let (out, rows, report) = fair(
        &spiral,
        "sapidis-farin",
        &["--clamp-ends", "g2", "--set", "max-iterations=50"],
        "sf-g2",
    );
    assert_ok(&out);
    let original = read_rows(&spiral);
    assert_eq!(rows[0], original[0]);
    assert_eq!(rows[59], original[59]);
    let knots: Vec<f64> = report["curve"]["knots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let (first, last) = (knots[4], knots[knots.len() - 5]);
    for step in report["steps"].as_array().unwrap() {
        let k = step["knot"].as_f64().unwrap();
        assert!(k != first && k != last, "end knot {k} faired under g2");
    }
}

/// A closed polygon given with its first point repeated at the end stays closed: the
/// smoothing spline (not periodic) would move the two copies apart, so it keeps both.
#[test]
fn smoothing_spline_keeps_a_repeated_end_point_closed() {
    let scratch = crate::scratch_dir("fair-baselines-");
    let path = scratch.path().join("closed-input.csv");
    let mut rows: Vec<String> = (0..24)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 24.0;
            let wobble = if k % 3 == 1 { 0.03 } else { 0.0 };
            format!("{},{}", (1.0 + wobble) * t.cos(), (1.0 + wobble) * t.sin())
        })
        .collect();
    rows.push(rows[0].clone());
    std::fs::write(&path, format!("x,y\n{}\n", rows.join("\n"))).unwrap();
    let (out, faired, _) = fair(
        &path,
        "smoothing-spline",
        &["--kind", "parametric", "--set", "p=0.5"],
        "closed",
    );
    assert_ok(&out);
    let original = read_rows(&path);
    assert_eq!(faired[0], original[0]);
    assert_eq!(faired[24], original[24]);
    assert!(
        faired.iter().zip(&original).any(|(a, b)| a != b),
        "nothing was smoothed"
    );
}

/// `--points` names bad points for the interactive methods; the others refuse it rather than
/// ignore it, and nurbs-weights refuses the end clamps its weights cannot hold.
#[test]
fn options_a_method_cannot_use_exit_2() {
    let input = airfoil();
    for (method, args, named) in [
        ("two-phase", vec!["--points", "3"], "--points"),
        ("smoothing-spline", vec!["--points", "3"], "--points"),
        ("sapidis-farin", vec!["--points", "3"], "--points"),
        ("nurbs-weights", vec!["--points", "3"], "--points"),
        ("nurbs-weights", vec!["--clamp-ends", "g1"], "--clamp-ends"),
        ("nurbs-weights", vec!["--clamp-ends", "g2"], "--clamp-ends"),
        // Parameters of the arbitrary-curve pipeline are checked on function input too.
        ("two-phase", vec!["--set", "segment-passes=abc"], "segment-passes"),
        (
            "two-phase",
            vec!["--set", "turning-limit=-5"],
            "turning-limit = -5 is out of range: a number in (0, 180]",
        ),
        (
            "two-phase",
            vec!["--set", "max-passes=0"],
            "`two-phase`: max-passes = 0 is out of range: an integer ≥ 1",
        ),
        (
            "two-phase",
            vec!["--set", "max-passes=2.5"],
            "max-passes = 2.5: expected an integer ≥ 1",
        ),
        (
            "zhang-cheng",
            vec![],
            "--method: `zhang-cheng` is a surface method and the input is a curve",
        ),
    ] {
        let (out, _, _) = fair(&input, method, &args, "refused");
        assert_eq!(out.status.code(), Some(2), "{method} {args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(stderr.contains(named), "{method} {args:?}: {stderr}");
    }
    // What the method can keep it keeps: g0 (the points never move).
    let (out, rows, _) = fair(
        &input,
        "nurbs-weights",
        &["--clamp-ends", "g0", "--set", "max-iterations=20"],
        "g0",
    );
    assert_ok(&out);
    assert_eq!(rows, read_rows(&input));
}
