//! Every claim of a study of one's own (`fuzzymotiv study`) recomputed from its per_seed.csv
//! by the analysis its study.json declares, independently of the pipeline's analysis code:
//! shared by the tests that run a study (study.rs) and those that check the committed ones
//! (verdicts.rs).

use std::collections::BTreeMap;
use std::path::Path;

use fuzzymotiv::statistics::{self, Settings, Verdict};

pub type Rows = Vec<BTreeMap<String, String>>;

pub fn read_csv(path: &Path) -> Rows {
    let mut r = csv::Reader::from_path(path).unwrap();
    r.deserialize().map(|row| row.unwrap()).collect()
}

pub fn f(row: &BTreeMap<String, String>, key: &str) -> f64 {
    row[key].parse().unwrap()
}

/// The values of `measure` in `arm` over the mean of the rooms, in `scope`, from per_seed.csv.
pub fn values(per_seed: &Rows, arm: &str, measure: &str, scope: &str) -> Vec<f64> {
    per_seed
        .iter()
        .filter(|r| r["arm"] == arm && r["measure"] == measure && r["room"].is_empty())
        .filter(|r| scope == "pooled" || format!("base={}", r["base_seed"]) == scope)
        .map(|r| f(r, "value"))
        .collect()
}

/// A claim's test recomputed from per-seed values by the rule study.json states: (effect, p,
/// detectable difference, margin in the hypothesis's way).
pub fn recompute(
    h: &serde_json::Value,
    levels: &BTreeMap<String, f64>,
    per_seed: &Rows,
    scope: &str,
    s: &Settings,
) -> (f64, f64, Option<f64>, f64) {
    let of = |arm: &serde_json::Value, measure: &str| {
        values(per_seed, arm.as_str().unwrap(), measure, scope)
    };
    let measure = h["measure"].as_str().unwrap_or("");
    let way = |expect: &serde_json::Value| if expect == "higher" { 1.0 } else { -1.0 };
    match h["kind"].as_str().unwrap() {
        "compare" => {
            let c = statistics::paired(&of(&h["a"], measure), &of(&h["b"], measure), s).unwrap();
            (c.difference, c.p, c.mdd, way(&h["expect"]) * c.difference)
        }
        "difference" => {
            let minus = |a: &str, b: &str| -> Vec<f64> {
                let (a, b) = (of(&h[a], measure), of(&h[b], measure));
                a.iter().zip(&b).map(|(a, b)| a - b).collect()
            };
            let (x, y) = (minus("a", "b"), minus("versus_a", "versus_b"));
            let c = statistics::paired(&x, &y, s).unwrap();
            (c.difference, c.p, c.mdd, way(&h["expect"]) * c.difference)
        }
        "rising" => {
            let c = statistics::paired(
                &of(&h["arm"], "last_mean_f"),
                &of(&h["arm"], "first_mean_f"),
                s,
            )
            .unwrap();
            (c.difference, c.p, c.mdd, c.difference)
        }
        "trend" => {
            let arms: Vec<&serde_json::Value> = h["arms"].as_array().unwrap().iter().collect();
            let xs: Vec<f64> = arms.iter().map(|a| levels[a.as_str().unwrap()]).collect();
            let ys: Vec<Vec<f64>> = arms.iter().map(|a| of(a, measure)).collect();
            let slopes: Vec<f64> = (0..ys[0].len())
                .map(|i| {
                    let y: Vec<f64> = ys.iter().map(|v| v[i]).collect();
                    if y.iter().all(|&v| v == y[0]) {
                        return 0.0; // a level line
                    }
                    let (mx, my) = (statistics::mean(&xs), statistics::mean(&y));
                    let sxy: f64 = xs.iter().zip(&y).map(|(x, y)| (x - mx) * (y - my)).sum();
                    sxy / xs.iter().map(|x| (x - mx) * (x - mx)).sum::<f64>()
                })
                .collect();
            let c = statistics::paired(&slopes, &vec![0.0; slopes.len()], s).unwrap();
            (c.difference, c.p, c.mdd, way(&h["expect"]) * c.difference)
        }
        "range" => {
            let v = of(&h["arm"], measure);
            let (min, max) = (h["min"].as_f64().unwrap(), h["max"].as_f64().unwrap());
            let n = v.len();
            let mean = statistics::paired(&v, &vec![0.0; n], s).unwrap();
            let p_min = statistics::paired(&v, &vec![min; n], s).unwrap().p;
            let p_max = statistics::paired(&v, &vec![max; n], s).unwrap().p;
            let m = mean.difference;
            let (margin, p) = if m < min {
                (m - min, p_min)
            } else if m > max {
                (max - m, p_max)
            } else {
                ((m - min).min(max - m), p_min.max(p_max))
            };
            (m, p, mean.mdd, margin)
        }
        other => panic!("kind {other}"),
    }
}

