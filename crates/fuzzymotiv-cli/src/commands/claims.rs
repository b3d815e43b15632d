//! `claims`: the paper's claims of a finished study recomputed from its records
//! (`summary.json`), at another significance level if asked, without running anything.

use std::path::PathBuf;

use fuzzymotiv_io::files::error::CliError;
use fuzzymotiv_io::files::guard::{FilesState, check_files, io_err, write_files};
use fuzzymotiv_io::records::{StudySummary, read_json};
use fuzzymotiv_io::render::study::{CLAIMS_ALPHA, claims};
use fuzzymotiv_io::render::tables::{Provenance, claims_table};

/// Arguments of `fuzzymotiv claims`.
#[derive(clap::Args)]
pub struct ClaimsArgs {
    /// A study directory written by `fuzzymotiv reproduce` (its summary.json is read).
    pub dir: PathBuf,
    /// Significance level α of the verdicts (0 < α < 1) and of the minimum detectable
    /// difference.
    #[arg(long, allow_hyphen_values = true, default_value_t = CLAIMS_ALPHA)]
    pub alpha: f64,
    /// Directory for claims.md and claims.csv (default: DIR itself; the same tables again are
    /// left alone, other ones are kept unless --force).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace claims.md and claims.csv that differ (regular files only).
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv claims`: reads DIR/summary.json, recomputes the claims at
/// `--alpha`, writes claims.md and claims.csv through the output guard and prints the table.
pub fn claims_command(args: ClaimsArgs) -> Result<(), CliError> {
    if args.alpha.is_nan() || args.alpha <= 0.0 || args.alpha >= 1.0 {
        return Err(CliError::input(format!(
            "--alpha must be between 0 and 1 (exclusive), got {}",
            args.alpha
        )));
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
    let recomputed = claims(&summary.settings, args.alpha);
    let (md, csv) = claims_table(&recomputed, &provenance);
    let out = args.out.unwrap_or(args.dir);
    let files = [
        (out.join("claims.md"), md.clone().into_bytes()),
        (out.join("claims.csv"), csv.into_bytes()),
    ];
    if check_files(&files, "--out", args.force)? == FilesState::Write {
        std::fs::create_dir_all(&out).map_err(|e| io_err(&out, e))?;
        write_files(&files)?;
    }
    fuzzymotiv_io::out!("{md}")?;
    Ok(())
}
