//! The model switches through the binary: the first release's model still gives its results
//! byte for byte, and the default (the paper's robot) is what a plain run uses.

use crate::common;
use common::*;

/// `motion = "wheels"`, `end_at_home = false`, `homing = "distance"` with the first release's
/// rooms (rooms/first-release/) reproduce the first release: generations, best genome and
/// recognition files are byte-identical to the golden saved from it (tests/golden/first-release).
#[test]
fn first_release_model_reproduces_its_golden() {
    let golden = repo().join("crates/fuzzymotiv-cli/tests/golden/first-release");
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("run");
    run_golden(
        &golden,
        &dir,
        &[
            "--threads",
            "2",
            "--set",
            "robot.motion=\"wheels\"",
            "--set",
            "trial.end_at_home=false",
            "--set",
            "fitness.homing=\"distance\"",
        ],
    );
    let files = ["generations.csv", "best_genome.json", "recognition.csv"];
    assert_pinned(&golden, &dir, &files, "the first release's model");
}

/// The files of a run that are pinned by the goldens.
const PINNED: [&str; 4] = [
    "generations.csv",
    "best_genome.json",
    "recognition.csv",
    "population.json",
];

fn default_golden() -> std::path::PathBuf {
    repo().join("crates/fuzzymotiv-cli/tests/golden/default")
}

