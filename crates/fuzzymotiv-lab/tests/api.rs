//! The lab's HTTP API against a server on an ephemeral port: the access guard (token, Host),
//! bad input (400/413 with the CLI's field-naming messages), a run started, streamed to two
//! clients and finished, a run cancelled, save, and the same generations as `fuzzymotiv run`.

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::Path;

use fuzzymotiv_lab::{Lab, LabOptions};
use serde_json::{Value, json};

/// An answer: status, head (lower-cased) and body (de-chunked).
struct Answer {
    status: u16,
    head: String,
    body: String,
}

impl Answer {
    fn json(&self) -> Value {
        serde_json::from_str(&self.body).unwrap_or_else(|e| panic!("{e}: {}", self.body))
    }
}

fn unchunk(mut body: &str) -> String {
    let mut out = String::new();
    while let Some((size, rest)) = body.split_once("\r\n") {
        let n = usize::from_str_radix(size.trim(), 16).unwrap_or(0);
        if n == 0 || rest.len() < n {
            break;
        }
        out.push_str(&rest[..n]);
        body = rest[n..].trim_start_matches("\r\n");
    }
    out
}

/// One HTTP/1.1 request (connection closed after it) with `extra` header lines.
fn request(addr: SocketAddr, method: &str, path: &str, extra: &[String], body: &str) -> Answer {
    let mut s = TcpStream::connect(addr).expect("connect");
    let mut head = format!("{method} {path} HTTP/1.1\r\nConnection: close\r\n");
    if !extra.iter().any(|h| h.to_lowercase().starts_with("host:")) {
        head += &format!("Host: {addr}\r\n");
    }
    for h in extra {
        head += &format!("{h}\r\n");
    }
    head += &format!(
        "Content-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        body.len()
    );
    s.set_read_timeout(Some(std::time::Duration::from_secs(120)))
        .unwrap();
    s.write_all(head.as_bytes()).unwrap();
    // A body the server refuses (413) may be cut short: what it answered is still read.
    let _ = s.write_all(body.as_bytes());
    let mut raw = Vec::new();
    let mut buf = [0u8; 65536];
    while let Ok(n) = s.read(&mut buf) {
        if n == 0 {
            break;
        }
        raw.extend_from_slice(&buf[..n]);
    }
    let text = String::from_utf8_lossy(&raw).into_owned();
    let (head, body) = text.split_once("\r\n\r\n").unwrap_or((&text, ""));
    let head = head.to_lowercase();
    let status = head[9..12].parse().unwrap();
    let body = if head.contains("transfer-encoding: chunked") {
        unchunk(body)
    } else {
        body.to_string()
    };
    Answer { status, head, body }
}

/// A lab in a temporary directory, with a client that sends its token.
struct Client {
    lab: Lab,
    _tmp: tempfile::TempDir,
}

impl Client {
    fn start() -> Client {
        Client::start_on(None)
    }
    /// A lab started on `config` (`--config`).
    fn start_on(config: Option<&Path>) -> Client {
        let tmp = tempfile::tempdir().unwrap();
        let mut opts = LabOptions::new(tmp.path().join("lab"));
        opts.port = 0;
        opts.threads = Some(2);
        opts.config = config.map(Path::to_path_buf);
        Client {
            lab: Lab::start(opts).expect("lab starts"),
            _tmp: tmp,
        }
    }
    /// A lab whose Studies panel lists the study files of `folder` (`--studies`).
    fn start_with_studies(folder: &Path) -> Client {
        let tmp = tempfile::tempdir().unwrap();
        let mut opts = LabOptions::new(tmp.path().join("lab"));
        opts.port = 0;
        opts.threads = Some(2);
        opts.studies = folder.to_path_buf();
        Client {
            lab: Lab::start(opts).expect("lab starts"),
            _tmp: tmp,
        }
    }
    fn auth(&self) -> Vec<String> {
        vec![format!("x-fuzzymotiv-token: {}", self.lab.token())]
    }
    fn get(&self, path: &str) -> Answer {
        request(self.lab.addr(), "GET", path, &self.auth(), "")
    }
    fn post(&self, path: &str, body: &Value) -> Answer {
        request(
            self.lab.addr(),
            "POST",
            path,
            &self.auth(),
            &body.to_string(),
        )
    }
    fn post_raw(&self, path: &str, body: &str) -> Answer {
        request(self.lab.addr(), "POST", path, &self.auth(), body)
    }
}

/// A run of a few seconds: small GA, short trials, two rooms.
fn small(generations: usize, seed: u64) -> Value {
    json!({ "name": "t", "seed": seed, "population": 6, "generations": generations,
            "steps": 100, "rooms": ["H", "square"],
            "motivations": { "curiosity": 0.5, "homing": 0.3, "orientation": 0.0, "energy": 0.2 } })
}

/// The events of a run's stream, read to its end: (event, data).
fn events(c: &Client, id: &str) -> Vec<(String, Value)> {
    let a = c.get(&format!("/api/runs/{id}/events"));
    assert_eq!(a.status, 200, "{}", a.body);
    assert!(a.head.contains("text/event-stream"));
    let mut out = Vec::new();
    let mut event = String::new();
    for line in a.body.lines() {
        if let Some(e) = line.strip_prefix("event: ") {
            event = e.to_string();
        } else if let Some(d) = line.strip_prefix("data: ") {
            out.push((event.clone(), serde_json::from_str(d).unwrap()));
        }
    }
    out
}

#[test]
fn requests_without_the_token_or_with_another_host_are_refused() {
    let c = Client::start();
    let addr = c.lab.addr();
    let none = request(addr, "GET", "/api/runs", &[], "");
    assert_eq!(none.status, 401);
    assert!(none.json()["error"].as_str().unwrap().contains("token"));
    let wrong = request(
        addr,
        "GET",
        "/api/runs",
        &["x-fuzzymotiv-token: 00".into()],
        "",
    );
    assert_eq!(wrong.status, 401);
    // DNS rebinding: the right token, another name.
    let mut rebound = c.auth();
    rebound.push("Host: evil.example:80".into());
    assert_eq!(request(addr, "GET", "/api/runs", &rebound, "").status, 403);
    // The token in the address sets a cookie and leads to the page without it.
    let first = request(addr, "GET", &format!("/?token={}", c.lab.token()), &[], "");
    assert_eq!(first.status, 303);
    assert!(first.head.contains("set-cookie: fuzzymotiv_lab_"));
    assert!(
        first.head.lines().any(|l| l.trim() == "location: /"),
        "{}",
        first.head
    );
    let cookie = format!("Cookie: fuzzymotiv_lab_{}={}", addr.port(), c.lab.token());
    let page = request(addr, "GET", "/", &[cookie], "");
    assert_eq!(page.status, 200);
    assert!(page.body.contains("<title>fuzzymotiv lab</title>"));
    assert!(
        page.head
            .contains("content-security-policy: default-src 'self'")
    );
    assert!(c.get("/lab.js").body.contains("EventSource"));
}

