//! Where the worlds differ (issue 54 item 4): each robot's front sensor against the distance
//! to a wall, in fuzzymotiv and in Enki, in one figure.
//!
//! ```text
//! readings_vs_distance OUT_DIR     # OUT_DIR/readings.csv and OUT_DIR/readings.svg
//! ```
//!
//! Run from the repository root. For each robot the sensor straight ahead (the Khepera's IR2,
//! the e-puck2's IR0, the Thymio II's prox.horizontal[2]) faces a wall head-on at 0–150 mm
//! (along its axis, from the sensor):
//!
//! - **fuzzymotiv**: the engine's noise-free reading ([`Arena::read_sensors`]) with the robot
//!   placed so, in the square room (the Thymio II's: 3× the square, rooms/thymio2/); poses where the body would overlap the wall are left out.
//!   The Khepera twice: with its robot file's table (the paper's robot) and with
//!   `configs/sensors/khepera-enki.toml`, the table `fuzzymotiv calibrate` made from Enki's
//!   Khepera measured as on a bench (the calibration loop).
//! - **Enki**: the median of Enki's readings at each distance: the e-puck and the Thymio II from
//!   `bench/enki/probe_robots.csv` (incidence 0), the Khepera from
//!   `configs/sensors/khepera-enki-bench.csv` (`khepera_h --bench`: readings already on the
//!   network's 0–1023 scale as `fuzzymotiv transfer` maps them).
//!
//! Readings are on each robot's own scale (0 to its `reading_max`), as the network divides them.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::ExitCode;

use fuzzymotiv::simulation::Pose;
use fuzzymotiv::statistics::quantile;
use fuzzymotiv_pipeline::files::inputs::load_config;
use fuzzymotiv_pipeline::render::figure::{Ticks, colour, esc, open, px};

/// A probed robot: its name, the `--set`s of its config, its front sensor, the curve's label.
struct Probe {
    robot: &'static str,
    sets: &'static [&'static str],
    sensor: usize,
    label: &'static str,
}

const PROBES: [Probe; 4] = [
    Probe {
        robot: "khepera",
        sets: &["rooms=[\"square\"]", "aem.enabled=false"],
        sensor: 2,
        label: "fuzzymotiv (robot file)",
    },
    Probe {
        robot: "khepera",
        sets: &[
            "rooms=[\"square\"]",
            "aem.enabled=false",
            "trial.sensor_table=\"configs/sensors/khepera-enki.toml\"",
        ],
        sensor: 2,
        label: "fuzzymotiv (table calibrated in Enki)",
    },
    Probe {
        robot: "epuck2",
        sets: &[
            "robot=\"epuck2\"",
            "rooms=[\"square\"]",
            "aem.enabled=false",
        ],
        sensor: 0,
        label: "fuzzymotiv (robot file)",
    },
    Probe {
        robot: "thymio2",
        sets: &[
            "robot=\"thymio2\"",
            "rooms=[\"rooms/thymio2/square.toml\"]",
            "aem.enabled=false",
        ],
        sensor: 2,
        label: "fuzzymotiv (robot file)",
    },
];

/// The robots of the figure, its panels in order, with their titles.
const PANELS: [(&str, &str); 3] = [
    ("khepera", "Khepera (IR2)"),
    ("epuck2", "e-puck2 (IR0)"),
    ("thymio2", "Thymio II (prox.horizontal[2])"),
];

/// One curve: (robot, source label) → (distance mm, reading) in order of distance.
type Curves = BTreeMap<(String, String), Vec<(f64, f64)>>;