/// `fuzzymotiv run GOLDEN/config.toml --out DIR EXTRA…`, asserted to succeed.
fn run_golden(golden: &std::path::Path, dir: &std::path::Path, extra: &[&str]) {
    let config = golden.join("config.toml");
    let mut args = vec![
        "run",
        config.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    ok(&args);
}

/// Asserts that `dir` holds the pinned files of `golden` byte for byte.
fn assert_pinned(golden: &std::path::Path, dir: &std::path::Path, files: &[&str], what: &str) {
    for file in files {
        let want = std::fs::read_to_string(golden.join(file)).unwrap();
        let got = std::fs::read_to_string(dir.join(file)).unwrap();
        assert!(want == got, "{file} differs from the golden ({what})");
    }
}

/// The default model (the paper's robot) gives its golden's results byte for byte, on 1 and 2
/// threads (tests/golden/default/README.md says how the golden was made).
#[test]
fn default_model_reproduces_its_golden() {
    let golden = default_golden();
    let out = tempfile::tempdir().unwrap();
    for threads in ["1", "2"] {
        let dir = out.path().join(format!("run-{threads}"));
        run_golden(&golden, &dir, &["--threads", threads]);
        assert_pinned(&golden, &dir, &PINNED, &format!("{threads} threads"));
    }
}

/// A small study of the default model gives its golden's tables and claims byte for byte.
#[test]
fn default_study_reproduces_its_golden() {
    let golden = default_golden().join("study");
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("study");
    let mut args = vec!["reproduce", "--quick", "--seeds", "2", "--quiet"];
    args.extend(["--out", dir.to_str().unwrap()]);
    for set in [
        "ga.population=10",
        "ga.generations=4",
        "trial.steps=150",
        "aem.epochs=50",
        "aem.test_runs=3",
    ] {
        args.extend(["--set", set]);
    }
    ok(&args);
    let files = [
        "table1.csv",
        "table2.csv",
        "table1_seeds.csv",
        "table2_seeds.csv",
        "claims.csv",
    ];
    assert_pinned(&golden, &dir, &files, "study");
    claims_are_recomputed_from_the_records(&dir);
}

/// `claims DIR` recomputes a finished study's claims from its summary.json: at the study's α
/// the same files (left alone); at another α, other verdicts, written beside the study's
/// (claims-alpha-A.md, .csv; the study's own never replaced) or to --out.
fn claims_are_recomputed_from_the_records(dir: &std::path::Path) {
    let read = |p: std::path::PathBuf| std::fs::read_to_string(p).unwrap();
    let (md, csv) = (read(dir.join("claims.md")), read(dir.join("claims.csv")));
    // Per room, exploratory and Holm-adjusted: four claims × five rooms.
    assert!(md.contains("Per room (exploratory"), "{md}");
    assert_eq!(md.matches("| high curiosity ").count(), 4 + 4 * 5, "{md}");
    ok(&["claims", dir.to_str().unwrap()]);
    assert_eq!(read(dir.join("claims.md")), md, "the same tables again");
    assert_eq!(read(dir.join("claims.csv")), csv);
    // Two seeds: the smallest p is 2/4, so only an α above 1/2 lets a claim be shown.
    let beside = ok(&["claims", dir.to_str().unwrap(), "--alpha", "0.6"]);
    assert_eq!(
        read(dir.join("claims.md")),
        md,
        "the study's own claims are kept"
    );
    assert_eq!(
        read(dir.join("claims.csv")),
        csv,
        "the study's own claims are kept"
    );
    assert_eq!(stdout(&beside), read(dir.join("claims-alpha-0.6.md")));
    assert!(read(dir.join("claims-alpha-0.6.csv")) != csv);
    let other = dir.with_file_name("claims-0.6");
    let o = ok(&[
        "claims",
        dir.to_str().unwrap(),
        "--alpha",
        "0.6",
        "--out",
        other.to_str().unwrap(),
    ]);
    let at = read(other.join("claims.md"));
    assert!(at.contains("at p < α = 0.6") && stdout(&o) == at, "{at}");
    assert!(!md.contains("smallest two-sided p is 2/2^2 = 0.5000 (1/16 for five seeds), below"));
    assert!(
        at.contains("smallest two-sided p is 2/2^2 = 0.5000 (1/16 for five seeds), below α = 0.6")
    );
    let bad = run(&["claims", dir.to_str().unwrap(), "--alpha", "1.5"]);
    assert!(
        stderr(&bad).contains("--alpha must be between 0 and 1"),
        "{}",
        stderr(&bad)
    );
}

/// `DIR.partial/` holding the golden's checkpoint fixture `name` (the golden's run killed
/// after its second generation), in a new temporary directory.
fn staged_checkpoint(name: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let golden = default_golden();
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("run");
    let staging = out.path().join("run.partial");
    std::fs::create_dir(&staging).unwrap();
    for file in ["checkpoint.json", "config.resolved.toml"] {
        std::fs::copy(golden.join(name).join(file), staging.join(file)).unwrap();
    }
    (out, dir)
}

/// A checkpoint written by an earlier build of this model (tests/golden/default/checkpoint/)
/// still resumes, to the golden's files.
#[test]
fn a_checkpoint_of_an_earlier_build_resumes() {
    let (_out, dir) = staged_checkpoint("checkpoint");
    let o = ok(&["run", "--resume", dir.to_str().unwrap()]);
    assert!(stderr(&o).contains("at generation 3/4"), "{}", stderr(&o));
    assert_pinned(&default_golden(), &dir, &PINNED, "resumed");
}

/// A checkpoint of another model (tests/golden/default/checkpoint-model-1/, written before
/// model versions were recorded) is not resumed: the run would mix two models' results. The
/// message says which models, and nothing is written.
#[test]
fn a_checkpoint_of_another_model_is_refused() {
    let (out, dir) = staged_checkpoint("checkpoint-model-1");
    let o = run(&["run", "--resume", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let msg = stderr(&o);
    assert!(
        msg.contains("written by model 1") && msg.contains("this build is model 2"),
        "{msg}"
    );
    assert!(!dir.exists());
    let staged = out.path().join("run.partial").join("checkpoint.json");
    let fixture = default_golden().join("checkpoint-model-1/checkpoint.json");
    assert_eq!(
        std::fs::read(staged).unwrap(),
        std::fs::read(fixture).unwrap()
    );
}

/// A finished run of another model is kept, and the message says it is another model's
/// (not just "another run"); `--force` replaces it.
#[test]
fn a_finished_run_of_another_model_is_kept() {
    let golden = default_golden();
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("run");
    run_golden(&golden, &dir, &[]);
    let cfg = dir.join("config.resolved.toml");
    let text = std::fs::read_to_string(&cfg).unwrap();
    let old = text.replacen(", model 2 (all keys", " (all keys", 1);
    assert_ne!(old, text);
    std::fs::write(&cfg, &old).unwrap();
    let config = golden.join("config.toml");
    let o = run(&[
        "run",
        config.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("the results of model 1 of fuzzymotiv (this build is model 2"));
    assert_eq!(std::fs::read_to_string(&cfg).unwrap(), old, "kept");
    run_golden(&golden, &dir, &["--force"]);
    assert_pinned(&golden, &dir, &PINNED, "replaced with --force");
}

/// The default model differs from the first release's on the same rooms (so the switches are
/// real), and the resolved config records the new keys with their defaults.
#[test]
fn default_model_is_the_papers_robot() {
    let golden = repo().join("crates/fuzzymotiv-cli/tests/golden/first-release");
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("run");
    ok(&[
        "run",
        golden.join("config.toml").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    let resolved = std::fs::read_to_string(dir.join("config.resolved.toml")).unwrap();
    for key in [
        "motion = \"actions\"",
        "end_at_home = true",
        "homing = \"escape\"",
    ] {
        assert!(resolved.contains(key), "{key} missing in:\n{resolved}");
    }
    let want = std::fs::read_to_string(golden.join("generations.csv")).unwrap();
    let got = std::fs::read_to_string(dir.join("generations.csv")).unwrap();
    assert_ne!(want, got);
}

/// Bad values of the new keys exit 2 and name the field.
#[test]
fn bad_model_keys_name_the_field() {
    let cfg = repo().join("configs/tiny.toml");
    for (set, field) in [
        ("robot.motion=\"hover\"", "robot.motion"),
        ("trial.end_at_home=3", "trial.end_at_home"),
        ("fitness.homing=\"near\"", "fitness.homing"),
    ] {
        let o = run(&[
            "run",
            cfg.to_str().unwrap(),
            "--set",
            set,
            "--out",
            "/nonexistent/x",
        ]);
        assert_eq!(o.status.code(), Some(2), "{set}: {}", stderr(&o));
        assert!(stderr(&o).contains(field), "{set}: {}", stderr(&o));
    }
}

/// The report explains g and b as the run's own model defines them (docs/model.md §7): the
/// escape rule and per-action energy by default; distance homing and wheel speeds when switched.
#[test]
fn report_explains_g_and_b_for_its_model() {
    let cfg = repo().join("configs/tiny.toml");
    let out = tempfile::tempdir().unwrap();
    let page = |name: &str, sets: &[&str]| {
        let dir = out.path().join(name);
        let mut args = vec!["run", cfg.to_str().unwrap(), "--out", dir.to_str().unwrap()];
        for s in SMALL.iter().chain(sets) {
            args.extend(["--set", s]);
        }
        ok(&args);
        std::fs::read_to_string(dir.join("report.html")).unwrap()
    };
    let default = page("default", &[]);
    assert!(default.contains("if the robot left the home zone during the trial, else 0"));
    assert!(default.contains("every action (a move or a turn) uses one unit"));
    assert!(!default.contains("wheel speed"));
    let first = page(
        "first-release",
        &["robot.motion=\"wheels\"", "fitness.homing=\"distance\""],
    );
    assert!(first.contains("whether or not the robot left the home zone"));
    assert!(first.contains("(|sL| + |sR|) / (2·v_max)"));
}
