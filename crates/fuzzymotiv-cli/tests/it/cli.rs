//! End-to-end tests of the `fuzzymotiv` binary: real code paths, small sizes.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common;

use common::{
    Fm, SMALL, assert_same_files, bin, ok, repo, run, stderr, stdout, summary_without_time,
};

#[test]
fn fuzzy_prints_the_spec_worked_values() {
    for (x, y, f) in [
        (".8,.1,0,.1", ".95,.5,0,.79", 0.797220),
        (".5,.3,0,.2", ".55,.3,0,.58", 0.263309),
        (".25,.25,.25,.25", "1,1,1,1", 1.0),
    ] {
        let o = run(&["fuzzy", "--motivations", x, "--fitness", y]);
        assert!(o.status.success(), "{}", stderr(&o));
        let first = stdout(&o).lines().next().unwrap().to_string();
        let digits = first.trim_start_matches("0.").trim_start_matches('0').len();
        assert!(digits >= 9, "needs 9 significant digits: {first}");
        let v: f64 = first.parse().unwrap();
        assert!((v - f).abs() < 5e-7, "{x} {y}: {v} != {f}");
    }
    let o = run(&[
        "fuzzy",
        "--motivations",
        ".8,.1,0,.1",
        "--fitness",
        ".95,.5,0,.79",
        "--explain",
    ]);
    assert!(stdout(&o).contains("if a is"), "{}", stdout(&o));
}