#[test]
fn bad_input_gets_400_or_413_naming_the_field() {
    let c = Client::start();
    let a = c.post_raw("/api/runs", "{\"motivations\": ");
    assert_eq!(a.status, 400);
    assert!(
        a.json()["error"]
            .as_str()
            .unwrap()
            .starts_with("request body")
    );
    let mut s = small(3, 1);
    s["population"] = json!("many");
    let a = c.post("/api/runs", &s);
    assert_eq!(a.status, 400);
    assert!(
        a.json()["error"]
            .as_str()
            .unwrap()
            .contains("field `population`"),
        "{}",
        a.body
    );
    let mut s = small(3, 1);
    s["population"] = json!(100000);
    let e = c.post("/api/runs", &s).json()["error"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(e.contains("lab settings: field `ga.population`"), "{e}");
    let mut s = small(3, 1);
    s["motivations"]["curiosity"] = json!(0.9);
    let a = c.post("/api/runs", &s);
    assert_eq!(a.status, 400);
    assert!(
        a.json()["error"]
            .as_str()
            .unwrap()
            .contains("lab settings: field `motivations"),
        "{}",
        a.body
    );
    let mut s = small(3, 1);
    s["rooms"] = json!(["../../etc/passwd"]);
    assert!(
        c.post("/api/runs", &s).json()["error"]
            .as_str()
            .unwrap()
            .contains("field `rooms[0]`")
    );
    let big = format!("{{\"name\": \"{}\"}}", "x".repeat(100_000));
    assert_eq!(c.post_raw("/api/runs", &big).status, 413);
    // A drawn room with two corners: the text of `rooms --check`, naming the drawn room.
    let room = json!({ "room": { "name": "bad", "outline": [[0, 0], [500, 0]],
                       "home": { "x": 100, "y": 100, "heading_deg": 0 } } });
    let a = c.post("/api/rooms", &room);
    assert_eq!(a.status, 400);
    let p = a.json();
    assert_eq!(p["field"], "outline");
    assert!(
        p["error"]
            .as_str()
            .unwrap()
            .starts_with("drawn room `bad`: field `outline`: needs at least 3 points"),
        "{p}"
    );
    assert_eq!(c.get("/api/runs/nope").status, 404);
    assert_eq!(c.get("/api/compare?a=x").status, 400);
}

#[test]
fn a_drawn_room_is_saved_once_and_used_by_a_run() {
    let c = Client::start();
    let room = json!({ "save": true, "room": { "name": "box", "outline": [[0, 0], [800, 0], [800, 600], [0, 600]],
                       "home": { "x": 200, "y": 300, "heading_deg": 0 } } });
    let a = c.post("/api/rooms", &room);
    assert_eq!(a.status, 200, "{}", a.body);
    assert_eq!(a.json()["entry"], "box.toml");
    assert!(c.lab.dir().join("rooms/box.toml").is_file());
    assert_eq!(
        c.post("/api/rooms", &room).status,
        200,
        "the same room again is fine"
    );
    let mut other = room.clone();
    other["room"]["home"]["x"] = json!(300);
    assert_eq!(
        c.post("/api/rooms", &other).status,
        409,
        "another room of that name is kept"
    );
    let list = c.get("/api/rooms").json();
    assert!(
        list.as_array()
            .unwrap()
            .iter()
            .any(|r| r["entry"] == "box.toml")
    );
    let mut s = small(2, 3);
    s["rooms"] = json!(["H", "box.toml"]);
    let id = c.post("/api/runs", &s).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let end = events(&c, &id).pop().unwrap();
    assert_eq!(end.1["status"], "finished", "{}", end.1);
}

#[test]
fn two_clients_stream_a_run_and_a_long_run_is_cancelled() {
    let c = Client::start();
    let a = c.post("/api/runs", &small(4, 1));
    assert_eq!(a.status, 201, "{}", a.body);
    let id = a.json()["id"].as_str().unwrap().to_string();
    let long = c.post("/api/runs", &small(400, 2)).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let list = c.get("/api/runs").json();
    let queued = list
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["id"] == long.as_str())
        .unwrap();
    // Waiting behind the first run (position 1 or 2, as the worker may not have taken it yet).
    assert_eq!(queued["status"], "queued");
    assert!(
        matches!(queued["queue_position"].as_u64(), Some(1 | 2)),
        "{queued}"
    );
    let (one, two) = std::thread::scope(|s| {
        let h = s.spawn(|| events(&c, &id));
        (events(&c, &id), h.join().unwrap())
    });
    // The same events of each kind in the same order (a late subscriber's replayed history
    // may interleave `paths` and `generation` events differently from a live one).
    let by_kind = |events: &[(String, Value)]| {
        let mut sorted = events.to_vec();
        sorted.sort_by(|a, b| a.0.cmp(&b.0));
        sorted
    };
    assert_eq!(
        by_kind(&one),
        by_kind(&two),
        "both clients see the same events"
    );
    let gens: Vec<_> = one.iter().filter(|(e, _)| e == "generation").collect();
    assert_eq!(gens.len(), 4);
    assert!(one.iter().any(|(e, _)| e == "paths"));
    let (end, data) = one.last().unwrap();
    assert_eq!(
        (end.as_str(), data["status"].as_str()),
        ("end", Some("finished"))
    );
    assert_eq!(data["result"]["rows"].as_array().unwrap().len(), 2);
    assert!(
        c.lab
            .dir()
            .join("runs")
            .join(&id)
            .join("summary.json")
            .is_file()
    );
    // The long run: wait for its first generation, cancel it from this client.
    let mut stream = TcpStream::connect(c.lab.addr()).unwrap();
    let head = format!(
        "GET /api/runs/{long}/events HTTP/1.1\r\nHost: {}\r\nx-fuzzymotiv-token: {}\r\n\r\n",
        c.lab.addr(),
        c.lab.token()
    );
    stream.write_all(head.as_bytes()).unwrap();
    let mut seen = String::new();
    let mut buf = [0u8; 4096];
    while !seen.contains("event: generation") {
        let n = stream.read(&mut buf).unwrap();
        assert!(n > 0, "stream ended early: {seen}");
        seen += &String::from_utf8_lossy(&buf[..n]);
    }
    let a = c.post(&format!("/api/runs/{long}/cancel"), &json!({}));
    assert_eq!(a.status, 200);
    let end = events(&c, &long).pop().unwrap();
    assert_eq!(end.1["status"], "stopped");
    let gens = c.get(&format!("/api/runs/{long}")).json()["generations"]
        .as_array()
        .unwrap()
        .len();
    assert!(gens < 400, "stopped early ({gens} generations)");
    let runs = c.lab.dir().join("runs");
    assert!(!runs.join(&long).exists() && !runs.join(format!("{long}.partial")).exists());
}

