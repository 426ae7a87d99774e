//! Outputs written completely or not at all (`cad::atomic`): two outputs naming one file
//! refused before the run, a failing output leaving no other new file, and a run killed at
//! any moment leaving each output old or complete.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn fair_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fair"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run fair")
}

/// `n` points of the noisy segment as a CSV with an `x,y` header.
fn noisy_csv(n: usize) -> String {
    let mut text = String::from("x,y\n");
    for [x, y] in crate::noisy_segment::noisy_segment(n, 0.01, 20_261_206) {
        text.push_str(&format!("{x},{y}\n"));
    }
    text
}

/// The names in `dir`, sorted.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("read dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn two_outputs_naming_one_file_are_refused_before_the_run() {
    let dir = crate::scratch_dir("fair-atomic-");
    std::fs::write(dir.path().join("in.csv"), noisy_csv(50)).unwrap();
    std::fs::write(dir.path().join("x.csv"), "old\n").unwrap();
    let cases: [(&[&str], &str, &str, &str); 5] = [
        (&["-o", "x.csv", "--report", "x.csv"], "-o", "--report", "x.csv"),
        (&["--report", "x.csv", "-o", "./x.csv"], "-o", "--report", "x.csv"),
        (&["-o", "./x.csv", "--plot", "x.csv"], "-o", "--plot", "x.csv"),
        (
            &["--report", "r.json", "--plot", "./r.json"],
            "--report",
            "--plot",
            "./r.json",
        ),
        (&["-o", "-", "--report", "-"], "-o", "--report", "<stdout>"),
    ];
    for (outputs, first, second, path) in cases {
        let mut args = vec!["curve", "in.csv"];
        args.extend_from_slice(outputs);
        let r = fair_in(dir.path(), &args);
        let stderr = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&format!(
                "{path}: cannot write: {first} and {second} both name it"
            )),
            "{args:?}: {stderr}"
        );
        assert!(r.stdout.is_empty(), "{args:?}");
        assert_eq!(entries(dir.path()), ["in.csv", "x.csv"], "{args:?}");
        assert_eq!(
            std::fs::read_to_string(dir.path().join("x.csv")).unwrap(),
            "old\n"
        );
    }
    // Writing over the input is allowed: the output replaces it when complete.
    let r = fair_in(dir.path(), &["curve", "in.csv", "-o", "./in.csv", "-q"]);
    assert_eq!(r.status.code(), Some(0), "{}", String::from_utf8_lossy(&r.stderr));
    assert_eq!(entries(dir.path()), ["in.csv", "x.csv"]);
    assert_eq!(
        std::fs::read_to_string(dir.path().join("in.csv"))
            .unwrap()
            .lines()
            .count(),
        51
    );
}

#[test]
fn lines_refuses_two_outputs_naming_one_file() {
    let dir = crate::scratch_dir("fair-atomic-lines-");
    let table = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/hull_block_island_boat/offsets_table_inches.csv"
    );
    let r = fair_in(
        dir.path(),
        &["lines", table, "--report", "r.json", "--plot", "./r.json"],
    );
    let stderr = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("./r.json: cannot write: --report and --plot both name it"),
        "{stderr}"
    );
    assert!(entries(dir.path()).is_empty());
}

#[cfg(target_os = "linux")]
#[test]
fn a_failing_output_leaves_no_other_new_file() {
    let dir = crate::scratch_dir("fair-atomic-full-");
    std::fs::write(dir.path().join("in.csv"), noisy_csv(200)).unwrap();
    // No -o file before: none after.
    let r = fair_in(
        dir.path(),
        &["curve", "in.csv", "-o", "out.csv", "--report", "/dev/full"],
    );
    let stderr = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("/dev/full: cannot write: "), "{stderr}");
    assert_eq!(entries(dir.path()), ["in.csv"]);
    // An old -o file: intact, byte for byte, also when the plot is what fails.
    let old = b"x,y\n0,0\n1,1\n\xff old bytes\n".to_vec();
    std::fs::write(dir.path().join("out.csv"), &old).unwrap();
    let failing: [&[&str]; 2] = [
        &["curve", "in.csv", "-o", "out.csv", "--report", "/dev/full"],
        &[
            "curve",
            "in.csv",
            "-o",
            "out.csv",
            "--report",
            "r.json",
            "--plot",
            "no/such/dir/p.svg",
        ],
    ];
    for args in failing {
        let r = fair_in(dir.path(), args);
        assert_eq!(
            r.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&r.stderr)
        );
        assert_eq!(
            std::fs::read(dir.path().join("out.csv")).unwrap(),
            old,
            "{args:?}"
        );
        assert_eq!(entries(dir.path()), ["in.csv", "out.csv"], "{args:?}");
    }
    // /dev/null takes an output and is left a device.
    let r = fair_in(
        dir.path(),
        &["curve", "in.csv", "-o", "out.csv", "--report", "/dev/null", "-q"],
    );
    assert_eq!(r.status.code(), Some(0), "{}", String::from_utf8_lossy(&r.stderr));
    assert_ne!(std::fs::read(dir.path().join("out.csv")).unwrap(), old);
    assert!(!std::fs::metadata("/dev/null").unwrap().is_file());
}

/// What a killed run may leave in place of an output: the old bytes, or a complete new file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Old,
    New,
}

/// The kill test's files: the input and three outputs, each with old content to keep.
struct KillCase {
    dir: tempfile::TempDir,
    points: usize,
    old: [Vec<u8>; 3],
}

const OUTPUTS: [&str; 3] = ["out.csv", "report.json", "plot.svg"];

