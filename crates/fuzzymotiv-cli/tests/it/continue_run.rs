//! `fuzzymotiv run --continue DIR --generations N --out NEW`: a finished run continued to N
//! generations equals a fresh N-generation run in its results, and DIR is left as it was.

use crate::common;

use std::path::Path;

use common::{Fm, assert_same_files, repo, stderr, summary_without_time, tree};

/// A small run of `configs/tiny.toml` (with `extra` settings) of `generations` into `out`.
fn tiny_run(out: &Path, generations: usize, extra: &[&str]) {
    let g = format!("ga.generations={generations}");
    let mut sets = vec![
        "ga.population=8",
        "trial.steps=80",
        "aem.epochs=10",
        "aem.test_runs=2",
        &g,
    ];
    sets.extend_from_slice(extra);
    Fm::new(["run"])
        .arg(repo().join("configs/tiny.toml"))
        .out(out)
        .sets(&sets)
        .arg("--quiet")
        .ok();
}

/// `summary.json` without its wall time (the one field that may differ).
/// Continues a 2-generation run to 4 and compares with a fresh 4-generation run.
fn continued_equals_fresh(extra: &[&str]) {
    let tmp = tempfile::tempdir().unwrap();
    let (fresh, short, long) = (
        tmp.path().join("fresh"),
        tmp.path().join("short"),
        tmp.path().join("long"),
    );
    tiny_run(&fresh, 4, extra);
    tiny_run(&short, 2, extra);
    let before = tree(&short);
    let o = Fm::new(["run", "--continue"])
        .arg(&short)
        .arg("--generations")
        .arg("4")
        .out(&long)
        .arg("--quiet")
        .ok();
    assert_eq!(tree(&short), before, "--continue changed DIR");
    assert!(!tmp.path().join("long.partial").exists());
    let files = [
        "generations.csv",
        "best_genome.json",
        "recognition.csv",
        "table.md",
        "config.resolved.toml",
    ];
    assert_same_files(&fresh, &long, &files, "from a fresh run");
    assert_eq!(summary_without_time(&fresh), summary_without_time(&long));
    let rows = std::fs::read_to_string(long.join("generations.csv")).unwrap();
    assert_ne!(
        rows,
        std::fs::read_to_string(short.join("generations.csv")).unwrap()
    );
    // The same command again: the continued run is there, finished.
    let again = Fm::new(["run", "--continue"])
        .arg(&short)
        .arg("--generations")
        .arg("4")
        .out(&long)
        .ok();
    assert!(stderr(&again).contains("nothing to do"), "{}", stderr(&o));
}

#[test]
fn a_continued_run_equals_a_fresh_longer_run() {
    continued_equals_fresh(&[]);
}

#[test]
fn a_continued_per_room_run_equals_a_fresh_longer_run() {
    continued_equals_fresh(&["training=\"per-room\"", "rooms=[\"H\",\"square\"]"]);
}

