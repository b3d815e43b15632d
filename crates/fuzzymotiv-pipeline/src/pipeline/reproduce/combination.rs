//! The combination study: the study under every combination of [`COMBINATION`] (the paper's
//! TSK and the baselines of `[fitness] combine`), the claims under each, and each claim's
//! effect and each baseline's behaviour against the TSK's, paired by seed.

use std::time::Instant;

use crate::files::error::CliError;
use crate::files::guard::StagedDir;
use crate::files::inputs::Loaded;
use crate::records::combination::CombinationSummary;
use crate::records::context::RenderContext;
use crate::records::{PROGRAM, StudySummary, read_json, to_json};
use crate::render::combination::{
    COMBINATION, behaviour_rows, behaviour_svg, behaviour_table, claim_difference_rows,
    claim_difference_table, claims_table,
};
use crate::render::figures::write_figure_at;
use crate::render::report::study_page;
use crate::render::study::SettingRuns;
use crate::render::tables::Provenance;

use super::runs::{commit, first_config, study_seeds, variant_summary};
use super::variants::{VariantClaims, run_variants_measuring};
use super::{Front, ReproduceOptions};

/// The study under every combination, then `combination.md`, `claim_differences.csv`,
/// `behaviour.csv`, `behaviour.svg`, `report.html` and `summary.json`; returns the tables.
pub fn combination(options: &ReproduceOptions, front: Front<'_>) -> Result<String, CliError> {
    let start = Instant::now();
    let seeds = study_seeds(options);
    let measured = run_variants_measuring(options, front, &seeds, &COMBINATION, end_spreads)?;
    let Some((staged, measured)) = measured else {
        return Ok(String::new());
    };
    let (rows, spreads): (Vec<VariantClaims>, Vec<_>) = measured.into_iter().unzip();
    let studies = COMBINATION
        .iter()
        .map(|v| read_json(&staged.staging.join(v.name).join("summary.json")))
        .collect::<Result<Vec<StudySummary>, CliError>>()?;
    let named: Vec<(&str, &StudySummary)> =
        COMBINATION.iter().map(|v| v.name).zip(&studies).collect();
    let behaviour = behaviour_rows(&named, &spreads);
    let claim_differences = claim_difference_rows(&named);
    let first = first_config(options, &seeds)?;
    let prov = Provenance::new(&seeds, &RenderContext::of(&first), options.quick);
    let (table, csv) = behaviour_table(&behaviour, seeds.len());
    let claims = claims_table(&rows, &prov.line());
    let (differences, differences_csv) = claim_difference_table(&claim_differences, seeds.len());
    let md = format!("{claims}\n\n{differences}\n\n{table}");
    staged.write("combination.md", &md)?;
    staged.write("claim_differences.csv", &differences_csv)?;
    staged.write("behaviour.csv", &csv)?;
    let figure = behaviour_svg(&behaviour);
    write_figure_at(&staged.staging.join("behaviour.svg"), &figure, front.png)?;
    write_page(&staged, &md, &figure, start)?;
    let summary = CombinationSummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: options.seed,
        seeds,
        quick: options.quick,
        population: prov.population,
        generations: prov.generations,
        overrides: options.sets.clone(),
        combinations: (rows.iter())
            .map(|(v, claims)| variant_summary(v, claims))
            .collect(),
        behaviour,
        end_spreads: spreads,
        claim_differences,
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    commit(staged, start, front.progress)?;
    Ok(md + "\n")
}

/// The study's `report.html`: its tables, its figure and a link to each combination's study.
fn write_page(staged: &StagedDir, md: &str, figure: &str, start: Instant) -> Result<(), CliError> {
    let parts: Vec<(String, String)> = (COMBINATION.iter())
        .map(|v| (format!("{}/report.html", v.name), v.name.to_string()))
        .collect();
    staged.write(
        "report.html",
        study_page(
            "Does the fuzzy combination matter?",
            start.elapsed().as_secs_f64(),
            md,
            &[(
                figure,
                "Each baseline − TSK per measure and setting, paired by seed, with its 95 % interval; a filled point is significant and at least the detectable difference.",
            )],
            &parts,
        ),
    )
}

/// Per setting and seed, the end spread of the seed's robots (`Experiment::end_spreads`, mean
/// over rooms).
fn end_spreads(
    loaded: &[Vec<Loaded>],
    studies: &[SettingRuns<'_>],
) -> Result<Vec<Vec<f64>>, CliError> {
    loaded
        .iter()
        .zip(studies)
        .map(|(loaded, study)| {
            loaded
                .iter()
                .zip(&study.finished)
                .map(|(l, done)| {
                    let spreads = l.experiment.end_spreads(&done.outcome).map_err(|e| {
                        CliError::input(format!(
                            "a run's best genome does not fit its network: {e}"
                        ))
                    })?;
                    Ok(spreads.iter().sum::<f64>() / spreads.len().max(1) as f64)
                })
                .collect()
        })
        .collect()
}
