//! `fair surface --method zhang-cheng | kjellander` end to end: the grid comes back the same
//! size, the report shows the fairing (max z_ij and e_s fall), the constraints hold, the plot
//! has its highlight-line panels, and bad options exit 2 with one line.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh scratch directory for a test's files, removed when the returned guard is dropped.
fn out_dir(name: &str) -> tempfile::TempDir {
    crate::scratch_dir(&format!("fair-surface-{name}-"))
}

/// A 9 × 8 height field with two bumps, as `i,j,x,y,z`.
fn write_grid(dir: &Path) -> PathBuf {
    let mut text = String::from("i,j,x,y,z\n");
    for i in 0..9 {
        for j in 0..8 {
            let (x, y) = (i as f64 * 10.0, j as f64 * 8.0);
            let bump = match (i, j) {
                (3, 3) => 1.5,
                (6, 5) => -1.0,
                _ => 0.0,
            };
            let z = 0.02 * x * x / 10.0 + 0.1 * y + bump;
            text.push_str(&format!("{i},{j},{x},{y},{z}\n"));
        }
    }
    let path = dir.join("panel.csv");
    std::fs::write(&path, text).unwrap();
    path
}

fn read_grid(path: &Path) -> Vec<[f64; 5]> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3], v[4]]
        })
        .collect()
}

fn fair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .output()
        .unwrap()
}

struct Run {
    output: Vec<[f64; 5]>,
    report: serde_json::Value,
}

/// Fairs the grid with `extra` options; returns the run, the input grid and the plot's SVG text.
fn fair_surface(name: &str, extra: &[&str]) -> (Run, Vec<[f64; 5]>, String) {
    let scratch = out_dir(name);
    let dir = scratch.path();
    let input = write_grid(dir);
    let (out, report, plot) = (dir.join("out.csv"), dir.join("report.json"), dir.join("plot.svg"));
    let mut args = vec!["surface", input.to_str().unwrap(), "--quiet"];
    args.extend_from_slice(extra);
    args.extend([
        "-o",
        out.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--plot",
        plot.to_str().unwrap(),
    ]);
    let result = fair(&args);
    assert!(
        result.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&result.stderr)
    );
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    (
        Run {
            output: read_grid(&out),
            report,
        },
        read_grid(&input),
        std::fs::read_to_string(plot).unwrap(),
    )
}

fn distance(a: &[f64; 5], b: &[f64; 5]) -> f64 {
    ((a[2] - b[2]).powi(2) + (a[3] - b[3]).powi(2) + (a[4] - b[4]).powi(2)).sqrt()
}

#[test]
fn zhang_cheng_automatic_fairs_the_grid_and_draws_highlight_lines() {
    let (run, input, svg) = fair_surface("automatic", &["--method", "zhang-cheng"]);
    assert_eq!(run.output.len(), input.len());
    for (a, b) in run.output.iter().zip(&input) {
        assert_eq!((a[0], a[1]), (b[0], b[1]), "same order");
    }
    let r = &run.report;
    assert_eq!(r["method"], "zhang-cheng");
    assert_eq!(r["kind"], "surface");
    assert_eq!(r["mode"], "automatic");
    let (z0, z1) = (
        r["before"]["max_z"].as_f64().unwrap(),
        r["after"]["max_z"].as_f64().unwrap(),
    );
    let (e0, e1) = (
        r["before"]["e_s"].as_f64().unwrap(),
        r["after"]["e_s"].as_f64().unwrap(),
    );
    assert!(z1 < 0.2 * z0, "max z {z0} -> {z1}");
    assert!(e1 < e0, "e_s {e0} -> {e1}");
    // Energy never rises step by step.
    let energies: Vec<f64> = r["energy_per_step"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e.as_f64().unwrap())
        .collect();
    assert!(energies.windows(2).all(|w| w[1] <= w[0] * (1.0 + 1e-12)));
    assert_eq!(r["iterations"].as_u64().unwrap() as usize, energies.len());
    // The report's moved list names exactly the points that moved; corners never move.
    let moved: Vec<usize> = r["moved"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_u64().unwrap() as usize)
        .collect();
    let actually: Vec<usize> = (0..input.len())
        .filter(|&k| distance(&run.output[k], &input[k]) > 0.0)
        .collect();
    assert_eq!(moved, actually);
    for k in [0, 7, 64, 71] {
        assert!(!moved.contains(&k));
    }
    // s_d and m_d are the displacements.
    let m_d = run
        .output
        .iter()
        .zip(&input)
        .map(|(a, b)| distance(a, b))
        .fold(0.0, f64::max);
    assert!((r["m_d"].as_f64().unwrap() - m_d).abs() <= 1e-9 * (1.0 + m_d));
    assert_eq!(r["curve"]["rows"], 9);
    assert_eq!(r["curve"]["columns"], 8);
    // The plot: highlight lines before and after, and both z_ij maps.
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let text: String = doc
        .descendants()
        .filter(|n| n.is_text())
        .map(|n| n.text().unwrap_or(""))
        .collect();
    for title in [
        "highlight lines, input",
        "highlight lines, faired",
        "z_ij, input",
        "z_ij, faired",
    ] {
        assert!(text.contains(title), "{title}");
    }
    assert!(doc.descendants().filter(|n| n.has_tag_name("polyline")).count() > 40);
}

