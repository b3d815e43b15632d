//! `fuzzymotiv recognise`: the rooms a run's room model recognises in a real robot's logs
//! ([`fuzzymotiv_pipeline::records::robot_log::recognise_logs`] over the library's
//! `Experiment::recognizer` and `Experiment::explain_actions`).

use std::path::PathBuf;

use crate::console::{note, outln};
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::FilesState;
use fuzzymotiv_pipeline::pipeline::recognise::recognise_into;

/// Arguments of `fuzzymotiv recognise`.
#[derive(clap::Args)]
pub struct RecogniseArgs {
    /// A run directory (its best_genome.json and config.resolved.toml; all-rooms training).
    #[arg(value_name = "RUN_DIR")]
    pub run: PathBuf,
    /// The logs: CSV files, one row per step, with an `action` column (straight, left, right,
    /// back) or `m_left` and `m_right` (motor outputs in [0, 1]); other columns (`ir0`…`ir7`,
    /// a pose `x`, `y`, `heading`) are read past. Per log the answer gives the room, the SOM's
    /// winner, the room's r-node and their distance in nodes against the gate's width
    /// (`aem.threshold`), and the log's distance to the room's stored vector.
    #[arg(value_name = "LOG", required = true)]
    pub logs: Vec<PathBuf>,
    /// Also write recognised.csv and recognised.md into this directory (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Replace existing files of these names that hold something else.
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv recognise`.
pub fn recognise(args: RecogniseArgs) -> Result<(), CliError> {
    let out = args.out.as_deref();
    let (md, state) = recognise_into(&args.run, &args.logs, out, args.force)?;
    if let (Some(out), Some(state)) = (out, state) {
        if state == FilesState::Write {
            note!("wrote {}", out.display());
        } else {
            note!("{} already holds these files; nothing to do", out.display());
        }
    }
    outln!("{md}")
}
