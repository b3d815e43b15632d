//! `fuzzymotiv transfer`: a run's evolved controller driven in Enki, an independent simulator
//! (docs/guide/transfer.md).
//!
//! The run's room is built in Enki (every wall segment of the room file as an immovable
//! rectangle 2 cm thick on the wall's far side, in a walled world 10 cm larger on every side;
//! millimetres become Enki's centimetres), Enki's own model of the run's robot (`Khepera`,
//! `EPuck`, `Thymio2`: stock bodies, sensors and noise) starts at the room's home pose, and the
//! run's controller exported as C (`fuzzymotiv export --to c`, bit for bit the simulator's
//! network) drives it through a small C++ program ([`HARNESS`], compiled here with `c++`
//! against Debian's `libenki-dev`). Each test run becomes a robot log (the format
//! `recognise` and `replay --log` read) and is measured by the code that measures a simulated
//! trial ([`fuzzymotiv::experiment::Experiment::logged_trial`]), beside the run's own test runs
//! in the simulator measured the same way.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use fuzzymotiv::experiment::{Experiment, LoggedStep, LoggedTrial, Run};
use fuzzymotiv::export::{CSources, ExportedController};
use fuzzymotiv::modelling::Action;
use fuzzymotiv::simulation::{Controller, Mlp, MlpShape, Pose, Readings, Room, Vec2};
use serde::{Deserialize, Serialize};

use crate::files::error::CliError;
use crate::files::guard::{FilesState, check_files_dir, io_err, write_into};
use crate::files::inputs::load_config;
use crate::records::genome::{SavedGenome, locate, read_genome};
use crate::records::robot_log::{LogActions, recognise_actions, steps_log};
use crate::records::test_runs::{self, TestRunRow};
use crate::records::{extra_terms, to_csv};

/// The C++ program that runs one test run in Enki (its usage and output are in its comment).
pub const HARNESS: &str = include_str!("transfer/harness.cpp");

/// Centimetres of Enki per millimetre of fuzzymotiv.
const CM: f64 = 0.1;
/// The room's margin inside Enki's walled world (cm).
const MARGIN_CM: f64 = 10.0;
/// The thickness of a wall block (cm).
const WALL_CM: f64 = 2.0;
/// The longest physics step (s).
const PHYSICS_DT: f64 = 0.01;

/// Enki's model of one of fuzzymotiv's robots, and how its readings become the network's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnkiModel {
    /// The robot file's name (`robot = "…"`).
    pub robot: &'static str,
    /// Enki's class.
    pub class: &'static str,
    /// reading = min(scale · Enki's reading, reading_max).
    pub scale: f64,
    /// Where the scale comes from.
    pub source: &'static str,
}

/// The robots Enki has a model of.
pub const ENKI_MODELS: [EnkiModel; 3] = [
    EnkiModel {
        robot: "khepera",
        class: "Khepera",
        scale: 1023.0 / 1200.0,
        source: "Enki's Khepera saturates at m = 1200 (Khepera.cpp: IRSensor range 10 cm, m 1200, x0 -0.9, c 7, noise sd 20), the Khepera's proximity reading at 1023 (robots/khepera.toml): full scale onto full scale, 1023 / 1200",
    },
    EnkiModel {
        robot: "epuck2",
        class: "EPuck",
        scale: 1.0,
        source: "robots/epuck2.toml's response table was measured in Enki (bench/enki/probe_robots.py) and its reading_max 3731 is Enki's saturation m: Enki's readings as they are, clamped to 3731",
    },
    EnkiModel {
        robot: "thymio2",
        class: "Thymio2",
        scale: 1.0,
        source: "robots/thymio2.toml's response table was measured in Enki (bench/enki/probe_robots.py) and its reading_max 4505 is Enki's saturation m: Enki's readings as they are, clamped to 4505",
    },
];

