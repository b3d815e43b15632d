//! Input files read with bounds (configs, room files, sweep files, sensor tables, robot logs):
//! a device, an endless pipe, a binary file or a file over its size is refused at once with
//! status 2, naming the file and what is wrong, in bounded memory. Each command here runs
//! under `ulimit -v` (1 GB of address space), so reading without bounds would fail otherwise;
//! each must end because it refuses: a command still running after a minute is killed and
//! fails the test, so the suite never hangs.

use crate::common;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::{Fm, SMALL, repo, stderr, stdout, within_a_minute};

/// Address space the commands may use (KiB, for `ulimit -v`).
const MEMORY_KIB: u32 = 1_000_000;

/// `fuzzymotiv ARGS` under `ulimit -v` [`MEMORY_KIB`], killed (and the test failed) if it is
/// still running after a minute ([`within_a_minute`]).
fn bounded(args: &[&str]) -> Output {
    let mut sh = Command::new("sh");
    sh.arg("-c")
        .arg(format!("ulimit -v {MEMORY_KIB}; exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_fuzzymotiv"))
        .args(args);
    within_a_minute(sh)
}

/// `fuzzymotiv ARGS` refused with status 2 in bounded memory; its message, which names `file`
/// and says `what`.
fn refused(args: &[&str], file: &str, what: &str) -> String {
    let o = bounded(args);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {msg}");
    assert!(msg.contains(file) && msg.contains(what), "{args:?}: {msg}");
    assert!(!msg.contains("panicked"), "{args:?}: {msg}");
    msg
}

/// A FIFO in `dir` fed without end with `chunk` by a thread (which stops when the reader
/// closes it; left blocked, it ends with the test process).
fn endless_fifo(dir: &Path, name: &str, chunk: Vec<u8>) -> PathBuf {
    let fifo = dir.join(name);
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let path = fifo.clone();
    std::thread::spawn(move || {
        let Ok(mut f) = std::fs::OpenOptions::new().write(true).open(&path) else {
            return;
        };
        while f.write_all(&chunk).is_ok() {}
    });
    fifo
}

/// A tiny run with room modelling in `dir/run`.
fn tiny_run(dir: &Path) -> PathBuf {
    let run = dir.join("run");
    let cfg = repo().join("configs/tiny.toml");
    Fm::new(["run".as_ref(), cfg.as_os_str(), "--quiet".as_ref()])
        .out(&run)
        .sets(&SMALL)
        .ok();
    run
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_device_as_an_input_file_is_refused_at_once_naming_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let out = tmp.path().join("out");
    let table = tmp.path().join("table.toml");
    for (args, what) in [
        (
            vec!["calibrate", "/dev/zero", "--out", s(&table)],
            "measurements file",
        ),
        (
            vec!["calibrate", "/dev/urandom", "--out", s(&table)],
            "measurements file",
        ),
        (vec!["run", "/dev/zero", "--out", s(&out)], "config file"),
        (vec!["rooms", "--check", "/dev/zero"], "room file"),
        (vec!["plan", "/dev/zero"], "sweep file"),
        (vec!["recognise", s(&run), "/dev/zero"], "log file"),
        (
            vec!["replay", s(&run), "--room", "H", "--log", "/dev/zero"],
            "log file",
        ),
    ] {
        let file = args.iter().find(|a| a.starts_with("/dev/")).unwrap();
        let msg = refused(&args, file, "is a device, not a file");
        assert!(
            msg.contains(&format!("a {what} is read from a regular file")),
            "{msg}"
        );
    }
    assert!(!out.exists() && !table.exists());
}

#[test]
fn an_endless_pipe_is_refused_at_its_first_bad_byte_or_its_size_limit() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let table = tmp.path().join("table.toml");
    let zeros = endless_fifo(tmp.path(), "zeros", vec![0; 1 << 16]);
    refused(
        &["calibrate", s(&zeros), "--out", s(&table)],
        s(&zeros),
        "line 1: a NUL byte (0x00), so this is not text",
    );
    let noise = endless_fifo(tmp.path(), "noise", b"sensor,\xfe\xff".repeat(1 << 12));
    refused(
        &["calibrate", s(&noise), "--out", s(&table)],
        s(&noise),
        "line 1: byte 0xfe is not UTF-8 text",
    );
    let comments = b"# a comment line, forever\n".repeat(1 << 12);
    let fifo = endless_fifo(tmp.path(), "comments", comments.clone());
    refused(
        &["calibrate", s(&fifo), "--out", s(&table)],
        s(&fifo),
        "is larger than the 16 MiB a measurements file may be",
    );
    let fifo = endless_fifo(tmp.path(), "config", comments);
    let out = tmp.path().join("out");
    refused(
        &["run", s(&fifo), "--out", s(&out)],
        s(&fifo),
        "is larger than the 16 MiB a config file may be",
    );
    let fifo = endless_fifo(tmp.path(), "one-line", b"straight,".repeat(1 << 12));
    refused(
        &["recognise", s(&run), s(&fifo)],
        s(&fifo),
        "line 1 is longer than the 1 MiB a line of a log file may be",
    );
    let fifo = endless_fifo(tmp.path(), "log-zeros", vec![0; 1 << 16]);
    refused(
        &["recognise", s(&run), s(&fifo)],
        s(&fifo),
        "line 1: a NUL byte",
    );
    assert!(!table.exists() && !out.exists());
}

#[test]
fn a_bad_byte_in_a_log_is_refused_naming_its_line() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let log = tmp.path().join("log.csv");
    std::fs::write(&log, b"action\nstraight\nleft\nri\xffght\nback\n").unwrap();
    refused(
        &["recognise", s(&run), s(&log)],
        s(&log),
        "line 4: byte 0xff is not UTF-8 text; a log file is UTF-8 text",
    );
}

/// A 66 MB log of one short column (the log that took 1.8 GB when a log was held whole, and
/// fails under this test's 1 GB of address space) is read line by line: recognised, every step
/// counted.
#[test]
fn a_large_log_is_recognised_in_bounded_memory() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let log = tmp.path().join("big.csv");
    let mut text = String::from("action\n");
    let mut rows = 0;
    while text.len() < 66_000_000 {
        text.push_str("straight\nleft\nright\nback\n");
        rows += 4;
    }
    std::fs::write(&log, &text).unwrap();
    drop(text);
    let o = bounded(&["recognise", s(&run), s(&log)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let md = stdout(&o);
    assert!(
        md.contains(&format!("| {} | {rows} | 100 |", log.display()))
            && md.contains("25 / 25 / 25 / 25"),
        "{rows} rows: {md}"
    );
}

/// A room file or sensor table a config names is read with the same bounds: one over 16 MiB
/// is refused naming it and what it is.
#[test]
fn an_oversized_room_file_or_sensor_table_named_by_a_config_is_refused_naming_it() {
    let tmp = tempfile::tempdir().unwrap();
    let big = tmp.path().join("big.toml");
    std::fs::write(&big, "# a comment\n".repeat(1_500_000)).unwrap();
    let out = tmp.path().join("out");
    for (config, what) in [
        ("rooms = [\"big.toml\"]\n", "room file"),
        (
            "[trial]\nsensor_table = \"big.toml\"\n",
            "sensor table file",
        ),
    ] {
        let cfg = tmp.path().join("c.toml");
        std::fs::write(&cfg, config).unwrap();
        refused(
            &["run", s(&cfg), "--out", s(&out)],
            s(&big),
            &format!("is larger than the 16 MiB a {what} may be"),
        );
    }
    assert!(!out.exists());
}
