//! A study's run directories and figures name seeds by their index (`seed-01`, "#03"), the seed
//! itself beside it; the records keep the seeds. A study written with directories named by the
//! seed (`seed-704825065232813`, earlier builds) is another study: refused, never mixed.

use std::path::Path;

use crate::common;

use common::{Fm, stderr, tree};

/// Tiny sizes: a ten-seed study in about a second.
const TINY: [&str; 5] = [
    "ga.population=4",
    "ga.generations=1",
    "trial.steps=50",
    "aem.epochs=5",
    "aem.test_runs=1",
];

/// `reproduce --quick --seeds N --seed BASE` into `out`.
fn study(out: &Path, seeds: &str, base: &str) -> Fm {
    Fm::new([
        "reproduce",
        "--quick",
        "--quiet",
        "--seeds",
        seeds,
        "--seed",
        base,
    ])
    .out(out)
    .sets(&TINY)
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&read(path)).unwrap()
}

#[test]
fn study_directories_are_named_by_seed_index() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("study");
    study(&out, "10", "1").ok();
    let summary = json(&out.join("summary.json"));
    let seeds: Vec<u64> = serde_json::from_value(summary["seeds"].clone()).unwrap();
    assert_eq!(seeds.len(), 10);
    assert_eq!(seeds[0], 1, "index 1 is the base seed");
    for (s, setting) in summary["settings"].as_array().unwrap().iter().enumerate() {
        let name = setting["name"].as_str().unwrap();
        let mut dirs: Vec<String> = std::fs::read_dir(out.join(name))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        dirs.sort();
        let want: Vec<String> = (1..=10).map(|k| format!("seed-{k:02}")).collect();
        assert_eq!(dirs, want, "{name}: zero-padded to the width of the count");
        // The records keep the seeds, each beside its directory.
        for (k, per_seed) in setting["per_seed"].as_array().unwrap().iter().enumerate() {
            assert_eq!(per_seed["seed"], seeds[k]);
            assert_eq!(per_seed["run_dir"], format!("{name}/seed-{:02}", k + 1));
            let config = read(&out.join(format!("{name}/seed-{:02}/config.resolved.toml", k + 1)));
            assert!(config.contains(&format!("seed = {}", seeds[k])), "{config}");
        }
        // The figures and the report name the median seed by its index, its seed beside it.
        let median = setting["median_seed"].as_u64().unwrap();
        let m = seeds.iter().position(|&s| s == median).unwrap() + 1;
        let label = format!("median seed: #{m:02} (seed {median}) of 10");
        let tag = name.replace('-', "_");
        let svg = read(&out.join(format!("trajectories_{tag}.svg")));
        assert!(svg.contains(&label), "{label} not in the figure");
        let html = read(&out.join("report.html"));
        assert!(html.contains(&label), "{label} not in the report");
        assert!(html.contains(&format!("\"{name}/seed-{m:02}/report.html\"")));
        // The per-seed table shows each index with its seed.
        let md = read(&out.join(format!("table{}.md", s + 1)));
        assert!(md.contains(&format!("| H | #03 ({}) |", seeds[2])), "{md}");
    }
    // The CSV records hold the seeds, not the directory names.
    let per_seed_csv = read(&out.join("table1_seeds.csv"));
    assert!(
        per_seed_csv.contains(&format!("\nH,{},", seeds[1])),
        "{per_seed_csv}"
    );
    assert!(!per_seed_csv.contains("seed-"), "{per_seed_csv}");
}

#[test]
fn a_study_of_fewer_than_ten_seeds_has_one_digit_indices() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("study");
    study(&out, "3", "7").ok();
    let summary = json(&out.join("summary.json"));
    assert_eq!(
        summary["settings"][1]["per_seed"][2]["run_dir"],
        "low-curiosity/seed-3"
    );
    assert!(out.join("low-curiosity/seed-3/report.html").is_file());
    assert!(!out.join("low-curiosity/seed-7").exists());
}

/// Turns a study written by this build into the layout of earlier builds: run directories
/// named by the seed, and its identity naming them so.
fn to_seed_named_layout(out: &Path) {
    let summary = json(&out.join("summary.json"));
    let seeds: Vec<u64> = serde_json::from_value(summary["seeds"].clone()).unwrap();
    let mut identity = read(&out.join("identity.json"));
    for setting in ["high-curiosity", "low-curiosity"] {
        for (k, seed) in seeds.iter().enumerate() {
            let (new, old) = (format!("seed-{}", k + 1), format!("seed-{seed}"));
            std::fs::rename(out.join(setting).join(&new), out.join(setting).join(&old)).unwrap();
            identity = identity.replace(&format!("{setting}/{new}/"), &format!("{setting}/{old}/"));
        }
    }
    std::fs::write(out.join("identity.json"), identity).unwrap();
}

/// The same command on `out`: refused with exit 2 (no panic), naming `what`, nothing changed.
fn assert_refused(cmd: Fm, kept: &Path, what: &str) {
    let before = tree(kept);
    let o = cmd.run();
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains(what) && !e.contains("panicked"), "{e}");
    assert_eq!(tree(kept), before, "the old study is kept as it was");
}

#[test]
fn a_study_with_seed_named_directories_is_refused_not_mixed() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("study");
    study(&out, "2", "5").ok();
    to_seed_named_layout(&out);
    assert_refused(
        study(&out, "2", "5"),
        &out,
        "holds the results of a different run",
    );

    // Written before identity.json existed: not recognised as this study either.
    std::fs::remove_file(out.join("identity.json")).unwrap();
    assert_refused(
        study(&out, "2", "5"),
        &out,
        "holds the results of a different run",
    );

    // Unfinished (a `.partial` staging directory): not resumed into the new layout.
    let out = dir.path().join("unfinished");
    study(&out, "2", "5").ok();
    to_seed_named_layout(&out);
    std::fs::remove_file(out.join("summary.json")).unwrap();
    let partial = dir.path().join("unfinished.partial");
    std::fs::rename(&out, &partial).unwrap();
    assert_refused(
        study(&out, "2", "5"),
        &partial,
        "holds an unfinished output of another run or command",
    );
    assert!(!out.exists());
}