/// What `fuzzymotiv transfer` is asked.
#[derive(Debug, Clone)]
pub struct TransferRequest<'a> {
    /// The run directory.
    pub run: &'a Path,
    /// A room of the run (its name).
    pub room: &'a str,
    /// Test runs in Enki.
    pub runs: usize,
    /// The output directory.
    pub out: &'a Path,
    /// Enki's base seed (test run k uses seed + k) [default: the run's seed].
    pub seed: Option<u64>,
    /// Replace other files of these names.
    pub force: bool,
}

/// One test run's measures, in one world (a row of `measures.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeasureRow {
    /// `enki` or `fuzzymotiv`.
    pub world: String,
    /// The room.
    pub room: String,
    /// The test run's number.
    pub test: usize,
    /// Enki's seed (empty for the simulator's test runs, which use the run's AEM test streams).
    pub seed: Option<u64>,
    /// 100·a: % of the optimal exploration.
    pub exploration_pct: f64,
    /// 100·g.
    pub homing_pct: f64,
    /// 100·b.
    pub battery_pct: f64,
    /// 100 if the room model recognised the room, 0 if not; empty without a room model.
    pub recognition_pct: Option<f64>,
    /// The room recognised, if any.
    pub answer: Option<String>,
    /// Steps executed before the trial ended.
    pub executed_steps: usize,
    /// Executed steps whose move was blocked (fuzzymotiv) or touched a wall (Enki).
    pub blocked_steps: usize,
    /// The step that brought the escaped robot back home, if it came back.
    pub home_at: Option<usize>,
}

/// What a transfer did.
#[derive(Debug, Clone)]
pub struct Transferred {
    /// The files, in order.
    pub files: Vec<PathBuf>,
    /// Whether they already held these bytes (nothing written).
    pub unchanged: bool,
    /// The comparison of the two worlds, one line each.
    pub comparison: String,
    /// Notes for the user.
    pub notes: Vec<String>,
}

/// The run being transferred.
struct Source {
    config: PathBuf,
    experiment: Experiment,
    genome: SavedGenome,
    weights: Vec<f64>,
    room: usize,
    model: EnkiModel,
    run: Run,
}

/// The output files' names for `runs` test runs.
fn file_names(runs: usize) -> Vec<String> {
    let mut names: Vec<String> = (0..runs).map(|k| format!("run-{k}.csv")).collect();
    names.extend(["test_runs.csv", "measures.csv", "transfer.md"].map(String::from));
    names
}

/// The logs `run-K.csv` in `out` with K ≥ `runs`: an earlier transfer's with more test runs,
/// which this one's measures.csv and test_runs.csv would not count.
fn stale_runs(out: &Path, runs: usize) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(out) else {
        return Vec::new();
    };
    let mut stale: Vec<(usize, PathBuf)> = entries
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            let name = e.file_name().into_string().ok()?;
            let k: usize = name
                .strip_prefix("run-")?
                .strip_suffix(".csv")?
                .parse()
                .ok()?;
            (k >= runs).then(|| (k, e.path()))
        })
        .collect();
    stale.sort();
    stale.into_iter().map(|(_, p)| p).collect()
}

/// Refuses an `--out` holding an earlier transfer's extra logs unless `force` (then they are
/// removed once the new files are written: see [`transfer`]).
fn check_stale_runs(out: &Path, runs: usize, force: bool) -> Result<Vec<PathBuf>, CliError> {
    let stale = stale_runs(out, runs);
    if stale.is_empty() || force {
        return Ok(stale);
    }
    let names: Vec<String> = stale
        .iter()
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    Err(CliError::input(format!(
        "--out {}: holds {} of an earlier transfer with more test runs than --runs {runs}; this \
         transfer's measures would not count them. Choose another --out, or --force to replace \
         that transfer (its extra logs are removed)",
        out.display(),
        names.join(", ")
    )))
}

