//! `fuzzymotiv recognise RUN LOG…`: the rooms a run's room model recognises in a robot's logs
//! (one CSV per log: the action per step, or the motor outputs).

use crate::common;

use std::path::Path;

use common::{Fm, ok, stderr, stdout};

const SIZES: [&str; 5] = [
    "ga.population=10",
    "ga.generations=3",
    "trial.steps=150",
    "aem.epochs=50",
    "aem.test_runs=3",
];

const ROOMS: [&str; 5] = ["H", "T", "L", "square", "rectangle"];

/// A tiny run and the replays of its room-modelling runs (`DIR/rep-ROOM.csv`).
fn run_and_replays(dir: &Path) {
    let config = common::repo().join("configs/high-curiosity.toml");
    Fm::new(["run", config.to_str().unwrap(), "--quiet"])
        .out(&dir.join("run"))
        .sets(&SIZES)
        .ok();
    let run = dir.join("run");
    let rep = dir.join("rep");
    ok(&[
        "replay",
        run.to_str().unwrap(),
        "--out",
        rep.to_str().unwrap(),
    ]);
}

/// The replay's motor outputs alone, as a log with `m_left` and `m_right` columns.
fn motors_log(replay: &Path, out: &Path) {
    let text = std::fs::read_to_string(replay).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (l, r) = (col("mL"), col("mR"));
    let mut log = String::from("t,m_left,m_right\n");
    for (k, line) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').collect();
        log.push_str(&format!("{k},{},{}\n", cells[l], cells[r]));
    }
    std::fs::write(out, log).unwrap();
}

