//! `fuzzymotiv study`: a study of one's own (the shipped fetch-urgency study at a tiny size)
//! runs from the command line, writes typed records whose every verdict is recomputed here
//! from its own per-seed values, gives the same bytes in shards as whole, and bad study files
//! are refused (status 2, the file and field named, nothing written).

use std::path::{Path, PathBuf};

use crate::common;

use common::recompute::{Rows, f, read_csv, recompute_every_verdict};
use common::{ok, repo, run, stderr, stdout};
use fuzzymotiv::statistics;

/// The analysis' files, the same bytes whoever wrote them.
const ANALYSIS: [&str; 6] = [
    "per_seed.csv",
    "claims.csv",
    "rooms.csv",
    "study.json",
    "report.md",
    "forest.svg",
];

/// The shipped studies/fetch-urgency.toml, made tiny (a small GA, short trials, no AEM), its
/// config named by an absolute path, with `base_seeds` and `extra` hypotheses.
fn tiny_study(dir: &Path, base_seeds: &str, extra: &str) -> PathBuf {
    let text = std::fs::read_to_string(repo().join("studies/fetch-urgency.toml")).unwrap();
    let config = repo().join("configs/fetch.toml");
    let text = text
        .replace("seeds = 10\n", "seeds = 4\n")
        .replace("base_seeds = [1, 11]", &format!("base_seeds = {base_seeds}"))
        .replace(
            "config = \"../configs/fetch.toml\"",
            &format!(
                "config = {:?}\nset = {{ ga = {{ population = 8, generations = 3 }}, trial = {{ steps = 150 }}, aem = {{ enabled = false }} }}",
                config.display().to_string()
            ),
        );
    assert!(text.contains("population = 8") && text.contains("seeds = 4\n"));
    let path = dir.join("study.toml");
    std::fs::write(&path, format!("{text}{extra}")).unwrap();
    path
}

/// Four more hypotheses, of the kinds and measures the shipped file lacks: a range, a trend of
/// a term, a difference of differences of the time to the goal and a comparison of the end
/// spread (both read back from the runs).
const MORE: &str = r#"
[[hypothesis]]
id = "explores"
kind = "range"
measure = "exploration_pct"
arm = "urgency-0.3"
min = 5
max = 95

[[hypothesis]]
id = "safety-trend"
kind = "trend"
measure = "safety"
arms = ["urgency-0.1", "urgency-0.3", "urgency-0.5"]
expect = "decreasing"

[[hypothesis]]
id = "sooner-and-sooner"
kind = "difference"
measure = "time_to_goal"
a = "urgency-0.5"
b = "urgency-0.3"
versus_a = "urgency-0.3"
versus_b = "urgency-0.1"
expect = "lower"

[[hypothesis]]
id = "ends-closer"
kind = "compare"
measure = "end_spread"
a = "urgency-0.5"
b = "urgency-0.1"
expect = "lower"
"#;

fn study(file: &Path, out: &Path, more: &[&str]) -> std::process::Output {
    let mut args = vec![
        "study",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--threads",
        "2",
        "-q",
    ];
    args.extend(more);
    ok(&args)
}

