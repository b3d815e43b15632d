//! `reproduce --urgency`: the fetch mission under urgency weights 0, 0.1, 0.2 and 0.3 taken
//! from curiosity, paired seeds; success rate, time to the goal, exploration, battery and
//! homing per weight, and each step up in urgency compared.

use crate::common;

use std::path::{Path, PathBuf};

use common::{Fm, stderr, stdout};

/// Tiny sizes on two of the built-in fetch rooms.
const SIZES: [&str; 6] = [
    "ga.population=10",
    "ga.generations=3",
    "trial.steps=80",
    "aem.epochs=10",
    "aem.test_runs=2",
    "rooms=[\"fetch-H\", \"fetch-square\"]",
];

const WEIGHTS: [(&str, &str, &str); 4] = [
    ("urgency-0.0", "0.8", "0.0"),
    ("urgency-0.1", "0.7", "0.1"),
    ("urgency-0.2", "0.6", "0.2"),
    ("urgency-0.3", "0.5", "0.3"),
];

fn read(p: PathBuf) -> String {
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The tiny study's command line into `out`, one thread (the kill points fall in known runs).
fn study(out: &Path) -> Fm {
    Fm::new([
        "reproduce",
        "--urgency",
        "--seeds",
        "2",
        "--quiet",
        "--threads",
        "1",
    ])
    .out(out)
    .sets(&SIZES)
}

/// Every weight runs its seeds with its motivations, from any directory (the config and the
/// rooms are built in); the tables, the CSVs and the summary say the same; success rates
/// are percentages.
#[test]
fn urgency_runs_four_weights_on_the_fetch_rooms_and_its_outputs_agree() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("u");
    let o = study(&out).in_dir(tmp.path()).ok();
    let md = read(out.join("urgency.md"));
    assert_eq!(stdout(&o).trim_end(), md.trim_end());
    for (name, c, u) in WEIGHTS {
        for seed in ["seed-1", "seed-2"] {
            let config = read(out.join(name).join(seed).join("config.resolved.toml"));
            assert!(
                config.contains(&format!("curiosity = {c}\n"))
                    && config.contains(&format!("urgency = {u}\n"))
                    && config.contains("homing = 0.1\n")
                    && config.contains("energy = 0.1\n"),
                "{name}: {config}"
            );
            assert!(
                config.contains(r#"rooms = ["rooms/fetch-H.toml", "rooms/fetch-square.toml"]"#),
                "{config}"
            );
        }
        let tag = name.replace('-', "_");
        assert!(
            out.join(format!("trajectories_{tag}.svg")).is_file(),
            "{tag}"
        );
        assert!(
            md.contains(&format!("| {u} | ({c}, 0.1, 0, 0.1, {u}) |")),
            "{md}"
        );
    }
    let summary: serde_json::Value = serde_json::from_str(&read(out.join("summary.json"))).unwrap();
    assert_eq!(summary["weights"], serde_json::json!([0.0, 0.1, 0.2, 0.3]));
    let seeds = summary["per_seed"].as_array().unwrap();
    assert_eq!(seeds.len(), 4 * 2);
    for s in seeds {
        let success = s["success_pct"].as_f64().unwrap();
        assert!((0.0..=100.0).contains(&success), "{s}");
        assert_eq!(s["time_to_goal"].is_null(), success == 0.0, "{s}");
    }
    // The same seeds under every weight.
    let seed_of = |k: usize| seeds[k]["seed"].as_u64().unwrap();
    assert_eq!([seed_of(0), seed_of(1)], [seed_of(6), seed_of(7)]);
    let rows = summary["comparisons"].as_array().unwrap();
    assert!(rows.len() >= 4 * 4, "{rows:?}");
    let csv = read(out.join("urgency.csv"));
    assert_eq!(csv.lines().count(), 1 + rows.len());
    for r in rows {
        let line = format!(
            "| {} | {:.1} → {:.1} | {} |",
            r["measure"].as_str().unwrap(),
            r["from"].as_f64().unwrap(),
            r["to"].as_f64().unwrap(),
            r["pairs"]
        );
        assert!(md.contains(&line), "{line} not in {md}");
    }
    assert_eq!(read(out.join("urgency_seeds.csv")).lines().count(), 1 + 8);
    let svg = read(out.join("urgency.svg"));
    assert!(
        svg.contains("% success") && svg.contains("urgency u"),
        "{svg}"
    );
    assert!(out.join("fitness.svg").is_file());
    // The study's page: every row of its tables, its figures (the median seeds' trajectories
    // too) and each run's own report.
    let page = read(out.join("report.html"));
    assert!(page.contains("<h1>Urgency for missions"), "{page}");
    let table_rows = md
        .lines()
        .filter(|l| l.starts_with('|') && !l.starts_with("|---"));
    assert_eq!(page.matches("<tr>").count(), table_rows.count(), "{page}");
    assert!(page.contains("% success") && page.contains("urgency u"));
    assert_eq!(page.matches("the median seed").count(), 4, "{page}");
    assert!(
        page.contains(r#"<a href="urgency-0.3/seed-2/report.html">"#),
        "{page}"
    );
}

/// Killed at deterministic points (as kill -9 would), the same command resumes and ends with
/// the files of an uninterrupted study; run again, it has nothing to do.
#[test]
fn killed_urgency_study_resumes_to_the_files_of_an_uninterrupted_one() {
    use std::os::unix::process::ExitStatusExt;
    let tmp = tempfile::tempdir().unwrap();
    let reference = tmp.path().join("reference");
    study(&reference).ok();
    let out = tmp.path().join("killed");
    // 4 weights × 2 seeds × 3 generations, one run after another: the kills fall in the first
    // run, then in later ones (the finished runs read back).
    for n in [2, 7, 9] {
        let o = study(&out)
            .env("FUZZYMOTIV_TEST_ABORT_AFTER", &n.to_string())
            .run();
        assert_eq!(o.status.signal(), Some(6), "not aborted after {n}");
        assert!(!out.exists(), "a killed study is not in place");
    }
    let o = study(&out).ok();
    assert!(
        stderr(&o).contains("resuming the unfinished study"),
        "{}",
        stderr(&o)
    );
    let (got, want) = (common::results(&out), common::results(&reference));
    let names = |r: &[(PathBuf, Vec<u8>)]| r.iter().map(|(p, _)| p.clone()).collect::<Vec<_>>();
    assert_eq!(names(&got), names(&want));
    let differ: Vec<&PathBuf> = (got.iter().zip(&want))
        .filter(|(a, b)| a.1 != b.1)
        .map(|(a, _)| &a.0)
        .collect();
    assert!(differ.is_empty(), "these files differ: {differ:?}");
    let o = study(&out).ok();
    assert!(stderr(&o).contains("nothing to do"), "{}", stderr(&o));
}

/// Another study in --out is kept: the urgency study refuses it without --force and
/// replaces it with.
#[test]
fn urgency_refuses_another_study_in_out_without_force() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("u");
    study(&out).ok();
    let before = read(out.join("summary.json"));
    let other = Fm::new(["reproduce", "--seeds", "1", "--quiet"])
        .out(&out)
        .sets(&SIZES[..5]);
    let o = other.run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--force"), "{}", stderr(&o));
    assert_eq!(read(out.join("summary.json")), before);
    // And the other way round: the urgency study in the default study's place.
    let study_dir = tmp.path().join("s");
    Fm::new(["reproduce", "--seeds", "1", "--quiet"])
        .out(&study_dir)
        .sets(&SIZES[..5])
        .ok();
    let o = study(&study_dir).run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!study_dir.join("urgency.md").exists());
    study(&study_dir).arg("--force").ok();
    assert!(study_dir.join("urgency.md").is_file());
}

/// A --set of what the study varies (urgency's or curiosity's weight) is refused, and so is a
/// room the study does not have built in; nothing is written.
#[test]
fn urgency_refuses_to_have_its_weights_set_or_rooms_it_does_not_have() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("u");
    let o = study(&out).sets(&["motivations.urgency=0.5"]).run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("this study sets `motivations.urgency` itself"),
        "{}",
        stderr(&o)
    );
    let o = study(&out).sets(&["rooms=[\"H\"]"]).run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("`H` is not one of the rooms") && stderr(&o).contains("fetch-square"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
}

/// The urgency study is one of the studies: it conflicts with the others' flags.
#[test]
fn urgency_conflicts_with_the_other_studies() {
    let o = Fm::new(["reproduce", "--urgency", "--combination"]).run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("cannot be used with"), "{}", stderr(&o));
}
