//! A small synchronous HTTP/1.1 server: `httparse` reads the request head, the rest is here.
//!
//! One request per connection (`Connection: close`), which is all a local page needs and keeps
//! every limit simple:
//! - the head is read up to [`Settings::max_head`] bytes (431 past it), the body up to
//!   [`Settings::max_body`] (413 past it, decided from `Content-Length` before a byte of the
//!   body is read); a body must come with `Content-Length` (411 otherwise: no chunked uploads);
//! - a request must arrive whole within [`Settings::read_deadline`] or [`Settings::deadline`],
//!   whichever is shorter (408 otherwise), however
//!   it trickles in: each read's timeout is what is left of that deadline, so a client sending
//!   one byte every few seconds cannot hold a connection for longer;
//! - every connection is read on its own thread, at most [`Settings::queue`] at once and
//!   [`Settings::per_client`] from one address (503 past either), so slow clients hold
//!   threads that sleep, never the workers;
//! - [`Settings::workers`] requests are answered (faired) at once; a request has
//!   [`Settings::deadline`] (`fair serve --deadline`) from its first byte to the last byte of
//!   its answer, reading, fairing and writing. The work runs under a [`Cancel`] token with
//!   that deadline ([`optim::cancel`]); the connection's thread watches it, every
//!   [`WATCH`], and cancels the token when the deadline passes (the answer is then 503
//!   naming the deadline) or when the client has closed its connection (nothing to answer).
//!   The work stops at its next checkpoint and frees its worker: abandoned work does not
//!   burn a core. A client that half-closes its connection (shuts down its sending side)
//!   while waiting counts as gone: HTTP/1.1 clients, the page's `fetch` and curl among
//!   them, do not;
//! - an answer over [`Settings::max_response`] bytes is not sent: 422 naming the limit;
//! - duplicate `Host`, `Content-Length` or `Transfer-Encoding` headers are refused (400): two
//!   framings of one request are how requests are smuggled past proxies;
//! - a panic while handling a request is caught and answered with 500: the server lives on.
//!
//! Why not `tiny_http` (the usual light choice): its 0.12 release drains an unread body into
//! one buffer the size of the declared `Content-Length`, so a single request declaring 10^17
//! bytes aborts the whole process ("memory allocation failed"); checked against 0.12.0.
//!
//! Requests whose `Host` is not a loopback name are refused (403) while the server listens on a
//! loopback address: a web page elsewhere cannot reach it through DNS rebinding.

use std::collections::HashMap;
use std::io::{self, BufRead, BufReader, Read, Write};
use std::net::{IpAddr, Ipv4Addr, SocketAddr, TcpListener, TcpStream};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use optim::cancel::Cancel;

use super::api::{self, Context};

/// How often the connection's thread checks a request being answered for its deadline and
/// for its client having left: the longest a cancelled request's work goes on unwatched.
const WATCH: Duration = Duration::from_millis(100);

/// The least time an answer made at the deadline (the 503 saying so) has to be written.
const GRACE: Duration = Duration::from_secs(1);

/// How the server listens and what it accepts.
#[derive(Debug, Clone)]
pub(crate) struct Settings {
    /// The address to listen on (default 127.0.0.1).
    pub bind: IpAddr,
    /// The port (0: any free port).
    pub port: u16,
    /// The largest request body in bytes.
    pub max_body: usize,
    /// The largest request head (request line and headers) in bytes. Default 64 KiB.
    pub max_head: usize,
    /// Write timeout of a connection, and the longest wait for one read. Default 30 s.
    pub timeout: Duration,
    /// The time a whole request (head and body) has to arrive. Default 20 s.
    pub read_deadline: Duration,
    /// The time from a request's first byte to the last byte of its answer (reading,
    /// fairing, writing). Default 120 s (`fair serve --deadline`).
    pub deadline: Duration,
    /// Requests answered at once. Default 8 (fairing is CPU-bound; more would only share
    /// the cores).
    pub workers: usize,
    /// Connections open at once (being read, waiting or answered). Default 256.
    pub queue: usize,
    /// Connections open at once from one address. Default 64 (a page may fire dozens of
    /// requests at once; every local client shares 127.0.0.1).
    pub per_client: usize,
    /// The largest answer body in bytes. Default 64 MiB.
    pub max_response: usize,
    /// Print one line per request on standard error.
    pub log: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            bind: IpAddr::V4(Ipv4Addr::LOCALHOST),
            port: super::DEFAULT_PORT,
            max_body: super::DEFAULT_MAX_UPLOAD,
            max_head: 64 << 10,
            timeout: Duration::from_secs(30),
            read_deadline: Duration::from_secs(20),
            deadline: Duration::from_secs(120),
            workers: 8,
            queue: 256,
            per_client: 64,
            max_response: 64 << 20,
            log: false,
        }
    }
}

