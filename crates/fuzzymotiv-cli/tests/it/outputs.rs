//! `--out` naming what cannot be an output directory: the message says what it really is, and
//! the staging name of another output (`NAME.partial`) is never taken as an output.

use crate::common;

use std::path::Path;

use common::{Fm, SMALL, repo, stderr};

/// `fuzzymotiv run configs/tiny.toml --out OUT` with small sizes.
fn tiny_run(out: &Path) -> Fm {
    let cfg = repo().join("configs/tiny.toml");
    Fm::new(["run".as_ref(), cfg.as_os_str()])
        .out(out)
        .sets(&SMALL)
}

fn refused(fm: Fm) -> String {
    let o = fm.run();
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    msg
}

#[test]
fn out_naming_a_link_a_fifo_or_a_file_says_what_it_is() {
    let tmp = tempfile::tempdir().unwrap();
    let target = tmp.path().join("real");
    std::fs::create_dir(&target).unwrap();
    let link = tmp.path().join("link");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let fifo = tmp.path().join("fifo");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let file = tmp.path().join("file");
    std::fs::write(&file, "mine").unwrap();
    for (out, what) in [
        (&link, "is a symbolic link"),
        (&fifo, "is a FIFO (named pipe), not a directory"),
        (&file, "is a regular file, not a directory"),
    ] {
        let msg = refused(tiny_run(out));
        assert!(
            msg.contains(what) && msg.contains("--out"),
            "{}: {msg}",
            out.display()
        );
        let sweep = repo().join("configs/sweep-small.toml");
        let msg = refused(Fm::new(["sweep".as_ref(), sweep.as_os_str()]).out(out));
        assert!(msg.contains(what), "sweep {}: {msg}", out.display());
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    assert!(
        std::fs::read_dir(&target).unwrap().next().is_none(),
        "wrote through the link"
    );
}

#[test]
fn out_ending_in_partial_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let staging = tmp.path().join("x.partial");
    let sweep = repo().join("configs/sweep-small.toml");
    let s = staging.to_str().unwrap();
    let commands = [
        tiny_run(&staging),
        Fm::new(["reproduce", "--quick", "--seeds", "1"]).out(&staging),
        Fm::new(["sweep".as_ref(), sweep.as_os_str()]).out(&staging),
        Fm::new(["claims", "study", "--out", s]),
        Fm::new(["compare", "a", "b", "--out", s]),
    ];
    for fm in commands {
        let msg = refused(fm);
        assert!(msg.contains(".partial") && msg.contains("--out"), "{msg}");
        assert!(!staging.exists(), "{msg}");
    }
}

/// `--help` and `--version` write through the same standard output as every result: a full
/// one is the one-line error with status 1 of docs/guide/cli.md ("Pipes, full disks"), not a silent success.
#[test]
fn help_and_version_on_a_full_stdout_are_a_one_line_error() {
    for args in [
        &["--help"][..],
        &["--version"],
        &["-V"],
        &["run", "--help"],
        &["claims", "-h"],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let o = common::bin().args(args).stdout(full).output().unwrap();
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(e.starts_with("error: standard output:"), "{args:?}: {e}");
        assert_eq!(e.lines().count(), 1, "{args:?}: {e}");
        // And on a working one, the help as before.
        let o = common::bin().args(args).output().unwrap();
        assert!(o.status.success() && !o.stdout.is_empty(), "{args:?}");
    }
}

