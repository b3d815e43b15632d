//! `fuzzymotiv recognise`: rooms recognised from a real robot's logs by a run's room model.
//!
//! A log is a CSV file, one row per control step, with a header naming its columns:
//! - `action`: the step's action label, `straight`, `left` (+30°), `right` (−30°) or `back`
//!   (180°), as the simulator's `actions` motion executes them; or, instead,
//! - `m_left`, `m_right` (or `mL`, `mR`, as a replay's CSV names them): the network's motor
//!   outputs in [0, 1], labelled by the `wheels` model's rule with the run's
//!   `aem.action_tolerance` (with `actions` motion the simulator labels the speeds after its
//!   wheel noise, so a step near the tolerance may be labelled otherwise than it executed: log
//!   the executed action where the robot knows it);
//! - optionally the tracked pose, `x`, `y` (mm, in the room's frame; `x_mm`, `y_mm` as a
//!   replay's CSV names them) and `heading`: `fuzzymotiv replay --log` draws the path;
//! - any other columns (e.g. `ir0`…`ir7`, or a replay's `s0`…`s7` and `heading_rad`, a time
//!   stamp) are read past;
//! - a row whose action (or both motor outputs) is empty holds no step (e.g. the final pose
//!   that `fuzzymotiv replay`'s CSV ends with, so a replay is a log too) and is skipped.
//!
//! The run's recogniser is rebuilt from its best robot exactly as its room modelling trained it
//! (`Experiment::recognizer`), and each log's first `trial.steps` actions are recognised
//! (`Experiment::explain_actions`: the room, the SOM's winner, the recognised room's r-node, their
//! distance in nodes against the gate's width `aem.threshold`, and the distance of the log's
//! vector to the room's stored vector).

use std::fs::File;
use std::path::{Path, PathBuf};

use fuzzymotiv::experiment::{Experiment, LoggedStep, Run};
use fuzzymotiv::modelling::Action;
use fuzzymotiv::simulation::{MAX_SENSORS, Mlp, Pose, Readings};
use serde::{Deserialize, Serialize};

use crate::files::bounded::{Bounded, InputKind, csv_refusal, open_input};
use crate::files::error::CliError;
use crate::files::inputs::load_config;
use crate::records::genome::{locate, read_genome};
use crate::records::to_csv;

/// One log's answer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecognitionRecord {
    /// The log file, as given.
    pub log: String,
    /// Its steps (rows).
    pub steps: usize,
    /// The steps recognised: the first `trial.steps` (a shorter log is padded as idle steps).
    pub used: usize,
    /// The room recognised, empty when none is (the SOM's gate or a tie).
    pub room: String,
    /// The SOM's winning node.
    pub winner: usize,
    /// Steps per action among the steps used (the `used` first ones, those recognised):
    /// straight, left, right, back.
    pub straight: usize,
    /// Left turns (+30°).
    pub left: usize,
    /// Right turns (−30°).
    pub right: usize,
    /// Turns on the spot (180°).
    pub back: usize,
    /// The recognised room's r-node (its stored instance's winning node); empty when none is.
    pub r_node: Option<usize>,
    /// `|winner − r_node|` in nodes, at most `gate`; empty when no room is recognised.
    pub node_distance: Option<usize>,
    /// The SOM gate's width (`aem.threshold`): a room is a candidate when its r-node lies
    /// within this many nodes of the winner.
    pub gate: usize,
    /// The Euclidean distance of the log's environment vector to the recognised room's stored
    /// vector (the nearest-neighbour step); empty when no room is recognised.
    pub vector_distance: Option<f64>,
}

/// `recognised.csv`'s text.
pub fn recognition_csv(records: &[RecognitionRecord]) -> String {
    to_csv(records)
}

