//! Messages of bad input: each names the option or field really at fault, states its real
//! range, and shows numbers compactly; all exit with status 2.

use crate::common;

use std::path::Path;

use common::{Fm, repo, stderr};

/// `fuzzymotiv run` of the high-curiosity config with `sets`, expected to be refused with
/// status 2 before anything is written; returns its message.
fn refused_run(sets: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/high-curiosity.toml");
    let o = Fm::new(["run".as_ref(), cfg.as_os_str()])
        .out(&dir.path().join("out"))
        .sets(sets)
        .run();
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{sets:?}: {msg}");
    assert!(!dir.path().join("out").exists(), "{sets:?} wrote output");
    msg
}

#[test]
fn a_nan_motivation_is_blamed_on_its_own_field() {
    for name in ["curiosity", "homing", "orientation", "energy"] {
        let msg = refused_run(&[&format!("motivations.{name}=nan")]);
        assert!(
            msg.contains(&format!("field `motivations.{name}`")) && msg.contains("NaN"),
            "{name}: {msg}"
        );
        let (source, rest) = msg.split_once(": field ").unwrap();
        assert_eq!(
            source,
            format!("error: --set motivations.{name}=nan"),
            "{msg}"
        );
        assert_eq!(rest.matches("motivations.").count(), 1, "{name}: {msg}");
    }
}

/// Issue #52 item 7: a bad value given by `--set` is named as that `--set`, not as the file,
/// whether reading (a string for a number) or checking (a population of 1) refuses it; a
/// value of the file is still the file's.
#[test]
fn a_bad_set_value_is_blamed_on_the_set_not_the_file() {
    for set in ["ga.population=x", "ga.population=1", "ga={population=1}"] {
        let msg = refused_run(&[set]);
        assert!(
            msg.starts_with(&format!("error: --set {set}: field `ga.population`: ")),
            "{set}: {msg}"
        );
    }
    let msg = refused_run(&["ga.generations=2", "motivations.homing=0.3"]);
    assert!(
        msg.starts_with("error: ")
            && msg.contains("high-curiosity.toml")
            && msg.contains("sum to 1"),
        "{msg}"
    );
}

/// A `--set` of a whole table is not blamed for a value of the file it does not hold
/// (`population = 1` in the file, `--set ga={generations=5}`), nor a `--set` of a motivation's
/// weight for the term the file gives it: both are named as the file with that `--set`.
#[test]
fn a_set_is_not_blamed_for_a_value_of_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let refused = |text: &str, set: &str| {
        let cfg = dir.path().join("c.toml");
        std::fs::write(&cfg, text).unwrap();
        let o = Fm::new(["run".as_ref(), cfg.as_os_str()])
            .out(&dir.path().join("out"))
            .sets(&[set])
            .run();
        assert_eq!(o.status.code(), Some(2), "{set}: {}", stderr(&o));
        assert!(!dir.path().join("out").exists(), "{set} wrote output");
        stderr(&o)
    };
    let msg = refused("[ga]\npopulation = 1\n", "ga={generations=5}");
    assert!(
        msg.contains("c.toml with --set ga={generations=5}: field `ga.population`"),
        "{msg}"
    );
    let text = "[motivations]\nx = { weight = 0.5, term = \"nope\" }\ncuriosity = 0.5\n";
    let msg = refused(text, "motivations.x.weight=0.5");
    assert!(
        msg.contains("c.toml with --set motivations.x.weight=0.5: field `motivations.x"),
        "{msg}"
    );
}

/// Motivations that no longer sum to 1 after a `--set` are named as the file with that
/// `--set` (the sum comes from both), not as the file alone; a `--set` elsewhere is not named.
#[test]
fn a_motivation_sum_off_after_a_set_names_the_file_with_that_set() {
    let msg = refused_run(&["ga.generations=2", "motivations.homing=0.3"]);
    let says = "high-curiosity.toml with --set motivations.homing=0.3: field `motivations`: \
                motivations must sum to 1";
    assert!(msg.starts_with("error: ") && msg.contains(says), "{msg}");
    assert!(!msg.contains("ga.generations"), "{msg}");
}

