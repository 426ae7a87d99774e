//! The server stays available to a normal request while slow or hostile clients hold
//! connections, refuses ambiguous framing, reads regular files only and shows no local path.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use super::client::{get, raw};
use super::{scratch, Served};

#[test]
fn sixteen_trickling_connections_do_not_hold_a_normal_request() {
    let server = Served::start(&[]);
    // Sixteen requests whose heads never end: a byte every 200 ms each (twice the old pool
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
                std::thread::sleep(Duration::from_millis(200));
            }
            slow
        })
    };
    std::thread::sleep(Duration::from_millis(500));
    // The normal request is answered, not refused with 503 at its deadline (before, it was
    // not answered at all while the trickle went on).
    let reply = get(&server.address, "/api/methods");
    assert_eq!(reply.status, 200, "{}", reply.error());
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
