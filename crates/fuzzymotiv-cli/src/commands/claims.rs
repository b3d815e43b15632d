//! `claims`: the paper's claims of a finished study recomputed from its records
//! (`summary.json`), at another significance level if asked, without running anything.

use std::path::PathBuf;

use crate::console::note;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::FilesState;
use fuzzymotiv_pipeline::pipeline::claims::recompute_claims;
use fuzzymotiv_pipeline::render::study::CLAIMS_ALPHA;

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

/// Entry point of `fuzzymotiv claims`.
pub fn claims_command(args: ClaimsArgs) -> Result<(), CliError> {
    let done = recompute_claims(&args.dir, args.alpha, args.out.as_deref(), args.force)?;
    let (md_path, csv_path) = (done.paths[0].display(), done.paths[1].display());
    if done.state == FilesState::Write {
        note!("wrote {md_path} and {csv_path}");
    } else {
        note!("{md_path} and {csv_path} already hold these claims; nothing to do");
    }
    crate::console::out!("{}", done.md)?;
    Ok(())
}