/// Issue #52 item 7: every config or room-file message names the whole path of its field:
/// a table's missing key (`motivations.x.weight`, `waypoints[1].y`), coefficients in plain
/// words (not serde's "untagged enum"), an empty motivation name, a motivation spelled with a
/// capital (a name, not a sum error).
#[test]
fn config_and_room_messages_name_the_whole_field_path() {
    let dir = tempfile::tempdir().unwrap();
    let check = |text: &str, field: &str, says: &str| {
        let cfg = dir.path().join("c.toml");
        std::fs::write(&cfg, text).unwrap();
        let o = Fm::new(["run".as_ref(), cfg.as_os_str()])
            .out(&dir.path().join("out"))
            .run();
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{text}: {msg}");
        assert!(
            msg.contains(&format!("c.toml: field `{field}`: ")) && msg.contains(says),
            "{text}: {msg}"
        );
        assert!(
            !msg.contains("untagged") && !msg.contains("panicked"),
            "{msg}"
        );
    };
    check(
        "[motivations]\nx = { term = \"a\" }\n",
        "motivations.x.weight",
        "missing field",
    );
    check(
        "[motivations.x]\nterm = \"a\"\n",
        "motivations.x.weight",
        "missing field",
    );
    check(
        "[fuzzy]\ncoefficients = \"lin\"\n",
        "fuzzy.coefficients",
        "\"linear\", \"ratio\" or a list",
    );
    check("[motivations]\n\"\" = 1.0\n", "motivations", "empty name");
    check(
        "[motivations]\nCuriosity = 0.8\nhoming = 0.1\norientation = 0.0\nenergy = 0.1\n",
        "motivations.Curiosity",
        "did you mean `curiosity`?",
    );
    let room = dir.path().join("r.toml");
    let outline = "name = \"r\"\noutline = [[0,0],[800,0],[800,800],[0,800]]\n";
    let waypoints =
        "[[waypoints]]\nx = 300\ny = 300\nradius = 40\n[[waypoints]]\nx = 500\nradius = 40\n";
    for (text, field) in [
        (
            format!("{outline}home = {{ x = 40, y = 40, heading_deg = 0 }}\n{waypoints}"),
            "waypoints[1].y",
        ),
        (
            format!("{outline}home = {{ x = 40, heading_deg = 0 }}\n"),
            "home.y",
        ),
    ] {
        std::fs::write(&room, text).unwrap();
        let o = Fm::new(["rooms".as_ref(), "--check".as_ref(), room.as_os_str()]).run();
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{msg}");
        assert!(
            msg.contains(&format!("r.toml: field `{field}`: missing field")),
            "{msg}"
        );
    }
}

/// A weight out of [0, 1] or NaN is blamed on `motivations.x.weight` when written in a table
/// (`[motivations.x] weight = -1`, `x = { weight = -1 }`) and on `motivations.x` when written
/// as `x = -1`.
#[test]
fn a_bad_motivation_weight_names_the_weight_key_of_a_table() {
    let dir = tempfile::tempdir().unwrap();
    for value in ["-1", "nan"] {
        for (text, field) in [
            (
                format!("[motivations.x]\nweight = {value}\n"),
                "motivations.x.weight",
            ),
            (
                format!("[motivations]\nx = {{ weight = {value} }}\n"),
                "motivations.x.weight",
            ),
            (format!("[motivations]\nx = {value}\n"), "motivations.x"),
        ] {
            let cfg = dir.path().join("c.toml");
            std::fs::write(&cfg, &text).unwrap();
            let o = Fm::new(["run".as_ref(), cfg.as_os_str()])
                .out(&dir.path().join("out"))
                .run();
            let msg = stderr(&o);
            assert_eq!(o.status.code(), Some(2), "{text}: {msg}");
            assert!(
                msg.contains(&format!(
                    "c.toml: field `{field}`: x must be a number in [0, 1]"
                )),
                "{text}: {msg}"
            );
        }
    }
}

