//! `fuzzymotiv robustness` from the command line.

use crate::common;

use common::{ok, repo, run};

/// A run's best robot under every standard perturbation: one CSV row each, intervals around
/// the means, a figure naming every perturbation; the files are not replaced by a different study without --force.
#[test]
fn robustness_writes_one_row_and_one_figure_row_per_perturbation_and_keeps_earlier_results() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = dir.path().join("run");
    let config = repo().join("configs/tiny.toml");
    ok(&[
        "run",
        config.to_str().unwrap(),
        "--out",
        run_dir.to_str().unwrap(),
        "--quiet",
        "--set",
        "ga.population=6",
        "--set",
        "ga.generations=2",
        "--set",
        "trial.steps=60",
        "--set",
        "aem.epochs=5",
        "--set",
        "aem.test_runs=1",
    ]);
    let out = dir.path().join("rob");
    let args = [
        "robustness",
        run_dir.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--trials",
        "3",
    ];
    ok(&args);
    let csv = std::fs::read_to_string(out.join("robustness.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 1 + 24, "{csv}");
    assert!(lines[1].starts_with("none,9,"), "{csv}");
    for line in &lines[1..] {
        let v: Vec<f64> = line
            .split(',')
            .skip(2)
            .map(|x| x.parse().unwrap())
            .collect();
        for c in v.chunks(3) {
            assert!(c[1] <= c[0] && c[0] <= c[2], "{line}");
        }
    }
    // The run has one room model: each perturbation's trials are recognised by it too.
    assert!(
        lines[0].ends_with(",recognition,recognition_lo,recognition_hi"),
        "{csv}"
    );
    let svg = std::fs::read_to_string(out.join("robustness.svg")).unwrap();
    assert!(svg.contains(">recognised</text>"), "no recognition panel");
    for line in &lines[1..] {
        let label = line.split(',').next().unwrap();
        assert!(
            svg.contains(&format!(">{label}</text>")),
            "{label} not in the figure"
        );
    }
    // The table's notes say what the perturbations change for this robot (`actions` motion).
    let md = std::fs::read_to_string(out.join("robustness.md")).unwrap();
    let notes = md
        .split("\nNotes:\n")
        .nth(1)
        .expect("robustness.md has notes");
    for start in ["- noise=n sets trial.noise", "- wheels×k", "- radius=r"] {
        assert!(notes.contains(start), "{start}: {notes}");
    }
    assert!(notes.contains("`actions` motion"), "{notes}");
    assert!(!notes.contains("no table×k rows"), "{notes}");
    ok(&args); // the same study again: the same files, nothing to do
    let mut other = args.to_vec();
    other[5] = "4";
    let o = run(&other);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        std::fs::read_to_string(out.join("robustness.csv")).unwrap(),
        csv
    );
}

/// A small run's arguments: `config`, into `out`, on `threads` threads.
fn small_run(config: &std::path::Path, out: &std::path::Path, threads: &str) -> Vec<String> {
    let mut args: Vec<String> = ["run", config.to_str().unwrap(), "--out"]
        .map(String::from)
        .to_vec();
    args.push(out.to_str().unwrap().into());
    for a in ["--quiet", "--threads", threads] {
        args.push(a.into());
    }
    for s in [
        "ga.population=8",
        "ga.generations=3",
        "trial.steps=100",
        "aem.epochs=5",
        "aem.test_runs=1",
    ] {
        args.push("--set".into());
        args.push(s.into());
    }
    args
}

fn run_args(args: &[String]) -> std::process::Output {
    run(&args.iter().map(String::as_str).collect::<Vec<_>>())
}