/// The engine's readings of `probe`'s front sensor facing the east wall of its config's first
/// room (the square room; the Thymio II's 3× square), half-way up it.
fn engine_curve(probe: &Probe) -> Result<(Vec<(f64, f64)>, f64), String> {
    let sets: Vec<String> = probe.sets.iter().map(|s| s.to_string()).collect();
    let loaded = load_config(None, &sets, None).map_err(|e| e.to_string())?;
    let params = loaded.experiment.trial_params();
    let arena = &loaded.experiment.arenas()[0];
    let (low, high) = arena.room().bounds();
    let (wall_x, mid_y) = (high.x, (low.y + high.y) / 2.0);
    let spec = params.robot().spec();
    let mount = spec.mounts()[probe.sensor];
    let mut curve = Vec::new();
    for d in 0..=150 {
        let d = f64::from(d);
        let pose = Pose::facing_wall(&mount, wall_x, mid_y, d);
        if arena.overlaps(pose.position()) {
            continue;
        }
        curve.push((d, arena.read_sensors(&pose)[probe.sensor]));
    }
    Ok((curve, spec.reading_max()))
}

/// Reads a CSV file into rows of (column → cell).
fn read_rows(path: &str) -> Result<Vec<BTreeMap<String, String>>, String> {
    let fail = |e: csv::Error| format!("{path}: {e}");
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(path)
        .map_err(fail)?;
    let header = reader.headers().map_err(fail)?.clone();
    reader
        .records()
        .map(|r| {
            let r = r.map_err(fail)?;
            Ok(header
                .iter()
                .map(String::from)
                .zip(r.iter().map(String::from))
                .collect())
        })
        .collect()
}

fn number(row: &BTreeMap<String, String>, column: &str, path: &str) -> Result<f64, String> {
    let text = row.get(column).map(String::as_str).unwrap_or("");
    text.parse()
        .map_err(|_| format!("{path}: column `{column}`: `{text}` is not a number"))
}

/// Enki's e-puck and Thymio II head-on medians from probe_robots.csv.
fn enki_probe(path: &str, curves: &mut Curves) -> Result<(), String> {
    for row in read_rows(path)? {
        if number(&row, "incidence_deg", path)? != 0.0 {
            continue;
        }
        let robot = row.get("robot").cloned().unwrap_or_default();
        let d = number(&row, "axis_mm", path)?;
        let median = number(&row, "median", path)?;
        if d <= 150.0 {
            curves
                .entry((robot, "Enki".into()))
                .or_default()
                .push((d, median));
        }
    }
    Ok(())
}

/// Enki's Khepera: the median of the bench file's readings per distance.
fn enki_bench(path: &str, curves: &mut Curves) -> Result<(), String> {
    let mut by_distance: BTreeMap<u64, (f64, Vec<f64>)> = BTreeMap::new();
    for row in read_rows(path)? {
        let d = number(&row, "distance_mm", path)?;
        let entry = by_distance.entry(d.to_bits()).or_insert((d, Vec::new()));
        entry.1.push(number(&row, "reading", path)?);
    }
    let mut curve: Vec<(f64, f64)> = by_distance
        .into_values()
        .map(|(d, mut v)| {
            v.sort_by(f64::total_cmp);
            (d, quantile(&v, 0.5))
        })
        .collect();
    curve.sort_by(|a, b| a.0.total_cmp(&b.0));
    curves.insert(("khepera".into(), "Enki".into()), curve);
    Ok(())
}

fn all_curves() -> Result<(Curves, BTreeMap<String, f64>), String> {
    let mut curves = Curves::new();
    let mut scale = BTreeMap::new();
    for probe in &PROBES {
        let (curve, max) = engine_curve(probe)?;
        curves.insert((probe.robot.into(), probe.label.into()), curve);
        scale.insert(probe.robot.to_string(), max);
    }
    enki_probe("bench/enki/probe_robots.csv", &mut curves)?;
    enki_bench("configs/sensors/khepera-enki-bench.csv", &mut curves)?;
    Ok((curves, scale))
}

fn csv_text(curves: &Curves) -> String {
    let mut out = String::from("robot,source,distance_mm,reading\n");
    for ((robot, source), curve) in curves {
        for (d, r) in curve {
            out += &format!("{robot},{source},{d},{r}\n");
        }
    }
    out
}

