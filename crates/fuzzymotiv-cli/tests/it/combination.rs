//! `reproduce --combination`: the study under the TSK and under each baseline combination,
//! the claims under each, and the behaviour of each baseline against the TSK.

use crate::common;

use std::path::Path;

use common::{Fm, assert_killed_study_resumes, stderr, stdout};

const SIZES: [&str; 6] = [
    "ga.population=10",
    "ga.generations=3",
    "trial.steps=80",
    "aem.epochs=10",
    "aem.test_runs=2",
    "rooms=[\"H\", \"square\"]",
];

fn read(p: std::path::PathBuf) -> String {
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// Every combination runs in its own directory; the behaviour table pairs each baseline with
/// the TSK for both settings and the five measures (the end spread measured from the runs);
/// the summary and the CSV say the same.
#[test]
fn combination_runs_each_combination_and_compares_their_behaviour() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("c");
    let o = Fm::new(["reproduce", "--combination", "--seeds", "2", "--quiet"])
        .out(&out)
        .sets(&SIZES)
        .ok();
    let md = read(out.join("combination.md"));
    assert_eq!(stdout(&o).trim_end(), md.trim_end());
    for dir in ["default", "weighted-sum", "weighted-squares"] {
        assert!(out.join(dir).join("summary.json").is_file(), "{dir}");
    }
    let config = read(out.join("weighted-sum/high-curiosity/seed-1/config.resolved.toml"));
    assert!(config.contains("combine = \"weighted-sum\""), "{config}");
    let summary: serde_json::Value = serde_json::from_str(&read(out.join("summary.json"))).unwrap();
    assert_eq!(summary["combinations"].as_array().unwrap().len(), 3);
    let rows = summary["behaviour"].as_array().unwrap();
    assert_eq!(rows.len(), 2 * 2 * 5, "{rows:?}");
    // Per combination, setting and seed, an end spread in % of the room's largest distance.
    let spreads = summary["end_spreads"].as_array().unwrap();
    assert_eq!(spreads.len(), 3);
    for setting in spreads.iter().flat_map(|c| c.as_array().unwrap()) {
        let seeds = setting.as_array().unwrap();
        assert_eq!(seeds.len(), 2);
        assert!(
            seeds
                .iter()
                .all(|v| (0.0..=100.0).contains(&v.as_f64().unwrap()))
        );
    }
    assert!(md.contains("% end spread"), "{md}");
    let csv = read(out.join("behaviour.csv"));
    assert_eq!(csv.lines().count(), 1 + rows.len());
    assert!(md.contains("| tsk | the paper's TSK rule base |"), "{md}");
    let svg = read(out.join("behaviour.svg"));
    assert!(svg.contains("% optimal exploration") && svg.contains("weighted-sum − TSK"));

    // Per baseline and comparison claim, the claim's effect against the TSK's: each effect is
    // the one of that combination's own claims, the difference theirs.
    let differences = summary["claim_differences"].as_array().unwrap();
    assert_eq!(differences.len(), 2 * 4, "{differences:?}");
    let effect = |combination: &str, claim: &str| {
        let dir = if combination == "tsk" {
            "default"
        } else {
            combination
        };
        let s: serde_json::Value =
            serde_json::from_str(&read(out.join(dir).join("summary.json"))).unwrap();
        let c = (s["claims"].as_array().unwrap().iter())
            .find(|c| c["claim"] == claim)
            .unwrap_or_else(|| panic!("{claim} not in {dir}"));
        c["stats"]["difference"].as_f64().unwrap()
    };
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9 * (1.0 + a.abs());
    for r in differences {
        let (name, claim) = (
            r["combination"].as_str().unwrap(),
            r["claim"].as_str().unwrap(),
        );
        let (mine, tsk) = (effect(name, claim), effect("tsk", claim));
        assert!(
            close(r["effect_combination"].as_f64().unwrap(), mine),
            "{r}"
        );
        assert!(close(r["effect_tsk"].as_f64().unwrap(), tsk), "{r}");
        assert!(close(r["difference"].as_f64().unwrap(), mine - tsk), "{r}");
        let line = format!("| {name} | {claim} | {mine:+.1} | {tsk:+.1} |");
        assert!(md.contains(&line), "{line} not in {md}");
    }
    let csv = read(out.join("claim_differences.csv"));
    assert_eq!(csv.lines().count(), 1 + differences.len());
    assert!(
        md.contains("Does the combination change the claims' effects?"),
        "{md}"
    );
    assert_study_page(
        &out,
        "Does the fuzzy combination matter?",
        &md,
        "weighted-sum − TSK",
    );
    let page = read(out.join("report.html"));
    for dir in ["default", "weighted-sum", "weighted-squares"] {
        assert!(
            page.contains(&format!("<a href=\"{dir}/report.html\">")),
            "{dir}"
        );
    }
}

/// The study's `report.html` has its title, every table row of its Markdown as an HTML row
/// (as many rows as the Markdown has table lines, less their rules) and its figure, inline.
fn assert_study_page(out: &Path, title: &str, md: &str, in_figure: &str) {
    let page = read(out.join("report.html"));
    assert!(page.contains(&format!("<h1>{title}</h1>")), "{page}");
    let table_lines = md.lines().filter(|l| l.starts_with('|')).count();
    let rules = md.lines().filter(|l| l.starts_with("|---")).count();
    assert_eq!(page.matches("<tr>").count(), table_lines - rules, "{page}");
    assert!(page.contains("<svg") && page.contains(in_figure), "{page}");
}

