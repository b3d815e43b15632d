//! The urgency study, the paper's future work "urgency for completing specific missions"
//! (crates/fuzzymotiv-render/src/urgency.rs): the fetch mission under four urgency weights
//! taken from curiosity, paired seeds, run as the paper's study is (resumable, the output
//! guard's staging), then compared weight by weight.

use std::path::Path;
use std::time::Instant;

use crate::files::error::CliError;
use crate::files::guard::io_err;
use crate::records::urgency::{UrgencySeed, UrgencySummary};
use crate::records::{PROGRAM, to_json};
use crate::render::figures::write_figure_at;
use crate::render::report::study_page;
use crate::render::study::SettingRuns;
use crate::render::svg::fitness_panels_svg;
use crate::render::tables::Provenance;
use crate::render::urgency::{
    URGENCY, WEIGHTS, comparisons, seed_record, seeds_csv, urgency_svg, urgency_table,
};

use super::paper::write_setting_figure;
use super::runs::{Part, commit, refuse_own_keys, run_one_study, study_seeds};
use super::{Front, ReproduceOptions};

/// What each setting sets itself (a `--set` of it is refused).
const OWN: &str = "urgency's weight u and curiosity 0.8 − u";

/// Every (weight, seed) into `OUT/urgency-U/seed-NN/`, then `urgency.md`/`.csv`,
/// `urgency_seeds.csv`, `urgency.svg`, the median seed's trajectories per weight,
/// `fitness.svg`, `report.html` and `summary.json`; returns the table.
pub fn urgency(options: &ReproduceOptions, front: Front<'_>) -> Result<String, CliError> {
    let start = Instant::now();
    let parts: Vec<Part<'_>> = URGENCY.iter().map(|s| (s.name, OWN, s.sets)).collect();
    refuse_own_keys(&options.sets, &parts)?;
    let seeds = study_seeds(options);
    let Some((staged, studies)) = run_one_study(options, front, &URGENCY, "urgency")? else {
        return Ok(String::new());
    };
    let per_seed = seed_records(&studies);
    let rows = comparisons(&per_seed);
    let prov = Provenance::new(&seeds, &studies[0].contexts[0], options.quick);
    let (md, csv) = urgency_table(&per_seed, &rows, &prov.line());
    staged.write("urgency.md", &md)?;
    staged.write("urgency.csv", &csv)?;
    staged.write("urgency_seeds.csv", seeds_csv(&per_seed))?;
    let figure = urgency_svg(&per_seed);
    write_figure_at(&staged.staging.join("urgency.svg"), &figure, front.png)?;
    let panels = (studies.iter())
        .map(|study| write_setting_figure(front, &staged.staging, study))
        .collect::<Result<Vec<_>, CliError>>()?;
    let fitness = fitness_panels_svg(&panels);
    write_figure_at(&staged.staging.join("fitness.svg"), &fitness, front.png)?;
    staged.write(
        "report.html",
        page(&staged.staging, &studies, &md, &figure, &fitness, start)?,
    )?;
    let summary = UrgencySummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: options.seed,
        seeds,
        quick: options.quick,
        population: prov.population,
        generations: prov.generations,
        overrides: options.sets.clone(),
        weights: WEIGHTS.to_vec(),
        per_seed,
        comparisons: rows,
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    commit(staged, start, front.progress)?;
    Ok(md + "\n")
}

/// The study's `report.html`: its table, its figure, the fitness figure and each weight's
/// median-seed trajectories (read back from `dir`, where they were just written).
fn page(
    dir: &Path,
    studies: &[SettingRuns<'_>],
    md: &str,
    figure: &str,
    fitness: &str,
    start: Instant,
) -> Result<String, CliError> {
    let trajectories = (studies.iter())
        .map(|s| {
            let path = dir.join(format!("trajectories_{}.svg", s.setting.tag));
            std::fs::read_to_string(&path)
                .map(|svg| {
                    (
                        svg,
                        format!("{}: the median seed's best robot.", s.setting.name),
                    )
                })
                .map_err(|e| io_err(&path, e))
        })
        .collect::<Result<Vec<_>, CliError>>()?;
    let mut figures = vec![
        (
            figure,
            "Each measure against urgency's weight: means over seeds with 95 % intervals.",
        ),
        (
            fitness,
            "Fitness evolution per weight: medians over seeds with inter-quartile bands.",
        ),
    ];
    figures.extend(trajectories.iter().map(|(s, c)| (s.as_str(), c.as_str())));
    let parts: Vec<(String, String)> = (studies.iter())
        .flat_map(|s| (0..s.finished.len()).map(move |k| (s, k)))
        .map(|(s, k)| {
            let dir = s.run_dir(k);
            (format!("{dir}/report.html"), dir)
        })
        .collect();
    Ok(study_page(
        "Urgency for missions: the fetch mission at four urgency weights",
        start.elapsed().as_secs_f64(),
        md,
        &figures,
        &parts,
    ))
}

/// Every weight's seeds, weight by weight ([`seed_record`]).
fn seed_records(studies: &[SettingRuns<'_>]) -> Vec<UrgencySeed> {
    studies
        .iter()
        .zip(WEIGHTS)
        .flat_map(|(study, u)| {
            (study.finished.iter().enumerate()).map(move |(k, done)| {
                seed_record(study.setting.name, u, (k + 1, study.seeds[k]), done)
            })
        })
        .collect()
}
