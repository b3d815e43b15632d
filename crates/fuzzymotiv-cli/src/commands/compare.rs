//! `compare A B --out DIR`: two runs, studies or sweep settings compared per room and overall
//! (`fuzzymotiv_pipeline::pipeline::compare`), written through the output guard.

use std::path::PathBuf;

use crate::console::note;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::FilesState;
use fuzzymotiv_pipeline::pipeline::compare::{CompareRequest, compare_into};
use fuzzymotiv_pipeline::render::study::CLAIMS_ALPHA;

use crate::png::rasteriser;

/// Arguments of `fuzzymotiv compare`.
#[derive(clap::Args)]
pub struct CompareArgs {
    /// A: a run directory, a study directory (reproduce) or a merged sweep directory.
    pub a: PathBuf,
    /// B: an output of the same kind and rooms as A (may be A itself, with two --setting).
    pub b: PathBuf,
    /// Directory for compare.md, compare.csv and compare.svg (created if missing; files that
    /// differ are kept unless --force).
    #[arg(long)]
    pub out: PathBuf,
    /// A setting of a study or sweep: once, that setting of both; twice, A's then B's.
    #[arg(long = "setting", value_name = "S")]
    pub setting: Vec<String>,
    /// Significance level α of the `*` marks and of the minimum detectable difference.
    #[arg(long, allow_hyphen_values = true, default_value_t = CLAIMS_ALPHA)]
    pub alpha: f64,
    /// Also write compare.png beside compare.svg.
    #[arg(long)]
    pub png: bool,
    /// Replace compare.* files that differ (regular files only).
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv compare`.
pub fn compare_command(args: CompareArgs) -> Result<(), CliError> {
    let (md, state) = compare_into(&CompareRequest {
        a: &args.a,
        b: &args.b,
        out: &args.out,
        settings: &args.setting,
        alpha: args.alpha,
        png: rasteriser(args.png),
        force: args.force,
    })?;
    if state == FilesState::Same {
        note!(
            "{} already holds these files; nothing to do",
            args.out.display()
        );
    }
    crate::console::out!("{md}")?;
    Ok(())
}
