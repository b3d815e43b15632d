//! `fuzzymotiv claims`: the paper's claims of a finished study recomputed from its records
//! (`summary.json`) at a significance level, without running anything ([`recompute_claims`]),
//! written through the output guard as `claims.md` and `claims.csv` (or, in the study's own
//! directory at another α, `claims-alpha-A.*` beside its own). [`check_alpha`] is the one
//! check of a significance level (`claims`, `compare`).

use std::path::{Path, PathBuf};

use crate::files::error::CliError;
use crate::files::guard::{FilesState, check_files_dir, write_into};
use crate::records::{StudySummary, read_json};
use crate::render::study::{claims, claims_stem};
use crate::render::tables::{Provenance, claims_table};

/// Refuses a significance level α outside (0, 1).
pub fn check_alpha(alpha: f64) -> Result<(), CliError> {
    if alpha.is_nan() || alpha <= 0.0 || alpha >= 1.0 {
        return Err(CliError::input(format!(
            "--alpha must be between 0 and 1 (exclusive), got {}",
            fuzzymotiv::params::Num(alpha)
        )));
    }
    Ok(())
}

/// What [`recompute_claims`] wrote.
#[derive(Debug)]
pub struct RecomputedClaims {
    /// The claims table, Markdown.
    pub md: String,
    /// The Markdown and CSV files, in that order.
    pub paths: [PathBuf; 2],
    /// Whether they were written or already held these claims.
    pub state: FilesState,
}

/// The claims of the study in `dir` recomputed at `alpha` from its `summary.json` (each
/// verdict by the stated rule, whatever an earlier build wrote there), written as
/// `claims.md` and `claims.csv` into `out`, or into `dir` under the α's stem. Other files of
/// those names are kept unless `force`; messages name `--out` only when it was given.
pub fn recompute_claims(
    dir: &Path,
    alpha: f64,
    out: Option<&Path>,
    force: bool,
) -> Result<RecomputedClaims, CliError> {
    check_alpha(alpha)?;
    if let Some(out) = out {
        check_files_dir(out, "--out", &["claims.md", "claims.csv"])?;
    }
    let summary_path = dir.join("summary.json");
    let summary: StudySummary = read_json(&summary_path)?;
    if summary.settings.len() != 2 {
        return Err(CliError::input(format!(
            "{}: a study of the paper's two settings has 2 settings, this one has {}",
            summary_path.display(),
            summary.settings.len()
        )));
    }
    let provenance = Provenance {
        seeds: summary.seeds.clone(),
        population: summary.population,
        generations: summary.generations,
        quick: summary.quick,
    };
    let recomputed = claims(&summary.settings, alpha);
    let (md, csv) = claims_table(&recomputed, &provenance);
    let (target, stem) = match out {
        Some(out) => (out.to_path_buf(), "claims".to_string()),
        None => (dir.to_path_buf(), claims_stem(alpha)),
    };
    let paths = [
        target.join(format!("{stem}.md")),
        target.join(format!("{stem}.csv")),
    ];
    let files = [
        (paths[0].clone(), md.clone().into_bytes()),
        (paths[1].clone(), csv.into_bytes()),
    ];
    let option = if out.is_some() { "--out" } else { "" };
    let state = write_into(&target, &files, option, force)?;
    Ok(RecomputedClaims { md, paths, state })
}
