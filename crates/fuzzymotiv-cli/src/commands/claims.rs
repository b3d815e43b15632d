//! `claims`: the paper's claims of a finished study recomputed from its records
//! (`summary.json`), at another significance level if asked, without running anything.

use std::path::PathBuf;

use crate::console::note;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::{FilesState, check_files_dir, write_into};
use fuzzymotiv_pipeline::records::{StudySummary, read_json};
use fuzzymotiv_pipeline::render::study::{CLAIMS_ALPHA, claims, claims_stem};
use fuzzymotiv_pipeline::render::tables::{Provenance, claims_table};

/// Arguments of `fuzzymotiv claims`.
#[derive(clap::Args)]
pub struct ClaimsArgs {
    /// A study directory written by `fuzzymotiv reproduce` (its summary.json is read).
    pub dir: PathBuf,
    /// Significance level α of the verdicts (0 < α < 1) and of the minimum detectable
    /// difference.
    #[arg(long, allow_hyphen_values = true, default_value_t = CLAIMS_ALPHA)]
    pub alpha: f64,
    /// Directory for claims.md and claims.csv [default: DIR itself: at the study's α its own
    /// claims.md and claims.csv (the same tables again are left alone); at another α, A,
    /// claims-alpha-A.md and .csv beside them, never replacing the study's]. Files there with
    /// other contents are kept unless --force.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace claims files that differ (regular files only).
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv claims`: reads DIR/summary.json, recomputes the claims at
/// `--alpha`, writes them through the output guard ([`claims_files`]) and prints the table.
pub fn claims_command(args: ClaimsArgs) -> Result<(), CliError> {
    if args.alpha.is_nan() || args.alpha <= 0.0 || args.alpha >= 1.0 {
        return Err(CliError::input(format!(
            "--alpha must be between 0 and 1 (exclusive), got {}",
            fuzzymotiv::params::Num(args.alpha)
        )));
    }
    if let Some(out) = &args.out {
        check_files_dir(out, "--out", &["claims.md", "claims.csv"])?;
    }
    let summary: StudySummary = read_json(&args.dir.join("summary.json"))?;
    if summary.settings.len() != 2 {
        return Err(CliError::input(format!(
            "{}: a study of the paper's two settings has 2 settings, this one has {}",
            args.dir.join("summary.json").display(),
            summary.settings.len()
        )));
    }
    let provenance = Provenance {
        seeds: summary.seeds.clone(),
        population: summary.population,
        generations: summary.generations,
        quick: summary.quick,
    };
    // Each verdict from the study's own records by the stated rule, whatever an earlier
    // build wrote in summary.json.
    let recomputed = claims(&summary.settings, args.alpha);
    let (md, csv) = claims_table(&recomputed, &provenance);
    let (dir, files) = claims_files(&args, md.clone(), csv);
    // Messages name --out only when the user gave it.
    let option = if args.out.is_some() { "--out" } else { "" };
    let (md_path, csv_path) = (files[0].0.display(), files[1].0.display());
    if write_into(&dir, &files, option, args.force)? == FilesState::Write {
        note!("wrote {md_path} and {csv_path}");
    } else {
        note!("{md_path} and {csv_path} already hold these claims; nothing to do");
    }
    crate::console::out!("{md}")?;
    Ok(())
}

/// Where the claims go: `--out` gets claims.md and claims.csv; without it they go beside the
/// study, named by [`claims_stem`] (the study's own files at its α, `claims-alpha-A.*` at
/// another).
fn claims_files(args: &ClaimsArgs, md: String, csv: String) -> (PathBuf, [(PathBuf, Vec<u8>); 2]) {
    let (dir, stem) = match &args.out {
        Some(out) => (out.clone(), "claims".to_string()),
        None => (args.dir.clone(), claims_stem(args.alpha)),
    };
    let files = [
        (dir.join(format!("{stem}.md")), md.into_bytes()),
        (dir.join(format!("{stem}.csv")), csv.into_bytes()),
    ];
    (dir, files)
}
