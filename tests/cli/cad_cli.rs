//! `fair curve -o FILE.igs|.step|.dxf` and `fair surface -o FILE.igs|.step` end to end: the
//! file read back by `cad::read_path` holds a curve (surface) through the faired points to
//! 1e-9 of their size, for a function method, parametric methods, nurbs-weights and a
//! surface; a rebuild keeps its stated control points and deviation; bad combinations of
//! options exit 2 naming the option, before anything is written.
//!
//! The faired points come from a second run writing them as CSV (the methods are
//! deterministic), and each is projected onto the file's curve independently of the report's
//! parameters: the closest of a dense sampling, refined by ternary search.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use curve_repr::{Curve, NurbsCurve, Surface, Vec3};

fn data(relative: &str) -> String {
    format!("{}/data/{relative}", env!("CARGO_MANIFEST_DIR"))
}

fn fair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .output()
        .unwrap()
}

fn ok(output: &Output) {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// The coordinate rows of a CSV with a header (every column numeric).
fn rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(|x| x.trim().parse().unwrap()).collect())
        .collect()
}

fn lift(row: &[f64]) -> Vec3 {
    Vec3::new(row[0], row[1], row.get(2).copied().unwrap_or(0.0))
}

fn size(points: &[Vec3]) -> f64 {
    let mut low = Vec3::from_element(f64::INFINITY);
    let mut high = Vec3::from_element(f64::NEG_INFINITY);
    for p in points {
        low = low.inf(p);
        high = high.sup(p);
    }
    (high - low).norm()
}

/// The distance from `p` to `curve`: the closest of 64 samples per knot span, refined by
/// ternary search over the neighbouring samples.
fn distance(curve: &NurbsCurve<3>, p: &Vec3) -> f64 {
    let knots = curve.knot_vector().distinct();
    let mut samples = Vec::new();
    for w in knots.windows(2) {
        for k in 0..64 {
            samples.push(w[0] + (w[1] - w[0]) * k as f64 / 64.0);
        }
    }
    samples.extend(knots.last());
    let d = |t: f64| (curve.eval(t) - p).norm();
    let best = (0..samples.len())
        .min_by(|&a, &b| d(samples[a]).total_cmp(&d(samples[b])))
        .unwrap();
    let (mut a, mut b) = (
        samples[best.saturating_sub(1)],
        samples[(best + 1).min(samples.len() - 1)],
    );
    for _ in 0..200 {
        let (m1, m2) = (a + (b - a) / 3.0, b - (b - a) / 3.0);
        if d(m1) < d(m2) {
            b = m2;
        } else {
            a = m1;
        }
    }
    d(0.5 * (a + b)).min(d(samples[best]))
}

