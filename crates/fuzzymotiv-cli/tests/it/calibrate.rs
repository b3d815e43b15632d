//! `fuzzymotiv calibrate` and `trial.sensor_table` from the command line.

use crate::common;

use common::{ok, repo, run, stderr, stdout};

/// The shipped sample measurements become a table a config can name, and the run reads it.
#[test]
fn calibrate_writes_a_table_that_a_run_reads() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("robot.toml");
    let csv = repo().join("configs/sensors/khepera-bench.csv");
    let out = ok(&[
        "calibrate",
        csv.to_str().unwrap(),
        "--out",
        table.to_str().unwrap(),
    ]);
    let text = stdout(&out);
    assert!(
        text.starts_with("sensor,distance_mm,readings,median,mean,std,std_over_mean\n0,5,5,1002,"),
        "{text}"
    );
    assert!(
        stderr(&out).contains("trial.noise = 0.075 "),
        "{}",
        stderr(&out)
    );
    // The guide quotes the estimate calibrate prints for this file, in its config and its text.
    let printed = stderr(&out)
        .split("sensor noise estimate: trial.noise = ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .unwrap()
        .to_string();
    let guide = std::fs::read_to_string(repo().join("docs/guide/real-robot.md")).unwrap();
    for quoted in [
        format!("noise = {printed} "),
        format!("prints `trial.noise = {printed}`"),
    ] {
        assert!(
            guide.contains(&quoted),
            "real-robot.md does not quote `{quoted}`"
        );
    }
    let written = std::fs::read_to_string(&table).unwrap();
    assert!(written.contains("[[sensor.7.ray]]"), "{written}");
    // Again: the same table, nothing to do; another file is kept without --force.
    let again = ok(&[
        "calibrate",
        csv.to_str().unwrap(),
        "--out",
        table.to_str().unwrap(),
    ]);
    assert!(stderr(&again).contains("already holds this table"));
    let other = dir.path().join("other.toml");
    std::fs::write(&other, "x = 1\n").unwrap();
    let kept = run(&[
        "calibrate",
        csv.to_str().unwrap(),
        "--out",
        other.to_str().unwrap(),
    ]);
    assert_eq!(kept.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(&other).unwrap(), "x = 1\n");
    // A run names the table relative to its config.
    let config = dir.path().join("c.toml");
    std::fs::write(
        &config,
        "name = \"t\"\nrooms = [\"square\", \"H\"]\n[trial]\nsensor_table = \"robot.toml\"\n",
    )
    .unwrap();
    let run_dir = dir.path().join("run");
    let sets = [
        "--set",
        "ga.population=4",
        "--set",
        "ga.generations=1",
        "--set",
        "trial.steps=30",
        "--set",
        "aem.epochs=2",
        "--set",
        "aem.test_runs=1",
        "--quiet",
    ];
    let mut args = vec![
        "run",
        config.to_str().unwrap(),
        "--out",
        run_dir.to_str().unwrap(),
    ];
    args.extend(sets);
    ok(&args);
    let resolved = std::fs::read_to_string(run_dir.join("config.resolved.toml")).unwrap();
    assert!(
        resolved.contains("sensor_table = \"") && resolved.contains("robot.toml\""),
        "{resolved}"
    );
}