/// A request as the routes see it: method, path (without the query) and body.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Request {
    /// `GET`, `POST`, ...
    pub method: String,
    /// The path as sent, percent-encoded, without `?query`.
    pub path: String,
    /// The `Content-Type` header, if any.
    pub content_type: Option<String>,
    /// The body.
    pub body: Vec<u8>,
}

/// An answer: status, content type and body (plus headers for the page).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Response {
    /// The HTTP status.
    pub status: u16,
    /// The `Content-Type`.
    pub content_type: &'static str,
    /// Further headers.
    pub headers: Vec<(&'static str, String)>,
    /// The body.
    pub body: Vec<u8>,
}

impl Response {
    /// A JSON answer.
    pub(crate) fn json(status: u16, value: &serde_json::Value) -> Response {
        Response {
            status,
            content_type: "application/json",
            headers: Vec::new(),
            body: value.to_string().into_bytes(),
        }
    }

    /// A JSON error answer `{"error": message}`.
    pub(crate) fn error(status: u16, message: impl Into<String>) -> Response {
        Response::json(status, &serde_json::json!({ "error": message.into() }))
    }

    /// Adds a header.
    pub(crate) fn with_header(mut self, name: &'static str, value: impl Into<String>) -> Response {
        self.headers.push((name, value.into()));
        self
    }
}

/// The reason phrase of the statuses the server sends.
fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        408 => "Request Timeout",
        411 => "Length Required",
        413 => "Content Too Large",
        415 => "Unsupported Media Type",
        417 => "Expectation Failed",
        422 => "Unprocessable Content",
        431 => "Request Header Fields Too Large",
        500 => "Internal Server Error",
        501 => "Not Implemented",
        503 => "Service Unavailable",
        505 => "HTTP Version Not Supported",
        _ => "Status",
    }
}

/// A listening server; [`Server::run`] serves until the process ends.
#[derive(Debug)]
pub(crate) struct Server {
    listener: TcpListener,
    context: Arc<Context>,
    settings: Settings,
}

impl Server {
    /// Binds to the settings' address and port.
    pub(crate) fn bind(settings: &Settings, context: Context) -> io::Result<Server> {
        let listener = TcpListener::bind(SocketAddr::new(settings.bind, settings.port))?;
        Ok(Server {
            listener,
            context: Arc::new(context),
            settings: settings.clone(),
        })
    }

    /// The address bound (with the port chosen when 0 was asked for).
    pub(crate) fn local_addr(&self) -> SocketAddr {
        self.listener
            .local_addr()
            .unwrap_or_else(|_| SocketAddr::new(self.settings.bind, self.settings.port))
    }

    /// Accepts connections, each read on its own thread within the connection limits;
    /// returns only if accepting fails for good.
    pub(crate) fn run(self) {
        let local = self.local_addr();
        let open = Arc::new(Open::default());
        let slots = Arc::new(Slots::new(self.settings.workers.max(1)));
        for stream in self.listener.incoming() {
            // A failed accept (a client gone before it was accepted, too many open files) is
            // that client's loss; the server goes on.
            let Ok(stream) = stream else { continue };
            let client = stream
                .peer_addr()
                .map_or(IpAddr::V4(Ipv4Addr::UNSPECIFIED), |a| a.ip());
            let Some(ticket) = open.enter(client, &self.settings) else {
                refuse_busy(stream, &self.settings);
                continue;
            };
            let context = Arc::clone(&self.context);
            let settings = self.settings.clone();
            let slots = Arc::clone(&slots);
            let spawned = std::thread::Builder::new().spawn(move || {
                let _ticket = ticket;
                serve_connection(stream, &context, &settings, &slots, local);
            });
            // No thread to be had: the connection (moved into the closure) is dropped.
            drop(spawned);
        }
    }
}

/// The connections open, in all and by client address.
#[derive(Default)]
struct Open {
    counts: Mutex<(usize, HashMap<IpAddr, usize>)>,
}

/// One open connection, counted until dropped.
struct Ticket {
    open: Arc<Open>,
    client: IpAddr,
}

