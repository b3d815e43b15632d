//! The paper's study: high against low curiosity over paired seeds, each setting's tables and
//! figures, the paper's claims tested on them, `report.html` and `summary.json`.

use std::path::Path;
use std::time::Instant;

use crate::files::error::CliError;
use crate::files::guard::write_atomic;
use crate::records::{ClaimRecord, PROGRAM, StudySummary, to_json};
use crate::render::figures::write_figure_at;
use crate::render::report::{Section, reproduce_page};
use crate::render::study::{
    CLAIMS_ALPHA, DEFAULT_MODEL, SETTINGS, SettingRuns, claims as paper_claims, overall,
};
use crate::render::svg::{FitnessPanel, best_paths_svg, fitness_panels_svg};
use crate::render::tables::{
    Provenance, claims_html, claims_table, spread_html, study_table, verdict,
};

use super::runs::{commit, run_one_study};
use super::{Front, ReproduceOptions};

/// The paper's study into `options.out`; returns its tables and its claims, one a line.
pub fn paper(options: &ReproduceOptions, front: Front<'_>) -> Result<String, CliError> {
    let start = Instant::now();
    let Some((staged, studies)) = run_one_study(options, front, &SETTINGS, DEFAULT_MODEL.name)?
    else {
        return Ok(String::new());
    };
    let written = write_study(
        options,
        front,
        options.seed,
        &staged.staging,
        &studies,
        start,
    )?;
    commit(staged, start, front.progress)?;
    Ok(written.tables + &claim_lines(&written.claims))
}

/// What [`write_study`] wrote: the study's claims, and its tables as the paper's study shows
/// them.
pub struct WrittenStudy {
    /// The claims, each verdict from the study's records.
    pub claims: Vec<ClaimRecord>,
    /// Each setting's table under its title.
    pub tables: String,
}

/// Tables, figures, claims, `report.html` and `summary.json` of a study at base seed `base` in
/// `dir`; the claims are the study's own, each verdict from its records by the stated rule
/// ([`paper_claims`]).
pub fn write_study(
    options: &ReproduceOptions,
    front: Front<'_>,
    base: u64,
    dir: &Path,
    studies: &[SettingRuns<'_>],
    start: Instant,
) -> Result<WrittenStudy, CliError> {
    let mut tables = String::new();
    let provenance = Provenance::new(&studies[0].seeds, &studies[0].contexts[0], options.quick);
    let mut panels = Vec::new();
    for (k, study) in studies.iter().enumerate() {
        let (md, csv, seeds_csv) = study_table(study, &provenance);
        write_atomic(&dir.join(format!("table{}.md", k + 1)), &md)?;
        write_atomic(&dir.join(format!("table{}.csv", k + 1)), &csv)?;
        write_atomic(&dir.join(format!("table{}_seeds.csv", k + 1)), &seeds_csv)?;
        tables += &format!(
            "Table {} — {} (C, H, O, E) = {:?}\n{md}\n",
            k + 1,
            study.setting.name,
            study.contexts[study.median()].motivations.as_array(),
        );
        panels.push(write_setting_figure(front, dir, study)?);
    }
    let fitness = fitness_panels_svg(&panels);
    write_figure_at(&dir.join("fitness.svg"), &fitness, front.png)?;
    let settings: Vec<_> = studies.iter().map(SettingRuns::summary).collect();
    let claims = paper_claims(&settings, CLAIMS_ALPHA);
    let (md, csv) = claims_table(&claims, &provenance);
    write_atomic(&dir.join("claims.md"), &md)?;
    write_atomic(&dir.join("claims.csv"), &csv)?;
    let wall_seconds = start.elapsed().as_secs_f64();
    let page = page(
        options,
        studies,
        &provenance,
        &claims,
        wall_seconds,
        &fitness,
    );
    write_atomic(&dir.join("report.html"), page)?;
    let summary = StudySummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: base,
        seeds: provenance.seeds.clone(),
        quick: options.quick,
        population: provenance.population,
        generations: provenance.generations,
        overrides: options.sets.clone(),
        settings,
        claims: claims.clone(),
        wall_seconds,
    };
    write_atomic(&dir.join("summary.json"), to_json(&summary))?;
    Ok(WrittenStudy { claims, tables })
}

/// The setting's trajectories figure (its median seed's best robot); returns its panel of the
/// study's fitness figure (medians and inter-quartile bands over seeds).
pub fn write_setting_figure(
    front: Front<'_>,
    dir: &Path,
    study: &SettingRuns<'_>,
) -> Result<FitnessPanel, CliError> {
    let m = study.median();
    let ctx = &study.contexts[m];
    // `(C,H,O,E) = [..]` for the paper's four motivations, every weight by name for others.
    // A list of named weights follows the setting's name after a colon, as a run's title.
    let label = ctx.motivations.label();
    let sep = if label.starts_with('(') { " " } else { ": " };
    let title = format!(
        "{}{sep}{label}, {}",
        study.setting.name,
        study.median_label()
    );
    write_figure_at(
        &dir.join(format!("trajectories_{}.svg", study.setting.tag)),
        &best_paths_svg(
            &format!("Best robot, {title}"),
            &ctx.rooms,
            &study.finished[m].trajectories(),
        ),
        front.png,
    )?;
    // The legend says what is drawn over how many seeds.
    // (The name of a setting beyond the paper's four motivations says what it varies.)
    let panel = if ctx.motivations.table.is_empty() {
        format!("{} {:?}", study.setting.name, ctx.motivations.as_array())
    } else {
        study.setting.name.to_string()
    };
    Ok(study.fitness_panel(&panel))
}

/// The study's report page.
fn page(
    options: &ReproduceOptions,
    studies: &[SettingRuns<'_>],
    provenance: &Provenance,
    claims: &[ClaimRecord],
    wall_seconds: f64,
    fitness: &str,
) -> String {
    let spreads: Vec<String> = studies.iter().map(spread_html).collect();
    let sections: Vec<Section<'_>> = studies
        .iter()
        .zip(&spreads)
        .map(|(study, spread)| {
            let m = study.median();
            Section {
                id: study.setting.name,
                title: format!("{} ({})", study.setting.name, study.median_label()),
                ctx: &study.contexts[m],
                done: &study.finished[m],
                paper: Some(study.setting),
                link: Some(format!("{}/report.html", study.run_dir(m))),
                spread: Some(spread.as_str()),
                overall: Some(overall(study)),
            }
        })
        .collect();
    reproduce_page(
        &sections,
        &provenance.line(),
        &options.sets,
        wall_seconds,
        &claims_html(claims),
        fitness,
    )
}

/// The claims one a line: the claim, its verdict and its evidence.
pub fn claim_lines(claims: &[ClaimRecord]) -> String {
    claims
        .iter()
        .map(|c| format!("{}: {} ({})\n", c.claim, verdict(c), c.evidence))
        .collect()
}
