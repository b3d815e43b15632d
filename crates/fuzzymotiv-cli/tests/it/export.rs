//! `fuzzymotiv export`: the exported C gives the simulator's motor outputs and actions bit for
//! bit on recorded trials (compiled with the system `cc`), and the command's files and refusals.

use crate::common;

use common::{ok, repo, run, stderr, stdout};

use std::path::{Path, PathBuf};
use std::process::Command;

use fuzzymotiv::export::{CSources, ExportedController};
use fuzzymotiv::random::{rng_from_seed, uniform};
use fuzzymotiv::simulation::{
    Arena, Mlp, MlpShape, Motion, RawRobot, RawTrial, Room, Trajectory, TrialParams, run_trial,
};

/// The C compiler every Rust toolchain needs for linking; its absence fails the test.
fn cc() -> &'static str {
    let found = Command::new("cc").arg("--version").output();
    assert!(
        found.is_ok_and(|o| o.status.success()),
        "the bit-parity test compiles the exported C with the system C compiler `cc`, which was not found: install one (e.g. apt-get install gcc; Rust needs it to link anyway)"
    );
    "cc"
}

/// Reads 8 readings per line (hex bit patterns of doubles) and prints, per line, the bits of
/// mL and mR and the action from `fm_controller_step_readings`, then the same from
/// `fm_controller_step` when every reading is a whole number (else `-`). A line `L x` prints
/// `fm_logistic(x)`'s bits.
const DRIVER: &str = r#"
#include <inttypes.h>
#include <stdio.h>
#include "fm_controller.h"

typedef union { double d; uint64_t u; } bits;

int main(void)
{
    char kind[4];
    while (scanf("%3s", kind) == 1) {
        if (kind[0] == 'L') {
            bits x, y;
            if (scanf("%" SCNx64, &x.u) != 1) return 2;
            y.d = fm_logistic(x.d);
            printf("%016" PRIx64 "\n", y.u);
        } else {
            bits in[8], m[2];
            double ir[8], motors[2];
            uint16_t ir16[8];
            int action, i, whole = 1;
            for (i = 0; i < 8; i++) {
                if (scanf("%" SCNx64, &in[i].u) != 1) return 2;
                ir[i] = in[i].d;
                ir16[i] = (uint16_t)ir[i];
                if ((double)ir16[i] != ir[i]) whole = 0;
            }
            fm_controller_step_readings(ir, motors, &action);
            m[0].d = motors[0];
            m[1].d = motors[1];
            printf("%016" PRIx64 " %016" PRIx64 " %d", m[0].u, m[1].u, action);
            if (whole) {
                fm_controller_step(ir16, motors, &action);
                m[0].d = motors[0];
                m[1].d = motors[1];
                printf(" %016" PRIx64 " %016" PRIx64 " %d\n", m[0].u, m[1].u, action);
            } else {
                printf(" -\n");
            }
        }
    }
    return 0;
}
"#;

/// Writes the exported C and the driver into `dir` and compiles them with the flags the
/// header asks for; the driver's path.
fn build_driver(dir: &Path, c: &CSources) -> PathBuf {
    std::fs::write(dir.join(CSources::HEADER_NAME), &c.header).unwrap();
    std::fs::write(dir.join(CSources::SOURCE_NAME), &c.source).unwrap();
    compile_driver(dir)
}

/// Compiles the driver with the exported C already in `dir`; the driver's path.
fn compile_driver(dir: &Path) -> PathBuf {
    std::fs::write(dir.join("driver.c"), DRIVER).unwrap();
    let exe = dir.join("driver");
    let out = Command::new(cc())
        .args([
            "-std=c99",
            "-O2",
            "-ffp-contract=off",
            "-Wall",
            "-Wextra",
            "-Werror",
        ])
        .arg(dir.join(CSources::SOURCE_NAME))
        .arg(dir.join("driver.c"))
        .arg("-o")
        .arg(&exe)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "cc failed on the exported C:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    exe
}

/// Runs the driver on `input` (through a file: no pipe to fill); its output lines.
fn run_driver(exe: &Path, input: &str) -> Vec<String> {
    let path = exe.with_extension("in");
    std::fs::write(&path, input).unwrap();
    let out = Command::new(exe)
        .stdin(std::fs::File::open(&path).unwrap())
        .output()
        .unwrap();
    assert!(out.status.success(), "driver failed");
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(String::from)
        .collect()
}

