//! `fuzzymotiv calibrate` and `trial.sensor_table` from the command line.

mod common;

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
