//! `--out` naming what cannot be an output directory: the message says what it really is, and
//! the staging name of another output (`NAME.partial`) is never taken as an output.

mod common;

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
