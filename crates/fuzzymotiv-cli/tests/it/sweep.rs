//! Sweeps: the same results whole, in shards, with any thread count, and after kills.

use std::path::{Path, PathBuf};

use crate::common;

use common::{Fm, bin, ok, run, stderr};

const SWEEP: &str = r#"
name = "t"
seed = 9
rooms = ["H", "square"]
[ga]
population = 10
generations = 4
[trial]
steps = 120
[aem]
epochs = 20
test_runs = 2
[sweep]
replicates = 2
motivations = [[0.8, 0.1, 0.0, 0.1], [0.5, 0.3, 0.0, 0.2]]
[sweep.grid]
"trial.noise" = [0.06, 0.03]
"#;

fn sweep_file(dir: &Path) -> PathBuf {
    let p = dir.join("sweep.toml");
    std::fs::write(&p, SWEEP).unwrap();
    p
}

fn results(dir: &Path) -> String {
    ok(&["merge", dir.to_str().unwrap()]);
    std::fs::read_to_string(dir.join("results.csv")).unwrap()
}

#[test]
fn plan_is_stable_and_counts_jobs() {
    let dir = tempfile::tempdir().unwrap();
    let f = sweep_file(dir.path());
    let count = String::from_utf8(ok(&["plan", f.to_str().unwrap(), "--count"]).stdout).unwrap();
    assert_eq!(count.trim(), "8"); // 2 points × 2 noise levels × 2 replicates
    let a = ok(&["plan", f.to_str().unwrap()]).stdout;
    let b = ok(&["plan", f.to_str().unwrap()]).stdout;
    assert_eq!(a, b);
    let lines: Vec<serde_json::Value> = String::from_utf8(a)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let ids: std::collections::BTreeSet<_> = lines
        .iter()
        .map(|l| l["id"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(ids.len(), 8, "ids are unique");
    // Seeds come from the key: the same key gives the same seed in a different sweep file.
    let other = dir.path().join("other.toml");
    std::fs::write(&other, SWEEP.replace("[0.8, 0.1, 0.0, 0.1], ", "")).unwrap();
    let o = String::from_utf8(ok(&["plan", other.to_str().unwrap()]).stdout).unwrap();
    let first: serde_json::Value = serde_json::from_str(o.lines().next().unwrap()).unwrap();
    let same = lines.iter().find(|l| l["key"] == first["key"]).unwrap();
    assert_eq!(same["seed"], first["seed"]);
    assert_eq!(same["id"], first["id"]);
}

#[test]
fn whole_sharded_and_threaded_sweeps_agree() {
    let dir = tempfile::tempdir().unwrap();
    let f = sweep_file(dir.path());
    let f = f.to_str().unwrap();
    let whole = dir.path().join("whole");
    ok(&[
        "sweep",
        f,
        "--out",
        whole.to_str().unwrap(),
        "--threads",
        "2",
    ]);
    let sharded = dir.path().join("sharded");
    for i in 0..3 {
        ok(&[
            "sweep",
            f,
            "--out",
            sharded.to_str().unwrap(),
            "--shard",
            &format!("{i}/3"),
            "--threads",
            "1",
        ]);
    }
    let by_env = dir.path().join("env");
    for k in 0..8 {
        let o = bin()
            .args([
                "sweep",
                f,
                "--out",
                by_env.to_str().unwrap(),
                "--index-from-env",
                "SLURM_ARRAY_TASK_ID",
            ])
            .env("SLURM_ARRAY_TASK_ID", k.to_string())
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let r = results(&whole);
    assert_eq!(r.lines().count(), 1 + 8 * 2, "{r}");
    assert_eq!(r, results(&sharded));
    assert_eq!(r, results(&by_env));
    // A rerun skips finished jobs.
    let o = ok(&["sweep", f, "--out", whole.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("0 jobs run, 8 already done"));
    let agg = std::fs::read_to_string(whole.join("aggregate.csv")).unwrap();
    assert_eq!(agg.lines().count(), 1 + 4 * 2);
    assert!(whole.join("summary.svg").is_file());
}

#[test]
fn killed_sweep_finishes_with_identical_results() {
    let dir = tempfile::tempdir().unwrap();
    let text = SWEEP
        .replace("generations = 4", "generations = 25")
        .replace("population = 10", "population = 24");
    let f = dir.path().join("sweep.toml");
    std::fs::write(&f, text).unwrap();
    let f = f.to_str().unwrap();
    let reference = dir.path().join("reference");
    ok(&["sweep", f, "--out", reference.to_str().unwrap()]);
    // Deterministic kill points: the process aborts (as `kill -9` would) once this many
    // generations are checkpointed. One thread, so jobs go one after another (8 jobs × 25
    // generations): inside the first job, at the end of the second, inside later ones.
    let killed = dir.path().join("killed");
    let mut kills = 0;
    for n in [10u32, 40, 23, 60] {
        let o = bin()
            .args([
                "sweep",
                f,
                "--out",
                killed.to_str().unwrap(),
                "--threads",
                "1",
            ])
            .env("FUZZYMOTIV_TEST_ABORT_AFTER", n.to_string())
            .output()
            .unwrap();
        assert!(!o.status.success(), "not killed after {n} generations");
        kills += 1;
    }
    ok(&["sweep", f, "--out", killed.to_str().unwrap()]);
    assert_eq!(results(&reference), results(&killed), "after {kills} kills");
}

#[test]
fn bad_sweeps_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "[sweep]\nmotivations = [[0.5, 0.5, 0.5, 0.0]]\n",
            "motivations",
        ),
        ("[sweep]\nreplicates = 0\n", "sweep.replicates"),
        ("[sweep.simplex]\nstep = 0.3\n", "sweep.simplex.step"),
        (
            "[sweep.simplex]\nstep = 0.1\nfixed = { charisma = 0.1 }\n",
            "sweep.simplex.fixed.charisma",
        ),
        (
            "[sweep.grid]\n\"ga.population\" = []\n",
            "sweep.grid.ga.population",
        ),
        ("[sweep.grid]\n\"ga.population\" = [0]\n", "ga.population"),
        ("[sweep]\ncolour = 1\n", "sweep"),
        ("name = \"no sweep table\"\n", "sweep"),
    ];
    for (k, (text, field)) in cases.iter().enumerate() {
        let f = dir.path().join(format!("s{k}.toml"));
        std::fs::write(&f, text).unwrap();
        let out = dir.path().join(format!("o{k}"));
        let o = run(&["sweep", f.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "case {k}: {e}");
        assert!(
            e.contains(&format!("`{field}`")),
            "case {k}: should name `{field}`: {e}"
        );
        assert!(!out.exists(), "case {k}: wrote output");
    }
    let f = sweep_file(dir.path());
    let o = run(&[
        "sweep",
        f.to_str().unwrap(),
        "--out",
        dir.path().join("x").to_str().unwrap(),
        "--index",
        "99",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let o = run(&[
        "sweep",
        f.to_str().unwrap(),
        "--out",
        dir.path().join("y").to_str().unwrap(),
        "--shard",
        "3/3",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let o = bin()
        .args([
            "sweep",
            f.to_str().unwrap(),
            "--out",
            dir.path().join("z").to_str().unwrap(),
            "--index-from-env",
            "NO_SUCH_VAR_X",
        ])
        .env_remove("NO_SUCH_VAR_X")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn simplex_sweep_covers_the_grid() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("simplex.toml");
    std::fs::write(
        &f,
        "[sweep.simplex]\nstep = 0.25\nfixed = { orientation = 0.0 }\n",
    )
    .unwrap();
    let count = String::from_utf8(ok(&["plan", f.to_str().unwrap(), "--count"]).stdout).unwrap();
    // (C, H, E) in quarters summing to 1: C(4+2, 2) = 15 points.
    assert_eq!(count.trim(), "15");
    std::fs::write(&f, "[sweep.simplex]\nstep = 0.5\n").unwrap();
    let count = String::from_utf8(ok(&["plan", f.to_str().unwrap(), "--count"]).stdout).unwrap();
    // All four free in halves: C(2+3, 3) = 10 points.
    assert_eq!(count.trim(), "10");
}

#[test]
fn orientation_study_runs_from_one_command() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("orientation");
    let o = Fm::new(["reproduce", "--orientation", "--quick"])
        .out(&out)
        .sets(&[
            "ga.population=8",
            "ga.generations=2",
            "trial.steps=100",
            "aem.epochs=10",
            "aem.test_runs=2",
            "sweep.replicates=1",
        ])
        .run();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let agg = std::fs::read_to_string(out.join("aggregate.csv")).unwrap();
    assert_eq!(agg.lines().count(), 1 + 3 * 5, "{agg}");
    for setting in [
        "C=0.5,H=0.3,O=0,E=0.2",
        "C=0.4,H=0.2,O=0.3,E=0.1",
        "C=0.3,H=0.1,O=0.5,E=0.1",
    ] {
        assert!(agg.contains(setting), "{setting} missing");
    }
    // O > 0 jobs measured l online: some generation has a non-zero mean l.
    let plan = std::fs::read_to_string(out.join("plan.jsonl")).unwrap();
    let oriented: serde_json::Value = serde_json::from_str(plan.lines().nth(2).unwrap()).unwrap();
    let gens = std::fs::read_to_string(
        out.join("jobs")
            .join(oriented["id"].as_str().unwrap())
            .join("generations.csv"),
    )
    .unwrap();
    assert!(
        gens.lines()
            .skip(1)
            .any(|l| l.split(',').nth(8).unwrap().parse::<f64>().unwrap() > 0.0),
        "{gens}"
    );
    let o = run(&[
        "reproduce",
        "--orientation",
        "--out",
        dir.path().join("bad").to_str().unwrap(),
        "--set",
        "ga.population=0",
    ]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn editing_a_room_file_changes_the_job_id() {
    let dir = tempfile::tempdir().unwrap();
    let room = |w: u32| {
        format!(
            "name = \"box\"\noutline = [[0,0],[{w},0],[{w},400],[0,400]]\nhome = {{ x = 100, y = 100, heading_deg = 0 }}\n"
        )
    };
    std::fs::write(dir.path().join("box.toml"), room(400)).unwrap();
    let f = dir.path().join("s.toml");
    std::fs::write(
        &f,
        "rooms = [\"H\", \"box.toml\"]\n[sweep]\nreplicates = 1\n",
    )
    .unwrap();
    let id = |f: &Path| {
        let plan = String::from_utf8(ok(&["plan", f.to_str().unwrap()]).stdout).unwrap();
        let job: serde_json::Value = serde_json::from_str(plan.lines().next().unwrap()).unwrap();
        job["id"].as_str().unwrap().to_string()
    };
    let before = id(&f);
    assert_eq!(before, id(&f));
    std::fs::write(dir.path().join("box.toml"), room(500)).unwrap();
    assert_ne!(before, id(&f));
}

/// Regression: results.csv was written by hand without CSV escaping, so a room named
/// `a, "b"` or a swept string value (`robot.motion = "wheels"`, whose setting holds quotes)
/// broke its rows; and two columns were named `homing` (the motivation weight and the homing
/// result). Now every cell goes through the csv crate, every column name is unique, and each
/// swept key has its own `grid.KEY` column.
#[test]
fn results_csv_is_escaped_and_its_columns_are_unique() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("odd.toml"),
        "name = 'a, \"b\"'\noutline = [[0,0],[600,0],[600,500],[0,500]]\nhome = { x = 100, y = 100, heading_deg = 0 }\n",
    )
    .unwrap();
    let f = dir.path().join("s.toml");
    std::fs::write(
        &f,
        r#"seed = 3
rooms = ["H", "odd.toml"]
[ga]
population = 6
generations = 2
[trial]
steps = 60
[aem]
epochs = 5
test_runs = 1
[sweep]
motivations = [[0.8, 0.1, 0.0, 0.1]]
[sweep.grid]
"robot.motion" = ["actions", "wheels"]
"trial.noise" = [0.06]
"#,
    )
    .unwrap();
    let out = dir.path().join("out");
    ok(&["sweep", f.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let text = results(&out);
    let table = fuzzymotiv_pipeline::records::SweepResults::read(&out.join("results.csv")).unwrap();
    assert_eq!(table.grid, ["robot.motion", "trial.noise"]);
    assert_eq!(table.rows.len(), 2 * 2, "{text}");
    let header = text.lines().next().unwrap();
    let names: Vec<&str> = header.split(',').collect();
    let unique: std::collections::BTreeSet<&str> = names.iter().copied().collect();
    assert_eq!(unique.len(), names.len(), "duplicate column in {header}");
    for name in [
        "homing",
        "homing_pct",
        "grid.robot.motion",
        "grid.trial.noise",
    ] {
        assert!(names.contains(&name), "{name} missing in {header}");
    }
    let rooms: std::collections::BTreeSet<&str> =
        table.rows.iter().map(|r| r.room.as_str()).collect();
    assert_eq!(rooms, ["H", "a, \"b\""].into_iter().collect());
    let motions: Vec<&str> = table.rows.iter().map(|r| r.grid[0].as_str()).collect();
    assert_eq!(motions, ["actions", "actions", "wheels", "wheels"]);
    assert!(table.rows.iter().all(|r| r.grid[1] == "0.06"));
    assert!(table.rows[2].setting.contains("robot.motion=\"wheels\""));
    assert!(table.rows.iter().all(|r| r.values[0].is_some()));
    let agg = std::fs::read_to_string(out.join("aggregate.csv")).unwrap();
    assert!(agg.contains("\"a, \"\"b\"\"\""), "{agg}");
}

/// A swept sweep of one small job (two rooms) in `dir/out`.
fn one_job_sweep(dir: &Path) -> std::path::PathBuf {
    let f = dir.join("s.toml");
    std::fs::write(
        &f,
        "rooms = [\"H\", \"square\"]\n[ga]\npopulation = 6\ngenerations = 2\n[trial]\nsteps = 60\n[aem]\nepochs = 5\ntest_runs = 1\n[sweep]\n",
    )
    .unwrap();
    let out = dir.join("out");
    ok(&["sweep", f.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    out
}

/// A job's summary.json with a missing or malformed field stops `merge` with exit code 2 and
/// a message naming the file and the field (no NaN or "?" in the results).
#[test]
fn merge_names_the_bad_field_of_a_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = one_job_sweep(dir.path());
    let job = std::fs::read_dir(out.join("jobs"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let summary = job.join("summary.json");
    let good = std::fs::read_to_string(&summary).unwrap();
    for (bad, field) in [
        (
            good.replace("\"average_fitness\"", "\"avg_fitness\""),
            "missing field `average_fitness`",
        ),
        (
            good.replacen("\"curiosity\": 0.8", "\"curiosity\": \"high\"", 1),
            "`motivations.curiosity`",
        ),
    ] {
        assert_ne!(bad, good);
        std::fs::write(&summary, &bad).unwrap();
        let o = run(&["merge", out.to_str().unwrap()]);
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{e}");
        assert!(e.contains("summary.json") && e.contains(field), "{e}");
    }
}

/// `merge` never replaces merged tables with empty ones: an emptied plan and a sweep none of
/// whose jobs has finished are errors (exit 2), and `results.csv` stays as it was.
#[test]
fn merge_with_nothing_to_merge_keeps_the_tables() {
    let dir = tempfile::tempdir().unwrap();
    let out = one_job_sweep(dir.path());
    let merged = results(&out);
    let plan = std::fs::read_to_string(out.join("plan.jsonl")).unwrap();
    std::fs::write(out.join("plan.jsonl"), "\n").unwrap();
    let o = run(&["merge", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("holds no jobs"), "{}", stderr(&o));
    std::fs::write(out.join("plan.jsonl"), plan).unwrap();
    for done in std::fs::read_dir(out.join("jobs")).unwrap() {
        let _ = std::fs::remove_file(done.unwrap().path().join("DONE"));
    }
    let o = run(&["merge", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("has finished"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(out.join("results.csv")).unwrap(),
        merged
    );
}

/// A file written into a folder that does not exist: a file-system error (exit 1) naming the
/// folder, not the temporary file the write would have used.
#[test]
fn plan_into_a_missing_folder_names_the_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("nope/x/plan.jsonl");
    let sweep = common::repo().join("configs/sweep-small.toml");
    let o = run(&[
        "plan",
        sweep.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("nope/x does not exist") && !e.contains("x/.tmp"),
        "{e}"
    );
}

/// A sweep varies the robot like any key: a grid over `robot.file` runs the Khepera and the
/// e-puck2 side by side, each job's resolved config names its robot and evolves its network,
/// and the merged results have one row per robot.
#[test]
fn a_sweep_varies_the_robot() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("robots.toml");
    let text = "name = \"robots\"\nrooms = [\"H\", \"square\"]\n[ga]\npopulation = 8\ngenerations = 2\n[trial]\nsteps = 80\n[aem]\nenabled = false\n[sweep]\nreplicates = 1\n[sweep.grid]\n\"robot.file\" = [\"khepera\", \"epuck2\"]\n";
    std::fs::write(&f, text).unwrap();
    let out = dir.path().join("out");
    ok(&["sweep", f.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let mut robots = Vec::new();
    let jobs = std::fs::read_dir(out.join("jobs"))
        .unwrap()
        .map(|j| j.unwrap().path());
    for job in jobs.filter(|j| j.is_dir()) {
        let config = std::fs::read_to_string(job.join("config.resolved.toml"));
        let config = config.unwrap();
        robots.push(config.contains("file = \"epuck2\"\nradius = 37.0"));
    }
    robots.sort();
    assert_eq!(robots, [false, true], "one Khepera job, one e-puck2 job");
    let csv = results(&out);
    assert_eq!(
        csv.lines().filter(|l| l.contains("epuck2")).count(),
        csv.lines().count() / 2,
        "{csv}"
    );
}
