//! The server stays available to a normal request while slow or hostile clients hold
//! connections, refuses ambiguous framing, reads regular files only and shows no local path.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use super::client::{get, post, raw};
use super::{scratch, Served};

#[test]
fn sixteen_trickling_connections_do_not_hold_a_normal_request() {
    let server = Served::start(&["--deadline", "10"]);
    // Sixteen requests whose heads never end: a byte every second each (twice the old pool
    // of workers, each of which such a client held for ever).
    let mut slow: Vec<TcpStream> = (0..16)
        .map(|_| {
            let mut s = TcpStream::connect(&server.address).unwrap();
            s.write_all(
                format!(
                    "GET /api/methods HTTP/1.1\r\nHost: {}\r\nX-Slow: ",
                    server.address
                )
                .as_bytes(),
            )
            .unwrap();
            s
        })
        .collect();
    let stop = Arc::new(AtomicBool::new(false));
    let trickle = {
        let stop = Arc::clone(&stop);
        std::thread::spawn(move || {
            while !stop.load(Ordering::Relaxed) {
                for s in &mut slow {
                    let _ = s.write_all(b"a");
                }
                // One byte a second, in short sleeps so that the test stops promptly.
                for _ in 0..10 {
                    if stop.load(Ordering::Relaxed) {
                        break;
                    }
                    std::thread::sleep(Duration::from_millis(100));
                }
            }
            slow
        })
    };
    std::thread::sleep(Duration::from_millis(2500));
    // The normal request is answered, and well within its deadline of 10 s (before, it was
    // not answered at all while the trickle went on).
    let asked = std::time::Instant::now();
    let reply = get(&server.address, "/api/methods");
    let took = asked.elapsed();
    assert_eq!(reply.status, 200, "{}", reply.error());
    assert!(took < Duration::from_secs(5), "the normal request took {took:?}");
    stop.store(true, Ordering::Relaxed);
    let slow = trickle.join().unwrap();
    // The slow requests were still being read: none of them has an answer yet.
    for mut s in slow {
        s.set_nonblocking(true).unwrap();
        let mut byte = [0u8; 1];
        assert!(
            matches!(s.read(&mut byte), Err(e) if e.kind() == std::io::ErrorKind::WouldBlock),
            "a trickling request was answered"
        );
    }
}

#[test]
fn duplicate_framing_headers_are_refused() {
    let server = Served::start(&[]);
    let host = format!("Host: {}\r\n", server.address);
    for extra in [host.as_str(), "Content-Length: 0\r\nContent-Length: 0\r\n"] {
        let request = format!("GET /api/methods HTTP/1.1\r\n{host}{extra}Connection: close\r\n\r\n");
        let reply = raw(&server.address, request.as_bytes()).unwrap();
        assert_eq!(reply.status, 400, "{extra:?}");
        assert!(
            reply.error().contains("headers; one is allowed"),
            "{}",
            reply.error()
        );
    }
}

#[cfg(unix)]
#[test]
fn a_listed_file_replaced_by_a_fifo_is_refused_and_no_path_is_shown() {
    let guard = scratch("fifo");
    let dir = guard.path().join("lines");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("a.csv"), "x,y\n0,0\n1,1\n2,0\n").unwrap();
    let server = Served::start(&[&dir.display().to_string()]);
    let list = get(&server.address, "/api/datasets").json().to_string();
    assert!(!list.contains(&guard.path().display().to_string()), "{list}");
    std::fs::remove_file(dir.join("a.csv")).unwrap();
    let made = std::process::Command::new("mkfifo")
        .arg(dir.join("a.csv"))
        .status();
    if !made.is_ok_and(|s| s.success()) {
        return;
    }
    let reply = get(&server.address, "/api/datasets/lines/a.csv");
    assert_eq!(reply.status, 400, "{}", reply.error());
    assert!(reply.error().contains("not a regular file"), "{}", reply.error());
}

/// A nurbs-weights request whose search (one weight per point, Nelder–Mead) takes far
/// longer than a second in the test build: every evaluation re-solves the curve.
fn slow_request(points: usize) -> String {
    let rows: Vec<[f64; 2]> = (0..points)
        .map(|i| {
            let x = i as f64 * 0.05;
            [x, x.sin() + 0.01 * (7.3 * i as f64).sin()]
        })
        .collect();
    serde_json::json!({
        "points": rows,
        "method": "nurbs-weights",
        "params": {"law": "per-point", "solver": "nelder-mead"},
    })
    .to_string()
}

/// The server's CPU ticks over `seconds` once whatever it was doing has had `settle` to stop.
#[cfg(target_os = "linux")]
fn ticks_after(server: &Served, settle: Duration, seconds: u64) -> u64 {
    std::thread::sleep(settle);
    let before = server.cpu_ticks();
    std::thread::sleep(Duration::from_secs(seconds));
    server.cpu_ticks() - before
}

