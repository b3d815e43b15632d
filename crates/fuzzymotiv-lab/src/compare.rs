//! Two finished runs side by side: their curves, paths and per-room tables, and per measure
//! (exploration, homing, battery, F) the library's paired test over the rooms they share
//! (`fuzzymotiv::statistics::paired`: sign-flip permutation p, bootstrap interval).

use fuzzymotiv::statistics::{Expect, Settings, Verdict, paired};
use serde_json::{Value, json};

use crate::errors::ApiError;
use crate::runs::{RunEntry, Runs, Status};

/// The measures compared, as `summary.json`'s per-room rows name them.
const MEASURES: [&str; 4] = [
    "exploration_pct",
    "homing_pct",
    "battery_pct",
    "average_fitness",
];

/// What the page shows of one side.
fn side(e: &RunEntry) -> Result<Value, ApiError> {
    let (status, shown) = &*e.lock();
    if *status != Status::Finished {
        return Err(ApiError::conflict(format!(
            "run `{}` has not finished; only finished runs are compared",
            e.id
        )));
    }
    Ok(
        json!({ "id": e.id, "about": e.about, "generations": shown.generations,
               "result": shown.result, "paths": shown.paths }),
    )
}

/// Per room name, the value of `measure` in a side's table.
fn values(side: &Value, measure: &str) -> Vec<(String, f64)> {
    let rows = side["result"]["rows"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    rows.iter()
        .filter_map(|r| Some((r["room"].as_str()?.to_string(), r[measure].as_f64()?)))
        .collect()
}

/// A comparison's verdict read as which run is higher (a − b > 0 is "A higher").
fn direction(verdict: Verdict) -> &'static str {
    match verdict {
        Verdict::Holds => "A higher",
        Verdict::Opposite => "B higher",
        Verdict::NotSignificant => "not significant",
    }
}

/// The paired test of one measure over the rooms both runs have.
fn test(a: &Value, b: &Value, measure: &str) -> Value {
    let va = values(a, measure);
    let vb = values(b, measure);
    let (xs, ys): (Vec<f64>, Vec<f64>) = va
        .iter()
        .filter_map(|(room, x)| vb.iter().find(|(r, _)| r == room).map(|(_, y)| (*x, *y)))
        .unzip();
    match paired(&xs, &ys, &Settings::default()) {
        Ok(c) => json!({ "measure": measure, "rooms": xs.len(), "mean_a": c.mean_a,
            "mean_b": c.mean_b, "difference": c.difference, "ci_low": c.ci_low,
            "ci_high": c.ci_high, "p": c.p, "min_p": c.min_p,
            "verdict": direction(c.verdict(Expect::Higher)) }),
        Err(e) => json!({ "measure": measure, "rooms": xs.len(), "error": e.to_string() }),
    }
}

/// The comparison of runs `a` and `b`.
pub fn compare(runs: &Runs, a: &str, b: &str) -> Result<Value, ApiError> {
    let find = |id: &str| {
        runs.get(id)
            .ok_or_else(|| ApiError::not_found(format!("no run `{id}` in this lab")))
    };
    let (sa, sb) = (side(&*find(a)?)?, side(&*find(b)?)?);
    let tests: Vec<Value> = MEASURES.iter().map(|m| test(&sa, &sb, m)).collect();
    Ok(json!({ "a": sa, "b": sb, "tests": tests,
        "note": "paired over the rooms both runs have: a − b per room; a verdict needs p < 0.05, which five rooms cannot give (smallest p 1/16)" }))
}
