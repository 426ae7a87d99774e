//! The `fair` binary on bad input: exit status 2, one line on standard error naming the file
//! (and the line where there is one), never a panic or a backtrace.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A file named `name` in a fresh scratch directory; reads as its path (`Deref<Target = Path>`),
/// and the directory goes with everything in it when this is dropped.
struct TempFile {
    path: PathBuf,
    _dir: tempfile::TempDir,
}

impl std::ops::Deref for TempFile {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.path
    }
}

/// A fresh file under the system temp directory holding `text`.
fn temp_file(name: &str, text: &str) -> TempFile {
    let dir = crate::scratch_dir("fair-cli-test-");
    let path = dir.path().join(name);
    std::fs::write(&path, text).expect("temp file");
    TempFile { path, _dir: dir }
}

fn fair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .output()
        .expect("run fair")
}

fn fair_with_stdin(args: &[&str], stdin: &str) -> Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("spawn fair");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(stdin.as_bytes())
        .expect("write stdin");
    child.wait_with_output().expect("wait fair")
}

/// Asserts exit status 2 and a single clean stderr line containing every `needle`; returns it.
fn assert_bad_input(output: &Output, needles: &[&str]) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    assert_eq!(output.status.code(), Some(2), "stderr: {stderr}");
    assert!(
        !stderr.contains("panicked") && !stderr.contains("RUST_BACKTRACE"),
        "{stderr}"
    );
    assert_eq!(stderr.trim_end().lines().count(), 1, "not one line: {stderr:?}");
    assert!(stderr.starts_with("fair: "), "{stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "`{needle}` not in {stderr:?}");
    }
    stderr
}

#[test]
fn empty_file() {
    let path = temp_file("empty.csv", "");
    let p = path.to_str().unwrap();
    for sub in ["curve", "inspect", "surface"] {
        assert_bad_input(&fair(&[sub, p]), &[p, "no points"]);
    }
}

#[test]
fn one_point() {
    let path = temp_file("one.csv", "x,y\n1.0,2.0\n");
    let p = path.to_str().unwrap();
    assert_bad_input(&fair(&["curve", p]), &[p, "1 point"]);
    assert_bad_input(&fair(&["inspect", p]), &[p, "1 point"]);
}

#[test]
fn non_numeric_field() {
    let path = temp_file("text.csv", "x,y\n0,0\n1,1\n2,abc\n3,0\n");
    let p = path.to_str().unwrap();
    let line = format!("{p}:4:");
    assert_bad_input(&fair(&["curve", p]), &[&line, "abc"]);
    assert_bad_input(&fair(&["inspect", p]), &[&line, "abc"]);
}

#[test]
fn nan_value() {
    let path = temp_file("nan.csv", "0,0\n1,NaN\n2,0\n3,1\n");
    let p = path.to_str().unwrap();
    assert_bad_input(&fair(&["curve", p]), &[&format!("{p}:2:"), "not finite"]);
    let path = temp_file("inf.json", "{\"points\": [\n[0, 0],\n[1, 1e999],\n[2, 0]\n]}");
    let p = path.to_str().unwrap();
    assert_bad_input(&fair(&["curve", p]), &[&format!("{p}:3:")]);
}

#[test]
fn mismatched_columns() {
    let path = temp_file("ragged.csv", "x,y\n0,0\n1,1\n2,2,2\n3,0\n");
    let p = path.to_str().unwrap();
    assert_bad_input(&fair(&["curve", p]), &[&format!("{p}:4:"), "3 fields"]);
}

#[test]
fn bad_surface_grid() {
    let path = temp_file("grid.csv", "i,j,x,y,z\n0,0,0,0,0\n0,1,0,1,0\n0,0,1,0,0\n");
    let p = path.to_str().unwrap();
    assert_bad_input(&fair(&["surface", p]), &[&format!("{p}:4:"), "twice"]);
    let path = temp_file("holes.csv", "i,j,x,y,z\n0,0,0,0,0\n0,1,0,1,0\n1,0,1,0,0\n");
    let p = path.to_str().unwrap();
    assert_bad_input(&fair(&["surface", p]), &[p, "missing"]);
}

#[test]
fn missing_file() {
    let dir = crate::scratch_dir("fair-cli-test-");
    let path = dir.path().join("does-not-exist.csv");
    let p = path.to_str().unwrap();
    assert_bad_input(&fair(&["curve", p]), &[p, "cannot read"]);
    assert_bad_input(&fair(&["inspect", p]), &[p, "cannot read"]);
}

