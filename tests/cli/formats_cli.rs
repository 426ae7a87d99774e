//! `fair curve` on every input format, from a file and from standard input: the output has the
//! input's format (header, JSON document with its other keys, airfoil name line), the same
//! count and order of points, and the report is valid JSON.

use std::io::Write;
use std::process::{Command, Output, Stdio};

/// A fresh scratch directory for a test's files, removed when the returned guard is dropped.
fn temp_dir(name: &str) -> tempfile::TempDir {
    crate::scratch_dir(&format!("fair-formats-{name}-"))
}

/// A method wired in every build of the command, kept quick.
const METHOD: [&str; 4] = ["--method", "nurbs-weights", "--set", "max-iterations=10"];

fn fair(args: &[&str], stdin: Option<&str>) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .args(METHOD)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut pipe = child.stdin.take().unwrap();
    if let Some(text) = stdin {
        pipe.write_all(text.as_bytes()).unwrap();
    }
    drop(pipe);
    child.wait_with_output().unwrap()
}

/// The points of the NACA 2412 upper surface.
fn points() -> Vec<[f64; 2]> {
    let text = std::fs::read_to_string(format!(
        "{}/data/airfoil_naca2412/naca2412_upper.csv",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            [v[0], v[1]]
        })
        .collect()
}

fn numbers(line: &str) -> Vec<f64> {
    line.split([',', ' ', '\t'])
        .filter(|t| !t.is_empty())
        .map(|t| t.parse().unwrap())
        .collect()
}

/// Writes `text` to a fresh file called `file_name`, runs `fair curve FILE -o OUT -q`, asserts
/// success and returns what was written to OUT.
fn round_trip(file_name: &str, text: &str) -> String {
    let scratch = temp_dir(file_name);
    let dir = scratch.path();
    let input = dir.join(file_name);
    std::fs::write(&input, text).unwrap();
    let output = dir.join(format!("out-{file_name}"));
    let run = fair(
        &[
            "curve",
            input.to_str().unwrap(),
            "-o",
            output.to_str().unwrap(),
            "-q",
        ],
        None,
    );
    assert!(
        run.status.success(),
        "{file_name}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    std::fs::read_to_string(&output).unwrap()
}

fn check_rows(lines: &[&str], expected: &[[f64; 2]]) {
    assert_eq!(lines.len(), expected.len());
    for (line, point) in lines.iter().zip(expected) {
        let got = numbers(line);
        assert_eq!(got.len(), 2, "{line}");
        // nurbs-weights never moves a point: the values come back exactly.
        assert_eq!([got[0], got[1]], *point, "{line}");
    }
}

#[test]
fn csv_with_header_file_and_stdin() {
    let pts = points();
    let text = std::iter::once("x,y".to_string())
        .chain(pts.iter().map(|p| format!("{},{}", p[0], p[1])))
        .collect::<Vec<_>>()
        .join("\n");
    let scratch = temp_dir("csv");
    let dir = scratch.path();
    let input = dir.join("in.csv");
    std::fs::write(&input, &text).unwrap();
    let output = dir.join("out.csv");
    let report = dir.join("report.json");
    let run = fair(
        &[
            "curve",
            input.to_str().unwrap(),
            "-o",
            output.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
            "-q",
        ],
        None,
    );
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let written = std::fs::read_to_string(&output).unwrap();
    let lines: Vec<&str> = written.lines().collect();
    assert_eq!(lines[0], "x,y");
    check_rows(&lines[1..], &pts);
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(report["n"].as_u64().unwrap() as usize, pts.len());

    // The same from standard input to standard output; the summary goes to stderr.
    let run = fair(&["curve", "-", "-o", "-"], Some(&text));
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let stdout = String::from_utf8(run.stdout).unwrap();
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines[0], "x,y");
    check_rows(&lines[1..], &pts);
    assert!(String::from_utf8_lossy(&run.stderr).contains("<stdin>"));
}

#[test]
fn csv_without_header_and_whitespace_separated() {
    let pts = points();
    for (name, separator) in [("plain.csv", ","), ("spaced.txt", " ")] {
        let text: String = pts
            .iter()
            .map(|p| format!("{}{separator}{}\n", p[0], p[1]))
            .collect();
        let written = round_trip(name, &text);
        let lines: Vec<&str> = written.lines().collect();
        check_rows(&lines, &pts);
        assert_eq!(lines[0].contains(','), separator == ",", "{name}: {}", lines[0]);
    }
}

#[test]
fn json_document_keeps_its_other_keys() {
    let pts = points();
    let document = serde_json::json!({ "name": "NACA 2412 upper", "units": "chord", "points": pts });
    let written: serde_json::Value =
        serde_json::from_str(&round_trip("in.json", &document.to_string())).unwrap();
    assert_eq!(written["name"], "NACA 2412 upper");
    assert_eq!(written["units"], "chord");
    let got: Vec<[f64; 2]> = serde_json::from_value(written["points"].clone()).unwrap();
    assert_eq!(got, pts);

    // JSON on standard input.
    let run = fair(&["curve", "-", "-o", "-"], Some(&document.to_string()));
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let written: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(written["name"], "NACA 2412 upper");
}

#[test]
fn selig_airfoil_keeps_its_name_line() {
    let pts = points();
    let text = std::iter::once("NACA 2412 upper (Selig format)".to_string())
        .chain(pts.iter().map(|p| format!("  {:.6}  {:.6}", p[0], p[1])))
        .collect::<Vec<_>>()
        .join("\n");
    let expected: Vec<[f64; 2]> = text
        .lines()
        .skip(1)
        .map(|l| {
            let v = numbers(l);
            [v[0], v[1]]
        })
        .collect();
    let written = round_trip("naca2412.dat", &text);
    let lines: Vec<&str> = written.lines().collect();
    assert_eq!(lines[0], "NACA 2412 upper (Selig format)");
    check_rows(&lines[1..], &expected);
}