/// What cannot be continued is a clear error (exit 2) and nothing is written.
#[test]
fn what_cannot_be_continued_is_a_clear_error() {
    let tmp = tempfile::tempdir().unwrap();
    let done = tmp.path().join("done");
    tiny_run(&done, 2, &[]);
    let before = tree(&done);
    let cont = |dir: &Path, n: &str, out: &Path| {
        Fm::new(["run", "--continue"])
            .arg(dir)
            .arg("--generations")
            .arg(n)
            .out(out)
            .run()
    };
    let new = tmp.path().join("new");
    let expect = |o: std::process::Output, words: &str| {
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(
            stderr(&o).contains(words),
            "{words:?} not in: {}",
            stderr(&o)
        );
        assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
    };
    expect(cont(&done, "2", &new), "expected a total greater than 2");
    expect(
        cont(&done, "99999999999", &new),
        "--generations 99999999999: must be an integer in 1..=1000000",
    );
    expect(cont(&done, "4", &done), "choose a new --out");
    expect(cont(&done, "4", &done.join("inside")), "choose a new --out");
    expect(
        cont(&tmp.path().join("none"), "4", &new),
        "no such directory",
    );
    // An older run directory: no population.json.
    let older = tmp.path().join("older");
    std::fs::create_dir(&older).unwrap();
    for (f, bytes) in &before {
        if f != Path::new("population.json") && f.parent() == Some(Path::new("")) {
            std::fs::write(older.join(f), bytes).unwrap();
        }
    }
    expect(cont(&older, "4", &new), "no population.json");
    // An unfinished one (only its staging directory).
    let unfinished = tmp.path().join("unfinished");
    std::fs::create_dir(tmp.path().join("unfinished.partial")).unwrap();
    std::fs::write(
        tmp.path().join("unfinished.partial/config.resolved.toml"),
        &before[Path::new("config.resolved.toml")],
    )
    .unwrap();
    expect(cont(&unfinished, "4", &new), "run --resume");
    // A config edited after the run: the run is only read, so no --force advice.
    let edited = tmp.path().join("edited");
    std::fs::create_dir(&edited).unwrap();
    for (f, bytes) in &before {
        if f.parent() == Some(Path::new("")) {
            std::fs::write(edited.join(f), bytes).unwrap();
        }
    }
    let config = String::from_utf8(before[Path::new("config.resolved.toml")].clone()).unwrap();
    let population = config
        .lines()
        .find(|l| l.starts_with("population = "))
        .unwrap();
    let more = config.replace(population, "population = 13");
    std::fs::write(edited.join("config.resolved.toml"), more).unwrap();
    let o = cont(&edited, "4", &new);
    expect(o, "edited after it ran");
    // --generations without --continue, --continue without --out.
    let o = Fm::new(["run", "--generations", "4"]).run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    // Beside a config it would otherwise be ignored (the config's generations run).
    let o = Fm::new(["run"])
        .arg(done.join("config.resolved.toml"))
        .arg("--generations")
        .arg("4")
        .out(&new)
        .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--set ga.generations=N"),
        "{}",
        stderr(&o)
    );
    let o = Fm::new(["run", "--continue"])
        .arg(&done)
        .arg("--generations")
        .arg("4")
        .run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!new.exists() && !tmp.path().join("new.partial").exists());
    assert_eq!(tree(&done), before, "DIR was changed");
}

/// A room file is part of the run: `config.resolved.toml` records a digest of each, and a run
/// whose room file changed since is neither continued nor resumed (that would evolve the rest
/// of it in another room); with the file restored, both go on.
#[test]
fn a_changed_room_file_stops_continue_and_resume() {
    let tmp = tempfile::tempdir().unwrap();
    let room = tmp.path().join("U.toml");
    let original = std::fs::read_to_string(repo().join("rooms/U.toml")).unwrap();
    std::fs::write(&room, &original).unwrap();
    let rooms = format!("rooms=[\"H\", {:?}]", room.to_str().unwrap());
    let done = tmp.path().join("done");
    tiny_run(&done, 2, &[&rooms]);
    let config = std::fs::read_to_string(done.join("config.resolved.toml")).unwrap();
    assert!(config.contains("# Room file "), "{config}");
    let killed = tmp.path().join("killed");
    let o = Fm::new(["run"])
        .arg(repo().join("configs/tiny.toml"))
        .out(&killed)
        .sets(&[
            "ga.population=8",
            "trial.steps=80",
            "ga.generations=4",
            &rooms,
        ])
        .env("FUZZYMOTIV_TEST_ABORT_AFTER", "2")
        .run();
    assert!(!o.status.success());
    let moved = original.replace("[400,80],[500,80]", "[420,80],[520,80]");
    assert_ne!(moved, original);
    std::fs::write(&room, &moved).unwrap();
    let cont = || {
        Fm::new(["run", "--continue"])
            .arg(&done)
            .arg("--generations")
            .arg("3")
            .out(&tmp.path().join("more"))
            .arg("--quiet")
            .run()
    };
    let resume = || {
        Fm::new(["run", "--resume"])
            .arg(&killed)
            .arg("--quiet")
            .run()
    };
    for o in [cont(), resume()] {
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(
            stderr(&o).contains("a room file changed since the run"),
            "{}",
            stderr(&o)
        );
    }
    assert!(!tmp.path().join("more").exists() && !killed.exists());
    // A replay goes on, in the room as it is now, and says so.
    let o = Fm::new(["replay"])
        .arg(&done)
        .out(&tmp.path().join("replay/r.html"))
        .run();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("warning: ") && stderr(&o).contains("not the run's"));
    std::fs::write(&room, &original).unwrap();
    for o in [cont(), resume()] {
        assert!(o.status.success(), "{}", stderr(&o));
    }
}