/// Every claim of the study in `out` recomputed from its per_seed.csv by the analysis its
/// study.json states (α, the rule, Holm over the hypotheses): effect, p, adjusted p, verdict;
/// and with several base seeds every row of its agreement.csv, from the per-seed values of
/// its base seed's first seeds, its `pooled` the pooled verdict of claims.csv. How many.
pub fn recompute_every_verdict(out: &Path) -> usize {
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("study.json")).unwrap()).unwrap();
    let per_seed = read_csv(&out.join("per_seed.csv"));
    let hypotheses = record["hypotheses"].as_array().unwrap().len();
    // A study without hypotheses writes no claims.csv; one with them always does.
    let claims_csv = out.join("claims.csv");
    assert_eq!(
        claims_csv.is_file(),
        hypotheses > 0,
        "{}",
        claims_csv.display()
    );
    let claims = if hypotheses > 0 {
        read_csv(&claims_csv)
    } else {
        Rows::new()
    };
    let arms_csv = out.join("arms.csv");
    if arms_csv.is_file() {
        recompute_arm_measures(&per_seed, &read_csv(&arms_csv));
    }
    let mut checked = recompute_verdicts(&record, &per_seed, &claims);
    let agreement = out.join("agreement.csv");
    let bases = record["base_seeds"].as_array().unwrap().len();
    // A study writes agreement.csv with several base seeds (the study tests count its rows);
    // committed records may leave it out, never have it with one base seed.
    assert!(
        !agreement.is_file() || bases > 1,
        "agreement.csv with {bases} base seed"
    );
    if !agreement.is_file() {
        return checked;
    }
    let mut rows = read_csv(&agreement);
    let seeds = record["seeds"].as_u64().unwrap() as usize;
    assert_eq!(rows.len(), (seeds - 1) * bases * hypotheses);
    for r in &mut rows {
        let pooled = (claims.iter())
            .find(|c| c["scope"] == "pooled" && c["id"] == r["id"])
            .unwrap();
        assert_eq!(r["pooled"], pooled["verdict"], "{r:?}: pooled verdict");
        assert_eq!(r["agrees"], (r["verdict"] == r["pooled"]).to_string());
        r.insert("scope".into(), "pooled".into());
    }
    let mut groups: Vec<(String, String)> = (rows.iter())
        .map(|r| (r["seeds"].clone(), r["base_seed"].clone()))
        .collect();
    groups.dedup();
    for (n, base) in groups {
        let count: usize = n.parse().unwrap();
        let first: Rows = (per_seed.iter())
            .filter(|r| r["base_seed"] == base && r["replicate"].parse::<usize>().unwrap() < count)
            .cloned()
            .collect();
        let judged: Rows = (rows.iter())
            .filter(|r| r["seeds"] == n && r["base_seed"] == base)
            .cloned()
            .collect();
        checked += recompute_verdicts(&record, &first, &judged);
    }
    checked
}