impl Open {
    /// Counts a connection from `client`, or `None` when a limit is reached.
    fn enter(self: &Arc<Self>, client: IpAddr, settings: &Settings) -> Option<Ticket> {
        let mut counts = self
            .counts
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let (total, by_client) = &mut *counts;
        let mine = by_client.entry(client).or_insert(0);
        if *total >= settings.queue.max(1) || *mine >= settings.per_client.max(1) {
            return None;
        }
        *total += 1;
        *mine += 1;
        Some(Ticket {
            open: Arc::clone(self),
            client,
        })
    }
}

impl Drop for Ticket {
    fn drop(&mut self) {
        let mut counts = self
            .open
            .counts
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let (total, by_client) = &mut *counts;
        *total = total.saturating_sub(1);
        if let Some(mine) = by_client.get_mut(&self.client) {
            *mine -= 1;
            if *mine == 0 {
                by_client.remove(&self.client);
            }
        }
    }
}

/// Answers 503 to a connection over the limits without reading it, never waiting on the
/// client (the accepting thread must not block).
fn refuse_busy(stream: TcpStream, settings: &Settings) {
    let _ = stream.set_nonblocking(true);
    let response = Response::error(
        503,
        format!(
            "too many connections: at most {} at once, {} from one address",
            settings.queue, settings.per_client
        ),
    );
    let mut stream = stream;
    let _ = write_response(&mut stream, &response, false, Instant::now() + GRACE);
}

/// The workers: how many requests may be answered at once.
struct Slots {
    free: Mutex<usize>,
    freed: Condvar,
}

impl Slots {
    fn new(count: usize) -> Slots {
        Slots {
            free: Mutex::new(count),
            freed: Condvar::new(),
        }
    }

    /// Takes a slot, waiting until `deadline` at most; false if none came free by then.
    fn take(&self, deadline: Instant) -> bool {
        let mut free = self
            .free
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        while *free == 0 {
            let now = Instant::now();
            if now >= deadline {
                return false;
            }
            free = match self.freed.wait_timeout(free, deadline - now) {
                Ok((guard, _)) => guard,
                Err(poisoned) => poisoned.into_inner().0,
            };
        }
        *free -= 1;
        true
    }

    fn give_back(&self) {
        let mut free = self
            .free
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        *free += 1;
        self.freed.notify_one();
    }
}

/// What the watch over a request's work gave.
enum Answered {
    /// The answer to send.
    Response(Response),
    /// The client left before the answer was ready; its work was cancelled.
    Gone,
}

/// Answers `request` on a worker by `deadline`, watching the work every [`WATCH`]: 503 when
/// no worker comes free or the answer is not ready by then, [`Answered::Gone`] when the
/// client closes its connection first. Either way the work's token is cancelled, so the
/// work stops at its next checkpoint and gives its worker back.
fn answer_in_time(
    request: Request,
    context: &Arc<Context>,
    slots: &Arc<Slots>,
    deadline: Instant,
    settings: &Settings,
    client: &TcpStream,
) -> Answered {
    let limit = settings.deadline.as_secs_f64();
    let late = || {
        Response::error(
            503,
            format!("the request was not answered within its deadline of {limit} s (fair serve --deadline); its work was stopped: send fewer points or lighter settings"),
        )
    };
    if !slots.take(deadline) {
        return Answered::Response(Response::error(
            503,
            format!("the server is busy: no worker came free within the request's deadline of {limit} s"),
        ));
    }
    let token = Cancel::with_deadline(deadline);
    let (sender, receiver) = std::sync::mpsc::channel();
    let context = Arc::clone(context);
    let held = Arc::clone(slots);
    let work = token.clone();
    let spawned = std::thread::Builder::new().spawn(move || {
        let response = work.scope(|| answer(request, &context));
        held.give_back();
        let _ = sender.send(response);
    });
    if spawned.is_err() {
        slots.give_back();
        return Answered::Response(Response::error(503, "the server could not start a worker thread"));
    }
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        match receiver.recv_timeout(left.min(WATCH)) {
            // The work stopped at a checkpoint because the deadline passed.
            Ok(response) if response.status == 503 && token.is_cancelled() => {
                return Answered::Response(late())
            }
            Ok(response) if response.body.len() > settings.max_response => {
                return Answered::Response(Response::error(
                    422,
                    format!(
                        "the answer has {} bytes, more than the limit of {} bytes: send fewer points",
                        response.body.len(),
                        settings.max_response
                    ),
                ))
            }
            Ok(response) => return Answered::Response(response),
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                return Answered::Response(Response::error(
                    500,
                    "internal error: the worker stopped without an answer",
                ))
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                if Instant::now() >= deadline {
                    token.cancel();
                    return Answered::Response(late());
                }
                if client_gone(client) {
                    token.cancel();
                    return Answered::Gone;
                }
            }
        }
    }
}

