//! `fuzzymotiv study`: a study of one's own (the shipped fetch-urgency study at a tiny size)
//! runs from the command line, writes typed records whose every verdict is recomputed here
//! from its own per-seed values, gives the same bytes in shards as whole, and bad study files
//! are refused (status 2, the file and field named, nothing written).

use std::path::{Path, PathBuf};

mod common;

use common::recompute::{f, read_csv, recompute_every_verdict};
use common::{ok, repo, run, stderr, stdout};

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

/// Two more hypotheses, of the kinds the shipped file lacks: a range and a trend of a term.
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
    // Six hypotheses, judged pooled and at each of the two base seeds.
    assert_eq!(recompute_every_verdict(&out), 18);
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
        "## Per room",
        "## Seeds",
        "name = \"fetch-urgency\"",
    ] {
        assert!(report.contains(part), "report.md lacks {part}");
    }
    let forest = std::fs::read_to_string(out.join("forest.svg")).unwrap();
    assert_eq!(forest.matches("<circle").count(), 18, "a dot per result");
    // The rooms' table: the five fetch rooms per hypothesis over a measure (all but `learns`)
    // and scope.
    assert_eq!(read_csv(&out.join("rooms.csv")).len(), 5 * 5 * 3);
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
    let cases: [(&str, &str, &[&str]); 10] = [
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
    for (k, (line, by, says)) in cases.iter().enumerate() {
        let file = edited(dir.path(), &format!("bad{k}.toml"), line, by);
        let out = dir.path().join(format!("out{k}"));
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

/// The shipped studies/paper.toml made tiny (three seeds of base seed 1, a small GA, short
/// trials), its configs named by absolute paths; and the same size as `reproduce`'s `--set`s.
fn tiny_paper_study(dir: &Path) -> (PathBuf, [&'static str; 3]) {
    let text = std::fs::read_to_string(repo().join("studies/paper.toml")).unwrap();
    let configs = repo().join("configs");
    let text = text
        .replace(
            "seeds = 20\nbase_seeds = [1, 11]\n",
            "seeds = 3\nbase_seeds = [1]\nset = { ga = { population = 8, generations = 4 }, trial = { steps = 150 } }\n",
        )
        .replace("\"../configs/", &format!("\"{}/", configs.display()));
    assert!(text.contains("population = 8") && text.contains("base_seeds = [1]\n"));
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
    let (file, sets) = tiny_paper_study(dir.path());
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

/// Every shipped study file (studies/*.toml) loads, every run's config checked, and
/// replicates: it runs at two base seeds or more, so that it reports each base seed's verdict
/// beside the pooled one.
#[test]
fn every_shipped_study_file_loads_and_runs_at_two_base_seeds() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo().join("studies"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 6, "{files:?}");
    for file in files {
        let study = fuzzymotiv_pipeline::study::Study::load(&file)
            .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        assert!(
            study.base_seeds.len() >= 2,
            "{}: base seeds {:?}",
            file.display(),
            study.base_seeds
        );
    }
}
