//! The page in headless Chromium, driven over WebDriver (chromedriver) with plain HTTP: load a
//! data set, click a point, fair it, check that the comb redraws and that the counts shown are
//! the command's report, undo and check the points are the input's bit for bit. Screenshots
//! of each state go to `target/tmp/serve-browser/`.
//!
//! Needs `chromium` and `chromedriver` on the PATH (Debian: `apt-get install chromium
//! chromium-driver`). Without them the test says so and passes, unless `CI` is set: then it
//! fails, because CI must run it (`.ci/run` installs both).

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use super::client::{get, request, Reply};
use super::{command_report, file_bits, root, scratch, Served};
use serde_json::{json, Value};

const WL03: &str = "data/hull_gunnerus/waterlines/wl_03.csv";
/// The point the test fairs: the largest third-derivative jump of the waterline's ripple.
const POINT: usize = 12;

fn which(names: &[&str]) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    names
        .iter()
        .flat_map(|name| std::env::split_paths(&path).map(move |dir| dir.join(name)))
        .find(|candidate| candidate.is_file())
}

/// A running chromedriver, stopped by its process id when dropped.
struct Driver {
    child: Child,
    address: String,
}

impl Drop for Driver {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Driver {
    fn start(binary: &Path) -> Driver {
        // A free port from the system, handed to chromedriver (which takes no port 0).
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .expect("a free port")
            .port();
        let child = Command::new(binary)
            .arg(format!("--port={port}"))
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromedriver");
        let driver = Driver {
            child,
            address: format!("127.0.0.1:{port}"),
        };
        let deadline = Instant::now() + Duration::from_secs(30);
        loop {
            if let Ok(reply) = request(&driver.address, "GET", "/status", &[], b"") {
                if reply.status == 200 && reply.json()["value"]["ready"] == true {
                    return driver;
                }
            }
            assert!(Instant::now() < deadline, "chromedriver did not start");
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    fn call(&self, method: &str, path: &str, body: Option<Value>) -> Value {
        let text = body.map(|b| b.to_string()).unwrap_or_default();
        let headers: &[(&str, &str)] = if text.is_empty() {
            &[]
        } else {
            &[("Content-Type", "application/json")]
        };
        let reply: Reply =
            request(&self.address, method, path, headers, text.as_bytes()).expect("WebDriver request");
        let value = reply.json();
        assert_eq!(reply.status, 200, "{method} {path}: {value}");
        value["value"].clone()
    }
}

/// One browser session.
struct Session<'a> {
    driver: &'a Driver,
    id: String,
}

impl Session<'_> {
    fn post(&self, path: &str, body: Value) -> Value {
        self.driver
            .call("POST", &format!("/session/{}{path}", self.id), Some(body))
    }

    fn script(&self, script: &str) -> Value {
        self.post("/execute/sync", json!({ "script": script, "args": [] }))
    }

    fn wait_for(&self, what: &str, script: &str) {
        let deadline = Instant::now() + Duration::from_secs(90);
        while self.script(script) != Value::Bool(true) {
            let status = self.script("return document.getElementById('status').textContent");
            assert!(Instant::now() < deadline, "waiting for {what}; status: {status}");
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    fn ready_with(&self, history: usize, index: usize) {
        self.wait_for(
            &format!("history {history}, index {index}"),
            &format!(
                "const b = document.body.dataset; return b.state === 'ready' && b.history === '{history}' && b.index === '{index}'"
            ),
        );
    }

    fn click(&self, css: &str) {
        let element = self.post("/element", json!({ "using": "css selector", "value": css }));
        let id = element
            .as_object()
            .and_then(|o| o.values().next())
            .and_then(Value::as_str)
            .unwrap_or_else(|| panic!("no element {css}: {element}"))
            .to_string();
        self.post(&format!("/element/{id}/click"), json!({}));
    }

    fn screenshot(&self, path: &Path) {
        let encoded = self
            .driver
            .call("GET", &format!("/session/{}/screenshot", self.id), None);
        let png = base64(encoded.as_str().expect("base64 text"));
        assert!(png.starts_with(b"\x89PNG"), "not a PNG");
        std::fs::write(path, png).expect("write screenshot");
    }

    fn attribute(&self, id: &str, name: &str) -> String {
        self.script(&format!(
            "const e = document.getElementById('{id}'); return e ? e.getAttribute('{name}') : null"
        ))
        .as_str()
        .unwrap_or_else(|| panic!("no #{id}"))
        .to_string()
    }

    fn points_bits(&self) -> Vec<Vec<u64>> {
        let text = self.script("return JSON.stringify(window.fairPage.current().points)");
        let value: Value = serde_json::from_str(text.as_str().unwrap()).unwrap();
        super::bits(&value)
    }
}

fn base64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    };
    let digits: Vec<u8> = text.bytes().filter_map(value).collect();
    let mut out = Vec::with_capacity(digits.len() * 3 / 4);
    for chunk in digits.chunks(4) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, d)| n | (u32::from(*d) << (18 - 6 * i)));
        out.extend(&n.to_be_bytes()[1..chunk.len()]);
    }
    out
}

#[test]
fn base64_decodes() {
    assert_eq!(base64("TWFu"), b"Man");
    assert_eq!(base64("TWE="), b"Ma");
    assert_eq!(base64("TQ=="), b"M");
}

