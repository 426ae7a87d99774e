//! `fair curve --method strain-energy | kjellander | poliakoff` end to end through the binary:
//! automatic and interactive modes, `--fixed`, `--tolerance`, `--clamp-ends`, config files,
//! 2D and 3D, and clear errors.

use std::path::PathBuf;
use std::process::{Command, Output};

/// A fresh scratch directory for a test's files, removed when the returned guard is dropped.
fn temp_dir() -> tempfile::TempDir {
    crate::scratch_dir("fair-strain-energy-")
}

/// A noisy arc of `n` points (radius 10, pseudo-random noise 0.05), planar or lifted in z.
fn noisy_arc(n: usize, spatial: bool) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            let a = i as f64 * 0.1;
            let e = 0.05 * ((i as f64 * 12.9898).sin() * 43758.5453).fract();
            let mut row = vec![(10.0 + e) * a.cos(), (10.0 + e) * a.sin()];
            if spatial {
                row.push(0.3 * i as f64 + e);
            }
            row
        })
        .collect()
}

fn write_csv(dir: &std::path::Path, rows: &[Vec<f64>]) -> PathBuf {
    let header = if rows[0].len() == 3 { "x,y,z" } else { "x,y" };
    let mut text = format!("{header}\n");
    for r in rows {
        let cells: Vec<String> = r.iter().map(|v| format!("{v:?}")).collect();
        text.push_str(&cells.join(","));
        text.push('\n');
    }
    let path = dir.join("in.csv");
    std::fs::write(&path, text).unwrap();
    path
}

fn read_rows(path: &std::path::Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('x'))
        .map(|l| l.split(',').map(|x| x.trim().parse::<f64>().unwrap()).collect())
        .collect()
}

struct Run {
    output: Output,
    points: Vec<Vec<f64>>,
    report: serde_json::Value,
}

fn run(rows: &[Vec<f64>], args: &[&str]) -> Run {
    let scratch = temp_dir();
    let dir = scratch.path();
    let input = write_csv(dir, rows);
    let out = dir.join("out.csv");
    let report = dir.join("report.json");
    let output = Command::new(env!("CARGO_BIN_EXE_fair"))
        .arg("curve")
        .arg(&input)
        .args(args)
        .arg("--quiet")
        .arg("-o")
        .arg(&out)
        .arg("--report")
        .arg(&report)
        .output()
        .unwrap();
    let (points, report) = if output.status.success() {
        (
            read_rows(&out),
            serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap(),
        )
    } else {
        (Vec::new(), serde_json::Value::Null)
    };
    Run {
        output,
        points,
        report,
    }
}

fn ok(run: &Run) {
    assert!(
        run.output.status.success(),
        "{}",
        String::from_utf8_lossy(&run.output.stderr)
    );
}

fn bad(run: &Run, words: &[&str]) {
    assert_eq!(
        run.output.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&run.output.stderr)
    );
    let err = String::from_utf8_lossy(&run.output.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    for w in words {
        assert!(err.contains(w), "`{w}` not in {err}");
    }
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt()
}

fn energies(report: &serde_json::Value) -> (f64, f64) {
    (
        report["strain_energy_before"].as_f64().unwrap(),
        report["strain_energy_after"].as_f64().unwrap(),
    )
}

/// Automatic mode, 2D and 3D, all three names: the energy falls, the ends and `--fixed`
/// points are bit for bit the input's, `moved` lists exactly the points that differ.
#[test]
fn automatic_mode_lowers_energy_and_keeps_fixed_points() {
    for spatial in [false, true] {
        let rows = noisy_arc(40, spatial);
        for (method, parametrization) in [
            ("strain-energy", "chord-length"),
            ("kjellander", "uniform"),
            ("poliakoff", "chord-length"),
        ] {
            let r = run(
                &rows,
                &["--method", method, "--fixed", "5,20", "--kind", "parametric"],
            );
            ok(&r);
            assert_eq!(r.report["method"], method);
            assert_eq!(r.report["mode"], "automatic");
            assert_eq!(r.report["parametrization"], parametrization);
            assert_eq!(r.points.len(), rows.len());
            let (before, after) = energies(&r.report);
            assert!(after < before, "{method}: {after} >= {before}");
            for i in [0, 5, 20, 39] {
                assert_eq!(r.points[i], rows[i], "{method}: point {i} moved");
            }
            let differ: Vec<u64> = (0..rows.len())
                .filter(|&i| r.points[i] != rows[i])
                .map(|i| i as u64)
                .collect();
            let moved: Vec<u64> = r.report["moved"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_u64().unwrap())
                .collect();
            assert_eq!(moved, differ);
            assert!(!moved.is_empty());
            assert_eq!(r.report["curve"]["type"], "hermite");
            assert_eq!(r.report["curve"]["knots"].as_array().unwrap().len(), rows.len());
        }
    }
}