#[test]
fn a_lab_run_gives_the_generations_of_fuzzymotiv_run_and_saves_as_a_run_directory() {
    let c = Client::start();
    let id = c.post("/api/runs", &small(3, 5)).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    assert_eq!(events(&c, &id).pop().unwrap().1["status"], "finished");
    // "Download config", then what `fuzzymotiv run config.toml` does with it.
    let config = c.get(&format!("/api/runs/{id}/config.toml"));
    assert_eq!(config.status, 200);
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("config.toml");
    std::fs::write(&path, &config.body).unwrap();
    let loaded = fuzzymotiv_pipeline::files::inputs::load_config(Some(&path), &[], None).unwrap();
    let out = tmp.path().join("run");
    let progress = fuzzymotiv_pipeline::pipeline::progress::NoProgress;
    fuzzymotiv_pipeline::pipeline::run_dir::execute(&loaded, &out, &progress, false, None).unwrap();
    let lab_dir = c.lab.dir().join("runs").join(&id);
    let read = |p: &Path| std::fs::read(p).unwrap();
    assert_eq!(
        read(&lab_dir.join("generations.csv")),
        read(&out.join("generations.csv"))
    );
    assert_eq!(
        read(&lab_dir.join("population.json")),
        read(&out.join("population.json"))
    );
    // Save as run directory: once; again is fine; another run is never put there.
    let a = c.post(&format!("/api/runs/{id}/save"), &json!({ "name": "mine" }));
    assert_eq!(a.status, 200, "{}", a.body);
    let saved = c.lab.dir().join("saved/mine");
    assert_eq!(
        read(&saved.join("generations.csv")),
        read(&out.join("generations.csv"))
    );
    assert_eq!(
        c.post(&format!("/api/runs/{id}/save"), &json!({ "name": "mine" }))
            .status,
        200
    );
    let other = c.post("/api/runs", &small(2, 6)).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    assert_eq!(events(&c, &other).pop().unwrap().1["status"], "finished");
    let a = c.post(
        &format!("/api/runs/{other}/save"),
        &json!({ "name": "mine" }),
    );
    assert_eq!(a.status, 409, "{}", a.body);
    assert_eq!(
        c.post(
            &format!("/api/runs/{other}/save"),
            &json!({ "name": "../x" })
        )
        .status,
        400
    );
    // Compare the two as `fuzzymotiv compare`: four measures, each in two rooms and overall.
    let cmp = c.get(&format!("/api/compare?a={id}&b={other}")).json();
    assert_eq!(cmp["tests"].as_array().unwrap().len(), 4 * 3);
    assert_eq!(cmp["tests"][2]["room"], "overall");
    // A new lab on the same directory lists the finished runs.
    let dir = c.lab.dir().to_path_buf();
    let Client { lab, _tmp: keep } = c;
    lab.stop();
    let mut opts = LabOptions::new(dir);
    opts.port = 0;
    let again = Lab::start(opts).unwrap();
    let list = request(
        again.addr(),
        "GET",
        "/api/runs",
        &[format!("x-fuzzymotiv-token: {}", again.token())],
        "",
    );
    assert!(list.body.contains(&id) && list.body.contains(&other));
    drop(keep);
}

/// Bound to every interface (`--bind 0.0.0.0`): the page is printed with 127.0.0.1, and any IP
/// address with the lab's port is a good Host (another machine's browser names this one by its
/// address), but a host name still is not (DNS rebinding).
#[test]
fn every_interface_answers_ip_addresses_not_names() {
    let tmp = tempfile::tempdir().unwrap();
    let mut opts = LabOptions::new(tmp.path().join("lab"));
    opts.port = 0;
    opts.bind = "0.0.0.0".parse().unwrap();
    let lab = Lab::start(opts).expect("lab starts");
    let port = lab.addr().port();
    assert!(
        lab.url()
            .starts_with(&format!("http://127.0.0.1:{port}/?token="))
    );
    let local: SocketAddr = ([127, 0, 0, 1], port).into();
    let token = format!("x-fuzzymotiv-token: {}", lab.token());
    for (host, status) in [
        (format!("127.0.0.1:{port}"), 200),
        (format!("localhost:{port}"), 200),
        (format!("192.0.2.7:{port}"), 200),
        (format!("[2001:db8::7]:{port}"), 200),
        (format!("192.0.2.7:{}", port.wrapping_add(1)), 403),
        (format!("attacker.example:{port}"), 403),
    ] {
        let a = request(
            local,
            "GET",
            "/api/info",
            &[token.clone(), format!("Host: {host}")],
            "",
        );
        assert_eq!(a.status, status, "Host {host}: {}", a.body);
    }
}

#[test]
fn a_browser_without_the_token_gets_a_page_saying_how_to_get_in() {
    let c = Client::start();
    let addr = c.lab.addr();
    let browser = ["Accept: text/html,application/xhtml+xml,*/*;q=0.8".to_string()];
    let page = request(addr, "GET", "/", &browser, "");
    assert_eq!(page.status, 401);
    assert!(
        page.head.contains("content-type: text/html"),
        "{}",
        page.head
    );
    assert!(
        page.body
            .contains("<h1>This lab needs its access token</h1>")
    );
    assert!(page.body.contains("/?token=") && page.body.contains("--token"));
    // The page's script still gets JSON, which it shows in its own words.
    let api = request(addr, "GET", "/api/runs", &[], "");
    assert_eq!(api.status, 401);
    assert!(api.json()["error"].as_str().unwrap().contains("--token"));
}

#[test]
fn a_lab_started_with_a_token_keeps_it_across_restarts() {
    let tmp = tempfile::tempdir().unwrap();
    let token = "0123456789abcdef-kept_token";
    let start = || {
        let mut opts = LabOptions::new(tmp.path().join("lab"));
        opts.port = 0;
        opts.threads = Some(1);
        opts.token = Some(token.to_string());
        Lab::start(opts).expect("lab starts")
    };
    for _ in 0..2 {
        let lab = start();
        assert_eq!(lab.token(), token);
        assert!(lab.url().ends_with(&format!("/?token={token}")));
        let auth = [format!("x-fuzzymotiv-token: {token}")];
        assert_eq!(
            request(lab.addr(), "GET", "/api/runs", &auth, "").status,
            200
        );
        lab.stop();
    }
}

#[test]
fn stopped_runs_stay_in_the_list_marked_stopped() {
    let c = Client::start();
    let busy = c.post("/api/runs", &small(400, 1)).json()["id"]
        .as_str()
        .unwrap()
        .to_string();
    // More stopped runs than the lab keeps curves of: each is queued, then stopped.
    let mut stopped = Vec::new();
    for seed in 0..40 {
        let a = c.post("/api/runs", &small(2, 100 + seed));
        assert_eq!(a.status, 201, "{}", a.body);
        let id = a.json()["id"].as_str().unwrap().to_string();
        assert_eq!(
            c.post(&format!("/api/runs/{id}/cancel"), &json!({})).status,
            200
        );
        stopped.push(id);
    }
    assert_eq!(
        c.post(&format!("/api/runs/{busy}/cancel"), &json!({}))
            .status,
        200
    );
    let list = c.get("/api/runs").json();
    let listed: Vec<&Value> = list.as_array().unwrap().iter().collect();
    for id in &stopped {
        let run = listed.iter().find(|r| r["id"] == id.as_str());
        assert_eq!(
            run.map(|r| &r["status"]),
            Some(&json!("stopped")),
            "{id}: {list}"
        );
    }
}

#[test]
fn comparing_two_runs_tests_every_measure_over_their_test_runs_as_compare_does() {
    let c = Client::start();
    let ids: Vec<String> = [1, 2]
        .iter()
        .map(|&seed| {
            let a = c.post("/api/runs", &small(2, seed));
            assert_eq!(a.status, 201, "{}", a.body);
            a.json()["id"].as_str().unwrap().to_string()
        })
        .collect();
    for id in &ids {
        assert_eq!(events(&c, id).last().unwrap().1["status"], "finished");
    }
    let r = c.get(&format!("/api/compare?a={}&b={}", ids[0], ids[1]));
    assert_eq!(r.status, 200, "{}", r.body);
    let r = r.json();
    let tests = r["tests"].as_array().unwrap();
    // What `fuzzymotiv compare A B` computes for the two run directories, row for row.
    use fuzzymotiv_pipeline::pipeline::compare::{choose, compare, load};
    let runs = c.lab.dir().join("runs");
    let a = load(&runs.join(&ids[0]), "A").unwrap();
    let b = load(&runs.join(&ids[1]), "B").unwrap();
    let cli = compare(&a, &b, &choose(&a, &b, &[]).unwrap(), 0.05).unwrap();
    assert_eq!(tests.len(), cli.rows.len());
    for (t, row) in tests.iter().zip(&cli.rows) {
        let mut t = t.clone();
        assert!(t.as_object_mut().unwrap().remove("verdict").is_some());
        assert_eq!(t, serde_json::to_value(row).unwrap());
    }
    let metrics: Vec<&str> = tests
        .iter()
        .map(|t| t["metric"].as_str().unwrap())
        .collect();
    assert!(metrics.contains(&"recognition_pct"), "{metrics:?}");
    assert!(tests.iter().all(|t| t["n_a"].as_u64() > Some(1)), "{r}");
    assert!(r["note"].as_str().unwrap().contains("test runs"), "{r}");
}

