//! `fuzzymotiv compare`: runs over their test runs (`test_runs.csv`), studies over seeds and
//! sweep settings over replicates; the design it says it used; refusals (kinds, rooms, older
//! run directories, settings) with exit code 2; its files through the output guard.

use crate::common;
use common::*;

use std::path::{Path, PathBuf};

use fuzzymotiv_pipeline::records::compare::{CompareRow, read};

/// A small run of two rooms with four test runs per room.
fn small_run(dir: &Path, name: &str, seed: u64, rooms: &str, extra: &[&str]) -> PathBuf {
    let cfg = dir.join(format!("{name}.toml"));
    std::fs::write(
        &cfg,
        format!(
            "name = \"{name}\"\nseed = {seed}\nrooms = [{rooms}]\n[ga]\npopulation = 6\ngenerations = 2\n[trial]\nsteps = 80\n[aem]\nepochs = 20\ntest_runs = 4\n"
        ),
    )
    .unwrap();
    let out = dir.join(name);
    Fm::new(["run", cfg.to_str().unwrap(), "--quiet"])
        .out(&out)
        .sets(extra)
        .ok();
    out
}

fn compare(a: &Path, b: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["compare", a.to_str().unwrap(), b.to_str().unwrap()];
    args.extend(["--out", out.to_str().unwrap()]);
    args.extend_from_slice(extra);
    run(&args)
}

fn refused(o: &std::process::Output, says: &str) {
    assert_eq!(o.status.code(), Some(2), "{}", stderr(o));
    assert!(
        stderr(o).contains(says),
        "wanted {says:?} in: {}",
        stderr(o)
    );
}

/// Two runs: the test runs are recorded; compared unpaired (other seed) or paired (same
/// seed), per room and overall on the four test-run metrics; the same output again is left
/// alone, another is kept without --force; other rooms and an older run directory are refused.
#[test]
fn runs_are_compared_over_their_test_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let rooms = "\"H\", \"square\"";
    let a = small_run(dir, "a", 1, rooms, &[]);
    let b = small_run(dir, "b", 2, rooms, &[]);
    let c = small_run(
        dir,
        "c",
        1,
        rooms,
        &["motivations.curiosity=0.5", "motivations.homing=0.4"],
    );
    let runs = std::fs::read_to_string(a.join("test_runs.csv")).unwrap();
    assert!(
        runs.starts_with(
            "room,test,exploration_pct,recognition_pct,battery_pct,homing_pct,answer\n"
        ),
        "{runs}"
    );
    assert_eq!(runs.lines().count(), 1 + 2 * 4, "{runs}");

    let out = dir.join("ab");
    let o = compare(&a, &b, &out, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let md = std::fs::read_to_string(out.join("compare.md")).unwrap();
    assert_eq!(stdout(&o), md);
    assert!(md.contains("**unpaired**, 4 against 4 test runs"), "{md}");
    let rows: Vec<CompareRow> = read(&out.join("compare.csv")).unwrap();
    // Four metrics (a test run has no average fitness) × (two rooms + overall).
    assert_eq!(rows.len(), 4 * 3, "{rows:?}");
    assert!(
        rows.iter()
            .all(|r| r.design == "unpaired" && r.n_a == 4 && r.n_b == 4)
    );
    assert!(
        rows.iter()
            .all(|r| r.ci_low <= r.difference && r.difference <= r.ci_high)
    );
    assert!(
        rows.iter()
            .all(|r| (r.difference - (r.mean_a - r.mean_b)).abs() < 1e-9)
    );
    let svg = std::fs::read_to_string(out.join("compare.svg")).unwrap();
    assert!(
        svg.starts_with("<svg") && svg.matches("<circle").count() == 12 + 2,
        "{svg}"
    );
    // Its legend says what the colours mean.
    assert!(
        svg.contains("Holm-adjusted p &lt; 0.05: a difference"),
        "{svg}"
    );

    // The same comparison again: the same bytes, left alone; another α: kept without --force.
    assert!(compare(&a, &b, &out, &[]).status.success());
    assert_eq!(std::fs::read_to_string(out.join("compare.md")).unwrap(), md);
    refused(&compare(&a, &b, &out, &["--alpha", "0.1"]), "pass --force");
    assert!(
        compare(&a, &b, &out, &["--alpha", "0.1", "--force"])
            .status
            .success()
    );
    assert_ne!(std::fs::read_to_string(out.join("compare.md")).unwrap(), md);

    // The same seed: test run k uses the same streams in both runs, so paired.
    let o = compare(&a, &c, &dir.join("ac"), &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("**paired** over 4 test runs"),
        "{}",
        stdout(&o)
    );

    // Other rooms, --setting with runs, an older run directory, a bad α.
    let d = small_run(dir, "d", 1, "\"H\", \"T\"", &[]);
    refused(
        &compare(&a, &d, &dir.join("ad"), &[]),
        "has the rooms H, square, B",
    );
    refused(
        &compare(&a, &b, &dir.join("x"), &["--setting", "a"]),
        "leave --setting out",
    );
    std::fs::remove_file(d.join("test_runs.csv")).unwrap();
    refused(
        &compare(&d, &d, &dir.join("dd"), &[]),
        "no test_runs.csv: this run directory was written before",
    );
    refused(
        &compare(&a, &b, &dir.join("x"), &["--alpha", "0"]),
        "--alpha must be between 0 and 1",
    );
    refused(
        &compare(&a, &dir.join("none"), &dir.join("x"), &[]),
        "not a directory",
    );
    assert!(!dir.join("x").exists());
}