#[test]
fn kjellander_preset_runs_one_point_per_step() {
    let (run, input, _) = fair_surface("kjellander", &["--method", "kjellander"]);
    let r = &run.report;
    assert_eq!(r["method"], "kjellander");
    assert!(r["after"]["max_z"].as_f64().unwrap() < r["before"]["max_z"].as_f64().unwrap());
    // One point per step: each step's energy record follows one move; boundary untouched.
    for (a, b) in run.output.iter().zip(&input) {
        let boundary = a[0] == 0.0 || a[0] == 8.0 || a[1] == 0.0 || a[1] == 7.0;
        if boundary {
            assert_eq!(distance(a, b), 0.0);
        }
    }
    assert_eq!(r["boundary_steps"], 0);
}

#[test]
fn constraints_hold() {
    // Grid index k = i * 8 + j: node (3, 3) is 27, (6, 5) is 53.
    let (run, input, _) = fair_surface(
        "fixed",
        &["--method", "zhang-cheng", "--fixed", "27", "--tolerance", "0.2"],
    );
    assert_eq!(distance(&run.output[27], &input[27]), 0.0);
    for (a, b) in run.output.iter().zip(&input) {
        assert!(distance(a, b) <= 0.2 * (1.0 + 1e-12));
    }
    let (run, input, _) = fair_surface("interactive", &["--method", "zhang-cheng", "--points", "27,53"]);
    assert_eq!(run.report["mode"], "interactive");
    for (k, (a, b)) in run.output.iter().zip(&input).enumerate() {
        if k != 27 && k != 53 {
            assert_eq!(distance(a, b), 0.0, "point {k} moved");
        }
    }
    assert!(distance(&run.output[27], &input[27]) > 0.5);
    // `--clamp-ends g0` keeps the boundary (9 × 8 grid: rows i = 0, 8, columns j = 0, 7),
    // which the automatic algorithm fairs otherwise.
    let (free, _, _) = fair_surface("unclamped", &["--method", "zhang-cheng"]);
    let on_boundary = |k: usize| matches!((k / 8, k % 8), (0 | 8, _) | (_, 0 | 7));
    let boundary_moved = |run: &Run| {
        run.output
            .iter()
            .zip(&input)
            .enumerate()
            .filter(|(k, (a, b))| on_boundary(*k) && distance(a, b) > 0.0)
            .count()
    };
    assert!(boundary_moved(&free) > 0, "the test needs a boundary that moves");
    let (clamped, _, _) = fair_surface("clamped", &["--method", "zhang-cheng", "--clamp-ends", "g0"]);
    assert_eq!(boundary_moved(&clamped), 0);
    assert!(clamped
        .output
        .iter()
        .zip(&input)
        .any(|(a, b)| distance(a, b) > 0.0));
}

