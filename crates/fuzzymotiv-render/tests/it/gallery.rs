//! Every kind of SVG figure the render crate draws, from the committed records under
//! `docs/results/` where there are some and from made-up inputs otherwise: each opens with the
//! one font stack and closes, and no text of it leaves its viewBox. With
//! `FUZZYMOTIV_GALLERY=DIR` set the figures are also written to `DIR/<kind>.svg`, to render
//! to PNG (`rsvg-convert`) and look at before and after a change to the figures.

use std::path::PathBuf;

use fuzzymotiv::evolution::Stats;
use fuzzymotiv::experiment::GenerationRecord;
use fuzzymotiv::random::rng_from_seed;
use fuzzymotiv::simulation::{Arena, Controller, Room, Trajectory, TrialParams, run_trial};
use fuzzymotiv_records::records::Fixed;
use fuzzymotiv_records::records::StudySummary;
use fuzzymotiv_records::records::compare::CompareRow;
use fuzzymotiv_records::records::hypotheses::StudyRecord;
use fuzzymotiv_records::records::robustness::RobustnessRecord;
use fuzzymotiv_render::svg::{LoggedPath, SettingPoint, SomRoom};
use serde_json::Value;

/// The workspace's root.
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A committed record, read as JSON.
fn record(path: &str) -> Value {
    let text = std::fs::read_to_string(root().join(path)).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Field `key` of a committed record, read as the type the caller takes.
macro_rules! field {
    ($path:expr, $key:expr) => {
        serde_json::from_value::<Vec<_>>(record($path)[$key].clone()).unwrap()
    };
}

/// Straight on, left when a front sensor sees a wall, about when both do.
struct WallShy;

impl Controller for WallShy {
    fn step(&mut self, s: &[f64]) -> [f64; 2] {
        match (s[2].max(s[1]) > 0.3, s[3].max(s[4]) > 0.3) {
            (true, true) => [0.0, 0.0],
            (false, true) | (true, false) => [0.0, 1.0],
            _ => [1.0, 1.0],
        }
    }
}

/// A made-up evolution of `n` generations: F rising, the population minimum jumping.
fn history(n: usize, seed: usize) -> Vec<GenerationRecord> {
    (0..n)
        .map(|g| {
            let t = g as f64 / n.max(1) as f64;
            let best = 0.5 + 0.4 * t + 0.01 * seed as f64;
            let mean = 0.1 + 0.6 * t + 0.02 * ((g + seed) % 3) as f64;
            let mut r = GenerationRecord {
                generation: g,
                stats: Stats {
                    mean,
                    std: 0.1,
                    min: if g % 2 == 0 { 0.1 } else { mean - 0.05 },
                    max: best,
                },
                terms: Default::default(),
            };
            r.terms.a = 0.3 + 0.5 * t;
            r.terms.g = 0.6 * t * t;
            r.terms.b = 0.9 - 0.2 * t;
            r
        })
        .collect()
}

/// The rooms of the trajectory figure: two built-in rooms, the U room and a fetch room with
/// its goal, each with a wall-shy robot's 400-step trial.
fn trials() -> Vec<(Room, Trajectory)> {
    let from_file = |name: &str| {
        let path = root().join("rooms").join(name);
        Room::from_toml_str(&std::fs::read_to_string(&path).unwrap(), name).unwrap()
    };
    let rooms = [
        Room::builtin("H").unwrap(),
        Room::builtin("square").unwrap(),
        from_file("U.toml"),
        from_file("fetch-H.toml"),
    ];
    rooms
        .into_iter()
        .map(|room| {
            let arena = Arena::new(room.clone(), &TrialParams::default());
            let tr = run_trial(&arena, &mut WallShy, &mut rng_from_seed(3));
            (room, tr)
        })
        .collect()
}

/// A robustness record with F at `f` and its interval ± 0.05.
fn robustness(label: &str, f: f64) -> RobustnessRecord {
    let v = Fixed;
    RobustnessRecord {
        perturbation: label.into(),
        trials: 4,
        f: v(f),
        f_lo: v(f - 0.05),
        f_hi: v(f + 0.05),
        exploration: v(0.5),
        exploration_lo: v(0.4),
        exploration_hi: v(0.6),
        homing: v(0.2),
        homing_lo: v(0.1),
        homing_hi: v(0.3),
        battery: v(0.9),
        battery_lo: v(0.9),
        battery_hi: v(0.9),
        recognition: Some(v(0.75)),
        recognition_lo: Some(v(0.5)),
        recognition_hi: Some(v(1.0)),
        extra: Vec::new(),
    }
}

/// A comparison row of `compare_svg`.
fn compare_row(setting: &str, metric: &str, room: &str, d: f64, p: f64) -> CompareRow {
    CompareRow {
        setting: setting.into(),
        metric: metric.into(),
        room: room.into(),
        design: "paired".into(),
        n_a: 5,
        n_b: 5,
        mean_a: 50.0 + d,
        mean_b: 50.0,
        difference: d,
        ci_low: d - 6.0,
        ci_high: d + 6.0,
        p,
        exact: true,
        p_holm: p * 2.0,
        mdd: None,
    }
}

/// Sweep settings over the simplex (`n` of them).
fn sweep_points(n: usize) -> Vec<SettingPoint> {
    (0..n)
        .map(|k| {
            let c = k as f64 / n as f64;
            SettingPoint {
                label: format!("setting-{k}"),
                motivations: [c, 0.8 - 0.8 * c, 0.0, 0.2],
                values: [
                    Some(100.0 * c),
                    Some(50.0),
                    None,
                    Some(20.0 + 7.0 * k as f64),
                ],
                spread: [Some(3.0), Some(12.5), None, None],
                n: [15, 15, 0, 15],
            }
        })
        .collect()
}

/// The figures drawn from made-up inputs: their names and SVGs.
fn made_up_figures() -> Vec<(&'static str, String)> {
    use fuzzymotiv_render::{compare, robustness as rb, svg};
    let runs = vec![
        (
            "high-curiosity [0.8, 0.1, 0.0, 0.1]".to_string(),
            history(200, 0),
        ),
        (
            "low-curiosity [0.1, 0.1, 0.0, 0.8]".to_string(),
            history(30, 1),
        ),
    ];
    let trials = trials();
    let pairs: Vec<(&Room, &Trajectory)> = trials.iter().map(|(r, t)| (r, t)).collect();
    let logs = [LoggedPath {
        label: "robot.csv".into(),
        room: 0,
        points: (0..40)
            .map(|k| (300.0 + 8.0 * k as f64, 250.0 + 3.0 * k as f64))
            .collect(),
    }];
    let names: Vec<String> = (fuzzymotiv::fitness::PAPER_LABEL_NAMES.iter())
        .map(|s| s.to_string())
        .collect();
    let nodes = [15, 0, 8, 12];
    let som: Vec<SomRoom<'_>> = ["H", "square", "U", "fetch-H"]
        .iter()
        .enumerate()
        .map(|(k, name)| SomRoom {
            name,
            r_node: nodes[k],
            winners: vec![nodes[k], (k * 5) % 16, 15],
        })
        .collect();
    let compare_rows: Vec<CompareRow> = ["H", "L", "all rooms"]
        .iter()
        .enumerate()
        .flat_map(|(k, room)| {
            let d = 8.0 - 6.0 * k as f64;
            [
                compare_row("high-curiosity", "exploration_pct", room, d, 0.01),
                compare_row("high-curiosity", "homing_pct", room, -3.0, 0.4),
            ]
        })
        .collect();
    let perturbations = [
        robustness("none", 0.6),
        robustness("dead=3", 0.2),
        robustness("table×0.7", 0.62),
    ];
    let title = "A wall-shy robot in four rooms";
    let peaks = [0.0, 0.25, 0.5, 0.75, 1.0];
    vec![
        ("fitness", svg::fitness_svg(&runs)),
        ("terms", svg::terms_svg(&runs)),
        ("membership", svg::membership_svg(&peaks, &names)),
        (
            "trajectories",
            svg::trajectories_svg_with(title, &pairs, &logs),
        ),
        (
            "som",
            svg::som_svg("The rooms on the SOM line", 16, 3, &som),
        ),
        ("sweep-bars", svg::sweep_summary_svg(&sweep_points(4))),
        ("sweep-ternary", svg::sweep_summary_svg(&sweep_points(12))),
        (
            "compare",
            compare::compare_svg("A vs B", &compare_rows, 0.05),
        ),
        (
            "robustness",
            rb::robustness_svg("Robustness of the best robot", &perturbations),
        ),
    ]
}

/// The figures drawn from the committed records: their names and SVGs.
fn recorded_figures() -> Vec<(&'static str, String)> {
    use fuzzymotiv_render::{combination, forest, replication, strength, urgency};
    let mut studies: Vec<StudySummary> = Vec::new();
    for population in [30, 60, 100, 200] {
        let study = record("docs/results/five-seed/summary.json");
        let mut s: StudySummary = serde_json::from_value(study).unwrap();
        s.population = population;
        studies.push(s);
    }
    let replication_record = "docs/results/replication/summary.json";
    let base: Vec<u64> =
        serde_json::from_value(record(replication_record)["base_seeds"].clone()).unwrap();
    let forest_record: StudyRecord =
        serde_json::from_value(record("docs/results/combination-study/study.json")).unwrap();
    vec![
        ("forest", forest::forest_svg(&forest_record)),
        (
            "replication",
            replication::replication_svg(
                [base[0], base[1]],
                &field!(replication_record, "pooled"),
                &field!(replication_record, "by_seeds"),
            ),
        ),
        ("strength", strength::strength_svg(&studies)),
        (
            "behaviour",
            combination::behaviour_svg(&field!(
                "docs/results/combination/summary.json",
                "behaviour"
            )),
        ),
        (
            "urgency",
            urgency::urgency_svg(&field!("docs/results/urgency/summary.json", "per_seed")),
        ),
    ]
}

/// Every figure kind: its name and its SVG.
fn figures() -> Vec<(&'static str, String)> {
    let mut all = made_up_figures();
    all.extend(recorded_figures());
    all
}

/// An attribute's value in an element's start tag.
fn attr(head: &str, name: &str) -> Option<String> {
    let start = head.find(&format!(" {name}=\""))? + name.len() + 3;
    Some(head[start..].split('"').next()?.to_string())
}

/// Every text's anchor point (x, y) lies inside the figure's viewBox.
fn texts_inside(svg: &str) -> Result<(), String> {
    let root = svg.split('>').next().unwrap();
    let vb: Vec<f64> = attr(root, "viewBox")
        .ok_or("no viewBox")?
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    for el in svg.split("<text").skip(1) {
        let head = el.split('>').next().unwrap();
        let (x, y): (f64, f64) = (
            attr(head, "x").unwrap().parse().unwrap(),
            attr(head, "y").unwrap().parse().unwrap(),
        );
        if !(x >= vb[0] && x <= vb[0] + vb[2] && y >= vb[1] && y <= vb[1] + vb[3]) {
            return Err(format!("text at ({x}, {y}) outside {vb:?}: {el}"));
        }
    }
    Ok(())
}

#[test]
fn every_figure_kind_opens_closes_and_keeps_its_texts_inside() {
    let out = std::env::var_os("FUZZYMOTIV_GALLERY").map(PathBuf::from);
    if let Some(dir) = &out {
        std::fs::create_dir_all(dir).unwrap();
    }
    let font = format!("font-family=\"{}\"", fuzzymotiv_render::figure::FONT_STACK);
    for (name, svg) in figures() {
        assert!(svg.starts_with("<svg "), "{name}");
        assert!(svg.split('>').next().unwrap().contains(&font), "{name}");
        assert!(svg.ends_with("</svg>\n"), "{name}");
        assert_eq!(svg.matches("<svg").count(), 1, "{name}");
        assert_eq!(
            svg.matches("<text").count(),
            svg.matches("</text>").count(),
            "{name}"
        );
        texts_inside(&svg).unwrap_or_else(|e| panic!("{name}: {e}"));
        if let Some(dir) = &out {
            std::fs::write(dir.join(format!("{name}.svg")), &svg).unwrap();
        }
    }
}
