//! `fair surface --join EDGE=FILE[:G]` end to end (issue 46): two halves of one noisy
//! surface, the second faired joined to the first (a grid file or a STEP file); the report's
//! `joins` before and after; the neighbour's file unchanged; what is refused.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn fair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .output()
        .unwrap()
}

/// Deterministic noise in [−1, 1].
fn noise(i: usize, j: usize, s: usize) -> f64 {
    let t = ((i * 7919 + j * 104_729 + s * 1_299_709) as f64 * 12.9898).sin() * 43_758.545_3;
    2.0 * (t - t.floor()) - 1.0
}

/// A noisy half of one smooth surface over x ∈ [x0, x1] × y ∈ [0, 1] (metres × 10), as
/// `i,j,x,y,z`.
fn write_half(dir: &Path, name: &str, x0: f64, x1: f64, columns: usize, seed: usize) -> PathBuf {
    let mut text = String::from("i,j,x,y,z\n");
    for i in 0..14 {
        for j in 0..columns {
            let x = x0 + (x1 - x0) * i as f64 / 13.0;
            let y = j as f64 / (columns - 1) as f64;
            let z = 0.3 * (x - 0.4).powi(2) + 0.15 * (3.0 * y).sin() * (1.0 + x);
            let p = [
                x + 0.003 * noise(i, j, seed),
                y + 0.003 * noise(i, j, seed + 1),
                z + 0.003 * noise(i, j, seed + 2),
            ];
            text.push_str(&format!(
                "{i},{j},{},{},{}\n",
                p[0] * 10.0,
                p[1] * 10.0,
                p[2] * 10.0
            ));
        }
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn report(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn ok(out: &Output) {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

fn refused(out: &Output, expected: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(expected), "{stderr}");
}

/// The first half faired (jump-lsq) to `first.csv`, the second half's raw grid.
fn halves(dir: &Path) -> (PathBuf, PathBuf) {
    let raw = write_half(dir, "first-raw.csv", 0.0, 0.5, 17, 1);
    let first = dir.join("first.csv");
    ok(&fair(&[
        "surface",
        s(&raw),
        "--method",
        "jump-lsq",
        "-q",
        "-o",
        s(&first),
    ]));
    (first, write_half(dir, "second.csv", 0.5, 1.0, 17, 11))
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn surface_join_g1_to_a_grid_holds_the_tangent_plane_and_leaves_the_neighbour() {
    let dir = crate::scratch_dir("fair-surface-join-");
    let (first, second) = halves(dir.path());
    let bytes = std::fs::read(&first).unwrap();
    let (out, rep) = (dir.path().join("out.csv"), dir.path().join("out.json"));
    let join = format!("u0={}", s(&first));
    ok(&fair(&[
        "surface",
        s(&second),
        "--join",
        &join,
        "-q",
        "-o",
        s(&out),
        "--report",
        s(&rep),
    ]));
    assert_eq!(
        std::fs::read(&first).unwrap(),
        bytes,
        "the neighbour's file is untouched"
    );
    let r = report(&rep);
    assert_eq!(r["method"], "jump-lsq");
    let j = &r["joins"][0];
    assert_eq!(
        (j["edge"].as_str(), j["continuity"].as_str()),
        (Some("u0"), Some("g1")),
        "{j}"
    );
    assert_eq!(j["neighbour_edge"], "u1");
    let (before, after) = (&j["before"], &j["after"]);
    assert!(before["angle_degrees"].as_f64().unwrap() > 0.5, "{j}");
    assert!(before["gap"].as_f64().unwrap() > 0.01, "{j}");
    assert!(after["gap"].as_f64().unwrap() <= 1e-12 * 10.0, "{j}");
    assert!(after["angle_degrees"].as_f64().unwrap() <= 1e-9, "{j}");
    assert!(after["curvature_jump"].as_f64().unwrap() <= 1e-9, "{j}");
    // The faired edge row is the neighbour's last row, to the output's printed digits.
    let rows = |p: &Path| -> Vec<Vec<f64>> {
        std::fs::read_to_string(p)
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(|x| x.trim().parse().unwrap()).collect())
            .collect()
    };
    let (a, b) = (rows(&first), rows(&out));
    for j in 0..17 {
        let (p, q) = (&a[13 * 17 + j], &b[j]);
        for c in 2..5 {
            assert!((p[c] - q[c]).abs() <= 1e-12 * 10.0, "node {j}: {p:?} vs {q:?}");
        }
    }
}

#[test]
fn surface_join_g1_to_a_step_surface() {
    let dir = crate::scratch_dir("fair-surface-join-step-");
    let (first, second) = halves(dir.path());
    let step = dir.path().join("first.step");
    ok(&fair(&[
        "surface",
        s(&first),
        "--method",
        "jump-lsq",
        "--set",
        "lambda=0",
        "-q",
        "-o",
        s(&step),
    ]));
    let bytes = std::fs::read(&step).unwrap();
    let rep = dir.path().join("out.json");
    let join = format!("u0={}:g1", s(&step));
    ok(&fair(&[
        "surface",
        s(&second),
        "--join",
        &join,
        "-q",
        "-o",
        s(&dir.path().join("o.csv")),
        "--report",
        s(&rep),
    ]));
    assert_eq!(std::fs::read(&step).unwrap(), bytes);
    let j = &report(&rep)["joins"][0];
    assert!(j["before"]["angle_degrees"].as_f64().unwrap() > 0.5, "{j}");
    assert!(j["after"]["angle_degrees"].as_f64().unwrap() <= 0.01, "{j}");
    assert!(j["after"]["gap"].as_f64().unwrap() <= 1e-9, "{j}");
}

#[test]
fn surface_join_refusals_exit_2_with_the_reason() {
    let dir = crate::scratch_dir("fair-surface-join-bad-");
    let (first, second) = halves(dir.path());
    let narrow = write_half(dir.path(), "narrow.csv", 0.0, 0.5, 12, 3);
    let join = |text: &str| format!("{text}={}", s(&first));
    let mismatch = format!("u0={}", s(&narrow));
    refused(
        &fair(&["surface", s(&second), "--join", &mismatch]),
        "no edge of the neighbour",
    );
    refused(
        &fair(&["surface", s(&second), "--join", &join("x0")]),
        "not an edge",
    );
    refused(
        &fair(&[
            "surface",
            s(&second),
            "--join",
            &join("u0"),
            "--method",
            "zhang-cheng",
        ]),
        "holds no edge",
    );
    refused(
        &fair(&["surface", s(&second), "--join", &join("u0"), "--clamp-ends", "g0"]),
        "lies on the joined edge u0",
    );
    refused(
        &fair(&["surface", s(&second), "--join", &join("u0"), "--tolerance", "0.1"]),
        "tolerance band",
    );
    let missing = format!("u0={}", s(&dir.path().join("missing.csv")));
    refused(&fair(&["surface", s(&second), "--join", &missing]), "missing.csv");
    refused(&fair(&["curve", s(&second), "--join", &join("u0")]), "--join");
}
