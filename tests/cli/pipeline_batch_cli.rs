//! The command's composition features end to end, on the built binary: pipelines of stages
//! from TOML and JSON config files, `--print-config`, and batches (a directory with a
//! malformed file, a JSON-lines stream on standard input).

use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};

fn data(relative: &str) -> String {
    format!("{}/data/{relative}", env!("CARGO_MANIFEST_DIR"))
}

/// A fresh scratch directory for a test's files, removed when the returned guard is dropped.
fn temp_dir(name: &str) -> tempfile::TempDir {
    crate::scratch_dir(&format!("fair-pipeline-{name}-"))
}

fn fair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .output()
        .unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(|x| x.trim().parse::<f64>().unwrap()).collect())
        .collect()
}

/// A quick NURBS-weights stage (the method is wired in every build of the command).
const QUICK: &str = "max-iterations = 30\n";

#[test]
fn a_toml_pipeline_runs_its_stages_in_order_and_reports_each() {
    let scratch = temp_dir("toml");
    let dir = scratch.path();
    let config = dir.join("pipeline.toml");
    std::fs::write(
        &config,
        format!(
            "[constraints]\nfixed = [2]\n\n[[stage]]\nmethod = \"nurbs-weights\"\ncriterion = \"e2\"\n{QUICK}\n[[stage]]\nmethod = \"nurbs-weights\"\ncriterion = \"ek\"\n{QUICK}"
        ),
    )
    .unwrap();
    let report = dir.join("report.json");
    let input = data("airfoil_naca2412/naca2412_upper.csv");
    let out = fair(&[
        "curve",
        &input,
        "--config",
        config.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = json(&report);
    assert_eq!(report["method"], "nurbs-weights+nurbs-weights");
    let stages = report["stages"].as_array().unwrap();
    assert_eq!(stages.len(), 2);
    assert_eq!(stages[0]["method"], "nurbs-weights");
    assert_eq!(stages[0]["params"]["criterion"], "e2");
    assert_eq!(stages[1]["params"]["criterion"], "ek");
    let total: u64 = stages.iter().map(|s| s["iterations"].as_u64().unwrap()).sum();
    assert_eq!(report["iterations"].as_u64().unwrap(), total);
    // The last stage's curve is the report's curve.
    assert_eq!(report["curve"]["type"], "nurbs");
}

#[test]
fn a_json_config_is_read_like_toml_and_print_config_round_trips() {
    let scratch = temp_dir("json");
    let dir = scratch.path();
    let config = dir.join("pipeline.json");
    std::fs::write(
        &config,
        "{\n  \"constraints\": {\"fixed\": [1], \"tolerance\": 0.5},\n  \"stage\": [{\"method\": \"nurbs-weights\", \"max-iterations\": 30}]\n}\n",
    )
    .unwrap();
    let input = data("airfoil_naca2412/naca2412_upper.csv");
    let printed = fair(&[
        "curve",
        &input,
        "--config",
        config.to_str().unwrap(),
        "--print-config",
    ]);
    assert!(printed.status.success(), "{}", stderr(&printed));
    let text = String::from_utf8(printed.stdout).unwrap();
    assert!(text.contains("fixed = [1]"), "{text}");
    assert!(text.contains("tolerance = 0.5"), "{text}");
    assert!(text.contains("max-iterations = 30"), "{text}");
    // Every parameter of the method is written with its default.
    assert!(text.contains("law = \"bernstein\""), "{text}");
    // The printed config is a config that runs and gives the same parameters.
    let again = dir.join("printed.toml");
    std::fs::write(&again, &text).unwrap();
    let report = dir.join("report.json");
    let out = fair(&[
        "curve",
        &input,
        "--config",
        again.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "-q",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = json(&report);
    assert_eq!(report["method"], "nurbs-weights");
    assert_eq!(report["params"]["max-iterations"], 30.0);
    assert_eq!(report["params"]["law"], "bernstein");
}

#[test]
fn print_config_of_a_plain_command_line() {
    let input = data("airfoil_naca2412/naca2412_upper.csv");
    let out = fair(&[
        "curve",
        &input,
        "--method",
        "nurbs-weights",
        "--set",
        "criterion=e3",
        "--set",
        "max-iterations=20",
        "--clamp-ends",
        "g0",
        "--print-config",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).unwrap();
    let table: toml::Table = toml::from_str(&text).unwrap();
    assert_eq!(table["constraints"]["clamp-ends"].as_str(), Some("g0"));
    let stage = &table["stage"].as_array().unwrap()[0];
    assert_eq!(stage["method"].as_str(), Some("nurbs-weights"));
    assert_eq!(stage["criterion"].as_str(), Some("e3"));
    // A value the method refuses is refused here too, not printed as a good config.
    for setting in ["p=7", "rule=newton"] {
        let out = fair(&[
            "curve",
            &input,
            "--method",
            "smoothing-spline",
            "--set",
            setting,
            "--print-config",
        ]);
        assert_eq!(out.status.code(), Some(2), "{setting}");
        assert!(out.stdout.is_empty(), "{setting}");
    }
}

#[test]
fn config_mistakes_exit_two_naming_the_file_and_line() {
    let scratch = temp_dir("bad");
    let dir = scratch.path();
    let input = data("airfoil_naca2412/naca2412_upper.csv");
    let cases: [(&str, &str, &str); 4] = [
        (
            "unknown.toml",
            "[[stage]]\nmethod = \"frobnicate\"\n",
            "frobnicate",
        ),
        (
            "param.toml",
            "[[stage]]\nmethod = \"nurbs-weights\"\nbogus = 1\n",
            "param.toml:3",
        ),
        ("syntax.toml", "[[stage]]\nmethod = = 1\n", "syntax.toml:2"),
        ("constraint.toml", "[constraints]\nfixed = [99]\n", "--fixed"),
    ];
    for (name, text, expected) in cases {
        let config = dir.join(name);
        std::fs::write(&config, text).unwrap();
        let out = fair(&["curve", &input, "--config", config.to_str().unwrap(), "-q"]);
        assert_eq!(out.status.code(), Some(2), "{name}: {}", stderr(&out));
        let message = stderr(&out);
        assert_eq!(message.lines().count(), 1, "{message}");
        assert!(message.contains(expected), "{name}: {message}");
    }
    // A pipeline and --method together are ambiguous.
    let config = dir.join("pipe.toml");
    std::fs::write(&config, "[[stage]]\nmethod = \"nurbs-weights\"\n").unwrap();
    let out = fair(&[
        "curve",
        &input,
        "--config",
        config.to_str().unwrap(),
        "--method",
        "nurbs-weights",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--method"), "{}", stderr(&out));
}

#[test]
fn a_directory_batch_reports_every_curve_and_the_bad_one_without_stopping() {
    let scratch = temp_dir("batch");
    let dir = scratch.path();
    let inputs = dir.join("in");
    std::fs::create_dir_all(&inputs).unwrap();
    std::fs::copy(data("airfoil_naca2412/naca2412_upper.csv"), inputs.join("a.csv")).unwrap();
    std::fs::write(inputs.join("b.csv"), "x,y\n0,0\n1,oops\n2,1\n").unwrap();
    std::fs::copy(
        data("hull_block_island_boat/waterlines/wl_36in.csv"),
        inputs.join("c.csv"),
    )
    .unwrap();
    let outputs = dir.join("out");
    let plots = dir.join("plots");
    let report = dir.join("report.jsonl");
    let out = fair(&[
        "curve",
        inputs.to_str().unwrap(),
        "--method",
        "nurbs-weights",
        "--set",
        "max-iterations=30",
        "-o",
        outputs.to_str().unwrap(),
        "--plot",
        plots.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "-q",
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("1 of 3"), "{}", stderr(&out));
    let lines: Vec<serde_json::Value> = std::fs::read_to_string(&report)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 3);
    assert!(lines[0]["source"].as_str().unwrap().ends_with("a.csv"));
    assert_eq!(lines[0]["method"], "nurbs-weights");
    let error = lines[1]["error"].as_str().unwrap();
    assert!(error.contains("b.csv:3") && error.contains("oops"), "{error}");
    assert_eq!(lines[1]["exit_status"], 2);
    assert_eq!(
        lines[2]["n"].as_u64().unwrap() as usize,
        rows(&inputs.join("c.csv")).len()
    );
    // Outputs for the good curves only, same points (nurbs-weights moves none).
    assert_eq!(rows(&outputs.join("a.csv")), rows(&inputs.join("a.csv")));
    assert!(outputs.join("c.csv").exists() && !outputs.join("b.csv").exists());
    for stem in ["a", "c"] {
        let svg = std::fs::read_to_string(plots.join(format!("{stem}.svg"))).unwrap();
        let document = roxmltree::Document::parse(&svg).unwrap();
        assert!(document
            .descendants()
            .any(|n| n.has_tag_name("path") || n.has_tag_name("polyline")));
    }
}

#[test]
fn a_json_lines_stream_on_standard_input_gives_one_line_per_curve() {
    let points: Vec<[f64; 2]> = (0..12).map(|i| [i as f64, (i as f64 * 0.4).sin()]).collect();
    let good = serde_json::json!({ "points": points }).to_string();
    let stream = format!("{good}\n{{\"points\": [[0, 1]]}}\nnot json\n\n{good}\n");
    let mut child = Command::new(env!("CARGO_BIN_EXE_fair"))
        .args([
            "curve",
            "-",
            "--batch",
            "--method",
            "nurbs-weights",
            "--set",
            "max-iterations=20",
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(stream.as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let lines: Vec<serde_json::Value> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 4, "blank lines are skipped");
    assert_eq!(lines[0]["source"], "<stdin>:1");
    assert_eq!(lines[0]["n"], 12);
    assert!(lines[1]["error"]
        .as_str()
        .unwrap()
        .starts_with("<stdin>:2: 1 point"));
    assert!(lines[2]["error"].as_str().unwrap().starts_with("<stdin>:3: "));
    assert_eq!(lines[3]["source"], "<stdin>:5");
    assert!(!stderr(&out).contains("panicked"));
}

#[test]
fn a_pipeline_that_moves_points_keeps_fixed_points_and_the_tolerance_band_over_all_stages() {
    let scratch = temp_dir("moving");
    let dir = scratch.path();
    let config = dir.join("pipeline.toml");
    let band = 0.05;
    std::fs::write(
        &config,
        format!(
            "[constraints]\nfixed = [3, 9]\ntolerance = {band}\n\n[[stage]]\nmethod = \"strain-energy\"\n\n[[stage]]\nmethod = \"batten\"\n"
        ),
    )
    .unwrap();
    let input = data("hull_block_island_boat/sheer_3d.csv");
    let output = dir.join("out.csv");
    let report = dir.join("report.json");
    let out = fair(&[
        "curve",
        &input,
        "--config",
        config.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "-q",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let before = rows(Path::new(&input));
    let after = rows(&output);
    assert_eq!(before.len(), after.len());
    for i in [3, 9] {
        assert_eq!(before[i], after[i], "fixed point {i} moved");
    }
    let largest = before
        .iter()
        .zip(&after)
        .map(|(a, b)| a.iter().zip(b).map(|(u, v)| (u - v).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    assert!(largest <= band * (1.0 + 1e-12), "moved {largest} > {band}");
    let report = json(&report);
    assert_eq!(report["method"], "strain-energy+batten");
    let stages = report["stages"].as_array().unwrap();
    assert_eq!(stages.len(), 2);
    // The first stage moved points; the second got only what the first left of the band.
    assert!(stages[0]["moved"].as_u64().unwrap() > 0, "{stages:?}");
    let first = stages[0]["m_d"].as_f64().unwrap();
    let second = stages[1]["m_d"].as_f64().unwrap_or(0.0);
    assert!(second <= band - first + 1e-12, "{first} + {second} > {band}");
    let moved: Vec<usize> = serde_json::from_value(report["moved"].clone()).unwrap();
    let differ: Vec<usize> = (0..before.len()).filter(|&i| before[i] != after[i]).collect();
    assert_eq!(moved, differ);
    assert!((report["m_d"].as_f64().unwrap() - largest).abs() < 1e-12);
}
