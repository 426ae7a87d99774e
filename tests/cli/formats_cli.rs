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

/// A whitespace table with a header is read by the header's names, from a file and from
/// standard input: with `y x` the second column is x (increasing, so `--kind function`
/// holds), and the output keeps the header and the columns where they were.
#[test]
fn a_whitespace_header_names_the_columns() {
    let pts = points();
    let text: String = std::iter::once("y x\n".to_string())
        .chain(pts.iter().map(|p| format!("{} {}\n", p[1], p[0])))
        .collect();
    let swapped: Vec<[f64; 2]> = pts.iter().map(|p| [p[1], p[0]]).collect();
    let written = round_trip("table.txt", &text);
    let lines: Vec<&str> = written.lines().collect();
    assert_eq!(lines[0], "y x");
    check_rows(&lines[1..], &swapped);
    // A `.dat` file with such a header is a table too; `-o *.dat` writes a Selig file, x first.
    let written = round_trip("table.dat", &text);
    let lines: Vec<&str> = written.lines().collect();
    assert_eq!(lines[0], "table");
    check_rows(&lines[1..], &pts);
    let run = fair(&["curve", "-", "-o", "-", "--kind", "function"], Some(&text));
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let stdout = String::from_utf8(run.stdout).unwrap();
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines[0], "y x");
    check_rows(&lines[1..], &swapped);
}

/// Another key's value comes back as written: a 23-digit integer digit for digit, the keys
/// in the file's order; a key given twice is refused with its line.
#[test]
fn json_other_values_come_back_as_written() {
    let pts = points();
    let text = format!(
        "{{\"zulu\": \"first\",\n \"id\": 12345678901234567890123,\n \"points\": {},\n \"alpha\": 1.50}}",
        serde_json::to_string(&pts).unwrap()
    );
    let written = round_trip("keys.json", &text);
    let at = |needle: &str| {
        written
            .find(needle)
            .unwrap_or_else(|| panic!("{needle} in {written}"))
    };
    assert!(at("\"zulu\"") < at("\"id\": 12345678901234567890123,"));
    assert!(at("\"id\"") < at("\"points\"") && at("\"points\"") < at("\"alpha\": 1.50"));
    let twice = "{\"points\": [[0, 0], [1, 1], [2, 0]],\n\"units\": \"m\",\n\"units\": \"mm\"}";
    let run = fair(&["curve", "-", "-o", "-"], Some(twice));
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.starts_with("fair: <stdin>:3: the key `units` is given twice"),
        "{stderr}"
    );
}

/// x not strictly increasing: `--kind function` refuses naming the line; `auto` fairs it as
/// parametric and says so on standard error with the line.
#[test]
fn a_function_file_whose_x_goes_back_is_named() {
    let text = "x,y\n0,0\n1,0.5\n3,0.2\n2,0.9\n4,0.1\n5,0.3\n";
    let run = fair(&["curve", "-", "-o", "-", "--kind", "function"], Some(text));
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.starts_with("fair: <stdin>:5: --kind function needs x strictly increasing"),
        "{stderr}"
    );
    let run = fair(&["curve", "-", "-o", "-"], Some(text));
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let stderr = String::from_utf8_lossy(&run.stderr);
    let note = stderr
        .lines()
        .find(|l| l.contains("parametric curve"))
        .unwrap_or_else(|| panic!("no note in {stderr}"));
    assert!(
        note.starts_with("fair: note: <stdin>:5: x = 2 follows x = 3, so x is not strictly increasing"),
        "{note}"
    );
    let run = fair(&["curve", "-", "-o", "-", "-q"], Some(text));
    assert!(!String::from_utf8_lossy(&run.stderr).contains("parametric curve"));
}

/// Garbage of any length without a line end (old Mac files, binary) gives one short line.
#[test]
fn a_message_quotes_a_few_hundred_characters_at_most() {
    let cr_only = format!("x,y\r0,1\r1,{}\r", "9".repeat(2_000_000) + "q");
    let one_line = format!("{}\n", "z".repeat(3_000_000));
    for text in [cr_only, one_line] {
        let run = fair(&["curve", "-", "-o", "-"], Some(&text));
        assert_eq!(run.status.code(), Some(2));
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(stderr.lines().count(), 1, "{}", &stderr[..200.min(stderr.len())]);
        assert!(
            stderr.chars().count() <= 500,
            "{} characters",
            stderr.chars().count()
        );
    }
}

/// A surface grid is read by its header's names: `x,y,z,j,i` gives the grid `i,j,x,y,z`
/// gives, faired the same, each written back in its own column order.
#[test]
fn a_surface_grid_is_read_by_name() {
    let cell = |i: usize, j: usize| {
        let (x, y) = (i as f64, j as f64);
        [
            x,
            y,
            0.1 * x * y + if (i + j).is_multiple_of(3) { 0.05 } else { 0.0 },
        ]
    };
    let mut plain = String::from("i,j,x,y,z\n");
    let mut moved = String::from("x,y,z,j,i\n");
    for i in 0..6 {
        for j in 0..5 {
            let [x, y, z] = cell(i, j);
            plain.push_str(&format!("{i},{j},{x},{y},{z}\n"));
            moved.push_str(&format!("{x},{y},{z},{j},{i}\n"));
        }
    }
    let surface = |text: &str| {
        let mut child = Command::new(env!("CARGO_BIN_EXE_fair"))
            .args(["surface", "-", "-o", "-", "-q"])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        child.stdin.take().unwrap().write_all(text.as_bytes()).unwrap();
        let run = child.wait_with_output().unwrap();
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        String::from_utf8(run.stdout).unwrap()
    };
    // Each output as (i, j) -> (x, y, z), by its own header.
    let cells = |written: &str| {
        let mut rows = written.lines();
        let header: Vec<&str> = rows.next().unwrap().split(',').collect();
        let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
        let mut cells: Vec<(i64, i64, [f64; 3])> = rows
            .map(|row| {
                let v = numbers(row);
                (
                    v[column("i")] as i64,
                    v[column("j")] as i64,
                    [v[column("x")], v[column("y")], v[column("z")]],
                )
            })
            .collect();
        cells.sort_by_key(|c| (c.0, c.1));
        (header.join(","), cells)
    };
    let (plain_header, plain_cells) = cells(&surface(&plain));
    let (moved_header, moved_cells) = cells(&surface(&moved));
    assert_eq!(
        (plain_header.as_str(), moved_header.as_str()),
        ("i,j,x,y,z", "x,y,z,j,i")
    );
    assert_eq!(plain_cells.len(), 30);
    assert_eq!(plain_cells, moved_cells);
}
