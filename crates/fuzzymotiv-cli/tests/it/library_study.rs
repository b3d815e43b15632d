//! Issue #55: a study runs from the library (`fuzzymotiv_pipeline::pipeline::reproduce`) with plain
//! options and a progress of the caller's, with the command line's results.

use crate::common;

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use common::{Fm, SMALL, assert_same_results, stderr, stdout};
use fuzzymotiv::experiment::Experiment;
use fuzzymotiv_pipeline::files::notes::Notes;
use fuzzymotiv_pipeline::pipeline::progress::{
    JobsSummary, NoProgress, RunProgress, SweepProgress,
};
use fuzzymotiv_pipeline::pipeline::reproduce::{
    Front, ReproduceOptions, ReproduceProgress, StudyKind, reproduce,
};

/// A progress that records what it is told.
#[derive(Default)]
struct Recorded {
    begun: Mutex<Vec<usize>>,
    runs: Mutex<Vec<String>>,
    ended: Mutex<usize>,
    notes: Mutex<Vec<String>>,
}

impl Notes for Recorded {
    fn note(&self, line: &str) {
        self.notes.lock().unwrap().push(line.to_string());
    }
}

impl ReproduceProgress for Recorded {
    fn begin(&self, _exp: &Experiment, runs: usize) {
        self.begun.lock().unwrap().push(runs);
    }
    fn run(&self, name: &str) -> Box<dyn RunProgress + '_> {
        self.runs.lock().unwrap().push(name.to_string());
        Box::new(NoProgress)
    }
    fn end(&self) {
        *self.ended.lock().unwrap() += 1;
    }
    fn jobs(&self) -> Box<dyn SweepProgress + '_> {
        Box::new(NoProgress)
    }
}

/// The paper's study from the library writes the same results as `fuzzymotiv reproduce` (but
/// for wall times), returns what the command prints, and reports each of its runs by name.
#[test]
fn a_study_runs_from_the_library_with_the_command_lines_results() {
    let dir = tempfile::tempdir().unwrap();
    let cli = dir.path().join("cli");
    let o = Fm::new(["reproduce", "--quick", "--seeds", "2", "--threads", "1"])
        .sets(&SMALL)
        .out(&cli)
        .run();
    assert!(o.status.success(), "{}", stderr(&o));
    let lib = dir.path().join("lib");
    let options = ReproduceOptions {
        out: lib.clone(),
        quick: true,
        seeds: 2,
        threads: Some(1),
        sets: SMALL.iter().map(|s| s.to_string()).collect(),
        ..ReproduceOptions::new(StudyKind::Paper)
    };
    let progress = Recorded::default();
    let front = Front {
        progress: &progress,
        png: None,
    };
    let text = reproduce(&options, front).unwrap();
    assert_eq!(text, stdout(&o));
    assert_same_results(&lib, &cli);
    assert_eq!(*progress.begun.lock().unwrap(), [4]);
    assert_eq!(*progress.ended.lock().unwrap(), 1);
    let mut runs = progress.runs.lock().unwrap().clone();
    runs.sort();
    assert_eq!(
        runs,
        [
            "high-curiosity seed #1",
            "high-curiosity seed #2",
            "low-curiosity seed #1",
            "low-curiosity seed #2"
        ]
    );
    // Issue #56 item 2: the library's notes come to the caller's progress (the command line
    // prints them on stderr), the same lines.
    let notes = progress.notes.lock().unwrap().clone();
    assert!(
        notes.len() == 1 && notes[0].starts_with(&format!("wrote {} (", lib.display())),
        "{notes:?}"
    );
    assert!(stderr(&o).contains("wrote "), "{}", stderr(&o));
    // Run again, the study is already there: nothing to do, nothing to show.
    assert_eq!(reproduce(&options, front).unwrap(), "");
    let notes = progress.notes.lock().unwrap().clone();
    assert!(notes[1].contains("already holds this study"), "{notes:?}");
}

/// The command line's default output directories are the library's, per study and size.
#[test]
fn each_study_has_its_default_output_directory() {
    let out = |kind: StudyKind, quick| kind.default_out(quick).display().to_string();
    assert_eq!(out(StudyKind::Paper, false), "results");
    assert_eq!(out(StudyKind::Paper, true), "results-quick");
    assert_eq!(
        out(StudyKind::SearchStrength, true),
        "results-search-strength-quick"
    );
    assert_eq!(out(StudyKind::Urgency, false), "results-urgency");
}