/// Every row of arms.csv (an arm's seeds, mean and sample sd of a measure in a room, or over
/// the rooms, in a scope) recomputed from per_seed.csv; and every arm and measure of
/// per_seed.csv has its rows.
pub fn recompute_arm_measures(per_seed: &Rows, arms: &Rows) {
    for row in arms {
        let v: Vec<f64> = (per_seed.iter())
            .filter(|r| r["arm"] == row["arm"] && r["measure"] == row["measure"])
            .filter(|r| r["room"] == row["room"])
            .filter(|r| {
                row["scope"] == "pooled" || format!("base={}", r["base_seed"]) == row["scope"]
            })
            .map(|r| f(r, "value"))
            .collect();
        assert_eq!(row["seeds"], v.len().to_string(), "{row:?}");
        assert_eq!(f(row, "mean"), statistics::mean(&v), "{row:?}: mean");
        let sd = statistics::sample_sd(&v);
        assert_eq!(row["sd"].parse().ok(), sd, "{row:?}: sd");
    }
    for r in per_seed {
        assert!(
            (arms.iter()).any(|a| a["scope"] == "pooled"
                && a["arm"] == r["arm"]
                && a["measure"] == r["measure"]
                && a["room"] == r["room"]),
            "arms.csv has no row of {r:?}"
        );
    }
}

/// Every claim of `claims` (rows with a scope) recomputed from `per_seed` by the analysis
/// `record` (study.json) states; how many.
pub fn recompute_verdicts(record: &serde_json::Value, per_seed: &Rows, claims: &Rows) -> usize {
    let a = &record["analysis"];
    // The resampling of a scope's tests is seeded by its first seed, as the paper's study's.
    let first_seed = |scope: &str| {
        (per_seed.iter())
            .find(|r| scope == "pooled" || format!("base={}", r["base_seed"]) == scope)
            .map_or(0, |r| r["seed"].parse().unwrap())
    };
    let settings = |scope: &str| Settings {
        alpha: a["alpha"].as_f64().unwrap(),
        confidence: a["confidence"].as_f64().unwrap(),
        power: a["power"].as_f64().unwrap(),
        seed: first_seed(scope),
        ..Settings::default()
    };
    let levels: BTreeMap<String, f64> = (record["arms"].as_array().unwrap().iter())
        .filter_map(|arm| Some((arm["name"].as_str()?.to_string(), arm["level"].as_f64()?)))
        .collect();
    let hypotheses = record["hypotheses"].as_array().unwrap();
    let mut scopes: Vec<&str> = claims.iter().map(|c| c["scope"].as_str()).collect();
    scopes.dedup();
    for scope in scopes {
        let s = settings(scope);
        let tested: Vec<_> = (hypotheses.iter())
            .map(|h| recompute(h, &levels, per_seed, scope, &s))
            .collect();
        let p: Vec<f64> = tested.iter().map(|t| t.1).collect();
        let adjusted = match a["holm"].as_str().unwrap() {
            "hypotheses" => statistics::holm(&p),
            _ => p.clone(),
        };
        let rows: Vec<_> = claims.iter().filter(|c| c["scope"] == scope).collect();
        assert_eq!(rows.len(), hypotheses.len());
        for ((row, (effect, p, mdd, margin)), p_adj) in rows.iter().zip(tested).zip(adjusted) {
            let inconclusive = a["rule"] == "power" && mdd.is_some_and(|m| margin.abs() < m);
            let verdict = if inconclusive {
                Verdict::Inconclusive
            } else {
                Verdict::of(margin, p_adj, statistics::Expect::Higher, s.alpha)
            };
            let what = format!("{} ({scope})", row["id"]);
            assert_eq!(f(row, "effect"), effect, "{what}: effect");
            assert_eq!(f(row, "p"), p, "{what}: p");
            assert_eq!(f(row, "p_adjusted"), p_adj, "{what}: adjusted p");
            assert_eq!(row["verdict"], verdict.label(), "{what}: verdict");
        }
    }
    claims.len()
}
