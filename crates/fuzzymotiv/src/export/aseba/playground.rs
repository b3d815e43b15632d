//! The kit in Aseba's own simulator: `asebaplayground` (headless) with a Thymio II in front of
//! a wall (`tests/data/thymio-wall.playground`), `asebaswitch -d` between it and `asebahttp`
//! (its dump shows the bytecode sent), the kit's .aesl loaded by an HTTP PUT. Needs the Debian
//! package `aseba`, `curl` and an installed UTF-8 locale other than C.UTF-8 (`en_US.UTF-8`):
//! run by .ci/run.

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use super::tests::{controller, random_weights};
use super::*;
use crate::random::rng_from_seed;

/// The locale Aseba's tools need (they abort under C.UTF-8).
const LOCALE: &str = "en_US.UTF-8";

/// Children killed (by their own id) when the test ends, however it ends.
struct Children(Vec<Child>);

impl Drop for Children {
    fn drop(&mut self) {
        for c in &mut self.0 {
            let _ = c.kill();
            let _ = c.wait();
        }
    }
}

fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

fn spawn(dir: &Path, log: &str, program: &str, args: &[&str]) -> Child {
    let out = std::fs::File::create(dir.join(log)).unwrap();
    Command::new(program)
        .args(args)
        .current_dir(dir)
        .env("LC_ALL", LOCALE)
        .env("QT_QPA_PLATFORM", "offscreen")
        .env("HOME", dir)
        .stdout(out.try_clone().unwrap())
        .stderr(out)
        .stdin(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("{program}: {e}"))
}

/// Whether a socket listens on `port` (read from /proc/net/tcp{,6}: connecting to find out
/// would take the playground's robot's only connection).
fn listening(port: u16) -> bool {
    let needle = format!(":{port:04X} ");
    ["/proc/net/tcp", "/proc/net/tcp6"].iter().any(|f| {
        std::fs::read_to_string(f)
            .unwrap_or_default()
            .lines()
            .any(|l| {
                let cols: Vec<&str> = l.split_whitespace().collect();
                cols.len() > 3 && format!("{} ", cols[1]).ends_with(&needle) && cols[3] == "0A"
            })
    })
}

