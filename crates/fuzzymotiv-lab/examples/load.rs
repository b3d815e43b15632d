//! The lab under load (a step of `.ci/run`, not of `cargo test`): 20 clients start and cancel
//! runs for 30 s while they also ask for plain pages (`/api/info`, `/api/runs`). Checks that
//! every request got an answer (no refused connection, no 5xx but 503 "queue full"), prints
//! the latency of the plain requests, and checks that the resident memory after the test is
//! within 64 MiB of its level after a warm-up.
//!
//! `cargo run --release -p fuzzymotiv-lab --example load [-- SECONDS CLIENTS]`

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use fuzzymotiv_lab::{Lab, LabOptions};

/// Allowed growth of the resident memory from after the warm-up to after the test.
const MEMORY_MARGIN_MIB: f64 = 64.0;

/// One request; the status, or an error when no answer came.
fn request(
    addr: SocketAddr,
    token: &str,
    method: &str,
    path: &str,
    body: &str,
) -> Result<(u16, String), String> {
    let mut s = TcpStream::connect(addr).map_err(|e| e.to_string())?;
    s.set_read_timeout(Some(Duration::from_secs(30)))
        .map_err(|e| e.to_string())?;
    let head = format!(
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nx-fuzzymotiv-token: {token}\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    );
    s.write_all(head.as_bytes()).map_err(|e| e.to_string())?;
    let mut raw = String::new();
    s.read_to_string(&mut raw).map_err(|e| e.to_string())?;
    let status = raw
        .get(9..12)
        .and_then(|c| c.parse().ok())
        .ok_or_else(|| format!("no status in {raw:?}"))?;
    Ok((status, raw))
}

fn resident_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let kib: f64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap_or(0.0);
    kib / 1024.0
}

fn percentile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

/// What one client does until `stop`: start a small run, ask for plain pages, cancel it.
fn client(
    addr: SocketAddr,
    token: &str,
    k: usize,
    stop: &AtomicBool,
    latencies: &Mutex<Vec<f64>>,
    failures: &Mutex<Vec<String>>,
    answered: &AtomicUsize,
) {
    let run = format!(
        r#"{{"name":"load","seed":{k},"population":8,"generations":6,"steps":200,"rooms":["H","square"],"motivations":{{"curiosity":0.5,"homing":0.3,"orientation":0,"energy":0.2}}}}"#
    );
    let check = |r: Result<(u16, String), String>, what: &str| -> Option<String> {
        match r {
            Ok((status, raw)) if status < 500 || status == 503 => {
                answered.fetch_add(1, Ordering::Relaxed);
                Some(raw)
            }
            Ok((status, raw)) => {
                failures
                    .lock()
                    .unwrap()
                    .push(format!("{what}: HTTP {status}: {raw}"));
                None
            }
            Err(e) => {
                failures.lock().unwrap().push(format!("{what}: {e}"));
                None
            }
        }
    };
    while !stop.load(Ordering::Relaxed) {
        let started = check(request(addr, token, "POST", "/api/runs", &run), "start");
        let id = started.as_deref().and_then(|raw| {
            let body = raw.split_once("\r\n\r\n")?.1;
            let v: serde_json::Value = serde_json::from_str(body).ok()?;
            v["id"].as_str().map(str::to_string)
        });
        for path in ["/api/info", "/api/runs"] {
            let t = Instant::now();
            if check(request(addr, token, "GET", path, ""), path).is_some() {
                latencies
                    .lock()
                    .unwrap()
                    .push(t.elapsed().as_secs_f64() * 1000.0);
            }
        }
        if let Some(id) = id {
            check(
                request(addr, token, "POST", &format!("/api/runs/{id}/cancel"), ""),
                "cancel",
            );
        }
    }
}

/// Runs `clients` clients for `secs` seconds.
fn phase(lab: &Lab, secs: u64, clients: usize) -> (Vec<f64>, Vec<String>, usize) {
    let stop = AtomicBool::new(false);
    let latencies = Mutex::new(Vec::new());
    let failures = Mutex::new(Vec::new());
    let answered = AtomicUsize::new(0);
    std::thread::scope(|s| {
        for k in 0..clients {
            let (stop, latencies, failures, answered) = (&stop, &latencies, &failures, &answered);
            s.spawn(move || {
                client(
                    lab.addr(),
                    lab.token(),
                    k,
                    stop,
                    latencies,
                    failures,
                    answered,
                )
            });
        }
        std::thread::sleep(Duration::from_secs(secs));
        stop.store(true, Ordering::Relaxed);
    });
    let mut l = latencies.into_inner().unwrap();
    l.sort_by(f64::total_cmp);
    (
        l,
        failures.into_inner().unwrap(),
        answered.load(Ordering::Relaxed),
    )
}

/// Waits until no run is queued or running.
fn drain(lab: &Lab) {
    let deadline = Instant::now() + Duration::from_secs(120);
    while Instant::now() < deadline {
        let list = request(lab.addr(), lab.token(), "GET", "/api/runs", "")
            .map(|r| r.1)
            .unwrap_or_default();
        if !list.contains("\"running\"") && !list.contains("\"queued\"") {
            return;
        }
        std::thread::sleep(Duration::from_millis(200));
    }
    panic!("runs still going 120 s after the load stopped");
}

fn main() {
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let secs = args.first().copied().unwrap_or(30);
    let clients = args.get(1).copied().unwrap_or(20) as usize;
    let tmp = tempfile::tempdir().expect("a temporary directory");
    let mut opts = LabOptions::new(tmp.path().join("lab"));
    opts.port = 0;
    opts.threads = Some(2);
    let lab = Arc::new(Lab::start(opts).expect("the lab starts"));
    let warm = phase(&lab, secs.min(5), clients);
    drain(&lab);
    let before = resident_mib();
    let (lat, failures, answered) = phase(&lab, secs, clients);
    drain(&lab);
    let after = resident_mib();
    println!(
        "load: {clients} clients × {secs} s: {answered} requests answered ({} in the warm-up), {} failed",
        warm.2,
        failures.len()
    );
    if !lat.is_empty() {
        println!(
            "plain requests (/api/info, /api/runs) while runs go on: {} timed, p50 {:.1} ms, p95 {:.1} ms, p99 {:.1} ms, max {:.1} ms",
            lat.len(),
            percentile(&lat, 0.5),
            percentile(&lat, 0.95),
            percentile(&lat, 0.99),
            lat[lat.len() - 1]
        );
    }
    println!(
        "resident memory: {before:.1} MiB after the warm-up, {after:.1} MiB after the test (margin {MEMORY_MARGIN_MIB} MiB)"
    );
    let mut ok = true;
    for f in failures.iter().take(10) {
        eprintln!("failed: {f}");
        ok = false;
    }
    if lat.is_empty() || percentile(&lat, 0.95) > 1000.0 {
        eprintln!("plain requests are not well under a second (p95 over 1000 ms)");
        ok = false;
    }
    if after > before + MEMORY_MARGIN_MIB {
        eprintln!(
            "memory grew by {:.1} MiB, more than {MEMORY_MARGIN_MIB} MiB",
            after - before
        );
        ok = false;
    }
    if let Ok(lab) = Arc::try_unwrap(lab) {
        lab.stop();
    }
    std::process::exit(if ok { 0 } else { 1 });
}
