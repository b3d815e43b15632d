//! `reproduce --combination`: the study under the TSK and under each baseline combination,
//! the claims under each, and the behaviour of each baseline against the TSK.

mod common;

use common::{Fm, stderr, stdout};

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
/// the TSK for both settings and the four measures; the summary and the CSV say the same.
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
    assert_eq!(rows.len(), 2 * 2 * 4, "{rows:?}");
    let csv = read(out.join("behaviour.csv"));
    assert_eq!(csv.lines().count(), 1 + rows.len());
    assert!(md.contains("| tsk | the paper's TSK rule base |"), "{md}");
    let svg = read(out.join("behaviour.svg"));
    assert!(svg.contains("% optimal exploration") && svg.contains("weighted-sum − TSK"));
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
