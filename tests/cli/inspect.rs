//! `fair inspect` and `fair demo` end to end: the report's numbers against an independent
//! computation of docs/CONTRACT.md's definitions written here from scratch (dense Gaussian
//! elimination, no code of the workspace), and the plot is well-formed SVG.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh scratch directory for a test's files, removed when the returned guard is dropped.
fn temp_dir(name: &str) -> tempfile::TempDir {
    crate::scratch_dir(&format!("fair-inspect-test-{name}-"))
}

fn fair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .output()
        .expect("run fair")
}

/// Solves the dense system A x = b by Gaussian elimination with partial pivoting.
fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap();
        a.swap(k, p);
        b.swap(k, p);
        let pivot = a[k].clone();
        for i in k + 1..n {
            let f = a[i][k] / pivot[k];
            for (entry, above) in a[i][k..].iter_mut().zip(&pivot[k..]) {
                *entry -= f * above;
            }
            b[i] -= f * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| a[k][j] * x[j]).sum();
        x[k] = (b[k] - s) / a[k][k];
    }
    x
}

/// docs/CONTRACT.md's count: drop |v| ≤ 1e-12 max |v|, then count w_k w_{k+1} < 0.
fn sign_changes(values: &[f64]) -> usize {
    let max = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let kept: Vec<f64> = values.iter().copied().filter(|v| v.abs() > 1e-12 * max).collect();
    kept.windows(2).filter(|w| w[0] * w[1] < 0.0).count()
}

/// e_i = (v_{i+1} − v_i)/(s_{i+1} − s_i) − (v_i − v_{i−1})/(s_i − s_{i−1}).
fn second_differences(s: &[f64], v: &[f64]) -> Vec<f64> {
    (1..s.len() - 1)
        .map(|i| (v[i + 1] - v[i]) / (s[i + 1] - s[i]) - (v[i] - v[i - 1]) / (s[i] - s[i - 1]))
        .collect()
}

fn read_points(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter_map(|l| {
            let row: Option<Vec<f64>> = l.split(',').map(|v| v.trim().parse().ok()).collect();
            row
        })
        .collect()
}

struct Expected {
    inflections: Option<usize>,
    vibrations: usize,
    e_s: f64,
    max_z: f64,
}

/// The function kind: c from the parabolic-runout spline function by a dense solve.
fn function_kind(points: &[Vec<f64>]) -> Expected {
    let x: Vec<f64> = points.iter().map(|p| p[0]).collect();
    let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
    let n = x.len();
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let m: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    let mut a = vec![vec![0.0; n]; n];
    let mut b = vec![0.0; n];
    a[0][0] = 1.0;
    a[0][1] = -1.0;
    a[n - 1][n - 2] = 1.0;
    a[n - 1][n - 1] = -1.0;
    for i in 1..n - 1 {
        a[i][i - 1] = h[i - 1];
        a[i][i] = 2.0 * (h[i - 1] + h[i]);
        a[i][i + 1] = h[i];
        b[i] = m[i] - m[i - 1];
    }
    let c = dense_solve(a, b);
    let e = second_differences(&x, &c);
    // y'' = 6c, linear on each interval: ∫ y''² = h (a² + ab + b²)/3.
    let e_s = (0..n - 1)
        .map(|i| {
            let (p, q) = (6.0 * c[i], 6.0 * c[i + 1]);
            h[i] * (p * p + p * q + q * q) / 3.0
        })
        .sum();
    Expected {
        inflections: Some(sign_changes(&c)),
        vibrations: sign_changes(&e),
        e_s,
        max_z: 6.0 * e.iter().fold(0.0_f64, |m, v| m.max(v.abs())),
    }
}

