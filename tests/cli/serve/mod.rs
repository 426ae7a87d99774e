//! `fair serve`: the JSON API against the command's own reports ([`api`]), bad requests,
//! concurrency, and the page in headless Chromium ([`browser`]).
//!
//! Each test starts its own `fair serve --port 0` (the port the system gives is read from the
//! first line the command prints) and stops it when done.

mod api;
mod availability;
mod browser;
mod client;

use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

/// A running `fair serve`, stopped (by its process id) when dropped.
pub(crate) struct Served {
    child: Child,
    /// `127.0.0.1:PORT`.
    pub(crate) address: String,
}

impl Served {
    /// Starts `fair serve --port 0 --quiet EXTRA...` and waits for its address.
    pub(crate) fn start(extra: &[&str]) -> Served {
        let mut child = Command::new(env!("CARGO_BIN_EXE_fair"))
            .args(["serve", "--port", "0", "--quiet"])
            .args(extra)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("start fair serve");
        let mut line = String::new();
        std::io::BufReader::new(child.stdout.take().expect("stdout"))
            .read_line(&mut line)
            .expect("read the address");
        let address = line
            .trim()
            .strip_prefix("fair serve: http://")
            .and_then(|rest| rest.strip_suffix('/'))
            .unwrap_or_else(|| panic!("unexpected first line {line:?}"))
            .to_string();
        Served { child, address }
    }

    /// Whether the server process is still running.
    pub(crate) fn alive(&mut self) -> bool {
        matches!(self.child.try_wait(), Ok(None))
    }

    /// The CPU time the server process has used so far, user and system, in clock ticks
    /// (utime + stime of /proc/PID/stat; 100 a second on Linux).
    #[cfg(target_os = "linux")]
    pub(crate) fn cpu_ticks(&self) -> u64 {
        let stat = std::fs::read_to_string(format!("/proc/{}/stat", self.child.id())).expect("stat");
        // Fields after the command name (which ends at the last `)`): state is field 3, utime 14.
        let rest = &stat[stat.rfind(')').expect("comm") + 2..];
        let fields: Vec<&str> = rest.split_whitespace().collect();
        fields[11].parse::<u64>().unwrap() + fields[12].parse::<u64>().unwrap()
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The repository's root (data files are read from `data/` there).
pub(crate) fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh directory for a test's files, removed when the returned guard is dropped.
pub(crate) fn scratch(name: &str) -> tempfile::TempDir {
    crate::scratch_dir(&format!("fair-serve-{name}-"))
}

/// Runs `fair ARGS` and returns the report it wrote with `--report`, checking success.
pub(crate) fn command_report(args: &[&str], report: &Path) -> serde_json::Value {
    let output = Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(args)
        .arg("--report")
        .arg(report)
        .output()
        .expect("run fair");
    assert!(
        output.status.success(),
        "fair {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_str(&std::fs::read_to_string(report).expect("report")).expect("report JSON")
}

/// The value with every `elapsed_ms` (a time, different on each run) removed.
pub(crate) fn untimed(value: &serde_json::Value) -> serde_json::Value {
    match value {
        serde_json::Value::Object(map) => serde_json::Value::Object(
            map.iter()
                .filter(|(k, _)| k.as_str() != "elapsed_ms")
                .map(|(k, v)| (k.clone(), untimed(v)))
                .collect(),
        ),
        serde_json::Value::Array(list) => serde_json::Value::Array(list.iter().map(untimed).collect()),
        other => other.clone(),
    }
}

/// Coordinate rows as exact bit patterns, so that comparisons are bit for bit.
pub(crate) fn bits(rows: &serde_json::Value) -> Vec<Vec<u64>> {
    rows.as_array()
        .expect("rows")
        .iter()
        .map(|r| {
            r.as_array()
                .expect("row")
                .iter()
                .map(|c| c.as_f64().expect("number").to_bits())
                .collect()
        })
        .collect()
}

/// A curve file's points as the command reads them, as exact bit patterns.
pub(crate) fn file_bits(path: &Path) -> Vec<Vec<u64>> {
    let input = fair::fair_cli::input::read_curve(&path.display().to_string()).expect("read curve");
    input
        .points
        .rows()
        .iter()
        .map(|r| r.iter().map(|c| c.to_bits()).collect())
        .collect()
}