/// `recognised.md`'s text: one row per log.
pub fn recognition_md(run: &Path, records: &[RecognitionRecord]) -> String {
    let mut md = format!(
        "Rooms recognised by the room model of {} (its best robot's SOM, rebuilt as its run trained it). The gate: a room is a candidate when its r-node lies within {} nodes of the SOM's winner; the nearest candidate's stored vector wins.\n\n| log | steps | used | room | SOM winner | straight / left / right / back | r-node (distance / gate) | vector distance |\n|---|---|---|---|---|---|---|---|\n",
        run.display(),
        records.first().map_or(0, |r| r.gate)
    );
    for r in records {
        let room = if r.room.is_empty() {
            "not recognised"
        } else {
            &r.room
        };
        let gate = match (r.r_node, r.node_distance) {
            (Some(n), Some(d)) => format!("{n} ({d} / {})", r.gate),
            _ => format!("– (gate {})", r.gate),
        };
        let distance = r
            .vector_distance
            .map_or("–".to_string(), |d| format!("{d:.4}"));
        md.push_str(&format!(
            "| {} | {} | {} | {room} | {} | {} / {} / {} / {} | {gate} | {distance} |\n",
            r.log, r.steps, r.used, r.winner, r.straight, r.left, r.right, r.back
        ));
    }
    md
}

/// The action label of a log's `action` cell.
fn action_of(word: &str) -> Option<Action> {
    match word.trim().to_ascii_lowercase().as_str() {
        "straight" => Some(Action::Straight),
        "left" | "left30" => Some(Action::Left30),
        "right" | "right30" => Some(Action::Right30),
        "back" | "turn180" => Some(Action::Turn180),
        _ => None,
    }
}

/// Which columns give a log's actions.
enum Source {
    Labels(usize),
    Motors(usize, usize),
}

/// The input kind of a robot's log: read line by line, at most
/// [`crate::files::bounded::LOG_LIMIT`] bytes.
pub const LOG: InputKind = InputKind::log("log file");

/// A log being read: its header, then its rows one at a time (see the module's docs), so that
/// memory does not grow with the log. [`RobotLog::actions`] gives `fuzzymotiv recognise` its
/// actions, [`RobotLog::path`] gives `fuzzymotiv replay --log` its path: one reader for both.
pub struct RobotLog {
    name: String,
    headers: csv::StringRecord,
    reader: csv::Reader<Bounded<File>>,
}

/// A log's steps as `recognise` uses them: the first actions (as many as a trial has steps)
/// and the number of steps of the whole log.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LogActions {
    /// The first actions, at most the number asked for.
    pub first: Vec<Action>,
    /// The steps (rows with an action) of the whole log.
    pub steps: usize,
}

/// Calls `f` with each row of `reader` and its line, one row in memory at a time; errors name
/// the file `name` and the line.
fn each_row(
    reader: &mut csv::Reader<Bounded<File>>,
    name: &str,
    mut f: impl FnMut(u64, &csv::StringRecord) -> Result<(), CliError>,
) -> Result<(), CliError> {
    let mut row = csv::StringRecord::new();
    loop {
        let more = reader.read_record(&mut row).map_err(|e| {
            csv_refusal(&e).unwrap_or_else(|| {
                let at = e
                    .position()
                    .map_or(String::new(), |p| format!(" line {}:", p.line()));
                CliError::input(format!("{name}:{at} {e}"))
            })
        })?;
        if !more {
            return Ok(());
        }
        f(row.position().map_or(0, |p| p.line()), &row)?;
    }
}

impl RobotLog {
    /// Opens a log and reads its header; errors name the file (and the line).
    pub fn read(path: &Path) -> Result<RobotLog, CliError> {
        let input = open_input(path, LOG)?;
        let name = input.name().to_string();
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .from_reader(input);
        let headers = reader
            .headers()
            .map_err(|e| {
                csv_refusal(&e).unwrap_or_else(|| {
                    CliError::input(format!("{name}: cannot read the header: {e}"))
                })
            })?
            .clone();
        Ok(RobotLog {
            name,
            headers,
            reader,
        })
    }

    /// The log's file, as given.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The index of the first of `names` the header has.
    fn column(&self, names: &[&str]) -> Option<usize> {
        names
            .iter()
            .find_map(|c| self.headers.iter().position(|h| h == *c))
    }