/// `recognise`, `robustness`, `compare` and `export --to c` write a few files into `--out DIR`
/// (and `claims`' claims.md and claims.csv) through the same guard as `run`: the current directory, a device, a regular file and `-`
/// (standard output takes one file) are refused with status 2 before any work, naming `--out`
/// and what it is; nothing is written. The one-file outputs (`calibrate`'s table,
/// `export --to json`) refuse a device and keep another file, as `replay` does.
#[test]
fn out_of_the_commands_writing_into_a_directory_or_a_file_is_guarded_like_the_others() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tmp.path().join("run");
    tiny_run(&run).arg("--quiet").ok();
    let log = tmp.path().join("log.csv");
    std::fs::write(&log, "action\nstraight\nleft\n").unwrap();
    let mine = tmp.path().join("mine.txt");
    std::fs::write(&mine, "mine").unwrap();
    let work = tmp.path().join("work");
    std::fs::create_dir(&work).unwrap();
    let (r, m) = (run.to_str().unwrap(), mine.to_str().unwrap());
    let study = repo().join("docs/results/twenty-seed");
    let into_directory = [
        vec!["recognise", r, log.to_str().unwrap()],
        vec!["robustness", r, "--trials", "2"],
        vec!["compare", r, r],
        vec!["export", r, "--to", "c"],
        vec!["claims", study.to_str().unwrap()],
    ];
    for args in &into_directory {
        for (out, what) in [
            (".", "is the current directory"),
            ("/dev/full", "is a device, not a directory"),
            (m, "is a regular file, not a directory"),
            ("-", "`-` is standard output, which takes one file"),
        ] {
            let msg = refused(Fm::new(args).arg("--out").arg(out).in_dir(&work));
            assert!(
                msg.contains(&format!("--out {out}: {what}")),
                "{args:?} --out {out}: {msg}"
            );
        }
    }
    let bench = repo().join("configs/sensors/khepera-bench.csv");
    let one_file = [
        vec!["calibrate", bench.to_str().unwrap()],
        vec!["export", r, "--to", "json"],
    ];
    for args in &one_file {
        for (out, what) in [
            ("/dev/full", "is a device, which is never replaced"),
            (
                m,
                "the file exists with other contents and is kept; pass --force",
            ),
        ] {
            let msg = refused(Fm::new(args).arg("--out").arg(out).in_dir(&work));
            assert!(
                msg.contains(&format!("--out {out}: {what}")),
                "{args:?} --out {out}: {msg}"
            );
        }
    }
    assert_eq!(std::fs::read_to_string(&mine).unwrap(), "mine");
    assert!(std::fs::read_dir(&work).unwrap().next().is_none());
}

/// `claims --out DIR` a second time finds claims.md and claims.csv already holding these
/// claims: it says so (naming both files) and writes nothing, as the other commands do.
#[test]
fn claims_again_into_the_same_out_says_the_files_are_already_there_and_unchanged() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("claims");
    let study = repo().join("docs/results/twenty-seed");
    let first = Fm::new(["claims"]).arg(&study).out(&out).ok();
    assert!(stderr(&first).contains("wrote "), "{}", stderr(&first));
    let written = std::fs::read(out.join("claims.md")).unwrap();
    let again = Fm::new(["claims"]).arg(&study).out(&out).ok();
    let said = stderr(&again);
    assert!(
        said.contains("claims.md and ")
            && said.contains("claims.csv already hold these claims; nothing to do"),
        "{said}"
    );
    assert!(!said.contains("wrote "), "{said}");
    assert_eq!(std::fs::read(out.join("claims.md")).unwrap(), written);
}

/// `--out -` of an output that is one file (`calibrate`'s sensor table, `export --to json`)
/// is standard output, as `fuzzy --export-fll -` is: the bytes the file would hold, and no file
/// named `-`.
#[test]
fn out_dash_of_a_one_file_output_is_standard_output() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tmp.path().join("run");
    tiny_run(&run).arg("--quiet").ok();
    let bench = repo().join("configs/sensors/khepera-bench.csv");
    let r = run.to_str().unwrap();
    for (args, file) in [
        (vec!["calibrate", bench.to_str().unwrap()], "table.toml"),
        (vec!["export", r, "--to", "json"], "controller.json"),
    ] {
        let path = tmp.path().join(file);
        let written = Fm::new(&args).out(&path).ok();
        let o = Fm::new(&args).arg("--out").arg("-").in_dir(tmp.path()).ok();
        assert_eq!(o.stdout, std::fs::read(&path).unwrap(), "{args:?}");
        assert!(!tmp.path().join("-").exists(), "{args:?}");
        if args[0] == "calibrate" {
            // The spread goes to standard error when the table takes standard output.
            assert!(common::stdout(&written).starts_with("sensor,distance_mm"));
            assert!(stderr(&o).contains("sensor,distance_mm"), "{}", stderr(&o));
        }
    }
}

/// An output directory whose `config.resolved.toml` is a FIFO beside a `summary.json` is not
/// read to find whether it holds this run: it is another run's, refused with status 2 at once
/// (no read that waits on the pipe without end).
#[test]
fn an_output_whose_identity_file_is_a_fifo_is_refused_without_reading_it() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("summary.json"), "{}").unwrap();
    let fifo = out.join("config.resolved.toml");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let cfg = repo().join("configs/tiny.toml");
    let mut cmd = common::bin();
    cmd.arg("run").arg(&cfg).arg("--out").arg(&out);
    let o = common::within_a_minute(cmd);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("holds the results of a different run"),
        "{msg}"
    );
}
