//! Every committed study's verdicts follow from its own records by the rule it states: an
//! effect within the minimum detectable difference (MDD) is "inconclusive" whatever p;
//! otherwise p ≥ α is "not significant", and p < α "holds" (or "higher"/"lower") or "opposite"
//! by the effect's sign. No verdict is looked up: the paper's studies are recomputed from their
//! per-seed tables, every other verdict in `docs/results` is checked against its own row, and
//! `fuzzymotiv claims` recomputes a committed study's claims to the committed bytes.

use crate::common;

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
    let checked = check_verdicts(&results());
    // The paper's four studies, the replication's, search strength, ablation, combination,
    // urgency: well over a hundred verdicts.
    assert!(checked > 100, "only {checked} verdicts checked");
}

/// Every verdict in the CSV files under `root` checked against its own row by the rule its
/// study states (a study of one's own: the analysis its study.json declares); how many.
fn check_verdicts(root: &Path) -> usize {
    let mut files = Vec::new();
    csv_files(root, &mut files);
    let mut checked = 0;
    for file in files {
        if let Some(study) = declared(&file) {
            checked += check_study_file(&file, &study);
            continue;
        }
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
    checked
}

/// The study.json of a study of one's own (`fuzzymotiv study`) whose claims.csv or rooms.csv
/// `file` is: its declared analysis and typed hypotheses.
fn declared(file: &Path) -> Option<serde_json::Value> {
    let name = file.file_name()?.to_str()?;
    if !["claims.csv", "rooms.csv", "agreement.csv"].contains(&name) {
        return None;
    }
    let text = std::fs::read_to_string(file.parent()?.join("study.json")).ok()?;
    serde_json::from_str(&text).ok()
}

/// A result's margin in its hypothesis's way: the effect (negated for `lower`), a range's
/// distance to its nearer bound (negative outside).
fn margin(h: &serde_json::Value, effect: f64) -> f64 {
    match h["kind"].as_str().unwrap() {
        "range" => {
            let above = effect - h["min"].as_f64().unwrap();
            let below = h["max"].as_f64().unwrap() - effect;
            if above < 0.0 {
                above
            } else if below < 0.0 {
                below
            } else {
                above.min(below)
            }
        }
        _ if h["expect"] == "lower" => -effect,
        _ => effect,
    }
}

/// A study's claims.csv (or rooms.csv, agreement.csv) by the analysis its study.json declares:
/// each group of tests (a scope's hypotheses; a hypothesis's rooms in a scope; the hypotheses on
/// a base seed's first n seeds) has its p Holm-adjusted when
/// Holm is declared over it (recomputed), and each verdict follows from the margin, the
/// adjusted p and the detectable difference by the declared α and rule.
fn check_study_file(file: &Path, study: &serde_json::Value) -> usize {
    let a = &study["analysis"];
    let alpha = a["alpha"].as_f64().unwrap();
    let rooms = file.file_name().is_some_and(|n| n == "rooms.csv");
    let holm = a["holm"] == if rooms { "rooms" } else { "hypotheses" };
    let hypothesis = |id: &str| {
        (study["hypotheses"].as_array().unwrap().iter())
            .find(|h| h["id"] == id)
            .unwrap_or_else(|| panic!("{}: no hypothesis {id}", file.display()))
    };
    let all = rows(file);
    let agreement = file.file_name().is_some_and(|n| n == "agreement.csv");
    let group_of = |r: &Row| -> String {
        match (rooms, agreement) {
            (true, _) => format!("{} {}", r["scope"], r["id"]),
            (_, true) => format!("first {} seeds of base={}", r["seeds"], r["base_seed"]),
            _ => r["scope"].clone(),
        }
    };
    let mut groups: Vec<String> = Vec::new();
    for r in &all {
        if !groups.contains(&group_of(r)) {
            groups.push(group_of(r));
        }
    }
    for scope in &groups {
        let group: Vec<&Row> = all.iter().filter(|r| &group_of(r) == scope).collect();
        let p: Vec<f64> = group.iter().map(|r| number(r, "p").unwrap()).collect();
        let adjusted = if holm {
            fuzzymotiv::statistics::holm(&p)
        } else {
            p
        };
        for (r, p_adj) in group.iter().zip(adjusted) {
            let at = format!("{}: {} ({scope})", file.display(), r["id"]);
            assert!(
                (number(r, "p_adjusted").unwrap() - p_adj).abs() < 1e-12,
                "{at}: adjusted p"
            );
            let m = margin(hypothesis(&r["id"]), number(r, "effect").unwrap());
            let below = number(r, "mdd").is_some_and(|mdd| m.abs() < mdd);
            let expected = if a["rule"] == "power" && below {
                Verdict::Inconclusive
            } else {
                Verdict::of(m, p_adj, Expect::Higher, alpha)
            };
            assert_eq!(r["verdict"], expected.label(), "{at}: the declared rule");
        }
    }
    all.len()
}

/// A study of one's own is checked by the analysis it declares, not the paper's: Holm over its
/// hypotheses (two claims at p 0.03 and 0.04, each alone significant, are not at their
/// adjusted 0.06), a `lower` comparison holding on a negative effect, a range by its distance
/// to its nearer bound; a verdict written against that rule is caught.
#[test]
fn a_study_of_ones_own_is_checked_by_its_declared_analysis() {
    let dir = tempfile::tempdir().unwrap();
    let study = serde_json::json!({
        "analysis": { "alpha": 0.05, "rule": "power", "holm": "hypotheses" },
        "hypotheses": [
            { "kind": "compare", "id": "up", "expect": "higher" },
            { "kind": "compare", "id": "down", "expect": "lower" },
            { "kind": "range", "id": "band", "min": 0.05, "max": 0.15 },
        ],
    });
    std::fs::write(dir.path().join("study.json"), study.to_string()).unwrap();
    let claims = |first: &str| {
        format!(
            "id,scope,effect,p,p_adjusted,mdd,verdict\n\
             up,pooled,5.0,0.03,0.06,1.0,{first}\n\
             down,pooled,-5.0,0.04,0.06,1.0,not significant\n\
             band,pooled,0.1,0.001,0.003,0.01,holds\n"
        )
    };
    std::fs::write(dir.path().join("claims.csv"), claims("not significant")).unwrap();
    assert_eq!(check_verdicts(dir.path()), 3);
    std::fs::write(dir.path().join("claims.csv"), claims("holds")).unwrap();
    let caught = std::panic::catch_unwind(|| check_verdicts(dir.path()));
    assert!(caught.is_err(), "a verdict on the unadjusted p is caught");
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

/// The transfer study's per-seed values (transfer.csv): for (setting, measure, world), each
/// seed's mean over its rooms, in the file's order of seeds; and each setting's seeds.
type TransferSeeds = (BTreeMap<Key, Vec<f64>>, BTreeMap<String, Vec<u64>>);

/// (setting, measure, world).
type Key = (String, String, String);

fn transfer_seed_means(path: &Path) -> TransferSeeds {
    let mut rooms: BTreeMap<Key, Vec<(String, Vec<f64>)>> = BTreeMap::new();
    let mut seeds: BTreeMap<String, Vec<u64>> = BTreeMap::new();
    for r in rows(path) {
        let seed: u64 = r["seed"].parse().unwrap();
        let list = seeds.entry(r["setting"].clone()).or_default();
        if list.last() != Some(&seed) {
            list.push(seed);
        }
        for world in ["fuzzymotiv", "enki"] {
            let Some(v) = number(&r, world) else { continue };
            let key = (
                r["setting"].clone(),
                r["measure"].clone(),
                world.to_string(),
            );
            let per_seed = rooms.entry(key).or_default();
            match per_seed.last_mut() {
                Some((s, values)) if *s == r["seed"] => values.push(v),
                _ => per_seed.push((r["seed"].clone(), vec![v])),
            }
        }
    }
    let means = rooms
        .into_iter()
        .map(|(k, v)| {
            (
                k,
                v.iter()
                    .map(|(_, v)| fuzzymotiv::statistics::mean(v))
                    .collect(),
            )
        })
        .collect();
    (means, seeds)
}

/// A recomputed comparison against its committed row: every number bit for bit (the records
/// keep each f64 at full precision) and the verdict by the stated rule.
fn assert_row_is(row: &Row, c: &fuzzymotiv::statistics::Comparison, verdict: &str, at: &str) {
    for (column, value) in [
        ("difference", c.difference),
        ("ci_low", c.ci_low),
        ("ci_high", c.ci_high),
        ("p", c.p),
        ("detectable", c.mdd.unwrap()),
    ] {
        assert_eq!(number(row, column), Some(value), "{at}: {column}");
    }
    assert_eq!(row["verdict"], verdict, "{at}: verdict");
}

/// A transfer study's records (`dir`: comparison.csv and claims.csv from transfer.csv, as
/// scripts/transfer_study.sh writes them) recomputed with the engine's statistics.
fn assert_transfer_records_are_recomputed(records: &str) {
    let dir = results().join(records);
    let (means, seeds) = transfer_seed_means(&dir.join("transfer.csv"));
    let settings = |first: u64| Settings {
        alpha: ALPHA,
        seed: first,
        ..Settings::default()
    };
    let comparison = rows(&dir.join("comparison.csv"));
    assert!(comparison.len() >= 10, "{} comparisons", comparison.len());
    for row in &comparison {
        let (setting, measure) = (&row["setting"], &row["measure"]);
        let get = |w: &str| &means[&(setting.clone(), measure.clone(), w.to_string())];
        let (sim, enki) = (get("fuzzymotiv"), get("enki"));
        let c = paired(enki, sim, &settings(seeds[setting][0])).unwrap();
        assert_eq!(number(row, "mean_fuzzymotiv"), Some(c.mean_b));
        assert_eq!(number(row, "mean_enki"), Some(c.mean_a));
        let verdict = rule(c.difference, c.p, c.mdd, Expect::Higher).direction_label();
        assert_row_is(
            row,
            &c,
            verdict,
            &format!("{records}/comparison.csv {setting} {measure}"),
        );
    }
    let claims = rows(&dir.join("claims.csv"));
    let homing = CLAIMS[3].0;
    for world in ["fuzzymotiv", "enki"] {
        let row = claims
            .iter()
            .find(|r| r["world"] == world && r["claim"] == homing);
        assert!(
            row.is_some(),
            "{records}/claims.csv has no homing claim in {world}"
        );
    }
    for row in &claims {
        let (claim, column, expect) = CLAIMS.iter().find(|c| c.0 == row["claim"]).unwrap();
        let get = |s: &str| &means[&(s.to_string(), column.to_string(), row["world"].clone())];
        let first = seeds["high-curiosity"][0];
        let c = paired(
            get("high-curiosity"),
            get("low-curiosity"),
            &settings(first),
        )
        .unwrap();
        let verdict = rule(c.difference, c.p, c.mdd, *expect).label();
        assert_row_is(
            row,
            &c,
            verdict,
            &format!("{records}/claims.csv {} {claim}", row["world"]),
        );
    }
}

#[test]
fn the_transfer_studys_comparisons_and_claims_are_recomputed_from_its_per_seed_records() {
    assert_transfer_records_are_recomputed("transfer");
}

#[test]
fn the_epuck2_transfer_studys_comparisons_and_claims_are_recomputed_from_its_per_seed_records() {
    assert_transfer_records_are_recomputed("transfer/epuck2");
}

#[test]
fn the_thymio2_transfer_studys_comparisons_and_claims_are_recomputed_from_its_per_seed_records() {
    assert_transfer_records_are_recomputed("transfer/thymio2");
}

#[test]
fn the_thymio2_transfer_study_is_in_its_scaled_rooms() {
    // The Thymio II's study runs in configs/thymio2.toml's rooms (rooms/thymio2/, the paper's
    // scaled 3×), not the paper's own: every room of its records is a scaled one, all five there.
    let rows = rows(&results().join("transfer/thymio2/transfer.csv"));
    let rooms: std::collections::BTreeSet<&str> = rows.iter().map(|r| r["room"].as_str()).collect();
    let scaled = ["H-x3", "L-x3", "T-x3", "rectangle-x3", "square-x3"];
    assert_eq!(rooms.into_iter().collect::<Vec<_>>(), scaled);
}

/// A transfer study's fuzzymotiv column (`records`/transfer.csv), measured from the runs' test
/// runs simulated again by the function that measures Enki's logs, is the study's own per-seed
/// tables (`study`/table1_seeds.csv, table2_seeds.csv; six decimals), and so its claims in
/// fuzzymotiv are the study's claims.csv, number for number.
fn assert_simulator_side_is_the_studys(records: &str, study_dir: &str) {
    let transfer = rows(&results().join(records).join("transfer.csv"));
    let mut checked = 0;
    for (setting, table) in [
        ("high-curiosity", "table1_seeds.csv"),
        ("low-curiosity", "table2_seeds.csv"),
    ] {
        for study in rows(&results().join(study_dir).join(table)) {
            for measure in [
                "exploration_pct",
                "homing_pct",
                "battery_pct",
                "recognition_pct",
            ] {
                let row = transfer.iter().find(|r| {
                    r["setting"] == setting
                        && r["seed"] == study["seed"]
                        && r["room"] == study["room"]
                        && r["measure"] == measure
                });
                let Some(row) = row else { continue };
                let (mine, theirs) = (number(row, "fuzzymotiv"), number(&study, measure));
                let at = format!(
                    "{setting} seed {} {} {measure}",
                    study["seed"], study["room"]
                );
                assert!((mine.unwrap() - theirs.unwrap()).abs() < 1e-5, "{at}");
                checked += 1;
            }
        }
    }
    assert!(checked >= 40, "only {checked} values checked");
    // Hence the claims in fuzzymotiv are the study's own, number for number.
    let study = rows(&results().join(study_dir).join("claims.csv"));
    for row in rows(&results().join(records).join("claims.csv")) {
        if row["world"] != "fuzzymotiv" {
            continue;
        }
        let theirs = study.iter().find(|r| r["claim"] == row["claim"]).unwrap();
        let at = format!("{records}/claims.csv, fuzzymotiv, \"{}\"", row["claim"]);
        for (mine, their) in [
            ("difference", "difference"),
            ("p", "p"),
            ("detectable", "mdd"),
        ] {
            let (a, b) = (number(&row, mine).unwrap(), number(theirs, their).unwrap());
            assert!(
                (a - b).abs() < 1e-9,
                "{at}: {mine} {a} against the study's {b}"
            );
        }
        assert_eq!(row["verdict"], theirs["verdict"], "{at}");
    }
}

#[test]
fn the_transfer_studys_simulator_side_is_the_ten_seed_studys_test_runs() {
    // The Khepera's transfer study reuses the ten-seed study's runs.
    assert_simulator_side_is_the_studys("transfer", "ten-seed");
}

#[test]
fn the_epuck2_transfer_studys_simulator_side_is_its_studys_test_runs() {
    // The e-puck2's study: `reproduce --set robot=epuck2`, its records kept in transfer/epuck2/study.
    assert_simulator_side_is_the_studys("transfer/epuck2", "transfer/epuck2/study");
}

#[test]
fn the_thymio2_transfer_studys_simulator_side_is_its_studys_test_runs() {
    assert_simulator_side_is_the_studys("transfer/thymio2", "transfer/thymio2/study");
}

/// A pair of transfer studies of the same seeds (`b`/pair.csv, `transfer_study pair`): each row
/// recomputed from the two studies' transfer.csv — b against a paired by seed in Enki, in
/// fuzzymotiv and in |Enki − fuzzymotiv| — every number bit for bit, the verdict by the rule.
fn assert_pair_is_recomputed(a: &str, b: &str) {
    let (means_a, seeds_a) = transfer_seed_means(&results().join(a).join("transfer.csv"));
    let (means_b, seeds_b) = transfer_seed_means(&results().join(b).join("transfer.csv"));
    assert_eq!(seeds_a, seeds_b, "{a} and {b} are not of the same seeds");
    let values = |means: &BTreeMap<Key, Vec<f64>>, setting: &str, measure: &str, world: &str| {
        let get =
            |w: &str| means[&(setting.to_string(), measure.to_string(), w.to_string())].clone();
        if world != "gap" {
            return get(world);
        }
        let (sim, enki) = (get("fuzzymotiv"), get("enki"));
        sim.iter().zip(&enki).map(|(s, e)| (e - s).abs()).collect()
    };
    let pair = rows(&results().join(b).join("pair.csv"));
    assert!(pair.len() >= 30, "{b}/pair.csv: {} rows", pair.len());
    for row in &pair {
        let (setting, measure, world) = (&row["setting"], &row["measure"], &row["world"]);
        let va = values(&means_a, setting, measure, world);
        let vb = values(&means_b, setting, measure, world);
        let options = Settings {
            alpha: ALPHA,
            seed: seeds_a[setting][0],
            ..Settings::default()
        };
        let c = paired(&vb, &va, &options).unwrap();
        assert_eq!(number(row, "mean_a"), Some(c.mean_b));
        assert_eq!(number(row, "mean_b"), Some(c.mean_a));
        let verdict = rule(c.difference, c.p, c.mdd, Expect::Higher).direction_label();
        assert_row_is(
            row,
            &c,
            verdict,
            &format!("{b}/pair.csv {setting} {measure} {world}"),
        );
    }
}

#[test]
fn the_randomised_robots_in_enki_are_recomputed_from_both_studies_per_seed_records() {
    assert_pair_is_recomputed("transfer", "transfer/randomised");
    assert_transfer_records_are_recomputed("transfer/randomised");
    assert_simulator_side_is_the_studys("transfer/randomised", "transfer/randomised/study");
}

#[test]
fn the_enki_calibrated_robots_in_enki_are_recomputed_from_both_studies_per_seed_records() {
    assert_pair_is_recomputed("transfer", "transfer/enki-table");
    assert_transfer_records_are_recomputed("transfer/enki-table");
    assert_simulator_side_is_the_studys("transfer/enki-table", "transfer/enki-table/study");
}

#[test]
fn the_readings_figures_fuzzymotiv_curves_are_the_engines_readings_now() {
    // docs/results/transfer/readings.csv (examples/readings_vs_distance.rs): each robot's front
    // sensor head-on to its room's east wall. Its fuzzymotiv rows must be what the engine reads
    // today, so the figure of the gap cannot go stale.
    use fuzzymotiv::simulation::Pose;
    let root = results().join("../..");
    let file = |path: &str| format!("\"{}\"", root.join(path).display());
    let square = ["rooms=[\"square\"]".to_string(), "aem.enabled=false".into()];
    let table = format!(
        "trial.sensor_table={}",
        file("configs/sensors/khepera-enki.toml")
    );
    let thymio_rooms = format!("rooms=[{}]", file("rooms/thymio2/square.toml"));
    let probes: [(&str, &str, Vec<String>, usize); 4] = [
        ("khepera", "fuzzymotiv (robot file)", square.to_vec(), 2),
        (
            "khepera",
            "fuzzymotiv (table calibrated in Enki)",
            [&square[..], &[table]].concat(),
            2,
        ),
        (
            "epuck2",
            "fuzzymotiv (robot file)",
            [&square[..], &["robot=\"epuck2\"".to_string()]].concat(),
            0,
        ),
        (
            "thymio2",
            "fuzzymotiv (robot file)",
            vec![
                "robot=\"thymio2\"".into(),
                thymio_rooms,
                "aem.enabled=false".into(),
            ],
            2,
        ),
    ];
    let rows = rows(&results().join("transfer/readings.csv"));
    for (robot, source, sets, sensor) in probes {
        let loaded = fuzzymotiv_pipeline::files::inputs::load_config(None, &sets, None).unwrap();
        let arena = &loaded.experiment.arenas()[0];
        let (low, high) = arena.room().bounds();
        let mount = loaded.experiment.trial_params().robot().spec().mounts()[sensor];
        let mine: Vec<&Row> = rows
            .iter()
            .filter(|r| r["robot"] == robot && r["source"] == source)
            .collect();
        assert!(mine.len() > 100, "{robot} {source}: {} rows", mine.len());
        for row in mine {
            let d = number(row, "distance_mm").unwrap();
            let pose = Pose::facing_wall(&mount, high.x, (low.y + high.y) / 2.0, d);
            let now = arena.read_sensors(&pose)[sensor];
            assert_eq!(
                number(row, "reading"),
                Some(now),
                "{robot} {source} at {d} mm"
            );
        }
    }
}

/// The paper's study as a study file (studies/paper.toml, committed in `paper-study/`) is the
/// paper's study at both its base seeds: each base seed's four comparisons have the numbers and
/// the verdicts of the committed study of the same seeds (`twenty-seed`, `twenty-seed-base-11`),
/// each recomputed here from the study's own per_seed.csv (its resampling seeded by the base
/// seed's first seed, as the paper's claims).
#[test]
fn the_paper_study_files_comparisons_are_the_paper_studies_at_both_base_seeds() {
    for (scope, study) in [
        ("base=1", "twenty-seed"),
        ("base=11", "twenty-seed-base-11"),
    ] {
        let paper = results().join(study).join("claims.csv");
        assert_comparisons_are("paper-study", scope, "", &paper);
    }
}

/// The combination study as a study file (studies/combination.toml, committed in
/// `combination-study/`) is `reproduce --combination`'s at both base seeds: under each
/// combination, each base seed's four comparisons are that combination's claims in
/// `combination/` (base seed 1) and `combination-base-11/`, recomputed from its per_seed.csv.
#[test]
fn the_combination_study_files_comparisons_are_reproduces_at_both_base_seeds() {
    for (scope, records) in [
        ("base=1", "combination"),
        ("base=11", "combination-base-11"),
    ] {
        for (arm, dir) in [
            ("tsk", "default"),
            ("sum", "weighted-sum"),
            ("squares", "weighted-squares"),
        ] {
            let paper = results().join(records).join(dir).join("claims.csv");
            assert_comparisons_are("combination-study", scope, arm, &paper);
        }
    }
}

/// The four comparisons of the committed study of one's own `study` in `scope` (ids
/// `explores`, … with `-SUFFIX` when `suffix` is not empty, arms `high-curiosity` and
/// `low-curiosity`, or `high-SUFFIX` and `low-SUFFIX`) have the numbers and verdicts of the
/// paper's claims in `paper` (a claims.csv of `reproduce`), each recomputed from the study's
/// per_seed.csv.
fn assert_comparisons_are(study: &str, scope: &str, suffix: &str, paper: &Path) {
    let dir = results().join(study);
    let claims = rows(&dir.join("claims.csv"));
    let per_seed = rows(&dir.join("per_seed.csv"));
    let paper = rows(paper);
    let in_scope = |r: &&Row| format!("base={}", r["base_seed"]) == scope;
    let first_seed: u64 = per_seed.iter().find(in_scope).unwrap()["seed"]
        .parse()
        .unwrap();
    let named = |name: &str| match suffix {
        "" => name.to_string(),
        s => format!("{name}-{s}"),
    };
    let (high, low) = match suffix {
        "" => ("high-curiosity".to_string(), "low-curiosity".to_string()),
        s => (format!("high-{s}"), format!("low-{s}")),
    };
    let ids = ["explores", "battery", "recognition", "homing"];
    for (&(claim, column, expect), id) in CLAIMS.iter().zip(ids) {
        let id = named(id);
        let at = format!("{study}/claims.csv, {id} ({scope})");
        let ours = (claims.iter())
            .find(|r| r["id"] == id && r["scope"] == scope)
            .unwrap_or_else(|| panic!("{at}: missing"));
        let theirs = paper.iter().find(|r| r["claim"] == claim).unwrap();
        for (a, b) in [
            ("effect", "difference"),
            ("ci_low", "ci_low"),
            ("ci_high", "ci_high"),
            ("p", "p"),
            ("mdd", "mdd"),
        ] {
            assert_eq!(
                number(ours, a),
                number(theirs, b),
                "{at}: {a} is reproduce's"
            );
        }
        assert_eq!(
            ours["verdict"], theirs["verdict"],
            "{at}: reproduce's verdict"
        );
        let of = |arm: &str| -> Vec<f64> {
            (per_seed.iter().filter(in_scope))
                .filter(|r| r["arm"] == arm && r["measure"] == column && r["room"].is_empty())
                .map(|r| number(r, "value").unwrap())
                .collect()
        };
        let options = Settings {
            alpha: ALPHA,
            seed: first_seed,
            ..Settings::default()
        };
        let c = paired(&of(&high), &of(&low), &options).unwrap();
        assert_eq!(
            number(ours, "effect"),
            Some(c.difference),
            "{at}: recomputed"
        );
        assert_eq!(number(ours, "p"), Some(c.p), "{at}: recomputed");
        let verdict = c.verdict_with_power(expect).label();
        assert_eq!(
            ours["verdict"], verdict,
            "{at}: recomputed from per_seed.csv"
        );
    }
}

/// The committed paper study (studies/paper.toml at base seeds 1 and 11) is the committed
/// replication (`reproduce --replication --seeds 20`): its agreement by seed count, computed
/// from its per_seed.csv by the study's code, has for the four comparisons at every number of
/// seeds from 2 to 20 each base seed's p-value and verdict of replication_seeds.csv.
#[test]
fn the_paper_study_files_agreement_is_the_committed_replications_at_every_seed_count() {
    use fuzzymotiv_pipeline::records::hypotheses::{PerSeedRow, StudyRecord};
    use fuzzymotiv_pipeline::records::{read_csv, read_json};
    let dir = results().join("paper-study");
    let per_seed: Vec<PerSeedRow> = read_csv(&dir.join("per_seed.csv")).unwrap();
    let study: StudyRecord = read_json(&dir.join("study.json")).unwrap();
    let level = |_: &str| f64::NAN;
    let (h, bases) = (&study.hypotheses, &study.base_seeds);
    let agreement = fuzzymotiv_pipeline::study::agreement::agreement(
        h,
        &per_seed,
        bases,
        study.seeds,
        &level,
        &study.analysis,
        &study.claims,
    )
    .unwrap();
    let replication = rows(&results().join("replication/replication_seeds.csv"));
    let mut checked = 0;
    for n in 2..=study.seeds {
        // replication_seeds.csv: per number of seeds, the four comparisons first.
        let theirs: Vec<&Row> = (replication.iter())
            .filter(|r| r["seeds"] == n.to_string())
            .collect();
        for (k, id) in ["explores", "battery", "recognition", "homing"]
            .iter()
            .enumerate()
        {
            assert_eq!(theirs[k]["claim"], CLAIMS[k].0);
            for (base, side) in [(1, "a"), (11, "b")] {
                let ours = (agreement.iter())
                    .find(|r| r.seeds == n && r.id == *id && r.base_seed == base)
                    .unwrap_or_else(|| panic!("no {id} at {n} seeds of base seed {base}"));
                let what = format!("{id} at {n} seeds of base seed {base}");
                assert_eq!(
                    Some(ours.p),
                    number(theirs[k], &format!("p_{side}")),
                    "{what}"
                );
                assert_eq!(
                    ours.verdict,
                    theirs[k][&format!("verdict_{side}")],
                    "{what}"
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 19 * 4 * 2);
}

/// The committed studies of one's own (`docs/results/*-study/`: paper, combination, search
/// strength, ablation, urgency, orientation, transfer; the guide's fetch-urgency), each with its hypotheses' results per
/// base seed and pooled (the orientation study has none: each arm's measures only).
const STUDY_FILES: [(&str, usize); 8] = [
    ("paper-study", 8 * 3),
    ("combination-study", 40 * 3 + AGREEMENT * 40),
    ("search-strength-study", 17 * 3 + 9 * 2 * 17),
    ("ablation-study", 20 * 3 + 4 * 2 * 20),
    ("urgency-study", 15 * 3 + AGREEMENT * 15),
    ("orientation-study", 0),
    ("transfer-study", 5 * 3 + 9 * 2 * 5),
    ("fetch-urgency-study", 4 * 3 + 9 * 2 * 4),
];

/// agreement.csv's rows per hypothesis of a twenty-seed study at two base seeds: each base
/// seed's first 2 to 20 seeds (the paper study's records leave agreement.csv out: verdicts.rs
/// computes it from per_seed.csv).
const AGREEMENT: usize = 19 * 2;

/// Every committed study file's every claim (each base seed's and the pooled: effect, p,
/// Holm's p, verdict) is recomputed from its own per_seed.csv by the analysis its study.json
/// declares; and no committed study of one's own is left out.
#[test]
fn every_committed_study_files_verdicts_are_recomputed_from_its_per_seed_csv() {
    for (study, results_count) in STUDY_FILES {
        let dir = results().join(study);
        assert_eq!(
            common::recompute::recompute_every_verdict(&dir),
            results_count,
            "{study}: every hypothesis at each base seed and pooled, and by seed count"
        );
    }
    let committed = std::fs::read_dir(results()).unwrap();
    let studies: Vec<String> = (committed.map(|e| e.unwrap().path()))
        .filter(|p| p.join("study.json").is_file())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    for study in &studies {
        assert!(
            STUDY_FILES.iter().any(|(s, _)| s == study),
            "{study} is not recomputed here"
        );
    }
}

/// The search-strength study as a study file (studies/search-strength.toml, committed in
/// `search-strength-study/`): at base seed 1, each population's four comparisons are the
/// claims of `reproduce --search-strength` (`search-strength/pop-N/`), recomputed from the
/// study's per_seed.csv.
#[test]
fn the_search_strength_study_files_comparisons_are_reproduces_at_base_seed_1() {
    for population in [30, 60, 100, 200] {
        let dir = format!("pop-{population}");
        let paper = results()
            .join("search-strength")
            .join(&dir)
            .join("claims.csv");
        assert_comparisons_are("search-strength-study", "base=1", &dir, &paper);
    }
}

/// The ablation as a study file (studies/ablation.toml, committed in `ablation-study/`): at
/// base seed 1, under the default model and each choice switched back, the four comparisons
/// are the claims of `reproduce --ablation` (`ablation/VARIANT/`), recomputed from the study's
/// per_seed.csv.
#[test]
fn the_ablation_study_files_comparisons_are_reproduces_at_base_seed_1() {
    for variant in [
        "default",
        "wheels",
        "no-end-at-home",
        "distance-homing",
        "first-release-rooms",
    ] {
        let paper = results().join("ablation").join(variant).join("claims.csv");
        assert_comparisons_are("ablation-study", "base=1", variant, &paper);
    }
}

/// The urgency study as a study file (studies/urgency.toml, committed in `urgency-study/`) at
/// base seed 1: each seed's missions done (`mission_done_pct`, the mean over the rooms of the
/// share of test runs that reach the goal) under each weight is that seed's success in
/// `reproduce --urgency` (`urgency/urgency_seeds.csv`), and every comparison of them in
/// `urgency/urgency.csv`, recomputed from the study's per_seed.csv with reproduce's resampling
/// (the statistics' default seed), is reproduce's row. The study's own claims resample with the
/// scope's first seed and adjust p by Holm over its ten hypotheses, so their intervals, p and
/// verdicts may differ from that row.
#[test]
fn the_urgency_study_files_missions_done_are_reproduces_success_at_base_seed_1() {
    let per_seed = rows(&results().join("urgency-study/per_seed.csv"));
    let success = rows(&results().join("urgency/urgency_seeds.csv"));
    let arm = |weight: &str| format!("urgency-{:.1}", weight.parse::<f64>().unwrap());
    let ours = |arm: &str| -> Vec<f64> {
        (per_seed.iter())
            .filter(|r| r["base_seed"] == "1" && r["arm"] == arm && r["room"].is_empty())
            .filter(|r| r["measure"] == "mission_done_pct")
            .map(|r| number(r, "value").unwrap())
            .collect()
    };
    for weight in ["0", "0.1", "0.2", "0.3"] {
        let theirs: Vec<f64> = (success.iter())
            .filter(|r| r["setting"] == arm(weight))
            .map(|r| number(r, "success_pct").unwrap())
            .collect();
        assert_eq!(theirs.len(), 20, "{weight}: reproduce's twenty seeds");
        assert_eq!(ours(&arm(weight)), theirs, "{weight}: each seed's success");
    }
    let steps = rows(&results().join("urgency/urgency.csv"));
    let steps: Vec<&Row> = steps
        .iter()
        .filter(|r| r["measure"] == "% success")
        .collect();
    assert_eq!(steps.len(), 4, "0 → 0.1, 0.1 → 0.2, 0.2 → 0.3, 0 → 0.3");
    for row in steps {
        let (from, to) = (arm(&row["from"]), arm(&row["to"]));
        let c = paired(&ours(&to), &ours(&from), &Settings::default()).unwrap();
        for (column, value) in [
            ("difference", c.difference),
            ("ci_low", c.ci_low),
            ("ci_high", c.ci_high),
            ("p", c.p),
            ("detectable", c.mdd.unwrap()),
        ] {
            assert_eq!(number(row, column), Some(value), "{from} → {to}: {column}");
        }
    }
}

/// The per-seed values (the mean over the rooms) of `measure` in `arm` in `scope` of a study's
/// per_seed.csv, in seed order.
fn scope_values(per_seed: &[Row], scope: &str, arm: &str, measure: &str) -> Vec<f64> {
    (per_seed.iter())
        .filter(|r| format!("base={}", r["base_seed"]) == scope)
        .filter(|r| r["arm"] == arm && r["measure"] == measure && r["room"].is_empty())
        .map(|r| number(r, "value").unwrap())
        .collect()
}

/// One of `reproduce --combination`'s paired comparisons (`theirs`, a row of behaviour.csv or
/// claim_differences.csv) and the study's hypothesis on the same per-seed values `a` against
/// `b` (`ours`, a row of claims.csv): the study's values give reproduce's every number and
/// verdict when resampled as reproduce resamples (seed 0, two-sided); the study's effect and
/// detectable difference are reproduce's; its interval, p and verdict are recomputed from the
/// same values resampled by the scope's first seed, in the hypothesis's direction.
fn assert_reproduces_comparison(ours: &Row, theirs: &Row, a: &[f64], b: &[f64], first_seed: u64) {
    let at = format!(
        "combination-study/claims.csv, {} ({})",
        ours["id"], ours["scope"]
    );
    assert_eq!(a.len(), 20, "{at}: twenty seeds");
    let reproduces = paired(a, b, &Settings::default()).unwrap();
    for (column, value) in [
        ("difference", reproduces.difference),
        ("ci_low", reproduces.ci_low),
        ("ci_high", reproduces.ci_high),
        ("p", reproduces.p),
        ("detectable", reproduces.mdd.unwrap()),
    ] {
        assert_eq!(
            number(theirs, column),
            Some(value),
            "{at}: reproduce's {column}"
        );
    }
    let two_sided = reproduces
        .verdict_with_power(Expect::Higher)
        .direction_label();
    assert_eq!(theirs["verdict"], two_sided, "{at}: reproduce's verdict");
    assert_eq!(
        number(ours, "effect"),
        number(theirs, "difference"),
        "{at}: effect"
    );
    assert_eq!(
        number(ours, "mdd"),
        number(theirs, "detectable"),
        "{at}: detectable"
    );
    let options = Settings {
        alpha: ALPHA,
        seed: first_seed,
        ..Settings::default()
    };
    let c = paired(a, b, &options).unwrap();
    for (column, value) in [
        ("effect", c.difference),
        ("ci_low", c.ci_low),
        ("ci_high", c.ci_high),
        ("p", c.p),
        ("mdd", c.mdd.unwrap()),
    ] {
        assert_eq!(
            number(ours, column),
            Some(value),
            "{at}: {column} recomputed"
        );
    }
    let expect = match ours["expect"].as_str() {
        "lower" => Expect::Lower,
        _ => Expect::Higher,
    };
    let verdict = c.verdict_with_power(expect).label();
    assert_eq!(
        ours["verdict"], verdict,
        "{at}: recomputed from per_seed.csv"
    );
}

/// The study file's arm suffix of a combination of reproduce's.
fn combination_arm(combination: &str) -> &'static str {
    match combination {
        "weighted-sum" => "sum",
        "weighted-squares" => "squares",
        other => panic!("combination {other}"),
    }
}

/// The combination study file's behaviour comparisons (each baseline against the TSK per
/// setting and measure) and claim differences (each claim's high − low under a baseline against
/// the TSK's) are `reproduce --combination`'s behaviour.csv and claim_differences.csv at both
/// base seeds: the study's per-seed values give reproduce's every number resampled as reproduce
/// resamples, and its own effect and detectable difference are reproduce's.
#[test]
fn the_combination_study_files_behaviour_and_claim_differences_are_reproduces_at_both_base_seeds() {
    let dir = results().join("combination-study");
    let claims = rows(&dir.join("claims.csv"));
    let per_seed = rows(&dir.join("per_seed.csv"));
    let mut checked = 0;
    for (scope, records) in [
        ("base=1", "combination"),
        ("base=11", "combination-base-11"),
    ] {
        let first_seed: u64 = (per_seed.iter())
            .find(|r| format!("base={}", r["base_seed"]) == scope)
            .unwrap()["seed"]
            .parse()
            .unwrap();
        let ours = |id: &str| {
            (claims.iter())
                .find(|r| r["id"] == id && r["scope"] == scope)
                .unwrap_or_else(|| panic!("combination-study/claims.csv: no {id} ({scope})"))
        };
        let values = |arm: &str, measure: &str| scope_values(&per_seed, scope, arm, measure);
        for r in rows(&results().join(records).join("behaviour.csv")) {
            let (name, measure) = match r["measure"].as_str() {
                "% optimal exploration" => ("explores", "exploration_pct"),
                "% homing" => ("homing", "homing_pct"),
                "% battery usage" => ("battery", "battery_pct"),
                "% recognition" => ("recognition", "recognition_pct"),
                "% end spread" => ("spread", "end_spread_pct"),
                other => panic!("{records}/behaviour.csv: measure {other}"),
            };
            let setting = r["setting"].strip_suffix("-curiosity").unwrap();
            let base = combination_arm(&r["combination"]);
            let id = format!("{name}-{setting}-{base}-vs-tsk");
            let a = values(&format!("{setting}-{base}"), measure);
            let b = values(&format!("{setting}-tsk"), measure);
            assert_reproduces_comparison(ours(&id), &r, &a, &b, first_seed);
            checked += 1;
        }
        for r in rows(&results().join(records).join("claim_differences.csv")) {
            let (&(_, measure, _), name) = (CLAIMS.iter())
                .zip(["explores", "battery", "recognition", "homing"])
                .find(|((claim, _, _), _)| *claim == r["claim"])
                .unwrap_or_else(|| panic!("{records}/claim_differences.csv: {}", r["claim"]));
            let base = combination_arm(&r["combination"]);
            let effect = |arm: &str| -> Vec<f64> {
                let high = values(&format!("high-{arm}"), measure);
                let low = values(&format!("low-{arm}"), measure);
                high.iter().zip(&low).map(|(h, l)| h - l).collect()
            };
            let (a, b) = (effect(base), effect("tsk"));
            let at = format!("{records}/claim_differences.csv, {name}-{base}");
            let mean = fuzzymotiv::statistics::mean;
            assert_eq!(number(&r, "effect_combination"), Some(mean(&a)), "{at}");
            assert_eq!(number(&r, "effect_tsk"), Some(mean(&b)), "{at}");
            let id = format!("{name}-{base}-vs-tsk");
            assert_reproduces_comparison(ours(&id), &r, &a, &b, first_seed);
            checked += 1;
        }
    }
    assert_eq!(checked, 2 * (20 + 8), "every comparison at both base seeds");
}

/// The transfer study as a study file (studies/transfer.toml, committed in `transfer-study/`)
/// at base seed 1 is `scripts/transfer_study.sh`'s (`transfer/transfer.csv`): each seed's Enki
/// exploration, homing, battery and recognition (the mean over the five rooms of its ten Enki
/// test runs) and its exploration's |Enki − fuzzymotiv| gap, seed by seed, bit for bit; its claims are
/// recomputed with the others (`every_committed_study_files_verdicts_…`).
#[test]
fn the_transfer_study_files_base_seed_1_is_the_transfer_scripts_enki_side() {
    let per_seed = rows(&results().join("transfer-study/per_seed.csv"));
    let (means, seeds) = transfer_seed_means(&results().join("transfer/transfer.csv"));
    let mut checked = 0;
    for setting in ["high-curiosity", "low-curiosity"] {
        let ours = |measure: &str| -> Vec<(u64, f64)> {
            (per_seed.iter())
                .filter(|r| r["base_seed"] == "1" && r["arm"] == setting)
                .filter(|r| r["measure"] == measure && r["room"].is_empty())
                .map(|r| (r["seed"].parse().unwrap(), number(r, "value").unwrap()))
                .collect()
        };
        for m in [
            "exploration_pct",
            "homing_pct",
            "battery_pct",
            "recognition_pct",
        ] {
            let world = |w: &str| &means[&(setting.to_string(), m.to_string(), w.to_string())];
            let (enki, sim) = (world("enki"), world("fuzzymotiv"));
            let gap: Vec<f64> = enki.iter().zip(sim).map(|(e, s)| (e - s).abs()).collect();
            let mut measures = vec![(format!("enki_{m}"), enki)];
            if m == "exploration_pct" {
                measures.push((format!("gap_{m}"), &gap)); // the gap a hypothesis reads
            }
            for (name, theirs) in measures {
                let (s, v): (Vec<u64>, Vec<f64>) = ours(&name).into_iter().unzip();
                assert_eq!(s, seeds[setting], "{setting} {name}: the script's seeds");
                assert_eq!(&v, theirs, "{setting} {name}: each seed's value");
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 2 * (4 + 1));
}
