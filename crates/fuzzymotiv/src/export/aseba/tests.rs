//! Tests of the Thymio II kit: the fixed-point program, run by the interpreter of Aseba's
//! 16-bit semantics, against the float network on readings recorded in the simulator.

use super::*;
use crate::export::kit::KitRobot;
use crate::random::{Rng64, rng_from_seed, uniform};
use crate::simulation::controller::{Controller, INPUTS, Mlp, MlpShape};
use crate::simulation::trial::{Arena, TrialParams};
use crate::simulation::{Room, TrialRun};

/// Largest |fixed − float| wheel target (Thymio units) accepted: the float target spans
/// ±500 units; 1/4096 of an input, the weights' rounding, the table and the truncations
/// stay below it (measured: see `fixed_point_agrees_with_the_float_network_on_recorded_readings`).
const TARGET_BOUND: f64 = 4.0;

fn thymio(sensors: usize) -> KitRobot {
    KitRobot {
        name: "thymio2".into(),
        sensors,
        reading_max: if sensors == 8 { 1023.0 } else { 4505.0 },
        v_max: 166.0,
        wheel_base: 94.0,
        dt: 0.1,
        turn_deg: 30.0,
    }
}

/// A controller for `sensors` inputs and `hidden` units with `weights` (the genome's order).
pub(super) fn controller(
    sensors: usize,
    hidden: usize,
    weights: Vec<f64>,
    motion: Motion,
) -> ExportedController {
    assert_eq!(weights.len(), hidden * (sensors + 1) + 2 * (hidden + 1));
    let name = if sensors == 8 { "khepera" } else { "thymio2" };
    let spec = crate::simulation::RobotSpec::builtin(name).unwrap();
    let raw = crate::simulation::RawRobot {
        motion,
        ..Default::default()
    };
    let robot = crate::simulation::Robot::from_raw(&raw, spec).unwrap();
    ExportedController {
        shape: MlpShape::with_hidden(hidden)
            .and_then(|s| s.with_inputs(sensors))
            .unwrap(),
        weights,
        v_max: 166.0,
        motion,
        tolerance: 0.25,
        robot: thymio(sensors),
        trial: crate::simulation::TrialParams::default().with_robot(robot),
    }
}

pub(super) fn random_weights(
    rng: &mut Rng64,
    sensors: usize,
    hidden: usize,
    spread: f64,
) -> Vec<f64> {
    (0..hidden * (sensors + 1) + 2 * (hidden + 1))
        .map(|_| uniform(rng, -spread, spread))
        .collect()
}

/// Readings recorded in the simulator: an 8-input network with random weights drives the
/// Khepera for `trials` trials in the built-in rooms; each step's eight noisy readings
/// (0…1023). For `n` = 7 the first seven are kept and scaled to the Thymio's 0…4505
/// (× 4505/1023), for `n` = 8 all eight in the simulator's scale; rounded to integers, as a
/// robot reports them.
fn recorded_readings(n: usize, trials: u64) -> Vec<Vec<i16>> {
    let mut rows = Vec::new();
    for seed in 0..trials {
        let room = ["square", "rectangle"][seed as usize % 2];
        let arena = Arena::new(Room::builtin(room).unwrap(), &TrialParams::default());
        let mut rng = rng_from_seed(100 + seed);
        let shape = MlpShape::default();
        let genome: Vec<f64> = (0..shape.genome_len())
            .map(|_| uniform(&mut rng, -3.0, 3.0))
            .collect();
        let mut mlp = Mlp::from_genome(shape, &genome).unwrap();
        let mut run = TrialRun::new(&arena, rng_from_seed(seed));
        while !run.is_over() {
            let ir = run.observe();
            let scale = if n == 7 { 4505.0 / 1023.0 } else { 1.0 };
            rows.push(ir[..n].iter().map(|v| (v * scale).round() as i16).collect());
            let m = mlp.step(&run.inputs());
            run.step(m);
        }
    }
    rows
}

/// `prog` loaded into the interpreter and initialised.
fn machine(prog: &AeslProgram, src: Source) -> Result<Machine, AsebaError> {
    let mut m = Machine::load(&prog.code, &prog.constants, &target_vars(src))?;
    m.run_init()?;
    Ok(m)
}

pub(super) fn loaded(c: &ExportedController, src: Source) -> (AeslProgram, Machine) {
    let prog = program::generate(c, src);
    let m = machine(&prog, src).unwrap();
    (prog, m)
}

