//! "Keep the promise everywhere": every way of writing output keeps `run`'s promise (results are
//! never replaced silently, the same command resumes or says it is done), and no command panics
//! when its standard output fails. Each test is named after the behaviour it checks.
//!
//! Kill points are deterministic: `FUZZYMOTIV_TEST_ABORT_AFTER=N` makes the binary abort (as
//! `kill -9` would) once N generations have been checkpointed, so nothing here depends on timing.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use common::{Fm, SMALL, bin, repo, stderr, stdout};

/// The files under `dir` (recursively, relative paths, in order) with their contents.
fn tree(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    common::tree(dir).into_iter().collect()
}

/// `configs/tiny.toml` run with the `SMALL` sizes into `out`.
fn tiny_run(out: &Path) {
    let cfg = repo().join("configs/tiny.toml");
    Fm::new(["run", cfg.to_str().unwrap()])
        .out(out)
        .sets(&SMALL)
        .ok();
}

/// `configs/sweep-small.toml` with another GA size and number of replicates.
fn small_sweep(population: usize, generations: usize, replicates: usize) -> String {
    std::fs::read_to_string(repo().join("configs/sweep-small.toml"))
        .unwrap()
        .replace("population = 40", &format!("population = {population}"))
        .replace("generations = 40", &format!("generations = {generations}"))
        .replace("replicates = 3", &format!("replicates = {replicates}"))
}

/// A small study's command line into `out`.
fn study(out: &Path) -> Fm {
    // One thread: the runs go one after another, so the kill points below fall in the first
    // run, between runs and in the last one whatever the machine.
    Fm::new([
        "reproduce",
        "--quick",
        "--seeds",
        "2",
        "--quiet",
        "--threads",
        "1",
    ])
    .out(out)
    .sets(&["ga.population=10", "ga.generations=4", "trial.steps=150"])
}

/// The command, aborted after `n` checkpointed generations.
fn aborted(cmd: Fm, n: usize) -> Output {
    use std::os::unix::process::ExitStatusExt;
    let o = cmd.env("FUZZYMOTIV_TEST_ABORT_AFTER", &n.to_string()).run();
    assert_eq!(
        o.status.signal(),
        Some(6),
        "not aborted after {n} generations"
    );
    o
}

/// The commands that error messages suggest (between backticks, starting with `fuzzymotiv`).
fn suggested(message: &str) -> Vec<String> {
    message
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|s| s.starts_with("fuzzymotiv "))
        .map(str::to_string)
        .collect()
}

/// Runs a suggested command line (`fuzzymotiv ARGS`, split at spaces) and asserts it works.
fn suggestion_works(command: &str) {
    let args: Vec<&str> = command.split_whitespace().skip(1).collect();
    let o = bin().args(&args).output().unwrap();
    assert!(
        o.status.success(),
        "the suggested `{command}` failed: {}",
        stderr(&o)
    );
}

/// `reproduce` killed at several deterministic points resumes with the same command
/// and ends with exactly the files of an uninterrupted study; a message that suggests a command
/// suggests one that works.
#[test]
fn killed_reproduce_resumes_to_the_files_of_an_uninterrupted_study() {
    let dir = tempfile::tempdir().unwrap();
    let reference = dir.path().join("reference");
    study(&reference).ok();
    let out = dir.path().join("killed");
    // 2 settings × 2 seeds × 4 generations = 16 generations, run one after another: the kills
    // fall inside the first run, inside the third (the first two then finished: read back) and
    // inside the last.
    for n in [3, 6, 5] {
        aborted(study(&out), n);
        assert!(!out.exists(), "a killed study is not in place");
    }
    let o = study(&out).ok();
    assert!(
        stderr(&o).contains("resuming the unfinished study"),
        "{}",
        stderr(&o)
    );
    common::assert_same_results(&out, &reference);
    assert_eq!(
        stdout(&o),
        stdout(&study(dir.path().join("again").as_path()).ok())
    );
    // The same command on the finished study: nothing to do.
    let o = study(&out).ok();
    assert!(stderr(&o).contains("nothing to do"), "{}", stderr(&o));

    // A killed `run` in the study's place: reproduce refuses, suggesting a command that works.
    let cfg = repo().join("configs/tiny.toml");
    let other = dir.path().join("other");
    aborted(
        Fm::new(["run", cfg.to_str().unwrap()])
            .out(&other)
            .sets(&SMALL),
        1,
    );
    let o = study(&other).run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let commands = suggested(&stderr(&o));
    assert_eq!(commands.len(), 1, "{}", stderr(&o));
    suggestion_works(&commands[0]);
    assert!(other.join("summary.json").is_file());
}