/// The first `Some` of `poll`, asked every 100 ms for up to 30 s (the processes answer when the
/// machine's load lets them: no fixed sleep decides a result); `None` after that.
fn eventually<T>(mut poll: impl FnMut() -> Option<T>) -> Option<T> {
    let start = Instant::now();
    loop {
        if let Some(v) = poll() {
            return Some(v);
        }
        if start.elapsed() > Duration::from_secs(30) {
            return None;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

fn wait_for_port(port: u16) {
    let start = Instant::now();
    while !listening(port) {
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "nothing listens on {port}"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// An asebahttp bridge at `port`.
struct Http(u16);

impl Http {
    fn curl(&self, args: &[&str], path: &str) -> Option<String> {
        let url = format!("http://127.0.0.1:{}/{path}", self.0);
        let out = Command::new("curl")
            .args(["-s", "-f", "--max-time", "10"])
            .args(args)
            .arg(&url)
            .output()
            .ok()?;
        out.status
            .success()
            .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
    }

    /// A variable of the node, if it reads as numbers now.
    fn try_var(&self, name: &str) -> Option<Vec<i16>> {
        let text = self.curl(&[], &format!("nodes/thymio-II/{name}"))?;
        serde_json::from_str(&text).ok()
    }

    /// A variable of the node, e.g. `prox.horizontal`.
    fn var(&self, name: &str) -> Vec<i16> {
        let text = self
            .curl(&[], &format!("nodes/thymio-II/{name}"))
            .unwrap_or_default();
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{name}: {text:?}: {e}"))
    }

    fn event(&self, name: &str, args: &[i16]) {
        let path: String = args.iter().map(|a| format!("/{a}")).collect();
        self.curl(&[], &format!("nodes/thymio-II/{name}{path}"))
            .unwrap_or_else(|| panic!("event {name} refused"));
    }

    fn put(&self, aesl: &Path) {
        let data = format!("@{}", aesl.display());
        self.curl(&["-X", "PUT", "--data-binary", &data], "nodes/thymio-II")
            .unwrap_or_else(|| {
                panic!(
                    "PUT {} refused: the program does not compile",
                    aesl.display()
                )
            });
    }
}

/// Words of bytecode the switch saw sent after log offset `from` ("N words of bytecode").
fn bytecode_sent(log: &Path, from: usize) -> usize {
    let text = std::fs::read_to_string(log).unwrap_or_default();
    text[from.min(text.len())..]
        .lines()
        .filter_map(|l| {
            l.split(" words of bytecode")
                .next()
                .filter(|_| l.contains(" words of bytecode"))
        })
        .filter_map(|head| head.rsplit(' ').next()?.parse::<usize>().ok())
        .sum()
}

fn write_kit(dir: &Path, c: &ExportedController) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    for f in thymio2_kit(c).files {
        std::fs::write(dir.join(&f.name), f.contents).unwrap();
    }
    dir.join(AESL_NAME)
}

/// Every 9th row of the kit's golden.csv: fm_test with its readings gives its fixed columns.
fn check_golden(http: &Http, c: &ExportedController) {
    let (_, mut m) = super::tests::loaded(c, THYMIO_PROX);
    for r in probe_readings(7, 4505).iter().step_by(9) {
        let expected = fixed_out(&mut m, r).unwrap();
        http.event("fm_test", r);
        assert_eq!(http.var("fm_paused"), [1]);
        assert_eq!(http.var("fm_m"), expected.m, "readings {r:?}");
        assert_eq!(http.var("fm_tgt"), expected.target, "readings {r:?}");
        assert_eq!(http.var("fm_act"), [expected.action], "readings {r:?}");
    }
}

/// The running program with `fm_monitor` = 1 emits `fm_state` = [the readings it copied from
/// prox.horizontal, the wheel targets it set] in the same handler: for each such event of the
/// SSE stream over `secs` seconds, the targets are exactly those the interpreter's run of the
/// same handler (`timer0`, or `prox` with no action running) sets for those readings.
fn check_live(http: &Http, c: &ExportedController, secs: u32) {
    let (_, mut m) = super::tests::loaded(c, THYMIO_PROX);
    let control = if c.motion == Motion::Wheels {
        "timer0"
    } else {
        "prox"
    };
    http.curl(&[], "nodes/thymio-II/fm_monitor/1")
        .expect("setting fm_monitor");
    let url = format!(
        "http://127.0.0.1:{}/nodes/thymio-II/events/fm_state",
        http.0
    );
    let out = Command::new("curl")
        .args(["-s", "-N", "--max-time", &secs.to_string(), &url])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    let (mut states, mut seeing) = (0, 0);
    for line in text
        .lines()
        .filter_map(|l| l.strip_prefix("data: fm_state "))
    {
        let v: Vec<i16> = line
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        assert_eq!(v.len(), 9, "{line}");
        let (readings, targets) = v.split_at(7);
        m.set("prox.horizontal", readings).unwrap();
        if c.motion == Motion::Actions {
            m.set("fm_busy", &[0]).unwrap();
        }
        m.run_event(control).unwrap();
        let predicted = [
            m.get("motor.left.target").unwrap()[0],
            m.get("motor.right.target").unwrap()[0],
        ];
        assert_eq!(targets, predicted, "readings {readings:?}");
        states += 1;
        seeing += usize::from(readings.iter().any(|&r| r > 0));
    }
    eprintln!(
        "{:?}: {states} decisions streamed in {secs} s, {seeing} seeing a wall",
        c.motion
    );
    // Wheels: one decision per control period (100 ms); actions: one per action executed
    // (about 100 ms of motion and up to 100 ms waiting for fresh readings).
    let per_second = if c.motion == Motion::Wheels { 5 } else { 2 };
    assert!(
        states >= per_second * secs as usize,
        "{states} decisions in {secs} s:\n{text}"
    );
    assert!(seeing > 0, "the Thymio never saw the wall");
}

/// A program of the integer operations the interpreter models, with run-time operands (so the
/// compiler cannot fold them): its results on the playground's VM are the interpreter's.
const SEMANTICS: &str = "var a = -7
var b = 30000
var m = -32768
var n1 = -1
var two = 2
var w[2] = [30000, 30000]
var v[2] = [2, 2]
var k = 4
var r[16]
r[0] = a / 2
r[1] = a / 3
r[2] = a % 3
r[3] = b + b
r[4] = b * 3
r[5] = (0 - 7) / 2
r[6] = m / n1
r[7] = abs(m)
call math.muldiv(r[8], b, 4, 8)
r[9] = b * 4 / 8
r[10] = a >> 1
r[11] = a / two
r[12] = -a / 4
call math.dot(r[13], w, v, k)
r[14] = m - 1
r[15] = (a * 1000) / 16
";

fn check_semantics(http: &Http, dir: &Path) {
    let aesl = dir.join("semantics.aesl");
    let node = SEMANTICS
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    std::fs::write(
        &aesl,
        format!("<!DOCTYPE aesl-source>\n<network>\n<node nodeId=\"1\" name=\"thymio-II\">{node}</node>\n</network>\n"),
    )
    .unwrap();
    http.put(&aesl);
    let mut m = interp::Machine::load(SEMANTICS, &[], &[]).unwrap();
    m.run_init().unwrap();
    let expected = m.get("r").unwrap();
    // Read until the VM has run the program (or 30 s: then its last reading is compared).
    let vm = eventually(|| http.try_var("r").filter(|v| *v == expected))
        .or_else(|| http.try_var("r"))
        .unwrap_or_default();
    eprintln!("semantics on the VM: {vm:?}");
    assert_eq!(
        vm,
        m.get("r").unwrap(),
        "the playground's VM and the interpreter differ"
    );
}

#[test]
#[ignore = "needs aseba: run by .ci/run"]
fn the_kit_compiles_and_runs_on_the_playgrounds_thymio() {
    let dir = std::env::temp_dir().join(format!("fm-thymio-kit-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let world = include_str!("../../../tests/data/thymio-wall.playground");
    let (p_robot, p_switch, p_http) = (free_port(), free_port(), free_port());
    std::fs::write(
        dir.join("world.playground"),
        world.replace("port=\"33333\"", &format!("port=\"{p_robot}\"")),
    )
    .unwrap();
    let mut children = Children(vec![spawn(
        &dir,
        "playground.log",
        "asebaplayground",
        &["world.playground"],
    )]);
    wait_for_port(p_robot);
    let robot = format!("tcp:localhost;{p_robot}");
    children.0.push(spawn(
        &dir,
        "switch.log",
        "asebaswitch",
        &["-d", "-p", &p_switch.to_string(), &robot],
    ));
    wait_for_port(p_switch);
    let switch = format!("tcp:localhost;{p_switch}");
    children.0.push(spawn(
        &dir,
        "http.log",
        "asebahttp",
        &["-p", &p_http.to_string(), &switch],
    ));
    wait_for_port(p_http);
    let http = Http(p_http);
    let start = Instant::now();
    while !http
        .curl(&[], "nodes")
        .unwrap_or_default()
        .contains("thymio-II")
    {
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "asebahttp lists no thymio-II"
        );
        std::thread::sleep(Duration::from_millis(200));
    }
    check_semantics(&http, &dir);
    let mut rng = rng_from_seed(2);
    for motion in [Motion::Wheels, Motion::Actions] {
        // Random weights, but both outputs biased forward: the robot heads for a wall.
        let mut w = random_weights(&mut rng, 7, 6, 3.0);
        w[6 * 8] = 2.0;
        w[6 * 8 + 7] = 2.0;
        let c = controller(7, 6, w, motion);
        let aesl = write_kit(&dir.join(format!("{motion:?}")), &c);
        let log = dir.join("switch.log");
        let before = std::fs::read_to_string(&log).map(|t| t.len()).unwrap_or(0);
        http.put(&aesl);
        // The switch has logged the new program's bytecode and the node counts its runs.
        let running = eventually(|| {
            let sent = bytecode_sent(&log, before) > 0;
            let runs = http.try_var("fm_count")?;
            (sent && runs.first().is_some_and(|&n| n > 0)).then_some(())
        });
        let words = bytecode_sent(&log, before);
        let prog = program::generate(&c, THYMIO_PROX);
        let estimate = interp::bytecode_words(&prog.code, &prog.constants).unwrap();
        eprintln!("{motion:?}: {words} words of bytecode sent (estimated {estimate})");
        assert!(words > 100 && words <= 1534, "{words}");
        assert!(running.is_some(), "the program does not run");
        check_live(&http, &c, 4);
        check_golden(&http, &c);
        http.event("fm_run", &[]);
    }
    drop(children);
    let _ = std::fs::remove_dir_all(&dir);
}