#[test]
fn the_float_reference_is_the_engines_network_for_eight_inputs() {
    let mut rng = rng_from_seed(3);
    for hidden in [1, 6, 9] {
        let shape = MlpShape::with_hidden(hidden).unwrap();
        let w = random_weights(&mut rng, INPUTS, hidden, 5.0);
        let mut mlp = Mlp::from_genome(shape, &w).unwrap();
        for readings in recorded_readings(8, 1).iter().step_by(7) {
            let r: Vec<f64> = readings.iter().map(|&v| f64::from(v)).collect();
            let x: [f64; INPUTS] = std::array::from_fn(|k| r[k].min(1023.0) / 1023.0);
            let float = quant::float_step(&w, INPUTS, hidden, &r, 1023.0);
            assert_eq!(float.map(f64::to_bits), mlp.step(&x).map(f64::to_bits));
        }
    }
}

/// Agreement statistics of `c`'s program with its float network on `readings`: largest
/// |Δ target| (units), largest |Δm|, share of equal labels, most VM steps of an evaluation.
fn agreement(c: &ExportedController, readings: &[Vec<i16>], src: Source) -> (f64, f64, f64, usize) {
    let (_, mut m) = loaded(c, src);
    let (mut dt, mut dm, mut same, mut steps) = (0.0f64, 0.0f64, 0, 0);
    for r in readings {
        let f = float_out(c, r);
        let q = fixed_out(&mut m, r).unwrap();
        for o in 0..2 {
            dt = dt.max((f64::from(q.target[o]) - f.target[o]).abs());
            dm = dm.max((f64::from(q.m[o]) / 4096.0 - f.m[o]).abs());
        }
        same += usize::from(f.action == q.action);
        steps = steps.max(q.steps);
    }
    (dt, dm, same as f64 / readings.len() as f64, steps)
}

#[test]
fn fixed_point_agrees_with_the_float_network_on_recorded_readings() {
    let mut rng = rng_from_seed(11);
    for n in [7, 8] {
        let readings = recorded_readings(n, 6);
        let src = Source {
            var: "prox.horizontal",
            len: n,
        };
        let seen = readings.iter().filter(|r| r.iter().any(|&v| v > 0)).count();
        assert!(
            seen > readings.len() / 5,
            "{seen} of {} readings see a wall",
            readings.len()
        );
        for (spread, motion) in [
            (2.0, Motion::Wheels),
            (5.0, Motion::Actions),
            (10.0, Motion::Wheels),
        ] {
            let c = controller(n, 6, random_weights(&mut rng, n, 6, spread), motion);
            let (dt, dm, labels, steps) = agreement(&c, &readings, src);
            eprintln!(
                "N={n} H=6 weights ±{spread}: {} readings, max |Δtarget| {dt:.3} units, max |Δm| {dm:.5}, labels {:.2} %, {steps} steps",
                readings.len(),
                100.0 * labels
            );
            assert!(dt <= TARGET_BOUND, "{dt}");
            assert!(labels >= 0.99, "{labels}");
            assert!(steps < 1000, "{steps}");
        }
    }
}

#[test]
fn weights_far_outside_the_q_range_are_scaled_not_wrapped() {
    let (n, h) = (7, 4);
    let mut rng = rng_from_seed(5);
    let mut w = random_weights(&mut rng, n, h, 1.0);
    // Hidden unit 0: bias 3·10⁵ (always on); unit 1: −2·10⁵ from input 2 and nothing else
    // (0.5 when the sensor reads 0, else off); an output weight of 7·10⁴ on unit 3 (whose
    // activation stays above 3·10⁻⁴: its sum is within ±8, so the output is always on).
    w[0] = 3.0e5;
    w[n + 1..2 * (n + 1)].fill(0.0);
    w[n + 1 + 1 + 2] = -2.0e5;
    let out = h * (n + 1);
    w[out + 4] = 7.0e4;
    let c = controller(n, h, w, Motion::Wheels);
    let prog = program::generate(&c, THYMIO_PROX);
    for u in &prog.units {
        let acc: i64 = u
            .weights
            .iter()
            .map(|w| i64::from(w.unsigned_abs()))
            .sum::<i64>()
            * 4096;
        assert!(acc < 1 << 31 && (0..=32).contains(&u.shift), "{u:?}");
    }
    assert!(
        prog.units[0].e < 0 && prog.units[0].weights[0] > 16384,
        "{:?}",
        prog.units[0]
    );
    let mut readings = recorded_readings(7, 2);
    readings.extend(probe_readings(7, 4505));
    let (dt, _, labels, _) = agreement(&c, &readings, THYMIO_PROX);
    assert!(dt <= TARGET_BOUND, "{dt}");
    assert!(labels >= 0.99, "{labels}");
}

