//! A sweep job's lock (`jobs/ID.lock`): `fuzzymotiv sweep` waits for a job another process
//! holds, then runs it if the holder died or skips it if the holder finished it. The test holds
//! the lock itself (as another worker would) and reads the binary's stderr until it says it
//! waits: no sleeps, no timing.

use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Stdio};

use crate::common;

use common::{bin, ok};

const SWEEP: &str = r#"
name = "locks"
seed = 4
rooms = ["H"]
[ga]
population = 6
generations = 2
[trial]
steps = 60
[aem]
enabled = false
[sweep]
replicates = 2
"#;

/// The id of job `index` of the sweep file `f`.
fn job_id(f: &Path, index: usize) -> String {
    let plan = String::from_utf8(ok(&["plan", f.to_str().unwrap()]).stdout).unwrap();
    let line: serde_json::Value = serde_json::from_str(plan.lines().nth(index).unwrap()).unwrap();
    line["id"].as_str().unwrap().to_string()
}

/// Holds the lock of job `id` in the sweep directory `out`, as another worker would.
fn hold(out: &Path, id: &str) -> File {
    std::fs::create_dir_all(out.join("jobs")).unwrap();
    let f = File::create(out.join("jobs").join(format!("{id}.lock"))).unwrap();
    f.try_lock().expect("the lock is free");
    f
}

/// `fuzzymotiv sweep F --out OUT --index 0`, started; returns once it says it waits for the lock.
// The child is returned to the caller, which waits for it.
#[allow(clippy::zombie_processes)]
fn start_waiting(f: &Path, out: &Path) -> (Child, BufReader<std::process::ChildStderr>) {
    let mut child = bin()
        .args(["sweep", f.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .args(["--index", "0", "--threads", "1"])
        .stderr(Stdio::piped())
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    let mut err = BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    loop {
        line.clear();
        assert!(
            err.read_line(&mut line).unwrap() > 0,
            "ended without waiting"
        );
        if line.contains("another worker is running it") {
            return (child, err);
        }
    }
}

fn rest(mut err: BufReader<std::process::ChildStderr>) -> String {
    let mut s = String::new();
    std::io::Read::read_to_string(&mut err, &mut s).unwrap();
    s
}

#[test]
fn a_waiting_task_runs_the_job_of_a_holder_that_died() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("sweep.toml");
    std::fs::write(&f, SWEEP).unwrap();
    let id = job_id(&f, 0);
    let out = dir.path().join("out");
    let lock = hold(&out, &id);
    let (mut child, err) = start_waiting(&f, &out);
    // While the lock is held, nothing of the job is written.
    assert!(!out.join("jobs").join(&id).exists());
    assert!(!out.join("jobs").join(format!("{id}.partial")).exists());
    drop(lock); // the holder dies
    let said = rest(err);
    assert!(child.wait().unwrap().success(), "{said}");
    assert!(said.contains("1 jobs run, 0 already done"), "{said}");
    // The same job as an undisturbed sweep.
    let reference = dir.path().join("reference");
    ok(&[
        "sweep",
        f.to_str().unwrap(),
        "--out",
        reference.to_str().unwrap(),
        "--index",
        "0",
    ]);
    let gens = |d: &Path| std::fs::read(d.join("jobs").join(&id).join("generations.csv")).unwrap();
    assert_eq!(gens(&out), gens(&reference));
}

#[test]
fn a_waiting_task_skips_the_job_its_holder_finished() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("sweep.toml");
    std::fs::write(&f, SWEEP).unwrap();
    let id = job_id(&f, 0);
    let reference = dir.path().join("reference");
    ok(&[
        "sweep",
        f.to_str().unwrap(),
        "--out",
        reference.to_str().unwrap(),
        "--index",
        "0",
    ]);
    let out = dir.path().join("out");
    let lock = hold(&out, &id);
    let (mut child, err) = start_waiting(&f, &out);
    // The holder finishes the job (moves its finished folder in), then lets go.
    std::fs::rename(reference.join("jobs").join(&id), out.join("jobs").join(&id)).unwrap();
    drop(lock);
    let said = rest(err);
    assert!(child.wait().unwrap().success(), "{said}");
    assert!(said.contains("0 jobs run, 1 already done"), "{said}");
}

#[test]
fn force_removes_the_lock_files_with_the_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("sweep.toml");
    std::fs::write(&f, SWEEP).unwrap();
    let out = dir.path().join("out");
    let (f_s, out_s) = (f.to_str().unwrap(), out.to_str().unwrap());
    ok(&["sweep", f_s, "--out", out_s]);
    let locks = |d: &Path| {
        std::fs::read_dir(d.join("jobs"))
            .map(|r| {
                r.flatten()
                    .filter(|e| e.path().extension().is_some_and(|x| x == "lock"))
                    .count()
            })
            .unwrap_or(0)
    };
    assert_eq!(locks(&out), 2);
    // Another plan with --force replaces the sweep: its jobs' locks go too.
    std::fs::write(&f, SWEEP.replace("seed = 4", "seed = 5")).unwrap();
    ok(&["sweep", f_s, "--out", out_s, "--force", "--index", "0"]);
    assert_eq!(locks(&out), 1);
}
