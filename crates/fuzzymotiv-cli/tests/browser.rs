//! The report pages in a real browser: headless Chromium driven through chromedriver's WebDriver
//! HTTP API (a tiny client on `std::net::TcpStream`). Checks that `report.html` runs its script
//! without console errors or network requests, that pressing play moves the robot, and saves
//! screenshots to `target/report-screenshot.png` (whole page),
//! `target/report-replay-screenshot.png` (the replay widget) and
//! `target/reproduce-report-screenshot.png` (the page of `reproduce`).
//!
//! Needs the Debian packages `chromium` and `chromium-driver` (`.ci/run` installs them).

use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

mod common;

use common::{Fm, SMALL, ok};

const CHROMIUM: &str = "/usr/bin/chromium";
const CHROMEDRIVER: &str = "/usr/bin/chromedriver";
/// WebDriver's key for element references.
const ELEMENT: &str = "element-6066-11e4-a52e-4f735466cecf";

fn target_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .expect("target/tmp has a parent")
        .to_path_buf()
}

fn require_browser() {
    for (path, package) in [(CHROMIUM, "chromium"), (CHROMEDRIVER, "chromium-driver")] {
        assert!(
            Path::new(path).is_file(),
            "{path} not found: the browser test needs the Debian package `{package}`; run .ci/run, which installs chromium and chromium-driver"
        );
    }
}

/// Decodes standard base64 (with or without padding).
fn base64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    };
    let mut out = Vec::with_capacity(text.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0);
    for v in text.bytes().filter_map(value) {
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
        }
    }
    out
}

/// Decodes an HTTP/1.1 chunked body.
fn unchunk(mut body: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    while let Some(eol) = body.windows(2).position(|w| w == b"\r\n") {
        let size_text = String::from_utf8_lossy(&body[..eol]);
        let size = usize::from_str_radix(size_text.split(';').next().unwrap_or("").trim(), 16)
            .unwrap_or(0);
        if size == 0 {
            break;
        }
        let start = eol + 2;
        out.extend_from_slice(&body[start..(start + size).min(body.len())]);
        body = &body[(start + size + 2).min(body.len())..];
    }
    out
}

/// A chromedriver process and (once created) its browser session; both end on drop.
struct Driver {
    child: Child,
    port: u16,
    session: Option<String>,
}

impl Driver {
    fn start() -> Driver {
        let port = TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .expect("a free local port")
            .port();
        let child = Command::new(CHROMEDRIVER)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver starts");
        let d = Driver {
            child,
            port,
            session: None,
        };
        let deadline = Instant::now() + Duration::from_secs(30);
        loop {
            if let Ok(v) = d.http("GET", "/status", None)
                && v["value"]["ready"] == true
            {
                break;
            }
            assert!(Instant::now() < deadline, "chromedriver did not get ready");
            std::thread::sleep(Duration::from_millis(100));
        }
        d
    }

    fn http(&self, method: &str, path: &str, body: Option<&Value>) -> Result<Value, String> {
        let mut stream =
            TcpStream::connect(("127.0.0.1", self.port)).map_err(|e| format!("connect: {e}"))?;
        stream
            .set_read_timeout(Some(Duration::from_secs(90)))
            .map_err(|e| e.to_string())?;
        let body = body.map(Value::to_string).unwrap_or_default();
        let request = format!(
            "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nContent-Type: application/json; charset=utf-8\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
            self.port,
            body.len()
        );
        stream
            .write_all(request.as_bytes())
            .map_err(|e| format!("send: {e}"))?;
        // chromedriver keeps the connection open: read the header, then Content-Length bytes
        // (or chunks up to the last one).
        let mut raw = Vec::new();
        let mut buf = [0u8; 65536];
        let split = loop {
            if let Some(p) = raw.windows(4).position(|w| w == b"\r\n\r\n") {
                break p;
            }
            let n = stream.read(&mut buf).map_err(|e| format!("receive: {e}"))?;
            if n == 0 {
                return Err("connection closed before the header ended".into());
            }
            raw.extend_from_slice(&buf[..n]);
        };
        let head = String::from_utf8_lossy(&raw[..split]).to_ascii_lowercase();
        let mut body = raw[split + 4..].to_vec();
        let length = head.lines().find_map(|l| {
            l.strip_prefix("content-length:")
                .and_then(|v| v.trim().parse::<usize>().ok())
        });
        let chunked = head.contains("transfer-encoding: chunked")
            || head.contains("transfer-encoding:chunked");
        loop {
            let done = match length {
                Some(n) => body.len() >= n,
                None if chunked => body.ends_with(b"0\r\n\r\n"),
                None => false,
            };
            if done {
                break;
            }
            let n = stream.read(&mut buf).map_err(|e| format!("receive: {e}"))?;
            if n == 0 {
                break;
            }
            body.extend_from_slice(&buf[..n]);
        }
        if chunked {
            body = unchunk(&body);
        }
        let status: u16 = head
            .split_whitespace()
            .nth(1)
            .and_then(|s| s.parse().ok())
            .ok_or("no HTTP status")?;
        let v: Value = serde_json::from_slice(&body).map_err(|e| format!("JSON: {e}"))?;
        if status == 200 {
            Ok(v)
        } else {
            Err(format!("HTTP {status}: {}", v["value"]))
        }
    }