#[test]
fn a_fetch_study_writes_typed_records_whose_every_verdict_is_recomputed_from_its_per_seed_csv() {
    let dir = tempfile::tempdir().unwrap();
    let file = tiny_study(dir.path(), "[1, 2]", MORE);
    let out = dir.path().join("out");
    let o = study(&file, &out, &[]);
    for name in ANALYSIS {
        assert!(out.join(name).is_file(), "{name} written");
    }
    // Eight hypotheses, judged pooled and at each of the two base seeds; and on each base
    // seed's first 2, 3 and 4 seeds (agreement.csv).
    assert_eq!(recompute_every_verdict(&out), 24 + 3 * 2 * 8);
    let printed = stdout(&o);
    assert!(
        printed.contains("sooner: ")
            && printed.contains("% urgency is higher in urgency-0.5 than in urgency-0.1"),
        "{printed}"
    );
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    for part in [
        "## Analysis",
        "## Claims",
        "forest.svg",
        "## Each base seed's verdict",
        "## Agreement by seed count",
        "## Per room",
        "## Seeds",
        "name = \"fetch-urgency\"",
        "4 paired seeds per base seed (base seeds 1, 2):",
    ] {
        assert!(report.contains(part), "report.md lacks {part}");
    }
    let forest = std::fs::read_to_string(out.join("forest.svg")).unwrap();
    assert_eq!(forest.matches("<circle").count(), 24, "a dot per result");
    // The rooms' table: the five fetch rooms per hypothesis over a measure (all but `learns`)
    // and scope.
    assert_eq!(read_csv(&out.join("rooms.csv")).len(), 5 * 7 * 3);
    // The time to the goal is a mean step of test runs, T (150 here) for one that never
    // arrived; the end spread a share of a room's largest distance.
    let per_seed = read_csv(&out.join("per_seed.csv"));
    let of = |m: &str| -> Vec<f64> {
        (per_seed.iter())
            .filter(|r| r["measure"] == m)
            .map(|r| f(r, "value"))
            .collect()
    };
    assert!(of("time_to_goal").iter().all(|t| (1.0..=150.0).contains(t)));
    assert!(
        of("end_spread_pct")
            .iter()
            .all(|v| (0.0..=100.0).contains(v))
    );
    assert_eq!(
        of("end_spread_pct").len(),
        3 * 2 * 4 * 6,
        "3 arms, 2 × 4 seeds, 5 rooms + all"
    );
}

#[test]
fn a_study_in_shards_gives_the_bytes_of_one_machine_and_resumes_without_running_again() {
    let dir = tempfile::tempdir().unwrap();
    let file = tiny_study(dir.path(), "[1]", "");
    let whole = dir.path().join("whole");
    study(&file, &whole, &[]);
    let sharded = dir.path().join("sharded");
    let first = study(&file, &sharded, &["--shard", "0/2"]);
    assert!(
        stdout(&first).is_empty(),
        "no claims before every run is there"
    );
    assert!(!sharded.join("claims.csv").exists());
    study(&file, &sharded, &["--shard", "1/2"]);
    for name in ANALYSIS {
        let (a, b) = (whole.join(name), sharded.join(name));
        assert_eq!(
            std::fs::read(&a).unwrap(),
            std::fs::read(&b).unwrap(),
            "{name}"
        );
    }
    // Again, whole: every run is finished, nothing runs; the same analysis.
    let before = std::fs::read(whole.join("claims.csv")).unwrap();
    let again = run(&[
        "study",
        file.to_str().unwrap(),
        "--out",
        whole.to_str().unwrap(),
    ]);
    assert!(again.status.success(), "{}", stderr(&again));
    assert!(
        stderr(&again).contains("0 jobs run, 12 already done"),
        "{}",
        stderr(&again)
    );
    assert_eq!(std::fs::read(whole.join("claims.csv")).unwrap(), before);
}

/// A study file with `line` replaced by `by` (or `by` appended when `line` is empty).
fn edited(dir: &Path, name: &str, line: &str, by: &str) -> PathBuf {
    let path = tiny_study(dir, "[1]", "");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = if line.is_empty() {
        format!("{text}{by}")
    } else {
        assert!(text.contains(line), "{line}");
        text.replacen(line, by, 1)
    };
    let bad = dir.join(name);
    std::fs::write(&bad, text).unwrap();
    bad
}