/// Ablation and orientation studies resume too: an aborted ablation finishes with the
/// same command.
#[test]
fn killed_ablation_resumes_with_the_same_command() {
    let dir = tempfile::tempdir().unwrap();
    let ablation = |out: &Path| {
        Fm::new([
            "reproduce",
            "--ablation",
            "--quick",
            "--seeds",
            "1",
            "--quiet",
        ])
        .out(out)
        .sets(&["ga.population=8", "ga.generations=2", "trial.steps=100"])
    };
    let reference = dir.path().join("reference");
    ablation(&reference).ok();
    let out = dir.path().join("killed");
    aborted(ablation(&out), 7);
    ablation(&out).ok();
    common::assert_same_results(&out, &reference);
}

/// `sweep --out` is protected: a directory of the user's, a run directory and the
/// current directory are refused; another plan is refused unless it only adds jobs; `--force`
/// replaces the sweep but never a file of the user's.
#[test]
fn sweep_out_never_replaces_a_users_directory_or_another_plan() {
    let dir = tempfile::tempdir().unwrap();
    let base = small_sweep(6, 2, 1);
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let one = write("one.toml", &base);
    let more = write(
        "more.toml",
        &base.replace("replicates = 1", "replicates = 2"),
    );
    let edited = write(
        "edited.toml",
        &base.replace("[0.2, 0.6, 0.0, 0.2]", "[0.3, 0.5, 0.0, 0.2]"),
    );
    let go = |file: &Path, out: &Path, extra: &[&str]| {
        let mut cmd = Fm::new(["sweep", file.to_str().unwrap(), "--quiet"]).out(out);
        for a in extra {
            cmd = cmd.arg(a);
        }
        cmd.arg("--threads").arg("2").run()
    };

    // A directory of the user's: refused, even with --force.
    let thesis = dir.path().join("thesis");
    std::fs::create_dir(&thesis).unwrap();
    std::fs::write(thesis.join("thesis.txt"), "mine").unwrap();
    for extra in [&[][..], &["--force"][..]] {
        let o = go(&one, &thesis, extra);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert_eq!(tree(&thesis).len(), 1);
    }
    // A run directory: refused without --force.
    let run_dir = dir.path().join("run");
    tiny_run(&run_dir);
    let before = tree(&run_dir);
    let o = go(&one, &run_dir, &[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(tree(&run_dir), before);
    // The current directory: refused.
    let o = Fm::new(["sweep", one.to_str().unwrap(), "--out", "."])
        .in_dir(&thesis)
        .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(tree(&thesis).len(), 1);

    // A sweep, then an edited plan into it: refused, the old jobs kept.
    let out = dir.path().join("sweep");
    assert!(go(&one, &out, &[]).status.success());
    let first = tree(&out);
    let o = go(&edited, &out, &[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("another plan"), "{}", stderr(&o));
    assert_eq!(tree(&out), first);
    // A plan that only adds replicates: the finished jobs are kept, the new ones run.
    let o = go(&more, &out, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("3 jobs run, 3 already done"),
        "{}",
        stderr(&o)
    );
    for (path, bytes) in &first {
        if path.starts_with("jobs") {
            assert_eq!(&std::fs::read(out.join(path)).unwrap(), bytes, "{path:?}");
        }
    }
    // --force replaces the sweep: old job folders go, a file of the user's stays.
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let o = go(&edited, &out, &["--force"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let jobs = std::fs::read_dir(out.join("jobs")).unwrap();
    // Job folders (their lock files are beside them).
    let jobs = jobs.filter(|e| e.as_ref().unwrap().path().is_dir()).count();
    assert_eq!(jobs, 3);
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
    // merge --png rasterises the summary.
    Fm::new(["merge", out.to_str().unwrap(), "--png"]).ok();
    assert!(out.join("summary.png").is_file());
}

/// `replay` never overwrites other files without `--force`; the same replay again
/// changes nothing; `--out` naming a directory is refused before anything is written.
#[test]
fn replay_never_overwrites_without_force() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = dir.path().join("run");
    tiny_run(&run_dir);
    let out = dir.path().join("rp");
    let page = out.join("replay.html");
    let replay = |extra: &[&str]| {
        let mut cmd = Fm::new(["replay", run_dir.to_str().unwrap(), "--room", "H"])
            .arg("--out")
            .arg(&page);
        for a in extra {
            cmd = cmd.arg(a);
        }
        cmd.run()
    };
    assert!(replay(&[]).status.success());
    let first = tree(&out);
    let o = replay(&[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("nothing to do"), "{}", stderr(&o));
    assert_eq!(tree(&out), first);
    // Another seed: other contents, kept unless --force.
    let o = replay(&["--seed", "5"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--force"), "{}", stderr(&o));
    assert_eq!(tree(&out), first);
    assert!(replay(&["--seed", "5", "--force"]).status.success());
    assert_ne!(tree(&out), first);
    // --out naming a directory: refused, nothing written beside it.
    let before = tree(dir.path());
    let o = Fm::new([
        "replay",
        run_dir.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
    .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("is a directory"), "{}", stderr(&o));
    assert_eq!(tree(dir.path()), before);
}

/// `fuzzy --export-fll FILE --force` never replaces what is not a regular file (a
/// FIFO, a directory, a symbolic link); `-` writes to standard output; the same file again is
/// left alone; another file is kept unless `--force`.
#[test]
fn fll_export_never_replaces_a_non_regular_file() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("fifo");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let sub = dir.path().join("sub");
    std::fs::create_dir(&sub).unwrap();
    let target = dir.path().join("target.txt");
    std::fs::write(&target, "mine").unwrap();
    let link = dir.path().join("link.fll");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let export = |path: &Path, m: &str, force: bool| {
        let mut cmd = Fm::new(["fuzzy", "--motivations", m, "--export-fll"]).arg(path);
        if force {
            cmd = cmd.arg("--force");
        }
        cmd.run()
    };
    for path in [&fifo, &sub, &link] {
        let o = export(path, ".8,.1,0,.1", true);
        assert_eq!(o.status.code(), Some(2), "{path:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("never replaced"), "{}", stderr(&o));
    }
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    assert!(sub.is_dir());
    assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "mine");

    let fll = dir.path().join("hc.fll");
    assert!(export(&fll, ".8,.1,0,.1", false).status.success());
    let o = export(&fll, ".8,.1,0,.1", false);
    assert!(o.status.success() && stderr(&o).contains("nothing to do"));
    let first = std::fs::read(&fll).unwrap();
    let o = export(&fll, ".5,.3,0,.2", false);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(std::fs::read(&fll).unwrap(), first);
    assert!(export(&fll, ".5,.3,0,.2", true).status.success());
    assert_ne!(std::fs::read(&fll).unwrap(), first);
    let o = export(Path::new("-"), ".8,.1,0,.1", false);
    assert!(o.status.success());
    let text = stdout(&o);
    assert!(text.starts_with("Engine: fuzzymotiv\n"), "{}", &text[..40]);
    assert_eq!(text.matches("rule: if").count(), 625);
    assert!(!dir.path().join("-").exists());
}

/// Commands that print to standard output and write no file.
const EXPLAIN: [&str; 6] = [
    "fuzzy",
    "--motivations",
    ".8,.1,0,.1",
    "--fitness",
    "1,.25,0,0",
    "--explain",
];
const FLL_TO_STDOUT: [&str; 5] = ["fuzzy", "--motivations", ".8,.1,0,.1", "--export-fll", "-"];
const BENCH: [&str; 7] = [
    "bench",
    "--steps",
    "50",
    "--repeat",
    "1",
    "--population",
    "4",
];

/// Every command that prints to standard output, with small sizes; `dir` holds a finished run
/// (`run`) and a finished sweep (`sweep`).
fn printing_commands(dir: &Path) -> Vec<Vec<String>> {
    let cfg = repo().join("configs/tiny.toml").display().to_string();
    let sweep_file = repo()
        .join("configs/sweep-small.toml")
        .display()
        .to_string();
    let d = |name: &str| dir.join(name).display().to_string();
    let mut small: Vec<String> = Vec::new();
    for s in SMALL {
        small.push("--set".into());
        small.push(s.into());
    }
    let mut commands: Vec<Vec<String>> = [
        vec!["rooms"],
        vec!["plan", &sweep_file],
        vec!["plan", &sweep_file, "--count"],
        EXPLAIN.to_vec(),
        FLL_TO_STDOUT.to_vec(),
        BENCH.to_vec(),
        vec!["merge", &d("sweep")],
        vec!["--help"],
        vec!["--version"],
    ]
    .iter()
    .map(|c| c.iter().map(|s| s.to_string()).collect())
    .collect();
    let mut run = vec![
        "run".to_string(),
        cfg.clone(),
        "--out".into(),
        d("fresh-run"),
    ];
    run.extend(small.iter().cloned());
    commands.push(run);
    let mut replay = vec!["replay".to_string(), d("run"), "--room".into(), "H".into()];
    replay.extend(["--out".into(), d("replay/r.html"), "--force".into()]);
    commands.push(replay);
    let mut study: Vec<String> = ["reproduce", "--quick", "--seeds", "1", "-q", "--force"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    study.extend(["--out".into(), d("study")]);
    study.extend(["--set", "ga.population=6", "--set", "ga.generations=2"].map(String::from));
    commands.push(study);
    commands
}

/// A finished run and sweep in `dir` for [`printing_commands`].
fn prepare(dir: &Path) {
    tiny_run(&dir.join("run"));
    let sweep = small_sweep(4, 1, 1);
    let file = dir.join("sweep.toml");
    std::fs::write(&file, sweep).unwrap();
    Fm::new(["sweep", file.to_str().unwrap(), "--quiet"])
        .out(&dir.join("sweep"))
        .ok();
}

/// With its standard output closed (`| head -1` after the reader has gone), every
/// command ends quietly with status 141, as a program killed by SIGPIPE; never a panic.
#[test]
fn closed_stdout_ends_quietly_with_141_without_panic() {
    let dir = tempfile::tempdir().unwrap();
    prepare(dir.path());
    for args in printing_commands(dir.path()) {
        // The reader is gone before the command starts: its first write fails with EPIPE.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = bin()
            .args(&args)
            .stdout(writer)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let e = stderr(&o);
        assert!(!e.contains("panicked"), "{args:?}: {e}");
        if args[0].starts_with("--") {
            // clap prints help and version itself and ignores the failure.
            continue;
        }
        assert_eq!(o.status.code(), Some(141), "{args:?}: {e}");
        assert!(!e.contains("error"), "{args:?}: {e}");
    }
}

/// A full disk: standard output to a file under a file-size limit of zero (SIGXFSZ
/// ignored, so the write fails with EFBIG as a full disk fails with ENOSPC) gives one line of
/// error, never a panic. Only commands that write no other file (the limit applies to them too).
#[test]
fn full_stdout_is_a_one_line_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let sweep_file = repo().join("configs/sweep-small.toml");
    for args in [
        vec!["rooms".to_string()],
        vec!["plan".into(), sweep_file.display().to_string()],
        FLL_TO_STDOUT.map(String::from).to_vec(),
        EXPLAIN.map(String::from).to_vec(),
        BENCH.map(String::from).to_vec(),
    ] {
        let out = dir.path().join("out.txt");
        let o = Command::new("sh")
            .arg("-c")
            .arg("trap '' XFSZ; ulimit -f 0; exec \"$@\" > \"$OUT\"")
            .arg("sh")
            .arg(env!("CARGO_BIN_EXE_fuzzymotiv"))
            .args(&args)
            .env("OUT", &out)
            .output()
            .unwrap();
        let e = stderr(&o);
        assert!(!e.contains("panicked"), "{args:?}: {e}");
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(e.starts_with("error: standard output:"), "{args:?}: {e}");
        assert_eq!(e.lines().count(), 1, "{args:?}: {e}");
    }
}

/// A closed standard error: a run loses its progress lines and notes but finishes.
#[test]
fn closed_stderr_drops_progress_and_the_run_finishes() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let out = dir.path().join("run");
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let mut args: Vec<String> = vec!["run".into(), cfg.display().to_string()];
    args.extend(["--out".into(), out.display().to_string()]);
    for s in SMALL {
        args.extend(["--set".into(), s.into()]);
    }
    let o = bin().args(&args).stderr(writer).output().unwrap();
    assert!(o.status.success(), "{}", stdout(&o));
    assert!(out.join("summary.json").is_file());
}

/// `--png` on a finished output writes the PNGs it lacks and nothing else.
#[test]
fn png_on_a_finished_output_adds_only_the_pngs() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let out = dir.path().join("run");
    let go = |png: bool| {
        let cmd = Fm::new(["run", cfg.to_str().unwrap()])
            .out(&out)
            .sets(&SMALL);
        (if png { cmd.arg("--png") } else { cmd }).ok()
    };
    go(false);
    let before = tree(&out);
    go(true);
    let after = tree(&out);
    let added: Vec<_> = after.iter().filter(|f| !before.contains(f)).collect();
    let names: Vec<String> = added.iter().map(|(p, _)| p.display().to_string()).collect();
    assert_eq!(names, ["fitness.png", "terms.png", "trajectories.png"]);
    assert!(before.iter().all(|f| after.contains(f)), "a file changed");
}

/// Review of the guard: a file named like a temporary file, or a link there, is never written
/// through; a directory holding a file of the user's beside our `summary.json` is not deleted by
/// `--force`; nor is a `DIR.partial` of the user's; a plan whose ids are paths removes nothing.
#[test]
fn force_never_deletes_or_writes_through_a_file_of_the_users() {
    let dir = tempfile::tempdir().unwrap();
    let keep = dir.path().join("keep.txt");
    std::fs::write(&keep, "important").unwrap();
    for name in ["hc.fll.tmp", ".tmp", "hc.tmp"] {
        let _ = std::os::unix::fs::symlink(&keep, dir.path().join(name));
    }
    let fll = dir.path().join("hc.fll");
    Fm::new(["fuzzy", "--motivations", ".8,.1,0,.1", "--export-fll"])
        .arg(&fll)
        .ok();
    assert_eq!(std::fs::read_to_string(&keep).unwrap(), "important");
    assert!(std::fs::symlink_metadata(&fll).unwrap().is_file());

    let cfg = repo().join("configs/tiny.toml");
    let proj = dir.path().join("proj");
    std::fs::create_dir(&proj).unwrap();
    std::fs::write(proj.join("summary.json"), "{}").unwrap();
    std::fs::write(proj.join("thesis.tex"), "mine").unwrap();
    let o = Fm::new(["run", cfg.to_str().unwrap(), "--force"])
        .out(&proj)
        .sets(&SMALL)
        .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("thesis.tex"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(proj.join("thesis.tex")).unwrap(),
        "mine"
    );

    let res = dir.path().join("res");
    let partial = dir.path().join("res.partial");
    std::fs::create_dir(&partial).unwrap();
    std::fs::write(partial.join("notes.txt"), "mine").unwrap();
    let o = Fm::new(["run", cfg.to_str().unwrap(), "--force"])
        .out(&res)
        .sets(&SMALL)
        .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(partial.join("notes.txt")).unwrap(),
        "mine"
    );

    let sweep = dir.path().join("sweep");
    std::fs::create_dir_all(sweep.join("jobs")).unwrap();
    std::fs::write(
        sweep.join("plan.jsonl"),
        r#"{"index":0,"id":"../../keep","key":"k","setting":"s","replicate":0,"seed":1,"overrides":[]}"#,
    )
    .unwrap();
    let o = Fm::new([
        "sweep",
        repo().join("configs/sweep-small.toml").to_str().unwrap(),
    ])
    .out(&sweep)
    .arg("--force")
    .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("16 hexadecimal digits"),
        "{}",
        stderr(&o)
    );
    assert!(keep.is_file());
}

/// Review of the guard: sweep array tasks started at the same moment on a new `--out` all run
/// (none takes the half-made directory of another for a foreign one), and together they give
/// the results of the whole sweep.
#[test]
fn array_tasks_started_together_share_a_new_sweep_directory() {
    let dir = tempfile::tempdir().unwrap();
    let text = small_sweep(4, 1, 2);
    let file = dir.path().join("s.toml");
    std::fs::write(&file, text).unwrap();
    let out = dir.path().join("out");
    let children: Vec<_> = (0..6)
        .map(|i| {
            bin()
                .args(["sweep", file.to_str().unwrap(), "--quiet", "--threads", "1"])
                .arg("--out")
                .arg(&out)
                .args(["--index", &i.to_string()])
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    for c in children {
        let o = c.wait_with_output().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let done = std::fs::read_dir(out.join("jobs"))
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().join("DONE").is_file())
        .count();
    assert_eq!(done, 6);
}

/// Review of the guard: `replay --out` whose name is that of one of the replay's own files is
/// refused before anything is written.
#[test]
fn replay_out_named_like_its_own_files_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = dir.path().join("run");
    tiny_run(&run_dir);
    for name in ["r.json", "r.svg"] {
        let before = tree(dir.path());
        let o = Fm::new(["replay", run_dir.to_str().unwrap(), "--room", "H", "--out"])
            .arg(dir.path().join(name))
            .run();
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        assert_eq!(tree(dir.path()), before, "{name}");
    }
}

/// A run killed after its last checkpoint became `population.json` but before the directory was
/// renamed into place (the staging directory holds every file but no checkpoint, and a temporary
/// file it was writing) finishes with the same command, without evolving again, and ends with
/// exactly the files of an uninterrupted run.
#[test]
fn killed_between_population_and_commit_finishes() {
    let dir = tempfile::tempdir().unwrap();
    let reference = dir.path().join("reference");
    tiny_run(&reference);
    let out = dir.path().join("killed");
    let staging = dir.path().join("killed.partial");
    std::fs::create_dir(&staging).unwrap();
    for (path, bytes) in tree(&reference) {
        std::fs::write(staging.join(path), bytes).unwrap();
    }
    std::fs::remove_file(staging.join("report.html")).unwrap();
    // A temporary file the killed process was writing: it must not end up in the output.
    std::fs::write(staging.join(".tmpAb12Cd"), "half a checkpoint").unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let o = Fm::new(["run", cfg.to_str().unwrap()])
        .out(&out)
        .sets(&SMALL)
        .ok();
    assert!(stderr(&o).contains("evolution finished"), "{}", stderr(&o));
    assert!(!staging.exists());
    common::assert_same_results(&out, &reference);
}

/// Output files get the usual permissions (0o666 less the umask, as a plain write gives them),
/// not a temporary file's 0o600: results in a shared directory stay readable by the group.
#[test]
fn output_files_are_readable_as_plain_writes_make_them() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let o = Command::new("sh")
        .arg("-c")
        .arg("umask 022; exec \"$@\"")
        .arg("sh")
        .arg(env!("CARGO_BIN_EXE_fuzzymotiv"))
        .args(["run", repo().join("configs/tiny.toml").to_str().unwrap()])
        .arg("--out")
        .arg(&out)
        .args(SMALL.iter().flat_map(|s| ["--set", s]))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    for (path, _) in tree(&out) {
        let mode = std::fs::metadata(out.join(&path))
            .unwrap()
            .permissions()
            .mode()
            & 0o777;
        assert_eq!(mode, 0o644, "{path:?}");
    }
}