fn params(motion: Motion, noise: f64) -> TrialParams {
    let trial = RawTrial {
        noise: Some(noise),
        ..RawTrial::default()
    };
    let robot = RawRobot {
        motion,
        ..RawRobot::default()
    };
    TrialParams::from_raw(
        &trial,
        &robot,
        fuzzymotiv::simulation::RobotSpec::khepera(),
        0.25,
    )
    .unwrap()
}

fn genome(shape: MlpShape, seed: u64, scale: f64) -> Vec<f64> {
    let mut rng = rng_from_seed(seed);
    (0..shape.genome_len())
        .map(|_| uniform(&mut rng, -scale, scale))
        .collect()
}

const ACTIONS: [&str; 4] = ["straight", "left30", "right30", "turn180"];

/// What the C must print for each executed step of `tr`: the recorded motor outputs' bits and
/// the action the library labels from the commanded (noise-free) speeds, which with noise 0 is
/// the recorded one.
fn expected(tr: &Trajectory, p: &TrialParams) -> Vec<(String, String)> {
    (0..tr.len())
        .filter(|&t| !tr.idle[t])
        .map(|t| {
            let [ml, mr] = tr.motors[t];
            let action = (p.robot().motion()).label(
                tr.motors[t],
                tr.speeds[t],
                p.robot().v_max(),
                p.action_tolerance(),
            );
            if p.noise() == 0.0 {
                assert_eq!(action, tr.actions[t], "step {t}");
            }
            let code = ACTIONS.iter().position(|a| *a == action.label()).unwrap();
            let line = format!("{:016x} {:016x} {code}", ml.to_bits(), mr.to_bits());
            let input: Vec<String> = (tr.sensors[t].iter())
                .map(|v| format!("{:x}", v.to_bits()))
                .collect();
            (format!("S {}\n", input.join(" ")), line)
        })
        .collect()
}

#[test]
fn exported_c_gives_the_simulators_outputs_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let mut checked = 0;
    let mut whole_checked = 0;
    // Genomes of the paper's 8-6-2 (the fixed-size vector path) and others (the general path),
    // with weights small and large (saturated units, sums beyond ±708: exp's edge cases).
    let genomes = [
        (6, 1, 5.0),
        (6, 2, 1.0),
        (6, 3, 400.0),
        (3, 4, 8.0),
        (11, 5, 3.0),
    ];
    for (g, &(hidden, seed, scale)) in genomes.iter().enumerate() {
        let shape = MlpShape::with_hidden(hidden).unwrap();
        let weights = genome(shape, seed, scale);
        for motion in [Motion::Actions, Motion::Wheels] {
            let sub = dir.path().join(format!("g{g}-{motion:?}"));
            std::fs::create_dir_all(&sub).unwrap();
            let export = ExportedController::new(shape, &weights, &params(motion, 0.0)).unwrap();
            let exe = build_driver(&sub, &export.c());
            let (mut input, mut want) = (String::new(), Vec::new());
            for room in ["H", "L", "square"] {
                for (trial_seed, noise) in [(11, 0.0), (12, 0.06), (13, 0.2)] {
                    let p = params(motion, noise);
                    let arena = Arena::new(Room::builtin(room).unwrap(), &p);
                    let mut mlp = Mlp::from_genome(shape, &weights).unwrap();
                    let tr = run_trial(&arena, &mut mlp, &mut rng_from_seed(trial_seed));
                    for (line, out) in expected(&tr, &p) {
                        input.push_str(&line);
                        want.push(out);
                    }
                }
            }
            let got = run_driver(&exe, &input);
            assert_eq!(got.len(), want.len());
            for (i, (got, want)) in got.iter().zip(&want).enumerate() {
                let (readings, whole) = got.split_at(want.len());
                assert_eq!(readings, want, "genome {g}, {motion:?}, step line {i}");
                if whole != " -" {
                    assert_eq!(whole.trim(), want, "uint16 entry, genome {g}, line {i}");
                    whole_checked += 1;
                }
                checked += 1;
            }
        }
    }
    // Enough steps, most of them near walls, and integer readings (noise 0) through the
    // uint16_t entry point.
    assert!(checked > 10_000, "{checked} steps");
    assert!(whole_checked > 3_000, "{whole_checked} steps");
}

