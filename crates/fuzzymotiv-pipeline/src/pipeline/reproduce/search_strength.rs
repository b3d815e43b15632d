//! The search-strength study: the study at every GA population of [`SEARCH_STRENGTH`], then
//! the claims with their statistics per population.

use std::time::Instant;

use crate::files::error::CliError;
use crate::records::{PROGRAM, StrengthSummary, StudySummary, read_json, to_json};
use crate::render::figures::write_figure_at;
use crate::render::strength::{SEARCH_STRENGTH, strength_svg, strength_table};

use super::runs::{commit, study_seeds, variant_summary};
use super::variants::run_variants;
use super::{Front, ReproduceOptions};

/// The study at every population, tabulated from each population's summary.json as
/// `search_strength.md`/`.csv` and the figure `search_strength.svg`; returns the table.
pub fn search_strength(options: &ReproduceOptions, front: Front<'_>) -> Result<String, CliError> {
    let start = Instant::now();
    let seeds = study_seeds(options);
    let Some((staged, _)) = run_variants(options, front, &seeds, &SEARCH_STRENGTH)? else {
        return Ok(String::new());
    };
    let studies = SEARCH_STRENGTH
        .iter()
        .map(|v| read_json(&staged.staging.join(v.name).join("summary.json")))
        .collect::<Result<Vec<StudySummary>, CliError>>()?;
    let (md, csv) = strength_table(&studies);
    staged.write("search_strength.md", &md)?;
    staged.write("search_strength.csv", &csv)?;
    write_figure_at(
        &staged.staging.join("search_strength.svg"),
        &strength_svg(&studies),
        front.png,
    )?;
    let summary = StrengthSummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: options.seed,
        seeds,
        quick: options.quick,
        generations: studies[0].generations,
        populations: studies.iter().map(|s| s.population).collect(),
        overrides: options.sets.clone(),
        variants: SEARCH_STRENGTH
            .iter()
            .zip(&studies)
            .map(|(v, s)| variant_summary(v, &s.claims))
            .collect(),
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    commit(staged, start, front.progress)?;
    Ok(md + "\n")
}
