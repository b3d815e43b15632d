//! Names and numbers: one name per quantity across `summary.json`, tables, CSV and Python (the
//! homing result is `homing_pct`, the motivation weight `homing`), and old summaries still read;
//! a standard deviation over one value is a dash in Markdown and an empty cell in CSV; the tables
//! say their std is the sample std (n − 1). The tests of `scripts/seeds_table.py` need python3
//! and are ignored by default (`.ci/run` runs them).
//!
//! `tests/fixtures/sweep-3edfbc7/` is a sweep directory written by the binary of commit 3edfbc7,
//! before the rename: its jobs' `summary.json` call the result `homing`, and its `results.csv`
//! is what that commit's `merge` wrote.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use fuzzymotiv_pipeline::records::{AggregateRow, SweepResults, read_csv};
use serde_json::Value;

use crate::common;

use common::{Fm, SMALL, ok, repo, run, stderr, stdout};

/// The sweep directory written by 3edfbc7 (two settings, one replicate each, rooms H and square).
fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/sweep-3edfbc7")
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// A copy of the fixture in `dir`.
fn old_sweep(dir: &Path, name: &str) -> PathBuf {
    let to = dir.join(name);
    copy_dir(&fixture(), &to);
    to
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `merge DIR`, then its `results.csv`.
fn merged(dir: &Path) -> String {
    ok(&["merge", dir.to_str().unwrap()]);
    read(&dir.join("results.csv"))
}

/// The sweep file of the fixture with `replicates` replicates.
fn sweep_file(dir: &Path, replicates: usize) -> PathBuf {
    let text = read(&fixture().join("sweep.toml"));
    assert!(text.contains("replicates = 1"));
    let f = dir.join(format!("sweep-{replicates}.toml"));
    std::fs::write(
        &f,
        text.replace("replicates = 1", &format!("replicates = {replicates}")),
    )
    .unwrap();
    f
}

/// Every path in `v` whose key is `homing` outside a `motivations` object (the weight's place).
fn homing_outside_motivations(v: &Value, path: &str, found: &mut Vec<String>) {
    match v {
        Value::Object(map) => {
            for (k, child) in map {
                let p = format!("{path}.{k}");
                if k == "homing" && !path.ends_with(".motivations") {
                    found.push(p.clone());
                }
                homing_outside_motivations(child, &p, found);
            }
        }
        Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                homing_outside_motivations(child, &format!("{path}[{i}]"), found);
            }
        }
        _ => {}
    }
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&read(path)).unwrap()
}

/// `summary.json` at `path` uses `homing_pct` for the result, `homing` only for the weight.
fn assert_one_homing_name(path: &Path) {
    let v = json(path);
    let mut found = Vec::new();
    homing_outside_motivations(&v, "", &mut found);
    assert!(
        found.is_empty(),
        "{}: `homing` at {found:?}",
        path.display()
    );
    assert!(
        read(path).contains("\"homing_pct\""),
        "{}: no homing_pct",
        path.display()
    );
}

/// A quick study with one seed per setting, run once for the tests that need it.
fn one_seed_study() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("names-one-seed-study");
        let _ = std::fs::remove_dir_all(&dir);
        let _ = std::fs::remove_dir_all(dir.with_extension("partial"));
        Fm::new(["reproduce", "--quick", "--seeds", "1"])
            .sets(&SMALL)
            .out(&dir)
            .ok();
        dir
    })
}