#[test]
fn unknown_method() {
    let path = temp_file("good.csv", "x,y\n0,0\n1,1\n2,0\n3,1\n4,0\n");
    let p = path.to_str().unwrap();
    assert_bad_input(
        &fair(&["curve", p, "--method", "no-such-method"]),
        &["no-such-method", "two-phase"],
    );
    assert_bad_input(&fair(&["curve", p, "--method", "zhang-cheng"]), &["zhang-cheng"]);
}

#[test]
fn unknown_subcommand_and_bad_options() {
    assert_bad_input(&fair(&["frobnicate"]), &["frobnicate"]);
    assert_bad_input(&fair(&[]), &["subcommand"]);
    let path = temp_file("opts.csv", "x,y\n0,0\n1,1\n2,0\n3,1\n4,0\n");
    let p = path.to_str().unwrap();
    assert_bad_input(&fair(&["curve", p, "--fixed", "1,x"]), &["--fixed", "x"]);
    assert_bad_input(&fair(&["curve", p, "--set", "novalue"]), &["NAME=VALUE"]);
    assert_bad_input(&fair(&["curve", p, "--tolerance", "-3"]), &["-3"]);
    assert_bad_input(&fair(&["curve", p, "--clamp-ends", "g7"]), &["g7"]);
    assert_bad_input(&fair(&["curve", p, "--fixed", "9"]), &["--fixed", "index 9"]);
    assert_bad_input(
        &fair(&["curve", p, "--method", "batten", "--set", "zz=1"]),
        &["--set", "zz"],
    );
    assert_bad_input(
        &fair(&["curve", p, "--kind", "function", "--bogus"]),
        &["--bogus"],
    );
}

#[test]
fn function_kind_needs_increasing_x() {
    let path = temp_file("loop.csv", "x,y\n0,0\n1,1\n0.5,2\n");
    let p = path.to_str().unwrap();
    assert_bad_input(
        &fair(&["curve", p, "--kind", "function"]),
        &[&format!("{p}:4:"), "increasing"],
    );
}

#[test]
fn standard_input_errors_name_stdin() {
    let output = fair_with_stdin(&["curve", "-"], "x,y\n0,0\n1,oops\n");
    assert_bad_input(&output, &["<stdin>:3:", "oops"]);
}

#[test]
fn help_version_and_methods_succeed() {
    for args in [
        &["--help"][..],
        &["--version"],
        &["methods"],
        &["curve", "--help"],
    ] {
        let output = fair(args);
        assert_eq!(
            output.status.code(),
            Some(0),
            "{args:?}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
        assert!(!output.stdout.is_empty());
    }
    let methods = String::from_utf8_lossy(&fair(&["methods"]).stdout).to_string();
    for name in [
        "two-phase",
        "strain-energy",
        "kjellander",
        "poliakoff",
        "batten",
        "nurbs-weights",
        "smoothing-spline",
        "sapidis-farin",
        "zhang-cheng",
    ] {
        assert!(methods.contains(name), "{name} missing from\n{methods}");
    }
    // The default method of each kind of input is named (the door's constants).
    assert!(
        methods.contains(
            "defaults: jump-lsq for functions, jump-lsq for parametric curves, jump-lsq for surfaces"
        ),
        "{methods}"
    );
}

/// An output path that cannot be written is found before anything is written: a bad
/// `--report` leaves no fresh `-o` file behind its exit status 2.
#[test]
fn unwritable_targets_are_found_before_writing() {
    let rows: String = (0..8).map(|k| format!("{k},{}\n", (k * k) % 5)).collect();
    let input = temp_file("c.csv", &format!("x,y\n{rows}"));
    let dir = input.parent().unwrap();
    let out = dir.join("out.csv");
    let missing = dir.join("no-such-dir").join("r.json");
    let result = fair(&[
        "curve",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--report",
        missing.to_str().unwrap(),
    ]);
    assert_bad_input(&result, &["r.json", "no directory"]);
    assert!(!out.exists(), "the output was written before the report failed");
    let result = fair(&["curve", input.to_str().unwrap(), "-o", dir.to_str().unwrap()]);
    assert_bad_input(&result, &["directory"]);
}
