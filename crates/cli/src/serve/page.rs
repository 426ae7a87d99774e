//! The page: HTML, JavaScript and CSS in `crates/cli/assets/serve/`, embedded in the binary
//! (`include_str!`): no build step, nothing fetched from elsewhere, so it works offline.
//!
//! The page only draws and asks: every number it shows comes from the API ([`super::api`]).
//! Its Content-Security-Policy allows scripts, styles and requests from this server only.

use super::http::Response;

/// The page's HTML.
pub(crate) const INDEX: &str = include_str!("../../assets/serve/index.html");
/// The page's script.
pub(crate) const SCRIPT: &str = include_str!("../../assets/serve/app.js");
/// The page's style sheet.
pub(crate) const STYLE: &str = include_str!("../../assets/serve/style.css");

/// What the page may load and where it may send requests: this server only.
pub(crate) const CONTENT_SECURITY_POLICY: &str = "default-src 'none'; script-src 'self'; style-src 'self'; \
     img-src 'self' data: blob:; connect-src 'self'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'";

fn asset(content_type: &'static str, text: &str) -> Response {
    Response {
        status: 200,
        content_type,
        headers: vec![("Content-Security-Policy", CONTENT_SECURITY_POLICY.to_string())],
        body: text.as_bytes().to_vec(),
    }
}

/// `GET /`.
pub(crate) fn index() -> Response {
    asset("text/html; charset=utf-8", INDEX)
}

/// `GET /app.js`.
pub(crate) fn script() -> Response {
    asset("text/javascript; charset=utf-8", SCRIPT)
}

/// `GET /style.css`.
pub(crate) fn style() -> Response {
    asset("text/css; charset=utf-8", STYLE)
}
