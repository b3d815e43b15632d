//! Every committed study's verdicts follow from its own records by the rule it states: an
//! effect within the minimum detectable difference (MDD) is "inconclusive" whatever p;
//! otherwise p ≥ α is "not significant", and p < α "holds" (or "higher"/"lower") or "opposite"
//! by the effect's sign. No verdict is looked up: the paper's studies are recomputed from their
//! per-seed tables, every other verdict in `docs/results` is checked against its own row, and
//! `fuzzymotiv claims` recomputes a committed study's claims to the committed bytes.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use common::Fm;
use fuzzymotiv::statistics::{Expect, Settings, Verdict, paired};

/// α of every shipped study.
const ALPHA: f64 = 0.05;

fn results() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/results")
}

type Row = BTreeMap<String, String>;

/// The rows of a CSV file as maps from column to cell.
fn rows(path: &Path) -> Vec<Row> {
    let mut reader =
        csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
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

/// A cell as a number; `None` when empty.
fn number(row: &Row, column: &str) -> Option<f64> {
    let cell = row.get(column)?;
    (!cell.is_empty()).then(|| {
        cell.parse()
            .unwrap_or_else(|e| panic!("{column} `{cell}`: {e}"))
    })
}

/// The paper's comparison claims: the per-seed column each compares and the direction claimed.
const CLAIMS: [(&str, &str, Expect); 4] = [
    (
        "high curiosity explores more than low curiosity",
        "exploration_pct",
        Expect::Higher,
    ),
    (
        "high curiosity uses more battery",
        "battery_pct",
        Expect::Higher,
    ),
    (
        "high curiosity recognises rooms better",
        "recognition_pct",
        Expect::Higher,
    ),
    (
        "high curiosity returns home less (lower % homing)",
        "homing_pct",
        Expect::Lower,
    ),
];

/// The stated rule on an effect `d`, its p and its MDD.
fn rule(d: f64, p: f64, mdd: Option<f64>, expect: Expect) -> Verdict {
    if mdd.is_some_and(|m| d.abs() < m) {
        Verdict::Inconclusive
    } else {
        Verdict::of(d, p, expect, ALPHA)
    }
}

/// Per seed (in the file's order), the mean over rooms of `column` of a `table*_seeds.csv`.
fn seed_means(path: &Path, column: &str) -> Vec<f64> {
    let mut by_seed: Vec<(String, Vec<f64>)> = Vec::new();
    for r in rows(path) {
        let v = number(&r, column).unwrap();
        match by_seed.iter_mut().find(|(s, _)| *s == r["seed"]) {
            Some((_, values)) => values.push(v),
            None => by_seed.push((r["seed"].clone(), vec![v])),
        }
    }
    by_seed
        .iter()
        .map(|(_, v)| fuzzymotiv::statistics::mean(v))
        .collect()
}

/// The studies of the paper's two settings whose per-seed tables are committed.
const PAPER_STUDIES: [&str; 4] = [
    "five-seed",
    "ten-seed",
    "twenty-seed",
    "twenty-seed-base-11",
];

#[test]
fn the_paper_studies_verdicts_are_recomputed_from_their_per_seed_tables() {
    for study in PAPER_STUDIES {
        let dir = results().join(study);
        let claims = rows(&dir.join("claims.csv"));
        let first_seed: u64 = rows(&dir.join("table1_seeds.csv"))[0]["seed"]
            .parse()
            .unwrap();
        for (claim, column, expect) in CLAIMS {
            let high = seed_means(&dir.join("table1_seeds.csv"), column);
            let low = seed_means(&dir.join("table2_seeds.csv"), column);
            let options = Settings {
                alpha: ALPHA,
                seed: first_seed,
                ..Settings::default()
            };
            let c = paired(&high, &low, &options).unwrap();
            let row = claims.iter().find(|r| r["claim"] == claim).unwrap();
            let at = format!("{study}/claims.csv, \"{claim}\"");
            // The tables keep six decimals: the effect to that, p and MDD to a little more.
            assert!(
                (c.difference - number(row, "difference").unwrap()).abs() < 1e-5,
                "{at}"
            );
            assert!((c.p - number(row, "p").unwrap()).abs() < 5e-3, "{at}");
            assert!(
                (c.mdd.unwrap() - number(row, "mdd").unwrap()).abs() < 1e-4,
                "{at}"
            );
            let verdict = c.verdict_with_power(expect).label();
            assert_eq!(row["verdict"], verdict, "{at}: recomputed from the seeds");
            assert_eq!(row["holds"] == "true", verdict == "holds", "{at}: holds");
        }
    }
}

/// The direction a row claims: the paper's claims by their own table, every other comparison
/// ("higher"/"lower" verdicts) a − b > 0.
fn expectation(row: &Row) -> Expect {
    let claim = row.get("claim").map(String::as_str);
    CLAIMS
        .iter()
        .find(|(c, _, _)| Some(*c) == claim)
        .map_or(Expect::Higher, |&(_, _, e)| e)
}

/// The columns of a file's effect, p and MDD, and of the verdict they decide; `None` for a file
/// without a verdict of that rule.
fn rule_columns(header: &Row) -> Option<[&'static str; 4]> {
    let has = |c: &str| header.contains_key(c);
    let effect = ["difference", "effect"].into_iter().find(|c| has(c))?;
    let mdd = ["mdd", "detectable"].into_iter().find(|c| has(c))?;
    // The replication's pooled verdict is the rule's; its last column is its own rule's
    // (checked by the next test).
    let verdict = ["verdict_pooled", "verdict"].into_iter().find(|c| has(c))?;
    has("p").then_some([effect, "p", mdd, verdict])
}

/// Every CSV file under `dir`, recursively.
fn csv_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            csv_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "csv") {
            out.push(path);
        }
    }
}