    /// Which columns give the log's actions; an error says what a log needs.
    fn source(&self) -> Result<Source, CliError> {
        match (
            self.column(&["action"]),
            self.column(&["m_left", "mL"]),
            self.column(&["m_right", "mR"]),
        ) {
            (Some(a), _, _) => Ok(Source::Labels(a)),
            (None, Some(l), Some(r)) => Ok(Source::Motors(l, r)),
            _ => Err(CliError::input(format!(
                "{}: the header has neither an `action` column nor `m_left` and `m_right`; \
                 a log names each step's action in a column `action` (straight, left, right or \
                 back) or its motor outputs in [0, 1] in two columns `m_left` and `m_right` \
                 (`mL` and `mR`, as a replay's CSV names them); found: {}",
                self.name,
                self.headers.iter().collect::<Vec<_>>().join(", ")
            ))),
        }
    }

    /// The log's actions (see the module's docs): the first `keep` of them and the number of
    /// steps of the whole log; `tolerance` labels motor outputs.
    pub fn actions(self, tolerance: f64, keep: usize) -> Result<LogActions, CliError> {
        let source = self.source()?;
        let RobotLog {
            name, mut reader, ..
        } = self;
        let mut got = LogActions {
            first: Vec::new(),
            steps: 0,
        };
        each_row(&mut reader, &name, |line, row| {
            if let Some(action) = action_in(&name, line, row, &source, tolerance)? {
                if got.first.len() < keep {
                    got.first.push(action);
                }
                got.steps += 1;
            }
            Ok(())
        })?;
        if got.steps == 0 {
            return Err(CliError::input(format!(
                "{name}: the log has no steps (rows after the header)"
            )));
        }
        Ok(got)
    }

    /// The logged path: the `x`, `y` columns (or `x_mm`, `y_mm`, as a replay's CSV names
    /// them), mm in the room's frame, one point per row that has them (a row with both empty
    /// is read past).
    pub fn path(self) -> Result<Vec<(f64, f64)>, CliError> {
        let name = &self.name;
        let (Some(x), Some(y)) = (self.column(&["x", "x_mm"]), self.column(&["y", "y_mm"])) else {
            return Err(CliError::input(format!(
                "{name}: the header has no `x` and `y` columns; --log draws a logged path, so each \
                 row needs the robot's position in mm in the room's frame (origin and axes as the \
                 room file's), `x` and `y` (or `x_mm` and `y_mm`, as a replay's CSV has them); \
                 found: {}",
                self.headers.iter().collect::<Vec<_>>().join(", ")
            )));
        };
        let RobotLog {
            name,
            headers,
            mut reader,
        } = self;
        let mut points = Vec::new();
        each_row(&mut reader, &name, |line, row| {
            let cell = |i: usize| row.get(i).unwrap_or("");
            if cell(x).is_empty() && cell(y).is_empty() {
                return Ok(());
            }
            let coordinate = |i: usize| -> Result<f64, CliError> {
                cell(i).parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| {
                    CliError::input(format!(
                        "{name}: line {line}: field `{}`: `{}` is not a position; write a number (mm)",
                        &headers[i],
                        cell(i)
                    ))
                })
            };
            points.push((coordinate(x)?, coordinate(y)?));
            Ok(())
        })?;
        if points.is_empty() {
            return Err(CliError::input(format!(
                "{name}: the log has no positions (rows with `x` and `y`)"
            )));
        }
        Ok(points)
    }
}

/// The columns of a log's logged steps ([`RobotLog::steps`]).
struct StepColumns {
    pose: [usize; 3],
    motors: Option<(usize, usize)>,
    collision: Option<usize>,
    sensors: Vec<usize>,
}