#[cfg(target_os = "linux")]
#[test]
fn a_request_over_its_deadline_is_answered_503_and_its_work_stops() {
    let server = Served::start(&["--deadline", "1"]);
    let asked = std::time::Instant::now();
    let reply = post(&server.address, "/api/curve", &slow_request(500));
    let took = asked.elapsed();
    assert_eq!(reply.status, 503, "{}", reply.error());
    assert!(reply.error().contains("deadline of 1 s"), "{}", reply.error());
    assert!(took < Duration::from_secs(4), "the 503 came after {took:?}");
    // Before cancellation the search went on for tens of seconds at a full core (about 100
    // ticks a second); now it stops at its next check. Watched from 2 s after the 503: with
    // the window beginning 0.5 s after, a loaded machine (a load of 5–6 on 2 cores) saw 43 and
    // 58 ticks in it, the search not yet at its check; an uncancelled search, which runs for
    // tens of seconds, would still take a share of a core well above 30 ticks there.
    let grown = ticks_after(&server, Duration::from_secs(2), 3);
    assert!(
        grown <= 30,
        "the server used {grown} ticks in the 3 s after its 503"
    );
    // Its worker is free again: a light request is answered.
    let reply = get(&server.address, "/api/methods");
    assert_eq!(reply.status, 200, "{}", reply.error());
}

#[cfg(target_os = "linux")]
#[test]
fn the_work_of_a_client_that_leaves_stops() {
    let server = Served::start(&[]);
    let body = slow_request(500);
    let mut stream = TcpStream::connect(&server.address).unwrap();
    let head = format!(
        "POST /api/curve HTTP/1.1\r\nHost: {}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        server.address,
        body.len()
    );
    stream.write_all(head.as_bytes()).unwrap();
    stream.write_all(body.as_bytes()).unwrap();
    // The work is under way: the server burns CPU (waited for up to 20 s, as other tests and
    // builds may share the cores).
    let start = server.cpu_ticks();
    let waited = std::time::Instant::now();
    while server.cpu_ticks() - start < 50 && waited.elapsed() < Duration::from_secs(20) {
        std::thread::sleep(Duration::from_millis(100));
    }
    let working = server.cpu_ticks() - start;
    assert!(working >= 50, "the request used only {working} ticks in 20 s");
    drop(stream);
    let grown = ticks_after(&server, Duration::from_millis(500), 3);
    assert!(
        grown <= 30,
        "the server used {grown} ticks in the 3 s after its client left"
    );
}

#[test]
fn work_over_the_limits_is_refused_naming_the_limit() {
    let server = Served::start(&[]);
    let line = |n: usize| -> Vec<[f64; 2]> { (0..n).map(|i| [i as f64, 0.0]).collect() };
    let over = serde_json::json!({"points": line(50_001)}).to_string();
    let reply = post(&server.address, "/api/curve", &over);
    assert_eq!(reply.status, 413, "{}", reply.error());
    assert!(reply.error().contains("limit of 50000"), "{}", reply.error());
    // More points than any request may send are refused while the body is read.
    let far_over = serde_json::json!({"points": line(200_000)}).to_string();
    let reply = post(&server.address, "/api/inspect", &far_over);
    assert_eq!(reply.status, 413, "{}", reply.error());
    assert!(reply.error().contains("50000"), "{}", reply.error());
    let grid: Vec<[f64; 3]> = (0..301 * 300)
        .map(|k| [(k / 300) as f64, (k % 300) as f64, 0.0])
        .collect();
    let surface = serde_json::json!({"rows": 301, "columns": 300, "points": grid}).to_string();
    let reply = post(&server.address, "/api/surface", &surface);
    assert_eq!(reply.status, 413, "{}", reply.error());
    assert!(reply.error().contains("limit of 90000"), "{}", reply.error());
    for (method, name, value, limit) in [
        ("two-phase", "max-passes", "5000", "1000"),
        ("strain-energy", "max-iterations", "1000000", "100000"),
    ] {
        let body = serde_json::json!({
            "points": [[0, 0], [1, 0.2], [2, 0.1], [3, 0.35], [4, 0.3], [5, 0.5]],
            "method": method,
            "params": {name: value.parse::<f64>().unwrap()},
        })
        .to_string();
        let reply = post(&server.address, "/api/curve", &body);
        assert_eq!(reply.status, 422, "{}", reply.error());
        assert!(
            reply.error().contains(&format!("params.{name}")) && reply.error().contains(limit),
            "{}",
            reply.error()
        );
    }
    // At the limits the work is accepted.
    let body = serde_json::json!({
        "points": [[0, 0], [1, 0.2], [2, 0.1], [3, 0.35], [4, 0.3], [5, 0.5]],
        "method": "two-phase",
        "params": {"max-passes": 1000},
    })
    .to_string();
    let reply = post(&server.address, "/api/curve", &body);
    assert_eq!(reply.status, 200, "{}", reply.error());
}
