//! The shipped study files against `reproduce`'s own code for the same runs, at a tiny size:
//! studies/combination.toml's behaviour comparisons (the end spread read back from the runs
//! included) and claim differences are `reproduce --combination`'s, studies/urgency.toml's
//! missions done and time to the goal are `reproduce --urgency`'s, and studies/orientation.toml
//! (no hypotheses: each arm's measures) is what `reproduce --orientation`'s merge makes of the
//! same runs.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::common;

use common::{ok, repo};

type Row = BTreeMap<String, String>;

fn read_csv(path: &Path) -> Vec<Row> {
    let mut r = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    r.deserialize().map(|row| row.unwrap()).collect()
}

fn f(row: &Row, key: &str) -> f64 {
    row[key]
        .parse()
        .unwrap_or_else(|e| panic!("{key} of {row:?}: {e}"))
}

/// studies/NAME.toml with each `(from, to)` of `edits` applied (each must apply) and its
/// configs named by absolute paths, written into `dir`.
fn tiny_file(dir: &Path, name: &str, edits: &[(&str, &str)]) -> PathBuf {
    let mut text = std::fs::read_to_string(repo().join("studies").join(name)).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{name}: {from}");
        text = text.replacen(from, to, 1);
    }
    let configs = repo().join("configs");
    let text = text.replace("\"../configs/", &format!("\"{}/", configs.display()));
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn study(file: &Path, out: &Path) {
    ok(&[
        "study",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--threads",
        "2",
        "-q",
    ]);
}

/// `reproduce FLAG` of three seeds at base seed 1 into `out`, with `sets`.
fn reproduce(flag: &str, out: &Path, sets: &[&str]) {
    let mut args = vec!["reproduce", flag, "--seeds", "3", "--threads", "2", "-q"];
    args.extend(["--out", out.to_str().unwrap()]);
    for s in sets {
        args.extend(["--set", s]);
    }
    ok(&args);
}

/// A study's claim `id` (pooled: one base seed) has reproduce's effect, p and detectable
/// difference in `theirs` (a row of its paired comparisons), and its verdict is reproduce's
/// two-sided one read in the hypothesis's direction.
fn assert_claim_is(claims: &[Row], id: &str, theirs: &Row) {
    let ours = (claims.iter())
        .find(|c| c["id"] == id && c["scope"] == "pooled")
        .unwrap_or_else(|| panic!("claims.csv has no {id}"));
    assert_eq!(f(ours, "effect"), f(theirs, "difference"), "{id}: effect");
    assert_eq!(f(ours, "p"), f(theirs, "p"), "{id}: p");
    assert_eq!(f(ours, "mdd"), f(theirs, "detectable"), "{id}: detectable");
    let way = |v: &str| match (v, ours["expect"].as_str()) {
        ("higher", "higher") | ("lower", "lower") => "holds".to_string(),
        ("higher", _) | ("lower", _) => "opposite".to_string(),
        (other, _) => other.to_string(),
    };
    assert_eq!(ours["verdict"], way(&theirs["verdict"]), "{id}: verdict");
}

/// The per-seed values (the mean over the rooms) of `measure` in `arm`, in seed order.
fn per_seed(rows: &[Row], arm: &str, measure: &str) -> Vec<f64> {
    (rows.iter())
        .filter(|r| r["arm"] == arm && r["measure"] == measure && r["room"].is_empty())
        .map(|r| f(r, "value"))
        .collect()
}

/// The tiny sizes both sides of a comparison run at.
const COMBINATION_SIZES: [&str; 6] = [
    "ga.population=8",
    "ga.generations=3",
    "trial.steps=120",
    "aem.epochs=10",
    "aem.test_runs=3",
    "rooms=[\"H\", \"square\"]",
];

