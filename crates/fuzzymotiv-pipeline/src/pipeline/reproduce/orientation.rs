//! The orientation study: a built-in sweep (configs/orientation-study.toml: three motivation
//! settings × seeds, online orientation), run in-process, then merged into tables and plots.

use std::path::Path;
use std::time::Instant;

use crate::files::error::CliError;
use crate::pipeline::sweep_jobs::run_jobs;
use crate::pipeline::sweep_merge::merge_dir;
use crate::pipeline::sweep_plan::Sweep;

use super::runs::add_pngs;
use super::{Front, ReproduceOptions};

/// The built-in sweep of the orientation study.
const ORIENTATION_STUDY: &str = include_str!("../../../../../configs/orientation-study.toml");

/// Does rewarding orientation (online recognition in the fitness) raise recognition, and at
/// what cost? The sweep's jobs into `options.out`, then its merge, whose table is the text
/// returned to show.
pub fn orientation(options: &ReproduceOptions, front: Front<'_>) -> Result<String, CliError> {
    let start = Instant::now();
    let out = &options.out;
    let mut sets: Vec<String> = Vec::new();
    sets.push(format!("seed={}", options.seed));
    if options.quick {
        sets.push("ga.population=30".into());
        sets.push("ga.generations=30".into());
        sets.push("sweep.replicates=2".into());
    }
    sets.extend(options.sets.iter().cloned());
    // Apply overrides to the document (config keys and sweep keys alike).
    let mut table: toml::Table =
        toml::from_str(ORIENTATION_STUDY).expect("built-in sweep is valid TOML");
    fuzzymotiv::experiment::apply_sets(&mut table, &sets)?;
    let text = toml::to_string(&table).expect("a table serialises");
    let sweep = Sweep::parse_str(&text, "built-in orientation study", Path::new("."))?;
    let notes = front.progress;
    for line in &sweep.notes {
        notes.note(&format!("note: {line}"));
    }
    let all: Vec<usize> = (0..sweep.jobs.len()).collect();
    notes.note(&format!(
        "orientation study: {} jobs into {}",
        all.len(),
        out.display()
    ));
    run_jobs(
        &sweep,
        &text,
        &all,
        out,
        options.force,
        &*front.progress.jobs(),
    )?;
    let merged = merge_dir(out, notes)?;
    if let Some(png) = front.png {
        add_pngs(out, png, notes)?;
    }
    notes.note(&format!(
        "orientation study done in {:.1} s",
        start.elapsed().as_secs_f64()
    ));
    Ok(merged.markdown)
}
