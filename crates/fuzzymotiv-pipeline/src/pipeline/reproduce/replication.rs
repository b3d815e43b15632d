//! The replication study: the paper's study at base seeds `seed` and `seed + 10` (`OUT/base-S/`,
//! each a whole study), then the claims from their seeds pooled and, per number of seeds, both
//! base seeds' verdicts.

use std::time::Instant;

use crate::files::error::CliError;
use crate::files::guard::StagedDir;
use crate::files::inputs::Loaded;
use crate::records::context::RenderContext;
use crate::records::replication::ReplicationSummary;
use crate::records::{PROGRAM, StudySummary, read_json, to_json};
use crate::render::figures::write_figure_at;
use crate::render::replication::{replication_svg, replication_table, seeds_csv};
use crate::render::report::study_page;
use crate::render::study::{DEFAULT_MODEL, SETTINGS};
use crate::render::tables::Provenance;

use super::paper::write_study;
use super::runs::{commit, load_settings, open_out, run_study, seeds_of};
use super::{Front, ReproduceOptions};

/// Both base seeds' studies, then `replication.md`/`.csv`, `replication_seeds.csv`,
/// `replication.svg`, `report.html` and `summary.json`; returns the table.
pub fn replication(options: &ReproduceOptions, front: Front<'_>) -> Result<String, CliError> {
    let start = Instant::now();
    let bases = [options.seed, options.seed.saturating_add(10)];
    let seeds = bases.map(|b| seeds_of(b, options.seeds));
    let names = bases.map(|b| format!("base-{b}"));
    let loaded = [0, 1].map(|i| load_settings(options, &SETTINGS, &seeds[i], &DEFAULT_MODEL));
    let [la, lb] = loaded;
    let loaded = [la?, lb?];
    let parts: Vec<(&str, &Vec<Vec<Loaded>>)> =
        names.iter().map(String::as_str).zip(&loaded).collect();
    let Some(staged) = open_out(options, front, &SETTINGS, &parts)? else {
        return Ok(String::new());
    };
    let runs = 2 * SETTINGS.len() * seeds[0].len();
    front.progress.begin(&loaded[0][0][0].experiment, runs);
    for (i, loaded) in loaded.iter().enumerate() {
        let dir = staged.staging.join(&names[i]);
        let label = format!("{} · ", names[i]);
        let studies = run_study(front, &SETTINGS, &seeds[i], loaded, &dir, &label)?;
        write_study(options, front, bases[i], &dir, &studies, Instant::now())?;
    }
    front.progress.end();
    let prov = Provenance::new(
        &seeds[0],
        &RenderContext::of(&loaded[0][0][0]),
        options.quick,
    );
    let md = write_replication(options, front, &staged, bases, &names, &prov, start)?;
    commit(staged, start, front.progress)?;
    Ok(md + "\n")
}

/// The replication's own files from both base seeds' `summary.json` in `staged`; returns its
/// table.
fn write_replication(
    options: &ReproduceOptions,
    front: Front<'_>,
    staged: &StagedDir,
    bases: [u64; 2],
    names: &[String; 2],
    prov: &Provenance,
    start: Instant,
) -> Result<String, CliError> {
    let [a, b] = [0, 1]
        .map(|i| read_json::<StudySummary>(&staged.staging.join(&names[i]).join("summary.json")));
    let (a, b) = (a?, b?);
    let (pooled, rows, by_seeds, needed) = crate::render::replication::replication(&a, &b);
    let seeds = prov.seeds.len();
    let (md, csv) = replication_table(bases, seeds, &rows, needed, &prov.line());
    staged.write("replication.md", &md)?;
    staged.write("replication.csv", &csv)?;
    staged.write("replication_seeds.csv", seeds_csv(&pooled, &by_seeds))?;
    let figure = replication_svg(bases, &pooled, &by_seeds);
    write_figure_at(&staged.staging.join("replication.svg"), &figure, front.png)?;
    let parts: Vec<(String, String)> = (names.iter())
        .map(|n| (format!("{n}/report.html"), n.clone()))
        .collect();
    staged.write(
        "report.html",
        study_page(
            "Verdicts that replicate: the study at two base seeds",
            start.elapsed().as_secs_f64(),
            &md,
            &[(
                figure.as_str(),
                "Per number of seeds, each claim's verdict at both base seeds (replication_seeds.csv).",
            )],
            &parts,
        ),
    )?;
    let summary = ReplicationSummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        base_seeds: bases,
        seeds,
        quick: options.quick,
        population: prov.population,
        generations: prov.generations,
        overrides: options.sets.clone(),
        rows,
        by_seeds,
        seeds_needed: needed,
        pooled,
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    Ok(md)
}
