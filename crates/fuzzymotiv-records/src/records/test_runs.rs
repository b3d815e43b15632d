//! `test_runs.csv`: one row per recognition test run of a run directory (the test runs behind
//! the per-room table's % exploration, % recognition, % battery and % homing), so that two runs
//! can be compared over their test runs (`fuzzymotiv compare`). A run that follows missions or
//! weighs terms of its own has more columns after the paper's, those of its `table.md`:
//! `mission_done_pct` (100 if the test run's mission was done, else 0) and `NAME_pct` (100·term)
//! per term beyond a, g, l, b ([`crate::records::extra_terms`]); the paper's runs keep their
//! bytes. Written and read by this module; run directories written before it have no such file.

use std::path::Path;

use fuzzymotiv::fitness::TermId;
use serde::{Deserialize, Serialize};

use crate::files::bounded::read_input;
use crate::files::error::CliError;
use crate::records::{
    CsvTable, Finished, RECORD, csv_text, csv_writer, parse_csv, to_csv, write_row,
};

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
    /// The run's measures beyond the paper's, (column, value) in column order after `answer`:
    /// [`MISSION_DONE`] when the run follows missions, then [`term_metric`] of each term
    /// beyond a, g, l, b; none for the paper's model (written by [`to_text`], read by
    /// [`read`]).
    #[serde(skip)]
    pub extra: Vec<(String, f64)>,
}

/// The column of whether a test run's mission was done (100) or not (0), as `summary.json`'s
/// rooms and a sweep's `results.csv` call the share of such runs.
pub const MISSION_DONE: &str = "mission_done_pct";

/// The column of 100·`term` (a term beyond a, g, l, b, by name): `NAME_pct`.
pub fn term_metric(term: &str) -> String {
    format!("{term}_pct")
}

/// The term of a [`term_metric`] column (`goal` of `goal_pct`).
pub fn metric_term(column: &str) -> &str {
    column.strip_suffix("_pct").unwrap_or(column)
}

/// The terms beyond a, g, l, b (each known by `name`) in the one order every table lists them:
/// by name, as `table.md`'s per-room columns do (a room row's `terms_pct` is a map by name);
/// `robustness.*` and `compare.*` follow it.
pub fn in_table_order<T>(mut terms: Vec<T>, name: impl Fn(&T) -> &str) -> Vec<T> {
    terms.sort_by(|a, b| name(a).cmp(name(b)));
    terms
}

/// The columns of the paper's model, in order.
const COLUMNS: [&str; 7] = [
    "room",
    "test",
    "exploration_pct",
    "recognition_pct",
    "battery_pct",
    "homing_pct",
    "answer",
];

/// The test runs of a finished run, room by room (the rooms of the per-room table, in order),
/// with a column per term of `extra` ([`crate::records::extra_terms`]) and, when the run
/// follows missions, [`MISSION_DONE`].
pub fn test_runs(done: &Finished, extra: &[(String, TermId)]) -> Vec<TestRunRow> {
    let names: Vec<&str> = done.rows.iter().map(|r| r.room.as_str()).collect();
    let mut rows = Vec::new();
    for (r, name) in names.iter().enumerate() {
        let room = &done.outcome.aem_for_room(r).rooms[r];
        let aem = room.recognition_pct.is_some();
        for (k, t) in room.tests.iter().enumerate() {
            let done = (t.terms.mission).map(|m| {
                (
                    MISSION_DONE.to_string(),
                    100.0 * f64::from(u8::from(m.done_at.is_some())),
                )
            });
            let terms =
                (extra.iter()).map(|(name, id)| (term_metric(name), 100.0 * t.terms.get(*id)));
            rows.push(TestRunRow {
                extra: done.into_iter().chain(terms).collect(),
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

/// `test_runs.csv`'s text: the paper's columns, then the first row's extra ones.
pub fn to_text(rows: &[TestRunRow]) -> String {
    let Some(first) = rows.first().filter(|r| !r.extra.is_empty()) else {
        return to_csv(rows);
    };
    let mut w = csv_writer();
    let mut header: Vec<String> = COLUMNS.iter().map(|c| c.to_string()).collect();
    header.extend(first.extra.iter().map(|(c, _)| c.clone()));
    write_row(&mut w, header);
    // `{:?}` writes a float as the serialiser of the paper's columns does (`100.0`, `47.5`).
    for r in rows {
        let mut cells = vec![r.room.clone(), r.test.to_string()];
        cells.push(format!("{:?}", r.exploration_pct));
        cells.push(
            r.recognition_pct
                .map_or(String::new(), |v| format!("{v:?}")),
        );
        cells.push(format!("{:?}", r.battery_pct));
        cells.push(format!("{:?}", r.homing_pct));
        cells.push(r.answer.clone().unwrap_or_default());
        cells.extend(r.extra.iter().map(|(_, v)| format!("{v:?}")));
        write_row(&mut w, cells);
    }
    csv_text(w)
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
    let text = read_input(&path, RECORD)?;
    let mut rows: Vec<TestRunRow> = parse_csv(&text, &path)?;
    let table = CsvTable::parse(&text, &path)?;
    let extra: Vec<String> = (table.headers.iter())
        .filter(|h| !COLUMNS.contains(&h.as_str()))
        .cloned()
        .collect();
    for (k, row) in rows.iter_mut().enumerate() {
        for column in &extra {
            let v: f64 = table.get(k, column)?;
            row.extra.push((column.clone(), v));
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fuzzymotiv::fitness::RECORD_COLUMN_NAMES;

    /// Every fixed column `test_runs.csv` writes (the paper's and the missions'), less `_pct`,
    /// is a name the engine refuses to a user term, so no term's `NAME_pct` repeats one.
    #[test]
    fn every_fixed_test_runs_column_is_a_name_a_user_term_cannot_take() {
        let row = TestRunRow {
            room: "r".into(),
            test: 0,
            exploration_pct: 0.0,
            recognition_pct: Some(0.0),
            battery_pct: 0.0,
            homing_pct: 0.0,
            answer: None,
            extra: vec![(MISSION_DONE.to_string(), 0.0)],
        };
        let text = to_text(&[row]);
        let header = text.lines().next().unwrap();
        assert!(header.starts_with(&COLUMNS.join(",")), "{header}");
        assert!(header.ends_with(MISSION_DONE), "{header}");
        for column in header.split(',') {
            assert!(
                RECORD_COLUMN_NAMES.contains(&metric_term(column)),
                "{column}"
            );
        }
    }
}