impl RobotLog {
    /// The columns [`RobotLog::steps`] reads; an error says what a log of steps needs.
    fn step_columns(&self) -> Result<StepColumns, CliError> {
        let pose = [
            self.column(&["x", "x_mm"]),
            self.column(&["y", "y_mm"]),
            self.column(&["heading", "heading_rad"]),
        ];
        let [Some(x), Some(y), Some(h)] = pose else {
            return Err(CliError::input(format!(
                "{}: the header lacks `x`, `y` or `heading`; measuring a logged trial needs each \
                 step's pose at its start (mm in the room's frame, heading in radians) and a last \
                 row with the final pose; found: {}",
                self.name,
                self.headers.iter().collect::<Vec<_>>().join(", ")
            )));
        };
        let sensors = (0..)
            .map_while(|k| self.column(&[&format!("ir{k}"), &format!("s{k}")]))
            .take(MAX_SENSORS)
            .collect();
        Ok(StepColumns {
            pose: [x, y, h],
            motors: self
                .column(&["m_left", "mL"])
                .zip(self.column(&["m_right", "mR"])),
            collision: self.column(&["collision"]),
            sensors,
        })
    }

    /// The log's steps as a trial measures them ([`Experiment::logged_trial`]): per row with an
    /// action (or motor outputs, labelled with `tolerance`) one step, its readings (`ir0`…, or
    /// a replay's `s0`…), motor outputs, `collision` (1 or 0, absent: 0) and, as the pose at
    /// its end, the next row's pose (the last row without an action holds the final pose; a
    /// log without one ends where its last step started). Errors name the file, line and
    /// field.
    pub fn steps(self, tolerance: f64) -> Result<Vec<LoggedStep>, CliError> {
        let source = self.source()?;
        let columns = self.step_columns()?;
        let RobotLog {
            name,
            headers,
            mut reader,
        } = self;
        let mut steps: Vec<LoggedStep> = Vec::new();
        let mut starts: Vec<Pose> = Vec::new();
        let mut last = None;
        each_row(&mut reader, &name, |line, row| {
            let number = |i: usize| -> Result<f64, CliError> {
                let cell = row.get(i).unwrap_or("");
                cell.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| {
                        CliError::input(format!(
                            "{name}: line {line}: field `{}`: `{cell}` is not a number",
                            &headers[i]
                        ))
                    })
            };
            let [x, y, h] = columns.pose;
            let pose = Pose::new(number(x)?, number(y)?, number(h)?);
            let Some(action) = action_in(&name, line, row, &source, tolerance)? else {
                last = Some(pose);
                return Ok(());
            };
            let sensors: Vec<f64> =
                (columns.sensors.iter().map(|&i| number(i))).collect::<Result<_, _>>()?;
            let motors = match columns.motors {
                Some((l, r)) => Some([number(l)?, number(r)?]),
                None => None,
            };
            let collided = columns.collision.map(number).transpose()? == Some(1.0);
            starts.push(pose);
            steps.push(LoggedStep {
                pose,
                sensors: Readings::from_slice(&sensors),
                motors,
                action,
                collided,
            });
            Ok(())
        })?;
        // Each step ends where the next one starts; the last one at the final pose.
        let ends = starts
            .iter()
            .skip(1)
            .copied()
            .chain(last.or(starts.last().copied()));
        for (s, end) in steps.iter_mut().zip(ends) {
            s.pose = end;
        }
        Ok(steps)
    }
}

