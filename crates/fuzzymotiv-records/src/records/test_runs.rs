//! `test_runs.csv`: one row per recognition test run of a run directory (the test runs behind
//! the per-room table's % exploration, % recognition, % battery and % homing), so that two runs
//! can be compared over their test runs (`fuzzymotiv compare`). Written and read by this module;
//! run directories written before it have no such file.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::files::error::CliError;
use crate::records::{Finished, read_csv, to_csv};

/// The file's name in a run directory.
pub const TEST_RUNS: &str = "test_runs.csv";

/// One test run of the robot standing for a room, in that room (fresh noise each).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TestRunRow {
    /// The room the robot was in.
    pub room: String,
    /// The test run's number in this room, from 0 (the same number uses the same random
    /// streams in two runs of the same seed).
    pub test: usize,
    /// 100·a of the test run.
    pub exploration_pct: f64,
    /// 100 if the room was recognised correctly, 0 if not; empty when AEM did not run.
    pub recognition_pct: Option<f64>,
    /// 100·b of the test run.
    pub battery_pct: f64,
    /// 100·g of the test run.
    pub homing_pct: f64,
    /// The room it was recognised as; empty if none (or AEM did not run).
    pub answer: Option<String>,
}

/// The test runs of a finished run, room by room (the rooms of the per-room table, in order).
pub fn test_runs(done: &Finished) -> Vec<TestRunRow> {
    let names: Vec<&str> = done.rows.iter().map(|r| r.room.as_str()).collect();
    let mut rows = Vec::new();
    for (r, name) in names.iter().enumerate() {
        let room = &done.outcome.aem_for_room(r).rooms[r];
        let aem = room.recognition_pct.is_some();
        for (k, t) in room.tests.iter().enumerate() {
            rows.push(TestRunRow {
                room: (*name).to_string(),
                test: k,
                exploration_pct: 100.0 * t.terms.a,
                recognition_pct: aem.then_some(if t.answer == Some(r) { 100.0 } else { 0.0 }),
                battery_pct: 100.0 * t.terms.b,
                homing_pct: 100.0 * t.terms.g,
                answer: t.answer.and_then(|a| names.get(a)).map(|a| a.to_string()),
            });
        }
    }
    rows
}

/// `test_runs.csv`'s text.
pub fn to_text(rows: &[TestRunRow]) -> String {
    to_csv(rows)
}

/// Reads `test_runs.csv` of the run directory `dir`; a directory written before the file
/// existed gets a message saying so and how to make one that has it.
pub fn read(dir: &Path) -> Result<Vec<TestRunRow>, CliError> {
    let path = dir.join(TEST_RUNS);
    if !path.is_file() {
        return Err(CliError::input(format!(
            "{}: no {TEST_RUNS}: this run directory was written before runs recorded their test \
             runs (or is incomplete); run its config again with this version to compare it over \
             its test runs (fuzzymotiv run {} --out NEW_DIR)",
            dir.display(),
            dir.join("config.resolved.toml").display()
        )));
    }
    read_csv(&path)
}
