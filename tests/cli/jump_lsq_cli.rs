//! `fair curve --method jump-lsq` end to end: a noisy curve is faired closer to its clean
//! twin, the report's extras say λ, σ̂ and the rule, `--set` overrides the rule, fixed points
//! and the band hold for a 3D curve, a closed polygon stays closed, bad values exit 2.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn read_rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with(|c: char| c.is_alphabetic()))
        .map(|l| l.split(',').map(|x| x.trim().parse::<f64>().unwrap()).collect())
        .collect()
}

/// Runs `fair curve INPUT --method jump-lsq ARGS -o OUT --report REPORT`.
fn fair(input: &Path, args: &[&str], tag: &str) -> (Output, Vec<Vec<f64>>, serde_json::Value) {
    let scratch = crate::scratch_dir("fair-jump-lsq-");
    let dir = scratch.path();
    let output = dir.join(format!("{tag}.csv"));
    let report = dir.join(format!("{tag}.json"));
    let result = Command::new(env!("CARGO_BIN_EXE_fair"))
        .arg("curve")
        .arg(input)
        .args(["--method", "jump-lsq", "--quiet"])
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

fn assert_ok(output: &Output) {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Deterministic noise of unit standard deviation (sum of four hashed uniforms).
fn noise(k: usize) -> f64 {
    let uniform = |j: usize| ((j as f64 * 12.9898).sin() * 43758.5453).rem_euclid(1.0);
    ((0..4).map(|j| uniform(4 * k + j + 7)).sum::<f64>() - 2.0) * 3f64.sqrt()
}

const SIGMA: f64 = 0.01;

/// y = sin 3x over [0, 6] at 300 points, clean and with noise of standard deviation 0.01 (the
/// noisy one written in `dir`).
/// (Not sin x: over [0, 6] that is so close to a spline with jumps linear in the knot index,
/// the method's null space, that even λ → ∞ moves the points by less than the noise.)
fn sine(dir: &Path) -> (PathBuf, Vec<[f64; 2]>) {
    let clean: Vec<[f64; 2]> = (0..300)
        .map(|k| {
            let x = 6.0 * k as f64 / 299.0;
            [x, (3.0 * x).sin()]
        })
        .collect();
    let path = dir.join("sine.csv");
    let mut text = String::from("x,y\n");
    for (k, p) in clean.iter().enumerate() {
        text.push_str(&format!("{},{}\n", p[0], p[1] + SIGMA * noise(k)));
    }
    std::fs::write(&path, text).unwrap();
    (path, clean)
}

fn rms_to(rows: &[Vec<f64>], clean: &[[f64; 2]]) -> f64 {
    (rows
        .iter()
        .zip(clean)
        .map(|(r, c)| (r[1] - c[1]).powi(2))
        .sum::<f64>()
        / rows.len() as f64)
        .sqrt()
}

#[test]
fn a_noisy_function_is_faired_closer_to_its_clean_twin() {
    let scratch = crate::scratch_dir("fair-jump-lsq-");
    let (input, clean) = sine(scratch.path());
    let original = read_rows(&input);
    let (out, rows, report) = fair(&input, &["--set", "rule=discrepancy"], "sine");
    assert_ok(&out);
    assert_eq!(report["method"], "jump-lsq");
    assert_eq!(report["kind"], "function");
    assert_eq!(report["rule"], "discrepancy");
    let sigma = report["sigma"].as_f64().unwrap();
    assert!((0.7 * SIGMA..1.4 * SIGMA).contains(&sigma), "σ̂ = {sigma}");
    assert!(report["lambda"].as_f64().unwrap() > 0.0);
    assert_eq!(report["lambda_limited"], false);
    // The discrepancy principle: RMS displacement = σ̂ (Morozov's; no factor to set).
    assert!(
        report["params"].get("noise-factor").is_none(),
        "{}",
        report["params"]
    );
    let rms = report["rms_displacement"].as_f64().unwrap();
    assert!((rms / sigma - 1.0).abs() < 1e-3, "{rms} vs σ̂ = {sigma}");
    for (a, b) in rows.iter().zip(&original) {
        assert_eq!(a[0], b[0], "x never changes");
    }
    let (before, after) = (rms_to(&original, &clean), rms_to(&rows, &clean));
    // Closer to the truth than the noisy input (measured: 0.0098 → 0.0059).
    assert!(after < before, "RMS to the clean sine {before} → {after}");
    assert!(report["penalty_after"].as_f64().unwrap() < report["penalty_before"].as_f64().unwrap());
}

#[test]
fn set_overrides_the_rule_and_bad_values_exit_2() {
    let scratch = crate::scratch_dir("fair-jump-lsq-");
    let (input, _) = sine(scratch.path());
    let original = read_rows(&input);
    let (out, rows, report) = fair(&input, &["--set", "lambda=0"], "given");
    assert_ok(&out);
    assert_eq!(report["rule"], "given");
    assert_eq!(report["lambda"].as_f64(), Some(0.0));
    assert_eq!(rows, original, "λ = 0 returns the input");
    let (out, _, report) = fair(&input, &["--set", "rule=gcv"], "gcv");
    assert_ok(&out);
    assert_eq!(report["rule"], "gcv");
    assert!(report["gcv"].as_f64().unwrap() > 0.0);
    assert_eq!(report["ends"], serde_json::json!(["runout", "runout"]));
    // `function-ends` = auto reports the pair it chose, whose GCV score is no higher than
    // the default runout pair's (runout is one of the four it compares).
    let (out, _, auto) = fair(
        &input,
        &["--set", "rule=gcv", "--set", "function-ends=auto"],
        "auto",
    );
    assert_ok(&out);
    let ends = auto["ends"].as_array().unwrap();
    assert_eq!(ends.len(), 2);
    assert!(ends.iter().all(|e| e == "runout" || e == "natural"), "{ends:?}");
    assert!(auto["gcv"].as_f64().unwrap() <= report["gcv"].as_f64().unwrap());
    // `difference-order` = auto (the default) reports the order it chose, whose GCV score is
    // no higher than d = 1's (one of the three it compares).
    assert_eq!(report["params"]["difference-order"], "auto");
    let d = report["difference_order"].as_u64().unwrap();
    assert!((1..=3).contains(&d), "{d}");
    let (out, _, one) = fair(
        &input,
        &["--set", "rule=gcv", "--set", "difference-order=1"],
        "order",
    );
    assert_ok(&out);
    assert_eq!(one["difference_order"], 1);
    assert!(report["gcv"].as_f64().unwrap() <= one["gcv"].as_f64().unwrap());
    // `exponent` = auto reports the exponent it used: on these evenly spaced x, 8 (the
    // default) without a search, the same fit.
    assert_eq!(report["exponent"], 8.0);
    let (out, _, spaced) = fair(
        &input,
        &["--set", "rule=gcv", "--set", "exponent=auto"],
        "exponent",
    );
    assert_ok(&out);
    assert_eq!(spaced["params"]["exponent"], "auto");
    assert_eq!(spaced["exponent"], 8.0);
    assert_eq!(spaced["gcv"], report["gcv"]);
    let (out, _, report) = fair(&input, &["--set", "target-sd=0.005"], "target");
    assert_ok(&out);
    assert_eq!(report["rule"], "target-sd");
    assert!((report["rms_displacement"].as_f64().unwrap() / 0.005 - 1.0).abs() < 1e-3);
    for bad in [
        "lambda=-1",
        "exponent=20",
        "exponent=-1",
        "exponent=some",
        "rule=oracle",
        "difference-order=7",
        "difference-order=1.5",
        "difference-order=some",
        "function-ends=maybe",
        // Private constants of the method, not settings.
        "noise-factor=1.5",
        "gcv-gamma=1.4",
        "end-jumps=2",
        "end-weight=100",
    ] {
        let (out, _, _) = fair(&input, &["--set", bad], "bad");
        assert_eq!(out.status.code(), Some(2), "{bad}");
    }
}

#[test]
fn a_3d_curve_keeps_fixed_points_and_the_band_and_a_closed_polygon_stays_closed() {
    let scratch = crate::scratch_dir("fair-jump-lsq-");
    let path = scratch.path().join("helix.csv");
    let mut text = String::from("x,y,z\n");
    for k in 0..80 {
        let s = k as f64 * 0.15;
        text.push_str(&format!(
            "{},{},{}\n",
            2.0 * s.cos() + 0.02 * noise(3 * k),
            2.0 * s.sin() + 0.02 * noise(3 * k + 1),
            0.3 * s + 0.02 * noise(3 * k + 2)
        ));
    }
    std::fs::write(&path, text).unwrap();
    let tolerance = 0.01;
    let (out, rows, report) = fair(
        &path,
        &[
            "--fixed",
            "10,40",
            "--tolerance",
            &tolerance.to_string(),
            "--clamp-ends",
            "g1",
        ],
        "helix",
    );
    assert_ok(&out);
    assert_eq!(report["kind"], "parametric");
    let original = read_rows(&path);
    for k in [0, 10, 40, 79] {
        assert_eq!(rows[k], original[k]);
    }
    for (a, b) in rows.iter().zip(&original) {
        let d: f64 = a.iter().zip(b).map(|(u, v)| (u - v).powi(2)).sum::<f64>().sqrt();
        assert!(d <= tolerance * (1.0 + 1e-12), "{d}");
    }
    assert!(report["pinned"].as_u64().unwrap() + report["reweighted"].as_u64().unwrap() > 0);

    // A noisy circle given with its first point repeated: periodic, and closed afterwards.
    let path = scratch.path().join("circle.csv");
    let mut text = String::from("x,y\n");
    let n = 60;
    for k in 0..=n {
        let a = std::f64::consts::TAU * (k % n) as f64 / n as f64;
        let r = 1.0 + 0.01 * noise(k % n);
        text.push_str(&format!("{},{}\n", r * a.cos(), r * a.sin()));
    }
    std::fs::write(&path, text).unwrap();
    let (out, rows, report) = fair(&path, &["--kind", "parametric"], "circle");
    assert_ok(&out);
    assert_eq!(report["closed"], true);
    assert_eq!(rows.len(), n + 1);
    assert_eq!(rows[0], rows[n]);
    let radius = |r: &Vec<f64>| (r[0] * r[0] + r[1] * r[1]).sqrt();
    let spread = |rs: &[Vec<f64>]| rs.iter().map(|r| (radius(r) - 1.0).abs()).fold(0.0, f64::max);
    assert!(
        spread(&rows) < 0.6 * spread(&original),
        "{} → {}",
        spread(&original),
        spread(&rows)
    );
    let (out, _, _) = fair(
        &path,
        &["--kind", "parametric", "--clamp-ends", "g1"],
        "circle-clamped",
    );
    assert_eq!(out.status.code(), Some(2));
}

/// `--corners` on the closed R140 airfoil (`data/airfoil_r140/r140.csv`, its sharp trailing
/// edge first and last): by default the trailing edge is found, kept bit for bit, the chord
/// keeps its length and the curve stays closed; with `--corners none` the fit rounds the edge
/// (the point moves); a malformed list and an index past the last point exit 2 naming
/// `--corners`.
#[test]
fn the_trailing_edge_stays_a_corner() {
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/airfoil_r140/r140.csv");
    let points = read_rows(&input);
    let n = points.len();
    let (result, faired, report) = fair(&input, &[], "corners");
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let corners = report["corners"].as_array().expect("corners in the report");
    assert!(corners.contains(&serde_json::json!(0)), "{corners:?}");
    assert_eq!(faired[0], points[0], "the trailing edge moved");
    assert_eq!(faired[n - 1], faired[0], "the curve was opened");
    // The report's curve (and so a CAD file) breaks there: one Ferguson segment per span, the
    // first leaving the edge and the last arriving at it in directions far apart.
    let segments = report["curve"]["segments"].as_array().expect("Ferguson segments");
    assert_eq!(report["curve"]["type"], "ferguson");
    assert_eq!(segments.len(), n - 1);
    let coefficient = |s: &serde_json::Value, k: usize| -> Vec<f64> {
        s[k].as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    // Each segment is its span of the pieces' splines: P(0) = a0 the span's first faired point,
    // P(1) = a0 + a1 + a2 + a3 the next.
    for (k, segment) in segments.iter().enumerate() {
        let end: Vec<f64> = (0..2)
            .map(|c| (0..4).map(|j| coefficient(segment, j)[c]).sum())
            .collect();
        for c in 0..2 {
            assert_eq!(
                coefficient(segment, 0)[c],
                faired[k][c],
                "segment {k} starts off its point"
            );
            assert!(
                (end[c] - faired[k + 1][c]).abs() < 1e-12,
                "segment {k} ends at {end:?}, not {:?}",
                faired[k + 1]
            );
        }
    }
    let leaving = coefficient(&segments[0], 1);
    let last = &segments[n - 2];
    // P'(1) = a1 + 2 a2 + 3 a3.
    let arriving: Vec<f64> = (0..2)
        .map(|c| coefficient(last, 1)[c] + 2.0 * coefficient(last, 2)[c] + 3.0 * coefficient(last, 3)[c])
        .collect();
    let cosine = (leaving[0] * arriving[0] + leaving[1] * arriving[1])
        / (leaving[0].hypot(leaving[1]) * arriving[0].hypot(arriving[1]));
    assert!(
        cosine < 0.0,
        "the edge is smooth in the report's curve: cos = {cosine}"
    );
    let (_, rounded, report) = fair(&input, &["--corners", "none"], "no-corners");
    assert!(report["corners"].is_null(), "{}", report["corners"]);
    assert_ne!(rounded[0], points[0], "without corners the edge is kept anyway");
    for bad in ["1;2", &format!("{n}")] {
        let (result, ..) = fair(&input, &["--corners", bad], "bad");
        assert_eq!(result.status.code(), Some(2), "--corners {bad}");
        assert!(
            String::from_utf8_lossy(&result.stderr).contains("--corners"),
            "{}",
            String::from_utf8_lossy(&result.stderr)
        );
    }
}
