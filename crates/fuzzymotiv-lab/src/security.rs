//! Who may talk to the lab: requests carrying its random token (`?token=` once, which sets a
//! cookie, or the `x-fuzzymotiv-token` header) and naming the server in their `Host` header
//! (so that a page of another site, DNS rebinding included, cannot drive it). Every answer
//! carries a Content-Security-Policy that allows requests to the server only.

use std::sync::Arc;

use axum::extract::{Request, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Redirect, Response};

use crate::errors::ApiError;

/// The header that may carry the token instead of the cookie.
pub const TOKEN_HEADER: &str = "x-fuzzymotiv-token";

/// The page's policy: scripts, styles, images and connections from the server only.
pub const PAGE_CSP: &str = "default-src 'self'; img-src 'self' data:; frame-ancestors 'self'; base-uri 'none'; form-action 'self'";

/// A run's report (`report.html`, self-contained with inline scripts and styles): inline code
/// may run, but it may request nothing.
pub const REPORT_CSP: &str = "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data:; frame-ancestors 'self'; base-uri 'none'";

/// The lab's secret and the names it answers to.
pub struct Access {
    pub token: String,
    /// Allowed `Host` header values, e.g. `127.0.0.1:8000` and `localhost:8000`.
    pub hosts: Vec<String>,
    /// Bound to every interface (`0.0.0.0`, `::`): any IP address with the served port is also
    /// allowed (an address, unlike a name, cannot be rebound to another server).
    pub any_ip_port: Option<u16>,
    /// The cookie's name (with the port: cookies do not tell ports apart).
    pub cookie: String,
}

/// A random token: 128 bits from the operating system, as hex.
pub fn random_token() -> std::io::Result<String> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes).map_err(|e| std::io::Error::other(e.to_string()))?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// Compares in time independent of where the strings differ.
fn same(a: &str, b: &str) -> bool {
    a.len() == b.len() && a.bytes().zip(b.bytes()).fold(0u8, |d, (x, y)| d | (x ^ y)) == 0
}

impl Access {
    fn host_ok(&self, headers: &HeaderMap) -> bool {
        let host = headers.get(header::HOST).and_then(|h| h.to_str().ok());
        let listed = |h: &str| self.hosts.iter().any(|a| a.eq_ignore_ascii_case(h));
        let any_ip = |h: &str| {
            let addr = h.parse::<std::net::SocketAddr>();
            self.any_ip_port
                .is_some_and(|p| addr.is_ok_and(|a| a.port() == p))
        };
        host.is_some_and(|h| listed(h) || any_ip(h))
    }

    fn cookie_token<'h>(&self, headers: &'h HeaderMap) -> Option<&'h str> {
        let cookies = headers.get_all(header::COOKIE).into_iter();
        cookies
            .filter_map(|c| c.to_str().ok())
            .flat_map(|c| c.split(';'))
            .filter_map(|kv| kv.trim().split_once('='))
            .find(|(k, _)| *k == self.cookie)
            .map(|(_, v)| v)
    }

    fn header_token(headers: &HeaderMap) -> Option<&str> {
        headers.get(TOKEN_HEADER).and_then(|v| v.to_str().ok())
    }

    fn query_token(query: Option<&str>) -> Option<&str> {
        query?.split('&').find_map(|kv| kv.strip_prefix("token="))
    }
}

/// The middleware: Host check, then token check; `?token=` sets the cookie and redirects to
/// the same path without it; every answer gets the security headers.
pub async fn guard(State(access): State<Arc<Access>>, req: Request, next: Next) -> Response {
    let headers = req.headers();
    if !access.host_ok(headers) {
        let e = ApiError {
            status: StatusCode::FORBIDDEN,
            message: format!(
                "the Host header must name this server ({}); other names are refused (DNS rebinding)",
                access.hosts.join(" or ")
            ),
        };
        return with_headers(e.into_response(), PAGE_CSP);
    }
    let page = wants_page(headers);
    if let Some(t) = Access::query_token(req.uri().query()) {
        if !same(t, &access.token) {
            return with_headers(refused(page), PAGE_CSP);
        }
        let cookie = format!(
            "{}={}; Path=/; HttpOnly; SameSite=Strict",
            access.cookie, access.token
        );
        let mut r = Redirect::to(req.uri().path()).into_response();
        if let Ok(v) = HeaderValue::from_str(&cookie) {
            r.headers_mut().insert(header::SET_COOKIE, v);
        }
        return with_headers(r, PAGE_CSP);
    }
    let given = Access::header_token(headers).or_else(|| access.cookie_token(headers));
    if !given.is_some_and(|t| same(t, &access.token)) {
        return with_headers(refused(page), PAGE_CSP);
    }
    let is_report = req.uri().path().ends_with("/report.html");
    let resp = next.run(req).await;
    with_headers(resp, if is_report { REPORT_CSP } else { PAGE_CSP })
}

/// Whether a request is a browser's for a page (it accepts HTML), not the page's script's.
fn wants_page(headers: &HeaderMap) -> bool {
    let accept = headers.get(header::ACCEPT).and_then(|v| v.to_str().ok());
    accept.is_some_and(|a| a.contains("text/html"))
}

/// What a browser gets without the token: a short page saying how to get in.
const REFUSED_PAGE: &str = "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
<title>fuzzymotiv lab: access token needed</title></head><body><h1>This lab needs its access token</h1>\
<p>Open the address <code>fuzzymotiv lab</code> printed when it started, the one ending in \
<code>/?token=…</code>: it lets this browser in.</p>\
<p>A lab makes a new token at every start, so a page opened before a restart is shut out. \
To keep one token across restarts, start the lab with <code>--token VALUE</code> \
(16 to 128 letters, digits, <code>-</code> or <code>_</code>).</p></body></html>\n";

/// The answer to a request without the right token: for a browser, [`REFUSED_PAGE`]; for the
/// API, its JSON error.
fn refused(page: bool) -> Response {
    if page {
        let mut r = (StatusCode::UNAUTHORIZED, REFUSED_PAGE).into_response();
        r.headers_mut().insert(
            header::CONTENT_TYPE,
            HeaderValue::from_static("text/html; charset=utf-8"),
        );
        return r;
    }
    ApiError {
        status: StatusCode::UNAUTHORIZED,
        message: "this lab needs its access token: open the address `fuzzymotiv lab` printed (…/?token=…); \
                  each start makes a new one unless the lab is started with --token"
            .into(),
    }
    .into_response()
}

fn with_headers(mut r: Response, csp: &'static str) -> Response {
    let h = r.headers_mut();
    h.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(csp),
    );
    h.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    h.insert(
        header::REFERRER_POLICY,
        HeaderValue::from_static("no-referrer"),
    );
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    r
}
