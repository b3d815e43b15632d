//! Two finished runs side by side: their curves, paths and per-room tables, and the
//! differences `fuzzymotiv compare` reports for two run directories (over their test runs,
//! paired when the runs share their seed; `fuzzymotiv_pipeline::pipeline::compare`), overall and per
//! room, every metric of the test runs (recognition included).

use fuzzymotiv_pipeline::pipeline::compare::{
    check_comparable, choose, compare as compare_dirs, load,
};
use serde_json::{Value, json};

use crate::errors::ApiError;
use crate::runs::{RunEntry, Runs, Status};

/// The level of the verdicts, as `fuzzymotiv compare`'s default `--alpha`.
const ALPHA: f64 = 0.05;

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

/// The comparison's rows as `fuzzymotiv compare A B` computes them for the two run
/// directories, with a verdict each; or why there are none (e.g. different rooms).
fn tests(runs: &Runs, a: &str, b: &str) -> Result<(Vec<Value>, String), String> {
    let (da, db) = (load(&runs.run_dir(a), "A"), load(&runs.run_dir(b), "B"));
    let (da, db) = (
        da.map_err(|e| e.to_string())?,
        db.map_err(|e| e.to_string())?,
    );
    check_comparable(&da, &db).map_err(|e| e.to_string())?;
    let pairs = choose(&da, &db, &[]).map_err(|e| e.to_string())?;
    let done = compare_dirs(&da, &db, &pairs, ALPHA).map_err(|e| e.to_string())?;
    let rows = done.rows.iter().map(|r| {
        let verdict = match (r.p_holm < ALPHA, r.difference > 0.0) {
            (false, _) => "not significant",
            (true, true) => "A higher",
            (true, false) => "B higher",
        };
        let mut v = serde_json::to_value(r).unwrap_or_default();
        v["verdict"] = json!(verdict);
        v
    });
    let note = format!(
        "As `fuzzymotiv compare A B`: over the runs' test runs ({}), per room and overall (per \
         test run, the mean over rooms); 95 % bootstrap interval; two-sided permutation p, \
         Holm-adjusted over the rooms of a measure; a verdict needs p < {ALPHA}.",
        done.rows.first().map_or("", |r| r.design.as_str())
    );
    Ok((rows.collect(), note))
}

/// The comparison of runs `a` and `b`.
pub fn compare(runs: &Runs, a: &str, b: &str) -> Result<Value, ApiError> {
    let find = |id: &str| {
        runs.get(id)
            .ok_or_else(|| ApiError::not_found(format!("no run `{id}` in this lab")))
    };
    let (sa, sb) = (side(&*find(a)?)?, side(&*find(b)?)?);
    let (tests, note) = match tests(runs, a, b) {
        Ok(found) => found,
        Err(why) => (Vec::new(), format!("No differences are tested: {why}")),
    };
    Ok(json!({ "a": sa, "b": sb, "tests": tests, "note": note }))
}