    /// A WebDriver command of the current session; panics with the driver's message on error.
    fn cmd(&self, method: &str, path: &str, body: Value) -> Value {
        let id = self.session.as_ref().expect("a session");
        let body = (method == "POST").then_some(&body);
        self.http(method, &format!("/session/{id}{path}"), body)
            .unwrap_or_else(|e| panic!("{method} {path}: {e}"))["value"]
            .take()
    }

    fn new_session(&mut self, profile: &Path) {
        let caps = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {
                "binary": CHROMIUM,
                "args": [
                    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                    "--no-first-run", "--disable-background-networking",
                    "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage",
                    "--hide-scrollbars", "--window-size=1280,1000",
                    format!("--user-data-dir={}", profile.display()),
                ],
            },
            "goog:loggingPrefs": {"browser": "ALL"},
        }}});
        let v = self
            .http("POST", "/session", Some(&caps))
            .unwrap_or_else(|e| panic!("cannot start headless Chromium: {e}"));
        self.session = Some(
            v["value"]["sessionId"]
                .as_str()
                .expect("a session id")
                .to_string(),
        );
    }

    fn script(&self, code: &str) -> Value {
        self.cmd("POST", "/execute/sync", json!({"script": code, "args": []}))
    }

    fn open(&self, page: &Path) {
        let url = format!("file://{}", page.canonicalize().unwrap().display());
        self.cmd("POST", "/url", json!({ "url": url }));
    }

    /// Console messages at level SEVERE since the last call (chromedriver's log endpoint).
    fn console_errors(&self) -> Vec<String> {
        let v = self.cmd("POST", "/se/log", json!({"type": "browser"}));
        v.as_array()
            .map(|list| {
                list.iter()
                    .filter(|e| e["level"] == "SEVERE")
                    .map(|e| e["message"].to_string())
                    .collect()
            })
            .unwrap_or_default()
    }

    fn element(&self, css: &str) -> String {
        let v = self.cmd(
            "POST",
            "/element",
            json!({"using": "css selector", "value": css}),
        );
        v[ELEMENT].as_str().expect("an element").to_string()
    }

    /// A screenshot of the whole page (not only the window) through the DevTools protocol.
    fn full_page_png(&self) -> Vec<u8> {
        let metrics = self.cmd(
            "POST",
            "/goog/cdp/execute",
            json!({"cmd": "Page.getLayoutMetrics", "params": {}}),
        );
        let size = &metrics["cssContentSize"];
        let (w, h) = (
            size["width"].as_f64().unwrap_or(1280.0),
            size["height"].as_f64().unwrap_or(1000.0),
        );
        let shot = self.cmd(
            "POST",
            "/goog/cdp/execute",
            json!({"cmd": "Page.captureScreenshot", "params": {
                "format": "png", "captureBeyondViewport": true,
                "clip": {"x": 0, "y": 0, "width": w, "height": h, "scale": 1},
            }}),
        );
        base64(shot["data"].as_str().expect("screenshot data"))
    }
}

