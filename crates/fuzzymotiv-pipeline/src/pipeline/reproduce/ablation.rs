//! The ablation: the study with the default model and with each new modelling choice switched
//! back ([`ABLATION`]), and which of the paper's claims hold under each.

use std::time::Instant;

use crate::files::error::CliError;
use crate::records::context::RenderContext;
use crate::records::{AblationSummary, PROGRAM, to_json};
use crate::render::study::ABLATION;
use crate::render::tables::{Provenance, ablation_table};

use super::runs::{commit, first_config, study_seeds, variant_summary};
use super::variants::run_variants;
use super::{Front, ReproduceOptions};

/// The study for every variant, then which claims hold under each (`ablation.md`/`.csv`,
/// `summary.json`); returns the table.
pub fn ablation(options: &ReproduceOptions, front: Front<'_>) -> Result<String, CliError> {
    let start = Instant::now();
    let seeds = study_seeds(options);
    let Some((staged, rows)) = run_variants(options, front, &seeds, &ABLATION)? else {
        return Ok(String::new());
    };
    let first = first_config(options, &seeds)?;
    let prov = Provenance::new(&seeds, &RenderContext::of(&first), options.quick);
    let (md, csv) = ablation_table(&rows, &prov);
    staged.write("ablation.md", &md)?;
    staged.write("ablation.csv", &csv)?;
    let summary = AblationSummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: options.seed,
        seeds,
        quick: options.quick,
        population: prov.population,
        generations: prov.generations,
        overrides: options.sets.clone(),
        variants: rows
            .iter()
            .map(|(v, claims)| variant_summary(v, claims))
            .collect(),
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    commit(staged, start, front.progress)?;
    Ok(md + "\n")
}