/// `scripts/seeds_table.py DIRS…`: (exit success, stdout, stderr).
fn seeds_table(dirs: &[&Path]) -> (bool, String, String) {
    let o = std::process::Command::new("python3")
        .arg(repo().join("scripts/seeds_table.py"))
        .args(dirs)
        .output()
        .unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// The Markdown table rows (not header, not the separator) of `md`.
fn table_rows(md: &str) -> Vec<&str> {
    md.lines()
        .filter(|l| {
            l.starts_with("| ") && !l.starts_with("| room |") && !l.starts_with("| setting |")
        })
        .collect()
}

/// The homing result was `homing` in summary.json, beside the motivation weight `homing`;
/// tables, results.csv and Python said `homing_pct`. Now every summary.json (run, sweep job,
/// study) says `homing_pct`, and summaries written before still merge: a whole old sweep, and
/// an old sweep finished by today's binary, give the very `results.csv` the old binary wrote.
#[test]
fn homing_pct_is_one_name_and_old_summaries_still_merge() {
    let dir = tempfile::tempdir().unwrap();
    let expected = read(&fixture().join("results.csv"));
    assert!(expected.lines().next().unwrap().ends_with(",homing_pct"));
    // The fixture is the old format: the result is `homing` in every room.
    for job in std::fs::read_dir(fixture().join("jobs")).unwrap() {
        let text = read(&job.unwrap().path().join("summary.json"));
        assert_eq!(text.matches("\"homing\":").count(), 1 + 2, "{text}");
        assert!(!text.contains("homing_pct"));
    }

    // The whole old sweep merges to the old results.csv.
    let old = old_sweep(dir.path(), "old");
    assert_eq!(merged(&old), expected);

    // Half finished by an earlier model (the fixture was planned by model 1): today's binary
    // does not finish it (that would mix two models in one sweep), and keeps it.
    let half = old_sweep(dir.path(), "half");
    let plan = stdout(&ok(&["plan", half.join("sweep.toml").to_str().unwrap()]));
    let last: Value = serde_json::from_str(plan.lines().last().unwrap()).unwrap();
    let last = half.join("jobs").join(last["id"].as_str().unwrap());
    std::fs::remove_dir_all(&last).unwrap();
    let o = run(&[
        "sweep",
        half.join("sweep.toml").to_str().unwrap(),
        "--out",
        half.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("planned by model 1 of fuzzymotiv, and this build is model 2"),
        "{}",
        stderr(&o)
    );
    assert!(
        !last.exists() && half.join("plan.jsonl").is_file(),
        "kept as it was"
    );

    // A new sweep of the same file: the same results, every job in the new format.
    let new = dir.path().join("new");
    ok(&[
        "sweep",
        fixture().join("sweep.toml").to_str().unwrap(),
        "--out",
        new.to_str().unwrap(),
        "--quiet",
    ]);
    // Job folders (beside them, the jobs' lock files).
    for job in std::fs::read_dir(new.join("jobs")).unwrap() {
        let job = job.unwrap().path();
        if job.is_dir() {
            assert_one_homing_name(&job.join("summary.json"));
        }
    }
    assert_eq!(merged(&new), expected);
    let table = SweepResults::read(&new.join("results.csv")).unwrap();
    let homing_weights: Vec<f64> = table.rows.iter().map(|r| r.motivations.homing).collect();
    assert_eq!(homing_weights, [0.1, 0.1, 0.3, 0.3]);

    // A study: its summary.json and every run directory's.
    let study = one_seed_study();
    assert_one_homing_name(&study.join("summary.json"));
    let s = json(&study.join("summary.json"));
    for setting in s["settings"].as_array().unwrap() {
        let run = study.join(setting["per_seed"][0]["run_dir"].as_str().unwrap());
        assert_one_homing_name(&run.join("summary.json"));
        assert!(setting["rows"][0]["homing_pct"].as_f64().is_some());
        assert!(
            setting["per_seed"][0]["rows"][0]["homing_pct"]
                .as_f64()
                .is_some()
        );
    }
}

/// seeds_table.py reads a study summary.json of either name (`homing`, `homing_pct`) alike.
#[test]
#[ignore = "needs python3: run by .ci/run"]
fn seeds_table_reads_old_and_new_homing_names_alike() {
    let dir = tempfile::tempdir().unwrap();
    let study = one_seed_study();
    let renamed = dir.path().join("old-study");
    std::fs::create_dir_all(&renamed).unwrap();
    std::fs::write(
        renamed.join("summary.json"),
        read(&study.join("summary.json")).replace("\"homing_pct\"", "\"homing\""),
    )
    .unwrap();
    let (ok_new, new_table, e) = seeds_table(&[study, study]);
    assert!(ok_new, "{e}");
    let (ok_old, old_table, e) = seeds_table(&[&renamed, &renamed]);
    assert!(ok_old, "{e}");
    assert_eq!(old_table, new_table);
}

/// A std over one value (one replicate, one seed) printed "± 0.00": now a dash in Markdown, an
/// empty cell in CSV, `null` in a study's summary.json.
#[test]
fn std_of_one_value_is_a_dash_not_zero() {
    let dir = tempfile::tempdir().unwrap();
    // merge: aggregate.md and aggregate.csv of one replicate per setting.
    let sweep = old_sweep(dir.path(), "sweep");
    let printed = stdout(&ok(&["merge", sweep.to_str().unwrap()]));
    let md = read(&sweep.join("aggregate.md"));
    assert_eq!(printed, md);
    let rows = table_rows(&md);
    assert_eq!(rows.len(), 4, "{md}");
    for row in rows {
        assert!(row.contains("| 1 |"), "{row}");
        assert_eq!(row.matches(" ± — |").count(), 5, "{row}");
        assert!(!row.contains("± 0.00"), "{row}");
    }
    let agg = read_csv::<AggregateRow>(&sweep.join("aggregate.csv")).unwrap();
    assert_eq!(agg.len(), 4);
    for r in &agg {
        assert!(r.average_fitness_mean.is_some() && r.homing_pct_mean.is_some());
        assert_eq!(
            [
                r.average_fitness_std,
                r.exploration_pct_std,
                r.recognition_pct_std,
                r.battery_pct_std,
                r.homing_pct_std
            ],
            [None; 5]
        );
    }
    let csv = read(&sweep.join("aggregate.csv"));
    assert!(
        csv.lines().nth(1).unwrap().ends_with(','),
        "the last std is an empty cell: {csv}"
    );

    // reproduce --seeds 1: the study tables, summary.json and report.
    let study = one_seed_study();
    for t in ["table1", "table2"] {
        let md = read(&study.join(format!("{t}.md")));
        let mean_rows: Vec<&str> = table_rows(&md)
            .into_iter()
            .filter(|l| l.contains('±'))
            .collect();
        assert_eq!(mean_rows.len(), 5, "{md}");
        for row in mean_rows {
            assert!(
                row.matches(" ± —").count() == 5 && !row.contains("± 0.0"),
                "{row}"
            );
        }
        let csv = read(&study.join(format!("{t}.csv")));
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        for line in lines {
            let cells: Vec<&str> = line.split(',').collect();
            for (h, c) in header.iter().zip(&cells) {
                if h.ends_with("_std") {
                    assert_eq!(*c, "", "{t}.csv: {h} in {line}");
                } else if *h == "average_fitness" {
                    assert!(c.parse::<f64>().is_ok(), "{t}.csv: {line}");
                }
            }
        }
    }
    let s = json(&study.join("summary.json"));
    for setting in s["settings"].as_array().unwrap() {
        for row in setting["std"].as_array().unwrap() {
            assert!(row["average_fitness"].is_null(), "{row}");
            assert!(row["homing_pct"].is_null(), "{row}");
        }
        assert!(setting["rows"][0]["average_fitness"].as_f64().is_some());
    }
    let report = read(&study.join("report.html"));
    assert!(report.contains(" ± — <span"), "the report's spread table");
    assert!(!report.contains(" ± 0.0 <span") && !report.contains(" ± 0.000 <span"));
}

/// seeds_table.py over one study with one seed per setting: a dash, not "± 0.0".
#[test]
#[ignore = "needs python3: run by .ci/run"]
fn seeds_table_shows_a_dash_for_one_seed() {
    let study = one_seed_study();
    let (success, out, e) = seeds_table(&[study]);
    assert!(success, "{e}");
    assert!(out.contains(" ± — |") && !out.contains("± 0.0"), "{out}");
}

/// What every table that shows a std says of it.
const SAYS: &str = "sample standard deviation, n − 1";

/// The tables said "± std" without saying which: it is the sample standard deviation (divided by
/// n − 1), and every table that shows one now says so.
#[test]
fn tables_say_their_std_is_the_sample_std() {
    // The statistic itself: divided by n − 1, not n.
    let (mean, std) = fuzzymotiv::statistics::mean_std(&[1.0, 2.0, 3.0, 4.0]);
    assert_eq!(mean, 2.5);
    assert!((std - (5.0f64 / 3.0).sqrt()).abs() < 1e-15, "{std}");

    // merge, with two replicates: aggregate.csv holds the sample std of results.csv's values.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("two");
    ok(&[
        "sweep",
        sweep_file(dir.path(), 2).to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    ok(&["merge", out.to_str().unwrap()]);
    let md = read(&out.join("aggregate.md"));
    assert!(md.contains(SAYS), "{md}");
    let results = SweepResults::read(&out.join("results.csv")).unwrap();
    let agg = read_csv::<AggregateRow>(&out.join("aggregate.csv")).unwrap();
    assert_eq!(agg.len(), 4);
    for a in &agg {
        assert_eq!(a.n, 2);
        let v: Vec<f64> = results
            .rows
            .iter()
            .filter(|r| r.setting == a.setting && r.room == a.room)
            .map(|r| r.values[4].unwrap())
            .collect();
        let sample = (v[0] - v[1]).abs() / 2f64.sqrt();
        let got = a.homing_pct_std.unwrap().0;
        assert!((got - sample).abs() < 1e-6, "{got} vs {sample} for {v:?}");
    }
    let csv = read(&out.join("aggregate.csv"));
    assert!(csv.starts_with("setting,room,n,average_fitness_mean,average_fitness_std,"));

    // The study's tables and its report.
    let study = one_seed_study();
    for t in ["table1.md", "table2.md", "report.html"] {
        assert!(read(&study.join(t)).contains(SAYS), "{t}");
    }
}

/// seeds_table.py's table says its std is the sample standard deviation too.
#[test]
#[ignore = "needs python3: run by .ci/run"]
fn seeds_table_says_its_std_is_the_sample_std() {
    let study = one_seed_study();
    let (success, out, e) = seeds_table(&[study, study]);
    assert!(success, "{e}");
    assert!(out.contains(SAYS), "{out}");
}