/// A lab under load ends thousands of runs: every ended run but the newest
/// `MAX_FORGOTTEN` (32) lets its curves and paths go, finished runs too (they kept them for
/// good, and the lab's memory grew without bound); a finished run keeps its result.
#[test]
fn finished_runs_beyond_the_newest_32_let_their_curves_go() {
    let c = Client::start();
    let ids: Vec<String> = (0..34)
        .map(|seed| {
            let a = c.post("/api/runs", &small(2, 200 + seed));
            assert_eq!(a.status, 201, "{}", a.body);
            a.json()["id"].as_str().unwrap().to_string()
        })
        .collect();
    // One worker runs them in order: when the last has finished, all have.
    assert_eq!(events(&c, &ids[33]).last().unwrap().1["status"], "finished");
    let run = |id: &str| c.get(&format!("/api/runs/{id}")).json();
    for (old, id) in ids.iter().enumerate().take(2) {
        let r = run(id);
        assert_eq!(r["status"], "finished", "{old}: {r}");
        assert_eq!(r["generations"], json!([]), "{old}: {r}");
        assert!(r["paths"].is_null() && !r["result"].is_null(), "{old}: {r}");
    }
    let newest = run(&ids[33]);
    assert_eq!(
        newest["generations"].as_array().map(Vec::len),
        Some(2),
        "{newest}"
    );
    assert!(!newest["paths"].is_null(), "{newest}");
}

#[test]
fn explain_takes_named_motivations_and_terms_as_well_as_the_four_numbers() {
    let c = Client::start();
    let old = c.post(
        "/api/explain",
        &json!({ "motivations": [0.5, 0.3, 0.0, 0.2], "fitness": [0.9, 0.5, 0.0, 0.8] }),
    );
    assert_eq!(old.status, 200, "{}", old.body);
    let named = c.post(
        "/api/explain",
        &json!({ "motivations": { "curiosity": 0.5, "homing": 0.3, "orientation": 0.0, "energy": 0.2 },
                 "fitness": { "a": 0.9, "g": 0.5, "l": 0.0, "b": 0.8 } }),
    );
    assert_eq!(named.status, 200, "{}", named.body);
    assert_eq!(old.json()["fitness"], named.json()["fitness"]);
    assert_eq!(old.json()["motivations"], json!([0.5, 0.3, 0.0, 0.2]));

    // Five motivations: the paper's four and urgency; every rule lists five labels.
    let five = json!({ "curiosity": 0.5, "homing": 0.1, "orientation": 0.0, "energy": 0.1,
                       "urgency": 0.3 });
    let a = c.post(
        "/api/explain",
        &json!({ "motivations": five, "fitness": { "a": 0.9, "g": 0.5, "l": 0.0, "b": 0.8, "urgency": 0.7 } }),
    );
    assert_eq!(a.status, 200, "{}", a.body);
    let x = a.json();
    assert_eq!(x["inputs"], json!(["a", "g", "l", "b", "urgency"]));
    assert_eq!(x["names"][4], "urgency");
    let rules = x["rules"].as_array().unwrap();
    assert!(
        !rules.is_empty()
            && rules
                .iter()
                .all(|r| r["labels"].as_array().unwrap().len() == 5)
    );
    let f = x["fitness"].as_f64().unwrap();
    let slower = c.post(
        "/api/explain",
        &json!({ "motivations": five, "fitness": { "a": 0.9, "g": 0.5, "l": 0.0, "b": 0.8, "urgency": 0.0 } }),
    );
    assert!(
        slower.json()["fitness"].as_f64().unwrap() < f,
        "urgency weighs in F"
    );

    // A term left out, a term no motivation weighs, an unknown term: 400 naming the field.
    let a = c.post(
        "/api/explain",
        &json!({ "motivations": five, "fitness": { "a": 0.9, "g": 0.5, "l": 0.0, "b": 0.8 } }),
    );
    assert_eq!(a.status, 400);
    assert!(
        a.json()["error"]
            .as_str()
            .unwrap()
            .contains("field `fitness.urgency`: missing"),
        "{}",
        a.body
    );
    let a = c.post(
        "/api/explain",
        &json!({ "motivations": [0.5, 0.3, 0.0, 0.2], "fitness": { "a": 0.9, "g": 0.5, "l": 0.0, "b": 0.8, "goal": 1 } }),
    );
    assert_eq!(a.status, 400);
    assert!(
        a.json()["error"]
            .as_str()
            .unwrap()
            .contains("field `fitness.goal`"),
        "{}",
        a.body
    );
    let a = c.post(
        "/api/explain",
        &json!({ "motivations": { "curiosity": 0.6, "energy": 0.1, "hurry": { "weight": 0.3, "term": "speed" } },
                 "fitness": { "a": 0.9 } }),
    );
    assert_eq!(a.status, 400);
    assert!(
        a.json()["error"]
            .as_str()
            .unwrap()
            .contains("field `motivations.hurry`"),
        "{}",
        a.body
    );
}