/// Whether the client has closed its connection: a non-blocking peek reads end of file (or
/// the connection was reset). Bytes waiting (a pipelined request) count as present. O(1).
fn client_gone(stream: &TcpStream) -> bool {
    if stream.set_nonblocking(true).is_err() {
        return false;
    }
    let mut byte = [0u8; 1];
    let gone = match stream.peek(&mut byte) {
        Ok(0) => true,
        Ok(_) => false,
        Err(e) => !matches!(
            e.kind(),
            io::ErrorKind::WouldBlock | io::ErrorKind::Interrupted | io::ErrorKind::TimedOut
        ),
    };
    let _ = stream.set_nonblocking(false);
    gone
}

/// What reading a request gave: a request, or the answer to send instead.
enum Incoming {
    Request(Request, Option<String>),
    Refused(Response),
    Gone,
}

/// Reads one request, answers it, closes the connection. Never panics past this point: a
/// panic in the routes becomes a 500.
fn serve_connection(
    stream: TcpStream,
    context: &Arc<Context>,
    settings: &Settings,
    slots: &Arc<Slots>,
    local: SocketAddr,
) {
    let started = Instant::now();
    let _ = stream.set_read_timeout(Some(settings.timeout));
    let _ = stream.set_write_timeout(Some(settings.timeout));
    let _ = stream.set_nodelay(true);
    let Ok(write_half) = stream.try_clone() else {
        return;
    };
    let mut reader = BufReader::new(stream);
    let deadline = started + settings.deadline;
    let read_by = started + settings.read_deadline.min(settings.deadline);
    let (line, head_only, response) = match read_request(&mut reader, settings, &write_half, read_by) {
        Incoming::Gone => return,
        Incoming::Refused(response) => ("-".to_string(), false, response),
        Incoming::Request(request, host) => {
            let line = format!("{} {}", request.method, request.path);
            let head_only = request.method == "HEAD";
            let response = match host_problem(host.as_deref(), local) {
                Some(problem) => Response::error(403, problem),
                None => match answer_in_time(request, context, slots, deadline, settings, &write_half) {
                    Answered::Response(response) => response,
                    Answered::Gone => {
                        if settings.log {
                            let _ = writeln!(
                                io::stderr(),
                                "fair serve: {line} → client left, work stopped ({:.1} ms)",
                                started.elapsed().as_secs_f64() * 1e3
                            );
                        }
                        return;
                    }
                },
            };
            (line, head_only, response)
        }
    };
    let refused_early = response.status == 413 || response.status == 431 || response.status == 411;
    let mut writer = write_half;
    let _ = write_response(
        &mut writer,
        &response,
        head_only,
        deadline.max(Instant::now() + GRACE),
    );
    if refused_early {
        // The client may still be sending a body we will not read: close our side, then
        // read (and drop) what arrives for a moment, so that the kernel does not reset the
        // connection before the client has read the answer.
        let _ = writer.shutdown(std::net::Shutdown::Write);
        linger(&mut reader);
    }
    if settings.log {
        let _ = writeln!(
            io::stderr(),
            "fair serve: {line} → {} ({:.1} ms)",
            response.status,
            started.elapsed().as_secs_f64() * 1e3
        );
    }
}

/// Reads and drops input for at most 2 s or 64 MiB, whichever comes first.
fn linger(reader: &mut BufReader<TcpStream>) {
    let deadline = Instant::now() + Duration::from_secs(2);
    let _ = reader
        .get_ref()
        .set_read_timeout(Some(Duration::from_millis(200)));
    let mut buffer = [0u8; 16 << 10];
    let mut total = 0usize;
    while Instant::now() < deadline && total < 64 << 20 {
        match reader.read(&mut buffer) {
            Ok(0) => return,
            Ok(n) => total += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) if matches!(e.kind(), io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut) => {}
            Err(_) => return,
        }
    }
}

/// The routes, with a panic turned into a 500.
fn answer(request: Request, context: &Context) -> Response {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| api::handle(&request, context))).unwrap_or_else(
        |payload| {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown failure".into());
            Response::error(500, format!("internal error: {message}"))
        },
    )
}

