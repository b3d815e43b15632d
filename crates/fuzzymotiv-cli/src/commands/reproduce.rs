//! `fuzzymotiv reproduce`: the paper's study (docs/model.md §10) in one command, and the
//! studies built on it. The arguments become [`ReproduceOptions`]; the study itself is
//! `fuzzymotiv_pipeline::pipeline::reproduce`.

use std::path::PathBuf;

use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::pipeline::reproduce::{
    Front, ReproduceOptions, StudyKind, reproduce as run_study,
};

use crate::args::OutputArgs;
use crate::png::rasteriser;
use crate::progress::ReproduceBar;

/// Arguments of `fuzzymotiv reproduce`.
#[derive(clap::Args)]
#[command(
    mut_arg("out", |a| a.help("Output directory [default: results; with --quick results-quick; with --orientation results-orientation(-quick); with --ablation results-ablation(-quick); with --search-strength results-search-strength(-quick); with --combination, --replication or --urgency results-combination, results-replication or results-urgency (-quick)]. Another study's results there are kept unless --force")),
    mut_arg("force", |a| a.help("Replace another study's results in --out (or an unfinished one) and start over")),
    mut_arg("seed", |a| a.help("Base seed, a whole number from 0 to 2^53 − 1: the study's first seed is this seed, the others derive from it [default: 1]")),
)]
pub struct ReproduceArgs {
    /// --out, --force, --quiet, --seed (default 1: the study's first seed is this seed, the
    /// others derive from it).
    #[command(flatten)]
    pub output: OutputArgs,
    /// Number of seeds per setting; tables give mean ± std over them and every seed's values.
    /// Twenty by default: from eleven seeds on, homing's verdict and Fig. 6's checks agree at
    /// two base seeds (docs/guide/cli.md: why twenty seeds).
    #[arg(long, allow_hyphen_values = true, default_value_t = 20, value_parser = clap::builder::RangedI64ValueParser::<u64>::new().range(1..=1000))]
    pub seeds: u64,
    /// A fast look: GA 30 × 30 instead of the paper's 200 × 200.
    #[arg(long)]
    pub quick: bool,
    /// Worker threads, 1 to 256 [default: all cores]; up to this many (setting, seed) runs go on at once,
    /// sharing them; results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = fuzzymotiv_pipeline::files::inputs::parse_threads)]
    pub threads: Option<usize>,
    /// Run the orientation study instead (configs/orientation-study.toml): does rewarding
    /// orientation (online recognition in the fitness) raise recognition, and at what cost?
    #[arg(long)]
    pub orientation: bool,
    /// Override a config key of both settings (repeatable), e.g. --set trial.steps=200.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Also write a PNG beside every SVG figure.
    #[arg(long)]
    pub png: bool,
    /// Run the ablation instead: the study once with the default model and once with each new
    /// modelling choice switched back (motion, end at home, homing, rooms), and which of the
    /// paper's claims hold under each.
    #[arg(long, conflicts_with = "orientation")]
    pub ablation: bool,
    /// Run the search-strength study instead: the study at GA populations 30, 60, 100 and 200
    /// (the paper's generations), and the paper's claims with their statistics at each, as one
    /// table and one figure (EXPERIMENTS.md).
    #[arg(long, conflicts_with_all = ["orientation", "ablation"])]
    pub search_strength: bool,
    /// Run the combination study instead: the study under the paper's TSK and under the two
    /// baselines of `[fitness] combine` (a weighted sum, a weighted sum of squares), the
    /// claims under each and, between each baseline and the TSK, the paired statistics of each
    /// claim's effect and of the behaviour (EXPERIMENTS.md: does the fuzzy combination matter?).
    #[arg(long, conflicts_with_all = ["orientation", "ablation", "search_strength"])]
    pub combination: bool,
    /// Run the replication study instead: the study at base seed --seed and at --seed + 10
    /// (--seeds each), the claims from each and from all their seeds pooled, and from how
    /// many seeds on both base seeds give the pooled verdicts (EXPERIMENTS.md: why N seeds).
    #[arg(long, conflicts_with_all = ["orientation", "ablation", "search_strength", "combination"])]
    pub replication: bool,
    /// Run the urgency study instead: the fetch mission (configs/fetch.toml: the paper's rooms
    /// with a goal zone in the far corner, built in) with urgency weights 0, 0.1, 0.2 and 0.3
    /// taken from curiosity of the high-curiosity setting, the same seeds for each; success
    /// rate, time to the goal, exploration, battery and homing per weight, and each step up in
    /// urgency compared (EXPERIMENTS.md: the paper's future work).
    #[arg(long, conflicts_with_all = ["orientation", "ablation", "search_strength", "combination", "replication"])]
    pub urgency: bool,
}

impl ReproduceArgs {
    /// `--seed`, by default 1.
    pub fn seed(&self) -> u64 {
        self.output.seed.unwrap_or(1)
    }

    /// The study the flags choose (the paper's without any).
    pub fn kind(&self) -> StudyKind {
        let flags = [
            (self.orientation, StudyKind::Orientation),
            (self.ablation, StudyKind::Ablation),
            (self.search_strength, StudyKind::SearchStrength),
            (self.combination, StudyKind::Combination),
            (self.replication, StudyKind::Replication),
            (self.urgency, StudyKind::Urgency),
        ];
        (flags.iter())
            .find(|(set, _)| *set)
            .map_or(StudyKind::Paper, |&(_, kind)| kind)
    }

    /// `--out`, or the default for the study and its size (a quick look never lands in the
    /// full study's directory).
    pub fn out_dir(&self) -> PathBuf {
        (self.output.out.clone()).unwrap_or_else(|| self.kind().default_out(self.quick))
    }

    /// The library's options for these arguments.
    pub fn options(&self) -> ReproduceOptions {
        ReproduceOptions {
            kind: self.kind(),
            out: self.out_dir(),
            force: self.output.force,
            seed: self.seed(),
            seeds: self.seeds,
            quick: self.quick,
            threads: self.threads,
            sets: self.sets.clone(),
        }
    }
}

/// Entry point of `fuzzymotiv reproduce`: the study of the arguments, its progress on stderr
/// and its tables (and the paper's claims) on stdout.
pub fn reproduce(args: ReproduceArgs) -> Result<(), CliError> {
    let progress = ReproduceBar::new(args.output.quiet);
    let front = Front {
        progress: &progress,
        png: rasteriser(args.png),
    };
    let text = run_study(&args.options(), front)?;
    if text.is_empty() {
        return Ok(());
    }
    crate::console::out!("{text}")
}
