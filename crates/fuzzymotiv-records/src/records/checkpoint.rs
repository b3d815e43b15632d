//! `checkpoint.json`: what a killed run needs to continue (in the run's staging directory,
//! removed when the run finishes).

use std::path::Path;

use fuzzymotiv::experiment::Start;
use fuzzymotiv::experiment::{Experiment, Run};
use fuzzymotiv::experiment::{GenerationRecord, GenerationState, Population, Stopped};
use serde::{Deserialize, Serialize};

use crate::files::bounded::{InputKind, read_input};
use crate::files::error::CliError;
use crate::files::guard::write_atomic;

/// File name of the checkpoint inside the staging directory.
pub const CHECKPOINT: &str = "checkpoint.json";

/// File name of a finished run's last checkpoint (every run done: the final population and
/// every generation's record, exact), from which the run is read back.
pub const POPULATION: &str = "population.json";

/// What a killed run needs to continue: per run of the protocol, the history so far and the
/// next population (floats stored as their exact bit patterns). The random streams are
/// derived per generation, so no generator state needs saving.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Checkpoint {
    /// Format version.
    pub format: u32,
    /// Program version that wrote it.
    pub version: String,
    /// Model version that wrote it ([`fuzzymotiv::MODEL_VERSION`]; 1 when absent): a run is
    /// never continued by a build of another model.
    #[serde(default = "crate::records::model_one")]
    pub model: u32,
    /// Wall time (s) of the run so far, over all sessions.
    #[serde(default)]
    pub wall_seconds: f64,
    /// The names of the experiment's user-defined terms, in the order their values stand in
    /// each generation record's `terms.user` (absent when it has none): a checkpoint is never
    /// continued by an experiment whose user terms differ, so a value never moves to another
    /// term.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub user_terms: Vec<String>,
    /// One entry per run.
    pub runs: Vec<CheckpointRun>,
}

/// The names of `exp`'s user-defined terms, in registration order.
fn user_term_names(exp: &Experiment) -> Vec<String> {
    exp.user_terms().iter().map(|u| u.name.clone()).collect()
}

/// One run's saved state.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct CheckpointRun {
    /// Run label.
    pub label: String,
    /// Whether the last generation has been evaluated (then `population` is the final one).
    pub done: bool,
    /// Per-generation records so far (floats printed by serde_json round-trip exactly).
    pub history: Vec<GenerationRecord>,
    /// Genomes to evaluate next (or the final population), as f64 bits.
    pub population: Vec<Vec<u64>>,
}

impl CheckpointRun {
    /// The saved state of an evolution after a generation.
    pub fn from_state(label: &str, state: &GenerationState<'_>) -> Self {
        let (done, pop) = match state.next {
            Some(next) => (false, next),
            None => (true, state.population),
        };
        CheckpointRun {
            label: label.to_string(),
            done,
            history: state.history.to_vec(),
            population: pop
                .iter()
                .map(|g| g.iter().map(|v| v.to_bits()).collect())
                .collect(),
        }
    }

    /// Where the library's run continues this evolution ([`Experiment::run_from`]); the
    /// saved population is checked against the experiment's network.
    ///
    /// [`Experiment::run_from`]: fuzzymotiv::experiment::Experiment::run_from
    pub fn start(&self, exp: &Experiment) -> Result<Start, CliError> {
        if self.population.is_empty() && !self.done {
            return Ok(Start::Fresh);
        }
        let population = self.population(exp)?;
        let history = self.history.clone();
        Ok(if self.done {
            Start::Finished {
                population,
                history,
            }
        } else {
            Start::Continue(Stopped {
                generation: history.len(),
                population,
                history,
            })
        })
    }

    /// The saved population as floats, checked against the experiment's network.
    pub fn population(&self, exp: &Experiment) -> Result<Population, CliError> {
        let genomes = (self.population.iter())
            .map(|g| g.iter().map(|&b| f64::from_bits(b)).collect())
            .collect();
        exp.population(genomes)
            .map_err(|e| CliError::input(format!("the checkpoint's population: {e}")))
    }
}

impl Checkpoint {
    /// No generation of `exp`'s runs done yet.
    pub fn fresh(exp: &Experiment, runs: &[Run]) -> Self {
        Checkpoint {
            format: 1,
            version: fuzzymotiv::VERSION.to_string(),
            model: fuzzymotiv::MODEL_VERSION,
            wall_seconds: 0.0,
            user_terms: user_term_names(exp),
            runs: runs
                .iter()
                .map(|r| CheckpointRun {
                    label: r.label.clone(),
                    ..Default::default()
                })
                .collect(),
        }
    }

    /// Reads the checkpoint at `path` and checks it against the experiment (no file: a fresh
    /// start); a checkpoint of another config is an error that says `--force` starts over.
    pub fn load(path: &Path, runs: &[Run], exp: &Experiment) -> Result<Self, CliError> {
        Self::load_or(
            path,
            runs,
            exp,
            "pass --force to discard it and start the run over",
        )
    }