/// Runs the transfer (see the module's docs) and writes its files through the output guard.
pub fn transfer(req: &TransferRequest) -> Result<Transferred, CliError> {
    if req.runs == 0 {
        return Err(CliError::input("--runs: must be at least 1 test run"));
    }
    let names = file_names(req.runs);
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    check_files_dir(req.out, "--out", &refs)?;
    let stale = check_stale_runs(req.out, req.runs, req.force)?;
    let src = load_source(req)?;
    let build = tempfile::tempdir().map_err(|e| CliError::io(format!("a build directory: {e}")))?;
    let harness = build_harness(&src, build.path())?;
    let network = network_of(&src)?;
    let base = req.seed.unwrap_or(src.experiment.seed());
    let mut notes = Vec::new();
    let mut logs = Vec::new();
    let mut enki = Vec::new();
    for k in 0..req.runs {
        let seed = base + k as u64;
        let trial = run_in_enki(&src, &network, &harness, build.path(), seed)?;
        let measured = src.experiment.logged_trial(src.room, &trial.steps);
        let kept = measured.executed;
        let home = src.experiment.arenas()[src.room].room().home;
        logs.push(steps_log(
            home,
            &trial.steps[..kept],
            Some(("enki", &trial.raw[..kept])),
        ));
        enki.push((seed, trial.steps[..kept].to_vec(), measured));
    }
    let answers = recognition(&src, &network, &enki, &mut notes)?;
    let enki_rows: Vec<MeasureRow> = (enki.iter().zip(&answers).enumerate())
        .map(|(k, ((seed, _, m), answer))| measure_row(&src, "enki", k, Some(*seed), m, answer))
        .collect();
    let sim_rows = simulated_rows(req.run, &src, &network, &mut notes)?;
    let comparison = comparison(&src, &enki_rows, &sim_rows);
    let mut files: Vec<(PathBuf, Vec<u8>)> = (logs.into_iter().enumerate())
        .map(|(k, text)| (req.out.join(&names[k]), text.into_bytes()))
        .collect();
    let tests = test_run_rows(&src, &enki, &answers);
    let mut all = enki_rows.clone();
    all.extend(sim_rows);
    let md = transfer_md(req, &src, base, &comparison);
    for (name, text) in [
        ("test_runs.csv", test_runs::to_text(&tests)),
        ("measures.csv", to_csv(&all)),
        ("transfer.md", md),
    ] {
        files.push((req.out.join(name), text.into_bytes()));
    }
    let state = write_into(req.out, &files, "--out", req.force)?;
    for path in stale {
        std::fs::remove_file(&path).map_err(|e| io_err(&path, e))?;
    }
    Ok(Transferred {
        files: files.into_iter().map(|(p, _)| p).collect(),
        unchanged: state == FilesState::Same,
        comparison,
        notes,
    })
}

/// The run's config, experiment, genome, the room and Enki's model of its robot.
fn load_source(req: &TransferRequest) -> Result<Source, CliError> {
    let (genome_path, config) = locate(req.run)?;
    let Some(config) = config else {
        return Err(CliError::input(format!(
            "{}: no config.resolved.toml beside the genome; transfer needs a run directory",
            req.run.display()
        )));
    };
    let genome = read_genome(&genome_path)?;
    let experiment = load_config(Some(&config), &[], None)?.experiment;
    let rooms: Vec<String> = (experiment.arenas().iter())
        .map(|a| a.room().name.clone())
        .collect();
    let Some(room) = rooms.iter().position(|r| r == req.room) else {
        return Err(CliError::input(format!(
            "--room: `{}` is not a room of {} (its rooms: {}); the measures need the run's own \
             room",
            req.room,
            config.display(),
            fuzzymotiv::params::joined_list(&rooms, "and")
        )));
    };
    let robot = experiment.trial_params().robot().spec().name().to_string();
    let Some(model) = ENKI_MODELS.iter().find(|m| m.robot == robot).copied() else {
        return Err(CliError::input(format!(
            "{}: field `robot`: Enki has no model of the robot `{robot}`; transfer drives \
             Enki's khepera, epuck2 or thymio2",
            config.display()
        )));
    };
    let run = (experiment.runs().into_iter())
        .find(|r| r.rooms.contains(&room))
        .unwrap_or_else(|| experiment.runs().remove(0));
    let weights = match genome.runs.iter().find(|(label, _)| *label == run.label) {
        Some((_, w)) => w.clone(),
        None => genome.weights.clone(),
    };
    Ok(Source {
        config,
        experiment,
        genome,
        weights,
        room,
        model,
        run,
    })
}