/// Fairs `input` with `method` twice, to CSV and to `file` (a CAD name), and returns the
/// faired points, the file read back and the report.
fn faired_and_file(
    input: &str,
    method: &str,
    file: &str,
    extra: &[&str],
    cad_extra: &[&str],
) -> (Vec<Vec3>, cad::CadModel, serde_json::Value) {
    let scratch = crate::scratch_dir("fair-cad-cli-");
    let dir = scratch.path();
    let stem = file.replace('.', "-");
    let csv = dir.join(format!("{stem}.csv"));
    let target = dir.join(file);
    let report = dir.join(format!("{stem}.json"));
    let mut args = vec!["curve", input, "-m", method, "-q"];
    args.extend_from_slice(extra);
    let mut points_run = args.clone();
    points_run.extend(["-o", csv.to_str().unwrap()]);
    ok(&fair(&points_run));
    let mut cad_run = args;
    cad_run.extend_from_slice(cad_extra);
    cad_run.extend([
        "-o",
        target.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    ok(&fair(&cad_run));
    let points: Vec<Vec3> = rows(&csv).iter().map(|r| lift(r)).collect();
    let model = cad::read_path(&target, None).unwrap();
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(report).unwrap()).unwrap();
    (points, model, report)
}

/// Every faired point lies on the file's one curve to 1e-9 of the points' size.
fn assert_through(points: &[Vec3], model: &cad::CadModel, what: &str) {
    assert_eq!(model.curves.len(), 1, "{what}");
    let curve = &model.curves[0].curve;
    let scale = size(points);
    let worst = points.iter().map(|p| distance(curve, p)).fold(0.0, f64::max);
    assert!(
        worst <= 1e-9 * scale,
        "{what}: a faired point is {worst} from the curve (size {scale})"
    );
}

#[test]
fn a_function_method_writes_its_spline_function_exactly_in_iges() {
    let input = data("airfoil_r140/r140_upper.csv");
    let (points, model, report) = faired_and_file(&input, "two-phase", "tp.igs", &[], &[]);
    assert_through(&points, &model, "two-phase");
    let cad = &report["cad"];
    assert_eq!(cad["format"], "iges");
    assert_eq!(cad["representation"], "spline-function");
    assert_eq!(cad["exact"], true);
    // On the exact curve the counts at the faired points are the report's own.
    assert_eq!(cad["faired"]["inflections"], report["after"]["inflections"]);
    assert_eq!(cad["faired"]["vibrations"], report["after"]["vibrations"]);
    assert_eq!(cad["wiggles_back"], false);
    assert_eq!(
        cad["control_points"],
        model.curves[0].curve.control_points().len()
    );
}

#[test]
fn parametric_methods_write_their_own_curves_in_step() {
    let input = data("airfoil_naca2412/naca2412.csv");
    for (method, representation) in [("strain-energy", "hermite"), ("batten", "ferguson")] {
        let file = format!("{method}.step");
        let (points, model, report) = faired_and_file(&input, method, &file, &["--kind", "parametric"], &[]);
        assert_through(&points, &model, method);
        assert_eq!(report["cad"]["representation"], representation, "{method}");
        assert_eq!(report["cad"]["format"], "step");
        assert!(
            report["cad"]["max_deviation"].as_f64().unwrap() <= 1e-12,
            "{method}"
        );
    }
}

#[test]
fn smoothing_spline_and_sapidis_farin_write_their_own_curves() {
    let input = data("airfoil_r140/r140_upper.csv");
    for (method, representation) in [
        ("smoothing-spline", "natural-cubic-spline"),
        ("sapidis-farin", "nurbs"),
    ] {
        let file = format!("{method}.igs");
        let (points, model, report) = faired_and_file(&input, method, &file, &[], &[]);
        assert_through(&points, &model, method);
        assert_eq!(report["cad"]["representation"], representation, "{method}");
    }
}

#[test]
fn nurbs_weights_writes_its_rational_curve_in_dxf() {
    let input = data("airfoil_naca2412/naca2412_upper.csv");
    let (points, model, report) = faired_and_file(
        &input,
        "nurbs-weights",
        "nw.dxf",
        &["--set", "max-iterations=60"],
        &[],
    );
    assert_through(&points, &model, "nurbs-weights");
    assert_eq!(report["cad"]["representation"], "nurbs");
    // The weights written are the report's, bit for bit.
    let weights: Vec<f64> = report["curve"]["weights"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_f64().unwrap())
        .collect();
    assert_eq!(model.curves[0].curve.weights(), &weights[..]);
}

#[test]
fn a_rebuild_has_its_control_points_and_its_stated_deviation() {
    let input = data("airfoil_r140/r140_upper.csv");
    let (points, model, report) = faired_and_file(
        &input,
        "two-phase",
        "rebuilt.step",
        &[],
        &["--control-points", "12"],
    );
    let cad = &report["cad"];
    assert_eq!(cad["exact"], false);
    assert_eq!(cad["control_points"], 12);
    let curve = &model.curves[0].curve;
    assert_eq!(curve.control_points().len(), 12);
    // A function stays a function of x: the curve at t = x_i is the point above x_i.
    let worst = points
        .iter()
        .map(|p| {
            let q = curve.eval(p.x);
            assert!((q.x - p.x).abs() <= 1e-12 * size(&points), "x(t) = t");
            (q.y - p.y).abs()
        })
        .fold(0.0, f64::max);
    let stated = cad["max_deviation"].as_f64().unwrap();
    assert!(
        (worst - stated).abs() <= 1e-12 * size(&points),
        "{worst} vs {stated}"
    );
    assert!(cad["written"]["vibrations"].is_u64() && cad["faired"]["vibrations"].is_u64());
    let back = cad["written"]["inflections"].as_u64() > cad["faired"]["inflections"].as_u64()
        || cad["written"]["vibrations"].as_u64() > cad["faired"]["vibrations"].as_u64();
    assert_eq!(cad["wiggles_back"], back);
}

fn grid(dir: &Path) -> PathBuf {
    let mut text = String::from("i,j,x,y,z\n");
    for i in 0..9 {
        for j in 0..8 {
            let (x, y) = (i as f64 * 10.0, j as f64 * 8.0);
            let bump = if (i, j) == (3, 3) { 1.5 } else { 0.0 };
            text.push_str(&format!("{i},{j},{x},{y},{}\n", 0.002 * x * x + 0.1 * y + bump));
        }
    }
    let path = dir.join("panel.csv");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_surface_is_written_as_its_bicubic_b_spline_surface() {
    let scratch = crate::scratch_dir("fair-cad-cli-");
    let dir = scratch.path();
    let input = grid(dir);
    let input = input.to_str().unwrap();
    let csv = dir.join("panel-faired.csv");
    ok(&fair(&["surface", input, "-q", "-o", csv.to_str().unwrap()]));
    let faired: Vec<Vec3> = rows(&csv).iter().map(|r| Vec3::new(r[2], r[3], r[4])).collect();
    for file in ["panel.igs", "panel.step"] {
        let target = dir.join(file);
        let report = dir.join(format!("{file}.json"));
        ok(&fair(&[
            "surface",
            input,
            "-q",
            "-o",
            target.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
        ]));
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(report).unwrap()).unwrap();
        assert_eq!(report["cad"]["representation"], "bicubic", "{file}");
        let model = cad::read_path(&target, None).unwrap();
        assert_eq!(model.surfaces.len(), 1, "{file}");
        let surface = &model.surfaces[0].surface;
        let knots = |name: &str| -> Vec<f64> {
            report["curve"][name]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect()
        };
        let (u, v) = (knots("u_knots"), knots("v_knots"));
        assert_eq!((u.len(), v.len()), (9, 8));
        let scale = size(&faired);
        for (i, &ui) in u.iter().enumerate() {
            for (j, &vj) in v.iter().enumerate() {
                let gap = (surface.eval(ui, vj) - faired[i * 8 + j]).norm();
                assert!(
                    gap <= 1e-9 * scale,
                    "{file}: P[{i}][{j}] is {gap} off the surface"
                );
            }
        }
    }
}

#[test]
fn bad_combinations_exit_2_naming_the_option_and_write_nothing() {
    let scratch = crate::scratch_dir("fair-cad-cli-");
    let dir = scratch.path();
    let input = data("airfoil_r140/r140_upper.csv");
    let panel = grid(dir);
    let igs = dir.join("never.igs");
    let igs = igs.to_str().unwrap();
    let dxf = dir.join("never.dxf");
    let dxf = dxf.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["curve", &input, "--control-points", "8"], "--control-points"),
        (
            vec!["curve", &input, "--fit-tolerance", "0.001"],
            "--fit-tolerance",
        ),
        (vec!["curve", &input, "--cad", "step"], "--cad"),
        (vec!["curve", &input, "--cad", "step", "-o", igs], "--cad"),
        (vec!["curve", &input, "--cad", "nurbs", "-o", igs], "--cad"),
        (
            vec!["curve", &input, "-o", igs, "--control-points", "3"],
            "--control-points",
        ),
        (
            vec![
                "curve",
                &input,
                "-o",
                igs,
                "--control-points",
                "8",
                "--fit-tolerance",
                "0.1",
            ],
            "--control-points",
        ),
        (
            vec!["curve", &input, "-o", igs, "--control-points", "400"],
            "--control-points",
        ),
        (vec!["curve", &input, "-o", igs, "--batch"], "-o"),
        (vec!["surface", panel.to_str().unwrap(), "-o", dxf], "-o"),
        (
            vec![
                "surface",
                panel.to_str().unwrap(),
                "-o",
                igs,
                "--control-points",
                "6",
            ],
            "--control-points",
        ),
    ];
    for (args, option) in cases {
        let output = fair(&args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(option), "{args:?}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{args:?}: {stderr}");
        assert!(
            !Path::new(igs).exists() && !Path::new(dxf).exists(),
            "{args:?} wrote a file"
        );
    }
}