/// One panel: the robot's curves, x 0–150 mm, y 0 to its reading_max.
fn panel(svg: &mut String, curves: &Curves, robot: &str, title: &str, max: f64, left: f64) {
    let (top, w, h) = (30.0, 250.0, 190.0);
    let x = |d: f64| px(left + d / 150.0 * w);
    let y = |r: f64| px(top + h - r / max * h);
    *svg += &format!(
        "<text x=\"{}\" y=\"18\" text-anchor=\"middle\" font-weight=\"bold\">{}</text>\n",
        px(left + w / 2.0),
        esc(title)
    );
    *svg += &format!(
        "<rect x=\"{left}\" y=\"{top}\" width=\"{w}\" height=\"{h}\" fill=\"none\" stroke=\"#999\"/>\n"
    );
    for t in Ticks::nice(0.0, 150.0, 5, true).values {
        *svg += &format!(
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{t}</text>\n",
            x(t),
            top + h + 14.0
        );
    }
    let ticks = Ticks::nice(0.0, max, 5, true);
    for &t in &ticks.values {
        *svg += &format!(
            "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n",
            left - 4.0,
            px(y(t) + 4.0),
            ticks.label(t)
        );
    }
    *svg += &format!(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">distance to the wall (mm)</text>\n",
        px(left + w / 2.0),
        top + h + 30.0
    );
    *svg += &format!(
        "<text transform=\"translate({},{}) rotate(-90)\" text-anchor=\"middle\">reading</text>\n",
        px(left - 40.0),
        px(top + h / 2.0)
    );
    for (k, label) in LEGEND.iter().enumerate() {
        let Some(curve) = curves.get(&(robot.to_string(), label.to_string())) else {
            continue;
        };
        let points: Vec<String> = curve
            .iter()
            .map(|&(d, r)| format!("{},{}", x(d), y(r.min(max))))
            .collect();
        *svg += &format!(
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.6\"{}/>\n",
            points.join(" "),
            colour(k),
            if k == 1 {
                " stroke-dasharray=\"5 3\""
            } else {
                ""
            }
        );
    }
}

/// The curves' labels, in the legend's order (and colours).
const LEGEND: [&str; 3] = [
    "fuzzymotiv (robot file)",
    "fuzzymotiv (table calibrated in Enki)",
    "Enki",
];

fn svg_text(curves: &Curves, scale: &BTreeMap<String, f64>) -> String {
    let mut svg = open(960, 290, 11);
    svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    for (k, (robot, title)) in PANELS.iter().enumerate() {
        let max = scale.get(*robot).copied().unwrap_or(1.0);
        panel(&mut svg, curves, robot, title, max, 60.0 + k as f64 * 315.0);
    }
    let mut x = 55.0;
    for (k, label) in LEGEND.iter().enumerate() {
        svg += &format!(
            "<line x1=\"{x}\" y1=\"275\" x2=\"{}\" y2=\"275\" stroke=\"{}\" stroke-width=\"2\"{}/>\n",
            x + 24.0,
            colour(k),
            if k == 1 {
                " stroke-dasharray=\"5 3\""
            } else {
                ""
            }
        );
        svg += &format!("<text x=\"{}\" y=\"279\">{}</text>\n", x + 30.0, esc(label));
        x += 60.0 + fuzzymotiv_pipeline::render::figure::text_width_at(label, false, 11.0);
    }
    svg + "</svg>\n"
}

fn run(out: &Path) -> Result<(), String> {
    let (curves, scale) = all_curves()?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    for (name, text) in [
        ("readings.csv", csv_text(&curves)),
        ("readings.svg", svg_text(&curves, &scale)),
    ] {
        let path = out.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.as_slice() {
        [out] => run(Path::new(out)),
        _ => Err("usage: readings_vs_distance OUT_DIR".into()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("readings_vs_distance: {e}");
            ExitCode::from(2)
        }
    }
}