#[test]
fn every_committed_verdict_follows_the_stated_rule_from_its_own_row() {
    let mut files = Vec::new();
    csv_files(&results(), &mut files);
    let mut checked = 0;
    for file in files {
        for row in rows(&file) {
            let Some([effect, p, mdd, verdict]) = rule_columns(&row) else {
                break;
            };
            let (Some(d), Some(p)) = (number(&row, effect), number(&row, p)) else {
                continue; // a row without a comparison (Fig. 6's checks, too few seeds)
            };
            let Some(mdd) = number(&row, mdd) else {
                continue; // Fig. 6's curve tests: no MDD, a band or a rise
            };
            let said = &row[verdict];
            if said.is_empty() {
                continue; // a comparison reported without a verdict (search strength's trend)
            }
            let expected = rule(d, p, Some(mdd), expectation(&row));
            let ok = said == expected.label() || said == expected.direction_label();
            assert!(
                ok,
                "{}: {row:?} says {said}, the rule {expected:?}",
                file.display()
            );
            checked += 1;
        }
    }
    // The paper's four studies, the replication's, search strength, ablation, combination,
    // urgency: well over a hundred verdicts.
    assert!(checked > 100, "only {checked} verdicts checked");
}

#[test]
fn the_replications_verdict_is_the_pooled_one_unless_its_base_seeds_disagree_at_the_edge() {
    let dir = results().join("replication");
    for row in rows(&dir.join("replication.csv")) {
        let (a, b, pooled) = (&row["verdict_a"], &row["verdict_b"], &row["verdict_pooled"]);
        let edge = row["at_edge"] == "true";
        if let (Some(d), Some(mdd)) = (number(&row, "effect"), number(&row, "mdd")) {
            // At the edge: the pooled effect within what one study of the base seeds' size
            // detects, which is at least the pooled MDD.
            assert!(!edge || d.abs() < mdd * 2f64.sqrt() + 1e-9, "{row:?}");
        }
        let expected = if edge && (a != pooled || b != pooled) {
            "inconclusive"
        } else {
            pooled.as_str()
        };
        assert_eq!(row["verdict"], expected, "{row:?}");
    }
    // Each base seed's verdicts are that study's own: the committed studies of the same seeds.
    for (base, study) in [
        ("base-1", "twenty-seed"),
        ("base-11", "twenty-seed-base-11"),
    ] {
        let mine = rows(&dir.join(base).join("claims.csv"));
        let study = rows(&results().join(study).join("claims.csv"));
        assert_eq!(mine, study, "replication/{base}");
    }
}

#[test]
fn claims_recomputes_a_committed_study_to_its_committed_verdicts() {
    for study in PAPER_STUDIES {
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join("claims");
        Fm::new(["claims"])
            .arg(results().join(study))
            .arg("--out")
            .arg(&out)
            .ok();
        let again = std::fs::read_to_string(out.join("claims.csv")).unwrap();
        let committed = std::fs::read_to_string(results().join(study).join("claims.csv")).unwrap();
        assert_eq!(again, committed, "{study}/claims.csv");
    }
}

#[test]
fn the_twenty_seed_studys_battery_claim_holds_by_its_own_data() {
    // p 0.005 < α and +2.88 points ≥ its MDD 2.63: the rule says "holds", and so does the
    // study, whatever another base seed finds (the replication's report says that).
    let claims = rows(&results().join("twenty-seed/claims.csv"));
    let battery = claims
        .iter()
        .find(|r| r["claim"] == "high curiosity uses more battery")
        .unwrap();
    assert_eq!(battery["verdict"], "holds");
    assert_eq!(battery["holds"], "true");
}