#[test]
fn fuzzy_rejects_bad_motivations_with_exit_2() {
    let o = run(&[
        "fuzzy",
        "--motivations",
        ".5,.3,0,.1",
        "--fitness",
        ".5,.5,.5,.5",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("sum to 1"), "{}", stderr(&o));
    let o = run(&[
        "fuzzy",
        "--motivations",
        ".5,.3,0",
        "--fitness",
        ".5,.5,.5,.5",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!stderr(&o).contains("panicked"));
}

/// `rooms --check` names every quantity it prints (area, perimeter, home pose with units) and
/// the room's mission: its goal zone, its waypoints, or that it has none.
#[test]
fn rooms_check_names_each_quantity_and_the_rooms_mission() {
    let files = [
        "rooms/fetch-square.toml",
        "rooms/patrol.toml",
        "rooms/U.toml",
    ];
    let paths: Vec<String> = (files.iter())
        .map(|f| repo().join(f).to_str().unwrap().to_string())
        .collect();
    let mut args = vec!["rooms", "--check"];
    args.extend(paths.iter().map(String::as_str));
    let out = stdout(&ok(&args));
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 3, "{out}");
    assert!(
        lines[0].ends_with(
            "fetch-square.toml: room fetch-square, area 0.640 m², perimeter 3.200 m, home (40, 40) mm heading 0°, goal (730, 730) radius 60 mm"
        ),
        "{out}"
    );
    assert!(
        lines[1].contains("3 waypoints in file order: (125, 125) radius 60 mm, "),
        "{out}"
    );
    assert!(
        lines[2].ends_with("no mission (no goal zone or waypoints)"),
        "{out}"
    );
}

#[test]
fn rooms_lists_builtins_and_checks_files() {
    let o = run(&["rooms"]);
    assert!(o.status.success());
    for name in ["H", "T", "L", "square", "rectangle"] {
        assert!(stdout(&o).lines().any(|l| l.starts_with(name)), "{name}");
    }
    let u = repo().join("rooms/U.toml");
    let o = run(&["rooms", "--check", u.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(
        &bad,
        "name='x'\noutline=[[0,0],[100,100],[100,0],[0,100]]\nhome={x=50,y=20,heading_deg=0}",
    )
    .unwrap();
    let o = run(&["rooms", "--check", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains("bad.toml") && e.contains("outline") && e.contains("intersects"),
        "{e}"
    );
}

/// A config run with small sizes; returns the run directory.
fn small_run(dir: &Path, name: &str, extra: &[&str]) -> PathBuf {
    let cfg = dir.join(format!("{name}.toml"));
    std::fs::write(&cfg, format!("name = \"{name}\"\nseed = 3\nrooms = [\"H\", \"square\"]\n[ga]\npopulation = 20\ngenerations = 10\n[trial]\nsteps = 150\n[aem]\nepochs = 50\ntest_runs = 3\n")).unwrap();
    let out = dir.join(name);
    let mut args = vec!["run", cfg.to_str().unwrap(), "--out", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

fn column(csv: &str, name: &str) -> Vec<f64> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let k = header.iter().position(|h| *h == name).unwrap();
    lines
        .map(|l| l.split(',').nth(k).unwrap().parse().unwrap())
        .collect()
}

#[test]
fn small_evolution_writes_every_file_and_improves() {
    let dir = tempfile::tempdir().unwrap();
    let out = small_run(dir.path(), "small", &[]);
    for f in [
        "config.resolved.toml",
        "generations.csv",
        "best_genome.json",
        "summary.json",
        "recognition.csv",
        "table.md",
    ] {
        assert!(out.join(f).is_file(), "missing {f}");
    }
    let csv = std::fs::read_to_string(out.join("generations.csv")).unwrap();
    assert!(csv.starts_with("generation,best,mean,std,min,max,a,g,l,b"));
    assert_eq!(csv.lines().count(), 11);
    let best = column(&csv, "best");
    let mean = column(&csv, "mean");
    assert!(best[9] > best[0], "best did not rise: {best:?}");
    assert!(mean[9] > mean[0], "mean did not rise: {mean:?}");
    let genome: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("best_genome.json")).unwrap())
            .unwrap();
    assert_eq!(genome["weights"].as_array().unwrap().len(), 68);
    assert_eq!(genome["shape"]["hidden"], 6);
    let resolved = std::fs::read_to_string(out.join("config.resolved.toml")).unwrap();
    assert!(resolved.contains("seed = 3") && resolved.contains(env!("CARGO_PKG_VERSION")));
    // The resolved config runs again as is.
    let again = dir.path().join("again");
    let o = run(&[
        "run",
        out.join("config.resolved.toml").to_str().unwrap(),
        "--out",
        again.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(again.join("generations.csv")).unwrap(),
        csv.as_bytes()
    );
    assert!(!dir.path().join("small.partial").exists());
}

#[test]
fn results_do_not_depend_on_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let one = small_run(dir.path(), "one", &["--threads", "1"]);
    let two = small_run(dir.path(), "two", &["--threads", "2"]);
    let files = [
        "generations.csv",
        "best_genome.json",
        "recognition.csv",
        "test_runs.csv",
        "table.md",
    ];
    assert_same_files(&one, &two, &files, "between one and two threads");
    let s1 = summary_without_time(&one);
    let s2 = summary_without_time(&two);
    assert_eq!(s1["rooms"], s2["rooms"]);
    assert_eq!(s1["runs"], s2["runs"]);
}

#[test]
fn per_room_training_writes_one_block_per_room() {
    let dir = tempfile::tempdir().unwrap();
    let out = small_run(
        dir.path(),
        "per",
        &["--set", "training=per-room", "--set", "ga.generations=3"],
    );
    let csv = std::fs::read_to_string(out.join("generations.csv")).unwrap();
    assert_eq!(csv.lines().filter(|l| l.ends_with(",H")).count(), 3);
    assert_eq!(csv.lines().filter(|l| l.ends_with(",square")).count(), 3);
}

/// Bad configs: exit code 2, a message naming the file and the field, no run directory.
#[test]
fn bad_configs_exit_2_and_name_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[(&str, &[&str], &str)] = &[
        ("[ga]\npopulaton = 5\n", &[], "ga.populaton"),
        ("[ga]\npopulation = 0\n", &[], "ga.population"),
        ("[ga]\npopulation = -4\n", &[], "ga.population"),
        ("[trial]\nsteps = \"many\"\n", &[], "trial.steps"),
        ("[trial]\ndt = nan\n", &[], "trial.dt"),
        ("[trial]\ndt = 1.0\n", &[], "trial.dt"),
        (
            "[motivations]\ncuriosity = 0.5\nhoming = 0.3\norientation = 0\nenergy = 0.1\n",
            &[],
            "motivations",
        ),
        ("rooms = []\n", &[], "rooms"),
        ("rooms = [\"H\", \"nowhere.toml\"]\n", &[], "rooms[1]"),
        ("rooms = [\"H\", \"H\"]\n", &[], "rooms[1]"),
        ("rooms = [\"H\"]\n", &[], "aem.enabled"),
        ("[fuzzy]\npeaks = [0, 0.5, 0.4]\n", &[], "fuzzy.peaks"),
        ("[fitness]\nenergy = \"save\"\n", &[], "fitness.energy"),
        ("", &["--set", "ga.mutation_rate=2"], "ga.mutation_rate"),
        ("", &["--set", "ga=3"], "ga"),
        ("seed = [1", &[], "seed"),
    ];
    for (k, (text, extra, field)) in cases.iter().enumerate() {
        let cfg = dir.path().join(format!("bad{k}.toml"));
        std::fs::write(&cfg, text).unwrap();
        let out = dir.path().join(format!("out{k}"));
        let mut args = vec!["run", cfg.to_str().unwrap(), "--out", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        let o = run(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "case {k} ({text:?}): {e}");
        assert!(
            e.contains(&format!("`{field}`")),
            "case {k}: message should name `{field}`: {e}"
        );
        // A value given by --set is named as that --set (issue #52 item 7), others by the file.
        let source = match extra {
            ["--set", set] => format!("--set {set}"),
            _ => format!("bad{k}.toml"),
        };
        assert!(
            e.contains(&source),
            "case {k}: message should name {source}: {e}"
        );
        assert!(!e.contains("panicked"), "case {k}: {e}");
        assert!(
            !out.exists() && !dir.path().join(format!("out{k}.partial")).exists(),
            "case {k}: wrote output"
        );
    }
    let o = run(&["run", dir.path().join("missing.toml").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn bad_room_file_in_config_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("r.toml"),
        "name='r'\noutline=[[0,0],[300,0],[300,300],[0,300]]\nhome={x=10,y=150,heading_deg=0}",
    )
    .unwrap();
    let cfg = dir.path().join("c.toml");
    std::fs::write(&cfg, "rooms = [\"H\", \"r.toml\"]\n").unwrap();
    let o = run(&[
        "run",
        cfg.to_str().unwrap(),
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("r.toml") && e.contains("`home`"), "{e}");
}

/// Runs `c.toml` with rooms `["H", "r.toml"]`, `r.toml` being `room`, into `o`; returns what it
/// did after checking it exited 2 and wrote nothing.
fn run_refused_with_room(dir: &Path, room: &str, extra: &[&str]) -> String {
    std::fs::write(dir.join("r.toml"), room).unwrap();
    let cfg = dir.join("c.toml");
    std::fs::write(&cfg, "rooms = [\"H\", \"r.toml\"]\n").unwrap();
    let out = dir.join("o");
    let o = Fm::new(["run", cfg.to_str().unwrap()])
        .out(&out)
        .sets(&SMALL)
        .sets(extra)
        .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!out.exists(), "a refused run wrote {}", out.display());
    let e = stderr(&o);
    assert!(!e.contains("panicked"), "{e}");
    e
}

#[test]
fn a_bad_goal_in_a_room_file_exits_2_naming_the_file_and_field_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let room =
        "name='r'\noutline=[[0,0],[800,0],[800,400],[0,400]]\nhome={x=100,y=200,heading_deg=0}\n";
    let e = run_refused_with_room(
        dir.path(),
        &format!("{room}goal={{x=900,y=200,radius=50}}\n"),
        &[],
    );
    assert!(
        e.contains("r.toml") && e.contains("`goal`") && e.contains("outside the room outline"),
        "{e}"
    );
    let e = run_refused_with_room(
        dir.path(),
        &format!("{room}[[waypoints]]\nx=300\ny=200\nradius=0\n"),
        &[],
    );
    assert!(
        e.contains("r.toml") && e.contains("`waypoints[0].radius`"),
        "{e}"
    );
    // Behind a wall with a 120 mm gap: reachable for the Khepera, not for a body of radius 60.
    let gap = format!(
        "{room}goal={{x=700,y=200,radius=50}}\n\
         [[obstacles]]\noutline=[[400,5],[420,5],[420,140],[400,140]]\n\
         [[obstacles]]\noutline=[[400,260],[420,260],[420,395],[400,395]]\n"
    );
    let e = run_refused_with_room(
        dir.path(),
        &gap,
        &["robot.radius=60", "rooms=[\"r.toml\"]", "aem.enabled=false"],
    );
    // The room list came from --set, so the message names that --set (issue #52 item 7).
    assert!(
        e.contains("--set rooms=")
            && e.contains("`rooms[0]`")
            && e.contains("room \"r\", field `goal`"),
        "{e}"
    );
    assert!(e.contains("cannot be reached from home"), "{e}");
}

#[test]
fn the_shipped_mission_rooms_run() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let out = dir.path().join("o");
    Fm::new(["run", cfg.to_str().unwrap()])
        .out(&out)
        .sets(&SMALL)
        .sets(&["rooms=[\"../rooms/fetch-L.toml\", \"../rooms/patrol.toml\"]"])
        .ok();
    let table = std::fs::read_to_string(out.join("table.md")).unwrap();
    assert!(
        table.contains("fetch-L") && table.contains("patrol"),
        "{table}"
    );
}

#[test]
fn user_room_takes_part_in_recognition() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("tiny");
    let cfg = repo().join("configs/tiny.toml");
    let o = run(&[
        "run",
        cfg.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--set",
        "ga.generations=3",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rec = std::fs::read_to_string(out.join("recognition.csv")).unwrap();
    assert!(
        rec.starts_with(
            "room,test_runs,correct,recognition_pct,as_H,as_square,as_U,not_recognised"
        ),
        "{rec}"
    );
    assert!(rec.lines().any(|l| l.starts_with("U,4,")), "{rec}");
}

#[test]
fn bench_json_has_the_documented_keys() {
    let o = run(&[
        "bench",
        "--steps",
        "4000",
        "--population",
        "10",
        "--repeat",
        "1",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    for k in ["robot_steps", "seconds", "robot_steps_per_sec"] {
        assert!(v[k].as_f64().unwrap() > 0.0, "{k}");
    }
}

/// `--steps` counts robot-steps in every room of the run: with two rooms (and no trial ending at
/// home) 4,000 steps are one evaluation of five robots, not two.
#[test]
fn bench_steps_count_every_room() {
    let o = run(&[
        "bench",
        "--steps",
        "4000",
        "--population",
        "5",
        "--repeat",
        "1",
        "--set",
        r#"rooms=["H","square"]"#,
        "--set",
        "trial.end_at_home=false",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["population_evaluations"], 1);
    assert_eq!(v["population_robot_steps"], 4000);
    assert_eq!(v["robot_steps"], 4000);
}

/// `--set robot=NAME` replaces the whole `[robot]` table, and with it the `robot.motion` that
/// `--motion` sets: bench refuses it (exit 2, pointing at `robot.file`) rather than measure the
/// robot's default motion under the name `wheels`; `--set robot.file=NAME` measures it in
/// `wheels`, and the report names the robot.
#[test]
fn bench_refuses_a_robot_set_that_drops_its_motion() {
    let base = [
        "bench",
        "--steps",
        "400",
        "--population",
        "2",
        "--repeat",
        "1",
    ];
    let wheels = [&base[..], &["--motion", "wheels", "--json", "--set"]].concat();
    let refused = run(&[&wheels[..], &["robot=epuck2"]].concat());
    assert_eq!(refused.status.code(), Some(2), "{}", stderr(&refused));
    let err = stderr(&refused);
    assert!(
        err.contains("--motion wheels") && err.contains("--set robot.file=NAME"),
        "{err}"
    );
    let o = ok(&[&wheels[..], &["robot.file=epuck2"]].concat());
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(
        (v["robot"].as_str(), v["motion"].as_str()),
        (Some("epuck2"), Some("wheels"))
    );
}

/// `--robot NAME` measures that robot, as `--set robot.file=NAME` does, in the motion
/// `--motion` asks for.
#[test]
fn bench_measures_the_robot_named_by_robot() {
    let o = ok(&[
        "bench",
        "--steps",
        "400",
        "--population",
        "2",
        "--repeat",
        "1",
        "--motion",
        "wheels",
        "--robot",
        "epuck2",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(
        (v["robot"].as_str(), v["motion"].as_str()),
        (Some("epuck2"), Some("wheels"))
    );
}

/// `--room` takes a room file, so the Thymio II is measured in its own rooms (rooms/thymio2/,
/// the paper's scaled 3x: in the paper's rooms its home is too near the walls for its body).
#[test]
fn bench_measures_the_thymio_in_its_rooms() {
    let room = repo().join("rooms/thymio2/H.toml");
    let o = ok(&[
        "bench",
        "--room",
        room.to_str().unwrap(),
        "--set",
        "robot=thymio2",
        "--steps",
        "400",
        "--population",
        "2",
        "--repeat",
        "1",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(
        (v["robot"].as_str(), v["room"].as_str()),
        (Some("thymio2"), Some("H-x3"))
    );
    assert!(v["population_robot_steps"].as_u64().unwrap() > 0);
}

/// The study runs as many (setting, seed) runs at a time as it has threads: its tables, and
/// every run's records, are the same bytes with one thread (one run at a time) and with three
/// (three of its four runs at once, and each population evaluated in parallel).
#[test]
fn reproduce_results_do_not_depend_on_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let study = |threads: &str| {
        let out = dir.path().join(format!("threads-{threads}"));
        let o = Fm::new(["reproduce", "--quick", "--seeds", "2", "--threads", threads])
            .sets(&SMALL)
            .out(&out)
            .run();
        assert!(o.status.success(), "{}", stderr(&o));
        out
    };
    let (one, three) = (study("1"), study("3"));
    let mut files = vec![
        "table1.csv".to_string(),
        "table2.csv".into(),
        "claims.csv".into(),
    ];
    for setting in ["high-curiosity", "low-curiosity"] {
        for index in [1, 2] {
            for f in ["generations.csv", "best_genome.json", "recognition.csv"] {
                files.push(format!("{setting}/seed-{index}/{f}"));
            }
        }
    }
    for f in files {
        assert_eq!(
            std::fs::read(one.join(&f)).unwrap(),
            std::fs::read(three.join(&f)).unwrap(),
            "{f} differs"
        );
    }
}

#[test]
fn reproduce_quick_writes_every_documented_file() {
    let dir = tempfile::tempdir().unwrap();
    // A quick look has its own default directory: it never lands in a full study's `results`.
    let out = dir.path().join("results-quick");
    let o = Fm::new(["reproduce", "--quick", "--seed", "5", "--seeds", "2"])
        .sets(&SMALL)
        .in_dir(dir.path())
        .run();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!dir.path().join("results").exists());
    for f in [
        "table1.md",
        "table1.csv",
        "table2.md",
        "table2.csv",
        "summary.json",
        "fitness.svg",
        "trajectories_high_curiosity.svg",
        "trajectories_low_curiosity.svg",
        "table1_seeds.csv",
        "claims.md",
        "claims.csv",
        "report.html",
    ] {
        assert!(out.join(f).is_file(), "missing {f}");
    }
    let second = fuzzymotiv::random::study_seed(5, 1);
    // The run directories are named by the seed's index (1 = the base seed).
    for index in [1, 2] {
        for f in [
            "high-curiosity/SEED/generations.csv",
            "low-curiosity/SEED/best_genome.json",
            "high-curiosity/SEED/report.html",
            "low-curiosity/SEED/trajectories.svg",
        ] {
            let f = f.replace("SEED", &format!("seed-{index}"));
            assert!(out.join(&f).is_file(), "missing {f}");
        }
    }
    let t1 = std::fs::read_to_string(out.join("table1.csv")).unwrap();
    assert!(t1.starts_with("room,seeds,average_fitness,average_fitness_std,paper_average_fitness,exploration_pct,exploration_pct_std,paper_exploration_pct"), "{t1}");
    assert_eq!(t1.lines().count(), 6);
    assert!(
        t1.lines().nth(1).unwrap().starts_with("H,2,") && t1.contains(",0.6421,"),
        "{t1}"
    );
    let per_seed = std::fs::read_to_string(out.join("table1_seeds.csv")).unwrap();
    assert_eq!(per_seed.lines().count(), 1 + 5 * 2, "{per_seed}");
    let md = std::fs::read_to_string(out.join("table1.md")).unwrap();
    assert!(
        md.contains(" ± ")
            && md.contains(&format!("2 seeds (5, {second})"))
            && md.contains("quick"),
        "{md}"
    );
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["seed"], 5);
    assert_eq!(s["seeds"], serde_json::json!([5, second]));
    assert!(second < 1 << 53, "seeds survive JSON readers");
    assert_eq!(s["settings"][0]["per_seed"].as_array().unwrap().len(), 2);
    assert!(
        s["settings"][0]["std"][0]["exploration_pct"]
            .as_f64()
            .is_some()
    );
    assert_eq!(s["claims"].as_array().unwrap().len(), 6);
    assert!(s["wall_seconds"].as_f64().unwrap() > 0.0);
    let settings = s["settings"].as_array().unwrap();
    assert_eq!(settings.len(), 2);
    assert_eq!(settings[1]["motivations"]["homing"], 0.3);
    let row = &settings[0]["rows"][0];
    for k in [
        "room",
        "average_fitness",
        "exploration_pct",
        "recognition_pct",
        "battery_pct",
        "homing_pct",
    ] {
        assert!(!row[k].is_null(), "row lacks {k}");
    }
    let svg = std::fs::read_to_string(out.join("trajectories_high_curiosity.svg")).unwrap();
    assert_eq!(svg.matches("<polyline").count(), 5, "one path per room");
}

/// The `fm-data` JSON block of a report page.
fn page_data(html: &str) -> serde_json::Value {
    let start = html
        .find(r#"<script type="application/json" id="fm-data">"#)
        .unwrap();
    let rest = &html[start..];
    let body = &rest[rest.find('>').unwrap() + 1..rest.find("</script>").unwrap()];
    serde_json::from_str(&body.replace("<\\/", "</")).unwrap()
}

#[test]
fn run_writes_a_self_contained_report_and_figures() {
    let dir = tempfile::tempdir().unwrap();
    let out = small_run(dir.path(), "rep", &["--png"]);
    for f in [
        "report.html",
        "fitness.svg",
        "fitness.png",
        "terms.svg",
        "terms.png",
        "trajectories.svg",
        "trajectories.png",
    ] {
        assert!(out.join(f).is_file(), "missing {f}");
    }
    let png = std::fs::read(out.join("fitness.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for needle in [
        "Fitness evolution",
        "Results per room",
        "firing rules",
        "Confusion matrix",
        "r-node",
        "config.resolved.toml",
        "seed = 3",
        "class=\"replay\"",
        "Content-Security-Policy",
    ] {
        assert!(html.contains(needle), "report lacks {needle}");
    }
    // Nothing is fetched: no external scripts, styles, images or fonts.
    for bad in ["<link", " src=", "@import", "url(", "https://"] {
        assert!(!html.contains(bad), "report contains {bad}");
    }
    let without_ns = html.replace("http://www.w3.org/2000/svg", "");
    assert!(
        !without_ns.contains("http://"),
        "report refers to the network"
    );
    // One replay room per config room, each with steps + 1 poses and one action per step.
    let data = page_data(&html);
    let rooms = data["replays"][0]["rooms"].as_array().unwrap();
    assert_eq!(rooms.len(), 2);
    for r in rooms {
        assert_eq!(r["x"].as_array().unwrap().len(), 151);
        assert_eq!(r["s"].as_array().unwrap().len(), 150);
        assert_eq!(r["a"].as_str().unwrap().len(), 150);
        assert!(r["a"].as_str().unwrap().chars().all(|c| "SLRT".contains(c)));
    }
}

fn replay(args: &[&str]) -> Output {
    let mut all = vec!["replay"];
    all.extend_from_slice(args);
    run(&all)
}

#[test]
fn replay_is_deterministic_and_redraws_the_reported_paths() {
    let dir = tempfile::tempdir().unwrap();
    let out = small_run(dir.path(), "rp", &[]);
    let run_dir = out.to_str().unwrap();
    let page = |name: &str| dir.path().join(name).join("replay.html");
    for name in ["one", "two"] {
        let o = replay(&[run_dir, "--out", page(name).to_str().unwrap(), "--png"]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    for f in [
        "replay.html",
        "replay.json",
        "replay-H.csv",
        "replay-square.csv",
        "replay.svg",
        "replay.png",
    ] {
        assert!(dir.path().join("one").join(f).is_file(), "missing {f}");
    }
    assert_same_files(
        &dir.path().join("one"),
        &dir.path().join("two"),
        &["replay-H.csv", "replay-square.csv", "replay.json"],
        "between two replays",
    );
    let csv = std::fs::read_to_string(dir.path().join("one/replay-H.csv")).unwrap();
    assert!(csv.starts_with(
        "step,x_mm,y_mm,heading_rad,s0,s1,s2,s3,s4,s5,s6,s7,mL,mR,action,collision,idle\n0,"
    ));
    assert_eq!(
        csv.lines().count(),
        1 + 150 + 1,
        "header, 150 steps, final pose"
    );
    // Without --seed the replay is the report's room-modelling run.
    let xs = column(&csv, "x_mm");
    let ys = column(&csv, "y_mm");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let reported = &page_data(&html)["replays"][0]["rooms"][0];
    assert_eq!(reported["room"], "H");
    for t in [0, 75, 150] {
        let rx = reported["x"][t].as_f64().unwrap();
        let ry = reported["y"][t].as_f64().unwrap();
        assert!(
            (rx - xs[t]).abs() <= 0.05 && (ry - ys[t]).abs() <= 0.05,
            "step {t}"
        );
    }
    // Another seed, another noise stream; one room only.
    let other = dir.path().join("other/replay.html");
    let o = replay(&[
        run_dir,
        "--room",
        "H",
        "--seed",
        "99",
        "--out",
        other.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!dir.path().join("other/replay-square.csv").exists());
    let again = std::fs::read_to_string(dir.path().join("other/replay-H.csv")).unwrap();
    assert_ne!(again, csv, "--seed had no effect");
    // A genome file alone (no config beside it, no --config) replays under the default config
    // (five rooms) and its own seed, and says so.
    let alone = dir.path().join("alone/replay.html");
    let genome = dir.path().join("lone-genome.json");
    std::fs::copy(out.join("best_genome.json"), &genome).unwrap();
    let o = replay(&[
        genome.to_str().unwrap(),
        "--room",
        "T",
        "--out",
        alone.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let t = std::fs::read_to_string(dir.path().join("alone/replay-T.csv")).unwrap();
    assert_eq!(t.lines().count(), 1 + 400 + 1, "default trial length");
    assert!(stderr(&o).contains("built-in defaults"), "{}", stderr(&o));
}

#[test]
fn replay_rejects_bad_input_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let out = small_run(dir.path(), "bad", &["--set", "ga.generations=2"]);
    let garbage = dir.path().join("garbage.json");
    std::fs::write(&garbage, "{ not json").unwrap();
    let short = dir.path().join("short.json");
    std::fs::write(&short, r#"{"shape": {"hidden": 6}, "weights": [0.5, 1.0]}"#).unwrap();
    let typo = dir.path().join("typo.json");
    std::fs::write(
        &typo,
        r#"{"shape": {"hidden": 6}, "weights": [0.5, "1.0"]}"#,
    )
    .unwrap();
    let shapeless = dir.path().join("shapeless.json");
    std::fs::write(&shapeless, r#"{"weights": [0.5]}"#).unwrap();
    let empty_dir = dir.path().join("empty");
    std::fs::create_dir(&empty_dir).unwrap();
    let page = dir.path().join("x/replay.html");
    let nowhere = dir.path().join("nowhere");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec![nowhere.to_str().unwrap()], "no such"),
        (vec![empty_dir.to_str().unwrap()], "config.resolved.toml"),
        (vec![garbage.to_str().unwrap()], "not valid JSON"),
        (vec![short.to_str().unwrap()], "68"),
        (vec![typo.to_str().unwrap()], "field `weights[1]`"),
        (vec![shapeless.to_str().unwrap()], "missing field `shape`"),
        (
            vec![out.to_str().unwrap(), "--room", "attic"],
            "not a room of the config",
        ),
    ];
    for (args, expect) in cases {
        let mut all = args.clone();
        all.extend_from_slice(&["--out", page.to_str().unwrap()]);
        let o = replay(&all);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
        assert!(e.contains(expect), "{args:?}: {e}");
        assert!(!e.contains("panicked"), "{args:?}: {e}");
    }
    assert!(!page.exists());
    // A page named like the trajectories (`y.json`, a bare name in the current directory)
    // would replace them: refused, nothing written.
    for name in ["y.json", "./y.json", "y.svg"] {
        let o = Fm::new([
            "replay",
            out.to_str().unwrap(),
            "--room",
            "H",
            "--out",
            name,
        ])
        .in_dir(dir.path())
        .run();
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        assert!(stderr(&o).contains("would both be"), "{}", stderr(&o));
        assert!(!dir.path().join("y-H.csv").exists(), "{name}");
    }
}

/// Kill a run at several points (deterministic ones: `FUZZYMOTIV_TEST_ABORT_AFTER=N` aborts the
/// process, as `kill -9` would, once N generations are checkpointed), resume it each time, and
/// get exactly the files of an uninterrupted run.
#[test]
fn killed_run_resumes_to_identical_results() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let sets = [
        "--set",
        "ga.population=12",
        "--set",
        "ga.generations=12",
        "--set",
        "trial.steps=200",
    ];
    let reference = dir.path().join("reference");
    let mut args = vec![
        "run",
        cfg.to_str().unwrap(),
        "--out",
        reference.to_str().unwrap(),
    ];
    args.extend_from_slice(&sets);
    assert!(run(&args).status.success());

    let out = dir.path().join("killed");
    let partial = dir.path().join("killed.partial");
    let mut fresh = vec!["run", cfg.to_str().unwrap(), "--out", out.to_str().unwrap()];
    fresh.extend_from_slice(&sets);
    let resume = vec!["run", "--resume", out.to_str().unwrap()];
    // 1 + 3 + 5 = 9 of the 12 generations, then the rest; the first resume uses --resume, the
    // others the same command.
    for (k, n) in [1, 3, 5].into_iter().enumerate() {
        let args = if k == 1 { &resume } else { &fresh };
        let o = bin()
            .args(args)
            .env("FUZZYMOTIV_TEST_ABORT_AFTER", n.to_string())
            .output()
            .unwrap();
        assert!(!o.status.success(), "not killed after {n} generations");
        assert!(partial.join("checkpoint.json").is_file());
    }
    let o = run(&fresh);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("at generation 10/12"), "{}", stderr(&o));
    let files = [
        "generations.csv",
        "best_genome.json",
        "recognition.csv",
        "table.md",
        "config.resolved.toml",
        "population.json",
    ];
    assert_same_files(&reference, &out, &files, "after the kills");
    assert!(!partial.exists());
}

#[test]
fn resume_without_an_interrupted_run_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(&[
        "run",
        "--resume",
        dir.path().join("nothing").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no interrupted run"), "{}", stderr(&o));
}

/// The library's corpus of bad configs and rooms, through the binary: exit 2, the field named,
/// nothing written, no panic.
#[test]
fn corpus_through_the_binary() {
    let corpus = repo().join("crates/fuzzymotiv/tests/corpus");
    let dir = tempfile::tempdir().unwrap();
    let mut n = 0;
    for entry in std::fs::read_dir(corpus.join("configs")).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let field = text
            .lines()
            .next()
            .unwrap()
            .trim_start_matches("# field: ")
            .trim()
            .to_string();
        let out = dir.path().join(format!("out{n}"));
        let o = run(&[
            "run",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{path:?}: {e}");
        assert!(
            e.contains(&format!("`{field}`")) && !e.contains("panicked"),
            "{path:?}: {e}"
        );
        assert!(
            !out.exists() && !dir.path().join(format!("out{n}.partial")).exists(),
            "{path:?} wrote output"
        );
        n += 1;
    }
    for entry in std::fs::read_dir(corpus.join("rooms")).unwrap() {
        let path = entry.unwrap().path();
        let o = run(&["rooms", "--check", path.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{path:?}");
        assert!(!stderr(&o).contains("panicked"));
        n += 1;
    }
    assert!(n >= 50);
}

/// `--out` pointing at a directory that is not a fuzzymotiv output is refused before the run,
/// and the directory is left untouched.
#[test]
fn out_dir_that_is_not_ours_is_never_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let precious = dir.path().join("precious");
    std::fs::create_dir(&precious).unwrap();
    std::fs::write(precious.join("thesis.tex"), "do not delete").unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let o = run(&[
        "run",
        cfg.to_str().unwrap(),
        "--out",
        precious.to_str().unwrap(),
        "--set",
        "ga.generations=2",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("not a fuzzymotiv output"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(precious.join("thesis.tex")).unwrap(),
        "do not delete"
    );
    // An earlier run directory is replaced.
    let out = dir.path().join("run");
    for _ in 0..2 {
        let o = run(&[
            "run",
            cfg.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--set",
            "ga.generations=2",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
}

/// Runs the binary in directory `cwd`.
fn in_dir(cwd: &Path, args: &[&str]) -> Output {
    bin().current_dir(cwd).args(args).output().unwrap()
}

/// The files of a directory with their contents (to see that nothing changed).
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file())
        .map(|p| (p.clone(), std::fs::read(&p).unwrap()))
        .collect();
    files.sort();
    files
}

/// Issue #13 item 1: results of another run (other config, other kind of output) are kept unless
/// --force; the same command again says it is done; an unfinished run is resumed, not discarded.
#[test]
fn results_are_never_replaced_silently() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let out = dir.path().join("r");
    let go = |extra: &[&str]| {
        let mut args = vec!["run", cfg.to_str().unwrap(), "--out", out.to_str().unwrap()];
        args.extend_from_slice(&["--set", "ga.generations=2"]);
        args.extend_from_slice(extra);
        run(&args)
    };
    assert!(go(&[]).status.success());
    let before = snapshot(&out);
    // The same command again: done, nothing rewritten.
    let o = go(&[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("already holds this run"),
        "{}",
        stderr(&o)
    );
    assert_eq!(snapshot(&out), before);
    // Another run (other seed): refused before any work, the results kept.
    let o = go(&["--seed", "4"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("different run") && stderr(&o).contains("--force"));
    assert_eq!(snapshot(&out), before);
    assert!(!dir.path().join("r.partial").exists());
    // --force replaces them.
    assert!(go(&["--seed", "4", "--force"]).status.success());
    assert!(
        std::fs::read_to_string(out.join("config.resolved.toml"))
            .unwrap()
            .contains("seed = 4")
    );
    // Another kind of output (a reproduce study): refused.
    let study = dir.path().join("study");
    std::fs::create_dir_all(study.join("high-curiosity")).unwrap();
    std::fs::write(study.join("summary.json"), "{}").unwrap();
    let o = run(&[
        "run",
        cfg.to_str().unwrap(),
        "--out",
        study.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(study.join("summary.json").is_file());
    // An unfinished run of another config: its checkpoint is kept unless --force.
    let other = dir.path().join("other.partial");
    std::fs::create_dir_all(&other).unwrap();
    std::fs::write(other.join("config.resolved.toml"), "seed = 99\n").unwrap();
    std::fs::write(other.join("checkpoint.json"), "{}").unwrap();
    let target = dir.path().join("other");
    let o = run(&[
        "run",
        cfg.to_str().unwrap(),
        "--out",
        target.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("unfinished"), "{}", stderr(&o));
    assert!(other.join("checkpoint.json").is_file());
}

/// Issue #13 item 2: `--out .` is refused at once and leaves nothing behind.
#[test]
fn out_dot_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let o = in_dir(dir.path(), &["run", cfg.to_str().unwrap(), "--out", "."]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("current directory"), "{}", stderr(&o));
    assert!(!stderr(&o).contains("generation"), "{}", stderr(&o));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    let parent = dir.path().parent().unwrap();
    assert!(
        !parent
            .join(format!(
                "{}.partial",
                dir.path().file_name().unwrap().to_str().unwrap()
            ))
            .exists()
    );
}

/// Issue #13 item 3: without a terminal, plain progress lines (setting, seed, generation, best F,
/// elapsed, ETA); none with --quiet.
#[test]
fn progress_lines_without_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let out = dir.path().join("p");
    let o = ok(&["run", cfg.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let e = stderr(&o);
    assert!(
        e.contains("tiny: seed 7, 1 × 10 generations of 20 robots"),
        "{e}"
    );
    assert!(e.contains("tiny seed 7: generation 1/10, best F "), "{e}");
    assert!(
        e.contains("generation 10/10") && e.contains("elapsed") && e.contains("ETA"),
        "{e}"
    );
    let q = dir.path().join("q");
    let o = ok(&[
        "run",
        cfg.to_str().unwrap(),
        "--out",
        q.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(!stderr(&o).contains("generation"), "{}", stderr(&o));
}

/// Issue #13 item 3: a killed run re-run with the same command resumes (saying from which
/// generation), and `wall_seconds` counts the time before the kill too.
#[test]
fn same_command_resumes_a_killed_run_and_counts_all_wall_time() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let out = dir.path().join("k");
    let cp = dir.path().join("k.partial/checkpoint.json");
    let args = [
        "run",
        cfg.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--set",
        "ga.generations=200",
        "--set",
        "ga.population=30",
    ];
    let mut child = bin()
        .args(args)
        .stderr(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let checkpoint = |p: &Path| -> Option<serde_json::Value> {
        serde_json::from_str(&std::fs::read_to_string(p).ok()?).ok()
    };
    let t0 = std::time::Instant::now();
    while checkpoint(&cp).is_none_or(|c| c["runs"][0]["history"].as_array().unwrap().len() < 3) {
        assert!(
            t0.elapsed().as_secs() < 60 && child.try_wait().unwrap().is_none(),
            "no checkpoint"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let before = checkpoint(&cp).unwrap();
    let done = before["runs"][0]["history"].as_array().unwrap().len();
    let earlier = before["wall_seconds"].as_f64().unwrap();
    assert!(earlier > 0.0);
    let o = ok(&args);
    let e = stderr(&o);
    assert!(
        e.contains(&format!("at generation {}/200", done + 1)),
        "{e}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert!(summary["wall_seconds"].as_f64().unwrap() >= earlier);
}

/// Issue #13 item 5: every seed in JSON output is exact for a double (< 2^53).
#[test]
fn plan_seeds_are_exact_as_doubles() {
    let o = ok(&[
        "plan",
        repo().join("configs/sweep-small.toml").to_str().unwrap(),
    ]);
    for line in stdout(&o).lines() {
        let job: serde_json::Value = serde_json::from_str(line).unwrap();
        assert!(job["seed"].as_u64().unwrap() < 1 << 53, "{line}");
    }
    let cfg = repo().join("configs/tiny.toml");
    let o = run(&["run", cfg.to_str().unwrap(), "--seed", "9007199254740992"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("0 to 9007199254740991"),
        "{}",
        stderr(&o)
    );
}

/// Issue #13 item 6: the run's table and summary say what produced them.
#[test]
fn tables_carry_their_provenance() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let out = dir.path().join("t");
    Fm::new(["run", cfg.to_str().unwrap()])
        .out(&out)
        .sets(&["ga.generations=2"])
        .ok();
    let table = std::fs::read_to_string(out.join("table.md")).unwrap();
    assert!(
        table.contains(&format!("fuzzymotiv {}", env!("CARGO_PKG_VERSION"))),
        "{table}"
    );
    assert!(
        table.contains("seed 7") && table.contains("GA 20 robots × 2 generations"),
        "{table}"
    );
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        (s["population"].as_u64(), s["generations"].as_u64()),
        (Some(20), Some(2))
    );
}

/// Issue #13 item 6: seeds_table.py refuses to average a quick and a full study.
#[test]
#[ignore = "needs python3: run by .ci/run"]
fn seeds_table_refuses_to_mix_quick_and_full_studies() {
    let dir = tempfile::tempdir().unwrap();
    let mut dirs = Vec::new();
    for quick in [true, false] {
        let d = dir.path().join(format!("study-{quick}"));
        std::fs::create_dir_all(&d).unwrap();
        let settings = serde_json::json!([{"name": "high-curiosity", "population": if quick {30} else {200}, "generations": 30, "rows": []}]);
        let doc = serde_json::json!({"version": "x", "seed": 1, "quick": quick, "settings": settings, "wall_seconds": 1.0});
        std::fs::write(d.join("summary.json"), doc.to_string()).unwrap();
        dirs.push(d);
    }
    let o = std::process::Command::new("python3")
        .arg(repo().join("scripts/seeds_table.py"))
        .args(&dirs)
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(stderr(&o).contains("quick"), "{}", stderr(&o));
}

/// Issue #13 item 7: the CLI's rough edges.
#[test]
fn plain_messages_for_rough_edges() {
    let dir = tempfile::tempdir().unwrap();
    let u = repo().join("rooms/U.toml");
    // rooms --check takes several files (as a shell glob gives them).
    let o = ok(&["rooms", "--check", u.to_str().unwrap(), u.to_str().unwrap()]);
    assert_eq!(stdout(&o).matches("ok  ").count(), 2);
    // run --help says CONFIG is required (unless --resume).
    let help = stdout(&ok(&["run", "--help"]));
    assert!(
        help.contains("Usage: fuzzymotiv run CONFIG") && help.contains("Required, unless --resume"),
        "{help}"
    );
    let cfg = repo().join("configs/tiny.toml");
    let c = cfg.to_str().unwrap();
    let expect = |args: &[&str], words: &[&str]| {
        let o = run(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        for w in words {
            assert!(
                stderr(&o).contains(w),
                "{args:?}: `{w}` not in {}",
                stderr(&o)
            );
        }
        assert!(!stderr(&o).contains("expected u64") && !stderr(&o).contains("expected usize"));
    };
    expect(
        &["run", c, "--seed", "-1"],
        &["whole number from 0 to 9007199254740991"],
    );
    expect(
        &["run", c, "--set", "seed=-3"],
        &["`seed`", "whole number from 0 to 9007199254740991"],
    );
    expect(
        &["run", c, "--set", "ga.population=2.5"],
        &["`ga.population`", "a whole number"],
    );
    expect(
        &["run", c, "--set", "trial.dt=abc"],
        &["`trial.dt`", "a number"],
    );
    // TOML syntax errors give line and column.
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "seed = 1\n[ga\npopulation = 3\n").unwrap();
    expect(&["run", bad.to_str().unwrap()], &["line 2, column"]);
    let bad_room = dir.path().join("bad-room.toml");
    std::fs::write(&bad_room, "name = 'x'\noutline = [[0,0],\n").unwrap();
    let o = run(&["rooms", "--check", bad_room.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("line "), "{}", stderr(&o));
    // A room file given as a config says so.
    expect(
        &["run", u.to_str().unwrap()],
        &["looks like a room file", "rooms --check"],
    );
    // Motivations within 1e-3 of 1 are normalised, with a note.
    let o = ok(&[
        "fuzzy",
        "--motivations",
        ".3333,.3333,.3333,0",
        "--fitness",
        "1,1,1,1",
    ]);
    assert!(stderr(&o).contains("normalised"), "{}", stderr(&o));
    expect(
        &[
            "fuzzy",
            "--motivations",
            ".3,.3,.3,0",
            "--fitness",
            "1,1,1,1",
        ],
        &["within 0.001"],
    );
    let m = dir.path().join("m.toml");
    std::fs::write(&m, "[motivations]\ncuriosity = 0.3333\nhoming = 0.3333\norientation = 0\nenergy = 0.3333\n[ga]\npopulation = 4\ngenerations = 1\n[trial]\nsteps = 20\n[aem]\nenabled = false\n").unwrap();
    let out = dir.path().join("m");
    let o = ok(&[
        "run",
        m.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(
        stderr(&o).matches("normalised").count(),
        1,
        "{}",
        stderr(&o)
    );
    let resolved = std::fs::read_to_string(out.join("config.resolved.toml")).unwrap();
    let raw: toml::Table = toml::from_str(&resolved).unwrap();
    let sum: f64 = ["curiosity", "homing", "orientation", "energy"]
        .iter()
        .map(|k| raw["motivations"][k].as_float().unwrap())
        .sum();
    assert!((sum - 1.0).abs() < 1e-12, "{resolved}");
}

/// Issue #13 item 7: a genome file is replayed under the config beside it (or --config), and
/// the program says which; the CSV names its units.
#[test]
fn replay_of_a_genome_file_uses_and_names_its_config() {
    let dir = tempfile::tempdir().unwrap();
    let out = small_run(dir.path(), "g", &[]);
    let genome = out.join("best_genome.json");
    let page = dir.path().join("rg/replay.html");
    let o = ok(&[
        "replay",
        genome.to_str().unwrap(),
        "--room",
        "H",
        "--out",
        page.to_str().unwrap(),
    ]);
    assert!(
        stderr(&o).contains("config.resolved.toml"),
        "{}",
        stderr(&o)
    );
    let csv = std::fs::read_to_string(dir.path().join("rg/replay-H.csv")).unwrap();
    assert!(csv.starts_with("step,x_mm,y_mm,heading_rad,"));
    assert_eq!(
        csv.lines().count(),
        150 + 2,
        "150 steps as trained, not the default 400"
    );
    let lone = dir.path().join("lone.json");
    std::fs::copy(&genome, &lone).unwrap();
    let page = dir.path().join("rl/replay.html");
    let cfg = out.join("config.resolved.toml");
    let o = ok(&[
        "replay",
        lone.to_str().unwrap(),
        "--config",
        cfg.to_str().unwrap(),
        "--room",
        "H",
        "--out",
        page.to_str().unwrap(),
    ]);
    assert!(stderr(&o).contains(cfg.to_str().unwrap()), "{}", stderr(&o));
    let again = std::fs::read_to_string(dir.path().join("rl/replay-H.csv")).unwrap();
    assert_eq!(again, csv);
}

/// `lab --bind` takes an IP address or `localhost`; a host name is refused before anything
/// starts (exit 2, saying what it accepts).
#[test]
fn lab_bind_refuses_a_host_name() {
    let dir = tempfile::tempdir().unwrap();
    let lab_dir = dir.path().join("lab");
    let o = run(&[
        "lab",
        "--bind",
        "example.org",
        "--dir",
        lab_dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("`localhost`"), "{}", stderr(&o));
    assert!(!lab_dir.exists());
}

/// `lab --token` takes 16 to 128 letters, digits, `-` or `_`; a short or odd one is refused
/// before anything starts (exit 2, saying what it accepts).
#[test]
fn lab_token_refuses_a_short_or_odd_token() {
    let dir = tempfile::tempdir().unwrap();
    let lab_dir = dir.path().join("lab");
    for bad in ["short", "0123456789abcdef; Path=/"] {
        let o = run(&["lab", "--token", bad, "--dir", lab_dir.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains("--token"), "{}", stderr(&o));
        assert!(stderr(&o).contains("16 to 128 letters"), "{}", stderr(&o));
        assert!(!lab_dir.exists());
    }
}

/// `lab` on a port in use, or with a file as `--dir`: exit 2 saying what to change, and no
/// lab directory left behind.
#[test]
fn lab_start_failures_are_the_users_to_fix() {
    let dir = tempfile::tempdir().unwrap();
    let busy = std::net::TcpListener::bind(("127.0.0.1", 0)).unwrap();
    let port = busy.local_addr().unwrap().port().to_string();
    let lab_dir = dir.path().join("lab");
    let o = run(&["lab", "--port", &port, "--dir", lab_dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("the port is in use"), "{}", stderr(&o));
    assert!(!lab_dir.exists());
    let file = dir.path().join("afile");
    std::fs::write(&file, "mine").unwrap();
    let o = run(&["lab", "--port", "0", "--dir", file.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("is not a directory"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
}

/// `lab --config FILE` reads the config as `run` does, before anything listens or is written:
/// a bad field, room, room file, term or size over the lab's limits exits 2 naming the file
/// and the field (here with the port busy, so the config is seen to be checked first), prints
/// no address and leaves no lab directory.
#[test]
fn lab_config_that_cannot_run_exits_2_naming_file_and_field_before_listening() {
    let dir = tempfile::tempdir().unwrap();
    let busy = std::net::TcpListener::bind(("127.0.0.1", 0)).unwrap();
    let port = busy.local_addr().unwrap().port().to_string();
    let lab_dir = dir.path().join("lab");
    std::fs::write(
        dir.path().join("r.toml"),
        "name = \"r\"\noutline = [[0,0],[100,0]]\nhome = { x = 10, y = 10, heading_deg = 0 }\n",
    )
    .unwrap();
    for (name, text, file, field) in [
        (
            "field",
            "[ga]\npopulation = -3\n",
            "field.toml",
            "field `ga.population`",
        ),
        (
            "room",
            "rooms = [\"nope.toml\"]\n",
            "room.toml",
            "field `rooms[0]`",
        ),
        (
            "roomfile",
            "rooms = [\"r.toml\"]\n",
            "r.toml",
            "field `outline`",
        ),
        (
            "size",
            "[ga]\npopulation = 1000\n",
            "size.toml",
            "more than the lab allows",
        ),
        (
            "term",
            "[motivations]\ncuriosity = 0.7\nrush = { weight = 0.3, term = \"hurry\" }\n",
            "term.toml",
            "field `motivations.rush`",
        ),
    ] {
        let config = dir.path().join(format!("{name}.toml"));
        std::fs::write(&config, text).unwrap();
        let o = run(&[
            "lab",
            "--config",
            config.to_str().unwrap(),
            "--port",
            &port,
            "--dir",
            lab_dir.to_str().unwrap(),
        ]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(file) && err.contains(field), "{name}: {err}");
        assert!(
            !err.contains("port is in use") && !err.contains("panicked"),
            "{name}: {err}"
        );
        assert!(String::from_utf8_lossy(&o.stdout).is_empty(), "{name}");
        assert!(!lab_dir.exists(), "{name}");
    }
    let missing = dir.path().join("missing.toml");
    let o = run(&[
        "lab",
        "--config",
        missing.to_str().unwrap(),
        "--port",
        &port,
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("missing.toml: cannot read config file"),
        "{}",
        stderr(&o)
    );
}

/// Each of bench's sizes is checked on its own: the message names the option, its range and
/// the value given (no unbounded --steps).
#[test]
fn bench_names_the_option_out_of_range() {
    for (option, value, range) in [
        ("--steps", "0", "1 to 10000000000"),
        ("--steps", "18446744073709551615", "1 to 10000000000"),
        ("--repeat", "0", "1 to 10000"),
        ("--population", "1", "2 to 1000000"),
    ] {
        let o = run(&["bench", option, value]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let want = format!("{option}: must be from {range}, got {value}");
        assert!(stderr(&o).contains(&want), "{}", stderr(&o));
    }
}

/// Issue #52 item 3: `fuzzy --motivations curiosity=0.7,urgency=0.3` and a config's
/// `[motivations]` of the same two names build the same two-input TSK (the config no longer
/// adds the paper's other three and fails "must sum to 1, got 1.2"); the config runs, and its
/// F under the library is the number `fuzzy` prints.
#[test]
fn fuzzy_and_a_config_read_the_same_motivation_names_alike() {
    let o = run(&[
        "fuzzy",
        "--motivations",
        "urgency=0.3,curiosity=0.7",
        "--fitness",
        "a=0.9,urgency=0.5",
        "--explain",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let printed = stdout(&o);
    let motivations = "[motivations]\ncuriosity = 0.7\nurgency = 0.3\n";
    let raw = fuzzymotiv::RawConfig::parse(motivations, "c.toml", &[]).unwrap();
    let tsk = fuzzymotiv::fitness::TskFitness::paper();
    let m = raw.motivations.validated(&tsk).unwrap();
    assert_eq!(m.input_names(), ["a", "urgency"]);
    let f = tsk.evaluate(&m, &[0.9, 0.5]);
    assert_eq!(printed.lines().next(), Some(format!("{f:.12}").as_str()));
    assert!(
        printed.ends_with('\n'),
        "--explain ends its last line: {printed:?}"
    );

    let tmp = tempfile::tempdir().unwrap();
    let config = tmp.path().join("two.toml");
    let room = repo().join("rooms/fetch-H.toml");
    let text = format!("rooms = [{:?}]\n{motivations}", room.display().to_string());
    std::fs::write(&config, text).unwrap();
    let out = tmp.path().join("out");
    let o = Fm::new(["run".as_ref(), config.as_os_str()])
        .out(&out)
        .sets(&SMALL)
        .sets(&["aem.enabled=false"])
        .ok();
    assert!(
        stderr(&o).contains("leaves out `homing`, `orientation` and `energy` of the paper's four"),
        "{}",
        stderr(&o)
    );
    let resolved = std::fs::read_to_string(out.join("config.resolved.toml")).unwrap();
    assert!(
        resolved.contains("[motivations]\ncuriosity = 0.7\nurgency = 0.3\n\n"),
        "{resolved}"
    );
}

/// The weights of a run's best genome.
fn genome_len(run: &Path) -> usize {
    let text = std::fs::read_to_string(run.join("best_genome.json")).unwrap();
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    doc["weights"].as_array().unwrap().len()
}

/// A config names its robot: `--set robot=epuck2` evolves the e-puck2's 8-6-2 network and the
/// Thymio II config its 7-6-2 network (62 weights); the resolved config names the robot, so a
/// run of another robot is another identity; the Khepera named explicitly is the default run.
#[test]
fn a_run_evolves_the_network_of_its_robot() {
    let dir = tempfile::tempdir().unwrap();
    let tiny = repo().join("configs/tiny.toml");
    let epuck = dir.path().join("epuck");
    Fm::new(["run".as_ref(), tiny.as_os_str()])
        .out(&epuck)
        .sets(&SMALL)
        .sets(&["robot=epuck2"])
        .ok();
    let resolved = std::fs::read_to_string(epuck.join("config.resolved.toml")).unwrap();
    assert!(
        resolved.contains("[robot]\nfile = \"epuck2\"\nradius = 37.0\n"),
        "{resolved}"
    );
    assert_eq!(genome_len(&epuck), 68);
    // The report says which robot and replays its own sensors (names, reading scale).
    let report = std::fs::read_to_string(epuck.join("report.html")).unwrap();
    assert!(report.contains("simulated GCtronic e-puck2 (8 proximity sensors) robots"));
    assert!(report.contains("\"max\":3731.0") && report.contains("IR0 front-right"));
    let thymio = dir.path().join("thymio");
    let sets = [SMALL.as_slice(), &["ga.generations=1", "aem.enabled=false"]].concat();
    Fm::new([
        "run".as_ref(),
        repo().join("configs/thymio2.toml").as_os_str(),
    ])
    .out(&thymio)
    .sets(&sets)
    .ok();
    assert_eq!(genome_len(&thymio), 7 * 6 + 6 + 2 * 7);
    let csv = std::fs::read_to_string(thymio.join("test_runs.csv")).unwrap();
    assert!(csv.lines().count() > 1, "{csv}");
    // The Khepera named is the Khepera by default: the same identity, the same bytes.
    let (named, plain) = (dir.path().join("named"), dir.path().join("plain"));
    let small = [SMALL.as_slice(), &["aem.enabled=false"]].concat();
    Fm::new(["run".as_ref(), tiny.as_os_str()])
        .out(&plain)
        .sets(&small)
        .ok();
    let named_sets = [small.as_slice(), &["robot=khepera"]].concat();
    Fm::new(["run".as_ref(), tiny.as_os_str()])
        .out(&named)
        .sets(&named_sets)
        .ok();
    assert_same_files(
        &named,
        &plain,
        &["config.resolved.toml", "best_genome.json"],
        "khepera by name",
    );
}

/// A hostile robot file exits 2 naming the file and the field, and writes nothing: a sensor
/// outside the body, a response that rises with distance, a step longer than the body radius,
/// a missing file.
#[test]
fn a_hostile_robot_file_names_its_file_and_field_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let good = fuzzymotiv::simulation::RobotSpec::builtin_text("epuck2").unwrap();
    let cases = [
        ("x = 33.5", "x = 60.0", "sensor[0].x"),
        ("v_max = 138.0", "v_max = 900.0", "v_max"),
        ("reading_max = 3731", "reading_max = -3", "reading_max"),
    ];
    for (k, (from, to, field)) in cases.iter().enumerate() {
        assert!(good.contains(from), "{from} not in the e-puck2's file");
        let robot = dir.path().join(format!("bad{k}.toml"));
        std::fs::write(&robot, good.replacen(from, to, 1)).unwrap();
        let config = dir.path().join(format!("c{k}.toml"));
        std::fs::write(
            &config,
            format!("robot = \"bad{k}.toml\"\nrooms = [\"H\", \"T\"]\n"),
        )
        .unwrap();
        let out = dir.path().join(format!("out{k}"));
        let o = run(&[
            "run",
            config.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{msg}");
        assert!(
            msg.contains(&format!("bad{k}.toml")) && msg.contains(field),
            "{field}: {msg}"
        );
        assert!(!msg.contains("panicked"), "{msg}");
        assert!(!out.exists(), "{field}: something was written");
    }
    let rising = good.replacen("reading = [", "reading = [1, ", 1).replacen(
        "distance_mm = [",
        "distance_mm = [0.1, ",
        1,
    );
    let robot = dir.path().join("rising.toml");
    std::fs::write(&robot, rising).unwrap();
    let o = run(&[
        "calibrate",
        "x.csv",
        "--robot",
        robot.to_str().unwrap(),
        "--out",
        "-",
    ]);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("rising.toml") && msg.contains("ray[0].reading"),
        "{msg}"
    );
    let config = dir.path().join("missing.toml");
    std::fs::write(&config, "robot = \"nowhere.toml\"\n").unwrap();
    let o = run(&[
        "run",
        config.to_str().unwrap(),
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("robot.file") && msg.contains("epuck2"),
        "{msg}"
    );
}