#[test]
fn the_sliders_follow_the_motivations_of_a_preset_or_a_loaded_config() {
    let c = Client::start();
    let info = c.get("/api/info").json();
    let high = info["presets"]["motivations"]["high curiosity"]
        .as_array()
        .unwrap()
        .clone();
    let names: Vec<&str> = high.iter().map(|m| m["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["curiosity", "homing", "orientation", "energy"]);
    assert_eq!(high[0]["weight"], 0.8);
    assert_eq!(high[0]["term"], "a");
    let fetch = info["presets"]["motivations"]["fetch"]
        .as_array()
        .unwrap()
        .clone();
    assert_eq!(fetch.len(), 5);
    assert_eq!(fetch[4]["name"], "urgency");

    let text = include_str!("../../../configs/fetch.toml");
    let a = c.post("/api/config", &json!({ "toml": text }));
    assert_eq!(a.status, 200, "{}", a.body);
    let loaded = a.json()["motivations"].clone();
    assert_eq!(
        loaded,
        json!(fetch),
        "configs/fetch.toml has the fetch preset's motivations"
    );

    let a = c.post(
        "/api/config",
        &json!({ "toml": "[motivations]\ncuriosity = 0.5\nhoming = 0.1\nenergy = 0.1\nrush = { weight = 0.3, term = \"hurry\" }\n" }),
    );
    assert_eq!(a.status, 400);
    let e = a.json()["error"].as_str().unwrap().to_string();
    assert!(
        e.starts_with("loaded config: field `motivations.rush`"),
        "{e}"
    );
}

/// A 1 m × 0.8 m room drawn in the page, home near one corner, a goal near the opposite one.
fn room_with_goal(name: &str, goal: Value) -> Value {
    json!({ "save": true, "room": { "name": name,
        "outline": [[0, 0], [1000, 0], [1000, 800], [0, 800]],
        "home": { "x": 100, "y": 100, "heading_deg": 0 },
        "goal": goal,
        "waypoints": [{ "x": 500, "y": 200, "radius": 80 }, { "x": 500, "y": 600, "radius": 80 }] } })
}

#[test]
fn a_room_with_a_goal_and_waypoints_is_saved_read_back_and_followed_by_a_run() {
    let c = Client::start();
    let a = c.post(
        "/api/rooms",
        &room_with_goal("fetchbox", json!({ "x": 850, "y": 650, "radius": 90 })),
    );
    assert_eq!(a.status, 200, "{}", a.body);
    let text = std::fs::read_to_string(c.lab.dir().join("rooms/fetchbox.toml")).unwrap();
    // As the shipped room files write it: the goal an inline table, the waypoints tables.
    assert!(text.contains("goal = { "), "{text}");
    assert_eq!(text.matches("[[waypoints]]").count(), 2, "{text}");
    let file: toml::Table = toml::from_str(&text).unwrap();
    assert_eq!(file["goal"]["x"].as_integer(), Some(850), "{text}");
    assert_eq!(file["goal"]["radius"].as_integer(), Some(90), "{text}");
    assert_eq!(file["waypoints"].as_array().unwrap().len(), 2, "{text}");
    // `fuzzymotiv rooms --check` reads it with its mission.
    let room = fuzzymotiv::simulation::Room::from_toml_str(&text, "fetchbox.toml").unwrap();
    assert_eq!(room.mission.waypoints.len(), 2);

    let list = c.get("/api/rooms").json();
    let listed = list
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["entry"] == "fetchbox.toml")
        .expect("the room is listed")
        .clone();
    let goal = &listed["room"]["mission"]["goal"];
    assert_eq!(goal["centre"]["x"], 850.0);
    assert_eq!(goal["radius"], 90.0);
    assert_eq!(
        listed["room"]["mission"]["waypoints"][1]["centre"]["y"],
        600.0
    );

    // Five motivations, urgency weighing the mission: the run measures the mission terms.
    let mut s = small(2, 5);
    s["rooms"] = json!(["fetchbox.toml"]);
    s["recognition"] = json!(false);
    s["motivations"] = json!({ "curiosity": 0.5, "homing": 0.1, "orientation": 0.0,
                               "energy": 0.1, "urgency": 0.3 });
    let a = c.post("/api/runs", &s);
    assert_eq!(a.status, 201, "{}", a.body);
    let id = a.json()["id"].as_str().unwrap().to_string();
    let seen = events(&c, &id);
    let gens: Vec<&Value> = seen
        .iter()
        .filter(|(k, _)| k == "generation")
        .map(|(_, v)| v)
        .collect();
    assert_eq!(gens.len(), 2);
    for g in &gens {
        let urgency = g["terms"]["urgency"].as_f64().expect("urgency measured");
        assert!((0.0..=1.0).contains(&urgency), "{g}");
        assert!(g["terms"]["goal"].as_f64().is_some(), "{g}");
    }
    let end = &seen.last().unwrap().1;
    assert_eq!(end["status"], "finished", "{end}");
    let about = &c.get("/api/runs").json()[0]["about"];
    assert_eq!(about["motivation_names"][4], "urgency");
    assert_eq!(about["motivations"][4], 0.3);

    // The paper's four alone measure no mission term.
    let a = c.post("/api/runs", &small(1, 6));
    let id = a.json()["id"].as_str().unwrap().to_string();
    let g = events(&c, &id)
        .into_iter()
        .find(|(k, _)| k == "generation")
        .unwrap()
        .1;
    assert_eq!(g["terms"], json!({}), "{g}");
}

#[test]
fn a_bad_goal_or_waypoint_gets_400_naming_the_room_file_field() {
    let c = Client::start();
    for (goal, field, says) in [
        (
            json!({ "x": 1500, "y": 400, "radius": 60 }),
            "goal",
            "outside the room outline",
        ),
        (
            json!({ "x": 850, "y": 650, "radius": 0 }),
            "goal.radius",
            "must be a radius > 0",
        ),
    ] {
        let a = c.post("/api/rooms", &room_with_goal("badgoal", goal));
        assert_eq!(a.status, 400, "{}", a.body);
        let p = a.json();
        assert_eq!(p["field"], field, "{p}");
        let e = p["error"].as_str().unwrap();
        assert!(
            e.starts_with(&format!("drawn room `badgoal`: field `{field}`")),
            "{e}"
        );
        assert!(e.contains(says), "{e}");
    }
    let mut room = room_with_goal("badway", json!({ "x": 850, "y": 650, "radius": 90 }));
    room["room"]["waypoints"][1] = json!({ "x": 500, "y": 900, "radius": 80 });
    let p = c.post("/api/rooms", &room).json();
    assert_eq!(p["field"], "waypoints[1]", "{p}");
    // Inside the outline but walled off from home: not reachable.
    let mut room = room_with_goal("walled", json!({ "x": 900, "y": 700, "radius": 40 }));
    room["room"]["obstacles"] = json!([{ "outline": [[800, 560], [995, 560], [995, 600], [840, 600], [840, 795], [800, 795]] }]);
    let p = c.post("/api/rooms", &room).json();
    assert_eq!(p["field"], "goal", "{p}");
    assert!(p["error"].as_str().unwrap().contains("walled"), "{p}");
    assert!(!c.lab.dir().join("rooms/badgoal.toml").exists());
    assert!(!c.lab.dir().join("rooms/walled.toml").exists());
    // A run whose urgency needs a mission, in a room without one: 400 naming the room.
    let mut s = small(2, 1);
    s["motivations"] = json!({ "curiosity": 0.5, "homing": 0.1, "orientation": 0.0,
                               "energy": 0.1, "urgency": 0.3 });
    let e = c.post("/api/runs", &s).json()["error"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(
        e.contains("field `rooms[0]`") && e.contains("has no"),
        "{e}"
    );
}

/// A file of the repository (configs/, rooms/).
fn repo_file(path: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

#[test]
fn a_lab_started_on_a_config_opens_on_its_motivations_rooms_and_settings() {
    let c = Client::start_on(Some(&repo_file("configs/fetch.toml")));
    let info = c.get("/api/info").json();
    let start = &info["start"];
    assert!(
        start["config"]
            .as_str()
            .unwrap()
            .ends_with("configs/fetch.toml")
    );
    assert_eq!(
        start["motivations"], info["presets"]["motivations"]["fetch"],
        "the sliders of configs/fetch.toml: the paper's four and urgency"
    );
    let s = &start["settings"];
    assert_eq!(
        (s["name"].as_str(), s["seed"].as_u64()),
        (Some("fetch"), Some(1))
    );
    assert_eq!(
        (s["population"].as_u64(), s["generations"].as_u64()),
        (Some(200), Some(200))
    );
    assert_eq!(
        (s["motion"].as_str(), s["recognition"].as_bool()),
        (Some("actions"), Some(true))
    );
    assert_eq!(
        start["not_set"],
        json!([]),
        "the lab sets everything fetch.toml sets"
    );
    let rooms: Vec<String> = serde_json::from_value(s["rooms"].clone()).unwrap();
    let names = ["H", "T", "L", "square", "rectangle"];
    assert_eq!(rooms.len(), 5);
    for (entry, name) in rooms.iter().zip(names) {
        assert!(Path::new(entry).is_absolute(), "{entry}");
        assert!(
            entry.ends_with(&format!("rooms/fetch-{name}.toml")),
            "{entry}"
        );
    }

    // The room list: the config's room files first, with their goals, then the built-in ones.
    let list = c.get("/api/rooms").json();
    let list = list.as_array().unwrap();
    for (view, entry) in list.iter().zip(&rooms) {
        assert_eq!(view["entry"], json!(entry));
        assert_eq!(
            (view["config"].as_bool(), view["builtin"].as_bool()),
            (Some(true), Some(false))
        );
        let goal = &view["room"]["mission"]["goal"];
        assert!(goal["radius"].as_f64().unwrap() > 0.0, "{view}");
    }
    assert_eq!(
        list[0]["room"]["mission"]["goal"]["centre"],
        json!({ "x": 730.0, "y": 730.0 })
    );
    assert_eq!(list[5]["entry"], "H");
    assert_eq!(list[5]["config"], false);

    // A run in two of them, which its resolved config names.
    let mut run = small(2, 5);
    run["rooms"] = json!([rooms[0], rooms[3]]);
    run["motivations"] = json!({ "curiosity": 0.5, "homing": 0.1, "orientation": 0.0,
                                 "energy": 0.1, "urgency": 0.3 });
    let a = c.post("/api/runs", &run);
    assert_eq!(a.status, 201, "{}", a.body);
    let id = a.json()["id"].as_str().unwrap().to_string();
    let end = events(&c, &id).pop().unwrap();
    assert_eq!(end.1["status"], "finished", "{}", end.1);
    let config = c.get(&format!("/api/runs/{id}/config.toml")).body;
    assert!(config.contains(&format!("\"{}\"", rooms[0])), "{config}");
}

#[test]
fn runs_name_only_the_room_files_of_the_config_the_lab_started_on() {
    let other = repo_file("rooms/U.toml").canonicalize().unwrap();
    let mut run = small(2, 5);
    run["rooms"] = json!(["H", other.display().to_string()]);
    for c in [
        Client::start(),
        Client::start_on(Some(&repo_file("configs/fetch.toml"))),
    ] {
        let a = c.post("/api/runs", &run);
        assert_eq!(a.status, 400, "{}", a.body);
        let e = a.json()["error"].as_str().unwrap().to_string();
        assert!(e.starts_with("lab settings: field `rooms[1]`: "), "{e}");
    }
    let c = Client::start();
    assert_eq!(c.get("/api/info").json()["start"], Value::Null);
}

#[test]
fn a_start_config_names_the_keys_the_lab_cannot_set() {
    let tmp = tempfile::tempdir().unwrap();
    let config = tmp.path().join("other.toml");
    std::fs::write(
        &config,
        "name = \"other\"\nseed = 7\nrooms = [\"H\", \"T\"]\ntraining = \"per-room\"\n\
         [ga]\npopulation = 12\ngenerations = 3\nelite = 3\n[trial]\nsteps = 150\nnoise = 0.05\n\
         [robot]\nmotion = \"wheels\"\n[aem]\nenabled = false\n",
    )
    .unwrap();
    let c = Client::start_on(Some(&config));
    let start = c.get("/api/info").json()["start"].clone();
    assert_eq!(
        start["not_set"],
        json!(["ga.elite", "training", "trial.noise"])
    );
    let s = &start["settings"];
    assert_eq!(
        (
            s["seed"].as_u64(),
            s["population"].as_u64(),
            s["generations"].as_u64()
        ),
        (Some(7), Some(12), Some(3))
    );
    assert_eq!(
        (s["steps"].as_u64(), s["motion"].as_str()),
        (Some(150), Some("wheels"))
    );
    assert_eq!(
        (s["recognition"].as_bool(), s["rooms"].clone()),
        (Some(false), json!(["H", "T"]))
    );
    // Built-in rooms are listed once, as built-in.
    let list = c.get("/api/rooms").json();
    assert_eq!(list[0]["entry"], "H");
    assert_eq!(list[0]["config"], false);
}

/// The run's generations, as `generations.csv` holds them.
fn generations_csv(c: &Client, id: &str) -> String {
    std::fs::read_to_string(c.lab.dir().join("runs").join(id).join("generations.csv")).unwrap()
}

/// Starts `settings`, waits for the end; the run's id.
fn finished_run(c: &Client, settings: &Value) -> String {
    let a = c.post("/api/runs", settings);
    assert_eq!(a.status, 201, "{}", a.body);
    let id = a.json()["id"].as_str().unwrap().to_string();
    let end = events(c, &id).pop().unwrap();
    assert_eq!(end.1["status"], "finished", "{}", end.1);
    id
}

#[test]
fn a_weighted_sum_run_writes_its_combination_and_evolves_on_another_f() {
    let c = Client::start();
    let tsk = finished_run(&c, &small(2, 5));
    let mut s = small(2, 5);
    s["combine"] = json!("weighted-sum");
    let sum = finished_run(&c, &s);

    // The downloaded config and the run directory's config and report say it; the TSK run's
    // settings and config are as before the option (no `combine` anywhere).
    let config = c.get(&format!("/api/runs/{sum}/config.toml")).body;
    assert!(
        config.contains("[fitness]") && config.contains("combine = \"weighted-sum\""),
        "{config}"
    );
    let dir = c.lab.dir().join("runs").join(&sum);
    let resolved = std::fs::read_to_string(dir.join("config.resolved.toml")).unwrap();
    assert!(
        resolved.contains("combine = \"weighted-sum\""),
        "{resolved}"
    );
    let report = std::fs::read_to_string(dir.join("report.html")).unwrap();
    assert!(
        report.contains("combine = &quot;weighted-sum&quot;"),
        "the report's configuration names the combination"
    );
    let default = c.get(&format!("/api/runs/{tsk}/config.toml")).body;
    assert!(!default.contains("combine"), "{default}");
    let detail = c.get(&format!("/api/runs/{tsk}")).json();
    assert!(detail["settings"].get("combine").is_none(), "{detail}");
    assert_eq!(detail["result"]["combine"], "tsk");
    assert_eq!(
        c.get(&format!("/api/runs/{sum}")).json()["result"]["combine"],
        "weighted-sum"
    );

    // The same seed, another F: the curves differ from the first generation on.
    assert_ne!(generations_csv(&c, &tsk), generations_csv(&c, &sum));
    let best = |id: &str| {
        let csv = generations_csv(&c, id);
        let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let col = head.iter().position(|h| *h == "best").unwrap();
        csv.lines()
            .nth(1)
            .unwrap()
            .split(',')
            .nth(col)
            .unwrap()
            .to_string()
    };
    assert_ne!(best(&tsk), best(&sum));
}

#[test]
fn an_unknown_fitness_combination_gets_400_naming_the_field_and_the_choices() {
    let c = Client::start();
    let mut s = small(2, 5);
    s["combine"] = json!("product");
    let a = c.post("/api/runs", &s);
    assert_eq!(a.status, 400, "{}", a.body);
    let e = a.json()["error"].as_str().unwrap().to_string();
    assert!(
        e.starts_with("lab settings: field `fitness.combine`"),
        "{e}"
    );
    assert!(
        e.contains("weighted-sum") && e.contains("weighted-squares"),
        "{e}"
    );
    let a = c.post(
        "/api/explain",
        &json!({ "motivations": [0.5, 0.3, 0.0, 0.2], "fitness": [0.9, 0.5, 0.0, 0.8],
                 "combine": "product" }),
    );
    assert_eq!(a.status, 400, "{}", a.body);
    let e = a.json()["error"].as_str().unwrap().to_string();
    assert!(e.starts_with("request body: field `combine`"), "{e}");
    assert!(
        e.contains("weighted-sum") && e.contains("weighted-squares"),
        "{e}"
    );
}

#[test]
fn explain_gives_f_under_the_chosen_combination_beside_the_tsks() {
    let c = Client::start();
    let ask = |combine: Option<&str>| {
        let mut body =
            json!({ "motivations": [0.5, 0.3, 0.0, 0.2], "fitness": [0.9, 0.5, 0.0, 0.8] });
        if let Some(k) = combine {
            body["combine"] = json!(k);
        }
        let a = c.post("/api/explain", &body);
        assert_eq!(a.status, 200, "{}", a.body);
        a.json()
    };
    let tsk = ask(None);
    assert_eq!(tsk["combine"], "tsk");
    assert_eq!(tsk["combined"], tsk["fitness"]);
    let sum = ask(Some("weighted-sum"));
    assert_eq!(sum["combine"], "weighted-sum");
    assert_eq!(
        sum["fitness"], tsk["fitness"],
        "the rules shown are the TSK's"
    );
    assert_eq!(sum["rules"], tsk["rules"]);
    let f = sum["combined"].as_f64().unwrap();
    assert!(
        (f - (0.5 * 0.9 + 0.3 * 0.5 + 0.2 * 0.8)).abs() < 1e-12,
        "{f}"
    );
    let squares = ask(Some("weighted-squares"))["combined"].as_f64().unwrap();
    assert!(
        (squares - (0.5 * 0.81 + 0.3 * 0.25 + 0.2 * 0.64)).abs() < 1e-12,
        "{squares}"
    );
}

#[test]
fn a_start_config_sets_the_fitness_combination() {
    let tmp = tempfile::tempdir().unwrap();
    let config = tmp.path().join("baseline.toml");
    std::fs::write(
        &config,
        "name = \"baseline\"\nrooms = [\"H\", \"T\"]\n[ga]\npopulation = 12\ngenerations = 3\n\
         [fitness]\ncombine = \"weighted-squares\"\n",
    )
    .unwrap();
    let c = Client::start_on(Some(&config));
    let start = c.get("/api/info").json()["start"].clone();
    assert_eq!(start["settings"]["combine"], "weighted-squares");
    assert_eq!(start["not_set"], json!([]), "the lab sets fitness.combine");
}

#[test]
fn the_robot_list_has_the_built_in_robots_with_their_sensor_layouts() {
    use fuzzymotiv::simulation::{BUILTIN_ROBOTS, RobotSpec};
    let c = Client::start();
    let a = c.get("/api/robots");
    assert_eq!(a.status, 200, "{}", a.body);
    let list = a.json();
    let list = list.as_array().unwrap();
    let names: Vec<&str> = list.iter().map(|r| r["name"].as_str().unwrap()).collect();
    assert_eq!(names, BUILTIN_ROBOTS);
    let sensors: Vec<u64> = list
        .iter()
        .map(|r| r["sensors"].as_u64().unwrap())
        .collect();
    assert_eq!(
        sensors,
        [8, 8, 7],
        "the Khepera's, the e-puck2's and the Thymio's"
    );
    for r in list {
        let spec = RobotSpec::builtin(r["name"].as_str().unwrap()).unwrap();
        assert_eq!(r["title"], spec.title());
        assert_eq!(r["radius"].as_f64(), Some(spec.radius()));
        assert_eq!(r["reading_max"].as_f64(), Some(spec.reading_max()));
        let layout = r["layout"].as_array().unwrap();
        assert_eq!(layout.len(), spec.sensors(), "{r}");
        for (s, (m, label)) in layout.iter().zip(spec.mounts().iter().zip(spec.labels())) {
            assert_eq!(
                (s["x"].as_f64(), s["y"].as_f64(), s["facing_deg"].as_f64()),
                (Some(m.x), Some(m.y), Some(m.facing_deg))
            );
            assert_eq!(s["label"], json!(label));
            let range = s["range"].as_f64().unwrap();
            assert!(range > 0.0 && range < 500.0, "{s}");
        }
    }
}

#[test]
fn a_run_on_the_epuck2_names_it_in_its_resolved_config_and_paths() {
    let c = Client::start();
    let mut s = small(2, 5);
    s["robot"] = json!("epuck2");
    let id = finished_run(&c, &s);
    let dir = c.lab.dir().join("runs").join(&id);
    let text = std::fs::read_to_string(dir.join("config.resolved.toml")).unwrap();
    let resolved: toml::Table = toml::from_str(&text).unwrap();
    assert_eq!(resolved["robot"]["file"].as_str(), Some("epuck2"), "{text}");
    let detail = c.get(&format!("/api/runs/{id}")).json();
    assert_eq!(detail["about"]["robot"], "epuck2");
    assert_eq!(detail["settings"]["robot"], "epuck2");
    // The final paths name the robot and end at a pose (x, y, heading) for the page to draw.
    let paths = &detail["result"]["paths"];
    assert_eq!(paths["robot"], "epuck2");
    for room in paths["rooms"].as_array().unwrap() {
        let pose = room["pose"].as_array().unwrap();
        let last = room["points"].as_array().unwrap().last().unwrap();
        assert_eq!((&pose[0], &pose[1]), (&last[0], &last[1]), "{room}");
        assert!(pose[2].is_f64(), "{room}");
    }
    // A run that names no robot drives the Khepera, and its config names none (as before).
    let k = finished_run(&c, &small(2, 5));
    let detail = c.get(&format!("/api/runs/{k}")).json();
    assert_eq!(detail["about"]["robot"], "khepera");
    let text = std::fs::read_to_string(
        c.lab
            .dir()
            .join("runs")
            .join(&k)
            .join("config.resolved.toml"),
    )
    .unwrap();
    let resolved: toml::Table = toml::from_str(&text).unwrap();
    assert!(resolved["robot"].get("file").is_none(), "{text}");
}

#[test]
fn an_unknown_robot_or_a_robot_file_is_refused_with_400_naming_it() {
    let c = Client::start();
    for name in ["rover", "../../robots/khepera4.toml"] {
        let mut s = small(2, 5);
        s["robot"] = json!(name);
        let a = c.post("/api/runs", &s);
        assert_eq!(a.status, 400, "{}", a.body);
        let e = a.json()["error"].as_str().unwrap().to_string();
        assert!(
            e.starts_with(&format!("lab settings: field `robot`: `{name}` is not a built-in robot (khepera, epuck2 or thymio2)")),
            "{e}"
        );
    }
    let mut s = small(2, 5);
    s["robot"] = json!(8);
    let e = c.post("/api/runs", &s).json()["error"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(e.contains("field `robot`"), "{e}");
    assert_eq!(c.get("/api/runs").json(), json!([]), "nothing was queued");
}

#[test]
fn a_thymio_run_in_the_papers_rooms_gets_the_clearance_error_and_runs_in_rooms_scaled_for_it() {
    let c = Client::start();
    let mut s = small(2, 5);
    s["robot"] = json!("thymio2");
    let a = c.post("/api/runs", &s);
    assert_eq!(a.status, 400, "{}", a.body);
    let e = a.json()["error"].as_str().unwrap().to_string();
    assert!(
        e.starts_with("lab settings: field `rooms[0]`: home of room \"H\"")
            && e.contains("closer than robot.radius 80"),
        "{e}"
    );
    // The repository's room scaled for it, loaded into the lab as the page's "Load room file" does.
    let text = std::fs::read_to_string(repo_file("rooms/thymio2/H.toml")).unwrap();
    let a = c.post("/api/rooms", &json!({ "toml": text, "save": true }));
    assert_eq!(a.status, 200, "{}", a.body);
    let entry = a.json()["entry"].as_str().unwrap().to_string();
    s["rooms"] = json!([entry]);
    s["recognition"] = json!(false);
    let id = finished_run(&c, &s);
    assert_eq!(
        c.get(&format!("/api/runs/{id}")).json()["about"]["robot"],
        "thymio2"
    );
}

#[test]
fn a_lab_started_on_the_thymio_config_picks_its_robot_and_sets_every_key() {
    let c = Client::start_on(Some(&repo_file("configs/thymio2.toml")));
    let start = c.get("/api/info").json()["start"].clone();
    assert_eq!(start["settings"]["robot"], "thymio2");
    assert_eq!(start["not_set"], json!([]), "{start}");
    // A robot file by path is not the lab's: the form keeps the default, and says so.
    let tmp = tempfile::tempdir().unwrap();
    let config = tmp.path().join("k4.toml");
    let robot = repo_file("robots/khepera4.toml").canonicalize().unwrap();
    let rooms = ["H", "T"].map(|r| {
        let path = repo_file(&format!("rooms/thymio2/{r}.toml"));
        path.canonicalize().unwrap().display().to_string()
    });
    let text = format!(
        "robot = {:?}\nrooms = {rooms:?}\n",
        robot.display().to_string()
    );
    std::fs::write(&config, text).unwrap();
    let c = Client::start_on(Some(&config));
    let start = c.get("/api/info").json()["start"].clone();
    assert!(start["settings"].get("robot").is_none(), "{start}");
    let not_set = start["not_set"].as_array().unwrap();
    assert!(not_set.contains(&json!("robot.file")), "{start}");
}

/// A study of a new kind at a tiny size: the fetch mission on an e-puck2, three arms of
/// urgency's weight, a comparison of the mission's time and a trend of exploration.
fn tiny_study() -> String {
    format!(
        r#"[study]
name = "epuck2-fetch"
seeds = 2
config = {:?}
set = {{ robot = "epuck2", ga = {{ population = 6, generations = 2 }}, trial = {{ steps = 60 }}, aem = {{ enabled = false }} }}

[[arm]]
name = "urgency-0.1"
level = 0.1
set = {{ "motivations.curiosity" = 0.7, "motivations.urgency" = 0.1 }}

[[arm]]
name = "urgency-0.3"
level = 0.3

[[arm]]
name = "urgency-0.5"
level = 0.5
set = {{ "motivations.curiosity" = 0.3, "motivations.urgency" = 0.5 }}

[[hypothesis]]
id = "sooner"
kind = "compare"
measure = "urgency"
a = "urgency-0.5"
b = "urgency-0.1"
expect = "higher"

[[hypothesis]]
id = "exploration-cost"
kind = "trend"
measure = "exploration"
arms = ["urgency-0.1", "urgency-0.3", "urgency-0.5"]
expect = "decreasing"
"#,
        repo_file("configs/fetch.toml").display().to_string()
    )
}

/// Issue #56 item 2: the pipeline's notes on a finished study of 6 runs are the page's (an API
/// field; the command line prints them on stderr), not printed by the lab.
fn the_pipelines_notes_are_the_pages(study: &Value) {
    assert_eq!(
        study["notes"],
        json!(["6 jobs run, 0 already done, 6 in this selection, 6 in the plan"]),
        "{study}"
    );
}

/// The lab's studies: the study folder's files listed with their text; a bad study refused
/// with 400 naming its field (a pasted one as `(pasted study)`); a listed study run in the
/// lab's `studies/ID/` writes what the library's `run_study` (`fuzzymotiv study`) writes, byte
/// for byte, and the list shows its progress and pooled claims, its forest plot served.
#[test]
fn a_study_started_in_the_lab_writes_what_fuzzymotiv_study_writes_and_shows_its_claims() {
    let folder = tempfile::tempdir().unwrap();
    let text = tiny_study();
    std::fs::write(folder.path().join("tiny.toml"), &text).unwrap();
    let c = Client::start_with_studies(folder.path());
    let listed = c.get("/api/studies").json();
    assert_eq!(
        listed["files"],
        json!([{ "file": "tiny.toml", "toml": text }])
    );
    assert_eq!(listed["studies"], json!([]));

    let bad = c.post(
        "/api/studies",
        &json!({ "toml": text.replace("seeds = 2", "seeds = 0") }),
    );
    assert_eq!(bad.status, 400, "{}", bad.body);
    let message = bad.json()["error"].as_str().unwrap().to_string();
    assert!(
        message.starts_with("(pasted study): field `study.seeds`"),
        "{message}"
    );
    let other = c.post(
        "/api/studies",
        &json!({ "toml": text, "file": "../x.toml" }),
    );
    assert_eq!(other.status, 400, "{}", other.body);
    assert!(other.body.contains("field `file`"), "{}", other.body);

    let started = c.post(
        "/api/studies",
        &json!({ "toml": text, "file": "tiny.toml" }),
    );
    assert_eq!(started.status, 201, "{}", started.body);
    let id = started.json()["id"].as_str().unwrap().to_string();
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(300);
    let study = loop {
        let list = c.get("/api/studies").json();
        let s = list["studies"][0].clone();
        assert_eq!(s["id"], json!(id));
        if s["status"] != "running" {
            break s;
        }
        assert!(
            std::time::Instant::now() < deadline,
            "the study never ended: {s}"
        );
        std::thread::sleep(std::time::Duration::from_millis(100));
    };
    assert_eq!(study["status"], "finished", "{study}");
    assert_eq!(
        (study["done"].as_u64(), study["total"].as_u64()),
        (Some(6), Some(6))
    );
    the_pipelines_notes_are_the_pages(&study);
    let claims = study["claims"].as_array().unwrap();
    let ids: Vec<&str> = claims.iter().map(|c| c["id"].as_str().unwrap()).collect();
    assert_eq!(ids, ["sooner", "exploration-cost"]);
    for key in [
        "effect",
        "ci_low",
        "ci_high",
        "p_adjusted",
        "mdd",
        "verdict",
        "sentence",
    ] {
        assert!(
            claims.iter().all(|c| !c[key].is_null()),
            "{key}: {claims:?}"
        );
    }

    // The library's own run of the same file: the same bytes.
    let lib = tempfile::tempdir().unwrap();
    let file = folder.path().join("tiny.toml");
    let study_file = fuzzymotiv_pipeline::study::Study::load(&file).unwrap();
    let options = fuzzymotiv_pipeline::study::StudyOptions {
        out: lib.path().join("out"),
        threads: Some(2),
        ..Default::default()
    };
    let progress = fuzzymotiv_pipeline::pipeline::progress::NoProgress;
    fuzzymotiv_pipeline::study::run_study(&study_file, &options, &progress).unwrap();
    let lab_dir = c.lab.dir().join("studies").join(&id);
    for name in [
        "per_seed.csv",
        "claims.csv",
        "rooms.csv",
        "arms.csv",
        "study.json",
        "report.md",
        "forest.svg",
    ] {
        let read = |d: &Path| std::fs::read(d.join(name)).unwrap();
        assert!(
            read(&lab_dir) == read(&lib.path().join("out")),
            "{name} differs"
        );
    }
    let forest = c.get(&format!("/api/studies/{id}/forest.svg"));
    assert_eq!(forest.status, 200);
    assert!(forest.head.contains("image/svg+xml") && forest.body.contains("<svg"));
    assert_eq!(c.get("/api/studies/study-99/forest.svg").status, 404);
}