/// `--points` selects the interactive mode: only the named points move; two adjacent ones are
/// replaced together (Eq. 15), which puts them on the spline through the others, so the
/// third-derivative jumps there vanish and the energy falls.
#[test]
fn interactive_mode_moves_only_the_named_points() {
    let mut rows = noisy_arc(30, false);
    for i in [12, 13] {
        rows[i][0] *= 1.03;
        rows[i][1] *= 1.03;
    }
    let r = run(&rows, &["--method", "strain-energy", "--points", "12,13"]);
    ok(&r);
    assert_eq!(r.report["mode"], "interactive");
    assert_eq!(r.report["moved"], serde_json::json!([12, 13]));
    for i in (0..rows.len()).filter(|i| ![12, 13].contains(i)) {
        assert_eq!(r.points[i], rows[i]);
    }
    let (before, after) = energies(&r.report);
    assert!(after < before);
    assert_eq!(r.report["iterations"], 1);
}

/// `--tolerance D`: no point moves farther than D; the report's m_d agrees.
#[test]
fn tolerance_bounds_every_move() {
    let rows = noisy_arc(40, true);
    let r = run(
        &rows,
        &[
            "--method",
            "poliakoff",
            "--tolerance",
            "0.002",
            "--set",
            "radius-scale=10",
        ],
    );
    ok(&r);
    let worst = rows
        .iter()
        .zip(&r.points)
        .map(|(a, b)| distance(a, b))
        .fold(0.0, f64::max);
    assert!(worst <= 0.002 * (1.0 + 1e-12), "moved {worst}");
    assert!(worst > 0.0);
    assert!((r.report["m_d"].as_f64().unwrap() - worst).abs() < 1e-12);
}

/// `--clamp-ends g0` keeps the ends (the method never moves them); g1 and g2 are refused with
/// a one-line message naming the option.
#[test]
fn clamp_ends() {
    let rows = noisy_arc(20, false);
    let r = run(&rows, &["--method", "kjellander", "--clamp-ends", "g0"]);
    ok(&r);
    assert_eq!(r.points[0], rows[0]);
    assert_eq!(r.points[19], rows[19]);
    for clamp in ["g1", "g2"] {
        bad(
            &run(&rows, &["--method", "strain-energy", "--clamp-ends", clamp]),
            &["--clamp-ends", clamp],
        );
    }
}

/// Parameters from a config file (top level and the method's table) and `--set`: they reach
/// the strategy (an energy tolerance of 0.5 from the file's method table stops the run far
/// earlier than 0; `max-iterations` caps it) and a bad value names the file and line.
#[test]
fn config_file_parameters() {
    let rows = noisy_arc(40, false);
    let scratch = temp_dir();
    let config = scratch.path().join("se.toml");
    std::fs::write(
        &config,
        "max-iterations = 100000\n[strain-energy]\nenergy-tolerance = 0.5\n",
    )
    .unwrap();
    let r = run(
        &rows,
        &["--method", "strain-energy", "--config", config.to_str().unwrap()],
    );
    ok(&r);
    let full = run(
        &rows,
        &["--method", "strain-energy", "--set", "energy-tolerance=0"],
    );
    ok(&full);
    let (coarse, fine) = (
        r.report["iterations"].as_u64().unwrap(),
        full.report["iterations"].as_u64().unwrap(),
    );
    assert!(
        coarse < fine,
        "energy-tolerance from the file not applied: {coarse} vs {fine}"
    );
    // Issue 15: termination reasons in one kebab-case spelling for every method.
    assert_eq!(r.report["termination"], "strategy-done");
    let limited = run(&rows, &["--method", "strain-energy", "--set", "max-iterations=3"]);
    ok(&limited);
    assert_eq!(limited.report["iterations"], 3);
    assert_eq!(limited.report["termination"], "max-iterations");
    let iterated = run(
        &rows,
        &[
            "--method",
            "strain-energy",
            "--set",
            "replacement=iterated",
            "--set",
            "pairs=on",
        ],
    );
    ok(&iterated);
    let (b, a) = energies(&iterated.report);
    assert!(a < b);
    std::fs::write(&config, "[strain-energy]\n\nenergy-tolerance = -1\n").unwrap();
    bad(
        &run(
            &rows,
            &["--method", "strain-energy", "--config", config.to_str().unwrap()],
        ),
        &["se.toml:3", "energy-tolerance"],
    );
    bad(
        &run(&rows, &["--method", "poliakoff", "--set", "pairs=maybe"]),
        &["pairs"],
    );
    bad(
        &run(
            &rows,
            &["--method", "kjellander", "--set", "parametrization=uniform"],
        ),
        &["parametrization"],
    );
}

/// Interactive bad points must be interior; indices past the end are refused too.
#[test]
fn bad_points_are_refused() {
    let rows = noisy_arc(10, false);
    bad(
        &run(&rows, &["--method", "strain-energy", "--points", "0"]),
        &["--points", "end point"],
    );
    bad(
        &run(&rows, &["--method", "strain-energy", "--points", "9"]),
        &["--points"],
    );
    bad(
        &run(&rows, &["--method", "strain-energy", "--points", "10"]),
        &["--points"],
    );
}
