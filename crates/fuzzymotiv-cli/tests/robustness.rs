//! `fuzzymotiv robustness` from the command line.

mod common;

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
    let svg = std::fs::read_to_string(out.join("robustness.svg")).unwrap();
    for line in &lines[1..] {
        let label = line.split(',').next().unwrap();
        assert!(
            svg.contains(&format!(">{label}</text>")),
            "{label} not in the figure"
        );
    }
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
