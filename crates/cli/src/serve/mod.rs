//! `fair serve`: interactive fairing in the browser, a local web page over a JSON API.
//!
//! The page (HTML, JavaScript and CSS embedded in the binary, [`page`]; no build step, no CDN,
//! works offline) draws what the API returns: the curve with its curvature comb, the z_i bars
//! and the x–c polyline or κ(t) plot; for surfaces the highlight lines and the z_ij map. It
//! holds no fairing logic of its own: every number comes from the API, which runs the same
//! code as `fair curve`, `fair surface` and `fair inspect` ([`engine`]), so its reports are
//! the command's reports.
//!
//! - [`http`]: a small synchronous HTTP/1.1 server (one request per connection, bounded
//!   header and body sizes, a deadline per request that cancels its work, a fixed pool of
//!   worker threads);
//! - [`limits`]: the work one request may ask for (points, nodes, iterations);
//! - [`api`]: the routes, the request and answer bodies, errors as 4xx with a message;
//! - [`engine`]: the one door to the fairing code (switching to the library's catalogue is a
//!   change inside it);
//! - [`drawing`]: what the page draws, beside the report: samples, comb, z, curvature,
//!   highlight lines;
//! - [`datasets`]: the embedded data sets and the files or folders named on the command line.
//!
//! Safe by default: it binds to 127.0.0.1 unless `--bind` says otherwise, refuses bodies over
//! `--max-upload` bytes, answers every bad request with a 4xx status and a one-line message,
//! and keeps no state between requests (the page keeps its history), so two tabs or users never
//! see each other's data.

pub(crate) mod api;
pub(crate) mod datasets;
pub(crate) mod drawing;
pub(crate) mod engine;
pub(crate) mod http;
pub(crate) mod limits;
pub(crate) mod page;

use std::io::Write;

use fair_door::error::{Error, Result};

pub(crate) use crate::args::{ServeArgs, DEFAULT_MAX_UPLOAD, DEFAULT_PORT};

/// Runs `fair serve`: binds, prints `fair serve: http://ADDR:PORT/` on standard output, and
/// serves until the process is stopped. Fails (exit status 2) when a FILE does not exist or
/// the address cannot be bound.
pub(crate) fn run(catalog: &fairing::catalog::Catalog, args: &ServeArgs) -> Result<()> {
    let datasets = datasets::Datasets::new(&args.files)?;
    let context = api::Context {
        catalog: catalog.clone(),
        datasets,
        max_upload: args.max_upload,
    };
    let settings = http::Settings {
        bind: args.bind,
        port: args.port,
        max_body: args.max_upload,
        deadline: std::time::Duration::from_secs(args.deadline),
        log: !args.quiet,
        ..http::Settings::default()
    };
    let server = http::Server::bind(&settings, context).map_err(|e| Error::Argument {
        option: "--port",
        message: format!("cannot listen on {}:{}: {e}", args.bind, args.port),
    })?;
    let address = server.local_addr();
    let mut out = std::io::stdout();
    let _ = writeln!(out, "fair serve: http://{address}/");
    let _ = out.flush();
    if !args.bind.is_loopback() {
        let _ = writeln!(
            std::io::stderr(),
            "fair serve: listening on {} — anyone who reaches this address can use the page and read the files given",
            args.bind
        );
    }
    server.run();
    Ok(())
}
