//! Merging a sweep directory: every finished job's `summary.json` into `results.csv`, the
//! mean ± sample std (n − 1) over replicates into `aggregate.csv` and `aggregate.md`, and
//! `summary.svg`. A std over one value is an empty cell in CSV and a dash in Markdown.

use std::fmt::Write as _;
use std::path::Path;

use fuzzymotiv::fitness::PAPER_MOTIVATIONS;
use fuzzymotiv::statistics;

use crate::files::error::CliError;
use crate::files::guard::write_atomic;
use crate::files::notes::Notes;
use crate::records::{
    AggregateRow, Job, METRICS, MotivationsRecord, RunSummary, SweepResultRow, SweepResults,
    read_json, to_csv,
};
use crate::render::svg::{SettingPoint, sweep_summary_svg};
use crate::render::tables::STD_IS_SAMPLE;

/// Writes `results.csv`, `aggregate.csv`, `aggregate.md` and `summary.svg` of the sweep
/// directory `dir` and says to `notes` how many jobs went in; the Markdown table (to show) is
/// the [`Merged::markdown`] returned.
pub fn merge_dir(dir: &Path, notes: &dyn Notes) -> Result<Merged, CliError> {
    let merged = write_merge(dir)?;
    notes.note(&format!(
        "merged {} jobs ({} rows) into {}; {} of {} jobs not finished",
        merged.jobs - merged.missing,
        merged.rows,
        dir.join("results.csv").display(),
        merged.missing,
        merged.jobs
    ));
    Ok(merged)
}

/// What [`write_merge`] wrote.
#[derive(Debug, Clone)]
pub struct Merged {
    /// `aggregate.md`'s text.
    pub markdown: String,
    /// Jobs in the plan.
    pub jobs: usize,
    /// Jobs not finished (left out of the tables).
    pub missing: usize,
    /// Rows of `results.csv` (one per room of a finished job).
    pub rows: usize,
}

/// [`merge_dir`]'s files, written without a note (for the Python bindings).
pub fn write_merge(dir: &Path) -> Result<Merged, CliError> {
    let jobs = Job::read_plan(&dir.join("plan.jsonl"))?;
    let (results, missing) = collect_results(dir, &jobs)?;
    if missing == jobs.len() {
        return Err(CliError::input(format!(
            "{}: none of the plan's {} jobs has finished (no jobs/ID/DONE), so there is nothing \
             to merge; its tables, if any, are kept. Run the sweep's jobs first",
            dir.display(),
            jobs.len()
        )));
    }
    write_atomic(&dir.join("results.csv"), results.to_csv())?;
    let groups = group_by_setting_and_room(&results.rows);
    let aggregate: Vec<AggregateRow> = groups
        .iter()
        .map(|((setting, room), members)| {
            AggregateRow::new(setting, room, members.len(), metric_stats(members))
        })
        .collect();
    write_atomic(&dir.join("aggregate.csv"), aggregate_csv(&aggregate))?;
    let md = aggregate_markdown(&groups);
    write_atomic(&dir.join("aggregate.md"), &md)?;
    write_atomic(
        &dir.join("summary.svg"),
        sweep_summary_svg(&setting_points(&groups)),
    )?;
    Ok(Merged {
        markdown: md,
        jobs: jobs.len(),
        missing,
        rows: results.rows.len(),
    })
}

/// The rows of every finished job (one per room), and the number of unfinished jobs.
fn collect_results(dir: &Path, jobs: &[Job]) -> Result<(SweepResults, usize), CliError> {
    let mut results = SweepResults::default();
    for job in jobs {
        for (key, _) in job.grid_values() {
            if !results.grid.iter().any(|k| k == key) {
                results.grid.push(key.to_string());
            }
        }
    }
    let mut missing = 0;
    for job in jobs {
        let job_dir = dir.join("jobs").join(&job.id);
        if !job_dir.join("DONE").is_file() {
            missing += 1;
            continue;
        }
        let summary: RunSummary = read_json(&job_dir.join("summary.json"))?;
        let values = job.grid_values();
        let grid: Vec<String> = results
            .grid
            .iter()
            .map(|k| {
                values
                    .iter()
                    .find(|(key, _)| key == k)
                    .map_or(String::new(), |(_, v)| cell_of_toml(v))
            })
            .collect();
        for name in other_motivations(&summary.motivations) {
            if !results.motivations.iter().any(|m| m == name) {
                results.motivations.push(name.to_string());
            }
        }
        for r in &summary.rooms {
            results.missions |= r.mission_done_pct.is_some();
            results.rows.push(SweepResultRow {
                job_id: job.id.clone(),
                index: job.index,
                setting: job.setting.clone(),
                replicate: job.replicate,
                seed: job.seed,
                motivations: summary.motivations.clone(),
                grid: grid.clone(),
                room: r.room.clone(),
                values: [
                    Some(r.average_fitness),
                    Some(r.exploration_pct),
                    r.recognition_pct,
                    Some(r.battery_pct),
                    Some(r.homing_pct),
                ],
                other_weights: Vec::new(),
                mission_done_pct: r.mission_done_pct,
            });
        }
    }
    // Once every job's motivations are known: each row's weight in each column (none where
    // its job lacks that motivation).
    for row in &mut results.rows {
        row.other_weights = weights_of(&row.motivations, &results.motivations);
    }
    Ok((results, missing))
}

