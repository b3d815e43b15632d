//! `fuzzymotiv reproduce --urgency`: the paper's future work, "urgency for completing specific
//! missions" (crates/fuzzymotiv-render/src/urgency.rs): the fetch mission under four urgency
//! weights taken from curiosity, paired seeds, run as `reproduce` runs its study (resumable,
//! the output guard's staging), then compared weight by weight.

use std::time::Instant;

use fuzzymotiv_io::files::error::CliError;
use fuzzymotiv_io::pipeline::lanes::set_threads;
use fuzzymotiv_io::records::urgency::{UrgencySeed, UrgencySummary};
use fuzzymotiv_io::records::{PROGRAM, to_json};
use fuzzymotiv_io::render::figures::write_figure_at;
use fuzzymotiv_io::render::study::SettingRuns;
use fuzzymotiv_io::render::svg::fitness_panels_svg;
use fuzzymotiv_io::render::tables::Provenance;
use fuzzymotiv_io::render::urgency::{
    URGENCY, WEIGHTS, comparisons, seed_record, seeds_csv, urgency_svg, urgency_table,
};

use crate::commands::reproduce::{
    Part, ReproduceArgs, commit, refuse_own_keys, run_one_study, study_seeds, write_setting_figure,
};
use crate::png::rasteriser;

/// What each setting sets itself (a `--set` of it is refused).
const OWN: &str = "urgency's weight u and curiosity 0.8 − u";

/// Entry point of `fuzzymotiv reproduce --urgency`: every (weight, seed) into
/// `OUT/urgency-U/seed-NN/`, then `urgency.md`/`.csv`, `urgency_seeds.csv`, `urgency.svg`,
/// the median seed's trajectories per weight, `fitness.svg` and `summary.json`.
pub fn urgency(args: ReproduceArgs) -> Result<(), CliError> {
    set_threads(args.threads)?;
    let start = Instant::now();
    let parts: Vec<Part<'_>> = URGENCY.iter().map(|s| (s.name, OWN, s.sets)).collect();
    refuse_own_keys(&args.sets, &parts)?;
    let seeds = study_seeds(&args);
    let Some((staged, studies)) = run_one_study(&args, &URGENCY, &seeds, "urgency")? else {
        return Ok(());
    };
    let per_seed = seed_records(&studies);
    let rows = comparisons(&per_seed);
    let prov = Provenance::new(&seeds, &studies[0].contexts[0], args.quick);
    let (md, csv) = urgency_table(&per_seed, &rows, &prov.line());
    staged.write("urgency.md", &md)?;
    staged.write("urgency.csv", &csv)?;
    staged.write("urgency_seeds.csv", seeds_csv(&per_seed))?;
    let png = rasteriser(args.png);
    write_figure_at(
        &staged.staging.join("urgency.svg"),
        &urgency_svg(&per_seed),
        png,
    )?;
    let panels = (studies.iter())
        .map(|study| write_setting_figure(&args, &staged.staging, study))
        .collect::<Result<Vec<_>, CliError>>()?;
    write_figure_at(
        &staged.staging.join("fitness.svg"),
        &fitness_panels_svg(&panels),
        png,
    )?;
    let summary = UrgencySummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: args.seed(),
        seeds,
        quick: args.quick,
        population: prov.population,
        generations: prov.generations,
        overrides: args.sets.clone(),
        weights: WEIGHTS.to_vec(),
        per_seed,
        comparisons: rows,
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    commit(staged, start)?;
    fuzzymotiv_io::outln!("{md}")
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
