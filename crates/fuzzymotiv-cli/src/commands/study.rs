//! `fuzzymotiv study STUDY.toml --out DIR`: a study of one's own (its arms, paired seeds and
//! typed hypotheses) run by the library ([`fuzzymotiv_pipeline::study`]); this front only parses the
//! arguments and prints.

use std::path::{Path, PathBuf};

use crate::console::note;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::records::hypotheses::{ClaimRow, POOLED};
use fuzzymotiv_pipeline::render::claim_format::claim_line;
use fuzzymotiv_pipeline::study::{
    Study, StudyOptions, StudyOutcome, StudyProgress, parse_shard, run_study,
};

use crate::progress::JobsProgress;

/// Arguments of `fuzzymotiv study`.
#[derive(clap::Args)]
pub struct StudyArgs {
    /// Study file: `[study]` (name, seeds, base_seeds), `[analysis]`, `[[arm]]`s and
    /// `[[hypothesis]]`s (docs/guide/studies.md).
    pub study: PathBuf,
    /// Output directory: the runs in DIR/jobs/ID/ (their transfers to Enki in
    /// DIR/transfer/ID/ROOM/), the analysis (claims.csv, per_seed.csv, rooms.csv, study.json,
    /// report.md, forest.svg; agreement.csv with several base seeds) beside them once every run
    /// is there.
    #[arg(long)]
    pub out: PathBuf,
    /// Run shard K of N (0-based): the runs whose plan index ≡ K mod N; the analysis is
    /// written by whichever command finds every run finished.
    #[arg(long, value_name = "K/N", allow_hyphen_values = true)]
    pub shard: Option<String>,
    /// Worker threads, 1 to 256 [default: all cores]; results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = fuzzymotiv_pipeline::files::inputs::parse_threads)]
    pub threads: Option<usize>,
    /// No progress lines on stderr.
    #[arg(long, short)]
    pub quiet: bool,
    /// Replace another study (or other fuzzymotiv output) in --out: its own files and run
    /// folders are removed, never another file.
    #[arg(long)]
    pub force: bool,
}

impl StudyProgress for JobsProgress {
    fn waiting(&self, done: usize, total: usize) {
        note!(
            "{done} of the study's {total} runs are finished: the analysis is written once the \
             other shards have run (or run the study again without --shard)"
        );
    }

    fn analysed(&self, _out: &Path, _claims: &[ClaimRow]) {}

    fn transferring(&self, done: usize, total: usize, key: &str, room: &str) {
        if !self.quiet() {
            note!(
                "transfer {} of {total}: run {key} to Enki in room {room}",
                done + 1
            );
        }
    }
}

/// Entry point of `fuzzymotiv study`.
pub fn study(args: StudyArgs) -> Result<(), CliError> {
    let shard = args.shard.as_deref().map(parse_shard).transpose()?;
    let study = Study::load(&args.study)?;
    crate::console::config_notes(&study.plan.notes);
    let options = StudyOptions {
        out: args.out.clone(),
        threads: args.threads,
        force: args.force,
        shard,
    };
    let progress = JobsProgress::new(args.quiet);
    if let StudyOutcome::Analysed(claims) = run_study(&study, &options, &progress)? {
        for c in claims.iter().filter(|c| c.scope == POOLED) {
            crate::console::outln!("{}", claim_line(c))?;
        }
        note!("report: {}", args.out.join("report.md").display());
    }
    Ok(())
}