/// Each room-modelling run's replay is recognised as its own room, at its stored instance's
/// node (the SOM rebuilt as the run trained it) with the gate's distance 0 and the stored
/// vector itself; a log of motor outputs is read too.
#[test]
fn each_replay_is_recognised_as_its_room_from_actions_or_motors() {
    let tmp = tempfile::tempdir().unwrap();
    run_and_replays(tmp.path());
    let summary = std::fs::read_to_string(tmp.path().join("run/summary.json")).unwrap();
    let r_nodes: Vec<String> = summary
        .split("\"r_node\":")
        .skip(1)
        .map(|s| {
            s.trim_start()
                .split([',', '\n', '}'])
                .next()
                .unwrap()
                .trim()
                .to_string()
        })
        .collect();
    assert_eq!(r_nodes.len(), ROOMS.len(), "{summary}");
    let run = tmp.path().join("run");
    let mut args = vec!["recognise".to_string(), run.display().to_string()];
    for room in ROOMS {
        args.push(
            tmp.path()
                .join(format!("rep-{room}.csv"))
                .display()
                .to_string(),
        );
    }
    let out = tmp.path().join("rec");
    args.extend(["--out".into(), out.display().to_string()]);
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = ok(&refs);
    let csv = std::fs::read_to_string(out.join("recognised.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), ROOMS.len(), "{csv}");
    for ((row, room), node) in rows.iter().zip(ROOMS).zip(&r_nodes) {
        assert_eq!(row[1], "150", "the final pose row is no step: {csv}");
        assert_eq!(row[3], room, "{csv}");
        assert_eq!(row[4], node, "{csv}");
        // The gate's reasons: the replay is the room's stored instance itself, so its r-node
        // is the winner (distance 0 of the gate's 10 nodes) and its vector is the stored one.
        assert_eq!(&row[9..], &[node.as_str(), "0", "10", "0.0"], "{csv}");
    }
    assert!(csv.starts_with("log,steps,used,room,winner,straight,left,right,back,r_node,node_distance,gate,vector_distance\n"), "{csv}");
    assert_eq!(
        stdout(&o).trim_end(),
        std::fs::read_to_string(out.join("recognised.md"))
            .unwrap()
            .trim_end()
    );
    let motors = tmp.path().join("motors-T.csv");
    motors_log(&tmp.path().join("rep-T.csv"), &motors);
    // Motor outputs are labelled by the wheels model's rule, without the simulator's wheel
    // noise (with `actions` motion it labels the noisy speeds), so the counts may differ by the
    // steps that noise moved across the tolerance; every row is a step.
    let o = ok(&["recognise", run.to_str().unwrap(), motors.to_str().unwrap()]);
    let line = stdout(&o)
        .lines()
        .find(|l| l.contains("motors-T.csv"))
        .unwrap()
        .to_string();
    let cells: Vec<&str> = line.split('|').map(str::trim).collect();
    assert_eq!(&cells[2..4], &["150", "150"], "{line}");
    let counts: usize = cells[6]
        .split(" / ")
        .map(|c| c.parse::<usize>().unwrap())
        .sum();
    assert_eq!(counts, 150, "{line}");
}

/// A bad log exits 2 naming the file, the line and the field; nothing is written.
#[test]
fn a_bad_log_is_refused_naming_its_file_line_and_field() {
    let tmp = tempfile::tempdir().unwrap();
    run_and_replays(tmp.path());
    let run = tmp.path().join("run");
    let out = tmp.path().join("rec");
    let cases = [
        (
            "step,action\n0,straight\n1,sideways\n",
            "line 3: field `action`: `sideways` is not an action",
        ),
        (
            "t,m_left,m_right\n0,0.5,1.5\n",
            "line 2: field `m_right`: `1.5` is not a motor output",
        ),
        (
            "t,speed\n0,1\n",
            "neither an `action` column nor `m_left` and `m_right`",
        ),
        ("step,action\n", "the log has no steps"),
    ];
    for (k, (text, want)) in cases.iter().enumerate() {
        let log = tmp.path().join(format!("bad-{k}.csv"));
        std::fs::write(&log, text).unwrap();
        let o = Fm::new(["recognise", run.to_str().unwrap(), log.to_str().unwrap()])
            .out(&out)
            .run();
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let e = stderr(&o);
        assert!(
            e.contains(&format!("bad-{k}.csv")) && e.contains(want),
            "{e}"
        );
        assert!(!out.exists(), "nothing written");
    }
}

/// `replay --log` draws a path from a log's `x`, `y` columns over one room: a config of several
/// rooms without `--room`, a log without positions or with a bad number exits 2 naming the
/// file (the line and the column); nothing is written.
#[test]
fn replay_log_is_refused_without_a_room_or_positions_naming_the_file_line_and_column() {
    let tmp = tempfile::tempdir().unwrap();
    run_and_replays(tmp.path());
    let run = tmp.path().join("run");
    let out = tmp.path().join("drawn").join("replay.html");
    let good = tmp.path().join("rep-T.csv");
    let cases = [
        (
            None,
            "x,y\n1,2\n",
            "--log: the config has 5 rooms (H, T, L, square, rectangle); a log is drawn over the room it was recorded in, so say which with --room ROOM",
        ),
        (
            Some("T"),
            "t,action\n0,straight\n",
            "the header has no `x` and `y` columns",
        ),
        (
            Some("T"),
            "t,x,y\n0,100,200\n1,100.5,abc\n",
            "line 3: field `y`: `abc` is not a position",
        ),
        (
            Some("T"),
            "t,x_mm,y_mm\n0,inf,200\n",
            "line 2: field `x_mm`: `inf` is not a position",
        ),
        (Some("T"), "t,x,y\n0,,\n", "the log has no positions"),
    ];
    for (k, (room, text, want)) in cases.iter().enumerate() {
        let log = tmp.path().join(format!("bad-{k}.csv"));
        std::fs::write(&log, text).unwrap();
        let mut fm = Fm::new(["replay", run.to_str().unwrap()])
            .arg("--log")
            .arg(&good)
            .arg("--log")
            .arg(&log)
            .arg("--out")
            .arg(&out);
        if let Some(room) = room {
            fm = fm.arg("--room").arg(room);
        }
        let o = fm.run();
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let e = stderr(&o);
        assert!(e.contains(want), "{e}");
        if room.is_some() {
            assert!(e.contains(&format!("bad-{k}.csv")), "{e}");
        }
        assert!(!out.parent().unwrap().exists(), "nothing written");
    }
}

/// A logged path with positions outside the room (another frame or other units) is drawn with a
/// warning that counts them.
#[test]
fn replay_log_warns_of_positions_outside_the_room() {
    let tmp = tempfile::tempdir().unwrap();
    run_and_replays(tmp.path());
    let run = tmp.path().join("run");
    let log = tmp.path().join("metres.csv");
    std::fs::write(&log, "t,x,y\n0,0.1,0.1\n1,5000,0.2\n2,0.3,-900\n").unwrap();
    let out = tmp.path().join("drawn").join("replay.html");
    let o = Fm::new(["replay", run.to_str().unwrap(), "--room", "square"])
        .arg("--log")
        .arg(&log)
        .arg("--out")
        .arg(&out)
        .ok();
    let e = stderr(&o);
    assert!(
        e.contains("metres.csv: 2 of 3 positions lie outside room square"),
        "{e}"
    );
    let svg = std::fs::read_to_string(out.with_extension("svg")).unwrap();
    assert!(svg.contains("logged path:"), "drawn all the same");
}

/// Issue #52 item 7: a log longer than a trial is recognised from its first `trial.steps`
/// steps ("used"), and the actions it reports are counted over those steps, not the whole log.
#[test]
fn the_actions_of_a_long_log_are_counted_over_the_steps_used() {
    let tmp = tempfile::tempdir().unwrap();
    let config = common::repo().join("configs/high-curiosity.toml");
    let run = tmp.path().join("run");
    Fm::new(["run", config.to_str().unwrap(), "--quiet"])
        .out(&run)
        .sets(&SIZES)
        .ok();
    let log = tmp.path().join("long.csv");
    let mut text = String::from("action\n");
    text.push_str(&"straight\n".repeat(150));
    text.push_str(&"back\n".repeat(250));
    std::fs::write(&log, text).unwrap();
    let out = tmp.path().join("rec");
    ok(&[
        "recognise",
        run.to_str().unwrap(),
        log.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let csv = std::fs::read_to_string(out.join("recognised.csv")).unwrap();
    let row: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    // log, steps, used, room, winner, straight, left, right, back
    assert_eq!((row[1], row[2]), ("400", "150"), "{csv}");
    assert_eq!(row[5..9], ["150", "0", "0", "0"], "{csv}");
}

/// A tiny run of `robot` (configs/tiny.toml; the Thymio II in its own rooms, configs/thymio2.toml)
/// in `dir/run-ROBOT`, and the room it is transferred in.
fn tiny_run_of(robot: &str, dir: &Path) -> (std::path::PathBuf, &'static str) {
    let run = dir.join(format!("run-{robot}"));
    let (config, room) = match robot {
        "thymio2" => ("configs/thymio2.toml", "H-x3"),
        _ => ("configs/tiny.toml", "H"),
    };
    let robot_set = format!("robot=\"{robot}\"");
    let mut sets = vec![
        "ga.population=10",
        "ga.generations=2",
        "trial.steps=100",
        "aem.epochs=20",
        "aem.test_runs=2",
    ];
    if robot != "thymio2" {
        sets.push(&robot_set);
    }
    Fm::new([
        "run",
        common::repo().join(config).to_str().unwrap(),
        "--quiet",
    ])
    .out(&run)
    .sets(&sets)
    .ok();
    (run, room)
}

/// `fuzzymotiv transfer` builds its Enki harness and runs a tiny run's controller in Enki for
/// the Khepera, the e-puck2 and the Thymio II: its logs are recognised by `recognise` and
/// drawn by `replay --log`, its test_runs.csv has the run's columns and its measures both
/// worlds'.
#[test]
#[ignore = "needs Enki (libenki-dev, python3-enki2): run by .ci/run"]
fn a_transferred_controllers_enki_logs_are_recognised_and_replayed() {
    let tmp = tempfile::tempdir().unwrap();
    for robot in ["khepera", "epuck2", "thymio2"] {
        let (run, room) = tiny_run_of(robot, tmp.path());
        let out = tmp.path().join(format!("enki-{robot}"));
        let o = Fm::new([
            "transfer",
            run.to_str().unwrap(),
            "--room",
            room,
            "--runs",
            "2",
        ])
        .out(&out)
        .ok();
        let said = stdout(&o);
        assert!(said.contains("Enki (2 test runs)"), "{robot}: {said}");
        assert!(said.contains("fuzzymotiv (2 test runs)"), "{robot}: {said}");
        let ours = std::fs::read_to_string(run.join("test_runs.csv")).unwrap();
        let enki = std::fs::read_to_string(out.join("test_runs.csv")).unwrap();
        assert_eq!(ours.lines().next(), enki.lines().next(), "{robot}");
        assert_eq!(enki.lines().count(), 3, "{robot}: {enki}");
        let measures = std::fs::read_to_string(out.join("measures.csv")).unwrap();
        assert_eq!(measures.matches("\nenki,").count(), 2, "{measures}");
        assert_eq!(measures.matches("\nfuzzymotiv,").count(), 2, "{measures}");
        let log = out.join("run-0.csv");
        let rec = out.join("recognised");
        ok(&[
            "recognise",
            run.to_str().unwrap(),
            log.to_str().unwrap(),
            "--out",
            rec.to_str().unwrap(),
        ]);
        assert!(rec.join("recognised.csv").is_file(), "{robot}");
        let page = tmp.path().join(format!("replay-{robot}.html"));
        ok(&[
            "replay",
            run.to_str().unwrap(),
            "--room",
            room,
            "--log",
            log.to_str().unwrap(),
            "--out",
            page.to_str().unwrap(),
        ]);
        let svg = std::fs::read_to_string(page.with_extension("svg")).unwrap();
        assert!(svg.contains("run-0.csv"), "{robot}: the log's legend line");
        // The same transfer again writes nothing new.
        let again = Fm::new([
            "transfer",
            run.to_str().unwrap(),
            "--room",
            room,
            "--runs",
            "2",
        ])
        .out(&out)
        .ok();
        assert!(
            stderr(&again).contains("nothing to do"),
            "{}",
            stderr(&again)
        );
    }
}

/// Without a C++ compiler transfer exits 2 naming the Debian package to install (and writes
/// nothing).
#[test]
fn transfer_without_a_compiler_names_the_package_to_install() {
    let tmp = tempfile::tempdir().unwrap();
    let (run, room) = tiny_run_of("khepera", tmp.path());
    let out = tmp.path().join("enki");
    let o = Fm::new([
        "transfer",
        run.to_str().unwrap(),
        "--room",
        room,
        "--runs",
        "1",
    ])
    .out(&out)
    .env("CC", "/nonexistent/cc")
    .env("CXX", "/nonexistent/c++")
    .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("apt-get install g++"), "{}", stderr(&o));
    assert!(!out.exists());
    // A room the run does not have is refused before anything is built.
    let o = Fm::new([
        "transfer",
        run.to_str().unwrap(),
        "--room",
        "T",
        "--runs",
        "1",
    ])
    .out(&out)
    .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("`T` is not a room of"),
        "{}",
        stderr(&o)
    );
}

/// A Thymio II run's genome (7 inputs) is replayed, its log drawn: replay sized the network by
/// the robot's sensors (it took the Khepera's 8 and refused 62 weights).
#[test]
fn a_thymio_runs_genome_of_seven_inputs_is_replayed_with_a_log() {
    let tmp = tempfile::tempdir().unwrap();
    let (run, room) = tiny_run_of("thymio2", tmp.path());
    let rep = tmp.path().join("rep.html");
    ok(&[
        "replay",
        run.to_str().unwrap(),
        "--room",
        room,
        "--out",
        rep.to_str().unwrap(),
    ]);
    let log = tmp.path().join(format!("rep-{room}.csv"));
    let again = tmp.path().join("again.html");
    ok(&[
        "replay",
        run.to_str().unwrap(),
        "--room",
        room,
        "--log",
        log.to_str().unwrap(),
        "--out",
        again.to_str().unwrap(),
    ]);
}