/// The network of the source's weights.
fn network_of(src: &Source) -> Result<Mlp, CliError> {
    src.experiment
        .network(&src.weights)
        .map_err(|e| CliError::input(format!("{}: {e}", src.genome.path.display())))
}

/// Writes the source's controller exported as C (`fuzzymotiv export --to c`'s files) and the
/// harness into `dir` and compiles them: the harness's path. A missing compiler or Enki is an
/// input error naming the Debian package to install.
fn build_harness(src: &Source, dir: &Path) -> Result<PathBuf, CliError> {
    let exp = &src.experiment;
    let controller = ExportedController::new(exp.shape(), &src.weights, exp.trial_params())
        .map_err(|e| {
            CliError::input(format!(
                "{}: field `weights`: {e}",
                src.genome.path.display()
            ))
        })?;
    let sources = controller.c();
    let c = dir.join("c");
    std::fs::create_dir_all(&c).map_err(|e| io_err(&c, e))?;
    for (name, text) in [
        (CSources::HEADER_NAME, &sources.header),
        (CSources::SOURCE_NAME, &sources.source),
    ] {
        let path = c.join(name);
        std::fs::write(&path, text).map_err(|e| io_err(&path, e))?;
    }
    let harness = dir.join("harness.cpp");
    std::fs::write(&harness, HARNESS).map_err(|e| io_err(&harness, e))?;
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let cxx = std::env::var("CXX").unwrap_or_else(|_| "c++".into());
    let object = dir.join("fm_controller.o");
    compile(
        &cc,
        &["-std=c99", "-O2", "-ffp-contract=off", "-c"],
        &[
            c.join("fm_controller.c"),
            PathBuf::from("-o"),
            object.clone(),
        ],
    )?;
    let binary = dir.join("fm_enki");
    let include = format!("-I{}", c.display());
    compile(
        &cxx,
        &["-std=c++17", "-O2", "-ffp-contract=off", &include],
        &[
            harness,
            object,
            PathBuf::from("-o"),
            binary.clone(),
            PathBuf::from("-lenki"),
        ],
    )?;
    Ok(binary)
}

/// Runs the compiler `tool` with `flags` and `args`; what is missing is said with its package.
fn compile(tool: &str, flags: &[&str], args: &[PathBuf]) -> Result<(), CliError> {
    let out = Command::new(tool).args(flags).args(args).output();
    let out = match out {
        Ok(out) => out,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(CliError::input(format!(
                "transfer compiles the exported controller and its Enki harness, but there is no \
                 compiler `{tool}`: install Debian's g++ (apt-get install g++), or name one in \
                 CC and CXX"
            )));
        }
        Err(e) => return Err(CliError::runtime(format!("{tool}: {e}"))),
    };
    if out.status.success() {
        return Ok(());
    }
    let said = String::from_utf8_lossy(&out.stderr);
    if said.contains("enki/") || said.contains("-lenki") {
        return Err(CliError::input(format!(
            "Enki is not installed (the C++ library and headers transfer builds against): \
             install Debian's libenki-dev (apt-get install libenki-dev); {tool} said: {}",
            said.lines()
                .find(|l| l.contains("enki"))
                .unwrap_or("")
                .trim()
        )));
    }
    Err(CliError::runtime(format!(
        "{tool} failed to build the Enki harness:\n{said}"
    )))
}

