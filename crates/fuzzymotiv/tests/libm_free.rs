//! The step loop calls no libm function (results must not depend on the platform's libm).
//!
//! This test disassembles its own executable with `objdump` (binutils), follows every direct
//! call from `step_loop` (a whole trial: sensors, noise, network, motion, collision, fitness
//! bookkeeping) and fails if any reachable function calls or loads the address of a libm
//! function. A control probe that does call `f64::exp` must be flagged, so the check itself is
//! tested.
#![cfg(all(target_os = "linux", target_arch = "x86_64"))]

use std::collections::{HashMap, HashSet};
use std::hint::black_box;
use std::process::Command;

use fuzzymotiv::fitness::terms::{Homing, TermsRecorder};
use fuzzymotiv::modelling::aem::DEFAULT_ACTION_TOLERANCE;
use fuzzymotiv::random::rng::{Rng64, rng_from_seed};
use fuzzymotiv::simulation::controller::{Mlp, MlpShape};
use fuzzymotiv::simulation::robot::{Motion, Pose, RawRobot};
use fuzzymotiv::simulation::room::Room;
use fuzzymotiv::simulation::trial::{Arena, RawTrial, TrialParams, simulate};

/// libm functions that must not be reached from the step loop (`fmod`, reached by
/// `wrap_angle` for |θ| ≥ 2π only, is exact by definition, so the same on every platform).
const LIBM: &[&str] = &[
    "exp", "exp2", "expm1", "log", "log2", "log1p", "pow", "sin", "cos", "sincos", "tan", "atan",
    "atan2", "hypot", "sinh", "cosh", "tanh", "cbrt", "fmod", "round", "floor", "ceil", "trunc",
    "rint",
];

#[inline(never)]
fn step_loop(arena: &Arena, mlp: &mut Mlp, rng: &mut Rng64) -> Pose {
    let mut rec = TermsRecorder::new(arena, Homing::Escape);
    let pose = simulate(arena, mlp, rng, &mut rec);
    black_box(rec.finish());
    pose
}

#[inline(never)]
fn control_probe(x: f64) -> f64 {
    black_box(x).exp()
}

/// Per function: direct call/jump targets and addresses named in `# addr` comments.
struct Disassembly {
    calls: HashMap<String, Vec<String>>,
    refs: HashMap<String, Vec<u64>>,
}

fn objdump(args: &[&str]) -> String {
    let exe = std::env::current_exe().expect("test executable");
    let out = Command::new("objdump")
        .args(args)
        .arg(&exe)
        .output()
        .expect("objdump (binutils) is needed by this test: apt-get install binutils");
    assert!(out.status.success(), "objdump {args:?} failed");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn disassemble() -> Disassembly {
    let text = objdump(&["-d", "--no-show-raw-insn", "-C"]);
    let mut d = Disassembly {
        calls: HashMap::new(),
        refs: HashMap::new(),
    };
    let mut current = String::new();
    for line in text.lines() {
        if let Some(name) = line.strip_suffix(">:").and_then(|l| l.split_once(" <")) {
            current = name.1.to_string();
            continue;
        }
        let insn = line.split_once(":\t").map_or("", |(_, i)| i);
        if insn.starts_with("call") || insn.starts_with("jmp") {
            if let Some(target) = insn.split_once(" <").and_then(|(_, t)| t.strip_suffix('>')) {
                let target = target.split('+').next().unwrap_or(target).to_string();
                d.calls.entry(current.clone()).or_default().push(target);
            }
        }
        if let Some((_, comment)) = insn.split_once("# ") {
            let addr = comment.split_whitespace().next().unwrap_or("");
            if let Ok(a) = u64::from_str_radix(addr, 16) {
                d.refs.entry(current.clone()).or_default().push(a);
            }
        }
    }
    d
}

/// GOT addresses that the dynamic linker fills with a libm function.
fn libm_slots() -> HashMap<u64, String> {
    let mut slots = HashMap::new();
    for line in objdump(&["-R"]).lines() {
        let mut f = line.split_whitespace();
        let (Some(addr), Some(_), Some(sym)) = (f.next(), f.next(), f.next()) else {
            continue;
        };
        let name = sym.split('@').next().unwrap_or(sym);
        if let (Ok(a), true) = (u64::from_str_radix(addr, 16), LIBM.contains(&name)) {
            slots.insert(a, name.to_string());
        }
    }
    slots
}

/// The libm functions reachable from the function whose name ends with `root`.
fn libm_reached(d: &Disassembly, slots: &HashMap<u64, String>, root: &str) -> Vec<String> {
    let start: Vec<&String> = d
        .calls
        .keys()
        .chain(d.refs.keys())
        .filter(|f| f.ends_with(root))
        .collect();
    assert!(!start.is_empty(), "{root} not found in the disassembly");
    let mut seen: HashSet<String> = start.iter().map(|s| s.to_string()).collect();
    let mut stack: Vec<String> = seen.iter().cloned().collect();
    let mut found = Vec::new();
    while let Some(f) = stack.pop() {
        let plain = f.split('@').next().unwrap_or(&f);
        if f.ends_with("@plt") && LIBM.contains(&plain) {
            found.push(format!("{plain} (plt)"));
        }
        for a in d.refs.get(&f).into_iter().flatten() {
            if let Some(name) = slots.get(a) {
                found.push(format!("{name} from {f}"));
            }
        }
        for t in d.calls.get(&f).into_iter().flatten() {
            if seen.insert(t.clone()) {
                stack.push(t.clone());
            }
        }
    }
    found
}

#[test]
fn the_step_loop_calls_no_libm_function() {
    // Run both probes so that they are kept and their code is real.
    let trial = RawTrial {
        steps: 50,
        ..RawTrial::default()
    };
    let params = |motion| {
        let robot = RawRobot {
            motion,
            ..RawRobot::default()
        };
        TrialParams::from_raw(&trial, &robot, DEFAULT_ACTION_TOLERANCE).unwrap()
    };
    let arena = |motion| Arena::new(Room::builtin("H").unwrap(), &params(motion));
    let genome: Vec<f64> = (0..68)
        .map(|k| ((k * 37 % 17) as f64 - 8.0) / 4.0)
        .collect();
    let mut mlp = Mlp::from_genome(MlpShape::default(), &genome).unwrap();
    // Both motion models run (the check below is static: it follows every call either takes).
    for motion in [Motion::Actions, Motion::Wheels] {
        black_box(step_loop(&arena(motion), &mut mlp, &mut rng_from_seed(1)));
    }
    black_box(control_probe(1.5));

    let d = disassemble();
    let slots = libm_slots();
    let control = libm_reached(&d, &slots, "control_probe");
    assert!(
        control.iter().any(|s| s.starts_with("exp")),
        "the check does not see f64::exp in the control probe: {control:?}"
    );
    let reached = libm_reached(&d, &slots, "libm_free::step_loop");
    assert!(
        reached.is_empty(),
        "the step loop reaches libm: {reached:?}"
    );
}