/// A room file's bad value or unknown key inside an inline table is named down to its key
/// (`goal.y`, `home_zone.y`, `waypoints[0].colour`, `waypoints[1].y`), and a string for a
/// number says "expected a number", not serde's "expected f64".
#[test]
fn room_messages_name_the_key_inside_an_inline_table_and_say_a_number() {
    let dir = tempfile::tempdir().unwrap();
    let room = dir.path().join("r.toml");
    let head = "name = \"r\"\noutline = [[0,0],[800,0],[800,800],[0,800]]\n\
                home = { x = 40, y = 40, heading_deg = 0 }\n";
    for (text, field, says) in [
        (
            "goal = { x = 100, y = \"q\", radius = 30 }",
            "goal.y",
            "expected a number",
        ),
        (
            "home_zone = { x = 100, y = \"q\", radius = 30 }",
            "home_zone.y",
            "expected a number",
        ),
        (
            "waypoints = [{ x = 100, y = 100, radius = 30, colour = 1 }]",
            "waypoints[0].colour",
            "unknown field `colour`",
        ),
        (
            "waypoints = [{ x = 100, y = 100, radius = 30 }, { x = 1, y = \"q\", radius = 30 }]",
            "waypoints[1].y",
            "expected a number",
        ),
    ] {
        std::fs::write(&room, format!("{head}{text}\n")).unwrap();
        let o = Fm::new(["rooms".as_ref(), "--check".as_ref(), room.as_os_str()]).run();
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{text}: {msg}");
        assert!(
            msg.contains(&format!("r.toml: field `{field}`: ")) && msg.contains(says),
            "{text}: {msg}"
        );
        assert!(!msg.contains("f64") && !msg.contains("panicked"), "{msg}");
    }
}

/// Every command that takes `--threads` refuses a number outside 1..=256 (and a negative one,
/// which clap would otherwise take for an option) with status 2 and a message naming
/// `--threads`, the range and the value, before starting anything.
#[test]
fn threads_outside_1_to_256_are_refused_naming_the_option_and_range() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let sweep = repo().join("configs/sweep-small.toml");
    let out = dir.path().join("out");
    let (cfg, sweep, out) = (
        cfg.to_str().unwrap(),
        sweep.to_str().unwrap(),
        out.to_str().unwrap(),
    );
    let commands: [&[&str]; 5] = [
        &["run", cfg, "--out", out],
        &["reproduce", "--quick", "--out", out],
        &["bench", "--steps", "10"],
        &["sweep", sweep, "--out", out],
        &["lab", "--port", "0", "--dir", out],
    ];
    for command in commands {
        for threads in ["0", "-1", "257", "100000"] {
            let o = Fm::new(command).arg("--threads").arg(threads).run();
            let msg = stderr(&o);
            assert_eq!(
                o.status.code(),
                Some(2),
                "{command:?} --threads {threads}: {msg}"
            );
            for part in ["--threads", "from 1 to 256", &format!("got {threads}")] {
                assert!(msg.contains(part), "{command:?} --threads {threads}: {msg}");
            }
            assert!(
                !Path::new(out).exists(),
                "{command:?} --threads {threads} wrote {out}"
            );
        }
    }
}

/// Numeric options take a leading hyphen as the start of their value, so their own check
/// answers a negative number (not clap's "unexpected argument '-5'").
#[test]
fn negative_numbers_reach_the_options_own_check() {
    let o = Fm::new([
        "fuzzy",
        "--motivations",
        "-0.2,0.9,0.2,0.1",
        "--fitness",
        "1,1,1,1",
    ])
    .run();
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("--motivations") && msg.contains("curiosity") && msg.contains("-0.2"),
        "{msg}"
    );
    // A fitness value is a term in [0, 1]: -5 reaches that check and is refused, naming a.
    let o = Fm::new([
        "fuzzy",
        "--motivations",
        "0.8,0.1,0,0.1",
        "--fitness",
        "-5,0,0,0",
    ])
    .run();
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("--fitness") && msg.contains("`a` is -5") && msg.contains("[0, 1]"),
        "{msg}"
    );
    for (command, option) in [
        (&["claims", "study", "--alpha", "-0.5"][..], "--alpha"),
        (&["lab", "--port", "-1"][..], "--port"),
        (&["bench", "--steps", "-1"][..], "--steps"),
        (&["reproduce", "--seeds", "-1"][..], "--seeds"),
        (
            &["sweep", "s.toml", "--out", "o", "--index", "-1"][..],
            "--index",
        ),
        (
            &[
                "run",
                "--continue",
                "r",
                "--generations",
                "-1",
                "--out",
                "o",
            ][..],
            "--generations",
        ),
    ] {
        let value = command[command.iter().position(|a| *a == option).unwrap() + 1];
        let o = Fm::new(command).run();
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{command:?}: {msg}");
        assert!(
            msg.contains(option) && msg.contains(value) && !msg.contains("unexpected argument"),
            "{command:?}: {msg}"
        );
        assert!(!msg.contains("invalid digit"), "{command:?}: {msg}");
    }
}