#[test]
fn exported_logistic_is_the_librarys_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let shape = MlpShape::default();
    let export =
        ExportedController::new(shape, &genome(shape, 1, 1.0), &TrialParams::default()).unwrap();
    let exe = build_driver(dir.path(), &export.c());
    let mut rng = rng_from_seed(99);
    let mut xs: Vec<f64> = (0..20_000)
        .map(|_| uniform(&mut rng, -40.0, 40.0))
        .collect();
    xs.extend((0..5_000).map(|_| uniform(&mut rng, -800.0, 800.0)));
    xs.extend([
        0.0, -0.0, 708.0, -708.0, 708.0001, -708.0001, 709.7, -709.7, 745.0, -745.0, 746.0, -746.0,
        1e-300, -1e-300, 1e300, -1e300,
    ]);
    xs.extend([f64::INFINITY, f64::NEG_INFINITY, f64::MAX, f64::MIN]);
    let input: String = xs
        .iter()
        .map(|x| format!("L {:x}\n", x.to_bits()))
        .collect();
    let got = run_driver(&exe, &input);
    for (x, line) in xs.iter().zip(&got) {
        let want = format!(
            "{:016x}",
            fuzzymotiv::simulation::logistic_lanes([*x])[0].to_bits()
        );
        assert_eq!(line, &want, "logistic({x:e})");
    }
    assert_eq!(got.len(), xs.len());
}