#[test]
fn bad_study_files_exit_2_naming_the_file_and_field_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let difference = |a: &str, b: &str, c: &str, d: &str, measure: &str| {
        format!(
            "\n[[hypothesis]]\nid = \"diff\"\nkind = \"difference\"\nmeasure = \"{measure}\"\na = \"{a}\"\nb = \"{b}\"\nversus_a = \"{c}\"\nversus_b = \"{d}\"\nexpect = \"lower\"\n"
        )
    };
    let (u1, u3, u5) = ("urgency-0.1", "urgency-0.3", "urgency-0.5");
    let more = [
        (
            difference(u5, u3, "urgency-0.9", u1, "urgency"),
            vec!["hypothesis[4].versus_a", "unknown arm `urgency-0.9`"],
        ),
        (
            difference(u5, u3, u1, u1, "urgency"),
            vec!["hypothesis[4].versus_b", "from itself"],
        ),
        (
            difference(u5, u3, u3, u5, "urgency"),
            vec!["hypothesis[4].versus_a", "compares two different pairs"],
        ),
        (
            difference(u5, u3, u3, u1, "hurry"),
            vec![
                "hypothesis[4].measure",
                "unknown measure `hurry`",
                "time_to_goal",
            ],
        ),
    ];
    let cases: [(&str, &str, &[&str]); 11] = [
        (
            "measure = \"urgency\"          #",
            "measure = \"hurry\" #",
            &[
                "hypothesis[0].measure",
                "unknown measure `hurry`:",
                "urgency_pct",
                "exploration_pct",
            ],
        ),
        (
            "b = \"urgency-0.1\"",
            "b = \"urgency-0.9\"",
            &["hypothesis[0].b", "unknown arm `urgency-0.9`"],
        ),
        (
            "b = \"urgency-0.1\"",
            "b = \"urgency-0.5\"",
            &["hypothesis[0].b", "with itself"],
        ),
        ("seeds = 4\n", "seeds = 0\n", &["study.seeds", "got 0"]),
        (
            "name = \"urgency-0.3\"\nlevel = 0.3\n",
            "name = \"urgency-0.3\"\n",
            &["hypothesis[1].arms", "has no `level`", "ordered"],
        ),
        (
            "rule = \"power\"",
            "rule = \"power\"\nbeta = 0.2",
            &["beta", "unknown field"],
        ),
        (
            "kind = \"rising\"",
            "kind = \"rising\"\nmeasure = \"goal\"",
            &["measure", "unknown field"],
        ),
        (
            "alpha = 0.05",
            "alpha = 1.5",
            &["analysis.alpha", "between 0 and 1"],
        ),
        (
            "",
            "\n[[hypothesis]]\nid = \"sooner\"\nkind = \"rising\"\narm = \"urgency-0.1\"\n",
            &["hypothesis[4].id", "used twice"],
        ),
        // A measure in Enki of arms that do not transfer.
        (
            "measure = \"urgency\"          #",
            "measure = \"enki_homing\" #",
            &["hypothesis[0].measure", "unknown measure `enki_homing_pct`"],
        ),
        // The low arm made the middle one (fetch.toml's curiosity): two arms of one config.
        (
            "\"motivations.curiosity\" = 0.7, \"motivations.urgency\" = 0.1",
            "\"motivations.curiosity\" = 0.5",
            &[
                "urgency-0.1;base=1;rep=0",
                "urgency-0.3;base=1;rep=0",
                "the same config",
            ],
        ),
    ];
    let more: Vec<(&str, &str, &[&str])> = (more.iter())
        .map(|(by, says)| ("", by.as_str(), says.as_slice()))
        .collect();
    let all: Vec<(&str, &str, &[&str])> = cases.iter().copied().chain(more).collect();
    assert_refused(dir.path(), &all);
}