impl Drop for Driver {
    fn drop(&mut self) {
        if let Some(id) = self.session.take() {
            let _ = self.http("DELETE", &format!("/session/{id}"), None);
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The page loaded without script errors, console errors or network requests, with `widgets`
/// replay widgets.
fn check_page_health(driver: &Driver, widgets: u64, what: &str) {
    let v = driver.script(
        "return {errors: window.fuzzymotivErrors || ['page script did not start'],
                 widgets: (window.fuzzymotivReplays || []).length,
                 requests: performance.getEntriesByType('resource').map(function (e) { return e.name; })};",
    );
    assert_eq!(v["errors"], json!([]), "{what}: script errors");
    assert_eq!(v["widgets"], widgets, "{what}: replay widgets");
    assert_eq!(v["requests"], json!([]), "{what}: network requests");
    let console = driver.console_errors();
    assert!(console.is_empty(), "{what}: console errors: {console:?}");
}

#[test]
fn report_page_runs_and_replays_in_chromium() {
    require_browser();
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("small.toml");
    std::fs::write(&cfg, "name = \"browser-test\"\nseed = 11\n").unwrap();
    let out = dir.path().join("run");
    Fm::new(["run", cfg.to_str().unwrap()])
        .out(&out)
        .sets(&SMALL)
        .ok();
    let report = out.join("report.html");
    assert!(report.is_file(), "run wrote no report.html");

    let mut driver = Driver::start();
    driver.new_session(&dir.path().join("chromium-profile"));
    driver.open(&report);
    check_page_health(&driver, 1, "run report");

    // The replay starts at step 0, at home; pressing play must move the drawn robot.
    let state = "var s = window.fuzzymotivReplays[0];
                 var c = document.querySelector('.replay canvas.room');
                 return {step: s.step, playing: s.playing, pose: c.getAttribute('data-pose'),
                         steps: +document.querySelector('.replay .slider').max};";
    let before = driver.script(state);
    assert_eq!(before["step"], 0, "{before}");
    assert_eq!(before["steps"], 100, "{before}");
    let play = driver.element(".replay button.play");
    driver.cmd("POST", &format!("/element/{play}/click"), json!({}));
    let deadline = Instant::now() + Duration::from_secs(20);
    let after = loop {
        std::thread::sleep(Duration::from_millis(200));
        let now = driver.script(state);
        if now["pose"] != before["pose"] && now["step"].as_u64().unwrap_or(0) >= 5 {
            break now;
        }
        assert!(
            Instant::now() < deadline,
            "pressing play did not move the robot: before {before}, now {now}"
        );
    };
    assert!(
        after["playing"] == true || after["step"] == 100,
        "the replay stopped early: {after}"
    );
    // The drawn pose is the recorded pose of the drawn step.
    let consistent = driver.script(
        "var s = window.fuzzymotivReplays[0];
         s.pause(); s.setStep(40);
         var d = JSON.parse(document.getElementById('fm-data').textContent).replays[0].rooms[0];
         var c = document.querySelector('.replay canvas.room');
         return c.getAttribute('data-pose') === d.x[40].toFixed(1) + ',' + d.y[40].toFixed(1) + ',' + d.h[40].toFixed(3);",
    );
    assert_eq!(consistent, true, "drawn pose differs from the data");
    check_page_health(&driver, 1, "run report after playing");

    let target = target_dir();
    let full = target.join("report-screenshot.png");
    std::fs::write(&full, driver.full_page_png()).unwrap();
    let widget = driver.element(".replay");
    driver.script("document.querySelector('.replay').scrollIntoView();");
    let shot = driver.cmd("GET", &format!("/element/{widget}/screenshot"), json!({}));
    let replay_png = target.join("report-replay-screenshot.png");
    std::fs::write(&replay_png, base64(shot.as_str().expect("base64 PNG"))).unwrap();
    for p in [&full, &replay_png] {
        let bytes = std::fs::read(p).unwrap();
        assert!(
            bytes.len() > 10_000 && &bytes[1..4] == b"PNG",
            "{}",
            p.display()
        );
    }
    eprintln!(
        "screenshots: {} and {}",
        full.display(),
        replay_png.display()
    );

    // The replay page of `fuzzymotiv replay` uses the same widget.
    let page = dir.path().join("replay/replay.html");
    ok(&[
        "replay",
        out.to_str().unwrap(),
        "--out",
        page.to_str().unwrap(),
    ]);
    driver.open(&page);
    check_page_health(&driver, 1, "replay page");
    let rooms =
        driver.script("return document.querySelectorAll('.replay .room-select option').length;");
    assert_eq!(rooms, 5, "one entry per room of the config");

    // The reproduce page: one widget per setting.
    let results = dir.path().join("results");
    Fm::new(["reproduce", "--seeds", "2"])
        .out(&results)
        .sets(&SMALL)
        .ok();
    driver.open(&results.join("report.html"));
    check_page_health(&driver, 2, "reproduce report");
    std::fs::write(
        target.join("reproduce-report-screenshot.png"),
        driver.full_page_png(),
    )
    .unwrap();
}