/// A saved genome replays from the library (`fuzzymotiv_pipeline::pipeline::replay`) into the
/// trajectory and the JSON entry that `fuzzymotiv replay` writes for it.
#[test]
fn a_genome_replays_from_the_library_as_the_command_line_replays_it() {
    use fuzzymotiv_pipeline::files::inputs::load_config;
    use fuzzymotiv_pipeline::pipeline::replay::{replay_config, replay_trials, room_files};
    use fuzzymotiv_pipeline::records::context::RenderContext;
    use fuzzymotiv_pipeline::records::genome::read_genome;

    let dir = tempfile::tempdir().unwrap();
    let run = dir.path().join("run");
    let cfg = dir.path().join("small.toml");
    std::fs::write(&cfg, "seed = 3\nrooms = [\"H\", \"square\"]\n").unwrap();
    let o = Fm::new(["run", cfg.to_str().unwrap()])
        .sets(&SMALL)
        .out(&run)
        .run();
    assert!(o.status.success(), "{}", stderr(&o));
    let page = dir.path().join("cli/replay.html");
    let o = Fm::new(["replay", run.to_str().unwrap()]).out(&page).run();
    assert!(o.status.success(), "{}", stderr(&o));

    let config = run.join("config.resolved.toml");
    let loaded = load_config(Some(&config), &[], None).unwrap();
    let genome = read_genome(&run.join("best_genome.json")).unwrap();
    let rooms = loaded.raw.rooms.clone();
    let loaded = replay_config(&loaded, &genome, rooms, "run").unwrap();
    let trials = replay_trials(&loaded.experiment, &genome, &mut |_| {}).unwrap();
    let ctx = RenderContext::of(&loaded);
    let mut files = Vec::new();
    let lib = dir.path().join("lib");
    let (lines, rooms) = room_files(&ctx, &lib, "replay", &trials, &mut files);
    assert_eq!(files.len(), ctx.rooms.len(), "a CSV per room");
    for (path, bytes) in &files {
        let name = path.strip_prefix(&lib).unwrap();
        let cli_csv = std::fs::read(dir.path().join("cli").join(name)).unwrap();
        assert!(*bytes == cli_csv, "{} differs", name.display());
    }
    assert!(lines[0].starts_with("H: a = "), "{lines:?}");
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("cli/replay.json")).unwrap())
            .unwrap();
    assert_eq!(json["rooms"], serde_json::Value::Array(rooms));
}

/// Stops every run once `limit` generations have been reported over the study.
struct StopAfter {
    limit: usize,
    seen: AtomicUsize,
}
impl RunProgress for &StopAfter {
    fn note(&self, _: &str) {}
    fn skip(&self, _: usize) {}
    fn generation(&self, _: &str, _: usize, _: usize, _: f64) {
        self.seen.fetch_add(1, Ordering::SeqCst);
    }
    fn stop(&self) -> bool {
        self.seen.load(Ordering::SeqCst) >= self.limit
    }
}
impl Notes for StopAfter {
    fn note(&self, _: &str) {}
}
impl SweepProgress for StopAfter {
    fn begin(&self, _: usize, _: usize) {}
    fn job(
        &self,
        _: &fuzzymotiv_pipeline::records::Job,
        _: usize,
        _: &Experiment,
    ) -> Box<dyn RunProgress + '_> {
        Box::new(self)
    }
    fn job_done(&self) {}
    fn end(&self, _summary: &JobsSummary) {}
}
impl fuzzymotiv_pipeline::study::StudyProgress for StopAfter {
    fn waiting(&self, _: usize, _: usize) {}
    fn analysed(
        &self,
        _: &std::path::Path,
        _: &[fuzzymotiv_pipeline::records::hypotheses::ClaimRow],
    ) {
    }
}

/// A study of one's own from the library (`fuzzymotiv_pipeline::study`) whose progress asks it to
/// stop (a front's cancel: Ctrl-C in Python, the lab's button) ends with an error after the
/// generation it asked at, and the same call again resumes it into the analysis of an
/// uninterrupted study, byte for byte. Without `RunProgress::stop` the study cannot be stopped
/// before all its runs are finished.
#[test]
fn a_study_stopped_by_its_progress_resumes_into_the_analysis_of_an_uninterrupted_one() {
    use fuzzymotiv_pipeline::study::{Study, StudyOptions, StudyOutcome, run_study};

    let dir = tempfile::tempdir().unwrap();
    let text = format!(
        "[study]\nname = \"stop\"\nseeds = 2\nconfig = {:?}\n\
         set = {{ ga = {{ population = 6, generations = 4 }}, trial = {{ steps = 60 }}, \
         aem = {{ enabled = false }}, rooms = [\"H\"] }}\n\
         [[arm]]\nname = \"low\"\nlevel = 0.1\nset = {{ \"motivations.curiosity\" = 0.1, \"motivations.energy\" = 0.8 }}\n\
         [[arm]]\nname = \"high\"\nlevel = 0.8\n\
         [[hypothesis]]\nid = \"explores\"\nkind = \"compare\"\nmeasure = \"exploration\"\n\
         a = \"high\"\nb = \"low\"\nexpect = \"higher\"\n",
        common::repo()
            .join("configs/tiny.toml")
            .display()
            .to_string()
    );
    let study = Study::parse_str(&text, "stop.toml", dir.path()).unwrap();
    let options = |out: &str| StudyOptions {
        out: dir.path().join(out),
        threads: Some(1),
        ..StudyOptions::default()
    };
    let whole = run_study(&study, &options("whole"), &NoProgress).unwrap();
    assert!(matches!(whole, StudyOutcome::Analysed(_)));
    let stopping = StopAfter {
        limit: 6,
        seen: AtomicUsize::new(0),
    };
    let err = run_study(&study, &options("stopped"), &stopping).unwrap_err();
    assert!(err.to_string().contains("resumes it"), "{err}");
    assert_eq!(stopping.seen.load(Ordering::SeqCst), 6);
    assert!(!dir.path().join("stopped/claims.csv").exists());
    let resumed = run_study(&study, &options("stopped"), &NoProgress).unwrap();
    assert_eq!(resumed, whole);
    for file in [
        "per_seed.csv",
        "claims.csv",
        "rooms.csv",
        "study.json",
        "report.md",
        "forest.svg",
    ] {
        let read = |out: &str| std::fs::read(dir.path().join(out).join(file)).unwrap();
        assert_eq!(read("stopped"), read("whole"), "{file}");
    }
}