/// The names of a job's motivations beyond the paper's four.
fn other_motivations(m: &MotivationsRecord) -> impl Iterator<Item = &str> {
    (m.table.iter())
        .map(|e| e.name.as_str())
        .filter(|name| !PAPER_MOTIVATIONS.contains(name))
}

/// The weights of the motivations named by `columns` in `m` (none where it lacks one).
fn weights_of(m: &MotivationsRecord, columns: &[String]) -> Vec<Option<f64>> {
    (columns.iter())
        .map(|c| m.table.iter().find(|e| e.name == *c).map(|e| e.weight))
        .collect()
}

/// A TOML value as a CSV cell: strings without their quotes, anything else as written.
fn cell_of_toml(text: &str) -> String {
    match toml::from_str::<toml::Table>(&format!("v = {text}")) {
        Ok(t) => match t.get("v") {
            Some(toml::Value::String(s)) => s.clone(),
            _ => text.to_string(),
        },
        Err(_) => text.to_string(),
    }
}

type Groups<'a> = Vec<((String, String), Vec<&'a SweepResultRow>)>;

/// The rows per (setting, room), in plan order.
fn group_by_setting_and_room(rows: &[SweepResultRow]) -> Groups<'_> {
    let mut groups: Groups<'_> = Vec::new();
    for r in rows {
        let key = (r.setting.clone(), r.room.clone());
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, v)) => v.push(r),
            None => groups.push((key, vec![r])),
        }
    }
    groups
}

/// Per metric, mean and sample std over the rows that have a value (see [`mean_std`]).
fn metric_stats(members: &[&SweepResultRow]) -> [(Option<f64>, Option<f64>); 5] {
    std::array::from_fn(|k| {
        let vals: Vec<f64> = members.iter().filter_map(|r| r.values[k]).collect();
        mean_std(&vals)
    })
}

fn aggregate_csv(rows: &[AggregateRow]) -> String {
    if rows.is_empty() {
        // No finished job yet: the header alone.
        let mut h = String::from("setting,room,n");
        for m in METRICS {
            let _ = write!(h, ",{m}_mean,{m}_std");
        }
        return h + "\n";
    }
    to_csv(rows)
}

fn aggregate_markdown(groups: &Groups<'_>) -> String {
    let mut md = String::from("| setting | room | n |");
    for m in METRICS {
        let _ = write!(md, " {m} |");
    }
    md.push_str("\n|---|---|---|");
    md.push_str(&"---|".repeat(METRICS.len()));
    md.push('\n');
    for ((setting, room), members) in groups {
        let _ = write!(md, "| {setting} | {room} | {} |", members.len());
        for (mean, std) in metric_stats(members) {
            let cell = match (mean, std) {
                (None, _) => "n/a".to_string(),
                (Some(m), None) => format!("{m:.2} ± —"),
                (Some(m), Some(s)) => format!("{m:.2} ± {s:.2}"),
            };
            let _ = write!(md, " {cell} |");
        }
        md.push('\n');
    }
    let _ = writeln!(
        md,
        "\nMean ± std over a setting's replicates that have a value ({STD_IS_SAMPLE})."
    );
    md
}

/// Per setting (in plan order), its motivations and the mean of every outcome over its rooms
/// and replicates, for `summary.svg`.
fn setting_points(groups: &Groups<'_>) -> Vec<SettingPoint> {
    let mut per_setting: Vec<(String, [f64; 4], [Vec<f64>; 5])> = Vec::new();
    for ((setting, _), members) in groups {
        let entry = match per_setting.iter().position(|(s, _, _)| s == setting) {
            Some(i) => &mut per_setting[i],
            None => {
                let m = members[0].motivations.as_array();
                per_setting.push((setting.clone(), m, Default::default()));
                per_setting.last_mut().expect("just pushed")
            }
        };
        for r in members {
            for (k, v) in r.values.iter().enumerate() {
                if let Some(v) = v {
                    entry.2[k].push(*v);
                }
            }
        }
    }
    per_setting
        .into_iter()
        .map(|(label, motivations, vals)| SettingPoint {
            label,
            motivations,
            values: std::array::from_fn(|k| mean_std(&vals[k + 1]).0),
            spread: std::array::from_fn(|k| mean_std(&vals[k + 1]).1),
            n: std::array::from_fn(|k| vals[k + 1].len()),
        })
        .collect()
}

/// Mean and sample standard deviation ([`statistics::mean`], [`statistics::sample_sd`]: divided
/// by n − 1): no mean for no values, no std for fewer than two (one value has no spread).
fn mean_std(v: &[f64]) -> (Option<f64>, Option<f64>) {
    if v.is_empty() {
        return (None, None);
    }
    (Some(statistics::mean(v)), statistics::sample_sd(v))
}