/// A logged trial as a robot log (the format [`RobotLog`] reads: `recognise`, `replay --log`
/// and [`RobotLog::steps`]): per step `step`, the pose at its start `x`, `y` (mm) and `heading`
/// (rad), the readings given to the network `ir0`…, then `raw` (e.g. another simulator's own
/// readings, `enki0`…, when given: (column stem, one row per step)), `m_left`, `m_right`,
/// `action` and `collision` (1 or 0); a last row holds the final pose only. Numbers are written
/// as the shortest decimals that read back as the same doubles.
pub fn steps_log(home: Pose, steps: &[LoggedStep], raw: Option<(&str, &[Readings])>) -> String {
    let n = steps.first().map_or(0, |s| s.sensors.len());
    let mut header = vec!["step".to_string(), "x".into(), "y".into(), "heading".into()];
    header.extend((0..n).map(|k| format!("ir{k}")));
    if let Some((stem, rows)) = raw {
        let m = rows.first().map_or(0, |r| r.len());
        header.extend((0..m).map(|k| format!("{stem}{k}")));
    }
    header.extend(["m_left", "m_right", "action", "collision"].map(String::from));
    let mut text = header.join(",") + "\n";
    let mut start = home;
    for (t, s) in steps.iter().enumerate() {
        let mut cells = vec![t.to_string()];
        cells.extend([start.x, start.y, start.heading].map(|v| v.to_string()));
        cells.extend(s.sensors.iter().map(|v| v.to_string()));
        if let Some((_, rows)) = raw {
            // A step without its raw row (fewer rows than steps) leaves the cells empty.
            let m = rows.first().map_or(0, |r| r.len());
            match rows.get(t) {
                Some(r) => cells.extend(r.iter().map(|v| v.to_string())),
                None => cells.extend((0..m).map(|_| String::new())),
            }
        }
        let [ml, mr] = s.motors.unwrap_or([0.5; 2]);
        cells.extend([ml.to_string(), mr.to_string(), s.action.label().to_string()]);
        cells.push(u8::from(s.collided).to_string());
        text.push_str(&(cells.join(",") + "\n"));
        start = s.pose;
    }
    let empty = header.len() - 4;
    text.push_str(&format!(
        "{},{},{},{}{}\n",
        steps.len(),
        start.x,
        start.y,
        start.heading,
        ",".repeat(empty)
    ));
    text
}

/// The action of a log's row (none for a row without one), or an error naming the file, the
/// line and the field.
fn action_in(
    name: &str,
    line: u64,
    row: &csv::StringRecord,
    source: &Source,
    tolerance: f64,
) -> Result<Option<Action>, CliError> {
    let cell = |i: usize| row.get(i).unwrap_or("");
    match *source {
        Source::Labels(a) if cell(a).is_empty() => Ok(None),
        Source::Motors(l, r) if cell(l).is_empty() && cell(r).is_empty() => Ok(None),
        Source::Labels(a) => action_of(cell(a)).map(Some).ok_or_else(|| {
            CliError::input(format!(
                "{name}: line {line}: field `action`: `{}` is not an action; write straight, left, right or back",
                cell(a)
            ))
        }),
        Source::Motors(l, r) => {
            let motor = |i: usize, field: &str| -> Result<f64, CliError> {
                cell(i)
                    .parse::<f64>()
                    .ok()
                    .filter(|v| (0.0..=1.0).contains(v))
                    .ok_or_else(|| {
                        CliError::input(format!(
                            "{name}: line {line}: field `{field}`: `{}` is not a motor output; write a number from 0 to 1",
                            cell(i)
                        ))
                    })
            };
            let (ml, mr) = (motor(l, "m_left")?, motor(r, "m_right")?);
            Ok(Some(Action::from_motors(ml, mr, tolerance)))
        }
    }
}

/// Reads a log's actions (see the module's docs): the first `keep` and the number of steps;
/// `tolerance` labels motor outputs.
pub fn read_robot_log(path: &Path, tolerance: f64, keep: usize) -> Result<LogActions, CliError> {
    RobotLog::read(path)?.actions(tolerance, keep)
}

/// The rooms a run directory's room model recognises in `logs` (see the module's docs).
pub fn recognise_logs(run: &Path, logs: &[PathBuf]) -> Result<Vec<RecognitionRecord>, CliError> {
    let (genome_path, config) = locate(run)?;
    let Some(config) = config else {
        return Err(CliError::input(format!(
            "{}: no config.resolved.toml beside the genome; recognise needs a run directory",
            run.display()
        )));
    };
    let genome = read_genome(&genome_path)?;
    let loaded = load_config(Some(&config), &[], None)?;
    let exp = &loaded.experiment;
    let runs = exp.runs();
    let [one] = runs.as_slice() else {
        return Err(CliError::input(format!(
            "{}: the run trains one robot per room (training = \"per-room\"), so it has no one room model for a robot's log; recognise needs an all-rooms run",
            config.display()
        )));
    };
    let network = exp
        .network(&genome.weights)
        .map_err(|e| CliError::input(format!("{}: {e}", genome_path.display())))?;
    let tolerance = exp.trial_params().action_tolerance();
    let steps = exp.trial_params().steps();
    let logs: Vec<(String, LogActions)> = logs
        .iter()
        .map(|p| {
            Ok((
                p.display().to_string(),
                read_robot_log(p, tolerance, steps)?,
            ))
        })
        .collect::<Result<_, CliError>>()?;
    recognise_actions(run, &config, exp, one, &network, logs)
}