/// `[trial.randomise]` draws each evaluation trial's robot: the evolution differs from the
/// plain one, does not depend on the number of threads, and the ranges are recorded.
#[test]
fn randomised_evolution_differs_from_plain_and_not_with_the_threads() {
    let dir = tempfile::tempdir().unwrap();
    let plain = dir.path().join("plain.toml");
    std::fs::write(&plain, "rooms = [\"square\", \"H\"]\n").unwrap();
    let randomised = dir.path().join("randomised.toml");
    std::fs::write(
        &randomised,
        "rooms = [\"square\", \"H\"]\n[trial.randomise]\nnoise = [0.0, 0.2]\nsensor_scale = [0.7, 1.3]\nwheel_bias = [-0.1, 0.1]\nradius = [27.5, 33.0]\n",
    )
    .unwrap();
    let read = |run: &str, file: &str| std::fs::read_to_string(dir.path().join(run).join(file));
    for (config, out, threads) in [
        (&plain, "plain", "1"),
        (&randomised, "one", "1"),
        (&randomised, "two", "2"),
    ] {
        let o = run_args(&small_run(config, &dir.path().join(out), threads));
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    for file in ["generations.csv", "best_genome.json"] {
        assert_eq!(
            read("one", file).unwrap(),
            read("two", file).unwrap(),
            "{file}"
        );
    }
    assert_ne!(
        read("plain", "generations.csv").unwrap(),
        read("one", "generations.csv").unwrap()
    );
    let resolved = read("one", "config.resolved.toml").unwrap();
    assert!(
        resolved.contains("[trial.randomise]\nnoise = [0.0, 0.2]\nsensor_scale = [0.7, 1.3]"),
        "{resolved}"
    );
    assert!(
        !read("plain", "config.resolved.toml")
            .unwrap()
            .contains("randomise")
    );
}

/// A range written high to low, a range out of bounds, an unknown key or a scale without a
/// sensor table exits 2 naming the file and the key, and writes nothing.
#[test]
fn bad_randomise_ranges_exit_2_naming_the_file_and_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("rand.toml");
    let out = dir.path().join("run");
    for (table, key, says) in [
        (
            "noise = [0.2, 0.1]",
            "trial.randomise.noise",
            "low end 0.2 is above the high end 0.1",
        ),
        (
            "wheel_bias = [-0.1, 0.9]",
            "trial.randomise.wheel_bias",
            "must lie within [-0.5, 0.5]",
        ),
        (
            "radius = [20, 30]",
            "trial.randomise.radius",
            "must be in [",
        ),
        (
            "noise = [0, 2]",
            "trial.randomise.noise",
            "must lie within [0, 0.5]",
        ),
        (
            "colour = [0, 1]",
            "trial.randomise.colour",
            "unknown field `colour`",
        ),
        (
            "sensor_scale = [0.7, 1.3]\n[trial]\nsensor_model = \"linear\"",
            "trial.randomise.sensor_scale",
            "\"sampled\" sensor model",
        ),
    ] {
        std::fs::write(&config, format!("[trial.randomise]\n{table}\n")).unwrap();
        let o = run_args(&small_run(&config, &out, "1"));
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{table}: {err}");
        assert!(
            err.contains("rand.toml") && err.contains(&format!("`{key}`")),
            "{err}"
        );
        assert!(err.contains(says), "{table}: {err}");
        assert!(!out.exists(), "{table}");
    }
}

/// Without room modelling there is no room model to recognise with: no recognition column.
#[test]
fn robustness_of_a_run_without_room_modelling_has_no_recognition() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = dir.path().join("run");
    let config = repo().join("configs/tiny.toml");
    let mut args = small_run(&config, &run_dir, "1");
    args.extend(["--set".into(), "aem.enabled=false".into()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    ok(&args);
    let out = dir.path().join("rob");
    ok(&[
        "robustness",
        run_dir.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--trials",
        "2",
    ]);
    let csv = std::fs::read_to_string(out.join("robustness.csv")).unwrap();
    assert!(
        csv.lines().next().unwrap().ends_with(",battery_hi"),
        "{csv}"
    );
    let md = std::fs::read_to_string(out.join("robustness.md")).unwrap();
    assert!(!md.contains("recognised"), "{md}");
}