#[test]
fn bad_options_exit_2_with_one_line() {
    let scratch = out_dir("bad");
    let input = write_grid(scratch.path());
    let input = input.to_str().unwrap();
    for args in [
        vec!["surface", input, "--method", "zhang-cheng", "--points", "0"],
        vec![
            "surface",
            input,
            "--method",
            "zhang-cheng",
            "--set",
            "objective=thin-plate",
        ],
        vec![
            "surface",
            input,
            "--method",
            "zhang-cheng",
            "--set",
            "replacement=halfway",
        ],
        vec![
            "surface",
            input,
            "--method",
            "kjellander",
            "--set",
            "energy-tolerance=-1",
        ],
        // No surface method holds tangents or curvatures across the boundary.
        vec!["surface", input, "--clamp-ends", "g1"],
        vec!["surface", input, "--method", "kjellander", "--clamp-ends", "g2"],
        // With g0 the boundary is fixed: a bad point on it is a contradiction.
        vec!["surface", input, "--clamp-ends", "g0", "--points", "3"],
        // --kind is for curves.
        vec!["surface", input, "--kind", "function"],
        vec!["inspect", input, "--kind", "parametric"],
    ] {
        let result = fair(&args);
        assert_eq!(result.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(!stderr.contains("panicked"));
    }
}

#[test]
fn the_smoothing_baseline_matches_a_displacement_and_is_listed() {
    let (run, input, _) = fair_surface(
        "smoothing-spline",
        &["--method", "smoothing-spline", "--set", "displacement=3.5"],
    );
    let r = &run.report;
    assert_eq!(r["method"], "smoothing-spline");
    assert_eq!(r["termination"], "strategy-done");
    let s_d: f64 = run.output.iter().zip(&input).map(|(a, b)| distance(a, b)).sum();
    assert!((s_d - 3.5).abs() < 1e-6 * 3.5, "S_d {s_d}");
    assert!((r["s_d"].as_f64().unwrap() - s_d).abs() < 1e-9 * s_d);
    assert!(r["after"]["max_z"].as_f64().unwrap() < r["before"]["max_z"].as_f64().unwrap());
    let p_u = r["p_u"].as_f64().unwrap();
    assert!(p_u > 0.0 && p_u < 1.0);
    // p and displacement together are refused: exit 2, one line naming the parameter.
    let scratch = out_dir("smoothing-spline-bad");
    let dir = scratch.path();
    let grid = write_grid(dir);
    let bad = fair(&[
        "surface",
        grid.to_str().unwrap(),
        "--method",
        "smoothing-spline",
        "--set",
        "p=0.5",
        "--set",
        "displacement=1",
        "-o",
        dir.join("out.csv").to_str().unwrap(),
    ]);
    assert_eq!(bad.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(stderr.contains("displacement"), "{stderr}");
    // `fair methods` lists it among the surface methods with its parameters.
    let listed = fair(&["methods"]);
    let text = String::from_utf8_lossy(&listed.stdout);
    for word in [
        "smoothing-spline",
        "displacement",
        "radius-scale",
        "refresh-knots",
    ] {
        assert!(text.contains(word), "`fair methods` lacks {word}");
    }
}

/// A surface run whose every step the rules refused (the Utah teapot's control net, fair
/// already: each step of zhang-cheng and each fit of jump-lsq would raise its largest z_ij)
/// reports `termination: refused` with the rule or the count, not `strategy-done`, and the
/// summary line says so.
#[test]
fn a_run_whose_every_step_was_refused_says_so() {
    let scratch = out_dir("refused");
    let dir = scratch.path();
    let input = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/surface_utah_teapot/teapot_body_control_net.csv"
    );
    for method in ["zhang-cheng", "jump-lsq"] {
        let (out, report) = (dir.join("out.csv"), dir.join("report.json"));
        let result = fair(&[
            "surface",
            input,
            "--method",
            method,
            "-o",
            out.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
        ]);
        assert!(
            result.status.success(),
            "{}",
            String::from_utf8_lossy(&result.stderr)
        );
        let said = format!(
            "{}{}",
            String::from_utf8_lossy(&result.stdout),
            String::from_utf8_lossy(&result.stderr)
        );
        assert!(
            said.contains("0 moved") && said.contains("; refused: "),
            "{method}: {said}"
        );
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        assert_eq!(report["moved"].as_array().map(Vec::len), Some(0), "{method}");
        assert_eq!(report["termination"], "refused", "{method}");
        if method == "zhang-cheng" {
            assert!(report["refused_steps"].as_u64().unwrap() > 0, "{report}");
            assert_eq!(report["refusal"], "max-z");
        } else {
            assert!(report["refused"].as_u64().unwrap() > 0, "{report}");
        }
    }
}

/// Adjacent noisy fixed nodes, which `jump-lsq` can pass through only by carrying their
/// curvature out into the net, are warned of on standard error and in the report's
/// `warnings` (with `fixed_spread` above 2); the fit is still written, the nodes held. One
/// fixed node is not warned of.
#[test]
fn adjacent_noisy_fixed_nodes_are_warned_of_and_still_held() {
    let scratch = out_dir("spread");
    let dir = scratch.path();
    let noise = |i: usize, j: usize| {
        let t = ((i * 7919 + j * 104_729 + 1_299_709) as f64 * 12.9898).sin() * 43_758.545_3;
        2.0 * (t - t.floor()) - 1.0
    };
    let mut text = String::from("i,j,x,y,z\n");
    for i in 0..40 {
        for j in 0..40 {
            let (x, y) = (i as f64 / 39.0, j as f64 / 39.0);
            let z = 0.3 * (3.0 * x).sin() * (2.0 * y).cos() + 0.02 * noise(i, j);
            text.push_str(&format!("{i},{j},{x},{y},{z}\n"));
        }
    }
    let input = dir.join("net.csv");
    std::fs::write(&input, text).unwrap();
    let run = (20 * 40 + 15..20 * 40 + 23)
        .map(|k| k.to_string())
        .collect::<Vec<_>>()
        .join(",");
    for (fixed, warned) in [("820", false), (run.as_str(), true)] {
        let (out, report) = (dir.join("out.csv"), dir.join("report.json"));
        let result = fair(&[
            "surface",
            input.to_str().unwrap(),
            "--fixed",
            fixed,
            "-o",
            out.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(result.status.success(), "{stderr}");
        assert_eq!(
            stderr.contains("warning") && stderr.contains("fixed nodes inside the net bend the fit"),
            warned,
            "{stderr}"
        );
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        assert_eq!(report["fixed_spread"].as_f64().unwrap() > 2.0, warned, "{report}");
        assert_eq!(report["warnings"].as_array().unwrap().len(), usize::from(warned));
        let (before, after) = (read_grid(&input), read_grid(&out));
        for k in fixed.split(',').map(|k| k.parse::<usize>().unwrap()) {
            assert_eq!(before[k], after[k], "fixed node {k} moved");
        }
    }
}