/// studies/combination.toml is `reproduce --combination` as hypotheses: the same runs, each
/// behaviour comparison (baseline against TSK per setting and measure, the end spread read back
/// from the runs: the very values reproduce measures) and each claim difference (a difference
/// of two paired differences) with reproduce's effect, p, detectable difference and verdict.
#[test]
fn the_combination_study_file_says_what_reproduce_combination_says_of_the_same_runs() {
    let dir = tempfile::tempdir().unwrap();
    let sizes = "set = { ga = { population = 8, generations = 3 }, trial = { steps = 120 }, aem = { epochs = 10, test_runs = 3 }, rooms = [\"H\", \"square\"] }";
    let header = format!("seeds = 3\nbase_seeds = [1]\n{sizes}\n");
    let file = tiny_file(
        dir.path(),
        "combination.toml",
        &[("seeds = 20\nbase_seeds = [1, 11]\n", &header)],
    );
    let (rep, out) = (dir.path().join("reproduce"), dir.path().join("study"));
    reproduce("--combination", &rep, &COMBINATION_SIZES);
    study(&file, &out);
    let claims = read_csv(&out.join("claims.csv"));
    let rows = read_csv(&out.join("per_seed.csv"));
    let base = |combination: &str| match combination {
        "weighted-sum" => "sum",
        "weighted-squares" => "squares",
        other => panic!("{other}"),
    };
    let behaviour = read_csv(&rep.join("behaviour.csv"));
    assert_eq!(behaviour.len(), 2 * 2 * 5, "every measure of both settings");
    for r in &behaviour {
        let measure = match r["measure"].as_str() {
            "% optimal exploration" => "explores",
            "% homing" => "homing",
            "% battery usage" => "battery",
            "% recognition" => "recognition",
            "% end spread" => "spread",
            other => panic!("{other}"),
        };
        let setting = r["setting"].strip_suffix("-curiosity").unwrap();
        let id = format!("{measure}-{setting}-{}-vs-tsk", base(&r["combination"]));
        assert_claim_is(&claims, &id, r);
    }
    // The end spreads are reproduce's own, seed by seed.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(rep.join("summary.json")).unwrap()).unwrap();
    for (v, combination) in ["tsk", "sum", "squares"].iter().enumerate() {
        for (s, setting) in ["high", "low"].iter().enumerate() {
            let theirs: Vec<f64> = (summary["end_spreads"][v][s].as_array().unwrap().iter())
                .map(|x| x.as_f64().unwrap())
                .collect();
            let arm = format!("{setting}-{combination}");
            assert_eq!(per_seed(&rows, &arm, "end_spread_pct"), theirs, "{arm}");
        }
    }
    let differences = read_csv(&rep.join("claim_differences.csv"));
    assert_eq!(differences.len(), 2 * 4, "every claim under both baselines");
    for r in &differences {
        let claim = &r["claim"];
        let name = ["explores", "battery", "recognises", "returns home"]
            .iter()
            .zip(["explores", "battery", "recognition", "homing"])
            .find(|(k, _)| claim.contains(**k))
            .unwrap()
            .1;
        let id = format!("{name}-{}-vs-tsk", base(&r["combination"]));
        assert_claim_is(&claims, &id, r);
        // The effect under each combination: the mean of its per-seed high − low.
        let column = if name == "explores" {
            "exploration_pct".to_string()
        } else {
            format!("{name}_pct")
        };
        let effect = |c: &str| {
            let h = per_seed(&rows, &format!("high-{c}"), &column);
            let l = per_seed(&rows, &format!("low-{c}"), &column);
            let d: Vec<f64> = h.iter().zip(&l).map(|(h, l)| h - l).collect();
            fuzzymotiv::statistics::mean(&d)
        };
        let b = base(&r["combination"]);
        assert!(
            (effect(b) - f(r, "effect_combination")).abs() < 1e-9,
            "{id}"
        );
        assert!((effect("tsk") - f(r, "effect_tsk")).abs() < 1e-9, "{id}");
    }
}

/// The tiny sizes of the urgency study on two of the fetch rooms.
const URGENCY_SIZES: [&str; 6] = [
    "ga.population=16",
    "ga.generations=4",
    "trial.steps=400",
    "aem.epochs=10",
    "aem.test_runs=2",
    "rooms=[\"fetch-H\", \"fetch-square\"]",
];