/// The scenario file of the harness for the source (without its seed): see [`HARNESS`].
fn scenario(src: &Source) -> String {
    let params = src.experiment.trial_params();
    let room = src.experiment.arenas()[src.room].room();
    let (lo, hi) = room.bounds();
    let to_enki = |p: Vec2| ((p.x - lo.x) * CM + MARGIN_CM, (p.y - lo.y) * CM + MARGIN_CM);
    let motion = match params.robot().motion() {
        fuzzymotiv::simulation::Motion::Actions => "actions",
        fuzzymotiv::simulation::Motion::Wheels => "wheels",
    };
    let mut s = String::new();
    let _ = writeln!(s, "robot {}\nmotion {motion}", src.model.robot);
    let _ = writeln!(s, "steps {}\ndt {:?}", params.steps(), params.dt());
    let _ = writeln!(s, "v_max {:?}", params.robot().v_max() * CM);
    let _ = writeln!(s, "scale {:?}", src.model.scale);
    let reading_max = params.robot().spec().reading_max();
    let _ = writeln!(s, "reading_max {reading_max:?}\nphysics_dt {PHYSICS_DT:?}");
    let _ = writeln!(
        s,
        "world {:?} {:?}",
        (hi.x - lo.x) * CM + 2.0 * MARGIN_CM,
        (hi.y - lo.y) * CM + 2.0 * MARGIN_CM
    );
    let (hx, hy) = to_enki(room.home.position());
    let _ = writeln!(s, "home {hx:?} {hy:?} {:?}", room.home.heading);
    for [cx, cy, length, angle] in wall_blocks(room) {
        let (x, y) = to_enki(Vec2::new(cx, cy));
        let _ = writeln!(
            s,
            "block {x:?} {y:?} {:?} {WALL_CM:?} {angle:?}",
            length * CM
        );
    }
    s
}

/// Each wall segment of `room` as a block (centre x, y in mm, length in mm, angle in rad)
/// lying on the segment's far side from the floor, [`WALL_CM`] thick.
fn wall_blocks(room: &Room) -> Vec<[f64; 4]> {
    let half = WALL_CM / CM / 2.0;
    (room.walls().into_iter())
        .filter_map(|w| {
            let d = w.b - w.a;
            let length = d.dot(d).sqrt();
            if length == 0.0 {
                return None;
            }
            let (u, mid) = (d * (1.0 / length), (w.a + w.b) * 0.5);
            let normal = Vec2::new(-u.y, u.x);
            // The floor is on the normal's side or the other: the block goes on the far one.
            let side = if room.contains(mid + normal * 1.0) {
                -1.0
            } else {
                1.0
            };
            let c = mid + normal * (side * half);
            Some([c.x, c.y, length, u.y.atan2(u.x)])
        })
        .collect()
}

/// One test run in Enki as the harness logged it.
struct EnkiTrial {
    steps: Vec<LoggedStep>,
    raw: Vec<Readings>,
}

/// Runs the harness once with Enki's seed `seed`; checks each step's motor outputs against the
/// library's network on the same readings, bit for bit.
fn run_in_enki(
    src: &Source,
    network: &Mlp,
    harness: &Path,
    dir: &Path,
    seed: u64,
) -> Result<EnkiTrial, CliError> {
    let file = dir.join(format!("scenario-{seed}.txt"));
    let text = format!("{}seed {seed}\n", scenario(src));
    std::fs::write(&file, text).map_err(|e| io_err(&file, e))?;
    let out = Command::new(harness).arg(&file).output();
    let out = out.map_err(|e| CliError::runtime(format!("{}: {e}", harness.display())))?;
    if !out.status.success() {
        let said = String::from_utf8_lossy(&out.stderr);
        if said.contains("libenki") {
            return Err(CliError::input(format!(
                "Enki's library does not load: install Debian's libenki-dev (apt-get install \
                 libenki-dev); the harness said: {}",
                said.trim()
            )));
        }
        return Err(CliError::runtime(format!(
            "the Enki harness failed: {}",
            said.trim()
        )));
    }
    let trial = parse_harness(src, &String::from_utf8_lossy(&out.stdout))?;
    check_bits(src, network, &trial)?;
    Ok(trial)
}

