//! The deployment kits: their files, the golden vectors replayed by the host C compiler, the
//! e-puck2 kit compiled against the firmware's header stubs, and the actions executor on a
//! simulated robot's odometry.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use super::golden::{self, label_of};
use super::{ExportedController, Kit, KitRobot, epuck2_kit, khepera_kit};
use crate::simulation::controller::{Controller, INPUTS, Mlp, MlpShape};
use crate::simulation::robot::{Motion, RawRobot, Robot};
use crate::simulation::trial::TrialParams;

/// The kits' host C flags: those the headers ask for, warnings as errors.
const CFLAGS: [&str; 6] = [
    "-std=c99",
    "-O2",
    "-ffp-contract=off",
    "-Wall",
    "-Wextra",
    "-Werror",
];

/// An e-puck2 as Enki models it (docs/robots-sources.md §1.3: wheel base 5.1 cm, 12.8 cm/s,
/// IR response up to 3731), in the firmware's calibrated-prox units.
fn epuck2_robot() -> KitRobot {
    KitRobot {
        name: "epuck2".into(),
        sensors: 8,
        reading_max: 3731.0,
        v_max: 128.0,
        wheel_base: 51.0,
        dt: 0.1,
        turn_deg: 30.0,
    }
}

/// A controller of `hidden` units with weights of size about `scale`, evolved with `motion`.
fn controller(hidden: usize, scale: f64, motion: Motion) -> ExportedController {
    let shape = MlpShape::with_hidden(hidden).unwrap();
    let genome: Vec<f64> = (0..shape.genome_len())
        .map(|i| scale * (i as f64 * 1.7).sin())
        .collect();
    let raw = RawRobot {
        motion,
        ..RawRobot::default()
    };
    let params = TrialParams::default()
        .with_robot(Robot::from_raw(&raw, crate::simulation::RobotSpec::khepera()).unwrap());
    ExportedController::new(shape, &genome, &params).unwrap()
}

fn epuck2_controller(motion: Motion) -> ExportedController {
    controller(6, 3.0, motion)
        .for_robot(epuck2_robot())
        .unwrap()
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fuzzymotiv-kit-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write_kit(kit: &Kit, dir: &Path) {
    for f in &kit.files {
        std::fs::write(dir.join(&f.name), &f.contents).unwrap();
    }
}

fn text<'a>(kit: &'a Kit, name: &str) -> &'a str {
    let file = kit.files.iter().find(|f| f.name == name).unwrap();
    std::str::from_utf8(&file.contents).unwrap()
}

/// Runs `cc` (the system C compiler) with `args` in `dir`; its output.
fn cc(dir: &Path, args: &[&str]) -> Output {
    Command::new("cc")
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the system C compiler `cc` runs")
}