#[test]
fn the_program_fits_the_thymios_memory_and_step_limits() {
    let mut rng = rng_from_seed(8);
    for (n, h) in [(7, 6), (8, 6), (7, 10)] {
        for motion in [Motion::Wheels, Motion::Actions] {
            let c = controller(n, h, random_weights(&mut rng, n, h, 4.0), motion);
            let src = Source {
                var: "prox.horizontal",
                len: n,
            };
            let (prog, mut m) = loaded(&c, src);
            let words = interp::bytecode_words(&prog.code, &prog.constants).unwrap();
            assert!(m.user_words() <= 512, "{} words", m.user_words());
            assert!(words <= 1534, "{words} bytecode words");
            let control = if motion == Motion::Wheels {
                "timer0"
            } else {
                "prox"
            };
            m.set("prox.horizontal", &vec![2000; n]).unwrap();
            let steps = m.run_event(control).unwrap();
            eprintln!(
                "N={n} H={h} {motion:?}: {} variable words, ~{words} bytecode words, {control} {steps} steps",
                m.user_words()
            );
            assert!(steps > 100 && steps < 1000, "{steps}");
            assert_eq!(m.get("fm_count"), Some(&[1i16][..]));
        }
    }
}

#[test]
fn the_wheels_program_runs_every_control_period_and_sets_the_targets() {
    let c = controller(
        7,
        6,
        random_weights(&mut rng_from_seed(2), 7, 6, 3.0),
        Motion::Wheels,
    );
    let (_, mut m) = loaded(&c, THYMIO_PROX);
    assert_eq!(m.get("timer.period"), Some(&[100i16, 0][..]));
    let wall = [4505, 4487, 4198, 2508, 0, 0, 0];
    m.set("prox.horizontal", &wall).unwrap();
    m.run_event("timer0").unwrap();
    let expected = fixed_out(&mut loaded(&c, THYMIO_PROX).1, &wall).unwrap();
    assert_eq!(m.get("motor.left.target"), Some(&[expected.target[0]][..]));
    assert_eq!(m.get("motor.right.target"), Some(&[expected.target[1]][..]));
    let f = float_out(&c, &wall);
    assert!((f64::from(expected.target[0]) - f.target[0]).abs() <= TARGET_BOUND);
    // With fm_monitor = 1 each decision emits fm_state = [readings, left, right target].
    assert!(m.take_emitted().is_empty());
    m.set("fm_monitor", &[1]).unwrap();
    m.run_event("timer0").unwrap();
    let mut state = wall.to_vec();
    state.extend(expected.target);
    assert_eq!(m.take_emitted(), [("fm_state".to_string(), state)]);
    // fm_test stops the control loop until fm_run.
    m.run_event("fm_test").unwrap();
    m.set("prox.horizontal", &[0; 7]).unwrap();
    m.run_event("timer0").unwrap();
    assert_eq!(m.get("motor.left.target"), Some(&[0i16][..]));
    m.run_event("fm_run").unwrap();
    m.run_event("timer0").unwrap();
    assert_eq!(m.get("fm_count"), Some(&[4i16][..]));
}

/// A 7-6-2 controller whose outputs are constant: every weight 0 but the output biases.
fn constant_controller(bias_left: f64, bias_right: f64) -> ExportedController {
    let (n, h) = (7, 6);
    let mut w = vec![0.0; h * (n + 1) + 2 * (h + 1)];
    w[h * (n + 1)] = bias_left;
    w[h * (n + 1) + h + 1] = bias_right;
    controller(n, h, w, Motion::Actions)
}