/// The harness's output as logged steps (poses in mm in the room's frame).
fn parse_harness(src: &Source, text: &str) -> Result<EnkiTrial, CliError> {
    let room = src.experiment.arenas()[src.room].room();
    let (lo, _) = room.bounds();
    let n = src.experiment.shape().inputs();
    let bad = |line: &str| CliError::runtime(format!("the Enki harness wrote `{line}`"));
    let mut starts = Vec::new();
    let (mut steps, mut raw) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let first = words.first().copied().unwrap_or("");
        let skip = if first == "step" { 2 } else { 1 };
        let v: Vec<f64> = (words.iter().skip(skip).map(|w| w.parse::<f64>()))
            .collect::<Result<_, _>>()
            .map_err(|_| bad(line))?;
        if v.len() < 3 {
            return Err(bad(line));
        }
        let pose = Pose::new(
            (v[0] - MARGIN_CM) / CM + lo.x,
            (v[1] - MARGIN_CM) / CM + lo.y,
            v[2],
        );
        starts.push(pose);
        if first == "end" {
            break;
        }
        if v.len() != 3 + 2 * n + 4 {
            return Err(bad(line));
        }
        let code = v[3 + 2 * n + 2] as usize;
        let actions = [
            Action::Straight,
            Action::Left30,
            Action::Right30,
            Action::Turn180,
        ];
        raw.push(Readings::from_slice(&v[3..3 + n]));
        steps.push(LoggedStep {
            pose,
            sensors: Readings::from_slice(&v[3 + n..3 + 2 * n]),
            motors: Some([v[3 + 2 * n], v[3 + 2 * n + 1]]),
            action: *actions.get(code).ok_or_else(|| bad(line))?,
            collided: v[3 + 2 * n + 3] != 0.0,
        });
    }
    if starts.len() != steps.len() + 1 {
        return Err(CliError::runtime(
            "the Enki harness ended without its final pose",
        ));
    }
    for (s, end) in steps.iter_mut().zip(&starts[1..]) {
        s.pose = *end;
    }
    Ok(EnkiTrial { steps, raw })
}

/// Each step's motor outputs are the library network's on the same readings, bit for bit
/// (the exported C is the simulator's network); an error says where they differ.
fn check_bits(src: &Source, network: &Mlp, trial: &EnkiTrial) -> Result<(), CliError> {
    let max = src.experiment.trial_params().robot().spec().reading_max();
    let mut net = network.clone();
    for (t, s) in trial.steps.iter().enumerate() {
        let inputs: Vec<f64> = (s.sensors.iter())
            .map(|&v| if v == 0.0 { 0.0 } else { v / max })
            .collect();
        let want = net.step(&inputs);
        let got = s.motors.unwrap_or_default();
        if want.map(f64::to_bits) != got.map(f64::to_bits) {
            return Err(CliError::runtime(format!(
                "step {t}: the exported C controller gave motors {got:?}, the network {want:?} \
                 on the same readings: this build's C export does not reproduce the {} network \
                 ({} inputs, readings up to {max})",
                src.model.robot,
                inputs.len()
            )));
        }
    }
    Ok(())
}

/// The room each Enki log is recognised as by the run's room model (none without one).
fn recognition(
    src: &Source,
    network: &Mlp,
    enki: &[(u64, Vec<LoggedStep>, LoggedTrial)],
    notes: &mut Vec<String>,
) -> Result<Vec<Option<Option<String>>>, CliError> {
    let exp = &src.experiment;
    if exp.runs().len() != 1 || !exp.aem().enabled() {
        notes.push(format!(
            "{}: the run has no one room model (per-room training or aem.enabled = false): \
             the Enki logs are not recognised",
            src.config.display()
        ));
        return Ok(vec![None; enki.len()]);
    }
    let logs = (enki.iter().enumerate())
        .map(|(k, (_, steps, _))| {
            let first: Vec<Action> = steps.iter().map(|s| s.action).collect();
            let steps = first.len();
            (format!("run-{k}.csv"), LogActions { first, steps })
        })
        .collect();
    let dir = src.config.parent().unwrap_or(Path::new("."));
    let records = recognise_actions(dir, &src.config, exp, &src.run, network, logs)?;
    Ok((records.into_iter())
        .map(|r| Some((!r.room.is_empty()).then_some(r.room)))
        .collect())
}