/// A huge or tiny number is shown compactly (`1e300`), not as hundreds of digits.
#[test]
fn numbers_in_messages_are_shown_compactly() {
    for (set, field) in [
        ("ga.parent_fraction=1e300", "ga.parent_fraction"),
        ("motivations.homing=1e300", "motivations.homing"),
        ("trial.dt=-1e-300", "trial.dt"),
    ] {
        let msg = refused_run(&[set]);
        let value = set.split_once('=').unwrap().1;
        assert!(
            msg.contains(field) && msg.contains(&format!("got {value}")),
            "{set}: {msg}"
        );
        assert!(!msg.contains("0000000000"), "{set}: {msg}");
    }
    let o = Fm::new(["claims", "study", "--alpha", "1e300"]).run();
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("--alpha") && msg.contains("got 1e300"),
        "{msg}"
    );
}

/// A value of the wrong type for a whole-number field (`1.5`, `-1`) is answered with the
/// field's own range, not "a whole number ≥ 0".
#[test]
fn type_errors_state_the_fields_real_range() {
    for (set, range) in [
        ("ga.population=1.5", "a whole number from 2 to 1000000"),
        ("ga.population=-1", "a whole number from 2 to 1000000"),
        ("ga.generations=2.5", "a whole number from 1 to 1000000"),
        ("trial.steps=-5", "a whole number from 1 to 10000000"),
        ("aem.test_runs=0.5", "a whole number from 1 to 100000"),
        ("network.hidden=\"six\"", "a whole number from 1 to 1024"),
        ("ga.elite=-1", "a whole number from 0 to ga.population − 1"),
        ("aem.threshold=-1", "a whole number ≥ 0"),
    ] {
        let msg = refused_run(&[set]);
        let field = set.split_once('=').unwrap().0;
        assert!(
            msg.contains(&format!("field `{field}`")) && msg.contains(range),
            "{set}: {msg}"
        );
    }
}

/// `fuzzy` with motivations X and fitness values Y: its exit code and stderr.
fn fuzzy(x: &str, y: &str) -> (Option<i32>, String) {
    let o = Fm::new(["fuzzy", "--motivations", x, "--fitness", y]).run();
    let msg = stderr(&o);
    assert!(!msg.contains("panicked"), "{msg}");
    (o.status.code(), msg)
}

/// `fuzzy --motivations Curiosity=1` gets the hint a config's `Curiosity = 1` gets: names are
/// case-sensitive, did you mean `curiosity`?
#[test]
fn fuzzy_motivation_spelled_with_a_capital_gets_the_configs_case_hint() {
    let (code, msg) = fuzzy("Curiosity=1", "a=1");
    assert_eq!(code, Some(2), "{msg}");
    assert!(
        msg.contains("`Curiosity`")
            && msg.contains("Names are case-sensitive: did you mean `curiosity`?"),
        "{msg}"
    );
    let (code, msg) = fuzzy("hurry=1", "hurry=1");
    assert_eq!(code, Some(2), "{msg}");
    assert!(!msg.contains("did you mean"), "{msg}");
}

