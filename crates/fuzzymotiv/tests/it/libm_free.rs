//! The step loop calls no libm function (results must not depend on the platform's libm).
//!
//! This test disassembles its own executable with `objdump` (binutils), follows every call from
//! `step_loop` (a whole trial: sensors, noise, network, motion, collision, fitness
//! bookkeeping), direct or through a GOT slot that the dynamic linker fills with one of the
//! executable's own functions, and fails if any reachable function calls or loads the address
//! of a libm function. A control probe that does call `f64::exp` must be flagged, so the check
//! itself is tested.
#![cfg(all(target_os = "linux", target_arch = "x86_64"))]

use std::collections::{HashMap, HashSet};
use std::hint::black_box;
use std::process::Command;

use fuzzymotiv::fitness::{Homing, TermsRecorder};
use fuzzymotiv::modelling::DEFAULT_ACTION_TOLERANCE;
use fuzzymotiv::random::{Rng64, rng_from_seed};
use fuzzymotiv::simulation::Room;
use fuzzymotiv::simulation::{Arena, RawTrial, TrialParams, simulate};
use fuzzymotiv::simulation::{Mlp, MlpShape};
use fuzzymotiv::simulation::{Motion, Pose, RawRobot};

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

/// A second control: libm (`log`) reached inside the library, which this crate calls as it
/// calls the trial (in a test build, through a GOT slot).
#[inline(never)]
fn control_probe_library(p: f64) -> f64 {
    fuzzymotiv::statistics::normal_quantile(black_box(p))
}

/// Per function: direct call/jump targets and addresses named in `# addr` comments; and the
/// functions by start address.
struct Disassembly {
    calls: HashMap<String, Vec<String>>,
    refs: HashMap<String, Vec<u64>>,
    starts: HashMap<u64, String>,
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
    // Mangled names: demangled ones merge the instances of a generic function into one name.
    let text = objdump(&["-d", "--no-show-raw-insn"]);
    let mut d = Disassembly {
        calls: HashMap::new(),
        refs: HashMap::new(),
        starts: HashMap::new(),
    };
    let mut current = String::new();
    for line in text.lines() {
        if let Some((addr, name)) = line.strip_suffix(">:").and_then(|l| l.split_once(" <")) {
            current = name.to_string();
            if let Ok(a) = u64::from_str_radix(addr, 16) {
                d.starts.insert(a, current.clone());
            }
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

/// What the dynamic linker writes into the GOT slots (by slot address).
struct Slots {
    /// A libm function's address.
    libm: HashMap<u64, String>,
    /// An address in this executable (`R_X86_64_RELATIVE`: load address + this offset).
    local: HashMap<u64, u64>,
}

fn slots() -> Slots {
    let mut slots = Slots {
        libm: HashMap::new(),
        local: HashMap::new(),
    };
    for line in objdump(&["-R"]).lines() {
        let mut f = line.split_whitespace();
        let (Some(addr), Some(kind), Some(sym)) = (f.next(), f.next(), f.next()) else {
            continue;
        };
        let Ok(slot) = u64::from_str_radix(addr, 16) else {
            continue;
        };
        let name = sym.split('@').next().unwrap_or(sym);
        if LIBM.contains(&name) {
            slots.libm.insert(slot, name.to_string());
        }
        let offset = sym
            .strip_prefix("*ABS*+0x")
            .map(|o| u64::from_str_radix(o, 16));
        if let (true, Some(Ok(target))) = (kind == "R_X86_64_RELATIVE", offset) {
            slots.local.insert(slot, target);
        }
    }
    slots
}

/// The libm functions reachable from the function `root` (a path such as
/// `it::libm_free::step_loop`: this module's path and the function's).
fn libm_reached(d: &Disassembly, slots: &Slots, root: &str) -> Vec<String> {
    // Its mangled name (legacy scheme): `_ZN` + each segment as length and text + `17h` hash.
    let mangled: String = root
        .split("::")
        .map(|s| format!("{}{s}", s.len()))
        .collect();
    let mangled = format!("_ZN{mangled}17h");
    let start: Vec<&String> = d
        .calls
        .keys()
        .chain(d.refs.keys())
        .filter(|f| f.starts_with(&mangled))
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
            if let Some(name) = slots.libm.get(a) {
                found.push(format!("{name} from {f}"));
            }
        }
        // Functions called directly, and those whose address a GOT slot read here holds.
        let through_got = (d.refs.get(&f).into_iter().flatten())
            .filter_map(|a| d.starts.get(slots.local.get(a)?));
        for t in d.calls.get(&f).into_iter().flatten().chain(through_got) {
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
        TrialParams::from_raw(
            &trial,
            &robot,
            fuzzymotiv::simulation::RobotSpec::khepera(),
            DEFAULT_ACTION_TOLERANCE,
        )
        .unwrap()
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
    black_box(control_probe_library(0.01));

    let d = disassemble();
    let slots = slots();
    // This module's functions by path (`it::libm_free::step_loop`).
    let here = |f: &str| format!("{}::{f}", module_path!());
    let control = libm_reached(&d, &slots, &here("control_probe"));
    assert!(
        control.iter().any(|s| s.starts_with("exp")),
        "the check does not see f64::exp in the control probe: {control:?}"
    );
    let control = libm_reached(&d, &slots, &here("control_probe_library"));
    assert!(
        control.iter().any(|s| s.starts_with("log")),
        "the check does not see log in the library's normal_quantile: {control:?}"
    );
    let reached = libm_reached(&d, &slots, &here("step_loop"));
    assert!(
        reached.is_empty(),
        "the step loop reaches libm: {reached:?}"
    );
}