    /// [`Checkpoint::load`], with `remedy` ending the error of a checkpoint of another config.
    pub fn load_or(
        path: &Path,
        runs: &[Run],
        exp: &Experiment,
        remedy: &str,
    ) -> Result<Self, CliError> {
        if !path.is_file() {
            // Killed before the first generation finished: start over.
            return Ok(Self::fresh(exp, runs));
        }
        let text = read_input(path, InputKind::record("checkpoint"))?;
        let cp: Checkpoint = serde_json::from_str(&text).map_err(|e| {
            CliError::input(format!(
                "{}: not a fuzzymotiv checkpoint: {e}",
                path.display()
            ))
        })?;
        if cp.model != fuzzymotiv::MODEL_VERSION {
            return Err(CliError::input(format!(
                "{}: written by model {} of fuzzymotiv, and this build is model {}, whose \
                 results differ; continuing it would mix two models in one run. Start it over \
                 with this build ({remedy})",
                path.display(),
                cp.model,
                fuzzymotiv::MODEL_VERSION
            )));
        }
        let names = user_term_names(exp);
        if cp.user_terms != names {
            return Err(CliError::input(format!(
                "{}: field `user_terms`: its generation records hold the values of the user terms \
                 {:?}, and this experiment registers {:?}; register the same terms in the same \
                 order to continue it, or {remedy}",
                path.display(),
                cp.user_terms,
                names
            )));
        }
        let ok = cp.runs.len() == runs.len()
            && cp.runs.iter().zip(runs).all(|(c, r)| {
                c.label == r.label
                    && if c.done {
                        c.history.len() == exp.ga().generations()
                            && c.population.len() == exp.ga().population()
                    } else {
                        c.history.len() < exp.ga().generations()
                    }
                    && c.population
                        .iter()
                        .all(|g| g.len() == exp.shape().genome_len())
                    && (c.history.is_empty() || c.population.len() == exp.ga().population())
            });
        if !ok {
            return Err(CliError::input(format!(
                "{}: the checkpoint does not match the run's config (runs, sizes); {remedy}",
                path.display()
            )));
        }
        Ok(cp)
    }

    /// Says where a resumed run continues.
    pub fn resume_note(&self, out: &Path, generations: usize) -> String {
        match self.runs.iter().find(|r| !r.done) {
            Some(r) => format!(
                "resuming {} at generation {}/{generations}{} ({} generation(s) were done, {:.1} s)",
                out.display(),
                r.history.len() + 1,
                if self.runs.len() > 1 {
                    format!(" of the robot of {}", r.label)
                } else {
                    String::new()
                },
                r.history.len(),
                self.wall_seconds
            ),
            None => format!(
                "resuming {}: evolution finished, writing the results",
                out.display()
            ),
        }
    }

    /// Writes the checkpoint (atomically).
    pub fn save(&self, path: &Path) -> Result<(), CliError> {
        write_atomic(path, serde_json::to_vec(self).expect("serialisable"))
    }
}

#[cfg(test)]
mod tests {
    use fuzzymotiv::experiment::UserTerm;

    use super::*;

    /// The paper's four and a fifth motivation weighing a term named `name` (registered as
    /// supplied, whatever it is called).
    fn experiment(name: &str, registered: &[&str]) -> Experiment {
        let text = format!(
            "[ga]\npopulation = 4\ngenerations = 2\n[aem]\nenabled = false\n[motivations]\n\
             curiosity = 0.7\nhoming = 0.1\norientation = 0.0\nenergy = 0.0\n{name} = 0.2\n"
        );
        let raw = fuzzymotiv::RawConfig::parse(&text, "mine.toml", &[]).unwrap();
        let rooms = vec![fuzzymotiv::Room::builtin("H").unwrap()];
        let terms: Vec<UserTerm> = registered.iter().map(|n| UserTerm::supplied(*n)).collect();
        Experiment::with_terms(&raw, rooms, &terms, "mine.toml").unwrap()
    }

    #[test]
    fn a_checkpoint_names_its_user_terms_and_is_not_continued_with_others() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(CHECKPOINT);
        let smooth = experiment("smooth", &["smooth", "spare"]);
        Checkpoint::fresh(&smooth, &smooth.runs())
            .save(&path)
            .unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.contains(r#""user_terms":["smooth","spare"]"#),
            "{text}"
        );
        assert!(Checkpoint::load(&path, &smooth.runs(), &smooth).is_ok());
        // The same names in another order would move each value to the other term.
        let swapped = experiment("smooth", &["spare", "smooth"]);
        let Err(e) = Checkpoint::load(&path, &swapped.runs(), &swapped) else {
            panic!("a checkpoint was continued with its user terms swapped");
        };
        let message = e.to_string();
        assert!(
            message.contains("field `user_terms`")
                && message.contains(r#"["smooth", "spare"]"#)
                && message.contains(r#"["spare", "smooth"]"#),
            "{message}"
        );
    }

    #[test]
    fn a_paper_checkpoint_writes_no_user_terms() {
        let raw =
            fuzzymotiv::RawConfig::parse("[aem]\nenabled = false\n", "paper.toml", &[]).unwrap();
        let exp = Experiment::new(
            &raw,
            vec![fuzzymotiv::Room::builtin("H").unwrap()],
            "paper.toml",
        )
        .unwrap();
        let json = serde_json::to_string(&Checkpoint::fresh(&exp, &exp.runs())).unwrap();
        assert!(!json.contains("user_terms"), "{json}");
    }
}
