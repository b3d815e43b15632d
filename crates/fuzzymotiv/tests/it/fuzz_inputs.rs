//! Bad input, tried systematically: generated config and room documents (wrong types, missing
//! fields, NaN/inf, huge numbers, self-intersecting outlines, unknown keys, …) must end in a
//! typed error naming a field — never a panic.

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::experiment::RawConfig;
use fuzzymotiv::simulation::Room;
use proptest::prelude::*;

const KEYS: &[&str] = &[
    "name",
    "seed",
    "rooms",
    "training",
    "motivations.curiosity",
    "motivations.homing",
    "motivations.orientation",
    "motivations.energy",
    "ga.population",
    "ga.generations",
    "ga.elite",
    "ga.parent_fraction",
    "ga.crossover",
    "ga.mutation_rate",
    "ga.mutation_sigma",
    "ga.weight_limit",
    "ga.init_range",
    "trial.steps",
    "trial.dt",
    "trial.noise",
    "trial.sensor_model",
    "robot.v_max",
    "robot.radius",
    "robot.wheel_base",
    "network.hidden",
    "fuzzy.peaks",
    "fuzzy.coefficients",
    "fitness.energy",
    "fitness.orientation",
    "aem.enabled",
    "aem.encoder",
    "aem.som_nodes",
    "aem.epochs",
    "aem.threshold",
    "aem.test_runs",
    "aem.action_tolerance",
    "aem.sigma_start",
    "ga.populaton",
    "colour",
    "trial.stpes",
    "motivations.charisma",
];

const VALUES: &[&str] = &[
    "0",
    "1",
    "-1",
    "2",
    "200",
    "-4",
    "9223372036854775807",
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "0.0",
    "0.5",
    "1.5",
    "1e-300",
    "\"\"",
    "\"x\"",
    "\"H\"",
    "\"linear\"",
    "\"ratio\"",
    "\"online\"",
    "\"per-room\"",
    "\"sampled\"",
    "\"heading\"",
    "true",
    "false",
    "[]",
    "[\"H\"]",
    "[\"H\", \"H\"]",
    "[\"H\", \"T\"]",
    "[0, 0.5, 0.4]",
    "[0, 0.25, 0.5, 0.75, 1]",
    "[1, 2]",
    "[nan]",
    "{ a = 1 }",
    "[[1, 2], [3]]",
    "1979-05-27",
];

fn document(entries: &[(usize, usize)]) -> String {
    // Group dotted keys into tables so the document is mostly valid TOML.
    let mut top = String::new();
    let mut tables: Vec<(String, String)> = Vec::new();
    for &(k, v) in entries {
        let key = KEYS[k % KEYS.len()];
        let value = VALUES[v % VALUES.len()];
        match key.split_once('.') {
            None => top.push_str(&format!("{key} = {value}\n")),
            Some((t, k)) => match tables.iter_mut().find(|(n, _)| n == t) {
                Some((_, body)) => body.push_str(&format!("{k} = {value}\n")),
                None => tables.push((t.to_string(), format!("{k} = {value}\n"))),
            },
        }
    }
    for (t, body) in tables {
        top.push_str(&format!("[{t}]\n{body}"));
    }
    top
}