/// A fitness term outside [0, 1] or not a number, in either form, exits 2 naming the term and
/// the range; the bounds themselves are fine.
#[test]
fn fuzzy_refuses_fitness_terms_outside_0_1_naming_the_term() {
    let paper = "0.8,0.1,0,0.1";
    let five = "curiosity=0.5,homing=0.1,orientation=0,energy=0.1,urgency=0.3";
    for (x, y, term) in [
        (paper, "0.5,1.5,0,0", "`g` is 1.5"),
        (paper, "0.5,0.5,0,-0.01", "`b` is -0.01"),
        (paper, "a=0.5,g=0.5,l=2,b=0", "`l` is 2"),
        (
            five,
            "a=0.5,g=0.5,l=0,b=0,urgency=1.25",
            "`urgency` is 1.25",
        ),
    ] {
        let (code, msg) = fuzzy(x, y);
        assert_eq!(code, Some(2), "{y}: {msg}");
        assert!(
            msg.contains("--fitness") && msg.contains(term) && msg.contains("outside [0, 1]"),
            "{y}: {msg}"
        );
    }
    for (x, y, named) in [
        (paper, "0.5,nan,0,0", "`nan` (g)"),
        (five, "a=0.5,g=0.5,l=0,b=0,urgency=NaN", "`urgency=NaN`"),
    ] {
        let (code, msg) = fuzzy(x, y);
        assert_eq!(code, Some(2), "{y}: {msg}");
        assert!(
            msg.contains(named) && msg.contains("not a finite number"),
            "{msg}"
        );
    }
    assert_eq!(fuzzy(paper, "0,1,0,1").0, Some(0));
    assert_eq!(fuzzy(five, "a=1,g=0,l=0,b=1,urgency=0").0, Some(0));
}

/// The named form's own errors: a motivation whose name is no term, a fitness value for no
/// input, an input without a value, the positional form for other motivations than the
/// paper's four, and named weights not summing to 1; each exits 2 naming the culprit.
#[test]
fn fuzzy_named_form_errors_name_the_motivation_or_term() {
    let (code, msg) = fuzzy("curiosity=0.5,foo=0.5", "a=0.5,foo=0.5");
    assert_eq!(code, Some(2), "{msg}");
    assert!(
        msg.contains("--motivations") && msg.contains("`foo`") && msg.contains("does not exist"),
        "{msg}"
    );
    assert!(msg.contains("urgency"), "the known terms are listed: {msg}");
    let (code, msg) = fuzzy("curiosity=0.5,urgency=0.5", "a=0.5,urgency=0.5,goal=0.2");
    assert_eq!(code, Some(2), "{msg}");
    assert!(
        msg.contains("--fitness") && msg.contains("`goal` is not an input"),
        "{msg}"
    );
    let (code, msg) = fuzzy("curiosity=0.5,urgency=0.5", "a=0.5");
    assert_eq!(code, Some(2), "{msg}");
    assert!(msg.contains("no value for `urgency`"), "{msg}");
    let (code, msg) = fuzzy("curiosity=0.5,urgency=0.5", "0.5,0.5");
    assert_eq!(code, Some(2), "{msg}");
    assert!(msg.contains("--fitness a=0.5,urgency=0.5"), "{msg}");
    let (code, msg) = fuzzy("curiosity=0.5,urgency=0.3", "a=0.5,urgency=0.5");
    assert_eq!(code, Some(2), "{msg}");
    assert!(
        msg.contains("--motivations") && msg.contains("sum to 1"),
        "{msg}"
    );
    let (code, msg) = fuzzy("curiosity=0.5,urgency=0.5", "a=0.5,urgency=0.5");
    assert_eq!(code, Some(0), "{msg}");
}

/// Issue #52 item 7: a record file holding an array where its object belongs says so, not
/// serde's "expected struct BestGenome with 11 elements" or an element's type; a wrong value
/// names its field in plain words ("expected a number", not "f64").
#[test]
fn a_genome_file_holding_an_array_says_an_object_was_expected() {
    let dir = tempfile::tempdir().unwrap();
    let genome = dir.path().join("best_genome.json");
    let out = dir.path().join("c.json");
    for (text, says) in [
        (
            "[]",
            "expected a JSON object { \"key\": value, … } (a BestGenome record), got an array",
        ),
        (
            "[1, 2]",
            "expected a JSON object { \"key\": value, … } (a BestGenome record), got an array",
        ),
        (
            "{\"shape\": {\"hidden\": 6}, \"weights\": [1, \"a\"]}",
            "field `weights[1]`: invalid type: string \"a\", expected a number",
        ),
    ] {
        std::fs::write(&genome, text).unwrap();
        let o = Fm::new([
            "export".as_ref(),
            genome.as_os_str(),
            "--to".as_ref(),
            "json".as_ref(),
        ])
        .out(&out)
        .run();
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{text}: {msg}");
        assert!(msg.contains(says), "{text}: {msg}");
        assert!(
            !msg.contains("elements") && !msg.contains("f64"),
            "{text}: {msg}"
        );
        assert!(!out.exists());
    }
}