#[test]
fn the_actions_executor_moves_each_label_by_odometry() {
    // (output biases, action, target left sign, target right sign, wheel travel in mm)
    let base = 94.0 / 2.0;
    let cases = [
        ((6.0, 6.0), 0, 1, 1, 16.6),
        ((0.0, 6.0), 1, -1, 1, base * 30f64.to_radians()),
        ((6.0, 0.0), 2, 1, -1, base * 30f64.to_radians()),
        ((-6.0, -6.0), 3, -1, 1, base * std::f64::consts::PI),
    ];
    for ((bl, br), action, sl, sr, travel) in cases {
        let c = constant_controller(bl, br);
        let (_, mut m) = loaded(&c, THYMIO_PROX);
        m.set("prox.horizontal", &[0; 7]).unwrap();
        m.run_event("prox").unwrap();
        assert_eq!(m.get("fm_act"), Some(&[action][..]));
        let vt = m.get("fm_vt").unwrap()[0];
        assert_eq!(vt, 500, "v_max 166 mm/s at 0.332 mm/s per unit");
        let target = |m: &Machine, side: &str| m.get(&format!("motor.{side}.target")).unwrap()[0];
        assert_eq!(
            (target(&m, "left"), target(&m, "right")),
            (sl * vt, sr * vt)
        );
        // The wheels turn at their targets; count the 10 ms ticks until the executor stops them.
        let mut ticks = 0;
        while m.get("fm_busy") == Some(&[1][..]) {
            let (l, r) = (target(&m, "left"), target(&m, "right"));
            m.set("motor.left.speed", &[l]).unwrap();
            m.set("motor.right.speed", &[r]).unwrap();
            assert!(m.run_event("motor").unwrap() < 1000);
            ticks += 1;
            assert!(ticks < 10_000);
        }
        // Each tick moves each wheel 500 units · 0.332 mm/s · 10 ms = 1.66 mm.
        let moved = f64::from(ticks) * 1.66;
        assert!(
            moved >= travel - 0.1 && moved < travel + 1.66 + 0.1,
            "action {action}: {moved} mm for {travel}"
        );
        assert_eq!((target(&m, "left"), target(&m, "right")), (0, 0));
        // A reading while busy starts nothing; the next one after the action does.
        m.run_event("prox").unwrap();
        assert_eq!(m.get("fm_count"), Some(&[2i16][..]));
        // Wheels that cannot turn (speed 0): the action ends after FM_TIMEOUT_TICKS.
        m.set("motor.left.speed", &[0]).unwrap();
        m.set("motor.right.speed", &[0]).unwrap();
        let mut stalled = 0;
        while m.get("fm_busy") == Some(&[1][..]) {
            m.run_event("motor").unwrap();
            stalled += 1;
            assert!(stalled < 10_000);
        }
        // 3 · turn180 (147.7 mm) / 166 mm/s = 2.67 s: 267 ticks, and one more to exceed them.
        assert_eq!(stalled, 268);
    }
}

#[test]
fn the_aesl_is_xml_whose_node_is_the_interpreted_program() {
    let c = controller(
        7,
        6,
        random_weights(&mut rng_from_seed(4), 7, 6, 3.0),
        Motion::Actions,
    );
    let kit = thymio2_kit(&c);
    let names: Vec<&str> = kit.files.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, [AESL_NAME, README_NAME, GOLDEN_NAME]);
    let aesl = String::from_utf8(kit.files[0].contents.clone()).unwrap();
    let doc = roxmltree::Document::parse_with_options(
        &aesl,
        roxmltree::ParsingOptions {
            allow_dtd: true,
            ..Default::default()
        },
    )
    .unwrap();
    let node = doc.descendants().find(|n| n.has_tag_name("node")).unwrap();
    assert_eq!(node.attribute("name"), Some("thymio-II"));
    let code = node.text().unwrap();
    assert!(code.contains("fm_sub >> 5") && aesl.contains("fm_sub &gt;&gt; 5"));
    let constants: Vec<(String, i64)> = doc
        .descendants()
        .filter(|n| n.has_tag_name("constant"))
        .map(|n| {
            (
                n.attribute("name").unwrap().into(),
                n.attribute("value").unwrap().parse().unwrap(),
            )
        })
        .collect();
    assert!(constants.contains(&("FM_UM_PER_UNIT".into(), 332)));
    let events: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("event"))
        .map(|n| n.attribute("size"))
        .collect();
    assert_eq!(events, [Some("7"), Some("0"), Some("9")]);
    // The file's program, run from the file, gives golden.csv's fixed-point columns.
    let mut m = Machine::load(code, &constants, &target_vars(THYMIO_PROX)).unwrap();
    m.run_init().unwrap();
    let golden = String::from_utf8(kit.files[2].contents.clone()).unwrap();
    let rows: Vec<Vec<f64>> = golden
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    // The readings the simulator recorded with the Thymio, then the probes.
    let recorded = crate::export::golden::vectors(&c).len();
    assert!(recorded > 100, "{recorded} recorded readings");
    assert_eq!(rows.len(), recorded + 1 + 4 * 7 + 2 + 64);
    for row in rows {
        let r: Vec<i16> = row[1..8].iter().map(|&v| v as i16).collect();
        let q = fixed_out(&mut m, &r).unwrap();
        let fixed: Vec<i16> = row[13..].iter().map(|&v| v as i16).collect();
        assert_eq!(fixed, [q.m[0], q.m[1], q.target[0], q.target[1], q.action]);
        assert!((row[10] - f64::from(q.target[0])).abs() <= TARGET_BOUND);
    }
}