/// Why a `Host` is refused on a loopback server, if it is: anything but `localhost`, a
/// loopback address or the bound address, with or without the port.
fn host_problem(host: Option<&str>, local: SocketAddr) -> Option<String> {
    if !local.ip().is_loopback() {
        return None;
    }
    let Some(host) = host else {
        return Some("a request needs a Host header".into());
    };
    // Strip the port: `[::1]:8765`, `127.0.0.1:8765`, `localhost`.
    let name = if let Some(rest) = host.strip_prefix('[') {
        rest.split(']').next().unwrap_or("")
    } else {
        host.rsplit_once(':').map_or(host, |(name, _)| name)
    };
    let loopback =
        name.eq_ignore_ascii_case("localhost") || name.parse::<IpAddr>().is_ok_and(|ip| ip.is_loopback());
    (!loopback).then(|| {
        format!("Host `{host}` refused: this server answers requests to localhost only (start it with --bind to serve others)")
    })
}

/// Sets the read timeout to what is left before `deadline` (at most the settings' timeout);
/// false when nothing is left.
fn arm(reader: &BufReader<TcpStream>, deadline: Instant, settings: &Settings) -> bool {
    let left = deadline.saturating_duration_since(Instant::now());
    if left.is_zero() {
        return false;
    }
    let _ = reader
        .get_ref()
        .set_read_timeout(Some(left.min(settings.timeout)));
    true
}

fn read_request(
    reader: &mut BufReader<TcpStream>,
    settings: &Settings,
    writer: &TcpStream,
    deadline: Instant,
) -> Incoming {
    let late = |what: &str| {
        Incoming::Refused(Response::error(
            408,
            format!(
                "the request {what} did not arrive within {} s",
                settings.read_deadline.as_secs_f64()
            ),
        ))
    };
    // The head: read until the blank line, within max_head.
    let mut head = Vec::with_capacity(1024);
    loop {
        if !arm(reader, deadline, settings) {
            return if head.is_empty() {
                Incoming::Gone
            } else {
                late("head")
            };
        }
        let available = match reader.fill_buf() {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) if matches!(e.kind(), io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut) => {
                return if head.is_empty() {
                    Incoming::Gone
                } else {
                    Incoming::Refused(Response::error(408, "the request head did not arrive in time"))
                };
            }
            Err(_) => return Incoming::Gone,
        };
        if available.is_empty() {
            return Incoming::Gone;
        }
        // Take bytes up to and including the end of the head, if it is in this chunk.
        let before = head.len();
        head.extend_from_slice(available);
        let end = find_head_end(&head, before.saturating_sub(3));
        let used = match end {
            Some(end) => end - before,
            None => available.len(),
        };
        reader.consume(used);
        if let Some(end) = end {
            head.truncate(end);
            break;
        }
        if head.len() > settings.max_head {
            return Incoming::Refused(Response::error(
                431,
                format!("the request head is over {} bytes", settings.max_head),
            ));
        }
    }
    if head.len() > settings.max_head {
        return Incoming::Refused(Response::error(
            431,
            format!("the request head is over {} bytes", settings.max_head),
        ));
    }
    let mut headers = [httparse::EMPTY_HEADER; 64];
    let mut parsed = httparse::Request::new(&mut headers);
    match parsed.parse(&head) {
        Ok(httparse::Status::Complete(_)) => {}
        Ok(httparse::Status::Partial) => {
            return Incoming::Refused(Response::error(400, "incomplete request head"));
        }
        Err(httparse::Error::TooManyHeaders) => {
            return Incoming::Refused(Response::error(431, "more than 64 request headers"));
        }
        Err(e) => return Incoming::Refused(Response::error(400, format!("malformed request: {e}"))),
    }
    let (Some(method), Some(target)) = (parsed.method, parsed.path) else {
        return Incoming::Refused(Response::error(400, "malformed request line"));
    };
    let header = |name: &str| {
        parsed
            .headers
            .iter()
            .find(|h| h.name.eq_ignore_ascii_case(name))
            .map(|h| String::from_utf8_lossy(h.value).trim().to_string())
    };
    for framing in ["host", "content-length", "transfer-encoding"] {
        let count = parsed
            .headers
            .iter()
            .filter(|h| h.name.eq_ignore_ascii_case(framing))
            .count();
        if count > 1 {
            return Incoming::Refused(Response::error(
                400,
                format!("the request has {count} `{framing}` headers; one is allowed"),
            ));
        }
    }
    if header("transfer-encoding").is_some() {
        return Incoming::Refused(Response::error(
            411,
            "chunked request bodies are not accepted; send the body with Content-Length",
        ));
    }
    let length = match header("content-length") {
        None => 0,
        Some(text) => match text.parse::<u64>() {
            Ok(n) => n,
            Err(_) => {
                return Incoming::Refused(Response::error(
                    400,
                    format!("Content-Length `{text}` is not a number"),
                ))
            }
        },
    };
    if length > settings.max_body as u64 {
        return Incoming::Refused(Response::error(
            413,
            format!(
                "the request body has {length} bytes, more than the limit of {} (fair serve --max-upload)",
                settings.max_body
            ),
        ));
    }
    match header("expect") {
        None => {}
        Some(value) if value.eq_ignore_ascii_case("100-continue") => {
            let mut writer = writer;
            let _ = writer.write_all(b"HTTP/1.1 100 Continue\r\n\r\n");
        }
        Some(value) => {
            return Incoming::Refused(Response::error(417, format!("Expect `{value}` is not supported")));
        }
    }
    let length = length as usize;
    let mut body = Vec::with_capacity(length.min(1 << 20));
    let mut chunk = [0u8; 64 << 10];
    while body.len() < length {
        if !arm(reader, deadline, settings) {
            return late("body");
        }
        let want = (length - body.len()).min(chunk.len());
        match reader.read(&mut chunk[..want]) {
            Ok(0) => return Incoming::Gone,
            Ok(n) => body.extend_from_slice(&chunk[..n]),
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) if matches!(e.kind(), io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut) => {
                return late("body");
            }
            Err(_) => return Incoming::Gone,
        }
    }
    let path = target.split(['?', '#']).next().unwrap_or("").to_string();
    let request = Request {
        method: method.to_string(),
        path,
        content_type: header("content-type"),
        body,
    };
    Incoming::Request(request, header("host"))
}