/// Bad measurements and bad tables exit 2 naming the file and the field; nothing is written.
#[test]
fn bad_measurements_and_tables_exit_2_naming_the_file_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "sensor,distance_mm,reading\n0,10,abc\n",
            "field `reading`: data row 1",
        ),
        (
            "sensor,dist,reading\n0,10,5\n",
            "field `distance_mm`: the header has no column",
        ),
        (
            "sensor,distance_mm,reading\n0,10,5000\n",
            "field `reading`: row 1: must be a reading in [0, 1023]",
        ),
        (
            "sensor,distance_mm,reading\n9,10,50\n",
            "field `sensor`: row 1: sensors are numbered 0 to 7",
        ),
    ];
    let out = dir.path().join("t.toml");
    for (text, want) in cases {
        let csv = dir.path().join("m.csv");
        std::fs::write(&csv, text).unwrap();
        let o = run(&[
            "calibrate",
            csv.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{text}");
        let e = stderr(&o);
        assert!(e.contains(&format!("m.csv: {want}")), "{e}");
        assert!(!out.exists());
    }
    let table = dir.path().join("robot.toml");
    std::fs::write(
        &table,
        "[[ray]]\ndistance_mm = [10, 50]\nreading = [300, 700]\n",
    )
    .unwrap();
    let config = dir.path().join("c.toml");
    std::fs::write(&config, "[trial]\nsensor_table = \"robot.toml\"\n").unwrap();
    let run_dir = dir.path().join("run");
    let o = run(&[
        "run",
        config.to_str().unwrap(),
        "--out",
        run_dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains("robot.toml: field `ray[0].reading`: must not increase"),
        "{e}"
    );
    assert!(!run_dir.exists());
}

/// The medians of a measurements CSV per sensor and distance, rounded to whole readings as the
/// table holds them (computed here from the file, not taken from `calibrate`).
fn medians_of(csv: &str) -> std::collections::BTreeMap<(usize, u32), f64> {
    let mut by: std::collections::BTreeMap<(usize, u32), Vec<f64>> = Default::default();
    for line in csv.lines().skip_while(|l| l.starts_with('#')).skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        by.entry((f[0].parse().unwrap(), f[1].parse().unwrap()))
            .or_default()
            .push(f[2].parse().unwrap());
    }
    by.into_iter()
        .map(|(k, mut v)| {
            v.sort_by(f64::total_cmp);
            let n = v.len();
            let m = if n % 2 == 1 {
                v[n / 2]
            } else {
                (v[n / 2 - 1] + v[n / 2]) / 2.0
            };
            (k, m.round())
        })
        .collect()
}

/// A table `calibrate` made from bench measurements, named by `trial.sensor_table`, makes the
/// simulated sensors read the measured medians: each sensor turned to face a wall at a gap
/// just short of a measured distance reads that distance's median (the first sample at or
/// beyond the wall), and nothing beyond the farthest one.
#[test]
fn a_calibrated_table_changes_the_sensor_readings_as_its_data_says() {
    use fuzzymotiv::simulation::{Arena, Pose, Room, SENSOR_LAYOUT, SENSORS};
    let dir = tempfile::tempdir().unwrap();
    let csv = repo().join("crates/fuzzymotiv-cli/tests/fixtures/calibrate/bench.csv");
    let table = dir.path().join("bench.toml");
    ok(&[
        "calibrate",
        csv.to_str().unwrap(),
        "--out",
        table.to_str().unwrap(),
    ]);
    let config = dir.path().join("c.toml");
    std::fs::write(&config, "[trial]\nsensor_table = \"bench.toml\"\n").unwrap();
    let loaded = fuzzymotiv_pipeline::files::inputs::load_config(Some(&config), &[], None).unwrap();
    let arena = Arena::new(
        Room::builtin("square").unwrap(),
        loaded.experiment.trial_params(),
    );
    let built_in = Arena::new(
        Room::builtin("square").unwrap(),
        &fuzzymotiv::simulation::TrialParams::default(),
    );
    // Sensor `s` facing the x = 800 wall of the square room, `gap` mm from it, at y = 400.
    let facing_wall = |s: usize, gap: f64| Pose::facing_wall(&SENSOR_LAYOUT[s], 800.0, 400.0, gap);
    let medians = medians_of(&std::fs::read_to_string(&csv).unwrap());
    let mut differs = 0;
    for s in 0..SENSORS {
        let rows: Vec<(f64, f64)> = medians
            .iter()
            .filter(|((t, _), _)| *t == s)
            .map(|(&(_, d), &m)| (f64::from(d), m))
            .collect();
        assert!(rows.len() >= 2, "sensor {s}: {rows:?}");
        for &(d, median) in &rows {
            for gap in [d - 0.25, d - 0.01] {
                let pose = facing_wall(s, gap);
                let got = arena.read_sensors(&pose)[s];
                assert_eq!(got, median, "sensor {s}, wall {gap} mm away");
                differs += usize::from(built_in.read_sensors(&pose)[s] != got);
            }
        }
        // Beyond the farthest measured distance the sensor reads nothing.
        let far = rows.last().unwrap().0;
        assert_eq!(arena.read_sensors(&facing_wall(s, far + 0.25))[s], 0.0);
    }
    // The bench table is not the built-in Khepera one: most of these readings differ from it.
    assert!(differs > SENSORS * 5, "{differs}");
}