/// The rooms the room model of `run` (its config `config`, experiment `exp`, its one all-rooms
/// run `one` and best robot `network`) recognises in logs already read: (name, actions).
pub fn recognise_actions(
    run: &Path,
    config: &Path,
    exp: &Experiment,
    one: &Run,
    network: &Mlp,
    logs: Vec<(String, LogActions)>,
) -> Result<Vec<RecognitionRecord>, CliError> {
    let recognizer = exp
        .recognizer(network, one)
        .map_err(|e| CliError::input(format!("{}: {e}", run.display())))?
        .ok_or_else(|| {
            CliError::input(format!(
                "{}: room modelling is off in this run (aem.enabled = false): it has no room model",
                config.display()
            ))
        })?;
    logs.into_iter()
        .map(|(log, actions)| {
            let why = exp
                .explain_actions(&recognizer, &actions.first)
                .map_err(|e| CliError::input(format!("{log}: {e}")))?;
            // The actions of the steps recognised, as `used` says, not of the whole log.
            let count = |a: Action| actions.first.iter().filter(|&&x| x == a).count();
            let chosen = why.chosen;
            Ok(RecognitionRecord {
                steps: actions.steps,
                used: actions.first.len(),
                room: chosen.map_or(String::new(), |c| exp.arenas()[c.room].room().name.clone()),
                winner: why.winner,
                r_node: chosen.map(|c| c.r_node),
                node_distance: chosen.map(|c| c.node_distance),
                gate: why.threshold,
                vector_distance: chosen.map(|c| c.vector_distance),
                straight: count(Action::Straight),
                left: count(Action::Left30),
                right: count(Action::Right30),
                back: count(Action::Turn180),
                log,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `text` as a log file of its own (removed at the end of the test).
    struct TempLog(PathBuf);

    impl TempLog {
        fn new(tag: &str, text: &str) -> TempLog {
            let path = std::env::temp_dir().join(format!(
                "fuzzymotiv-robot-log-{}-{tag}.csv",
                std::process::id()
            ));
            std::fs::write(&path, text).unwrap();
            TempLog(path)
        }
    }

    impl Drop for TempLog {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }

    /// One function, two sources: a simulated trial written as a robot log ([`steps_log`]),
    /// read back ([`RobotLog::steps`]) and measured ([`Experiment::logged_trial`]) gives the
    /// simulated trial's own terms bit for bit, and its blocked steps and executed steps, for
    /// both motion models.
    #[test]
    fn the_measures_of_a_simulated_trials_log_equal_its_own_terms() {
        use fuzzymotiv::experiment::{BuiltinRoomsOnly, RawConfig, Setup};
        for motion in ["actions", "wheels"] {
            let text = format!(
                "rooms = [\"H\", \"square\"]\n[robot]\nmotion = \"{motion}\"\n[trial]\nsteps = 250\n"
            );
            let raw = RawConfig::parse(&text, "t.toml", &[]).unwrap();
            let exp = Setup::resolve(raw, "t.toml", &BuiltinRoomsOnly)
                .unwrap()
                .experiment;
            let genome: Vec<f64> = (0..exp.shape().genome_len())
                .map(|k| ((k * 7919) % 13) as f64 / 3.0 - 2.0)
                .collect();
            let network = exp.network(&genome).unwrap();
            let tolerance = exp.trial_params().action_tolerance();
            for room in 0..2 {
                for seed in 0..5 {
                    let (tr, terms) = exp.traced_trial(&network, room, seed);
                    let steps = LoggedStep::of_trajectory(&tr);
                    let home = exp.arenas()[room].room().home;
                    let log = TempLog::new(
                        &format!("{motion}-{room}-{seed}"),
                        &steps_log(home, &steps, None),
                    );
                    let read = RobotLog::read(&log.0).unwrap().steps(tolerance).unwrap();
                    assert_eq!(read, steps, "{motion} {room} {seed}: the log reads back");
                    let m = exp.logged_trial(room, &read);
                    assert_eq!(m.terms, terms, "{motion} room {room} seed {seed}");
                    assert_eq!(m.executed, tr.executed());
                    let blocked = (0..tr.len()).filter(|&t| !tr.idle[t] && tr.collisions[t]);
                    assert_eq!(m.blocked, blocked.count());
                }
            }
        }
    }

    /// A log of two steps given one raw row writes the second step's raw cells empty (no
    /// index past the rows) and still reads back as its two steps.
    #[test]
    fn a_step_without_its_raw_row_is_logged_with_empty_raw_cells() {
        let step = |x: f64| LoggedStep {
            pose: Pose::new(x, 0.0, 0.0),
            sensors: Readings::from_slice(&[1.0, 2.0]),
            motors: Some([0.75, 0.75]),
            action: Action::Straight,
            collided: false,
        };
        let steps = [step(8.0), step(16.0)];
        let raw = [Readings::from_slice(&[3.0, 4.0])];
        let text = steps_log(Pose::new(0.0, 0.0, 0.0), &steps, Some(("enki", &raw)));
        let rows: Vec<&str> = text.lines().collect();
        assert_eq!(
            rows[0],
            "step,x,y,heading,ir0,ir1,enki0,enki1,m_left,m_right,action,collision"
        );
        assert_eq!(rows[2], "1,8,0,0,1,2,,,0.75,0.75,straight,0");
        let log = TempLog::new("raw-rows", &text);
        assert_eq!(RobotLog::read(&log.0).unwrap().steps(0.25).unwrap(), steps);
    }

    /// A replay's CSV names the motor outputs `mL`, `mR` and the readings `s0`…`s7`; a robot's
    /// log `m_left`, `m_right` and `ir0`…`ir7`: both read as the same steps.
    #[test]
    fn replay_and_log_column_names_give_the_same_actions() {
        let rows = ["0.9,0.9", "0.2,0.9", "0.9,0.1", "0.1,0.2", "0.6,0.55"];
        let log = |motors: &str, sensors: &str| {
            let mut t = format!("{sensors},{motors},heading\n");
            for r in rows {
                t.push_str(&format!("0,0,0,0,0,0,0,0,{r},0.0\n"));
            }
            t
        };
        let irs = "ir0,ir1,ir2,ir3,ir4,ir5,ir6,ir7";
        let ss = "s0,s1,s2,s3,s4,s5,s6,s7";
        let robot = TempLog::new("robot", &log("m_left,m_right", irs));
        let replay = TempLog::new("replay", &log("mL,mR", ss));
        let a = read_robot_log(&robot.0, 0.25, 10).unwrap();
        let b = read_robot_log(&replay.0, 0.25, 10).unwrap();
        assert_eq!(a, b);
        let distinct: std::collections::BTreeSet<String> =
            a.first.iter().map(|x| format!("{x:?}")).collect();
        assert_eq!(distinct.len(), 4, "{a:?}");
        // Neither pair: the message says what would be right and what was found.
        let none = TempLog::new("none", &log("left,right", irs));
        let e = read_robot_log(&none.0, 0.25, 10).unwrap_err().to_string();
        assert!(e.contains("`m_left` and `m_right`"), "{e}");
        assert!(e.contains("found: ir0, ir1"), "{e}");
        assert!(!e.contains("docs/"), "{e}");
    }
}