/// The index just past `\r\n\r\n` in `bytes`, searching from `from`.
fn find_head_end(bytes: &[u8], from: usize) -> Option<usize> {
    bytes
        .get(from..)?
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .map(|p| from + p + 4)
}

/// Writes the answer by `deadline`: each write waits at most what is left of it, so a client
/// that reads slowly cannot hold the connection past it (the answer is then cut off).
fn write_response(
    writer: &mut TcpStream,
    response: &Response,
    head_only: bool,
    deadline: Instant,
) -> io::Result<()> {
    let mut text = format!(
        "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nConnection: close\r\n\
         Cache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nReferrer-Policy: no-referrer\r\n",
        response.status,
        reason(response.status),
        response.content_type,
        response.body.len()
    );
    for (name, value) in &response.headers {
        text.push_str(&format!("{name}: {value}\r\n"));
    }
    text.push_str("\r\n");
    let mut bytes = text.into_bytes();
    if !head_only {
        bytes.extend_from_slice(&response.body);
    }
    for chunk in bytes.chunks(64 << 10) {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Err(io::Error::new(
                io::ErrorKind::TimedOut,
                "the request's deadline passed",
            ));
        }
        let _ = writer.set_write_timeout(Some(left));
        writer.write_all(chunk)?;
    }
    writer.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn local() -> SocketAddr {
        "127.0.0.1:8765".parse().unwrap()
    }

    #[test]
    fn hosts_on_loopback() {
        for ok in [
            "127.0.0.1:8765",
            "localhost:1",
            "localhost",
            "[::1]:8765",
            "127.0.0.2",
            "LOCALHOST:9",
        ] {
            assert_eq!(host_problem(Some(ok), local()), None, "{ok}");
        }
        for bad in [
            "evil.example:8765",
            "192.168.1.4:8765",
            "[2001:db8::1]:80",
            "localhost.evil.example",
        ] {
            assert!(host_problem(Some(bad), local()).is_some(), "{bad}");
        }
        assert!(host_problem(None, local()).is_some());
        let open: SocketAddr = "0.0.0.0:8765".parse().unwrap();
        assert_eq!(host_problem(Some("anything"), open), None);
    }

    #[test]
    fn head_end() {
        assert_eq!(find_head_end(b"GET / HTTP/1.1\r\n\r\nbody", 0), Some(18));
        assert_eq!(find_head_end(b"GET / HTTP/1.1\r\n", 0), None);
        assert_eq!(find_head_end(b"ab", 5), None);
    }
}