#[test]
fn the_page_fairs_a_clicked_point_and_undoes_it() {
    let (Some(chromium), Some(chromedriver)) = (
        which(&["chromium", "chromium-browser", "google-chrome"]),
        which(&["chromedriver"]),
    ) else {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI is set but chromium or chromedriver is missing: .ci/run installs them"
        );
        eprintln!("skipping the browser test: chromium and chromedriver are not on the PATH");
        return;
    };
    let shots = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("serve-browser");
    std::fs::create_dir_all(&shots).unwrap();
    let profile_guard = scratch("chromium-profile");
    let profile = profile_guard.path();
    let server = Served::start(&[]);
    let driver = Driver::start(&chromedriver);
    let created = driver.call(
        "POST",
        "/session",
        Some(json!({ "capabilities": { "alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {
                "binary": chromium,
                "args": [
                    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                    "--disable-background-networking", "--disable-component-update", "--disable-sync",
                    "--disable-dev-shm-usage",
                    "--window-size=1400,900", format!("--user-data-dir={}", profile.display()),
                ],
            },
        } } })),
    );
    let session = Session {
        driver: &driver,
        id: created["sessionId"].as_str().expect("a session").to_string(),
    };
    session.post("/url", json!({ "url": format!("http://{}/", server.address) }));
    session.wait_for("the page", "return document.body.dataset.state === 'ready'");

    // Load the waterline from the data set list.
    session.click(r#"#dataset option[value="gunnerus-wl03"]"#);
    session.ready_with(1, 0);
    session.screenshot(&shots.join("1-loaded.png"));
    let loaded = file_bits(&root().join(WL03));
    assert_eq!(session.points_bits(), loaded);
    let comb_before = session.attribute("comb", "d");
    assert!(comb_before.matches('M').count() > 100, "no comb drawn");

    // Click the point, then fair it.
    session.click(&format!(r#"#points [data-index="{POINT}"]"#));
    assert_eq!(
        session.script("return window.fairPage.selection().bad"),
        json!([POINT])
    );
    session.screenshot(&shots.join("2-picked.png"));
    session.click("#fair-selected");
    session.ready_with(2, 1);
    session.screenshot(&shots.join("3-faired.png"));

    // The comb was drawn anew, every tooth of the answer's comb.
    let comb_after = session.attribute("comb", "d");
    assert_ne!(comb_after, comb_before, "the comb did not redraw");
    let teeth = session.script("return window.fairPage.current().drawing.comb.points.length");
    assert_eq!(comb_after.matches('M').count() as u64, teeth.as_u64().unwrap());

    // The numbers shown are the command's report for the same point.
    let dir_guard = scratch("browser-command");
    let dir = dir_guard.path();
    let out = dir.join("faired.csv");
    let path = root().join(WL03).display().to_string();
    let point = POINT.to_string();
    let report = command_report(
        &[
            "curve",
            &path,
            "--method",
            "strain-energy",
            "--points",
            &point,
            "-o",
            out.to_str().unwrap(),
        ],
        &dir.join("report.json"),
    );
    assert_eq!(report["moved"], json!([POINT]), "the command moved other points");
    let shown = session.script(
        "const out = {}; for (const td of document.querySelectorAll('[data-field]')) \
         out[td.dataset.field] = [td.dataset.value, td.textContent]; return out",
    );
    let mut compared = 0;
    for (field, expected) in [
        "before.inflections",
        "before.vibrations",
        "before.e_s",
        "before.max_z",
        "after.inflections",
        "after.vibrations",
        "after.e_s",
        "after.max_z",
        "before.energies.e1",
        "before.energies.ek",
        "after.energies.e2",
        "after.energies.ek_prime",
        "s_d",
        "m_d",
        "iterations",
    ]
    .iter()
    .map(|f| (*f, f.split('.').fold(&report, |v, key| &v[key])))
    {
        let value = shown[field][0]
            .as_str()
            .unwrap_or_else(|| panic!("{field} not shown: {shown}"));
        let parsed: f64 = value.parse().unwrap_or_else(|_| panic!("{field} = {value}"));
        assert_eq!(
            parsed.to_bits(),
            expected.as_f64().unwrap().to_bits(),
            "{field}: shown {value}, report {expected}"
        );
        if expected.is_u64() {
            assert_eq!(shown[field][1], json!(expected.to_string()), "{field} as text");
        }
        compared += 1;
    }
    assert_eq!(compared, 15);
    let moved = report["moved"].as_array().unwrap().len().to_string();
    assert_eq!(shown["moved"][0], json!(moved));
    assert_eq!(
        session.points_bits(),
        file_bits(&out),
        "the page's points are not the command's"
    );

    // Undo: the input, bit for bit, and its comb as first drawn.
    session.click("#undo");
    session.ready_with(2, 0);
    session.screenshot(&shots.join("4-undone.png"));
    assert_eq!(session.points_bits(), loaded, "undo did not restore the input");
    assert_eq!(session.attribute("comb", "d"), comb_before);
    // Redo: the faired points again.
    session.click("#redo");
    session.ready_with(2, 1);
    assert_eq!(session.points_bits(), file_bits(&out));

    driver.call("DELETE", &format!("/session/{}", session.id), None);
    assert_eq!(get(&server.address, "/api/methods").status, 200);
}