/// The same comparison into the same --out again: its files already hold these bytes, so they
/// are left alone and the command says so (as robustness, recognise and claims do).
#[test]
fn the_same_comparison_again_says_its_files_are_left_alone() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let rooms = "\"H\", \"square\"";
    let a = small_run(dir, "a", 1, rooms, &[]);
    let b = small_run(dir, "b", 2, rooms, &[]);
    let out = dir.join("ab");
    let first = compare(&a, &b, &out, &[]);
    assert!(first.status.success(), "{}", stderr(&first));
    assert!(
        !stderr(&first).contains("nothing to do"),
        "{}",
        stderr(&first)
    );
    let again = compare(&a, &b, &out, &[]);
    assert!(again.status.success(), "{}", stderr(&again));
    assert!(
        stderr(&again).contains(&format!(
            "{} already holds these files; nothing to do",
            out.display()
        )),
        "{}",
        stderr(&again)
    );
    assert_eq!(stdout(&again), stdout(&first));
}

/// A small study with the seeds 1 and 2.
fn small_study(dir: &Path, name: &str, seed: &str) -> PathBuf {
    let out = dir.join(name);
    let mut args = vec![
        "reproduce",
        "--quick",
        "--seeds",
        "2",
        "--seed",
        seed,
        "--quiet",
    ];
    args.extend(["--out", out.to_str().unwrap()]);
    for set in [
        "ga.population=6",
        "ga.generations=2",
        "trial.steps=80",
        "aem.epochs=20",
        "aem.test_runs=2",
    ] {
        args.extend(["--set", set]);
    }
    ok(&args);
    out
}

/// Two studies with the same seeds are compared paired, setting by setting; two settings of one
/// study with --setting twice; a study against a run or a sweep is refused, saying what each is.
#[test]
fn studies_are_compared_over_seeds() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let s = small_study(dir, "s", "1");
    let o = compare(&s, &s, &dir.join("ss"), &[]);
    refused(&o, "name the settings to compare with --setting");
    let out = dir.join("hl");
    let o = compare(
        &s,
        &s,
        &out,
        &["--setting", "high-curiosity", "--setting", "low-curiosity"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let md = stdout(&o);
    assert!(
        md.contains("`high-curiosity` (A) against `low-curiosity` (B): **paired** over 2 seeds"),
        "{md}"
    );
    let rows = read(&out.join("compare.csv")).unwrap();
    // Five metrics (recognition too) × (five rooms + overall), all paired over the 2 seeds.
    assert_eq!(rows.len(), 5 * 6, "{rows:?}");
    assert!(rows.iter().all(|r| r.design == "paired" && r.n_a == 2));
    // The overall exploration is the claim's: per seed the mean over rooms, paired.
    let claims = std::fs::read_to_string(s.join("claims.csv")).unwrap();
    let overall = rows
        .iter()
        .find(|r| r.room == "overall" && r.metric == "exploration_pct")
        .unwrap();
    let claim = claims
        .lines()
        .find(|l| l.contains("explores more"))
        .unwrap();
    let diff: f64 = claim.split(',').nth(3).unwrap().parse().unwrap();
    assert!(
        (overall.difference - diff).abs() < 1e-9,
        "{overall:?} vs {claim}"
    );
    refused(
        &compare(&s, &s, &dir.join("x"), &["--setting", "medium"]),
        "--setting medium: A",
    );

    let run = s.join("high-curiosity/seed-1");
    refused(
        &compare(&s, &run, &dir.join("x"), &[]),
        "is a study directory (reproduce), B",
    );
    let sweep = repo().join("crates/fuzzymotiv-cli/tests/fixtures/sweep-3edfbc7");
    refused(
        &compare(&sweep, &s, &dir.join("x"), &[]),
        "is a sweep directory, B",
    );
}

/// Two settings of a merged sweep, compared over their replicates (unpaired: the seeds of
/// different settings differ); a sweep without results.csv asks for merge.
#[test]
fn sweep_settings_are_compared_over_replicates() {
    let tmp = tempfile::tempdir().unwrap();
    let sweep = repo().join("crates/fuzzymotiv-cli/tests/fixtures/sweep-3edfbc7");
    let out = tmp.path().join("c");
    let (hc, lc) = ("C=0.8,H=0.1,O=0,E=0.1", "C=0.5,H=0.3,O=0,E=0.2");
    let o = compare(&sweep, &sweep, &out, &["--setting", hc, "--setting", lc]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("**unpaired**, 1 against 1 replicates"),
        "{}",
        stdout(&o)
    );
    let rows = read(&out.join("compare.csv")).unwrap();
    assert!(
        rows.iter()
            .all(|r| r.setting == format!("{hc} vs {lc}") && r.mdd.is_none())
    );
    // The same setting of the same sweep: paired, no difference.
    let o = compare(&sweep, &sweep, &tmp.path().join("same"), &["--setting", hc]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = read(&tmp.path().join("same/compare.csv")).unwrap();
    assert!(
        rows.iter()
            .all(|r| r.design == "paired" && r.difference == 0.0 && r.p == 1.0)
    );
    let unmerged = tmp.path().join("unmerged");
    std::fs::create_dir(&unmerged).unwrap();
    std::fs::copy(sweep.join("plan.jsonl"), unmerged.join("plan.jsonl")).unwrap();
    refused(
        &compare(&unmerged, &sweep, &tmp.path().join("x"), &[]),
        "merge it first",
    );
}