/// The parametric kind: the natural chord-length spline by a dense solve of the moments.
fn parametric_kind(points: &[Vec<f64>]) -> Expected {
    let n = points.len();
    let d = points[0].len();
    let h: Vec<f64> = points
        .windows(2)
        .map(|w| {
            w[0].iter()
                .zip(&w[1])
                .map(|(a, b)| (b - a) * (b - a))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let mut t = vec![0.0];
    for step in &h {
        t.push(t.last().unwrap() + step);
    }
    // Moments M (= C'') per coordinate: natural ends M_0 = M_{n−1} = 0.
    let moments: Vec<Vec<f64>> = (0..d)
        .map(|k| {
            let mut a = vec![vec![0.0; n]; n];
            let mut b = vec![0.0; n];
            a[0][0] = 1.0;
            a[n - 1][n - 1] = 1.0;
            for i in 1..n - 1 {
                a[i][i - 1] = h[i - 1];
                a[i][i] = 2.0 * (h[i - 1] + h[i]);
                a[i][i + 1] = h[i];
                b[i] = 6.0
                    * ((points[i + 1][k] - points[i][k]) / h[i]
                        - (points[i][k] - points[i - 1][k]) / h[i - 1]);
            }
            dense_solve(a, b)
        })
        .collect();
    // C' at knot i: from the piece to the right (the last from the left).
    let first = |i: usize, k: usize| -> f64 {
        let mk = &moments[k];
        if i + 1 < n {
            (points[i + 1][k] - points[i][k]) / h[i] - h[i] * (2.0 * mk[i] + mk[i + 1]) / 6.0
        } else {
            let j = n - 2;
            (points[j + 1][k] - points[j][k]) / h[j] + h[j] * (mk[j] + 2.0 * mk[j + 1]) / 6.0
        }
    };
    let kappa: Vec<f64> = (0..n)
        .map(|i| {
            let d1: Vec<f64> = (0..d).map(|k| first(i, k)).collect();
            let d2: Vec<f64> = (0..d).map(|k| moments[k][i]).collect();
            let speed = d1.iter().map(|v| v * v).sum::<f64>().sqrt();
            let cross = if d == 2 {
                d1[0] * d2[1] - d1[1] * d2[0]
            } else {
                let c = [
                    d1[1] * d2[2] - d1[2] * d2[1],
                    d1[2] * d2[0] - d1[0] * d2[2],
                    d1[0] * d2[1] - d1[1] * d2[0],
                ];
                (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
            };
            cross / speed.powi(3)
        })
        .collect();
    let e = second_differences(&t, &kappa);
    let e_s = (0..n - 1)
        .map(|i| {
            (0..d)
                .map(|k| {
                    let (p, q) = (moments[k][i], moments[k][i + 1]);
                    h[i] * (p * p + p * q + q * q) / 3.0
                })
                .sum::<f64>()
        })
        .sum();
    // C''' on piece i is (M_{i+1} − M_i)/h_i.
    let third = |i: usize| -> Vec<f64> {
        (0..d)
            .map(|k| (moments[k][i + 1] - moments[k][i]) / h[i])
            .collect()
    };
    let max_z = (1..n - 1)
        .map(|i| {
            let (l, r) = (third(i - 1), third(i));
            l.iter()
                .zip(&r)
                .map(|(a, b)| (b - a) * (b - a))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    Expected {
        inflections: (d == 2).then(|| sign_changes(&kappa)),
        vibrations: sign_changes(&e),
        e_s,
        max_z,
    }
}

fn close(got: f64, want: f64) -> bool {
    (got - want).abs() <= 1e-7 * want.abs().max(1e-300)
}

/// Runs `fair inspect` with --report and --plot; checks the report against `expected` and
/// the SVG's structure.
fn check_inspect(relative: &str, kind: &str, expected: Expected) {
    let scratch = temp_dir(&relative.replace('/', "_"));
    let dir = scratch.path();
    let (report, plot) = (dir.join("report.json"), dir.join("plot.svg"));
    let input = root().join(relative);
    let output = fair(&[
        "inspect",
        input.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--plot",
        plot.to_str().unwrap(),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["method"], "inspect");
    assert_eq!(json["kind"], kind);
    assert_eq!(json["n"].as_u64().unwrap() as usize, read_points(&input).len());
    for side in ["before", "after"] {
        let m = &json[side];
        for field in ["e_s", "max_z"] {
            assert!(m[field].as_f64().is_some_and(f64::is_finite), "{side}.{field}");
        }
        for field in ["e1", "e2", "e3", "ek", "ek_prime"] {
            let v = m["energies"][field].as_f64().unwrap();
            assert!(v.is_finite() && v >= 0.0, "{side}.energies.{field} = {v}");
        }
        assert_eq!(
            m["inflections"].as_u64().map(|v| v as usize),
            expected.inflections,
            "{relative}"
        );
        assert_eq!(
            m["vibrations"].as_u64().unwrap() as usize,
            expected.vibrations,
            "{relative}"
        );
        let (e_s, max_z) = (m["e_s"].as_f64().unwrap(), m["max_z"].as_f64().unwrap());
        assert!(close(e_s, expected.e_s), "{relative}: e_s {e_s} {}", expected.e_s);
        assert!(
            close(max_z, expected.max_z),
            "{relative}: max_z {max_z} {}",
            expected.max_z
        );
    }
    let svg = std::fs::read_to_string(&plot).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("the plot is well-formed XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    let count = |name: &str| doc.descendants().filter(|n| n.tag_name().name() == name).count();
    assert!(count("path") >= 1, "no path (curvature comb)");
    assert!(count("polyline") >= 2, "no curve and curvature lines");
}

#[test]
fn inspect_function_kind_matches_the_definitions() {
    for file in [
        "data/airfoil_ua2-180/ua2-180_upper.csv",
        "data/airfoil_r140/r140_upper.csv",
        "data/hull_block_island_boat/waterlines/wl_36in.csv",
    ] {
        let expected = function_kind(&read_points(&root().join(file)));
        check_inspect(file, "function", expected);
    }
}

#[test]
fn inspect_parametric_kind_matches_the_definitions() {
    for file in [
        "data/airfoil_naca2412/naca2412.csv",
        "data/hull_block_island_boat/sheer_3d.csv",
    ] {
        let expected = parametric_kind(&read_points(&root().join(file)));
        check_inspect(file, "parametric", expected);
    }
}

#[test]
fn inspect_surface_reports_null_counts() {
    let scratch = temp_dir("surface");
    let dir = scratch.path();
    let report = dir.join("report.json");
    let input = root().join("data/surface_utah_teapot/teapot_body_control_net.csv");
    let output = fair(&[
        "inspect",
        input.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["kind"], "surface");
    assert!(json["before"]["inflections"].is_null() && json["before"]["vibrations"].is_null());
    assert!(json["before"]["max_z"].as_f64().unwrap() > 0.0);
    assert!(json["before"]["e_s"].as_f64().unwrap() > 0.0);
}

#[test]
fn inspect_repeated_points_exit_2_naming_the_file() {
    let scratch = temp_dir("repeated");
    let dir = scratch.path();
    let input = dir.join("repeated.csv");
    std::fs::write(&input, "x,y\n0,0\n1,1\n1,1\n0,2\n").unwrap();
    let output = fair(&["inspect", input.to_str().unwrap(), "--kind", "parametric"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("repeated.csv") && !stderr.contains("panicked"),
        "{stderr}"
    );
}

#[test]
fn demo_exits_0_and_writes_plots() {
    let scratch = temp_dir("demo");
    let dir = scratch.path();
    let output = fair(&["demo", "--out", dir.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{}\n{stdout}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        stdout.contains("ua2-180-upper") && stdout.contains("teapot-body"),
        "{stdout}"
    );
    let svgs: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.path().extension().is_some_and(|x| x == "svg"))
        .collect();
    assert!(svgs.len() >= 8, "{} SVGs", svgs.len());
    // One IGES, one STEP and one DXF beside the SVGs, each read back with its shape.
    for (file, curves, surfaces) in [
        ("r140-upper-two-phase.igs", 1, 0),
        ("teapot-body-zhang-cheng.step", 0, 1),
        ("gunnerus-wl03-strain-energy.dxf", 1, 0),
    ] {
        let model = cad::read_path(dir.join(file), None).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(
            (model.curves.len(), model.surfaces.len()),
            (curves, surfaces),
            "{file}"
        );
        let stem = file.rsplit_once('.').unwrap().0;
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join(format!("{stem}.json"))).unwrap())
                .unwrap();
        assert_eq!(report["cad"]["exact"], true, "{file}");
    }
    for entry in svgs {
        let text = std::fs::read_to_string(entry.path()).unwrap();
        let document = roxmltree::Document::parse(&text).expect("well-formed SVG");
        // Something is drawn: a path or polyline with at least two points.
        let drawn = document.descendants().any(|n| {
            let d = n.attribute("d").or_else(|| n.attribute("points")).unwrap_or("");
            (n.has_tag_name("path") || n.has_tag_name("polyline"))
                && d.split(|c: char| c.is_ascii_alphabetic() || c == ' ' || c == ',')
                    .filter(|t| !t.is_empty())
                    .count()
                    >= 4
        });
        assert!(drawn, "{}: no drawn path", entry.path().display());
    }
}