/// A tiny evolved run (noise 0, so every recorded action is the label of the motor outputs).
fn tiny_run(dir: &Path) -> PathBuf {
    let cfg = dir.join("tiny.toml");
    std::fs::write(&cfg, "name = \"tiny\"\nseed = 5\nrooms = [\"H\", \"square\"]\n[ga]\npopulation = 8\ngenerations = 2\n[trial]\nsteps = 150\nnoise = 0.0\n[aem]\nepochs = 20\ntest_runs = 2\n").unwrap();
    let out = dir.join("tiny");
    ok(&[
        "run",
        cfg.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    out
}

#[test]
fn exported_run_reproduces_its_replay_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = tiny_run(dir.path());
    let c_dir = dir.path().join("controller");
    let o = ok(&[
        "export",
        run_dir.to_str().unwrap(),
        "--to",
        "c",
        "--out",
        c_dir.to_str().unwrap(),
    ]);
    assert!(stdout(&o).contains("fm_controller.c"), "{}", stdout(&o));
    let page = dir.path().join("replay").join("replay.html");
    ok(&[
        "replay",
        run_dir.to_str().unwrap(),
        "--out",
        page.to_str().unwrap(),
    ]);
    let doc: serde_json::Value =
        serde_json::from_slice(&std::fs::read(page.with_extension("json")).unwrap()).unwrap();
    let exe = compile_driver(&c_dir);
    let p = params(Motion::Actions, 0.0);
    let mut steps = 0;
    for room in doc["rooms"].as_array().unwrap() {
        let tr: Trajectory = serde_json::from_value(room["trajectory"].clone()).unwrap();
        let (input, want): (String, Vec<String>) = expected(&tr, &p).into_iter().unzip();
        let got = run_driver(&exe, &input);
        assert_eq!(got.len(), want.len());
        for (got, want) in got.iter().zip(&want) {
            assert!(got.starts_with(want.as_str()), "{got} vs {want}");
        }
        steps += want.len();
    }
    assert!(steps >= 150, "{steps}");
}

#[test]
fn export_json_describes_the_network_and_refuses_to_replace_another_file() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = tiny_run(dir.path());
    let out = dir.path().join("controller.json");
    let (src, dst) = (run_dir.to_str().unwrap(), out.to_str().unwrap());
    ok(&["export", src, "--to", "json", "--out", dst]);
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(doc["format"], "fuzzymotiv-controller");
    assert_eq!(doc["network"]["layout"], "8-6-2");
    let genome: serde_json::Value =
        serde_json::from_slice(&std::fs::read(run_dir.join("best_genome.json")).unwrap()).unwrap();
    assert_eq!(doc["network"]["weights"], genome["weights"]);
    assert_eq!(doc["actions"]["motion"], "actions");
    // The same export again: nothing to do.
    let o = ok(&["export", src, "--to", "json", "--out", dst]);
    assert!(stderr(&o).contains("nothing to do"), "{}", stderr(&o));
    // Another file there is kept without --force.
    std::fs::write(&out, "mine").unwrap();
    let o = run(&["export", src, "--to", "json", "--out", dst]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--force"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "mine");
    ok(&["export", src, "--to", "json", "--out", dst, "--force"]);
    assert_ne!(std::fs::read_to_string(&out).unwrap(), "mine");
}

#[test]
fn export_of_a_genome_of_the_wrong_length_names_the_file_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let genome = dir.path().join("best_genome.json");
    std::fs::write(
        &genome,
        r#"{"shape": {"hidden": 6}, "weights": [0.5, 1.0]}"#,
    )
    .unwrap();
    let c_dir = dir.path().join("c");
    let o = run(&[
        "export",
        genome.to_str().unwrap(),
        "--to",
        "c",
        "--out",
        c_dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("best_genome.json") && e.contains("`weights`") && e.contains("68"),
        "{e}"
    );
    assert!(!e.contains("panicked"), "{e}");
    assert!(!c_dir.exists());
}

#[test]
fn export_c_refuses_a_file_as_its_directory() {
    let dir = tempfile::tempdir().unwrap();
    let genome = dir.path().join("best_genome.json");
    let weights = vec!["0.1"; 68].join(", ");
    std::fs::write(
        &genome,
        format!(r#"{{"shape": {{"hidden": 6}}, "weights": [{weights}]}}"#),
    )
    .unwrap();
    let file = dir.path().join("plain.txt");
    std::fs::write(&file, "keep").unwrap();
    let o = run(&[
        "export",
        genome.to_str().unwrap(),
        "--to",
        "c",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("is a regular file, not a directory"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep");
}

/// Runs the ONNX model of each genome with onnxruntime (the Python of
/// `FUZZYMOTIV_ONNX_PYTHON`, else `python3`) on recorded readings and requires the simulator's
/// motor outputs within 1e-6. Not bit for bit: onnxruntime's MatMul adds the products in its own
/// order (and may fuse them) and its Sigmoid uses its own exp; in practice they differ by ~1e-16.
#[test]
#[ignore = "needs python onnxruntime: run by .ci/run"]
fn onnx_export_agrees_with_the_simulator_under_onnxruntime() {
    let python = std::env::var("FUZZYMOTIV_ONNX_PYTHON").unwrap_or_else(|_| "python3".into());
    let dir = tempfile::tempdir().unwrap();
    let script = "import json, sys\nimport numpy as np\nimport onnxruntime as ort\nd = json.load(open(sys.argv[2]))\ns = ort.InferenceSession(sys.argv[1], providers=['CPUExecutionProvider'])\n(m,) = s.run(None, {'ir': np.array(d['ir'], dtype=np.float64)})\nprint(float(np.max(np.abs(m - np.array(d['motors'])))), m.shape[0])\n";
    for (g, &(hidden, seed, scale)) in [(6, 1, 5.0), (3, 4, 8.0), (6, 3, 40.0)].iter().enumerate() {
        let shape = MlpShape::with_hidden(hidden).unwrap();
        let weights = genome(shape, seed, scale);
        let p = params(Motion::Actions, 0.06);
        let export = ExportedController::new(shape, &weights, &p).unwrap();
        let model = dir.path().join(format!("g{g}.onnx"));
        std::fs::write(&model, export.onnx()).unwrap();
        let (mut ir, mut motors) = (Vec::new(), Vec::new());
        for room in ["H", "square"] {
            let arena = Arena::new(Room::builtin(room).unwrap(), &p);
            let mut mlp = Mlp::from_genome(shape, &weights).unwrap();
            let tr = run_trial(&arena, &mut mlp, &mut rng_from_seed(seed));
            for t in (0..tr.len()).filter(|&t| !tr.idle[t]) {
                ir.push(tr.sensors[t]);
                motors.push(tr.motors[t]);
            }
        }
        let data = dir.path().join(format!("g{g}.json"));
        let doc = serde_json::json!({ "ir": ir, "motors": motors });
        std::fs::write(&data, doc.to_string()).unwrap();
        let out = Command::new(&python)
            .args(["-c", script])
            .arg(&model)
            .arg(&data)
            .output()
            .unwrap_or_else(|e| panic!("{python} does not run: {e}"));
        assert!(
            out.status.success(),
            "onnxruntime failed ({python}; pip install onnxruntime numpy):\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        let mut words = text.split_whitespace();
        let diff: f64 = words.next().unwrap().parse().unwrap();
        let rows: usize = words.next().unwrap().parse().unwrap();
        assert_eq!(rows, ir.len());
        eprintln!("genome {g}: onnxruntime within {diff:e} of the simulator over {rows} steps");
        assert!(diff <= 1e-6, "genome {g}: onnxruntime differs by {diff:e}");
    }
}

/// A robot's log of `tr`'s executed steps written through the compiled exported controller
/// `exe`: per step the recorded IR readings, the motor outputs the C gives for them, and the
/// pose at the step's start; a last row holds the final pose only (no step). Checks that the
/// C's motor outputs are the simulator's, bit for bit.
fn log_through_c(exe: &Path, tr: &Trajectory, log: &Path) {
    let steps: Vec<usize> = (0..tr.len()).filter(|&t| !tr.idle[t]).collect();
    let input: String = (steps.iter())
        .map(|&t| {
            let bits: Vec<String> = (tr.sensors[t].iter())
                .map(|v| format!("{:x}", v.to_bits()))
                .collect();
            format!("S {}\n", bits.join(" "))
        })
        .collect();
    let got = run_driver(exe, &input);
    assert_eq!(got.len(), steps.len());
    let mut text = String::from("ir0,ir1,ir2,ir3,ir4,ir5,ir6,ir7,m_left,m_right,x,y,heading\n");
    for (&t, line) in steps.iter().zip(&got) {
        let motor = |k: usize| {
            let word = line.split_whitespace().nth(k).unwrap();
            f64::from_bits(u64::from_str_radix(word, 16).unwrap())
        };
        let (ml, mr) = (motor(0), motor(1));
        assert_eq!([ml.to_bits(), mr.to_bits()], tr.motors[t].map(f64::to_bits));
        let ir: Vec<String> = tr.sensors[t].iter().map(f64::to_string).collect();
        let p = tr.poses[t];
        text.push_str(&format!(
            "{},{ml},{mr},{},{},{}\n",
            ir.join(","),
            p.x,
            p.y,
            p.heading
        ));
    }
    let end = tr.poses[tr.executed()];
    text.push_str(&format!(",,,,,,,,,,{},{},{}\n", end.x, end.y, end.heading));
    std::fs::write(log, text).unwrap();
}

/// `fuzzymotiv recognise`'s CSV row for `log`, without the log's name and its step counts.
fn recognised(run_dir: &Path, log: &Path, out: &Path) -> Vec<String> {
    ok(&[
        "recognise",
        run_dir.to_str().unwrap(),
        log.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let csv = std::fs::read_to_string(out.join("recognised.csv")).unwrap();
    let row: Vec<String> = csv
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(String::from)
        .collect();
    // room, winner, then r_node, node_distance, gate, vector_distance.
    [&row[3..5], &row[9..]].concat()
}

/// The `points` of the first `<polyline` in `svg` that contains `marker`.
fn polyline_points<'a>(svg: &'a str, marker: &str) -> &'a str {
    let line = (svg.lines())
        .find(|l| l.starts_with("<polyline") && l.contains(marker))
        .unwrap_or_else(|| panic!("no polyline with {marker}"));
    line.split("points=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap()
}

/// The loop a robot runs, open-loop on the simulator's own readings: each room's replayed IR
/// readings go through the compiled exported C controller, whose motor outputs, bit-exact on
/// recorded readings, equal the simulator's; logged as a robot would (ir0..ir7, m_left,
/// m_right, x, y, heading), the log is recognised as the same room at the same SOM node (with
/// the same gate's distance and vector distance) as the replay itself, and `replay --log`
/// draws its path over the simulated one, point for point.
#[test]
fn a_log_written_through_the_exported_c_is_recognised_and_drawn_like_its_replay() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = tiny_run(dir.path());
    let c_dir = dir.path().join("controller");
    let run_arg = run_dir.to_str().unwrap();
    ok(&[
        "export",
        run_arg,
        "--to",
        "c",
        "--out",
        c_dir.to_str().unwrap(),
    ]);
    let exe = compile_driver(&c_dir);
    let page = dir.path().join("replay").join("replay.html");
    ok(&["replay", run_arg, "--out", page.to_str().unwrap()]);
    let doc: serde_json::Value =
        serde_json::from_slice(&std::fs::read(page.with_extension("json")).unwrap()).unwrap();
    let rooms = doc["rooms"].as_array().unwrap();
    assert_eq!(rooms.len(), 2);
    for room in rooms {
        let name = room["room"].as_str().unwrap();
        let tr: Trajectory = serde_json::from_value(room["trajectory"].clone()).unwrap();
        let log = dir.path().join(format!("robot-{name}.csv"));
        log_through_c(&exe, &tr, &log);
        let replayed = dir.path().join("replay").join(format!("replay-{name}.csv"));
        let want = recognised(&run_dir, &replayed, &dir.path().join(format!("rec-{name}")));
        let got = recognised(&run_dir, &log, &dir.path().join(format!("log-{name}")));
        assert_eq!(got, want, "{name}");
        assert_eq!(want[0], name, "the replay is recognised as its room");
        let drawn = dir.path().join(format!("drawn-{name}")).join("replay.html");
        let o = ok(&[
            "replay",
            run_arg,
            "--room",
            name,
            "--log",
            log.to_str().unwrap(),
            "--out",
            drawn.to_str().unwrap(),
        ]);
        assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
        let svg = std::fs::read_to_string(drawn.with_extension("svg")).unwrap();
        let logged = polyline_points(&svg, "class=\"logged\"");
        assert_eq!(logged, polyline_points(&svg, "#d62728"), "{name}");
        assert_eq!(logged.split_whitespace().count(), tr.executed() + 1);
        assert!(
            svg.contains(&format!("logged path: {}", log.display())),
            "{svg}"
        );
        let html = std::fs::read_to_string(&drawn).unwrap();
        assert!(html.contains("class=\"logged\""), "the page draws it too");
    }
}

/// Issue #52 item 7: an all-rooms run's genome lists its one robot under `runs`; export no
/// longer calls that "a robot per room", and `--room H` says the file holds one robot for all
/// rooms instead of "its rooms are all". `--help` and `export --help` name ONNX.
#[test]
fn an_all_rooms_genome_is_not_said_to_hold_a_robot_per_room() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = tiny_run(dir.path());
    let out = dir.path().join("c.json");
    let (src, dst) = (run_dir.to_str().unwrap(), out.to_str().unwrap());
    let o = ok(&["export", src, "--to", "json", "--out", dst]);
    assert!(!stderr(&o).contains("robot per room"), "{}", stderr(&o));
    let o = run(&["export", src, "--to", "json", "--out", dst, "--room", "H"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("holds one robot for all rooms") && !stderr(&o).contains("are all"),
        "{}",
        stderr(&o)
    );
    for help in [&["--help"][..], &["export", "--help"]] {
        assert!(stdout(&ok(help)).contains("ONNX"), "{help:?}");
    }
}

/// `--target khepera` writes the Khepera kit (the generic C byte for byte, the executor, the
/// I/O layer, golden vectors, a README) through the output guard: the same export again does
/// nothing, another file of a kit's name is kept without `--force`; `--target generic` is the
/// plain export. A kit for another robot than the run's, or `--target` with JSON, is an input
/// error naming `--target` (and both robots) that writes nothing.
#[test]
fn export_target_writes_the_runs_robot_kit_and_refuses_another_robots() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = tiny_run(dir.path());
    let src = run_dir.to_str().unwrap();
    let (kit, plain, generic) = (
        dir.path().join("kit"),
        dir.path().join("plain"),
        dir.path().join("generic"),
    );
    let export = |out: &Path, extra: &[&str]| {
        let mut args = vec!["export", src, "--to", "c", "--out", out.to_str().unwrap()];
        args.extend(extra);
        run(&args)
    };
    let o = export(&kit, &["--target", "khepera"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let names = [
        "fm_controller.h",
        "fm_controller.c",
        "fm_executor.h",
        "fm_executor.c",
        "fm_khepera.h",
        "fm_khepera.c",
        "golden.csv",
        "fm_golden.c",
        "README.txt",
    ];
    for name in names {
        assert!(stdout(&o).contains(name), "{name}: {}", stdout(&o));
    }
    assert!(
        stderr(&o).contains("wrote the khepera kit"),
        "{}",
        stderr(&o)
    );
    assert!(
        stderr(&o).contains("fm_robot_io"),
        "the kit's notes: {}",
        stderr(&o)
    );
    ok(&["export", src, "--to", "c", "--out", plain.to_str().unwrap()]);
    ok(&[
        "export",
        src,
        "--to",
        "c",
        "--target",
        "generic",
        "--out",
        generic.to_str().unwrap(),
    ]);
    for name in ["fm_controller.h", "fm_controller.c"] {
        let plain_bytes = std::fs::read(plain.join(name)).unwrap();
        assert_eq!(
            std::fs::read(kit.join(name)).unwrap(),
            plain_bytes,
            "{name}"
        );
        assert_eq!(
            std::fs::read(generic.join(name)).unwrap(),
            plain_bytes,
            "{name}"
        );
    }
    assert_eq!(std::fs::read_dir(&generic).unwrap().count(), 2);
    let golden = std::fs::read_to_string(kit.join("golden.csv")).unwrap();
    assert!(golden.lines().filter(|l| l.starts_with("0x")).count() > 100);
    // Again: nothing to do; a file of the user's under a kit's name is kept without --force.
    let o = export(&kit, &["--target", "khepera"]);
    assert!(stderr(&o).contains("nothing to do"), "{}", stderr(&o));
    std::fs::write(kit.join("README.txt"), "mine").unwrap();
    let o = export(&kit, &["--target", "khepera"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--force"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(kit.join("README.txt")).unwrap(),
        "mine"
    );
    let o = export(&kit, &["--target", "khepera", "--force"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        std::fs::read_to_string(kit.join("README.txt"))
            .unwrap()
            .contains("fm_robot_io")
    );
    // Another robot's kit, and a kit that is not C.
    for target in ["epuck2", "thymio2"] {
        let out = dir.path().join(target);
        let o = export(&out, &["--target", target]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let e = stderr(&o);
        assert!(
            e.contains(&format!("--target {target}: the controller was evolved for the robot `khepera`, not `{target}`")),
            "{e}"
        );
        assert!(!out.exists());
    }
    let json = dir.path().join("c.json");
    let dst = json.to_str().unwrap();
    let o = run(&[
        "export", src, "--to", "json", "--target", "khepera", "--out", dst,
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "--target khepera: a deployment kit is C code; a json export takes no --target"
        ),
        "{}",
        stderr(&o)
    );
    assert!(!json.exists());
}

/// The Thymio II's tiny run: 7 sensors reading 0-4505, so a 7-6-2 network.
fn tiny_thymio_run(dir: &Path) -> PathBuf {
    let out = dir.join("thymio2");
    let cfg = repo().join("configs/thymio2.toml");
    ok(&[
        "run",
        cfg.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--set",
        "ga.population=10",
        "--set",
        "ga.generations=2",
        "--set",
        "trial.steps=100",
        "--set",
        "aem.enabled=false",
    ]);
    out
}

#[test]
fn a_thymio_export_says_its_own_inputs_and_reading_scale_not_the_kheperas() {
    let dir = tempfile::tempdir().unwrap();
    let run_dir = tiny_thymio_run(dir.path());
    let src = run_dir.to_str().unwrap();
    let kit = dir.path().join("kit");
    let o = ok(&[
        "export",
        src,
        "--to",
        "c",
        "--target",
        "thymio2",
        "--out",
        kit.to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert!(
        e.contains("wrote the thymio2 kit of the 7-6-2 controller"),
        "{e}"
    );
    assert!(kit.join("fm_controller.aesl").is_file());
    let plain = dir.path().join("plain");
    let o = ok(&["export", src, "--to", "c", "--out", plain.to_str().unwrap()]);
    assert!(
        stderr(&o).contains("wrote the 7-6-2 controller"),
        "{}",
        stderr(&o)
    );
    let json = dir.path().join("c.json");
    ok(&[
        "export",
        src,
        "--to",
        "json",
        "--out",
        json.to_str().unwrap(),
    ]);
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(doc["inputs"]["reading_max"], 4505.0);
    let scaling = doc["inputs"]["scaling"].as_str().unwrap();
    assert!(scaling.starts_with("x = reading / 4505 "), "{scaling}");
    assert!(!scaling.contains("1023"), "{scaling}");
    let order = doc["network"]["weight_order"].as_str().unwrap();
    assert!(order.contains("w from input 6]"), "{order}");
}
