//! Helpers shared by the binary's integration tests (each test file uses some of them).
#![allow(dead_code)]

pub mod recompute;
pub mod webdriver;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `fuzzymotiv` binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_fuzzymotiv"))
}

/// The repository root.
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs the binary with `args` and returns what it did.
pub fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("binary runs")
}

/// Runs the binary and asserts it succeeded.
pub fn ok(args: &[&str]) -> Output {
    let o = run(args);
    assert!(
        o.status.success(),
        "fuzzymotiv {args:?} failed: {}",
        stderr(&o)
    );
    o
}

/// Every file under `dir`, recursively (relative path → contents), in path order.
pub fn tree(dir: &Path) -> std::collections::BTreeMap<PathBuf, Vec<u8>> {
    let mut files = std::collections::BTreeMap::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                todo.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().to_path_buf();
                files.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    files
}

/// Standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Standard output as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The output of `cmd`, which must end by itself: a command still running after a minute is
/// killed and fails the test (a refusal must not wait on a pipe or read without end), so the
/// suite never hangs.
pub fn within_a_minute(mut cmd: Command) -> Output {
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let shown = format!("{cmd:?}");
    let mut child = (cmd.stdout(Stdio::piped()).stderr(Stdio::piped()))
        .spawn()
        .expect("command runs");
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            let o = child.wait_with_output().unwrap();
            panic!("{shown} still ran after 60 s: {}", stderr(&o));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// Small GA, trials and AEM sizes (`--set` values) for tests that need a quick run.
pub const SMALL: [&str; 5] = [
    "ga.population=10",
    "ga.generations=3",
    "trial.steps=100",
    "aem.epochs=20",
    "aem.test_runs=2",
];

/// A command line of the binary being built, e.g.
/// `Fm::new(["run", cfg]).out(&dir).sets(&SMALL).ok()`.
pub struct Fm {
    cmd: Command,
    shown: Vec<String>,
}

impl Fm {
    /// `fuzzymotiv ARGS…`.
    pub fn new<S: AsRef<std::ffi::OsStr>>(args: impl IntoIterator<Item = S>) -> Fm {
        let mut fm = Fm {
            cmd: bin(),
            shown: Vec::new(),
        };
        for a in args {
            fm = fm.arg(a);
        }
        fm
    }

    /// One more argument.
    pub fn arg(mut self, a: impl AsRef<std::ffi::OsStr>) -> Fm {
        self.shown.push(a.as_ref().to_string_lossy().into_owned());
        self.cmd.arg(a);
        self
    }

    /// `--out DIR`.
    pub fn out(self, dir: &Path) -> Fm {
        self.arg("--out").arg(dir)
    }

    /// `--set KEY=VALUE` for each of `sets`.
    pub fn sets(mut self, sets: &[&str]) -> Fm {
        for s in sets {
            self = self.arg("--set").arg(s);
        }
        self
    }

    /// Sets an environment variable of the command.
    pub fn env(mut self, key: &str, value: &str) -> Fm {
        self.cmd.env(key, value);
        self
    }

    /// Runs in `dir` instead of the current directory.
    pub fn in_dir(mut self, dir: &Path) -> Fm {
        self.cmd.current_dir(dir);
        self
    }

    /// Runs it and returns what it did.
    pub fn run(mut self) -> Output {
        self.cmd.output().expect("binary runs")
    }

    /// Runs it and asserts it succeeded.
    pub fn ok(self) -> Output {
        let shown = self.shown.join(" ");
        let o = self.run();
        assert!(
            o.status.success(),
            "fuzzymotiv {shown} failed: {}",
            stderr(&o)
        );
        o
    }
}

/// Asserts that each of `files` holds the same bytes in directories `a` and `b`; `why` ends the
/// message (e.g. "between one and two threads").
pub fn assert_same_files(a: &Path, b: &Path, files: &[&str], why: &str) {
    for f in files {
        let read = |dir: &Path| {
            std::fs::read(dir.join(f)).unwrap_or_else(|e| panic!("{}: {e}", dir.join(f).display()))
        };
        let (x, y) = (read(a), read(b));
        assert!(
            x == y,
            "{f} differs {why}:\n{}\n--- against ---\n{}",
            String::from_utf8_lossy(&x),
            String::from_utf8_lossy(&y)
        );
    }
}

/// A run directory's `summary.json` without its `wall_seconds` (the one field that may differ
/// between two runs of the same experiment).
pub fn summary_without_time(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v.as_object_mut()
        .unwrap()
        .remove("wall_seconds")
        .expect("a wall time");
    v
}

/// The files under `dir` ([`tree`]) without what holds wall times: every `summary.json`'s
/// `wall_seconds` (at any depth) removed and the report pages left out.
pub fn results(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    fn strip(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Object(m) => {
                m.remove("wall_seconds");
                m.values_mut().for_each(strip);
            }
            serde_json::Value::Array(a) => a.iter_mut().for_each(strip),
            _ => {}
        }
    }
    tree(dir)
        .into_iter()
        .filter(|(p, _)| p.extension().is_none_or(|e| e != "html"))
        .map(|(p, bytes)| {
            if p.file_name().is_some_and(|n| n == "summary.json") {
                let mut v: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
                strip(&mut v);
                (p, v.to_string().into_bytes())
            } else {
                (p, bytes)
            }
        })
        .collect()
}

/// Asserts that two outputs hold the same results ([`results`]), naming the files that differ
/// (not dumping their bytes).
pub fn assert_same_results(got: &Path, want: &Path) {
    let (got, want) = (results(got), results(want));
    let names = |r: &[(PathBuf, Vec<u8>)]| r.iter().map(|(p, _)| p.clone()).collect::<Vec<_>>();
    assert_eq!(names(&got), names(&want), "not the same files");
    let differ: Vec<&PathBuf> = (got.iter().zip(&want))
        .filter(|(a, b)| a.1 != b.1)
        .map(|(a, _)| &a.0)
        .collect();
    assert!(differ.is_empty(), "these files differ: {differ:?}");
}

/// Runs `study(out)` killed (as `kill -9` would: `FUZZYMOTIV_TEST_ABORT_AFTER`, a deterministic
/// point) after each of `kills` checkpointed generations in turn, asserting each left nothing
/// in place; then the same command resumes (saying so) and ends with the files of
/// `reference`, an uninterrupted run of the same command; run again, it has nothing to do.
pub fn assert_killed_study_resumes(study: impl Fn(&Path) -> Fm, out: &Path, kills: &[usize]) {
    use std::os::unix::process::ExitStatusExt;
    let reference = out.with_extension("reference");
    study(&reference).ok();
    for n in kills {
        let o = study(out)
            .env("FUZZYMOTIV_TEST_ABORT_AFTER", &n.to_string())
            .run();
        assert_eq!(
            o.status.signal(),
            Some(6),
            "not aborted after {n}: {}",
            stderr(&o)
        );
        assert!(!out.exists(), "a killed study is not in place");
    }
    let o = study(out).ok();
    assert!(
        stderr(&o).contains("resuming the unfinished study"),
        "{}",
        stderr(&o)
    );
    assert_same_results(out, &reference);
    assert_eq!(
        stdout(&o),
        stdout(&study(&out.with_extension("again")).ok()),
        "the resumed study prints what an uninterrupted one prints"
    );
    let o = study(out).ok();
    assert!(stderr(&o).contains("nothing to do"), "{}", stderr(&o));
}