/// Parses and validates like the CLI (built-in rooms only); returns the error's field.
fn check(text: &str) -> Result<(), String> {
    let raw = RawConfig::parse(text, "fuzz.toml", &[]).map_err(|e| e.field)?;
    let rooms: Option<Vec<Room>> = raw.rooms.iter().map(|r| Room::builtin(r)).collect();
    let Some(rooms) = rooms else { return Ok(()) };
    Experiment::new(&raw, rooms, "fuzz.toml")
        .map(|_| ())
        .map_err(|e| e.field)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn generated_configs_never_panic(entries in prop::collection::vec((0usize..64, 0usize..64), 0..8)) {
        let text = document(&entries);
        // Duplicate keys are a TOML error; everything else must validate or name a field.
        if let Err(field) = check(&text) {
            prop_assert!(!field.is_empty(), "no field named for:\n{text}");
        }
    }

    #[test]
    fn generated_room_files_never_panic(
        points in prop::collection::vec((-2000.0f64..3000.0, -2000.0f64..3000.0), 0..9),
        special in 0usize..8,
        home in (-100.0f64..1100.0, -100.0f64..1100.0),
        obstacle in prop::option::of(prop::collection::vec((0.0f64..1000.0, 0.0f64..1000.0), 0..5)),
    ) {
        let fmt = |v: f64| match special {
            1 => "nan".to_string(),
            2 => "inf".to_string(),
            3 => "1e300".to_string(),
            _ => format!("{v:.1}"),
        };
        let outline: Vec<String> = points.iter().enumerate().map(|(i, (x, y))| {
            if i == 0 { format!("[{}, {}]", fmt(*x), y) } else { format!("[{x:.1}, {y:.1}]") }
        }).collect();
        let mut text = format!(
            "name = \"r\"\noutline = [{}]\nhome = {{ x = {:.1}, y = {:.1}, heading_deg = 0 }}\n",
            outline.join(", "), home.0, home.1
        );
        if special == 4 { text = text.replace("name = \"r\"\n", ""); }
        if special == 5 { text.push_str("colour = 1\n"); }
        if let Some(o) = obstacle {
            let pts: Vec<String> = o.iter().map(|(x, y)| format!("[{x:.1}, {y:.1}]")).collect();
            text.push_str(&format!("[[obstacles]]\noutline = [{}]\n", pts.join(", ")));
        }
        match Room::from_toml_str(&text, "fuzz-room.toml") {
            Ok(room) => {
                // A valid room must be usable by the simulator.
                let raw = fuzzymotiv::simulation::RawTrial { steps: 20, ..Default::default() };
                let params = fuzzymotiv::simulation::TrialParams::from_raw(&raw, &Default::default(), fuzzymotiv::simulation::RobotSpec::khepera(), 0.25).unwrap();
                let arena = fuzzymotiv::simulation::Arena::new(room, &params);
                prop_assert!(arena.reachable_cells() <= arena.cell_count());
            }
            Err(e) => prop_assert!(!e.field.is_empty() && !e.reason.is_empty()),
        }
    }
}

/// The corpus files of `tests/corpus/<kind>/`, each with the field its first line names
/// (`# field: ...`).
fn corpus(kind: &str) -> Vec<(std::path::PathBuf, String, String)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus")
        .join(kind);
    let mut cases: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| {
            let path = entry.unwrap().path();
            let text = std::fs::read_to_string(&path).unwrap();
            let expected = text
                .lines()
                .next()
                .and_then(|l| l.strip_prefix("# field: "))
                .unwrap_or_else(|| panic!("{path:?} lacks '# field: ' header"))
                .trim()
                .to_string();
            (path, text, expected)
        })
        .collect();
    cases.sort();
    cases
}

/// Regression corpus: every case names its field (kept as files in tests/corpus/).
#[test]
fn corpus_of_bad_configs_names_the_field() {
    let cases = corpus("configs");
    for (path, text, expected) in &cases {
        let got = check(text).expect_err(&format!("{path:?} should be rejected"));
        assert_eq!(&got, expected, "{path:?}");
    }
    assert!(cases.len() >= 20, "corpus too small: {}", cases.len());
}

#[test]
fn corpus_of_bad_rooms_names_the_field() {
    let cases = corpus("rooms");
    for (path, text, expected) in &cases {
        let got =
            Room::from_toml_str(text, "corpus").expect_err(&format!("{path:?} should be rejected"));
        assert_eq!(&got.field, expected, "{path:?}: {got}");
    }
    assert!(cases.len() >= 10, "corpus too small: {}", cases.len());
}