/// studies/urgency.toml on `reproduce --urgency`'s runs: each seed's missions done are its
/// success rate, and its time to the goal is reproduce's (the mean step of the test runs that
/// arrived) with T = 400 for each test run that did not; the missions' comparisons have
/// reproduce's numbers.
#[test]
fn the_urgency_study_file_times_the_missions_reproduce_urgency_times_counting_t_for_none() {
    let dir = tempfile::tempdir().unwrap();
    let rooms = repo().join("rooms");
    let sizes = format!(
        "set = {{ ga = {{ population = 16, generations = 4 }}, trial = {{ steps = 400 }}, aem = {{ epochs = 10, test_runs = 2 }}, rooms = [{:?}, {:?}] }}",
        rooms.join("fetch-H.toml").display().to_string(),
        rooms.join("fetch-square.toml").display().to_string()
    );
    let header = "seeds = 3\nbase_seeds = [1]\n";
    let config = format!(
        "config = {:?}\n{sizes}",
        repo().join("configs/fetch.toml").display().to_string()
    );
    let file = tiny_file(
        dir.path(),
        "urgency.toml",
        &[
            ("seeds = 20\nbase_seeds = [1, 11]\n", header),
            ("config = \"../configs/fetch.toml\"", &config),
        ],
    );
    let (rep, out) = (dir.path().join("reproduce"), dir.path().join("study"));
    reproduce("--urgency", &rep, &URGENCY_SIZES);
    study(&file, &out);
    let rows = read_csv(&out.join("per_seed.csv"));
    let tests = 2.0 * 2.0; // two rooms, two test runs each
    let seeds = read_csv(&rep.join("urgency_seeds.csv"));
    assert_eq!(seeds.len(), 4 * 3);
    // Both kinds of test run are here: some arrived, some never did.
    let arrived = (seeds.iter())
        .filter(|s| !s["time_to_goal"].is_empty())
        .count();
    let all = (seeds.iter())
        .filter(|s| f(s, "success_pct") == 100.0)
        .count();
    assert!(
        arrived > 0 && all < seeds.len(),
        "{arrived} of {} seeds arrived",
        seeds.len()
    );
    for arm in ["urgency-0.0", "urgency-0.1", "urgency-0.2", "urgency-0.3"] {
        let theirs: Vec<&Row> = seeds.iter().filter(|s| s["setting"] == arm).collect();
        let done = per_seed(&rows, arm, "mission_done_pct");
        let time = per_seed(&rows, arm, "time_to_goal");
        assert_eq!((done.len(), time.len()), (3, 3), "{arm}");
        for ((s, done), time) in theirs.iter().zip(done).zip(time) {
            let at = format!("{arm}, seed {}", s["seed"]);
            assert!((done - f(s, "success_pct")).abs() < 1e-9, "{at}: {done}");
            let arrived = (tests * done / 100.0).round();
            let steps = if s["time_to_goal"].is_empty() {
                0.0
            } else {
                f(s, "time_to_goal") * arrived
            };
            let want = (steps + 400.0 * (tests - arrived)) / tests;
            assert!((time - want).abs() < 1e-9, "{at}: {time} against {want}");
        }
    }
    let claims = read_csv(&out.join("claims.csv"));
    let success = read_csv(&rep.join("urgency.csv"));
    let success: Vec<&Row> = success
        .iter()
        .filter(|r| r["measure"] == "% success")
        .collect();
    assert_eq!(success.len(), 4);
    for r in success {
        let id = format!("mission_done-{:.1}-{:.1}", f(r, "from"), f(r, "to"));
        assert_claim_is(&claims, &id, r);
    }
}

/// studies/orientation.toml, a study without hypotheses, reports each arm's measures: over the
/// same runs, per arm and room, the seeds, means and standard deviations that the merge of
/// `reproduce --orientation` (`fuzzymotiv merge`, the same code) writes into aggregate.csv.
#[test]
fn the_orientation_study_file_reports_each_arms_measures_as_the_orientation_merge_does() {
    let dir = tempfile::tempdir().unwrap();
    let sizes = "set = { ga = { population = 8, generations = 3 }, trial = { steps = 120 }, aem = { epochs = 10, test_runs = 3 }, rooms = [\"H\", \"square\"], fitness = { orientation = \"online\" } }";
    let file = tiny_file(
        dir.path(),
        "orientation.toml",
        &[
            ("seeds = 5\n", "seeds = 3\n"),
            (
                "set = { ga = { population = 100, generations = 100 }, fitness = { orientation = \"online\" } }",
                sizes,
            ),
        ],
    );
    let out = dir.path().join("study");
    study(&file, &out);
    // No hypotheses: nothing to claim, per room or in a forest; each arm's measures only.
    for none in ["claims.csv", "rooms.csv", "forest.svg", "agreement.csv"] {
        assert!(!out.join(none).exists(), "{none}");
    }
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(report.contains("## Measures per arm") && !report.contains("## Claims"));
    assert!(report.contains("3 paired seeds (base seed 1):"), "{report}");
    ok(&["merge", out.to_str().unwrap()]);
    let aggregate = read_csv(&out.join("aggregate.csv"));
    let arms = read_csv(&out.join("arms.csv"));
    assert_eq!(aggregate.len(), 3 * 2, "three arms in two rooms");
    for a in &aggregate {
        for metric in [
            "average_fitness",
            "exploration_pct",
            "recognition_pct",
            "battery_pct",
            "homing_pct",
        ] {
            let ours = (arms.iter())
                .find(|m| {
                    m["arm"] == a["setting"] && m["room"] == a["room"] && m["measure"] == metric
                })
                .unwrap_or_else(|| panic!("arms.csv: no {metric} of {a:?}"));
            let at = format!("{} {} {metric}", a["setting"], a["room"]);
            assert_eq!(ours["seeds"], a["n"], "{at}");
            for (mine, theirs) in [("mean", "_mean"), ("sd", "_std")] {
                let want = f(a, &format!("{metric}{theirs}"));
                // aggregate.csv writes six decimals.
                assert!((f(ours, mine) - want).abs() <= 5e-7, "{at}: {mine}");
            }
        }
    }
}