fn succeeded(out: &Output, what: &str) {
    assert!(
        out.status.success(),
        "{what} failed:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

fn compile(dir: &Path, sources: &[&str], exe: &str) {
    let mut args: Vec<&str> = CFLAGS.to_vec();
    args.extend(sources);
    args.extend(["-o", exe]);
    succeeded(&cc(dir, &args), &format!("cc {sources:?}"));
}

#[test]
fn a_kit_for_another_robot_writes_its_sensor_count_and_reading_scale() {
    let c = epuck2_controller(Motion::Actions);
    let sources = c.c();
    for line in [
        "#define FM_INPUTS 8\n",
        "void fm_controller_step(const uint16_t ir[8], double motors[2], int *action);",
        " * Inputs: the eight IR readings in the simulator's scale 0..3731 (readings above 3731 are",
        " * order: the robot `epuck2`'s 8 sensors, numbered as its robot file numbers them (wire",
    ] {
        assert!(sources.header.contains(line), "{line}\n{}", sources.header);
    }
    assert!(!sources.header.contains("Khepera layout"));
    assert!(
        (sources.source).contains("static const double SENSOR_MAX = 0x1.d260000000000p+11;\n"),
        "3731"
    );
    assert!(
        sources
            .source
            .contains("v[i] = ir[i] > 3731 ? 3731.0 : (double)ir[i];")
    );
    let khepera = controller(6, 3.0, Motion::Actions).c();
    assert!(khepera.header.contains("classic Khepera layout"));
    assert!(
        khepera
            .source
            .contains("v[i] = ir[i] > 1023 ? 1023.0 : (double)ir[i];")
    );
}

#[test]
fn a_robot_whose_sensors_are_not_the_networks_inputs_is_refused() {
    let robot = KitRobot {
        sensors: 7,
        ..epuck2_robot()
    };
    let e = controller(6, 1.0, Motion::Actions)
        .for_robot(robot)
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "the robot `epuck2` has 7 sensors but the network has 8 inputs"
    );
    let robot = KitRobot {
        wheel_base: f64::NAN,
        ..epuck2_robot()
    };
    let e = controller(6, 1.0, Motion::Actions)
        .for_robot(robot)
        .unwrap_err();
    assert!(e.to_string().contains("wheel_base is NaN"), "{e}");
}

#[test]
fn each_kit_holds_the_network_the_executor_its_robot_layer_golden_vectors_and_a_readme() {
    let c = epuck2_controller(Motion::Actions);
    let names = |kit: &Kit| kit.files.iter().map(|f| f.name.clone()).collect::<Vec<_>>();
    let common = [
        "fm_controller.h",
        "fm_controller.c",
        "fm_executor.h",
        "fm_executor.c",
    ];
    let epuck2 = epuck2_kit(&c);
    let mut want: Vec<&str> = common.to_vec();
    want.extend([
        "fm_epuck2.h",
        "fm_epuck2.c",
        "golden.csv",
        "fm_golden.c",
        "README.txt",
    ]);
    assert_eq!(names(&epuck2), want);
    let khepera = khepera_kit(&controller(6, 3.0, Motion::Wheels));
    want[4..6].copy_from_slice(&["fm_khepera.h", "fm_khepera.c"]);
    assert_eq!(names(&khepera), want);
    // The generic network is the kit's, byte for byte; the files name no path of this
    // repository (whoever is handed a kit has none).
    assert_eq!(text(&epuck2, "fm_controller.c"), c.c().source);
    for file in epuck2.files.iter().chain(&khepera.files) {
        let body = std::str::from_utf8(&file.contents).unwrap();
        for path in ["docs/", "crates/", ".rs", ".md"] {
            assert!(!body.contains(path), "{path} in {}", file.name);
        }
    }
    let readme = text(&epuck2, "README.txt");
    for needle in [
        "fm_epuck2_start();",
        "calibrate_ir();",
        "motors_init();",
        "proximity_start(FAST_UPDATE);",
        "CSRC += ./main.c ./fm_controller.c ./fm_executor.c ./fm_epuck2.c",
        "-fno-single-precision-constant",
        "./fm_golden golden.csv",
        "straight drives both wheels 12.8 mm",
    ] {
        assert!(readme.contains(needle), "{needle} not in:\n{readme}");
    }
    let source = text(&epuck2, "fm_epuck2.c");
    assert!(
        source.contains("#define FM_EPUCK2_PERIOD_MS 100\n"),
        "{source}"
    );
    assert!(source.contains("#define FM_EPUCK2_READING_MAX 0x1.d260000000000p+11\n"));
    assert!(text(&khepera, "README.txt").contains("wheels get its speeds"));
    assert!(text(&epuck2, "fm_executor.h").contains("#define FM_STEP_MM 0x1.999999999999ap+3\n"));
}

/// Compiles each kit's `fm_golden.c` with its `fm_controller.c` and replays its `golden.csv`:
/// every motor output bit for bit and every label, for the Khepera (the simulator's scale) and
/// the e-puck2 (readings scaled to 0..3731), both motions, a large-weight network; a golden
/// motor output changed in its last bit is reported as one difference.
#[test]
#[ignore = "needs cc: run by .ci/run"]
fn kit_golden_vectors_replay_bit_for_bit_under_cc() {
    let controllers = [
        ("khepera-actions", controller(6, 3.0, Motion::Actions)),
        ("khepera-wheels-large", controller(11, 40.0, Motion::Wheels)),
        ("epuck2-actions", epuck2_controller(Motion::Actions)),
        ("epuck2-wheels", epuck2_controller(Motion::Wheels)),
    ];
    for (name, c) in controllers {
        let kit = if name.starts_with("epuck2") {
            epuck2_kit(&c)
        } else {
            khepera_kit(&c)
        };
        let dir = scratch(name);
        write_kit(&kit, &dir);
        compile(&dir, &["fm_golden.c", "fm_controller.c"], "fm_golden");
        let vectors = golden::vectors(&c).len();
        let out = Command::new(dir.join("fm_golden"))
            .arg(dir.join("golden.csv"))
            .output()
            .unwrap();
        succeeded(&out, name);
        let said = String::from_utf8_lossy(&out.stdout);
        assert_eq!(
            said,
            format!("{vectors} golden vectors, 0 differ\n"),
            "{name}"
        );
        assert!(vectors > 150, "{name}: {vectors}");
        // One motor output off by one bit.
        let csv = text(&kit, "golden.csv");
        let row = (csv.lines())
            .find(|l| {
                l.split(',')
                    .nth(INPUTS)
                    .is_some_and(|m| m.starts_with("0x1."))
            })
            .unwrap();
        let mut cells: Vec<String> = row.split(',').map(String::from).collect();
        let m = &mut cells[INPUTS];
        let bits = u64::from_str_radix(&m[4..17], 16).unwrap() ^ 1;
        m.replace_range(4..17, &format!("{bits:013x}"));
        let bad = csv.replacen(row, &cells.join(","), 1);
        std::fs::write(dir.join("bad.csv"), bad).unwrap();
        let out = Command::new(dir.join("fm_golden"))
            .arg(dir.join("bad.csv"))
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1), "{name}");
        let said = String::from_utf8_lossy(&out.stdout);
        assert!(
            said.ends_with(&format!("{vectors} golden vectors, 1 differ\n")),
            "{name}: {said}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// Every C file of both kits compiles warning-free with the host compiler (the e-puck2's
/// against the firmware header stubs in tests/data/epuck2-stubs), and with
/// `-fsingle-precision-constant` (ChibiOS's flag for boards with an FPU) the kit refuses to
/// compile rather than round the network's weights to float.
#[test]
#[ignore = "needs cc: run by .ci/run"]
fn kit_sources_compile_warning_free_and_refuse_single_precision_constants() {
    let stubs = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/epuck2-stubs");
    let include = format!("-I{}", stubs.display());
    for motion in [Motion::Actions, Motion::Wheels] {
        let dir = scratch(&format!("compile-{motion:?}"));
        let c = epuck2_controller(motion);
        write_kit(&epuck2_kit(&c), &dir);
        for file in ["fm_controller.c", "fm_executor.c", "fm_epuck2.c"] {
            let mut args: Vec<&str> = CFLAGS.to_vec();
            args.extend([include.as_str(), "-c", file]);
            succeeded(&cc(&dir, &args), &format!("{motion:?} {file}"));
        }
        let mut args: Vec<&str> = CFLAGS.to_vec();
        args.extend(["-fsingle-precision-constant", "-c", "fm_executor.c"]);
        let out = cc(&dir, &args);
        assert!(!out.status.success(), "fm_executor.c took single constants");
        let said = String::from_utf8_lossy(&out.stderr);
        assert!(said.contains("doubles_as_written"), "{said}");
        write_kit(&khepera_kit(&controller(6, 3.0, motion)), &dir);
        for file in ["fm_executor.c", "fm_khepera.c"] {
            let mut args: Vec<&str> = CFLAGS.to_vec();
            args.extend(["-c", file]);
            succeeded(&cc(&dir, &args), &format!("{motion:?} {file}"));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// The executor on a simulated robot: each period a wheel moves its commanded speed × the
/// period (the motor follows exactly) and its counter shows the whole ticks moved. From
/// counters at (1000, −500), each action's wheel travel and periods, then one
/// `fm_executor_step` from all-zero readings: the label, the action begun and the speeds.
const ODOMETRY: &str = r#"
#include <stdio.h>
#include <stdlib.h>
#include "fm_executor.h"

int main(int argc, char **argv)
{
    double tpm;
    int32_t limit, speeds[2];
    double ir[FM_INPUTS] = {0};
    fm_executor e;
    int a;
    if (argc != 3) return 2;
    tpm = strtod(argv[1], NULL);
    limit = (int32_t)strtol(argv[2], NULL, 10);
    for (a = 0; a < 4; a++) {
        int32_t start[2] = {1000, -500}, pos[2] = {1000, -500}, sp[2];
        double moved[2] = {0.0, 0.0};
        int periods = 0, k;
        fm_executor_init(&e, tpm, limit);
        fm_executor_begin(&e, a, pos[0], pos[1]);
        while (fm_executor_tick(&e, pos[0], pos[1], sp) && periods < 100000) {
            periods++;
            for (k = 0; k < 2; k++) {
                if (sp[k] > limit || sp[k] < -limit) return 3;
                moved[k] += (double)sp[k] * FM_PERIOD_S;
                pos[k] = start[k] + (int32_t)moved[k];
            }
        }
        printf("%d %ld %ld %d %ld\n", a, (long)(pos[0] - start[0]), (long)(pos[1] - start[1]),
               periods, (long)e.cruise);
    }
    fm_executor_init(&e, tpm, limit);
    fm_executor_step(&e, ir, 0, 0, speeds);
    printf("%d %d %ld %ld %lu\n", e.label, e.action, (long)speeds[0], (long)speeds[1],
           (unsigned long)e.steps);
    return 0;
}
"#;

/// What the odometry harness printed: per action (wheel travel L, R in ticks, periods, cruise
/// speed), then the first step's label, action, speeds and network runs.
struct Odometry {
    actions: Vec<[i64; 4]>,
    first: [i64; 5],
}

fn run_odometry(dir: &Path, ticks_per_mm: f64, limit: i32) -> Odometry {
    let out = Command::new(dir.join("odometry"))
        .args([ticks_per_mm.to_string(), limit.to_string()])
        .output()
        .unwrap();
    succeeded(&out, "odometry");
    let rows: Vec<Vec<i64>> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| l.split(' ').map(|w| w.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 5);
    Odometry {
        actions: rows[..4].iter().map(|r| [r[1], r[2], r[3], r[4]]).collect(),
        first: rows[4].clone().try_into().unwrap(),
    }
}

/// A straight action moves both wheels v_max·dt within one tick (1/ticks_per_mm mm) and, when
/// the motors are fast enough, in one period as in the simulator; left30 and right30 turn
/// ±30°, turn180 180°, on the spot, each within one step's resolution (both wheels one tick:
/// 2/(ticks_per_mm · wheel_base) rad); no speed exceeds the limit; with `wheels` motion the
/// first step's speeds are (2m − 1)·v_max in ticks/s, with `actions` motion the first step
/// begins the network's label.
#[test]
#[ignore = "needs cc: run by .ci/run"]
fn executor_moves_each_action_within_one_step_on_simulated_odometry() {
    let epuck2_ticks =
        super::EPUCK2_STEPS_PER_TURN / (std::f64::consts::PI * super::EPUCK2_WHEEL_DIAMETER_MM);
    for motion in [Motion::Actions, Motion::Wheels] {
        let c = epuck2_controller(motion);
        let r = c.robot().clone();
        let dir = scratch(&format!("odometry-{motion:?}"));
        write_kit(&epuck2_kit(&c), &dir);
        std::fs::write(dir.join("odometry.c"), ODOMETRY).unwrap();
        compile(
            &dir,
            &["odometry.c", "fm_executor.c", "fm_controller.c"],
            "odometry",
        );
        // The e-puck2's steppers; a coarse encoder; motors too slow for v_max.
        for (tpm, limit) in [(epuck2_ticks, 1100), (3.0, 10_000), (epuck2_ticks, 300)] {
            let got = run_odometry(&dir, tpm, limit);
            let quantum = 2.0 / (tpm * r.wheel_base);
            let [sl, sr, periods, cruise] = got.actions[0];
            assert_eq!(sl, sr, "straight, {tpm} ticks/mm");
            let mm = sl as f64 / tpm;
            assert!(
                (mm - r.straight_step()).abs() <= 1.0 / tpm,
                "straight {mm} mm"
            );
            assert!(cruise <= i64::from(limit));
            if cruise < i64::from(limit) {
                assert_eq!(periods, 1, "a straight step takes one period at {tpm}");
            }
            for (a, want_deg) in [(1, 30.0f64), (2, -30.0), (3, 180.0)] {
                let [dl, dr, periods, _] = got.actions[a];
                assert_eq!(dl, -dr, "action {a} on the spot");
                let turned = (dr - dl) as f64 / tpm / r.wheel_base;
                let err = (turned - want_deg.to_radians()).abs();
                assert!(
                    err <= quantum,
                    "action {a}: {turned} rad, {err} > {quantum}"
                );
                assert!(periods >= 1);
            }
            let mut mlp = Mlp::from_genome(c.shape(), c.weights()).unwrap();
            let motors = mlp.step(&[0.0; 8]);
            let label = label_of(&c, motors);
            let [got_label, action, left, right, runs] = got.first;
            assert_eq!(runs, 1);
            assert_eq!(got_label, label as i64, "{label:?}");
            match motion {
                Motion::Wheels => {
                    let speed = |m: f64| {
                        let v = ((2.0 * m - 1.0) * r.v_max * tpm).round() as i64;
                        v.clamp(-i64::from(limit), i64::from(limit))
                    };
                    assert_eq!([left, right], [speed(motors[0]), speed(motors[1])]);
                    assert_eq!(action, -1);
                }
                Motion::Actions => assert_eq!(action, got_label),
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