impl KillCase {
    fn new(points: usize) -> Self {
        let dir = crate::scratch_dir("fair-atomic-kill-");
        std::fs::write(dir.path().join("in.csv"), noisy_csv(points)).unwrap();
        let old = [
            b"x,y\n0,0\n1,1\n".to_vec(),
            b"{\"old\": true}\n".to_vec(),
            b"<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>\n".to_vec(),
        ];
        let case = KillCase { dir, points, old };
        case.reset();
        case
    }

    /// The outputs back to their old content, leftover temporary files removed.
    fn reset(&self) {
        for name in entries(self.dir.path()) {
            if name.contains(".fair-tmp-") {
                std::fs::remove_file(self.dir.path().join(name)).unwrap();
            }
        }
        for (name, old) in OUTPUTS.iter().zip(&self.old) {
            std::fs::write(self.dir.path().join(name), old).unwrap();
        }
    }

    fn spawn(&self) -> std::process::Child {
        Command::new(env!("CARGO_BIN_EXE_fair"))
            .current_dir(self.dir.path())
            .args([
                "curve",
                "in.csv",
                "--method",
                "strain-energy",
                "--kind",
                "parametric",
            ])
            .args([
                "-o",
                "out.csv",
                "--report",
                "report.json",
                "--plot",
                "plot.svg",
                "-q",
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("spawn fair")
    }

    /// Whether the run has begun writing: a temporary file, or an output no longer old.
    fn writing(&self) -> bool {
        entries(self.dir.path()).iter().any(|n| n.contains(".fair-tmp-"))
            || OUTPUTS
                .iter()
                .zip(&self.old)
                .any(|(name, old)| std::fs::read(self.dir.path().join(name)).ok().as_ref() != Some(old))
    }

    /// Each output's state; panics on a truncated or otherwise broken one, or on a leftover
    /// file that is not a recognisable temporary file.
    fn states(&self) -> [State; 3] {
        let read = |i: usize| std::fs::read(self.dir.path().join(OUTPUTS[i])).expect("output exists");
        let state = |i: usize, complete: &dyn Fn(&[u8]) -> bool| {
            let bytes = read(i);
            if bytes == self.old[i] {
                State::Old
            } else {
                assert!(
                    complete(&bytes),
                    "{} is neither old nor complete ({} bytes)",
                    OUTPUTS[i],
                    bytes.len()
                );
                State::New
            }
        };
        let points = self.points;
        let csv = move |b: &[u8]| {
            let text = std::str::from_utf8(b).unwrap_or("");
            let rows: Vec<&str> = text.lines().skip(1).collect();
            text.starts_with("x,y\n")
                && text.ends_with('\n')
                && rows.len() == points
                && rows.iter().all(|r| {
                    let v: Vec<Option<f64>> = r.split(',').map(|c| c.parse().ok()).collect();
                    v.len() == 2 && v.iter().all(|c| c.is_some_and(f64::is_finite))
                })
        };
        let json = |b: &[u8]| serde_json::from_slice::<serde_json::Value>(b).is_ok_and(|v| v.is_object());
        let svg = |b: &[u8]| b.starts_with(b"<svg") && b.ends_with(b"</svg>\n");
        for name in entries(self.dir.path()) {
            let known = name == "in.csv" || OUTPUTS.contains(&name.as_str());
            let temporary = OUTPUTS
                .iter()
                .any(|o| name.starts_with(&format!(".{o}.fair-tmp-")));
            assert!(known || temporary, "unexpected file left: {name}");
        }
        [state(0, &csv), state(1, &json), state(2, &svg)]
    }
}

/// A run killed (SIGKILL) at seeded moments, half of them anywhere in the run and half while
/// it writes: every output is its old content byte for byte or a complete new file (the CSV
/// with every point, the report valid JSON, the SVG closed), and nothing else is left but
/// files named `.<output>.fair-tmp-*`.
#[cfg(unix)]
#[test]
fn a_killed_run_leaves_each_output_old_or_complete() {
    use std::os::unix::process::ExitStatusExt;
    let case = KillCase::new(6_000);
    // One whole run: its duration, the moment it began writing, and complete outputs.
    let start = Instant::now();
    let mut child = case.spawn();
    let mut began = None;
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if began.is_none() && case.writing() {
            began = Some(start.elapsed());
        }
        std::thread::sleep(Duration::from_millis(1));
    };
    let total = start.elapsed();
    assert!(status.success(), "{status}");
    assert_eq!(case.states(), [State::New; 3]);
    assert_eq!(
        entries(case.dir.path()),
        ["in.csv", "out.csv", "plot.svg", "report.json"]
    );
    let began = began.unwrap_or(total);
    let writing = total.saturating_sub(began);

    let mut seed: u64 = 20_261_206;
    let mut uniform = move || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut killed_while_writing = 0;
    let mut seen = Vec::new();
    for k in 0..8 {
        case.reset();
        let start = Instant::now();
        let mut child = case.spawn();
        let u = uniform();
        if k % 2 == 0 {
            std::thread::sleep(total.mul_f64(u));
        } else {
            // Until it begins writing (or ends), then a fraction of the writing's duration.
            while child.try_wait().unwrap().is_none() && !case.writing() && start.elapsed() < 4 * total {
                std::thread::sleep(Duration::from_millis(1));
            }
            std::thread::sleep(writing.mul_f64(u));
        }
        let was_writing = case.writing();
        let _ = child.kill();
        let status = child.wait().unwrap();
        let states = case.states();
        if status.signal() == Some(9) && was_writing {
            killed_while_writing += 1;
        }
        seen.push((k, status.signal(), was_writing, states));
    }
    eprintln!("run {total:?}, writing {writing:?}; kills (k, signal, writing, states): {seen:?}");
    assert!(
        killed_while_writing >= 1,
        "no kill landed while the run was writing: {seen:?}"
    );
}