#[test]
fn cad_to_standard_output() {
    let input = data("airfoil_r140/r140_upper.csv");
    let output = fair(&["curve", &input, "--cad", "step", "-o", "-", "-q"]);
    ok(&output);
    let text = String::from_utf8(output.stdout).unwrap();
    let model = cad::read(&text, cad::Format::Step).unwrap();
    assert_eq!(model.curves.len(), 1);
}

/// `--cad-units m` declares metres (a ship's waterline in metres stays 35 m long, not 35 mm),
/// with the coordinates unchanged; `--step-schema ap242` writes AP242; both are refused where
/// they cannot apply.
#[test]
fn the_file_declares_the_units_and_schema_asked_for() {
    let scratch = crate::scratch_dir("fair-cad-cli-");
    let dir = scratch.path();
    let input = data("hull_gunnerus/waterlines/wl_03.csv");
    let step = dir.join("wl.step");
    let report = dir.join("wl.json");
    let run = |extra: &[&str]| {
        let mut args = vec!["curve", &input, "-q", "-o", step.to_str().unwrap()];
        args.extend(["--report", report.to_str().unwrap()]);
        args.extend_from_slice(extra);
        fair(&args)
    };
    ok(&run(&[]));
    assert!(!std::fs::read_to_string(&step).unwrap().contains("AP242_MANAGED"));
    let millimetres = cad::read_path(&step, None).unwrap();
    assert_eq!(millimetres.units, cad::Units::Millimetre);
    ok(&run(&["--cad-units", "m", "--step-schema", "ap242"]));
    let metres = cad::read_path(&step, None).unwrap();
    assert_eq!(metres.units, cad::Units::Metre);
    assert_eq!(
        metres.curves[0].curve.control_points(),
        millimetres.curves[0].curve.control_points(),
        "the coordinates are written as they are"
    );
    let text = std::fs::read_to_string(&step).unwrap();
    assert!(text.contains("AP242_MANAGED"), "not AP242");
    let value: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(value["cad"]["units"], "m");
    for (args, option) in [
        (vec!["curve", &input, "--cad-units", "m"], "--cad-units"),
        (vec!["curve", &input, "--step-schema", "ap242"], "--step-schema"),
        (
            vec![
                "curve",
                &input,
                "-o",
                dir.join("wl.igs").to_str().unwrap(),
                "--step-schema",
                "ap242",
            ],
            "--step-schema",
        ),
    ] {
        let output = fair(&args);
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains(option), "{args:?}: {stderr}");
    }
    assert!(!dir.join("wl.igs").exists());
}