/// A transfer to another world than Enki, of no runs, to a room the runs lack, or of a robot
/// Enki has no model of exits 2 naming the transfer's field, before anything runs.
#[test]
fn bad_transfer_tables_exit_2_naming_the_field_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // A robot of its own: the Khepera's file under another name, which Enki has no model of.
    let robot = std::fs::read_to_string(repo().join("robots/khepera.toml")).unwrap();
    let own = dir.path().join("own-robot.toml");
    std::fs::write(
        &own,
        robot.replacen("name = \"khepera\"", "name = \"own\"", 1),
    )
    .unwrap();
    let own_arm = format!(
        "name = \"urgency-0.3\"\nlevel = 0.3\nset = {{ robot = {:?} }}\ntransfer = {{ world = \"enki\", runs = 1 }}\n",
        own.display().to_string()
    );
    let cases: [(&str, &str, &[&str]); 4] = [
        (
            "seeds = 4\n",
            "seeds = 4\ntransfer = { world = \"gazebo\", runs = 2 }\n",
            &["study.transfer.world", "unknown world `gazebo`", "enki"],
        ),
        (
            "seeds = 4\n",
            "seeds = 4\ntransfer = { world = \"enki\", runs = 0 }\n",
            &["study.transfer.runs", "got 0"],
        ),
        (
            "seeds = 4\n",
            "seeds = 4\ntransfer = { world = \"enki\", runs = 2, rooms = [\"fetch-H\", \"kitchen\"] }\n",
            &[
                "study.transfer.rooms[1]",
                "`kitchen` is not a room",
                "urgency-0.1",
            ],
        ),
        (
            "name = \"urgency-0.3\"\nlevel = 0.3\n",
            &own_arm,
            &["arm[1].transfer", "the robot `own`", "no model"],
        ),
    ];
    assert_refused(dir.path(), &cases);
}

