//! The claims the default study reports "inconclusive" because they are at the edge of its
//! power (`fuzzymotiv_io::render::power`) are the ones the committed replication records
//! (`docs/results/replication`) say are, with the same numbers.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use common::Fm;

use fuzzymotiv_io::render::power::{AT_THE_EDGE, REPLICATED, REPLICATION_BASE_SEEDS};

fn results() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/results/replication")
}

/// The rows of a CSV file as maps from column to cell.
fn rows(path: &Path) -> Vec<BTreeMap<String, String>> {
    let mut reader = csv::Reader::from_path(path).unwrap();
    let header = reader.headers().unwrap().clone();
    reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            header
                .iter()
                .map(String::from)
                .zip(r.iter().map(String::from))
                .collect()
        })
        .collect()
}

fn number(cell: &str) -> f64 {
    cell.parse().unwrap_or_else(|e| panic!("`{cell}`: {e}"))
}

#[test]
fn the_claims_at_the_edge_are_the_committed_replications() {
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(results().join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["seeds_needed"], serde_json::Value::Null);
    assert_eq!(summary["model"], REPLICATED.model);
    assert_eq!(summary["population"], REPLICATED.population);
    assert_eq!(summary["generations"], REPLICATED.generations);
    assert_eq!(summary["quick"], REPLICATED.quick);
    assert_eq!(
        summary["overrides"].as_array().unwrap().is_empty(),
        !REPLICATED.overrides
    );
    assert_eq!(
        summary["seeds"].as_u64().unwrap() * 2,
        REPLICATED.seeds as u64
    );
    assert_eq!(
        summary["base_seeds"],
        serde_json::json!(REPLICATION_BASE_SEEDS)
    );

    let at_edge: Vec<_> = rows(&results().join("replication.csv"))
        .into_iter()
        .filter(|r| r["at_edge"] == "true")
        .collect();
    let names: Vec<&str> = at_edge.iter().map(|r| r["claim"].as_str()).collect();
    let ours: Vec<&str> = AT_THE_EDGE.iter().map(|e| e.claim).collect();
    assert_eq!(names, ours);
    let mdd_of = |base: u64, claim: &str| {
        let file = results().join(format!("base-{base}/claims.csv"));
        number(
            &rows(&file)
                .into_iter()
                .find(|r| r["claim"] == claim)
                .unwrap()["mdd"],
        )
    };
    for (row, edge) in at_edge.iter().zip(AT_THE_EDGE) {
        assert_eq!(number(&row["effect"]), edge.pooled_effect, "{}", edge.claim);
        let [a, b] = REPLICATION_BASE_SEEDS.map(|s| mdd_of(s, edge.claim));
        assert_eq!(a.max(b), edge.one_study_mdd, "{}", edge.claim);
        assert!(edge.pooled_effect.abs() <= edge.one_study_mdd);
    }
}

/// The claims of the committed default study (base seed 1, twenty seeds), recomputed by
/// `fuzzymotiv claims` from its summary.json with its marks, and with them taken away: the
/// marked study reports the claims at the edge "inconclusive" and keeps its own verdicts in the
/// note; without marks (another design, an older file) the own verdicts stand.
#[test]
fn claims_keep_a_studys_marks_at_the_edge() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/results/twenty-seed");
    let text = std::fs::read_to_string(source.join("summary.json")).unwrap();
    let mut summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let verdicts = |summary: &serde_json::Value, name: &str| {
        let dir = tmp.path().join(name);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("summary.json"), summary.to_string()).unwrap();
        let out = tmp.path().join(format!("{name}-claims"));
        Fm::new(["claims", dir.to_str().unwrap()]).out(&out).ok();
        let md = std::fs::read_to_string(out.join("claims.md")).unwrap();
        let by_claim: BTreeMap<String, String> = rows(&out.join("claims.csv"))
            .into_iter()
            .map(|r| (r["claim"].clone(), r["verdict"].clone()))
            .collect();
        (by_claim, md)
    };
    let battery = "high curiosity uses more battery";
    let homing = "high curiosity returns home less (lower % homing)";

    let note = serde_json::json!({
        "own_verdict": "holds", "pooled_effect": AT_THE_EDGE[1].pooled_effect,
        "one_study_mdd": AT_THE_EDGE[1].one_study_mdd, "pooled_seeds": 40, "base_seeds": [1, 11]
    });
    for c in summary["claims"].as_array_mut().unwrap() {
        if c["claim"] == battery {
            c["at_edge"] = note.clone();
        }
    }
    let (marked, md) = verdicts(&summary, "marked");
    assert_eq!(marked[battery], "inconclusive");
    assert_eq!(marked[homing], "holds");
    assert!(md.contains("At the edge of this study's power"), "{md}");
    assert!(md.contains("this study's own test: holds"), "{md}");

    for c in summary["claims"].as_array_mut().unwrap() {
        c.as_object_mut().unwrap().remove("at_edge");
    }
    let (own, md) = verdicts(&summary, "unmarked");
    assert_eq!(own[battery], "holds", "base seed 1's own test");
    assert_eq!(own[homing], "holds");
    assert!(!md.contains("At the edge"), "{md}");
}