/// A test run's row of measures.
fn measure_row(
    src: &Source,
    world: &str,
    test: usize,
    seed: Option<u64>,
    m: &LoggedTrial,
    answer: &Option<Option<String>>,
) -> MeasureRow {
    let room = src.experiment.arenas()[src.room].room().name.clone();
    MeasureRow {
        world: world.to_string(),
        test,
        seed,
        exploration_pct: 100.0 * m.terms.a,
        homing_pct: 100.0 * m.terms.g,
        battery_pct: 100.0 * m.terms.b,
        recognition_pct: answer.as_ref().map(|a| {
            if a.as_deref() == Some(&room) {
                100.0
            } else {
                0.0
            }
        }),
        answer: answer.clone().flatten(),
        executed_steps: m.executed,
        blocked_steps: m.blocked,
        home_at: m.home_at,
        room,
    }
}

/// The run's own test runs in the room, simulated again on their streams and measured by the
/// same code; their answers from the run's test_runs.csv (when it has one).
fn simulated_rows(
    dir: &Path,
    src: &Source,
    network: &Mlp,
    notes: &mut Vec<String>,
) -> Result<Vec<MeasureRow>, CliError> {
    let exp = &src.experiment;
    let room = &exp.arenas()[src.room].room().name;
    let recorded = match test_runs::read(dir) {
        Ok(rows) => rows,
        Err(e) => {
            notes.push(format!("the simulator's answers are not shown: {e}"));
            Vec::new()
        }
    };
    Ok((0..exp.aem().test_runs())
        .map(|t| {
            let (trajectory, _) = exp.test_run(network, &src.run, src.room, t);
            let m = exp.logged_trial(src.room, &LoggedStep::of_trajectory(&trajectory));
            let answer = (recorded.iter())
                .find(|r| r.room == *room && r.test == t && r.recognition_pct.is_some())
                .map(|r| r.answer.clone());
            measure_row(src, "fuzzymotiv", t, None, &m, &answer)
        })
        .collect())
}

/// The Enki test runs as rows of test_runs.csv (its columns, the run's extra ones included).
fn test_run_rows(
    src: &Source,
    enki: &[(u64, Vec<LoggedStep>, LoggedTrial)],
    answers: &[Option<Option<String>>],
) -> Vec<TestRunRow> {
    let extra = extra_terms(&src.experiment);
    let room = src.experiment.arenas()[src.room].room().name.clone();
    (enki.iter().zip(answers).enumerate())
        .map(|(k, ((_, _, m), answer))| {
            let done = (m.terms.mission).map(|mission| {
                let done = f64::from(u8::from(mission.done_at.is_some()));
                (test_runs::MISSION_DONE.to_string(), 100.0 * done)
            });
            let terms = (extra.iter())
                .map(|(name, id)| (test_runs::term_metric(name), 100.0 * m.terms.get(*id)));
            TestRunRow {
                room: room.clone(),
                test: k,
                exploration_pct: 100.0 * m.terms.a,
                recognition_pct: answer.as_ref().map(|a| {
                    if a.as_deref() == Some(&room) {
                        100.0
                    } else {
                        0.0
                    }
                }),
                battery_pct: 100.0 * m.terms.b,
                homing_pct: 100.0 * m.terms.g,
                answer: answer.clone().flatten(),
                extra: done.into_iter().chain(terms).collect(),
            }
        })
        .collect()
}