/// Each case (a line of the tiny study replaced) run: exit 2, the file named, the case's
/// words said, nothing written.
fn assert_refused(dir: &Path, cases: &[(&str, &str, &[&str])]) {
    for (k, (line, by, says)) in cases.iter().enumerate() {
        let file = edited(dir, &format!("bad{k}.toml"), line, by);
        let out = dir.join(format!("out{k}"));
        let o = run(&[
            "study",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let message = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "case {k}: {message}");
        assert!(
            message.contains(&format!("bad{k}.toml")),
            "case {k} names the file: {message}"
        );
        for s in *says {
            assert!(message.contains(s), "case {k} says {s:?}: {message}");
        }
        assert!(!message.contains("panicked"), "{message}");
        assert!(!out.exists(), "case {k}: nothing written");
    }
}

/// A study without hypotheses (a sweep of arms) names the measures it reports of each arm; with
/// neither, or a measure its runs do not write, or one twice, it exits 2 naming the file and
/// the field, nothing written.
#[test]
fn a_study_without_hypotheses_must_name_known_measures_to_report() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(tiny_study(dir.path(), "[1]", "")).unwrap();
    let arms_only = &text[..text.find("[[hypothesis]]").unwrap()];
    let cases: [(&str, &[&str]); 3] = [
        ("", &["`hypothesis`", "study.measures"]),
        (
            "measures = [\"exploration\", \"hurry\"]\n",
            &[
                "study.measures[1]",
                "unknown measure `hurry`",
                "time_to_goal",
            ],
        ),
        (
            "measures = [\"goal\", \"goal_pct\"]\n",
            &["study.measures[1]", "`goal_pct` is listed twice"],
        ),
    ];
    for (k, (measures, says)) in cases.iter().enumerate() {
        let file = dir.path().join(format!("arms{k}.toml"));
        let with = arms_only.replacen("seeds = 4\n", &format!("seeds = 4\n{measures}"), 1);
        std::fs::write(&file, with).unwrap();
        let out = dir.path().join(format!("out{k}"));
        let o = run(&[
            "study",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let message = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "case {k}: {message}");
        assert!(message.contains(&format!("arms{k}.toml")), "{message}");
        for s in *says {
            assert!(message.contains(s), "case {k} says {s:?}: {message}");
        }
        assert!(!out.exists(), "case {k}: nothing written");
    }
}

#[test]
fn a_study_directory_is_kept_from_another_study_unless_force_and_a_run_may_replace_it() {
    let dir = tempfile::tempdir().unwrap();
    let file = tiny_study(dir.path(), "[1]", "");
    let out = dir.path().join("out");
    study(&file, &out, &["--shard", "0/4"]);
    // Other base seeds: another plan.
    let other = dir.path().join("other.toml");
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::write(&other, text.replace("base_seeds = [1]", "base_seeds = [5]")).unwrap();
    let refused = run(&[
        "study",
        other.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(refused.status.code(), Some(2), "{}", stderr(&refused));
    study(&other, &out, &["--shard", "0/4", "--force"]);
    let plan = std::fs::read_to_string(out.join("plan.jsonl")).unwrap();
    assert!(
        plan.contains("base=5") && !plan.contains("base=1;"),
        "{plan}"
    );
    // A finished study's analysis files are ours: `run --force` may replace the directory.
    study(&other, &out, &[]);
    let config = repo().join("configs/tiny.toml");
    let replaced = run(&[
        "run",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--force",
        "--set",
        "ga.generations=1",
        "-q",
    ]);
    assert!(replaced.status.success(), "{}", stderr(&replaced));
    assert!(!out.join("claims.csv").exists() && out.join("summary.json").is_file());
}

#[test]
fn a_killed_study_resumes_its_runs_and_writes_the_analysis_of_an_uninterrupted_one() {
    let dir = tempfile::tempdir().unwrap();
    let file = tiny_study(dir.path(), "[1]", "");
    let whole = dir.path().join("whole");
    study(&file, &whole, &[]);
    let killed = dir.path().join("killed");
    // Killed (as kill -9) after 2 checkpointed generations of a run: in the first run, then
    // (its checkpoint resumed) further on.
    for _ in 0..3 {
        let o = common::bin()
            .args(["study", file.to_str().unwrap(), "--out"])
            .arg(&killed)
            .args(["--threads", "1", "-q"])
            .env("FUZZYMOTIV_TEST_ABORT_AFTER", "2")
            .output()
            .unwrap();
        assert!(!o.status.success(), "not killed: {}", stderr(&o));
        assert!(!killed.join("claims.csv").exists());
    }
    study(&file, &killed, &[]);
    for name in ANALYSIS {
        let (a, b) = (whole.join(name), killed.join(name));
        assert_eq!(
            std::fs::read(&a).unwrap(),
            std::fs::read(&b).unwrap(),
            "{name}"
        );
    }
}

/// The shipped studies/paper.toml made tiny (three seeds of `base_seeds`, a small GA, short
/// trials), its configs named by absolute paths; and the same size as `reproduce`'s `--set`s.
fn tiny_paper_study(dir: &Path, base_seeds: &str) -> (PathBuf, [&'static str; 3]) {
    let text = std::fs::read_to_string(repo().join("studies/paper.toml")).unwrap();
    let configs = repo().join("configs");
    let text = text
        .replace(
            "seeds = 20\nbase_seeds = [1, 11]\n",
            &format!("seeds = 3\nbase_seeds = {base_seeds}\nset = {{ ga = {{ population = 8, generations = 4 }}, trial = {{ steps = 150 }} }}\n"),
        )
        .replace("\"../configs/", &format!("\"{}/", configs.display()));
    assert!(
        text.contains("population = 8") && text.contains(&format!("base_seeds = {base_seeds}\n"))
    );
    let path = dir.join("paper.toml");
    std::fs::write(&path, text).unwrap();
    let sets = ["ga.population=8", "ga.generations=4", "trial.steps=150"];
    (path, sets)
}

/// `fuzzymotiv study studies/paper.toml` is the paper's study: the same runs as `reproduce`
/// (each run directory the same bytes but for wall times), every claim's numbers those of
/// reproduce's claims.csv (the comparisons' verdicts too: the same rule), and its every verdict
/// recomputed from its own per_seed.csv.
#[test]
fn the_paper_study_file_runs_reproduces_runs_and_gives_its_claims_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let (file, sets) = tiny_paper_study(dir.path(), "[1]");
    let (rep, out) = (dir.path().join("reproduce"), dir.path().join("study"));
    let mut args = vec!["reproduce", "--seeds", "3", "--threads", "2", "-q", "--out"];
    args.push(rep.to_str().unwrap());
    for s in &sets {
        args.extend(["--set", s]);
    }
    ok(&args);
    study(&file, &out, &[]);
    let plan = std::fs::read_to_string(out.join("plan.jsonl")).unwrap();
    for line in plan.lines() {
        let job: serde_json::Value = serde_json::from_str(line).unwrap();
        let seed_dir = format!("seed-{}", job["replicate"].as_u64().unwrap() + 1);
        let theirs = rep.join(job["setting"].as_str().unwrap()).join(seed_dir);
        let ours: Vec<_> = common::results(&out.join("jobs").join(job["id"].as_str().unwrap()))
            .into_iter()
            .filter(|(p, _)| p != Path::new("DONE") && p != Path::new("job.json"))
            .collect();
        assert!(
            common::results(&theirs) == ours,
            "{} differs from reproduce's {}",
            job["key"],
            theirs.display()
        );
    }
    let paper = read_csv(&rep.join("claims.csv"));
    let claims = read_csv(&out.join("claims.csv"));
    let claim = |id: &str| claims.iter().find(|c| c["id"] == id).unwrap();
    // reproduce's claims.csv: the four comparisons in ClaimId::COMPARISONS' order, then each
    // Fig. 6 check over both settings and per setting.
    for (k, id) in ["explores", "battery", "recognition", "homing"]
        .iter()
        .enumerate()
    {
        let (ours, theirs) = (claim(id), &paper[k]);
        for (a, b) in [
            ("effect", "difference"),
            ("ci_low", "ci_low"),
            ("ci_high", "ci_high"),
            ("p", "p"),
            ("mdd", "mdd"),
        ] {
            assert_eq!(f(ours, a), f(theirs, b), "{id}: {a}");
        }
        assert_eq!(ours["verdict"], theirs["verdict"], "{id}: verdict");
    }
    // Fig. 6's checks per setting: the same values and intervals (a range's bounds added to
    // its interval as reproduce adds them: equal to rounding), a rise's p too. Their verdicts
    // follow each study's own rule (docs/guide/studies.md).
    for (id, row) in [
        ("first-f-high", 5),
        ("first-f-low", 6),
        ("rises-high", 8),
        ("rises-low", 9),
    ] {
        let (ours, theirs) = (claim(id), &paper[row]);
        let setting = if id.ends_with("high") { "high" } else { "low" };
        assert!(theirs["claim"].ends_with(&format!("— {setting}-curiosity")));
        assert_eq!(f(ours, "effect"), f(theirs, "difference"), "{id}: effect");
        for key in ["ci_low", "ci_high"] {
            assert!((f(ours, key) - f(theirs, key)).abs() < 1e-12, "{id}: {key}");
        }
        if id.starts_with("rises") {
            assert_eq!(f(ours, "p"), f(theirs, "p"), "{id}: p");
        }
    }
    assert_eq!(recompute_every_verdict(&out), 8);
}

/// The paper's study at two base seeds is `reproduce --replication`: its agreement.csv judges
/// each hypothesis on each base seed's first n seeds (n = 2, 3) and the four comparisons there
/// have the replication's p-values and verdicts (replication_seeds.csv) beside the same pooled
/// verdicts (replication.csv); the report shows the agreement.
#[test]
fn the_paper_study_at_two_base_seeds_agrees_by_seed_count_as_reproduce_replication() {
    let dir = tempfile::tempdir().unwrap();
    let (file, sets) = tiny_paper_study(dir.path(), "[1, 11]");
    let (rep, out) = (dir.path().join("replication"), dir.path().join("study"));
    let mut args = vec![
        "reproduce",
        "--replication",
        "--seeds",
        "3",
        "--threads",
        "2",
    ];
    args.extend(["-q", "--out", rep.to_str().unwrap()]);
    for s in &sets {
        args.extend(["--set", s]);
    }
    ok(&args);
    study(&file, &out, &[]);
    let ours = read_csv(&out.join("agreement.csv"));
    let theirs = read_csv(&rep.join("replication_seeds.csv"));
    let pooled = read_csv(&rep.join("replication.csv"));
    let ids = ["explores", "battery", "recognition", "homing"];
    // Per seed count and base seed, the eight hypotheses of paper.toml.
    assert_eq!(ours.len(), 2 * 2 * 8);
    for n in ["2", "3"] {
        // replication_seeds.csv: per seed count, the claims with the four comparisons first.
        let at: Vec<_> = theirs.iter().filter(|r| r["seeds"] == n).collect();
        for (k, id) in ids.iter().enumerate() {
            for (base, side) in [("1", "a"), ("11", "b")] {
                let what = format!("{id} at {n} seeds of base seed {base}");
                let row = (ours.iter())
                    .find(|r| r["seeds"] == n && r["id"] == *id && r["base_seed"] == base)
                    .unwrap_or_else(|| panic!("no {what}"));
                assert_eq!(f(row, "p"), f(at[k], &format!("p_{side}")), "{what}: p");
                assert_eq!(row["verdict"], at[k][&format!("verdict_{side}")], "{what}");
                assert_eq!(row["pooled"], pooled[k]["verdict_pooled"], "{what}: pooled");
                let agrees = row["verdict"] == row["pooled"];
                assert_eq!(row["agrees"], agrees.to_string(), "{what}: agrees");
            }
        }
    }
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(report.contains("## Agreement by seed count"), "{report}");
    assert!(report.contains("| 3 |"), "{report}");
}

/// Every shipped study file (studies/*.toml) loads, every run's config checked, and each that
/// reports a verdict replicates: it runs at two base seeds or more, so that it reports each base
/// seed's verdict beside the pooled one (the orientation study, a sweep of arms, has none).
#[test]
fn every_shipped_study_file_loads_and_runs_at_two_base_seeds() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo().join("studies"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 7, "{files:?}");
    for file in files {
        let study = fuzzymotiv_pipeline::study::Study::load(&file)
            .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let sweep = file.ends_with("orientation.toml");
        assert_eq!(study.hypotheses.is_empty(), sweep, "{}", file.display());
        assert!(
            sweep || study.base_seeds.len() >= 2,
            "{}: base seeds {:?}",
            file.display(),
            study.base_seeds
        );
    }
}

/// Hypotheses over the transfer's measures: in Enki, and the gap between the worlds.
const IN_ENKI: &str = r#"
[[hypothesis]]
id = "homing-in-enki"
kind = "compare"
measure = "enki_homing"
a = "high-curiosity"
b = "low-curiosity"
expect = "lower"

[[hypothesis]]
id = "recognition-in-enki"
kind = "compare"
measure = "enki_recognition_pct"
a = "high-curiosity"
b = "low-curiosity"
expect = "higher"

[[hypothesis]]
id = "exploration-gap"
kind = "compare"
measure = "gap_exploration"
a = "high-curiosity"
b = "low-curiosity"
expect = "higher"
"#;

/// The mean of `column` over `world`'s rows of a transfer's measures.csv.
fn world_mean(measures: &Rows, world: &str, column: &str) -> f64 {
    let v: Vec<f64> = (measures.iter().filter(|r| r["world"] == world))
        .map(|r| f(r, column))
        .collect();
    statistics::mean(&v)
}

/// A study whose arms transfer their robots to Enki is `fuzzymotiv transfer` of each run: its
/// transfer directories have the command's bytes, its per-seed Enki values are the means of the
/// Enki test runs of measures.csv, its gap |Enki − fuzzymotiv| of the two worlds' means, and
/// every verdict is recomputed from them; each transfer is announced; run again, nothing is
/// transferred again.
#[test]
#[ignore = "needs python3-enki2 and libenki-dev (Enki) and g++: run by .ci/run"]
fn a_study_transfers_its_robots_to_enki_as_fuzzymotiv_transfer_does() {
    let dir = tempfile::tempdir().unwrap();
    let (file, _) = tiny_paper_study(dir.path(), "[1]");
    let text = std::fs::read_to_string(&file).unwrap().replacen(
        "seeds = 3\n",
        "seeds = 2\ntransfer = { world = \"enki\", runs = 2, rooms = [\"H\"] }\n",
        1,
    );
    std::fs::write(&file, format!("{text}{IN_ENKI}")).unwrap();
    let out = dir.path().join("study");
    let o = ok(&[
        "study",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let said = "transfer 1 of 4: run high-curiosity;base=1;rep=0 to Enki in room H";
    assert!(stderr(&o).contains(said), "{}", stderr(&o));
    let per_seed = read_csv(&out.join("per_seed.csv"));
    let plan = std::fs::read_to_string(out.join("plan.jsonl")).unwrap();
    for line in plan.lines() {
        let job: serde_json::Value = serde_json::from_str(line).unwrap();
        assert_transfer_is_the_commands(dir.path(), &out, &job, &per_seed);
    }
    assert_eq!(recompute_every_verdict(&out), 8 + 3);
    let measures = out
        .join("transfer")
        .join(plan_first_id(&plan))
        .join("H/measures.csv");
    let (claims, made) = (
        std::fs::read(out.join("claims.csv")).unwrap(),
        std::fs::metadata(&measures).unwrap().modified().unwrap(),
    );
    let again = run(&[
        "study",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert!(again.status.success(), "{}", stderr(&again));
    assert_eq!(std::fs::read(out.join("claims.csv")).unwrap(), claims);
    let kept = std::fs::metadata(&measures).unwrap().modified().unwrap();
    assert_eq!(kept, made, "a transfer made again");
}

/// Job `job`'s transfer to room H in the study `out` is `fuzzymotiv transfer`'s (run into
/// `dir`): the same files, and `per_seed`'s Enki homing and exploration gap its measures'.
fn assert_transfer_is_the_commands(
    dir: &Path,
    out: &Path,
    job: &serde_json::Value,
    per_seed: &Rows,
) {
    let id = job["id"].as_str().unwrap();
    let theirs = dir.join("transfer").join(id);
    ok(&[
        "transfer",
        out.join("jobs").join(id).to_str().unwrap(),
        "--room",
        "H",
        "--runs",
        "2",
        "--out",
        theirs.to_str().unwrap(),
    ]);
    let ours = out.join("transfer").join(id).join("H");
    for name in ["measures.csv", "test_runs.csv", "run-0.csv", "run-1.csv"] {
        let (a, b) = (ours.join(name), theirs.join(name));
        assert!(
            std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap(),
            "{id}: {name}"
        );
    }
    let measures = read_csv(&theirs.join("measures.csv"));
    let seed = job["seed"].to_string();
    let value = |measure: &str, room: &str| {
        let row = (per_seed.iter())
            .find(|r| {
                r["seed"] == seed
                    && r["arm"] == job["setting"].as_str().unwrap()
                    && r["measure"] == measure
                    && r["room"] == room
            })
            .unwrap_or_else(|| panic!("{id}: no {measure} in room `{room}`"));
        f(row, "value")
    };
    let enki = world_mean(&measures, "enki", "homing_pct");
    let gap = (world_mean(&measures, "enki", "exploration_pct")
        - world_mean(&measures, "fuzzymotiv", "exploration_pct"))
    .abs();
    for room in ["H", ""] {
        assert_eq!(value("enki_homing_pct", room), enki, "{id}: Enki's homing");
        assert_eq!(value("gap_exploration_pct", room), gap, "{id}: the gap");
    }
}

/// The id of a plan.jsonl's first job.
fn plan_first_id(plan: &str) -> String {
    let job: serde_json::Value = serde_json::from_str(plan.lines().next().unwrap()).unwrap();
    job["id"].as_str().unwrap().to_string()
}