/// A study's command line at the tiny sizes, one thread (the runs go one after another, so
/// the kill points fall in known runs whatever the machine).
fn tiny(study: &str, seeds: &str, out: &Path) -> Fm {
    Fm::new([
        "reproduce",
        study,
        "--seeds",
        seeds,
        "--quiet",
        "--threads",
        "1",
    ])
    .out(out)
    .sets(&SIZES)
}

/// `reproduce --combination` killed at deterministic points (as kill -9 would) resumes with the
/// same command and ends with the files of an uninterrupted study: the end spreads measured
/// on runs read back are the ones measured on runs just evolved.
#[test]
fn killed_combination_resumes_to_the_files_of_an_uninterrupted_one() {
    let tmp = tempfile::tempdir().unwrap();
    // 3 combinations × 2 settings × 2 seeds × 3 generations = 36, one run after another. The
    // kills fall in the TSK's first run (2), in the weighted sum's second (16 in all: the TSK's
    // runs then finished and read back) and in the weighted squares' last (33).
    assert_killed_study_resumes(
        |out| tiny("--combination", "2", out),
        &tmp.path().join("c"),
        &[2, 14, 17],
    );
}

/// `reproduce --replication` killed at deterministic points resumes with the same command and
/// ends with the files of an uninterrupted study.
#[test]
fn killed_replication_resumes_to_the_files_of_an_uninterrupted_one() {
    let tmp = tempfile::tempdir().unwrap();
    // 2 base seeds × 2 settings × 2 seeds × 3 generations = 24, one run after another. The
    // kills fall in base seed 1's first run (2), on base seed 1's very last checkpoint (12 in
    // all: its runs' records not yet written) and in base seed 11's last run (22).
    assert_killed_study_resumes(
        |out| tiny("--replication", "2", out),
        &tmp.path().join("r"),
        &[2, 10, 10],
    );
}

/// A --set of the key the study varies is refused: it would make the three studies one.
#[test]
fn combination_refuses_to_have_its_combine_set() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("c");
    let o = Fm::new(["reproduce", "--combination", "--seeds", "2", "--quiet"])
        .out(&out)
        .sets(&["fitness.combine=\"weighted-sum\""])
        .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("this study sets `fitness.combine` itself"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
}

/// `reproduce --replication`: the study at base seeds S and S + 10, each a whole study; the
/// claims from both and pooled; per number of seeds both base seeds' verdicts; the figure.
#[test]
fn replication_runs_two_base_seeds_and_pools_their_claims() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("r");
    let o = Fm::new(["reproduce", "--replication", "--seeds", "3", "--quiet"])
        .out(&out)
        .sets(&SIZES)
        .ok();
    let md = read(out.join("replication.md"));
    assert_eq!(stdout(&o).trim_end(), md.trim_end());
    for base in ["base-1", "base-11"] {
        let s: serde_json::Value =
            serde_json::from_str(&read(out.join(base).join("summary.json"))).unwrap();
        assert_eq!(s["seeds"].as_array().unwrap().len(), 3, "{base}");
    }
    let b: serde_json::Value =
        serde_json::from_str(&read(out.join("base-11/summary.json"))).unwrap();
    assert_eq!(b["seed"], 11);
    let summary: serde_json::Value = serde_json::from_str(&read(out.join("summary.json"))).unwrap();
    assert_eq!(summary["base_seeds"], serde_json::json!([1, 11]));
    assert_eq!(summary["rows"].as_array().unwrap().len(), 6);
    // Seeds 2 and 3 per base seed, each with every claim's two verdicts.
    assert_eq!(summary["by_seeds"].as_array().unwrap().len(), 2);
    let pooled = &summary["pooled"][0]["stats"]["seeds"];
    assert_eq!(pooled, 6, "the pooled claims see both base seeds' seeds");
    assert!(
        md.contains("| claim | base seed 1 | base seed 11 | pooled (6 seeds) |"),
        "{md}"
    );
    let seeds = read(out.join("replication_seeds.csv"));
    assert_eq!(seeds.lines().count(), 1 + 2 * 6);
    let svg = read(out.join("replication.svg"));
    assert!(svg.contains("base seed 11") && svg.contains("seeds per base seed"));
    assert_study_page(
        &out,
        "Verdicts that replicate: the study at two base seeds",
        &md,
        "seeds per base seed",
    );
    // Run again: the study is there, nothing to do.
    let again = Fm::new(["reproduce", "--replication", "--seeds", "3"])
        .out(&out)
        .sets(&SIZES)
        .ok();
    assert!(
        stderr(&again).contains("already holds this study"),
        "{}",
        stderr(&again)
    );
}

/// A run under a baseline says in its report that F is not the TSK's, and its rules' notes
/// say what the TSK would give; a TSK run's report says neither.
#[test]
fn a_baseline_runs_report_says_its_f_is_not_the_tsks() {
    let tmp = tempfile::tempdir().unwrap();
    let config = tmp.path().join("c.toml");
    std::fs::write(&config, "name = \"c\"\n").unwrap();
    for (combine, baseline) in [("weighted-sum", true), ("tsk", false)] {
        let out = tmp.path().join(combine);
        let set = format!("fitness.combine=\"{combine}\"");
        Fm::new(["run", config.to_str().unwrap(), "--quiet"])
            .out(&out)
            .sets(&SIZES)
            .sets(&[set.as_str()])
            .ok();
        let page = read(out.join("report.html"));
        assert_eq!(
            page.contains("This run&#39;s F is not the TSK&#39;s")
                || page.contains("This run's F is not the TSK's"),
            baseline,
            "{combine}"
        );
        assert_eq!(
            page.contains("The TSK would give F = Σ w·f / Σ w"),
            baseline,
            "{combine}"
        );
    }
}