/// One line per world: the means of the measures over its test runs.
fn comparison(src: &Source, enki: &[MeasureRow], sim: &[MeasureRow]) -> String {
    let room = &src.experiment.arenas()[src.room].room().name;
    let line = |name: &str, rows: &[MeasureRow]| {
        let n = rows.len().max(1) as f64;
        let mean = |f: &dyn Fn(&MeasureRow) -> f64| rows.iter().map(f).sum::<f64>() / n;
        let recognised: Vec<f64> = rows.iter().filter_map(|r| r.recognition_pct).collect();
        let recognition = if recognised.is_empty() {
            "–".to_string()
        } else {
            format!(
                "{:.1} %",
                recognised.iter().sum::<f64>() / recognised.len() as f64
            )
        };
        let home = rows.iter().filter(|r| r.home_at.is_some()).count();
        format!(
            "{room}, {name} ({} test runs): exploration {:.1} %, homing {:.1} %, battery {:.1} %, \
             recognition {recognition}, blocked {:.1} steps, home in {home} of {}",
            rows.len(),
            mean(&|r| r.exploration_pct),
            mean(&|r| r.homing_pct),
            mean(&|r| r.battery_pct),
            mean(&|r| r.blocked_steps as f64),
            rows.len()
        )
    };
    format!("{}\n{}", line("Enki", enki), line("fuzzymotiv", sim))
}

/// transfer.md: what was run, the mappings and the comparison.
fn transfer_md(req: &TransferRequest, src: &Source, base: u64, comparison: &str) -> String {
    let params = src.experiment.trial_params();
    let motion = format!("{:?}", params.robot().motion()).to_lowercase();
    let shape: MlpShape = src.experiment.shape();
    let mut md = format!(
        "# {} in Enki\n\nThe controller of {} ({}-{}-2, exported as C) drove Enki's {} in room {} \
         for {} test runs (Enki seeds {base} to {}), {motion} motion, {} steps of {} s.\n\n",
        src.model.robot,
        req.run.display(),
        shape.inputs(),
        shape.hidden(),
        src.model.class,
        req.room,
        req.runs,
        base + req.runs as u64 - 1,
        params.steps(),
        params.dt()
    );
    let _ = writeln!(
        md,
        "Readings: reading = min({:.6} × Enki's reading, {}); {}.\n",
        src.model.scale,
        params.robot().spec().reading_max(),
        src.model.source
    );
    let _ = writeln!(
        md,
        "Measured by the code that measures a simulated trial (the run's own test runs, \
         simulated again on their streams, beside):\n"
    );
    for line in comparison.lines() {
        let _ = writeln!(md, "- {line}");
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_earlier_transfers_extra_logs_are_refused_unless_forced() {
        let dir = tempfile::tempdir().unwrap();
        let write = |k: usize| std::fs::write(dir.path().join(format!("run-{k}.csv")), "x");
        for k in [0, 1, 2] {
            write(k).unwrap();
        }
        std::fs::write(dir.path().join("run-notes.csv"), "x").unwrap();
        // Three runs again (or more): nothing stale.
        assert!(check_stale_runs(dir.path(), 3, false).unwrap().is_empty());
        assert!(check_stale_runs(dir.path(), 10, false).unwrap().is_empty());
        for k in [7, 12] {
            write(k).unwrap();
        }
        // Two runs: run-2, run-7 and run-12 would be left beside them, uncounted.
        let err = check_stale_runs(dir.path(), 2, false).unwrap_err();
        let message = err.to_string();
        assert!(err.is_input(), "{message}");
        assert!(
            message.contains("run-2.csv, run-7.csv, run-12.csv"),
            "{message}"
        );
        assert!(message.contains("--force"), "{message}");
        let forced = check_stale_runs(dir.path(), 2, true).unwrap();
        let names: Vec<_> = forced
            .iter()
            .map(|p| p.file_name().unwrap().to_owned())
            .collect();
        assert_eq!(names, ["run-2.csv", "run-7.csv", "run-12.csv"]);
        // A directory that does not exist yet holds nothing.
        assert!(
            check_stale_runs(&dir.path().join("new"), 1, false)
                .unwrap()
                .is_empty()
        );
    }
}