#[test]
fn the_readme_gives_loading_units_quantisation_and_measured_figures() {
    let c = controller(
        7,
        6,
        random_weights(&mut rng_from_seed(6), 7, 6, 3.0),
        Motion::Wheels,
    );
    let kit = thymio2_kit(&c);
    let readme = String::from_utf8(kit.files[1].contents.clone()).unwrap();
    for needle in [
        "curl -X PUT --data-binary @fm_controller.aesl http://localhost:3000/nodes/thymio-II",
        "FM_UM_PER_UNIT = 332",
        "16.6 / 500.",
        "500\napproximately corresponds to a linear speed of 20 cm/s",
        "timer.period[0] = FM_PERIOD_MS = 100 ms",
        "math.dot(s, u, x, shift)",
        "words of the Thymio II's 512",
        "action labels equal in\n100.0 % of the rows",
    ] {
        assert!(readme.contains(needle), "{needle:?} not in:\n{readme}");
    }
    assert!(
        kit.notes.iter().all(|n| !n.starts_with("warning")),
        "{:?}",
        kit.notes
    );
}

#[test]
fn more_inputs_than_the_thymio_has_read_zero_and_say_so() {
    let c = controller(
        8,
        3,
        random_weights(&mut rng_from_seed(9), 8, 3, 3.0),
        Motion::Wheels,
    );
    let kit = thymio2_kit(&c);
    assert!(
        kit.notes.iter().any(|n| n.contains("inputs 7..7 read 0")),
        "{:?}",
        kit.notes
    );
    let aesl = String::from_utf8(kit.files[0].contents.clone()).unwrap();
    assert!(aesl.contains("call math.copy(fm_raw[0:6], prox.horizontal[0:6])"));
}

#[test]
fn a_network_too_large_for_the_thymio_is_exported_with_warnings() {
    let (n, h) = (7, 48);
    let c = controller(
        n,
        h,
        random_weights(&mut rng_from_seed(12), n, h, 3.0),
        Motion::Wheels,
    );
    let kit = thymio2_kit(&c);
    let warnings: Vec<&String> = kit
        .notes
        .iter()
        .filter(|n| n.starts_with("warning"))
        .collect();
    assert_eq!(warnings.len(), 3, "{:?}", kit.notes);
    assert!(
        warnings[0].contains("more than the Thymio II's 512"),
        "{warnings:?}"
    );
    assert!(warnings[1].contains("bytecode"), "{warnings:?}");
    assert!(
        warnings[2].contains("cuts an event after 1000"),
        "{warnings:?}"
    );
    let readme = String::from_utf8(kit.files[1].contents.clone()).unwrap();
    assert!(readme.contains(warnings[0].as_str()), "{readme}");
}

/// The largest H whose 7-H-2 kit stays within the Thymio's limits (no warning), per motion.
#[test]
fn the_kit_fits_the_thymio_up_to_a_dozen_hidden_units() {
    let mut rng = rng_from_seed(13);
    for motion in [Motion::Wheels, Motion::Actions] {
        let fits = |h: usize, rng: &mut Rng64| {
            let c = controller(7, h, random_weights(rng, 7, h, 4.0), motion);
            thymio2_kit(&c)
                .notes
                .iter()
                .all(|n| !n.starts_with("warning"))
        };
        let largest = (1..=40)
            .take_while(|&h| fits(h, &mut rng))
            .last()
            .unwrap_or(0);
        eprintln!("{motion:?}: 7-H-2 fits for H <= {largest}");
        assert!(largest >= 10, "{motion:?}: {largest}");
        assert!(!fits(largest + 1, &mut rng));
    }
}

#[test]
fn a_robot_without_sensors_gets_a_kit_that_says_why_not_a_program() {
    let mut c = controller(7, 2, vec![0.5; 2 * 8 + 2 * 3], Motion::Wheels);
    c.robot.sensors = 0;
    let kit = thymio2_kit(&c);
    assert_eq!(kit.files.len(), 1);
    assert!(
        kit.notes[0].contains("network of 0 inputs"),
        "{:?}",
        kit.notes
    );
}
